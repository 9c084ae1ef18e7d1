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

mod defaults;
mod explicit;
#[cfg(test)]
mod robustness;

use crate::knowledge::{self, Knowledge, Place, RoomType};
use crate::prompt::{Density, Reading};
use crate::words::{Lexicon, Support};

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
    /// Small objects: put away in the parent furniture's drawers and behind its doors.
    Stored,
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
    /// What the plan capped, in words for the user ("1000 chairs asked for, 120 planned:
    /// ...").
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub notes: Vec<String>,
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

/// Fewest small objects a room's plan holds before the stage sizes them to the built pieces
/// (at the usual density): below it the room gets storage pieces of its role
/// (`storage_for_clutter`). The stage grows a room's default clutter towards
/// `stages::clutter::ROOM_FLOOR` by at most `MAX_FLOOR_GROWTH` times, so this is their
/// quotient (a test there checks it).
pub const STORAGE_FLOOR: u32 = 30;

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
pub(crate) fn clutter_factor(d: Option<Density>) -> f64 {
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

/// At most this many of one thing that is neither kept in numbers nor one per parent (a
/// pitcher, a vase, a fruit bowl) per supporting piece, while the list has things kept in
/// numbers to take the rest.
pub(crate) const FEW_PER_PARENT: u32 = 4;

/// Splits `total` small objects over candidate nouns (most typical first): the first takes
/// half when it is a thing kept in numbers ([`kept_in_numbers`]: a bookshelf is mostly books,
/// a cupboard mostly plates, not a sideboard mostly vases), the rest cycle through the list in
/// order. A noun for which `single` holds (appliances, electronics, lamps) never takes the
/// half and stops at `singles_cap` (the number of parents: a counter has one coffee machine,
/// not half a dozen); one that is neither single nor kept in numbers stops at
/// [`FEW_PER_PARENT`] per parent while a noun kept in numbers is on the list (a sideboard's
/// pitchers and glasses: a few pitchers, the rest glasses).
pub(crate) fn split_counts(
    total: u32,
    items: &[&str],
    single: impl Fn(&str) -> bool,
    singles_cap: u32,
) -> Vec<(String, u32)> {
    let mut counts: Vec<(String, u32)> = Vec::new();
    if items.is_empty() || total == 0 {
        return counts;
    }
    let lex = crate::words::lexicon();
    let numerous = |noun: &str| !single(noun) && kept_in_numbers(lex, noun);
    let few =
        |noun: &str| !single(noun) && !numerous(noun) && items.iter().any(|other| numerous(other));
    let first = if items.len() > 1 && total >= 4 && numerous(items[0]) {
        total.div_ceil(2)
    } else {
        0
    };
    if first > 0 {
        counts.push((items[0].to_string(), first));
    }
    let rest = if first > 0 { &items[1..] } else { items };
    let mut left = total - first;
    while left > 0 {
        let mut added = false;
        for noun in rest {
            if left == 0 {
                break;
            }
            match counts.iter_mut().find(|(n, _)| n == noun) {
                Some((_, c)) if single(noun) && *c >= singles_cap => continue,
                Some((_, c)) if few(noun) && *c >= FEW_PER_PARENT * singles_cap.max(1) => {
                    continue;
                }
                Some((_, c)) => *c += 1,
                None => counts.push((noun.to_string(), 1)),
            }
            left -= 1;
            added = true;
        }
        if !added {
            // Every noun is at its cap: what is left goes to the first thing kept in numbers.
            if let Some(noun) = items.iter().copied().find(|n| numerous(n)) {
                match counts.iter_mut().find(|(n, _)| n == noun) {
                    Some((_, c)) => *c += left,
                    None => counts.push((noun.to_string(), left)),
                }
            }
            break;
        }
    }
    counts
}

/// True when `a` names `b` or a kind of `b`, or the other way round (explicit "table" covers
/// a default "dining table"; explicit "office chair" covers a default "chair").
/// Kinds of things a household keeps many of, side by side or stacked: books, tableware,
/// clothing, textiles, stationery, food, toys.
const KEPT_IN_NUMBERS: [&str; 7] = [
    "book",
    "tableware",
    "clothing",
    "textile",
    "stationery",
    "food",
    "toy",
];

/// Whether `noun` is a kind of [`KEPT_IN_NUMBERS`] in the lexicon.
pub(crate) fn kept_in_numbers(lex: &Lexicon, noun: &str) -> bool {
    KEPT_IN_NUMBERS.iter().any(|kind| covers(lex, noun, kind))
}

fn covers(lex: &Lexicon, a: &str, b: &str) -> bool {
    if a == b {
        return true;
    }
    lex.is_kind(a, b) || lex.is_kind(b, a)
}

/// Appliances, electronics, lamps, mirrors and clocks: one per supporting piece unless the
/// prompt asks for more (a vanity table grows more brushes, not a dozen hand mirrors).
pub(crate) fn one_per_parent(lex: &Lexicon, noun: &str) -> bool {
    ["appliance", "electronics", "lamp", "mirror", "clock"]
        .iter()
        .any(|kind| {
            covers(lex, noun, kind) || noun.strip_suffix(kind).is_some_and(|r| r.ends_with(' '))
        })
}

fn is_seat(lex: &Lexicon, noun: &str) -> bool {
    covers(lex, noun, "chair")
        || covers(lex, noun, "stool")
        || covers(lex, noun, "seating")
        || noun.ends_with("chair")
        || noun.ends_with("stool")
        || noun.ends_with("bench")
}

/// A seat that goes at a table: a chair, stool or bench, not lounge seating ("a big sofa and a
/// dining table for eight": eight chairs at the table, the sofa where sofas go).
fn is_table_seat(lex: &Lexicon, noun: &str) -> bool {
    is_seat(lex, noun)
        && !["sofa", "armchair"]
            .iter()
            .any(|lounge| covers(lex, noun, lounge) || noun.ends_with(lounge))
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
    plan_room_of_house(reading, room, &HouseContext::default())
}

/// What the whole prompt of a house says that one room's plan must honour.
#[derive(Debug, Clone, Default)]
pub struct HouseContext {
    /// The kinds (plan categories) the house's prompt counts exactly in other rooms: no
    /// default adds more of them ("the first bedroom holds two nightstands": the second
    /// bedroom gets none; "a vase of lilies" in the lobby: the corridor's console table holds
    /// no vases).
    pub elsewhere: Vec<String>,
    /// The kinds the house's prompt excludes anywhere ("There are no rugs anywhere in the
    /// apartment"): no room adds them unless that room asks for them.
    pub excluded: Vec<String>,
}

/// `plan_house_room`, with what the rest of the house's prompt says (see [`HouseContext`]).
pub fn plan_room_of_house(reading: &Reading, room: usize, house: &HouseContext) -> RoomPlan {
    let lex = crate::words::lexicon();
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
        house,
    };
    b.plan.styles.clone_from(&b.styles);
    b.explicit();
    b.place_settings();
    b.defaults();
    b.surface_parents();
    b.storage_for_clutter();
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
    /// Kinds the house's prompt counts exactly in other rooms (`plan_room_of_house`).
    house: &'a HouseContext,
}

impl Builder<'_> {
    // ---- explicit content -------------------------------------------------------------

    // ---- implied content ----------------------------------------------------------------
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::prompt;

    fn want<'a>(plan: &'a RoomPlan, noun: &str) -> &'a Want {
        plan.all_wants()
            .find(|w| w.noun == noun)
            .unwrap_or_else(|| panic!("no {noun} in {plan:#?}"))
    }

    #[test]
    fn a_few_pitchers_and_the_rest_glasses() {
        let lex = crate::words::lexicon();
        assert!(kept_in_numbers(lex, "glass") && !kept_in_numbers(lex, "pitcher"));
        let no_single = |_: &str| false;
        let get = |c: &[(String, u32)], n: &str| c.iter().find(|(m, _)| m == n).map_or(0, |x| x.1);
        // A sideboard's 30: at most 4 pitchers, the total kept.
        let c = split_counts(30, &["pitcher", "glass"], no_single, 1);
        assert_eq!((get(&c, "pitcher"), get(&c, "glass")), (4, 26));
        // Over two parents the cap doubles; with nothing kept in numbers there is no cap.
        let c = split_counts(30, &["pitcher", "glass"], no_single, 2);
        assert_eq!(get(&c, "pitcher"), 8);
        let c = split_counts(12, &["vase", "candlestick"], no_single, 1);
        assert_eq!(c.iter().map(|x| x.1).sum::<u32>(), 12);
        // Books first take half; vases and boxes stop at 4 and the books take the rest.
        let c = split_counts(30, &["book", "vase", "box"], no_single, 1);
        assert_eq!(c.iter().map(|x| x.1).sum::<u32>(), 30);
        assert!(get(&c, "vase") <= 4 && get(&c, "book") >= 15);
    }

    /// Counts that saturate in the reading (4000000000 desks) stay bounded in the plan.
    #[test]
    fn huge_numbers_stay_bounded() {
        let r = prompt::read(
            "A hall with 4000000000 desks, each with 4000000000 chairs, and 4000000000 pairs of \
             shoes.",
        );
        let plans = plan_rooms(&r);
        assert!(plans[0].all_wants().all(|w| w.count <= 120));
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
    fn a_counted_thing_gets_no_defaults_whose_head_it_is() {
        // The exam room's cabinets usually hold pill boxes and bandage boxes; "a box of latex
        // gloves" counts the room's boxes.
        let plain = plan_room(&prompt::read(
            "An exam room with an exam table and a cabinet.",
        ));
        assert!(plain.count_of("pill box") + plain.count_of("bandage box") > 0);
        let plan = plan_room(&prompt::read(
            "An exam room with an exam table, a cabinet and a counter that holds a box of latex \
             gloves.",
        ));
        assert_eq!(plan.count_of("pill box") + plan.count_of("bandage box"), 0);
        assert_eq!(plan.count_of("box"), 1);
    }

    #[test]
    fn a_default_does_not_hide_another_default_of_its_kind() {
        // The bathroom's shelf and towel rack (a kind of rack, a kind of shelf), its cabinet
        // and medicine cabinet: all the room's.
        let plan = plan_room(&prompt::read("A bathroom with a bathtub and a toilet."));
        for noun in ["towel rack", "medicine cabinet"] {
            assert!(
                plan.wall.iter().any(|w| w.noun == noun),
                "{noun}: {:?}",
                plan.wall
            );
        }
        assert!(plan.furniture.iter().any(|w| w.noun == "shelf"));
        // A bar's stools at its tables besides the bar stools at its counter.
        let plan = plan_room(&prompt::read("A bar."));
        for noun in ["bar stool", "stool"] {
            assert!(
                plan.furniture.iter().any(|w| w.noun == noun),
                "{noun}: {:?}",
                plan.furniture
            );
        }
        // An asked-for noun still covers the defaults of its kind.
        let plan = plan_room(&prompt::read("A bathroom with a cabinet."));
        assert!(!plan.wall.iter().any(|w| w.noun == "medicine cabinet"));
    }

    #[test]
    fn a_table_for_n_seats_n() {
        let plan = plan_room(&prompt::read(
            "A dining room with a long table for six people and a rug.",
        ));
        let chairs: u32 = plan
            .furniture
            .iter()
            .filter(|w| w.noun == "chair")
            .map(|w| w.count)
            .sum();
        assert_eq!(chairs, 6, "{:?}", plan.furniture);
        // A bare number ending the sentence.
        let plan = plan_room(&prompt::read("A dining room with a table for eight."));
        let chairs: u32 = plan
            .furniture
            .iter()
            .filter(|w| w.noun.ends_with("chair"))
            .map(|w| w.count)
            .sum();
        assert_eq!(chairs, 8, "{:?}", plan.furniture);
        // A table's seats are the prompt's, of whatever kind: no dining chairs besides.
        let plan = plan_room(&prompt::read(
            "The dining room features a long table with eight upholstered chairs beneath a \
             crystal chandelier.",
        ));
        let seats: Vec<(&str, u32)> = plan
            .furniture
            .iter()
            .filter(|w| is_seat(crate::words::lexicon(), &w.noun))
            .map(|w| (w.noun.as_str(), w.count))
            .collect();
        assert_eq!(seats, [("armchair", 8)], "{:?}", plan.furniture);
    }

    #[test]
    fn optional_pieces_stay_in_their_first_home() {
        let has = |p: &RoomPlan, n: &str| p.furniture.iter().any(|w| w.noun == n);
        let alone = plan_room(&prompt::read("a kitchen"));
        assert!(has(&alone, "dining table") && has(&alone, "sink"));
        let plans = plan_rooms(&prompt::read("A house with a kitchen and a dining room."));
        assert!(!has(&plans[0], "dining table"), "{:?}", plans[0].furniture);
        assert!(has(&plans[0], "sink"), "a kitchen keeps what it needs");
        assert!(has(&plans[1], "dining table"));
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

    #[test]
    fn what_the_library_stands_on_the_floor_is_furniture() {
        // A wood stove is a fireplace to the lexicon and a stove to the asset library: the
        // wall stage cannot hang it.
        let plan = plan_room(&prompt::read(
            "A kitchen with a cast-iron wood stove and a fireplace.",
        ));
        assert!(plan.wall.iter().all(|w| w.noun != "fireplace"), "{plan:#?}");
        assert!(plan.furniture.iter().any(|w| w.noun == "fireplace"));
    }

    #[test]
    fn more_of_a_thing_describes_nothing() {
        let plan = plan_room(&prompt::read(
            "A music room with a music stand beside the piano. Two more music stands are \
             folded in the corner, with an extra chair.",
        ));
        for w in plan.all_wants() {
            assert!(
                !w.description.contains("more") && !w.description.contains("extra"),
                "{w:?}"
            );
        }
        let stands: u32 = plan
            .all_wants()
            .filter(|w| w.noun == "music stand")
            .map(|w| w.count)
            .sum();
        assert_eq!(stands, 3);
    }
}
