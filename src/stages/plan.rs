//! What the built-in designers build: a room plan (furniture with arrangements, wall and
//! ceiling items, what goes on which surface), derived from the prompt reading and the room
//! type's defaults. Explicit prompt content wins over defaults; negations are obeyed.

use serde::{Deserialize, Serialize};

use crate::assets::procedural::{self, SupportClass};
use crate::prompt::{self, Count, Reading};

/// How a furniture piece is arranged.
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
    /// Facing another piece.
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
}

/// One wanted object (or group of identical objects).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Want {
    /// The noun (also the asset description unless `description` says more).
    pub noun: String,
    /// Free-text description for the asset router (attributes included).
    pub description: String,
    /// How many.
    pub count: u32,
    /// True when the prompt asked for it (coverage counts these).
    pub explicit: bool,
    /// True when the count is a minimum ("at least").
    pub at_least: bool,
    /// Arrangement (furniture) or placement hint.
    pub arrangement: Arrangement,
}

/// Small objects for one kind of supporting furniture.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SurfaceWant {
    /// Noun of the supporting furniture (`table`, `shelf`, ...).
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
    /// Nouns the prompt named that no generator knows (reported, not silent).
    pub unknown: Vec<String>,
}

impl RoomPlan {
    /// Explicitly requested nouns with their minimum counts (for coverage).
    pub fn requested(&self) -> Vec<(String, u32)> {
        let mut out: Vec<(String, u32)> = Vec::new();
        let all = self
            .furniture
            .iter()
            .chain(&self.wall)
            .chain(&self.ceiling)
            .chain(self.surfaces.iter().flat_map(|s| &s.items));
        for w in all.filter(|w| w.explicit) {
            match out.iter_mut().find(|(n, _)| *n == w.noun) {
                Some((_, c)) => *c = (*c).max(w.count),
                None => out.push((w.noun.clone(), w.count)),
            }
        }
        out
    }
}

fn count_of(c: Count, noun: &str) -> (u32, bool) {
    match c {
        Count::Exactly(n) => (n, false),
        Count::AtLeast(n) => (n, true),
        Count::Several => (if noun == "book" { 8 } else { 3 }, false),
    }
}

/// Default arrangement of a furniture noun.
fn arrangement_for(noun: &str, has_table: bool) -> Arrangement {
    match noun {
        "table" => Arrangement::Center,
        "chair" if has_table => Arrangement::Around {
            parent: "table".into(),
        },
        _ => Arrangement::AgainstWall,
    }
}

/// Builds the plan of a room from the prompt reading and the room type's defaults.
pub fn plan_room(reading: &Reading) -> RoomPlan {
    let mut plan = RoomPlan::default();
    let mut counts: Vec<(String, u32, bool, bool)> = Vec::new(); // noun, count, at_least, explicit
    for m in &reading.mentions {
        if m.negated {
            if !plan.excluded.contains(&m.category) {
                plan.excluded.push(m.category.clone());
            }
            continue;
        }
        let (n, at_least) = count_of(m.count, &m.category);
        match counts.iter_mut().find(|(c, ..)| *c == m.category) {
            Some(e) => e.1 = e.1.max(n),
            None => counts.push((m.category.clone(), n, at_least, true)),
        }
    }
    let has_floor_item = counts
        .iter()
        .any(|(c, ..)| procedural::prior(c).is_some_and(|p| p.support == SupportClass::Floor));
    if !has_floor_item && let Some(info) = prompt::room_types().get(&reading.room_type) {
        for (noun, n) in &info.defaults {
            if !counts.iter().any(|(c, ..)| c == noun) {
                counts.push((noun.clone(), *n, false, false));
            }
        }
    }
    counts.retain(|(c, n, ..)| *n > 0 && !plan.excluded.contains(c));
    let has_table = counts.iter().any(|(c, ..)| c == "table");
    // Anchors first: tables, then the rest of the floor pieces, chairs last.
    counts.sort_by_key(|(c, ..)| match c.as_str() {
        "table" => 0,
        "chair" => 2,
        _ => 1,
    });
    let mut surface_items: Vec<Want> = Vec::new();
    for (noun, count, at_least, explicit) in counts {
        let want = |arrangement| Want {
            noun: noun.clone(),
            description: noun.clone(),
            count: count.min(60),
            explicit,
            at_least,
            arrangement,
        };
        match procedural::prior(&noun).map(|p| p.support) {
            Some(SupportClass::Floor) => {
                plan.furniture.push(want(arrangement_for(&noun, has_table)))
            }
            Some(SupportClass::Wall) => plan.wall.push(want(Arrangement::Free)),
            Some(SupportClass::Ceiling) => plan.ceiling.push(want(Arrangement::Free)),
            Some(SupportClass::Surface) => surface_items.push(want(Arrangement::Free)),
            None => plan.unknown.push(noun.clone()),
        }
    }
    // Small objects: tableware on tables as place settings, books on shelves, the rest on any
    // surface (the designer falls back through every surface).
    let (tableware, rest): (Vec<Want>, Vec<Want>) = surface_items
        .into_iter()
        .partition(|w| matches!(w.noun.as_str(), "plate" | "mug") && has_table);
    if !tableware.is_empty() {
        plan.surfaces.push(SurfaceWant {
            parent: "table".into(),
            items: tableware,
            place_settings: true,
        });
    }
    let (books, others): (Vec<Want>, Vec<Want>) = rest.into_iter().partition(|w| w.noun == "book");
    if !books.is_empty() {
        plan.surfaces.push(SurfaceWant {
            parent: "shelf".into(),
            items: books,
            place_settings: false,
        });
    }
    if !others.is_empty() {
        plan.surfaces.push(SurfaceWant {
            parent: "any".into(),
            items: others,
            place_settings: false,
        });
    }
    plan
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn explicit_counts_negations_and_defaults() {
        let plan = plan_room(&prompt::read(
            "A kitchen with a table, four chairs and 6 mugs, and no cabinet.",
        ));
        let chairs = plan.furniture.iter().find(|w| w.noun == "chair").unwrap();
        assert_eq!(chairs.count, 4);
        assert_eq!(
            chairs.arrangement,
            Arrangement::Around {
                parent: "table".into()
            }
        );
        assert!(plan.excluded.contains(&"cabinet".to_string()));
        assert!(!plan.furniture.iter().any(|w| w.noun == "cabinet"));
        assert_eq!(plan.surfaces[0].parent, "table");
        assert!(plan.surfaces[0].place_settings);
        let mut req = plan.requested();
        req.sort();
        assert_eq!(
            req,
            vec![("chair".into(), 4), ("mug".into(), 6), ("table".into(), 1)]
        );
    }

    #[test]
    fn defaults_fill_a_bare_room() {
        let plan = plan_room(&prompt::read("a library"));
        assert!(
            plan.furniture
                .iter()
                .any(|w| w.noun == "shelf" && !w.explicit)
        );
        assert!(plan.requested().is_empty());
    }
}
