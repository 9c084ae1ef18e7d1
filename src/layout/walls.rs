//! From a placed house to scene rooms: clear floors, wall segments with their openings.
//!
//! Every side of a room is split where its neighbours change; each piece becomes a wall whose
//! centre line is the cell edge, running counter-clockwise so its frame's +Y points into the
//! room. A wall shared by two rooms appears in both rooms (facing into each, so the placement
//! stages see every wall around their floor) but is built once: the room listed first owns the
//! geometry, the other room's copy names it in [`Wall::mirror_of`]. Doors sit left, centre or
//! right within the clear span of their shared wall; windows on exterior walls avoid doors;
//! an open connection removes the whole shared wall.

use super::connect::{DoorPos, DoorSpec, Interval, Side, WindowSpec, intervals, side_extent};
use super::search::Placement;
use super::spec::{HouseSpec, Link};
use crate::scene::{Opening, OpeningKind, Room, Wall};

/// Gap kept between an opening and the end of its clear span, metres.
const END_GAP: f64 = 0.1;
/// Gap kept between a window and a door on the same wall, metres.
const OPENING_GAP: f64 = 0.3;

/// Start and end points of an interval walked counter-clockwise around `cell`.
fn endpoints(cell: &super::search::Rect, iv: &Interval) -> ([f64; 2], [f64; 2]) {
    match iv.side {
        Side::South => ([iv.lo, cell.y0], [iv.hi, cell.y0]),
        Side::East => ([cell.x1, iv.lo], [cell.x1, iv.hi]),
        Side::North => ([iv.hi, cell.y1], [iv.lo, cell.y1]),
        Side::West => ([cell.x0, iv.hi], [cell.x0, iv.lo]),
    }
}

/// Centre of a door of `width` along a wall of length `len` at `pos` (wall coordinates),
/// keeping it inside the clear span; `None` when the span is too short.
fn door_center(len: f64, t: f64, width: f64, pos: DoorPos) -> Option<f64> {
    let (lo, hi) = (t / 2.0 + END_GAP, len - t / 2.0 - END_GAP);
    if hi - lo < width - 1e-9 {
        return None;
    }
    Some(match pos {
        DoorPos::Left => lo + width / 2.0,
        DoorPos::Center => len / 2.0,
        DoorPos::Right => hi - width / 2.0,
    })
}

/// What building the rooms reported (openings that did not fit).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct BuildNotes {
    /// Problems in words, naming the door or window.
    pub notes: Vec<String>,
}

/// A wall segment before ids and mirrors are assigned.
struct Piece {
    start: [f64; 2],
    end: [f64; 2],
    side: Side,
    neighbor: Option<String>,
    outside: bool,
    openings: Vec<Opening>,
}

/// Builds the scene rooms of a placed house.
pub fn build_rooms(
    spec: &HouseSpec,
    placement: &Placement,
    doors: &[DoorSpec],
    windows: &[WindowSpec],
    thickness: f64,
) -> (Vec<Room>, BuildNotes) {
    let mut notes = BuildNotes::default();
    let t = thickness;
    let h = spec.wall_height;
    // Segments per room, counter-clockwise.
    let mut pieces: Vec<Vec<Piece>> = Vec::new();
    let mut placed_doors: Vec<String> = Vec::new();
    for r in &spec.rooms {
        let Some(cell) = placement.cells.get(&r.id) else {
            pieces.push(Vec::new());
            continue;
        };
        let mut mine = Vec::new();
        for iv in intervals(placement, &r.id) {
            let (start, end) = endpoints(cell, &iv);
            let len = iv.len();
            let mut openings = Vec::new();
            if let Some(q) = &iv.neighbor {
                let owner = spec.index(&r.id) < spec.index(q);
                if spec.pair(&r.id, q).is_some_and(|p| p.link == Link::Open) {
                    openings.push(Opening {
                        id: open_id(&r.id, q),
                        kind: OpeningKind::Open,
                        center: len / 2.0,
                        width: len,
                        bottom: 0.0,
                        height: h,
                    });
                }
                for d in doors.iter().filter(|d| d.joins(&r.id, Some(q))) {
                    // Left/right are seen from the owning room's wall; the other room mirrors.
                    let Some(c) = door_center(len, t, d.width, d.pos) else {
                        if owner {
                            notes.notes.push(format!(
                                "{}: the wall between {} and {} is too short for a {:.2} m door",
                                d.id, d.a, q, d.width
                            ));
                        }
                        continue;
                    };
                    let c = if owner { c } else { len - c };
                    openings.push(door_opening(&d.id, c, d.width));
                    placed_doors.push(d.id.clone());
                }
            }
            mine.push(Piece {
                start,
                end,
                side: iv.side,
                neighbor: iv.neighbor.clone(),
                outside: iv.outside,
                openings,
            });
        }
        // Exterior doors: the longest outside piece on the requested side.
        for d in doors.iter().filter(|d| d.a == r.id && d.b.is_none()) {
            let best = mine
                .iter_mut()
                .filter(|p| p.outside && Some(p.side) == d.side.or(Some(p.side)))
                .max_by(|a, b| seg_len(a).total_cmp(&seg_len(b)));
            match best.and_then(|p| door_center(seg_len(p), t, d.width, d.pos).map(|c| (p, c))) {
                Some((p, c)) => {
                    p.openings.push(door_opening(&d.id, c, d.width));
                    placed_doors.push(d.id.clone());
                }
                None => notes.notes.push(format!(
                    "{}: {} has no outside wall on the {} side long enough for a door",
                    d.id,
                    r.id,
                    d.side.map(Side::as_str).unwrap_or("any")
                )),
            }
        }
        // Windows: on the outside piece of the requested side nearest the wanted point,
        // moved off doors.
        for w in windows.iter().filter(|w| w.room == r.id) {
            let (lo, side_len) = side_extent(cell, w.side);
            let want_axis = match w.side {
                Side::South | Side::East => lo + w.along * side_len,
                Side::North | Side::West => lo + (1.0 - w.along) * side_len,
            };
            let mut placed = false;
            let mut order: Vec<usize> = (0..mine.len())
                .filter(|&i| mine[i].outside && mine[i].side == w.side)
                .collect();
            order.sort_by(|&a, &b| {
                axis_distance(&mine[a], want_axis).total_cmp(&axis_distance(&mine[b], want_axis))
            });
            for i in order {
                let p = &mut mine[i];
                let len = seg_len(p);
                let want = along_wall(p, want_axis);
                if let Some(c) = fit_window(len, t, w.width, want, &p.openings) {
                    p.openings.push(Opening {
                        id: w.id.clone(),
                        kind: OpeningKind::Window,
                        center: c,
                        width: w.width,
                        bottom: w.sill,
                        height: w.height.min(h - w.sill - 0.05).max(0.2),
                    });
                    placed = true;
                    break;
                }
            }
            if !placed {
                notes.notes.push(format!(
                    "{}: no free outside wall on the {} side of {} for a {:.2} m window",
                    w.id,
                    w.side.as_str(),
                    r.id,
                    w.width
                ));
            }
        }
        pieces.push(mine);
    }
    for d in doors {
        if !placed_doors.contains(&d.id) && !notes.notes.iter().any(|n| n.starts_with(&d.id)) {
            notes.notes.push(format!(
                "{}: {} and {} do not share a wall",
                d.id,
                d.a,
                d.b.as_deref().unwrap_or("the outside")
            ));
        }
    }

    // Ids, then mirrors: the copy in the later room names the owner's wall.
    let ids: Vec<Vec<String>> = spec
        .rooms
        .iter()
        .zip(&pieces)
        .map(|(r, ps)| {
            (0..ps.len())
                .map(|k| format!("{}_wall_{k}", r.id))
                .collect()
        })
        .collect();
    let mut rooms = Vec::new();
    for (ri, r) in spec.rooms.iter().enumerate() {
        let Some(cell) = placement.cells.get(&r.id) else {
            continue;
        };
        let mut walls: Vec<(Side, Wall)> = Vec::new();
        for (k, p) in pieces[ri].iter().enumerate() {
            let mirror_of = p.neighbor.as_ref().and_then(|q| {
                let qi = spec.index(q)?;
                if qi > ri {
                    return None;
                }
                // The owner's piece runs the other way between the same points.
                let j = pieces[qi]
                    .iter()
                    .position(|o| close(o.start, p.end) && close(o.end, p.start))?;
                Some(ids[qi][j].clone())
            });
            walls.push((
                p.side,
                Wall {
                    id: ids[ri][k].clone(),
                    start: p.start,
                    end: p.end,
                    thickness: t,
                    neighbor: p.neighbor.clone(),
                    openings: p.openings.clone(),
                    mirror_of,
                },
            ));
        }
        // Longest piece of each side first, so "the north wall" means the main one.
        walls.sort_by(|a, b| a.0.cmp(&b.0).then(b.1.length().total_cmp(&a.1.length())));
        let half = t / 2.0;
        let (x0, y0, x1, y1) = (
            cell.x0 + half,
            cell.y0 + half,
            cell.x1 - half,
            cell.y1 - half,
        );
        rooms.push(Room {
            id: r.id.clone(),
            room_type: r.room_type.clone(),
            label: Some(r.label.clone()),
            prompt: r.prompt.clone(),
            floor_polygon: vec![[x0, y0], [x1, y0], [x1, y1], [x0, y1]],
            wall_height: h,
            walls: walls.into_iter().map(|(_, w)| w).collect(),
            floor_material: r.floor_material.clone(),
            wall_material: r.wall_material.clone(),
        });
    }
    (rooms, notes)
}

fn close(a: [f64; 2], b: [f64; 2]) -> bool {
    (a[0] - b[0]).abs() < 1e-6 && (a[1] - b[1]).abs() < 1e-6
}

fn seg_len(p: &Piece) -> f64 {
    (p.end[0] - p.start[0]).hypot(p.end[1] - p.start[1])
}

/// Distance along the wall from its start of the point at `axis` on the side's axis.
fn along_wall(p: &Piece, axis: f64) -> f64 {
    match p.side {
        Side::South => axis - p.start[0],
        Side::East => axis - p.start[1],
        Side::North => p.start[0] - axis,
        Side::West => p.start[1] - axis,
    }
}

fn axis_distance(p: &Piece, axis: f64) -> f64 {
    let a = along_wall(p, axis);
    let len = seg_len(p);
    if a < 0.0 {
        -a
    } else if a > len {
        a - len
    } else {
        0.0
    }
}

/// Centre for a window of `width` near `want` on a wall of `len` that avoids `taken`.
fn fit_window(len: f64, t: f64, width: f64, want: f64, taken: &[Opening]) -> Option<f64> {
    let (lo, hi) = (
        t / 2.0 + END_GAP + width / 2.0,
        len - t / 2.0 - END_GAP - width / 2.0,
    );
    if hi < lo {
        return None;
    }
    let free = |c: f64| {
        taken
            .iter()
            .all(|o| (c - o.center).abs() >= (o.width + width) / 2.0 + OPENING_GAP)
    };
    let start = want.clamp(lo, hi);
    // Scan outwards from the wanted centre in 5 cm steps.
    let steps = ((hi - lo) / 0.05).ceil() as usize + 1;
    (0..=steps)
        .flat_map(|k| {
            let d = k as f64 * 0.05;
            [start + d, start - d]
        })
        .find(|c| (lo - 1e-9..=hi + 1e-9).contains(c) && free(*c))
}

fn door_opening(id: &str, center: f64, width: f64) -> Opening {
    Opening {
        id: id.to_string(),
        kind: OpeningKind::Door,
        center,
        width,
        bottom: 0.0,
        height: super::connect::DOOR[1],
    }
}

/// Id of the open connection between two rooms (same from both sides).
pub fn open_id(a: &str, b: &str) -> String {
    let (x, y) = if a < b { (a, b) } else { (b, a) };
    format!("open_{x}_{y}")
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::layout::connect::{auto_doors, auto_windows};
    use crate::layout::search::{Rect, SearchConfig, place};
    use crate::layout::{brief, spec};

    #[test]
    fn shared_walls_are_built_once_and_seen_from_both_sides() {
        let spec = spec::house_spec(&brief::read(
            "A one-bedroom apartment with a bedroom, a living room, and a bathroom.",
        ));
        let (p, _) = place(&spec, None, &SearchConfig::default());
        let doors = auto_doors(&spec, &p, 7);
        let windows = auto_windows(&spec, &p, &doors);
        let (rooms, notes) = build_rooms(&spec, &p, &doors, &windows, 0.12);
        assert!(notes.notes.is_empty(), "{notes:?}");
        let all: Vec<&Wall> = rooms.iter().flat_map(|r| &r.walls).collect();
        for w in all.iter().filter(|w| w.neighbor.is_some()) {
            let twins: Vec<&&Wall> = all
                .iter()
                .filter(|o| close(o.start, w.end) && close(o.end, w.start))
                .collect();
            assert_eq!(twins.len(), 1, "{} has no twin", w.id);
            // Exactly one of the two is built.
            assert!(
                w.mirror_of.is_some() != twins[0].mirror_of.is_some(),
                "{}",
                w.id
            );
            // The same doors, mirrored.
            for o in &w.openings {
                let m = twins[0].openings.iter().find(|x| x.id == o.id).unwrap();
                assert!((m.center - (w.length() - o.center)).abs() < 1e-9);
            }
        }
        // Every wall's frame +Y points into its own room's floor.
        for r in &rooms {
            let (lo, hi) = crate::geometry::polygon::bounds(&r.floor_polygon);
            let c = [(lo[0] + hi[0]) / 2.0, (lo[1] + hi[1]) / 2.0];
            for w in &r.walls {
                let mid = [(w.start[0] + w.end[0]) / 2.0, (w.start[1] + w.end[1]) / 2.0];
                let inward = w
                    .world_from_wall()
                    .transform_vector(&nalgebra::Vector3::y());
                assert!(inward.x * (c[0] - mid[0]) + inward.y * (c[1] - mid[1]) > 0.0);
            }
        }
    }

    #[test]
    fn door_positions_stay_in_the_clear_span() {
        for pos in [DoorPos::Left, DoorPos::Center, DoorPos::Right] {
            let c = door_center(2.0, 0.12, 0.9, pos).unwrap();
            assert!(c - 0.45 >= 0.06 + END_GAP - 1e-9 && c + 0.45 <= 2.0 - 0.06 - END_GAP + 1e-9);
        }
        assert!(door_center(1.0, 0.12, 0.9, DoorPos::Center).is_none());
        let _ = Rect::at(0.0, 0.0, 1.0, 1.0);
    }
}
