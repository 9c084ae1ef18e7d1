//! Checks of a built house: every room reachable from an exterior door through doors and open
//! connections (breadth-first search), en-suites entered only through their bedroom, no room
//! reachable only through a bathroom, required neighbours next to each other, no overlaps, and
//! how many rooms are reached only through another room that is not a corridor.
//!
//! The door graph is read from the rooms' walls (openings on walls with a neighbour), so the
//! same checks run on a reloaded `scene.json`.

use std::collections::{BTreeMap, BTreeSet, VecDeque};

use schemars::JsonSchema;
use serde::Serialize;

use super::knowledge::Role;
use super::search::{MIN_SHARED, Placement};
use super::spec::HouseSpec;
use crate::scene::{OpeningKind, Room};

/// Name of the outside in the door graph.
pub const OUTSIDE: &str = "outside";

/// The rooms joined by doors and open connections; `outside` for exterior doors.
pub fn door_graph(rooms: &[Room]) -> BTreeMap<String, BTreeSet<String>> {
    let mut g: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
    for r in rooms {
        g.entry(r.id.clone()).or_default();
        for w in &r.walls {
            let passable = w
                .openings
                .iter()
                .any(|o| matches!(o.kind, OpeningKind::Door | OpeningKind::Open));
            if !passable {
                continue;
            }
            let other = w.neighbor.clone().unwrap_or_else(|| OUTSIDE.to_string());
            g.entry(r.id.clone()).or_default().insert(other.clone());
            g.entry(other).or_default().insert(r.id.clone());
        }
    }
    g
}

/// Rooms reachable from the outside, avoiding the rooms in `blocked` (they may be reached but
/// not passed through).
pub fn reachable_from_outside(
    g: &BTreeMap<String, BTreeSet<String>>,
    blocked: &BTreeSet<String>,
) -> BTreeSet<String> {
    let mut seen = BTreeSet::new();
    let mut queue = VecDeque::from([OUTSIDE.to_string()]);
    seen.insert(OUTSIDE.to_string());
    while let Some(cur) = queue.pop_front() {
        if cur != OUTSIDE && blocked.contains(&cur) {
            continue;
        }
        for next in g.get(&cur).into_iter().flatten() {
            if seen.insert(next.clone()) {
                queue.push_back(next.clone());
            }
        }
    }
    seen.remove(OUTSIDE);
    seen
}

/// What validation found.
#[derive(Debug, Clone, Default, PartialEq, Serialize, JsonSchema)]
pub struct Validation {
    /// No errors.
    pub ok: bool,
    /// Problems that make the layout wrong, each naming the rooms involved.
    pub errors: Vec<String>,
    /// Things worth fixing.
    pub warnings: Vec<String>,
    /// Rooms no door path from outside reaches.
    pub unreachable: Vec<String>,
    /// Rooms that can only be reached by walking through a bathroom.
    pub only_through_bathroom: Vec<String>,
    /// Rooms reached only through another room that is not a corridor, hallway or entrance
    /// (en-suites, entered through their bedroom by design, are not counted).
    pub only_through_room: Vec<String>,
    /// Exterior doors.
    pub exterior_doors: usize,
}

/// Validates built rooms against their spec and placement.
pub fn validate(
    spec: &HouseSpec,
    placement: &Placement,
    rooms: &[Room],
    notes: &[String],
) -> Validation {
    let mut v = Validation::default();
    let g = door_graph(rooms);
    v.exterior_doors = g.get(OUTSIDE).map(|s| s.len()).unwrap_or(0);
    if v.exterior_doors == 0 {
        v.errors
            .push("no exterior door: add one to the entrance room".to_string());
    }
    let all = reachable_from_outside(&g, &BTreeSet::new());
    for r in &spec.rooms {
        if !all.contains(&r.id) {
            v.unreachable.push(r.id.clone());
        }
    }
    if !v.unreachable.is_empty() {
        v.errors.push(format!(
            "not reachable from the exterior door: {}",
            v.unreachable.join(", ")
        ));
    }
    // En-suites: one door, into their bedroom.
    for r in spec.rooms.iter().filter(|r| r.owner.is_some()) {
        let owner = r.owner.clone().unwrap_or_default();
        let links: Vec<String> = g.get(&r.id).into_iter().flatten().cloned().collect();
        if links != vec![owner.clone()] {
            v.errors.push(format!(
                "{} is an en-suite of {owner} but connects to: {}",
                r.id,
                if links.is_empty() {
                    "nothing".to_string()
                } else {
                    links.join(", ")
                }
            ));
        }
    }
    // Bathrooms are never passed through.
    let wet: BTreeSet<String> = spec
        .rooms
        .iter()
        .filter(|r| r.role == Role::Wet)
        .map(|r| r.id.clone())
        .collect();
    let dry_reach = reachable_from_outside(&g, &wet);
    for r in &spec.rooms {
        if all.contains(&r.id) && !dry_reach.contains(&r.id) {
            v.only_through_bathroom.push(r.id.clone());
        }
    }
    if !v.only_through_bathroom.is_empty() {
        v.errors.push(format!(
            "reachable only through a bathroom: {}",
            v.only_through_bathroom.join(", ")
        ));
    }
    // Rooms reached only through a room that is neither a hub nor an entrance (one with an
    // exterior door): the benchmark's flow measure.
    let entrances: BTreeSet<String> = g.get(OUTSIDE).cloned().unwrap_or_default();
    for r in &spec.rooms {
        // En-suites are meant to be entered through their bedroom.
        if !all.contains(&r.id) || entrances.contains(&r.id) || r.owner.is_some() {
            continue;
        }
        let blocked: BTreeSet<String> = spec
            .rooms
            .iter()
            .filter(|o| o.id != r.id && o.role != Role::Hub && !entrances.contains(&o.id))
            .map(|o| o.id.clone())
            .collect();
        if !reachable_from_outside(&g, &blocked).contains(&r.id) {
            v.only_through_room.push(r.id.clone());
        }
    }
    // Required neighbours and overlaps.
    for p in spec.adjacency.iter().filter(|p| p.required()) {
        if placement.shared(&p.a, &p.b) < MIN_SHARED - 1e-6 {
            v.errors.push(format!(
                "{} and {} must share a wall of at least {MIN_SHARED} m",
                p.a, p.b
            ));
        }
    }
    let ids: Vec<&String> = placement.cells.keys().collect();
    for (i, a) in ids.iter().enumerate() {
        for b in &ids[i + 1..] {
            if placement.cells[*a].overlaps(&placement.cells[*b]) {
                v.errors.push(format!("{a} overlaps {b}"));
            }
        }
    }
    for r in &spec.rooms {
        if !placement.cells.contains_key(&r.id) {
            v.errors.push(format!("{} is not placed", r.id));
        }
        if r.windows
            && !rooms.iter().any(|x| {
                x.id == r.id
                    && x.walls
                        .iter()
                        .any(|w| w.openings.iter().any(|o| o.kind == OpeningKind::Window))
            })
        {
            v.warnings.push(format!(
                "{} has no window (no outside wall free for one)",
                r.id
            ));
        }
    }
    v.warnings.extend(notes.iter().cloned());
    v.ok = v.errors.is_empty();
    v
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{Opening, Wall};

    fn room(id: &str, walls: Vec<(Option<&str>, bool)>) -> Room {
        Room {
            id: id.into(),
            room_type: "room".into(),
            label: None,
            prompt: String::new(),
            floor_polygon: vec![],
            wall_height: 2.7,
            walls: walls
                .into_iter()
                .enumerate()
                .map(|(k, (n, door))| Wall {
                    id: format!("{id}_wall_{k}"),
                    start: [0.0, 0.0],
                    end: [3.0, 0.0],
                    thickness: 0.12,
                    neighbor: n.map(str::to_string),
                    openings: if door {
                        vec![Opening {
                            id: format!("d{k}"),
                            kind: OpeningKind::Door,
                            center: 1.5,
                            width: 0.9,
                            bottom: 0.0,
                            height: 2.1,
                        }]
                    } else {
                        vec![]
                    },
                    mirror_of: None,
                })
                .collect(),
            floor_material: "oak".into(),
            wall_material: "plaster".into(),
        }
    }

    #[test]
    fn bfs_finds_cut_off_rooms_and_bathroom_passages() {
        // outside - hall - bath - bedroom; study has walls but no door.
        let rooms = vec![
            room("hall", vec![(None, true), (Some("bath"), true)]),
            room("bath", vec![(Some("hall"), true), (Some("bedroom"), true)]),
            room("bedroom", vec![(Some("bath"), true)]),
            room("study", vec![(Some("hall"), false)]),
        ];
        let g = door_graph(&rooms);
        let all = reachable_from_outside(&g, &BTreeSet::new());
        assert!(all.contains("bedroom") && !all.contains("study"));
        let dry = reachable_from_outside(&g, &BTreeSet::from(["bath".to_string()]));
        assert!(dry.contains("bath") && !dry.contains("bedroom"));
    }
}
