//! What the room type adds: seats and settings for set tables, furniture, wall and ceiling
//! items scaled by density and size, usual parents of small objects, default small objects,
//! and the final order.

use std::collections::BTreeMap;

use super::{
    Arrangement, Builder, MAX_COUNT, RoomPlan, STORAGE_FLOOR, SurfaceItem, SurfaceWant, Want,
    clutter_factor, covers, fill_factor, is_seat, is_table_like, is_table_seat, one_per_parent,
    pick, place_to_arrangement, split_counts,
};
use crate::assets::router::naming::footprint;
use crate::knowledge::{KbItem, Place, SurfaceRule};
use crate::prompt::{Density, Mention};
use crate::words::Support;

/// Largest footprint of an optional piece that still comes along when the prompt lists its
/// furniture, m² (a bookcase 0.3, a nightstand 0.2; a desk 0.7 and an armchair 0.6 do not).
const SMALL_PIECE_M2: f64 = 0.45;

impl Builder<'_> {
    /// "A table set for 4 people": seats per setting when the prompt names none, default
    /// setting items when it names none.
    pub(super) fn place_settings(&mut self) {
        let tables: Vec<(usize, Mention)> = self
            .mentions()
            .filter(|(_, m)| m.place_settings.is_some() && !m.negated)
            .map(|(i, m)| (i, m.clone()))
            .collect();
        for (i, t) in tables {
            let per = t.place_settings.unwrap_or(0);
            let (tables_n, _) = self.count(i, 0);
            let seats = per.saturating_mul(tables_n);
            let has_seats = self
                .plan
                .furniture
                .iter()
                .any(|w| is_table_seat(self.lex, &w.noun));
            if !has_seats && seats > 0 && !self.excluded("chair") {
                let seat = self
                    .kb
                    .seat_for(&t.category)
                    .map_or("chair", |(s, _)| s)
                    .to_string();
                self.plan.furniture.push(Want {
                    noun: seat.clone(),
                    description: self.default_description(&seat, Support::Floor),
                    count: seats.min(MAX_COUNT),
                    explicit: false,
                    at_least: false,
                    arrangement: Arrangement::Around {
                        parent: t.category.clone(),
                    },
                    height_m: None,
                    parent_instance: None,
                });
            } else if has_seats {
                // Seats the prompt counted go around the set table.
                for w in self
                    .plan
                    .furniture
                    .iter_mut()
                    .filter(|w| is_table_seat(self.lex, &w.noun))
                {
                    if matches!(w.arrangement, Arrangement::AgainstWall | Arrangement::Free) {
                        w.arrangement = Arrangement::Around {
                            parent: t.category.clone(),
                        };
                    }
                }
            }
            let has_items = self
                .surface
                .iter()
                .any(|s| s.place_settings && s.parent == t.category);
            if !has_items && seats > 0 {
                let rule = self
                    .kb
                    .surface_rule("dining table")
                    .map(|r| r.items.clone())
                    .unwrap_or_else(|| {
                        vec![
                            "plate".into(),
                            "glass".into(),
                            "fork".into(),
                            "knife".into(),
                        ]
                    });
                for item in rule {
                    if self.excluded(&item) {
                        continue;
                    }
                    self.surface.push(SurfaceItem {
                        parent: t.category.clone(),
                        want: Want {
                            noun: item.clone(),
                            description: item.clone(),
                            count: seats.min(MAX_COUNT),
                            explicit: false,
                            at_least: false,
                            arrangement: Arrangement::Free,
                            height_m: None,
                            parent_instance: None,
                        },
                        place_settings: true,
                    });
                }
            }
        }
    }

    /// The noun already planned that covers a default noun, if any: the same noun, or one it
    /// is a kind of (or that is a kind of it). The nouns of `own`, the room type's other
    /// defaults, cover only themselves: the bathroom's default shelf and its towel rack (a
    /// kind of rack, a kind of shelf) are both the room's, as are its cabinet and its
    /// medicine cabinet.
    fn covered_by(&self, noun: &str, own: &[String]) -> Option<String> {
        let present = self
            .plan
            .furniture
            .iter()
            .chain(&self.plan.wall)
            .chain(&self.plan.ceiling)
            .map(|w| w.noun.as_str())
            .chain(self.surface.iter().map(|s| s.want.noun.as_str()));
        let mut found = None;
        for p in present {
            if p == noun {
                return Some(p.to_string());
            }
            if found.is_none() && !own.iter().any(|o| o == p) && covers(self.lex, p, noun) {
                found = Some(p.to_string());
            }
        }
        found
    }

    /// True when another room of the house is the first home of a default `noun` (the
    /// house table `items_to_rooms`): a kitchen gets no optional dining table of its own
    /// when the house has a dining room.
    fn hosted_elsewhere(&self, noun: &str) -> bool {
        let Some(here) = self.reading.rooms.get(self.room) else {
            return false;
        };
        if self.reading.rooms.len() < 2 {
            return false;
        }
        let registry = crate::knowledge::rooms::registry();
        let Some(home) = registry
            .house()
            .items_to_rooms
            .get(noun)
            .and_then(|v| v.first())
        else {
            return false;
        };
        !registry.is_a(&here.room_type, home)
            && self
                .reading
                .rooms
                .iter()
                .enumerate()
                .any(|(i, r)| i != self.room && registry.is_a(&r.room_type, home))
    }

    /// True when the prompt names a default `noun` (or a kind of it, or what it is a kind of)
    /// with an exact count in another room of the house: "a dresser full of plates" in the
    /// kitchen is the house's one dresser, and the bedroom gets no optional one besides.
    fn named_elsewhere(&self, noun: &str) -> bool {
        self.counted_in_other_rooms()
            .any(|c| covers(self.lex, c, noun))
    }

    /// The kinds the prompt counts exactly in the house's other rooms: in this reading, and
    /// those the house's whole prompt gave (`plan_room_of_house`).
    pub(super) fn counted_in_other_rooms(&self) -> impl Iterator<Item = &str> {
        let here = (self.reading.rooms.len() >= 2)
            .then(|| {
                self.reading.mentions.iter().filter(|m| {
                    m.room != self.room
                        && !m.negated
                        && matches!(m.count, crate::prompt::Count::Exactly(_))
                })
            })
            .into_iter()
            .flatten()
            .map(|m| m.category.as_str());
        here.chain(self.house.elsewhere.iter().map(String::as_str))
    }

    /// True when the prompt counts exactly the kind `noun` is in another room of the house
    /// ("the first bedroom holds a double bed with two nightstands"): those are the house's,
    /// and no room adds more of it by default.
    fn counted_elsewhere(&self, noun: &str) -> bool {
        self.counted_in_other_rooms().any(|c| c == noun)
    }

    /// Room-type defaults, scaled by density and room size, minus what the prompt covers or
    /// excludes.
    pub(super) fn defaults(&mut self) {
        let Some(rt) = self.rt else { return };
        let t = fill_factor(self.density);
        let explicit_floor = self.plan.furniture.iter().filter(|w| w.explicit).count();
        // A prompt that lists its furniture gets the essentials and the room's small pieces
        // (shelves, side tables, plants, baskets, rugs: what holds and dresses the room), not
        // every large option (another sofa, a desk).
        let lists_furniture = explicit_floor >= 3;
        let lex = self.lex;
        let small_piece = |noun: &str| {
            lex.lookup(noun).is_some_and(|e| e.thin) || footprint(noun) <= SMALL_PIECE_M2
        };
        let scale = self
            .reading
            .rooms
            .get(self.room)
            .map_or(1.0, |r| r.size_scale);
        let add = |b: &mut Self, item: &KbItem, support: Support, own: &mut Vec<String>| {
            // An optional piece whose first home is another room of the house stays there.
            // So does an optional piece the prompt counts in another room.
            // So does any other piece the prompt counts exactly in another room (the house's
            // "two armchairs" are the ones it placed): only the piece that makes the room (its
            // first, the bed, the toilet) and a table's seats stay.
            let anchor = rt.furniture.first().is_some_and(|f| f.noun == item.noun);
            if b.excluded(&item.noun)
                || (item.count[0] == 0
                    && (b.hosted_elsewhere(&item.noun) || b.named_elsewhere(&item.noun)))
                || (!anchor
                    && !super::is_table_seat(lex, &item.noun)
                    && b.counted_elsewhere(&item.noun))
            {
                return;
            }
            if let Some(by) = b.covered_by(&item.noun, own) {
                b.floor_of.insert(item.noun.clone(), by);
                return;
            }
            let tt = if item.count[0] > 0 || !lists_furniture || small_piece(&item.noun) {
                t
            } else {
                0.0
            };
            let mut count = pick(item.count, tt);
            if matches!(item.place, Some(Place::Grid | Place::RowAlongWall)) && scale != 1.0 {
                count = ((count as f64) * scale).round() as u32;
                count = count.clamp(item.count[0].max(1), item.count[1].max(1) * 2);
            }
            if count == 0 {
                return;
            }
            let mut arrangement = item.place.as_ref().map_or(
                if support == Support::Floor {
                    Arrangement::AgainstWall
                } else {
                    Arrangement::Free
                },
                place_to_arrangement,
            );
            // Rule targets name default nouns; use what the plan has instead.
            arrangement = arrangement
                .with_target(|n| b.floor_of.get(n).cloned().unwrap_or_else(|| n.to_string()));
            // A table's seats are the ones the prompt gave it ("a table with eight upholstered
            // chairs" gets no dining chairs besides).
            if let Some(target) = arrangement.target()
                && super::is_seat(lex, &item.noun)
                && b.plan.furniture.iter().any(|w| {
                    w.explicit
                        && super::is_seat(lex, &w.noun)
                        && w.arrangement.target() == Some(target)
                })
            {
                return;
            }
            if let Some(target) = arrangement.target().map(str::to_string)
                && !b.has(&target)
            {
                // Seats without their table, nightstands without a bed: skip optional ones;
                // keep required ones against a wall.
                if item.count[0] == 0 {
                    return;
                }
                arrangement = match support {
                    Support::Floor => Arrangement::AgainstWall,
                    _ => Arrangement::Free,
                };
            }
            let want = Want {
                noun: item.noun.clone(),
                description: b.default_description(&item.noun, support),
                count,
                explicit: false,
                at_least: false,
                arrangement,
                height_m: item.height,
                parent_instance: None,
            };
            own.push(want.noun.clone());
            match support {
                Support::Floor => b.plan.furniture.push(want),
                Support::Wall => b.plan.wall.push(want),
                _ => b.plan.ceiling.push(want),
            }
        };
        let mut own = Vec::new();
        for item in &rt.furniture {
            add(self, item, Support::Floor, &mut own);
        }
        for item in &rt.wall_items {
            add(self, item, Support::Wall, &mut own);
        }
        for item in &rt.ceiling {
            add(self, item, Support::Ceiling, &mut own);
        }
        // Seats for table-like pieces the prompt named "with chairs" but without a count are
        // handled by `count`; seats for set tables by `place_settings`.
    }

    pub(super) fn has(&self, noun: &str) -> bool {
        self.plan
            .furniture
            .iter()
            .chain(&self.plan.wall)
            .chain(&self.plan.ceiling)
            .any(|w| w.noun == noun)
    }

    /// One piece the plan adds to hold small objects: placed by the knowledge base's rule for
    /// it, or `fallback`.
    fn added_piece(&self, noun: &str, support: Support, fallback: Arrangement) -> Want {
        Want {
            noun: noun.to_string(),
            description: self.default_description(noun, support),
            count: 1,
            explicit: false,
            at_least: false,
            arrangement: self.kb_arrangement(noun).unwrap_or(fallback),
            height_m: None,
            parent_instance: None,
        }
    }

    /// The furniture noun that holds what the prompt puts on the floor ("a pile of blocks on
    /// the floor"): a rug or mat of the plan, else a rug added for them. Small objects rest on
    /// the surfaces of furniture, and a rug is the floor's: the pile lies where people play
    /// or sit, clear of the furniture and the walkways the furniture stage keeps.
    fn floor_covering(&mut self) -> String {
        const COVERINGS: [&str; 4] = ["rug", "round rug", "yoga mat", "runner rug"];
        if let Some(w) = self
            .plan
            .furniture
            .iter()
            .find(|w| COVERINGS.contains(&w.noun.as_str()))
        {
            return w.noun.clone();
        }
        if !self.excluded("rug") {
            let rug = self.added_piece("rug", Support::Floor, Arrangement::Center);
            self.plan.furniture.push(rug);
            return "rug".into();
        }
        "any".into()
    }

    /// Small objects without a named parent go where they usually rest; a usual parent the
    /// room lacks is added ("a TV" brings a TV stand).
    pub(super) fn surface_parents(&mut self) {
        let lex = self.lex;
        for k in 0..self.surface.len() {
            if self.surface[k].parent == "floor" {
                self.surface[k].parent = self.floor_covering();
                continue;
            }
            if !self.surface[k].parent.is_empty() {
                continue;
            }
            let noun = self.surface[k].want.noun.clone();
            let rests: Vec<String> = lex
                .lookup(&noun)
                .map(|e| e.rests_on.clone())
                .unwrap_or_default();
            let room_rule = self
                .rt
                .and_then(|r| {
                    r.surfaces
                        .iter()
                        .find(|s| s.items.contains(&noun) && self.has(&s.parent))
                })
                .map(|s| s.parent.clone());
            let present = rests.iter().find_map(|p| {
                self.plan
                    .furniture
                    .iter()
                    .find(|w| covers(lex, &w.noun, p))
                    .map(|w| w.noun.clone())
            });
            let parent = if let Some(p) = present.or(room_rule) {
                p
            } else if let Some(p) = rests.first().filter(|p| !self.excluded(p)) {
                let p = p.clone();
                let support = lex.lookup(&p).map_or(Support::Floor, |e| e.support);
                let want = self.added_piece(&p, support, Arrangement::AgainstWall);
                match support {
                    Support::Wall => self.plan.wall.push(want),
                    _ => self.plan.furniture.push(want),
                }
                p
            } else {
                "any".to_string()
            };
            self.surface[k].parent = parent;
        }
    }

    /// The small-object rule for `parent`: the room type's, else the room-independent one.
    /// What a piece holds inside is the same in any room: a room's rule for its top takes the
    /// piece's own list when it has none.
    fn surface_rule_of(&self, parent: &str) -> Option<SurfaceRule> {
        let kb_rule = self.kb.surface_rule(parent);
        let mut rule = self
            .rt
            .and_then(|r| r.surface_rule(parent))
            .or(kb_rule)
            .cloned()?;
        if rule.inside.is_empty()
            && let Some(k) = kb_rule
        {
            rule.inside.clone_from(&k.inside);
        }
        Some(rule)
    }

    /// Small objects the plan will hold before the stage grows them to the built surfaces:
    /// what the prompt puts on pieces itself, and what `surface_defaults` plans on the pieces
    /// it left empty.
    fn planned_clutter(&self) -> u32 {
        let cf = clutter_factor(self.density);
        let t = fill_factor(self.density);
        let asked: u32 = self.surface.iter().map(|s| s.want.count).sum();
        let mut seen: Vec<&str> = Vec::new();
        let mut defaults = 0;
        for w in self.plan.furniture.iter().chain(&self.plan.wall) {
            if seen.contains(&w.noun.as_str()) || self.surface.iter().any(|s| s.parent == w.noun) {
                continue;
            }
            seen.push(&w.noun);
            let Some(rule) = self.surface_rule_of(&w.noun) else {
                continue;
            };
            if rule.place_settings {
                continue;
            }
            let open = ((pick(rule.count, t) as f64) * cf).round() as u32;
            let stored = (rule.inside.len() as f64 * cf).round() as u32;
            defaults += (open + stored) * w.count;
        }
        asked + defaults
    }

    /// A room whose planned pieces hold fewer small objects than [`STORAGE_FLOOR`] gets the
    /// storage and display pieces of its role (`clutter_storage` in `_house.json`), one at a
    /// time, until they do: the stage can grow a room's clutter to at most twice what the plan
    /// holds, so a music room of a piano, a drum kit and guitar stands stayed near 30 objects
    /// whatever its size. Not in a minimal or sparse room; never a piece the prompt excludes
    /// or counts exactly (here or in another room of the house).
    pub(super) fn storage_for_clutter(&mut self) {
        if matches!(self.density, Some(Density::Minimalist | Density::Sparse)) {
            return;
        }
        let Some(rt) = self.rt else { return };
        let registry = crate::knowledge::rooms::registry();
        let Some(pieces) = registry.house().clutter_storage.get(&rt.role) else {
            return;
        };
        for noun in pieces {
            if self.planned_clutter() >= STORAGE_FLOOR {
                return;
            }
            if self.excluded(noun) || self.fixed_by_prompt(noun) || self.named_elsewhere(noun) {
                continue;
            }
            match self.plan.furniture.iter_mut().find(|w| w.noun == *noun) {
                Some(w) if !w.explicit => w.count = (w.count + 1).min(MAX_COUNT),
                Some(_) => {}
                None => {
                    let support = self.lex.lookup(noun).map_or(Support::Floor, |e| e.support);
                    let want = self.added_piece(noun, support, Arrangement::AgainstWall);
                    match support {
                        Support::Wall => self.plan.wall.push(want),
                        _ => self.plan.furniture.push(want),
                    }
                }
            }
        }
    }

    /// Default small objects on parents that the prompt left empty.
    pub(super) fn surface_defaults(&mut self) {
        let cf = clutter_factor(self.density);
        let t = fill_factor(self.density);
        let parents: Vec<(String, u32)> = self
            .plan
            .furniture
            .iter()
            .chain(&self.plan.wall)
            .map(|w| (w.noun.clone(), w.count))
            .collect();
        let mut done: Vec<String> = Vec::new();
        for (parent, n_parents) in parents {
            if done.contains(&parent) || self.surface.iter().any(|s| s.parent == parent) {
                continue;
            }
            done.push(parent.clone());
            let Some(rule) = self.surface_rule_of(&parent) else {
                continue;
            };
            if rule.place_settings {
                let seats: u32 = self
                    .plan
                    .furniture
                    .iter()
                    .filter(|w| matches!(&w.arrangement, Arrangement::Around { parent: p } if *p == parent))
                    .map(|w| w.count)
                    .sum();
                if seats == 0 || matches!(self.density, Some(Density::Minimalist | Density::Sparse))
                {
                    continue;
                }
                let items: Vec<String> = rule
                    .items
                    .iter()
                    .filter(|i| !self.excluded(i))
                    .cloned()
                    .collect();
                for item in items {
                    self.surface.push(SurfaceItem {
                        parent: parent.clone(),
                        want: Want {
                            noun: item.clone(),
                            description: item.clone(),
                            count: seats.min(MAX_COUNT),
                            explicit: false,
                            at_least: false,
                            arrangement: Arrangement::Free,
                            height_m: None,
                            parent_instance: None,
                        },
                        place_settings: true,
                    });
                }
                continue;
            }
            let per_parent = ((pick(rule.count, t) as f64) * cf).round() as u32;
            let total = per_parent.saturating_mul(n_parents).min(MAX_COUNT);
            let usable = |i: &&String| !self.excluded(i) && !self.fixed_by_prompt(i);
            let items: Vec<&str> = rule
                .items
                .iter()
                .filter(usable)
                .map(String::as_str)
                .collect();
            let single = |noun: &str| one_per_parent(self.lex, noun);
            let counts = split_counts(total, &items, single, n_parents);
            // What is put away inside: a first estimate of one per candidate and parent; the
            // manipuland stage sizes it to the drawers and shelves the piece has.
            let inside: Vec<&str> = rule
                .inside
                .iter()
                .filter(usable)
                .map(String::as_str)
                .collect();
            let stored_total = ((inside.len() as u32 * n_parents) as f64 * cf).round() as u32;
            let stored = split_counts(stored_total.min(MAX_COUNT), &inside, single, n_parents);
            let arranged = counts
                .into_iter()
                .map(|c| (c, Arrangement::Free))
                .chain(stored.into_iter().map(|c| (c, Arrangement::Stored)));
            for ((noun, c), arrangement) in arranged {
                self.surface.push(SurfaceItem {
                    parent: parent.clone(),
                    want: Want {
                        noun: noun.clone(),
                        description: noun,
                        count: c,
                        explicit: false,
                        at_least: false,
                        arrangement,
                        height_m: None,
                        parent_instance: None,
                    },
                    place_settings: false,
                });
            }
        }
    }

    /// Arrangements whose target never made it into the plan fall back: a seat goes to a
    /// table-like piece that is there, anything else to a wall (or anywhere, off the floor).
    pub(super) fn repair_targets(&mut self) {
        let planned: Vec<String> = self
            .plan
            .furniture
            .iter()
            .chain(&self.plan.wall)
            .chain(&self.plan.ceiling)
            .map(|w| w.noun.clone())
            .collect();
        let table = self
            .plan
            .furniture
            .iter()
            .find(|w| is_table_like(self.lex, &w.noun))
            .map(|w| w.noun.clone());
        let lex = self.lex;
        let fix = |w: &mut Want, floor: bool| {
            let Some(t) = w.arrangement.target() else {
                return;
            };
            if planned.iter().any(|p| p == t)
                || (t == w.noun && matches!(w.arrangement, Arrangement::Facing { .. }))
            {
                return;
            }
            w.arrangement = match (&table, floor && is_seat(lex, &w.noun)) {
                (Some(t), true) => Arrangement::Around { parent: t.clone() },
                _ if floor => Arrangement::AgainstWall,
                _ => Arrangement::Free,
            };
        };
        for w in &mut self.plan.furniture {
            fix(w, true);
        }
        for w in self
            .plan
            .wall
            .iter_mut()
            .chain(self.plan.ceiling.iter_mut())
        {
            fix(w, false);
        }
    }

    pub(super) fn finish(mut self) -> RoomPlan {
        self.repair_targets();
        // Furniture order: anchors first, then what refers to them.
        let targets: BTreeMap<String, Option<String>> = self
            .plan
            .furniture
            .iter()
            .map(|w| (w.noun.clone(), w.arrangement.target().map(str::to_string)))
            .collect();
        let depth = |w: &Want| -> usize {
            let mut d = 0;
            let mut cur = w.arrangement.target().map(str::to_string);
            while let Some(t) = cur {
                if d > 4 || !targets.contains_key(&t) || t == w.noun {
                    break;
                }
                d += 1;
                cur = targets.get(&t).cloned().flatten();
            }
            d
        };
        let mut keyed: Vec<(usize, bool, usize, Want)> = self
            .plan
            .furniture
            .drain(..)
            .enumerate()
            .map(|(i, w)| (depth(&w), !w.explicit, i, w))
            .collect();
        keyed.sort_by_key(|(d, e, i, _)| (*d, *e, *i));
        self.plan.furniture = keyed.into_iter().map(|(.., w)| w).collect();
        // Group small objects by parent, keeping first-seen order.
        for s in self.surface {
            match self
                .plan
                .surfaces
                .iter_mut()
                .find(|g| g.parent == s.parent && g.place_settings == s.place_settings)
            {
                Some(g) => g.items.push(s.want),
                None => self.plan.surfaces.push(SurfaceWant {
                    parent: s.parent,
                    items: vec![s.want],
                    place_settings: s.place_settings,
                }),
            }
        }
        self.plan
    }
}
