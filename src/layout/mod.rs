//! Layout stage: from the prompt to rooms, their sizes and how they connect, then volumetric
//! walls and floors with doors, windows and open connections, per-room materials and per-room
//! prompts for the placement stages.
//!
//! The data flows: [`brief`] reads the prompt into rooms (counts, en-suites, the sentences
//! about each room), [`spec`] sizes them (type sizes, size words, contents) and decides who
//! may be entered from whom, [`search`] places them edge to edge as [`cells`], [`connect`]
//! plans doors and windows, [`walls`] builds the scene rooms, [`validate`] checks them (the
//! room's static asset is built by `assets::architecture`). [`state`], [`tools`], [`builtin`] and
//! [`stage`] run all of it as an agent-loop stage; [`ascii`] draws a text floor plan.
//! Furnishing the rooms is not done here.

pub mod ascii;
pub mod brief;
pub mod builtin;
pub mod cells;
pub mod connect;
pub mod knowledge;
pub mod materials;
pub mod search;
pub mod spec;
pub mod stage;
pub mod state;
pub mod tools;
pub mod validate;
pub mod walls;

use rand::RngExt;
use rand::rngs::ChaCha8Rng;

use crate::prompt::Reading;
use crate::scene::{Opening, OpeningKind, Room, rectangle_walls};

/// Default wall thickness, metres.
pub const WALL_THICKNESS: f64 = 0.12;
/// Standard door: width, height (metres).
pub const DOOR_SIZE: [f64; 2] = [0.9, 2.1];
/// Standard window: width, height, sill (metres).
pub const WINDOW_SIZE: [f64; 3] = [1.2, 1.2, 0.9];

/// One room for the whole prompt without the layout stage: clear floor from the type's typical
/// size (scaled by size words inside the type's range, then jittered by the seed), a door in
/// the south wall and a window in the north wall. The pipeline runs [`stage::run_layout`]
/// instead.
pub fn single_room(
    room_id: &str,
    reading: &Reading,
    prompt_text: &str,
    rng: &mut ChaCha8Rng,
) -> Room {
    let info = knowledge::kind(&reading.room_type);
    let [long, short] = info.size.scaled(reading.size_scale);
    let jitter = |rng: &mut ChaCha8Rng| 1.0 + rng.random_range(-0.05..0.05);
    let w = (long * jitter(rng) * 10.0).round() / 10.0;
    let d = (short * jitter(rng) * 10.0).round() / 10.0;
    let w = w.max(2.0);
    let d = d.max(2.0);
    let mut walls = rectangle_walls(room_id, [0.0, 0.0], w, d, WALL_THICKNESS);

    // Door in the south wall, near one end (where it leaves the most usable wall).
    let south_len = walls[0].length();
    let door_center = if rng.random_bool(0.5) {
        WALL_THICKNESS / 2.0 + 0.25 + DOOR_SIZE[0] / 2.0
    } else {
        south_len - WALL_THICKNESS / 2.0 - 0.25 - DOOR_SIZE[0] / 2.0
    };
    walls[0].openings.push(Opening {
        id: format!("{room_id}_door_0"),
        kind: OpeningKind::Door,
        center: door_center,
        width: DOOR_SIZE[0],
        bottom: 0.0,
        height: DOOR_SIZE[1],
    });
    // Window centred in the north wall.
    let north_len = walls[2].length();
    walls[2].openings.push(Opening {
        id: format!("{room_id}_window_0"),
        kind: OpeningKind::Window,
        center: north_len / 2.0,
        width: WINDOW_SIZE[0].min(north_len * 0.5),
        bottom: WINDOW_SIZE[2],
        height: WINDOW_SIZE[1],
    });
    Room {
        id: room_id.to_string(),
        room_type: reading.room_type.clone(),
        label: reading.rooms.first().map(|r| r.words.clone()),
        prompt: prompt_text.to_string(),
        floor_polygon: vec![[0.0, 0.0], [w, 0.0], [w, d], [0.0, d]],
        wall_height: info.wall_height,
        walls,
        floor_material: info.floor.clone(),
        wall_material: info.wall.clone(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::prompt;
    use rand::SeedableRng;

    #[test]
    fn kitchen_is_kitchen_sized_and_enclosed() {
        let reading = prompt::read("a kitchen with a table");
        let mut rng = ChaCha8Rng::seed_from_u64(1);
        let room = single_room("kitchen_0", &reading, "a kitchen with a table", &mut rng);
        let (lo, hi) = crate::geometry::polygon::bounds(&room.floor_polygon);
        assert!((hi[0] - lo[0] - 4.2).abs() < 0.4);
        assert_eq!(room.walls.len(), 4);
        // Walls close: each ends where the next starts.
        for i in 0..4 {
            assert_eq!(room.walls[i].end, room.walls[(i + 1) % 4].start);
        }
        let doors = room
            .walls
            .iter()
            .flat_map(|w| &w.openings)
            .filter(|o| o.kind == OpeningKind::Door)
            .count();
        assert_eq!(doors, 1);
    }

    #[test]
    fn size_words_scale_the_room() {
        let mut rng = ChaCha8Rng::seed_from_u64(1);
        let small = single_room("a", &prompt::read("a small bedroom"), "", &mut rng);
        let mut rng = ChaCha8Rng::seed_from_u64(1);
        let large = single_room("b", &prompt::read("a large bedroom"), "", &mut rng);
        let area = |r: &Room| crate::geometry::polygon::signed_area(&r.floor_polygon);
        assert!(area(&large) > 2.0 * area(&small));
    }
}
