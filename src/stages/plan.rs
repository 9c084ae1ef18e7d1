//! What the built-in designers build: a room plan (furniture with arrangements, wall and
//! ceiling items, what goes on which surface), merged from the prompt reading of one room and
//! its room type's knowledge.
//!
//! Rules: explicit prompt content always wins over defaults (a requested noun, or a broader or
//! narrower one, is never duplicated by a default); negations are obeyed (a default whose noun
//! or class was excluded is dropped); density words scale the defaults (minimalist: only what a
//! room of the type needs; cluttered: the high end of every range and more small objects);
//! attributes travel in `Want::description`; nouns the lexicon does not know are still planned
//! and also listed in `unknown`. The same reading always gives the same plan.
//!
//! This module plans; it does not place (the stage designers do) or build assets (the asset
//! router does).

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

use crate::knowledge::{self, KbItem, Knowledge, Place, RoomType};
use crate::prompt::{
    self, Count, Density, GroupKind, Lexicon, Mention, Per, Reading, RelationKind, Support, Target,
};

/// How a piece is arranged.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum Arrangement {
    /// Back against a free wall.
    AgainstWall,
    /// In a corner.
    Corner,
    /// In the open middle of the room.
    Center,
    /// Around a table-like parent, facing it.
    Around {
        /// The parent's noun.
        parent: String,
    },
    /// Facing another piece (the piece's own noun: facing each other).
    Facing {
        /// The target's noun.
        target: String,
    },
    /// Close to the window.
    NearWindow,
    /// Close to the entrance.
    NearEntrance,
    /// Anywhere sensible.
    Free,
    /// Small objects: one stack.
    Stack,
    /// Small objects: a loose pile.
    Pile,
    /// Small objects: inside a container.
    Inside {
        /// The container's noun.
        parent: String,
    },
    /// Wall or ceiling objects: above another object.
    Above {
        /// The target's noun.
        target: String,
    },
    /// Next to another piece.
    Beside {
        /// The target's noun.
        target: String,
    },
    /// One on each side of another piece (nightstands by the bed).
    Flanking {
        /// The target's noun.
        target: String,
    },
    /// In front of another piece (coffee table before the sofa).
    InFront {
        /// The target's noun.
        target: String,
    },
    /// Behind another piece (shelves behind the bar counter).
    Behind {
        /// The target's noun.
        target: String,
    },
    /// Under another piece (rug under the dining table).
    Under {
        /// The target's noun.
        target: String,
    },
    /// Between pieces (coffee table between two sofas).
    Between {
        /// The targets' nouns (one noun when the target is a group, "between them").
        targets: Vec<String>,
    },
    /// Across the room from something; `entrance` means the wall facing the door.
    AcrossFrom {
        /// The target's noun, or `entrance`.
        target: String,
    },
    /// At the front of the room (teacher's desk, board).
    FrontOfRoom,
    /// Several in a row along one wall.
    RowAlongWall,
    /// Several in a grid over the floor (classroom desks).
    Grid,
    /// Small objects: on top of another small object (cup on saucer, cheese on plate).
    On {
        /// The supporting object's noun.
        parent: String,
    },
}

impl Arrangement {
    /// The other object this arrangement refers to, if any.
    pub fn target(&self) -> Option<&str> {
        match self {
            Arrangement::Around { parent }
            | Arrangement::Inside { parent }
            | Arrangement::On { parent } => Some(parent),
            Arrangement::Facing { target }
            | Arrangement::Above { target }
            | Arrangement::Beside { target }
            | Arrangement::Flanking { target }
            | Arrangement::InFront { target }
            | Arrangement::Behind { target }
            | Arrangement::Under { target } => Some(target),
            Arrangement::AcrossFrom { target } if target != "entrance" => Some(target),
            Arrangement::Between { targets } => targets.first().map(String::as_str),
            _ => None,
        }
    }

    fn with_target(&self, f: impl Fn(&str) -> String) -> Arrangement {
        let mut a = self.clone();
        match &mut a {
            Arrangement::Around { parent }
            | Arrangement::Inside { parent }
            | Arrangement::On { parent } => *parent = f(parent),
            Arrangement::Facing { target }
            | Arrangement::Above { target }
            | Arrangement::Beside { target }
            | Arrangement::Flanking { target }
            | Arrangement::InFront { target }
            | Arrangement::Behind { target }
            | Arrangement::Under { target } => *target = f(target),
            Arrangement::AcrossFrom { target } if target != "entrance" => *target = f(target),
            Arrangement::Between { targets } => {
                for t in targets.iter_mut() {
                    *t = f(t);
                }
            }
            _ => {}
        }
        a
    }
}

/// One wanted object (or group of identical objects).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Want {
    /// The canonical noun (the asset router maps it to a generator).
    pub noun: String,
    /// Free-text description for the asset router (attributes included).
    pub description: String,
    /// How many (a total over all parents for small objects).
    pub count: u32,
    /// True when the prompt asked for it (coverage counts these).
    pub explicit: bool,
    /// True when the count is a minimum ("at least").
    pub at_least: bool,
    /// Arrangement (furniture) or placement hint.
    pub arrangement: Arrangement,
    /// Mounting height of wall items, metres (from the knowledge base).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub height_m: Option<f64>,
    /// Which member of a plural parent holds these ("the other bin": 1), when the prompt says.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub parent_instance: Option<u32>,
}

/// Small objects for one kind of supporting furniture.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SurfaceWant {
    /// Noun of the supporting furniture (`table`, `shelf`, ...), `floor` for objects on the
    /// floor, `any` when nothing in particular.
    pub parent: String,
    /// The objects (counts are totals over all parents of that noun).
    pub items: Vec<Want>,
    /// Lay the items out as one place setting per seat around the parent.
    pub place_settings: bool,
}

/// Everything the built-in designers should build in one room.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct RoomPlan {
    /// Floor furniture in placement order (anchors first).
    pub furniture: Vec<Want>,
    /// Wall-mounted objects.
    pub wall: Vec<Want>,
    /// Ceiling objects.
    pub ceiling: Vec<Want>,
    /// Small objects by supporting furniture.
    pub surfaces: Vec<SurfaceWant>,
    /// Nouns the prompt excluded.
    pub excluded: Vec<String>,
    /// Nouns the prompt named that no lexicon entry knows (planned anyway, reported).
    pub unknown: Vec<String>,
    /// Room-type key the plan was made for.
    #[serde(default)]
    pub room_type: String,
    /// Styles and themes of the whole room.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub styles: Vec<String>,
    /// Density the defaults were scaled for.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub density: Option<Density>,
}

impl RoomPlan {
    /// Explicitly requested nouns with their minimum counts (for coverage).
    pub fn requested(&self) -> Vec<(String, u32)> {
        let mut out: Vec<(String, u32)> = Vec::new();
        for w in self.all_wants().filter(|w| w.explicit) {
            match out.iter_mut().find(|(n, _)| *n == w.noun) {
                Some((_, c)) => *c += w.count,
                None => out.push((w.noun.clone(), w.count)),
            }
        }
        out
    }

    /// Every want of the plan (furniture, wall, ceiling, surface items).
    pub fn all_wants(&self) -> impl Iterator<Item = &Want> {
        self.furniture
            .iter()
            .chain(&self.wall)
            .chain(&self.ceiling)
            .chain(self.surfaces.iter().flat_map(|s| &s.items))
    }

    /// Total count of a noun over the whole plan.
    pub fn count_of(&self, noun: &str) -> u32 {
        self.all_wants()
            .filter(|w| w.noun == noun)
            .map(|w| w.count)
            .sum()
    }
}

/// Upper bound on one want's count (a room holds only so much).
const MAX_COUNT: u32 = 120;

/// How far into a [min, max] range the defaults go, per density.
fn fill_factor(d: Option<Density>) -> f64 {
    match d {
        Some(Density::Minimalist | Density::Sparse) => 0.0,
        Some(Density::Pristine) | None => 0.5,
        Some(Density::LivedIn) => 0.75,
        Some(Density::Cluttered | Density::Packed) => 1.0,
    }
}

/// Multiplier on small-object counts per density.
fn clutter_factor(d: Option<Density>) -> f64 {
    match d {
        Some(Density::Minimalist | Density::Sparse) => 0.5,
        Some(Density::Pristine) => 0.75,
        None => 1.0,
        Some(Density::LivedIn) => 1.25,
        Some(Density::Cluttered) => 1.6,
        Some(Density::Packed) => 2.0,
    }
}

fn pick(range: [u32; 2], t: f64) -> u32 {
    let (lo, hi) = (range[0].min(range[1]), range[0].max(range[1]));
    lo + ((hi - lo) as f64 * t).round() as u32
}

/// True when `a` names `b` or a kind of `b`, or the other way round (explicit "table" covers
/// a default "dining table"; explicit "office chair" covers a default "chair").
fn covers(lex: &Lexicon, a: &str, b: &str) -> bool {
    if a == b {
        return true;
    }
    let is_kind = |x: &str, of: &str| {
        let mut k = lex.lookup(x).and_then(|e| e.kind_of.clone());
        for _ in 0..3 {
            match k {
                Some(ref y) if y == of => return true,
                Some(ref y) => k = lex.lookup(y).and_then(|e| e.kind_of.clone()),
                None => return false,
            }
        }
        false
    };
    is_kind(a, b) || is_kind(b, a)
}

fn is_seat(lex: &Lexicon, noun: &str) -> bool {
    covers(lex, noun, "chair")
        || covers(lex, noun, "stool")
        || covers(lex, noun, "seating")
        || noun.ends_with("chair")
        || noun.ends_with("stool")
        || noun.ends_with("bench")
}

fn is_table_like(lex: &Lexicon, noun: &str) -> bool {
    lex.lookup(noun)
        .is_some_and(|e| e.holds && e.support == Support::Floor)
        && ["table", "desk", "counter", "workbench"]
            .iter()
            .any(|k| covers(lex, noun, k) || noun.ends_with(k))
}

fn place_to_arrangement(p: &Place) -> Arrangement {
    match p {
        Place::AgainstWall => Arrangement::AgainstWall,
        Place::Corner => Arrangement::Corner,
        Place::Center => Arrangement::Center,
        Place::Around(n) => Arrangement::Around { parent: n.clone() },
        Place::Facing(n) => Arrangement::Facing { target: n.clone() },
        Place::InFront(n) => Arrangement::InFront { target: n.clone() },
        Place::Behind(n) => Arrangement::Behind { target: n.clone() },
        Place::Beside(n) => Arrangement::Beside { target: n.clone() },
        Place::Flanking(n) => Arrangement::Flanking { target: n.clone() },
        Place::Under(n) => Arrangement::Under { target: n.clone() },
        Place::NearWindow => Arrangement::NearWindow,
        Place::NearEntrance => Arrangement::NearEntrance,
        Place::AcrossFrom(n) => Arrangement::AcrossFrom { target: n.clone() },
        Place::FrontOfRoom => Arrangement::FrontOfRoom,
        Place::RowAlongWall => Arrangement::RowAlongWall,
        Place::Grid => Arrangement::Grid,
        Place::Above(n) => Arrangement::Above { target: n.clone() },
        Place::Spread => Arrangement::Free,
    }
}

/// Builds the plan of a single-room reading (the first room of a house reading).
pub fn plan_room(reading: &Reading) -> RoomPlan {
    plan_house_room(reading, 0)
}

/// Builds the plans of every room of a reading, in room order.
pub fn plan_rooms(reading: &Reading) -> Vec<RoomPlan> {
    (0..reading.rooms.len().max(1))
        .map(|i| plan_house_room(reading, i))
        .collect()
}

/// Builds the plan of room `room` of a reading: the room's mentions merged with its room
/// type's defaults.
pub fn plan_house_room(reading: &Reading, room: usize) -> RoomPlan {
    let lex = prompt::lexicon();
    let kb = knowledge::knowledge();
    let info = reading.rooms.get(room);
    let room_type = info.map_or(reading.room_type.as_str(), |r| r.room_type.as_str());
    let rt = kb.room(room_type).or_else(|| kb.room("room"));
    let density = info.and_then(|r| r.density).or(reading.density);
    let styles: Vec<String> = info
        .map(|r| r.styles.clone())
        .unwrap_or_else(|| reading.styles.clone());
    let mut b = Builder {
        lex,
        kb,
        reading,
        room,
        rt,
        density,
        styles,
        plan: RoomPlan {
            room_type: room_type.to_string(),
            density,
            ..RoomPlan::default()
        },
        surface: Vec::new(),
        floor_of: BTreeMap::new(),
    };
    b.plan.styles.clone_from(&b.styles);
    b.explicit();
    b.place_settings();
    b.defaults();
    b.surface_parents();
    b.surface_defaults();
    b.finish()
}

/// A small object before grouping by parent.
#[derive(Debug, Clone)]
struct SurfaceItem {
    parent: String,
    want: Want,
    place_settings: bool,
}

struct Builder<'a> {
    lex: &'a Lexicon,
    kb: &'a Knowledge,
    reading: &'a Reading,
    room: usize,
    rt: Option<&'a RoomType>,
    density: Option<Density>,
    styles: Vec<String>,
    plan: RoomPlan,
    surface: Vec<SurfaceItem>,
    /// Default noun -> the explicit noun that covers it (for rule targets).
    floor_of: BTreeMap<String, String>,
}

impl Builder<'_> {
    fn mentions(&self) -> impl Iterator<Item = (usize, &Mention)> {
        self.reading.room_mentions(self.room)
    }

    fn excluded(&self, noun: &str) -> bool {
        self.plan
            .excluded
            .iter()
            .any(|x| covers(self.lex, noun, x) || x == noun)
    }

    /// Count of mention `i` in this plan: a plain count, or a per-parent count resolved
    /// against the parent's planned count; "several" from the knowledge base.
    fn count(&self, i: usize, depth: usize) -> (u32, bool) {
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
                (u * n, a || b)
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
                (u * settings * n, a || b)
            }
        }
    }

    /// What "several" means for a noun (per parent when `parent` is given).
    fn several(&self, m: &Mention, parent: Option<&Mention>) -> u32 {
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

    fn describe(&self, m: &Mention, support: Support) -> String {
        let d = m.description();
        if m.attributes.styles.is_empty() && support != Support::Surface {
            if let Some(s) = self.styles.first() {
                return format!("{s} style {d}");
            }
        }
        d
    }

    fn default_description(&self, noun: &str, support: Support) -> String {
        match self.styles.first() {
            Some(s) if support != Support::Surface => format!("{s} style {noun}"),
            _ => noun.to_string(),
        }
    }

    /// Arrangement from a mention's relations (explicit first), or None.
    fn relation_arrangement(&self, m: &Mention, count: u32) -> Option<Arrangement> {
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
        rels.sort_by_key(|r| (r.implied, rank(r.kind)));
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
    fn kb_arrangement(&self, noun: &str) -> Option<Arrangement> {
        self.rt
            .and_then(|r| r.item(noun))
            .and_then(|i| i.place.as_ref())
            .or_else(|| self.kb.placement(noun))
            .map(place_to_arrangement)
    }

    // ---- explicit content -------------------------------------------------------------

    fn explicit(&mut self) {
        let mentions: Vec<(usize, Mention)> =
            self.mentions().map(|(i, m)| (i, m.clone())).collect();
        for (_, m) in mentions.iter().filter(|(_, m)| m.negated) {
            if !self.plan.excluded.contains(&m.category) {
                self.plan.excluded.push(m.category.clone());
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
            if m.negated || skip.contains(i) || self.excluded(&m.category) {
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
            match support {
                Support::Floor => {
                    want.arrangement = self
                        .relation_arrangement(m, count)
                        .or_else(|| self.kb_arrangement(&m.category))
                        .unwrap_or(Arrangement::AgainstWall);
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

    /// A small object: its parent furniture and how it lies there.
    fn explicit_surface(&mut self, m: &Mention, mut want: Want) {
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

    // ---- implied content ----------------------------------------------------------------

    /// "A table set for 4 people": seats per setting when the prompt names none, default
    /// setting items when it names none.
    fn place_settings(&mut self) {
        let tables: Vec<(usize, Mention)> = self
            .mentions()
            .filter(|(_, m)| m.place_settings.is_some() && !m.negated)
            .map(|(i, m)| (i, m.clone()))
            .collect();
        for (i, t) in tables {
            let per = t.place_settings.unwrap_or(0);
            let (tables_n, _) = self.count(i, 0);
            let seats = per * tables_n;
            let has_seats = self
                .plan
                .furniture
                .iter()
                .any(|w| is_seat(self.lex, &w.noun));
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
                    .filter(|w| is_seat(self.lex, &w.noun))
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

    /// The explicit noun that covers a default noun, if any.
    fn covered_by(&self, noun: &str) -> Option<String> {
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
            if found.is_none() && covers(self.lex, p, noun) {
                found = Some(p.to_string());
            }
        }
        found
    }

    /// Room-type defaults, scaled by density and room size, minus what the prompt covers or
    /// excludes.
    fn defaults(&mut self) {
        let Some(rt) = self.rt else { return };
        let t = fill_factor(self.density);
        let explicit_floor = self.plan.furniture.iter().filter(|w| w.explicit).count();
        // A prompt that lists its furniture gets the essentials, not every option.
        let t_optional = if explicit_floor >= 3 { 0.0 } else { t };
        let scale = self
            .reading
            .rooms
            .get(self.room)
            .map_or(1.0, |r| r.size_scale);
        let add = |b: &mut Self, item: &KbItem, support: Support| {
            if b.excluded(&item.noun) {
                return;
            }
            if let Some(by) = b.covered_by(&item.noun) {
                b.floor_of.insert(item.noun.clone(), by);
                return;
            }
            let tt = if item.count[0] == 0 { t_optional } else { t };
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
            match support {
                Support::Floor => b.plan.furniture.push(want),
                Support::Wall => b.plan.wall.push(want),
                _ => b.plan.ceiling.push(want),
            }
        };
        for item in &rt.furniture {
            add(self, item, Support::Floor);
        }
        for item in &rt.wall_items {
            add(self, item, Support::Wall);
        }
        for item in &rt.ceiling {
            add(self, item, Support::Ceiling);
        }
        // Seats for table-like pieces the prompt named "with chairs" but without a count are
        // handled by `count`; seats for set tables by `place_settings`.
    }

    fn has(&self, noun: &str) -> bool {
        self.plan
            .furniture
            .iter()
            .chain(&self.plan.wall)
            .chain(&self.plan.ceiling)
            .any(|w| w.noun == noun)
    }

    /// Small objects without a named parent go where they usually rest; a usual parent the
    /// room lacks is added ("a TV" brings a TV stand).
    fn surface_parents(&mut self) {
        let lex = self.lex;
        for k in 0..self.surface.len() {
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
                let arrangement = self.kb_arrangement(&p).unwrap_or(Arrangement::AgainstWall);
                let want = Want {
                    noun: p.clone(),
                    description: self.default_description(&p, support),
                    count: 1,
                    explicit: false,
                    at_least: false,
                    arrangement,
                    height_m: None,
                    parent_instance: None,
                };
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

    /// Default small objects on parents that the prompt left empty.
    fn surface_defaults(&mut self) {
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
            let rule = self
                .rt
                .and_then(|r| r.surface_rule(&parent))
                .or_else(|| self.kb.surface_rule(&parent))
                .cloned();
            let Some(rule) = rule else { continue };
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
            let total = (per_parent * n_parents).min(MAX_COUNT);
            let items: Vec<&String> = rule.items.iter().filter(|i| !self.excluded(i)).collect();
            if items.is_empty() || total == 0 {
                continue;
            }
            // The most typical object takes half (a bookshelf is mostly books); the rest
            // cycle through the list in order.
            let mut counts: Vec<(String, u32)> = Vec::new();
            let first = if items.len() > 1 && total >= 4 {
                total.div_ceil(2)
            } else {
                0
            };
            if first > 0 {
                counts.push((items[0].clone(), first));
            }
            let rest: Vec<&String> = if first > 0 {
                items[1..].to_vec()
            } else {
                items.clone()
            };
            for k in 0..(total - first) as usize {
                let noun = rest[k % rest.len()].clone();
                match counts.iter_mut().find(|(n, _)| *n == noun) {
                    Some((_, c)) => *c += 1,
                    None => counts.push((noun, 1)),
                }
            }
            for (noun, c) in counts {
                self.surface.push(SurfaceItem {
                    parent: parent.clone(),
                    want: Want {
                        noun: noun.clone(),
                        description: noun,
                        count: c,
                        explicit: false,
                        at_least: false,
                        arrangement: Arrangement::Free,
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
    fn repair_targets(&mut self) {
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

    fn finish(mut self) -> RoomPlan {
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

#[cfg(test)]
mod tests {
    use super::*;

    fn want<'a>(plan: &'a RoomPlan, noun: &str) -> &'a Want {
        plan.all_wants()
            .find(|w| w.noun == noun)
            .unwrap_or_else(|| panic!("no {noun} in {plan:#?}"))
    }

    #[test]
    fn explicit_counts_negations_and_defaults() {
        let plan = plan_room(&prompt::read(
            "A kitchen with a table, four chairs and 6 mugs, and no cabinet.",
        ));
        let chairs = want(&plan, "chair");
        assert_eq!(chairs.count, 4);
        assert_eq!(
            chairs.arrangement,
            Arrangement::Around {
                parent: "table".into()
            }
        );
        assert!(plan.excluded.contains(&"cabinet".to_string()));
        // "no cabinet" also drops the kitchen's default kitchen cabinets.
        assert!(!plan.furniture.iter().any(|w| w.noun.contains("cabinet")));
        let mut req = plan.requested();
        req.sort();
        assert_eq!(
            req,
            vec![("chair".into(), 4), ("mug".into(), 6), ("table".into(), 1)]
        );
        // The explicit table covers the default dining table: no second table.
        assert!(!plan.furniture.iter().any(|w| w.noun == "dining table"));
        // Kitchen defaults fill the rest.
        assert!(
            plan.furniture
                .iter()
                .any(|w| w.noun == "refrigerator" && !w.explicit)
        );
    }

    #[test]
    fn defaults_fill_a_bare_room_and_density_scales() {
        let normal = plan_room(&prompt::read("a library"));
        assert!(
            normal
                .furniture
                .iter()
                .any(|w| w.noun == "bookshelf" && !w.explicit)
        );
        assert!(normal.requested().is_empty());
        let books = |p: &RoomPlan| p.count_of("book");
        let sparse = plan_room(&prompt::read("a minimalist library"));
        let full = plan_room(&prompt::read("a cluttered library"));
        assert!(
            books(&sparse) < books(&normal),
            "{} {}",
            books(&sparse),
            books(&normal)
        );
        assert!(
            books(&full) > books(&normal),
            "{} {}",
            books(&full),
            books(&normal)
        );
    }

    #[test]
    fn place_settings_imply_seats_and_items() {
        let plan = plan_room(&prompt::read(
            "A dining room with a table set for 4 people.",
        ));
        assert_eq!(want(&plan, "chair").count, 4);
        let g = plan.surfaces.iter().find(|s| s.place_settings).unwrap();
        assert_eq!(g.parent, "table");
        assert!(g.items.iter().any(|w| w.noun == "plate" && w.count == 4));
    }

    #[test]
    fn attributes_and_unknown_nouns() {
        let plan = plan_room(&prompt::read(
            "A Star Wars themed bedroom with a red ceramic mug on a desk and a glowing flux capacitor.",
        ));
        assert_eq!(want(&plan, "mug").description, "red ceramic mug");
        assert!(want(&plan, "bed").description.starts_with("Star Wars"));
        assert!(
            plan.unknown.contains(&"flux capacitor".to_string()),
            "{:?}",
            plan.unknown
        );
        assert!(plan.all_wants().any(|w| w.noun == "flux capacitor"));
    }

    #[test]
    fn tv_brings_its_stand_and_same_reading_same_plan() {
        let r = prompt::read("A gym with a TV.");
        let plan = plan_room(&r);
        assert!(plan.furniture.iter().any(|w| w.noun == "tv stand"));
        assert!(
            plan.surfaces
                .iter()
                .any(|s| s.parent == "tv stand" && s.items.iter().any(|w| w.noun == "tv"))
        );
        assert_eq!(plan, plan_room(&r));
    }
}
