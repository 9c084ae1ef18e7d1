//! What the prompt asked for: counts (per parent, per setting, "several"), arrangements from
//! relations, descriptions with attributes, small objects and their parents.

use std::collections::BTreeMap;

use super::{
    Arrangement, Builder, MAX_COUNT, SurfaceItem, Want, covers, fill_factor, is_seat,
    is_table_like, pick, place_to_arrangement,
};
use crate::knowledge::Place;
use crate::prompt::{self, Count, GroupKind, Mention, Per, RelationKind, Target};
use crate::words::Support;

/// The furniture that carries a small object the prompt puts somewhere on the floor.
const STAND: &str = "side table";

impl Builder<'_> {
    pub(super) fn mentions(&self) -> impl Iterator<Item = (usize, &Mention)> {
        self.reading.room_mentions(self.room)
    }

    pub(super) fn excluded(&self, noun: &str) -> bool {
        self.plan
            .excluded
            .iter()
            .any(|x| covers(self.lex, noun, x) || x == noun)
    }

    /// Asked for with an exact number: defaults add no more of it (a table "set for 4 with a
    /// plate each" has four plates, not four plus a china cabinet full), nor a compound whose
    /// head it is ("a box of latex gloves" on the counter: no pill boxes besides).
    pub(super) fn fixed_by_prompt(&self, noun: &str) -> bool {
        let headed = |c: &str| {
            noun.strip_suffix(c).is_some_and(|m| m.ends_with(' '))
                && crate::words::ground::is_kind_of_word(noun, c)
        };
        let fixes =
            |c: &str| c == noun || covers(self.lex, noun, c) || same_build(noun, c) || headed(c);
        self.reading
            .mentions
            .iter()
            .any(|m| !m.negated && matches!(m.count, Count::Exactly(_)) && fixes(&m.category))
            || self.house.elsewhere.iter().any(|c| fixes(c))
    }

    /// Count of mention `i` in this plan: a plain count, or a per-parent count resolved
    /// against the parent's planned count; "several" from the knowledge base.
    pub(super) fn count(&self, i: usize, depth: usize) -> (u32, bool) {
        let Some(m) = self.reading.mentions.get(i) else {
            return (1, false);
        };
        let unit = |m: &Mention, per_parent: Option<&Mention>| -> (u32, bool) {
            match m.count {
                Count::Exactly(n) => (n, false),
                Count::AtLeast(n) => (n, true),
                Count::Several => (self.several(m, per_parent), false),
            }
        };
        if depth > 4 {
            return unit(m, None);
        }
        match m.per {
            None => unit(m, None),
            Some(Per::Each { parent }) => {
                let p = self.reading.mentions.get(parent);
                let (u, a) = unit(m, p);
                let (n, b) = self.count(parent, depth + 1);
                (u.saturating_mul(n), a || b)
            }
            Some(Per::Setting { table }) => {
                let (u, a) = unit(m, None);
                let settings = self
                    .reading
                    .mentions
                    .get(table)
                    .and_then(|t| t.place_settings)
                    .unwrap_or(1);
                let (n, b) = self.count(table, depth + 1);
                (u.saturating_mul(settings).saturating_mul(n), a || b)
            }
        }
    }

    /// What "several" means for a noun (per parent when `parent` is given).
    pub(super) fn several(&self, m: &Mention, parent: Option<&Mention>) -> u32 {
        if let Some(p) = parent {
            if is_seat(self.lex, &m.category)
                && let Some((_, n)) = self.kb.seat_for(&p.category)
                && n > 0
            {
                return n;
            }
            return if m.support == Support::Surface { 3 } else { 1 };
        }
        let t = fill_factor(self.density);
        if let Some(item) = self.rt.and_then(|r| r.item(&m.category)) {
            return pick([item.count[0].max(2), item.count[1].max(2)], t);
        }
        if m.support == Support::Surface {
            let rule = self
                .rt
                .and_then(|r| r.surfaces.iter().find(|s| s.items.contains(&m.category)))
                .or_else(|| {
                    self.kb
                        .surface_rules()
                        .iter()
                        .find(|s| s.items.contains(&m.category))
                });
            if let Some(rule) = rule {
                return pick(rule.count, t).max(3);
            }
            return if m.category == "book" { 12 } else { 4 };
        }
        3
    }

    pub(super) fn describe(&self, m: &Mention, support: Support) -> String {
        let d = named_description(m);
        if m.attributes.styles.is_empty()
            && support != Support::Surface
            && let Some(s) = self.styles.first()
        {
            return format!("{s} style {d}");
        }
        d
    }

    pub(super) fn default_description(&self, noun: &str, support: Support) -> String {
        match self.styles.first() {
            Some(s) if support != Support::Surface => format!("{s} style {noun}"),
            _ => noun.to_string(),
        }
    }

    /// Arrangement from a mention's relations (explicit first), or None.
    pub(super) fn relation_arrangement(&self, m: &Mention, count: u32) -> Option<Arrangement> {
        let mentions = &self.reading.mentions;
        let cat = |t: Target| -> Option<String> {
            t.mention()
                .and_then(|j| mentions.get(j))
                .map(|x| x.category.clone())
        };
        let mut rels: Vec<&prompt::Relation> = m.relations.iter().collect();
        rels.sort_by_key(|r| r.implied);
        // Most specific first: seats around tables, facing, between, flanking, beside...
        let rank = |k: RelationKind| match k {
            RelationKind::Around => 0,
            RelationKind::InFrontOf => 1,
            RelationKind::Facing => 2,
            RelationKind::Between => 3,
            RelationKind::Flanking => 4,
            RelationKind::Under
            | RelationKind::Behind
            | RelationKind::NextTo
            | RelationKind::With => 5,
            RelationKind::Near => 6,
            _ => 7,
        };
        // A seat that comes with a table is at it, whatever else the sentence says of it ("a
        // table with eight chairs beneath a chandelier").
        let seat = is_seat(self.lex, &m.category);
        let at_table = |r: &prompt::Relation| {
            seat && r.kind == RelationKind::With
                && cat(r.target).is_some_and(|t| is_table_like(self.lex, &t))
        };
        rels.sort_by_key(|r| {
            if at_table(r) {
                (false, 0)
            } else {
                (r.implied, rank(r.kind))
            }
        });
        for r in rels {
            let a = match (r.kind, r.target) {
                (RelationKind::Around, t) => cat(t).map(|parent| Arrangement::Around { parent }),
                (RelationKind::InFrontOf, t @ Target::Mention(_)) => cat(t).map(|target| {
                    if is_seat(self.lex, &m.category) && is_table_like(self.lex, &target) {
                        Arrangement::Around { parent: target }
                    } else {
                        Arrangement::InFront { target }
                    }
                }),
                (RelationKind::Facing, Target::EachOther) => Some(Arrangement::Facing {
                    target: m.category.clone(),
                }),
                (RelationKind::Facing, Target::Window) => Some(Arrangement::NearWindow),
                (RelationKind::Facing, t @ Target::Mention(_)) => {
                    cat(t).map(|target| Arrangement::Facing { target })
                }
                (RelationKind::Between, t) => {
                    let mut targets: Vec<String> = cat(t).into_iter().collect();
                    targets.extend(r.second.and_then(cat));
                    (!targets.is_empty()).then_some(Arrangement::Between { targets })
                }
                (RelationKind::Flanking, Target::Entrance) => Some(Arrangement::NearEntrance),
                (RelationKind::Flanking, t) => {
                    cat(t).map(|target| Arrangement::Flanking { target })
                }
                (RelationKind::Under, t) => cat(t).map(|target| Arrangement::Under { target }),
                (RelationKind::Behind, t) => cat(t).map(|target| Arrangement::Behind { target }),
                (RelationKind::NextTo | RelationKind::Near, t @ Target::Mention(_)) => {
                    cat(t).map(|target| Arrangement::Beside { target })
                }
                (RelationKind::With, t @ Target::Mention(_)) => cat(t).and_then(|target| {
                    if is_seat(self.lex, &m.category) && is_table_like(self.lex, &target) {
                        Some(Arrangement::Around { parent: target })
                    } else if self.kb.placement(&m.category)
                        == Some(&Place::Flanking(target.clone()))
                    {
                        Some(Arrangement::Flanking { target })
                    } else {
                        None
                    }
                }),
                (RelationKind::AcrossFrom, Target::Entrance) => Some(Arrangement::AcrossFrom {
                    target: "entrance".into(),
                }),
                (RelationKind::AcrossFrom, t) => {
                    cat(t).map(|target| Arrangement::AcrossFrom { target })
                }
                (RelationKind::Along, Target::Wall) if count >= 2 => {
                    Some(Arrangement::RowAlongWall)
                }
                (
                    RelationKind::Against
                    | RelationKind::Along
                    | RelationKind::Near
                    | RelationKind::NextTo,
                    Target::Wall,
                ) => Some(Arrangement::AgainstWall),
                (RelationKind::In | RelationKind::Near | RelationKind::NextTo, Target::Corner) => {
                    Some(Arrangement::Corner)
                }
                (RelationKind::Center, _) => Some(Arrangement::Center),
                (
                    RelationKind::Near
                    | RelationKind::NextTo
                    | RelationKind::In
                    | RelationKind::Against,
                    Target::Window,
                ) => Some(Arrangement::NearWindow),
                (
                    RelationKind::Near | RelationKind::NextTo | RelationKind::In,
                    Target::Entrance,
                ) => Some(Arrangement::NearEntrance),
                (RelationKind::BackOf, _) => Some(Arrangement::AcrossFrom {
                    target: "entrance".into(),
                }),
                (RelationKind::FrontOf, _) => Some(Arrangement::FrontOfRoom),
                (RelationKind::Above, t @ Target::Mention(_)) => {
                    cat(t).map(|target| Arrangement::Above { target })
                }
                _ => None,
            };
            if a.is_some() {
                return a;
            }
        }
        None
    }

    /// The knowledge base's arrangement of a noun in this room (or anywhere).
    pub(super) fn kb_arrangement(&self, noun: &str) -> Option<Arrangement> {
        self.rt
            .and_then(|r| r.item(noun))
            .and_then(|i| i.place.as_ref())
            .or_else(|| self.kb.placement(noun))
            .map(place_to_arrangement)
    }

    pub(super) fn explicit(&mut self) {
        let mentions: Vec<(usize, Mention)> =
            self.mentions().map(|(i, m)| (i, m.clone())).collect();
        // "There are no lamps": the word as written excludes its whole kind (floor lamps and
        // ceiling lights too), not only the lexicon's usual lamp.
        for (_, m) in mentions.iter().filter(|(_, m)| m.negated) {
            for word in [&m.category, &m.noun] {
                if !self.plan.excluded.contains(word) {
                    self.plan.excluded.push(word.clone());
                }
            }
        }
        // "Nobody has ever put a television in here" at the end of a house prompt: what one
        // room excludes, no other room adds by default, unless that room asks for it.
        // The same for what the house's whole prompt excludes, when the room's own prompt is
        // read alone.
        let negated = self.reading.mentions.iter().filter(|m| m.negated);
        let excluded = negated
            .flat_map(|m| [&m.category, &m.noun])
            .chain(&self.house.excluded)
            .collect::<Vec<_>>();
        for category in excluded {
            let asked_here = mentions
                .iter()
                .any(|(_, h)| !h.negated && covers(self.lex, &h.category, category));
            if !asked_here && !self.plan.excluded.contains(category) {
                self.plan.excluded.push(category.clone());
            }
        }
        // Generic mentions that count specific ones: share the count out.
        let mut share: BTreeMap<usize, (u32, bool)> = BTreeMap::new();
        let mut skip: Vec<usize> = Vec::new();
        for (i, m) in &mentions {
            if m.negated || !m.generic || m.covers.is_empty() {
                continue;
            }
            let (n, at_least) = self.count(*i, 0);
            let k = m.covers.len() as u32;
            for (j, c) in m.covers.iter().enumerate() {
                let part = n / k + u32::from((j as u32) < n % k);
                share.insert(*c, (part, at_least));
            }
            skip.push(*i);
        }
        for (i, m) in &mentions {
            // A thing the prompt names is kept when only a broader kind is excluded: "at least
            // six hammers ... no power tool of any kind" keeps the hammers.
            if m.negated || skip.contains(i) || self.plan.excluded.contains(&m.category) {
                continue;
            }
            if !m.known && m.head.is_none() && !self.plan.unknown.contains(&m.category) {
                self.plan.unknown.push(m.category.clone());
            }
            let (mut count, mut at_least) = self.count(*i, 0);
            if let Some(&(n, a)) = share.get(i)
                && m.count == Count::Several
            {
                count = n.max(1);
                at_least = a;
            }
            if count > MAX_COUNT {
                self.plan.notes.push(format!(
                    "{count} {} asked for, {MAX_COUNT} planned: a room plans at most {MAX_COUNT} \
                     of one kind of object",
                    m.noun
                ));
            }
            let count = count.clamp(1, MAX_COUNT);
            let support = m.support;
            let description = self.describe(m, support);
            let mut want = Want {
                noun: m.category.clone(),
                description,
                count,
                explicit: true,
                at_least,
                arrangement: Arrangement::Free,
                height_m: None,
                parent_instance: None,
            };
            if support == Support::Floor
                && self.lex.lookup(&m.category).map(|e| e.support) == Some(Support::Surface)
            {
                // An object that rests on furniture, which the prompt stands somewhere in the
                // room ("a printer sits in the corner"): a stand made for it when the lexicon
                // names one among its usual parents ("a TV stands against the wall": a TV
                // stand), else a side table, carries it there.
                let arrangement = self
                    .relation_arrangement(m, count)
                    .unwrap_or(Arrangement::AgainstWall);
                let stand = self
                    .lex
                    .lookup(&m.category)
                    .and_then(|e| e.rests_on.iter().find(|p| p.ends_with("stand")).cloned())
                    .unwrap_or_else(|| STAND.to_string());
                // One stand carries one or two big things (a TV, a printer); a crowd of small
                // ones ("dozens of canvases") shares a couple.
                self.plan.furniture.push(Want {
                    noun: stand.clone(),
                    description: stand.clone(),
                    count: count.min(2),
                    explicit: false,
                    at_least: false,
                    arrangement,
                    height_m: None,
                    parent_instance: None,
                });
                self.surface.push(SurfaceItem {
                    parent: stand,
                    want,
                    place_settings: false,
                });
                continue;
            }
            match support {
                Support::Floor => {
                    want.arrangement = self
                        .relation_arrangement(m, count)
                        .or_else(|| self.kb_arrangement(&m.category))
                        .unwrap_or(Arrangement::AgainstWall);
                    self.plan.furniture.push(want);
                }
                // "a huge aquarium set into the wall": a floor thing with no wall-mounted kind
                // stands against the wall.
                Support::Wall
                    if self.floor_thing_without_wall_kind(&m.category)
                        || built_on_the_floor(&want.description) =>
                {
                    want.arrangement = Arrangement::AgainstWall;
                    self.plan.furniture.push(want);
                }
                Support::Wall => {
                    want.arrangement = self.relation_arrangement(m, count).unwrap_or_else(|| {
                        self.kb_arrangement(&m.category)
                            .unwrap_or(Arrangement::Free)
                    });
                    want.height_m = self
                        .rt
                        .and_then(|r| r.item(&m.category))
                        .and_then(|k| k.height);
                    self.plan.wall.push(want);
                }
                Support::Ceiling => {
                    want.arrangement = match self.relation_arrangement(m, count) {
                        Some(a @ Arrangement::Above { .. }) => a,
                        _ => self
                            .kb_arrangement(&m.category)
                            .filter(|a| matches!(a, Arrangement::Above { .. }))
                            .unwrap_or(Arrangement::Free),
                    };
                    self.plan.ceiling.push(want);
                }
                Support::Surface => self.explicit_surface(m, want),
            }
        }
    }

    /// A thing of the floor (by the lexicon) of which the lexicon knows no wall-mounted kind
    /// ("wall cabinet" for a cabinet, "wall shelf" for a shelf).
    fn floor_thing_without_wall_kind(&self, noun: &str) -> bool {
        let suffix = format!(" {noun}");
        self.lex
            .lookup(noun)
            .is_some_and(|e| e.support == Support::Floor)
            && !self.lex.objects.iter().any(|o| {
                o.support == Support::Wall
                    && (o.kind_of.as_deref() == Some(noun) || o.noun.ends_with(&suffix))
            })
    }

    /// A small object: its parent furniture and how it lies there.
    pub(super) fn explicit_surface(&mut self, m: &Mention, mut want: Want) {
        let mentions = &self.reading.mentions;
        let support = m
            .relations
            .iter()
            .filter(|r| {
                matches!(r.kind, RelationKind::On | RelationKind::In)
                    || (r.kind == RelationKind::With && r.target.mention().is_some())
            })
            .min_by_key(|r| r.implied);
        let mut parent = String::new();
        if let Some(r) = support {
            want.parent_instance = r.instance;
            match r.target {
                Target::Floor => parent = "floor".into(),
                Target::Mention(j) => {
                    // Nested small objects (pens in a pen holder on the desk): the furniture
                    // at the bottom of the chain is the parent, the holder is the arrangement.
                    let direct = mentions[j].category.clone();
                    let mut k = j;
                    for _ in 0..4 {
                        if mentions[k].support != Support::Surface {
                            break;
                        }
                        match mentions[k].parent() {
                            Some(p) => k = p,
                            None => break,
                        }
                    }
                    if mentions[j].support == Support::Surface {
                        want.arrangement = if r.kind == RelationKind::In || mentions[j].container {
                            Arrangement::Inside { parent: direct }
                        } else {
                            Arrangement::On { parent: direct }
                        };
                        if mentions[k].support != Support::Surface {
                            parent = mentions[k].category.clone();
                        }
                        want.parent_instance = None;
                    } else {
                        parent = direct.clone();
                        if r.kind == RelationKind::In && mentions[j].container {
                            want.arrangement = Arrangement::Inside { parent: direct };
                        }
                    }
                }
                _ => {}
            }
        }
        if matches!(want.arrangement, Arrangement::Free) {
            want.arrangement = match m.group.map(|g| g.kind) {
                Some(GroupKind::Stack) => Arrangement::Stack,
                Some(GroupKind::Pile | GroupKind::Mess) => Arrangement::Pile,
                _ => Arrangement::Free,
            };
        }
        let place_settings = matches!(m.per, Some(Per::Setting { .. }));
        self.surface.push(SurfaceItem {
            parent,
            want,
            place_settings,
        });
    }
}

/// Whether the library builds the same category for both nouns ("teddy bear" and "stuffed
/// animal" are both stuffed animals).
fn same_build(a: &str, b: &str) -> bool {
    let of = crate::assets::router::naming::category_of;
    of(a).is_some_and(|c| of(b) == Some(c))
}

/// A mention's description for the router, with the name the prompt gives it ("bedside
/// table", "two-burner hob", "patchwork quilt"), so the object is called what the prompt calls
/// it; the stage builds the plan's noun for it where the router would read the name as
/// something else (`StageState::route_asset`).
fn named_description(m: &Mention) -> String {
    let lex = crate::words::lexicon();
    let mut a = m.attributes.clone();
    // "two more music stands" are music stands.
    a.modifiers
        .retain(|w| !lex.is_relative_quantity(&w.to_lowercase()));
    if m.noun == m.category {
        return a.describe(&m.category);
    }
    let name_words: Vec<&str> = m
        .noun
        .split(' ')
        .filter(|w| !lex.is_relative_quantity(w))
        .collect();
    a.modifiers
        .retain(|w| !name_words.contains(&w.to_lowercase().as_str()));
    a.describe(&name_words.join(" "))
}

/// Whether the asset library builds `description` as a thing standing on the floor ("a
/// cast-iron wood stove" is a stove): the wall stage cannot hang it, so it stands against a
/// wall in the furniture stage.
fn built_on_the_floor(description: &str) -> bool {
    use crate::assets::procedural::{SupportClass, prior, support_sibling};
    // A kind with a wall-mounted sibling ("a cabinet on the wall": a wall cabinet) is hung.
    crate::assets::router::parse::main_categories(description)
        .first()
        .is_some_and(|c| {
            prior(c).is_some_and(|p| p.support == SupportClass::Floor)
                && support_sibling(c, SupportClass::Wall).is_none()
        })
}
