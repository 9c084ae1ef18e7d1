//! Doors and windows of a placed house: which pairs of rooms get a door (every room from one
//! of its parents, required pairs, then whatever is still unreachable), the exterior door of the
//! entrance, and windows on exterior walls of rooms that want daylight.
//!
//! Doors and windows are kept as requests (rooms, side, left/centre/right) so they survive a
//! re-layout; [`super::walls`] turns them into openings on wall segments.

use rand::rngs::ChaCha8Rng;
use rand::{RngExt, SeedableRng};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use super::knowledge::Role;
use super::search::{MIN_SHARED, Outside, Placement, Rect};
use super::spec::{HouseSpec, Link};

/// Standard interior door: width, height (metres).
pub const DOOR: [f64; 2] = [0.9, 2.1];
/// Exterior door width, metres.
pub const EXTERIOR_DOOR_WIDTH: f64 = 1.0;

/// A side of a rectangular room.
#[derive(
    Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema, PartialOrd, Ord,
)]
#[serde(rename_all = "snake_case")]
pub enum Side {
    /// Low y.
    South,
    /// High x.
    East,
    /// High y.
    North,
    /// Low x.
    West,
}

impl Side {
    /// Counter-clockwise order starting south.
    pub const ALL: [Side; 4] = [Side::South, Side::East, Side::North, Side::West];

    /// `south`, `east`, ...
    pub fn as_str(self) -> &'static str {
        match self {
            Side::South => "south",
            Side::East => "east",
            Side::North => "north",
            Side::West => "west",
        }
    }

    /// Parses a side name.
    pub fn parse(s: &str) -> Option<Side> {
        match s.trim().to_ascii_lowercase().as_str() {
            "south" | "s" | "bottom" => Some(Side::South),
            "east" | "e" | "right" => Some(Side::East),
            "north" | "n" | "top" => Some(Side::North),
            "west" | "w" | "left" => Some(Side::West),
            _ => None,
        }
    }
}

/// Where along its wall segment a door sits (seen from the owning room's wall direction).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum DoorPos {
    /// Near the segment's start.
    Left,
    /// In the middle.
    Center,
    /// Near the segment's end.
    Right,
}

/// A door between two rooms, or from a room to the outside.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct DoorSpec {
    /// Door id, e.g. `door_3`.
    pub id: String,
    /// One room.
    pub a: String,
    /// The other room; `None` for an exterior door.
    pub b: Option<String>,
    /// Position along the shared segment.
    pub pos: DoorPos,
    /// For an exterior door: the side of `a` it is on.
    pub side: Option<Side>,
    /// Width, metres.
    pub width: f64,
    /// Placed by the layout (re-planned after a re-layout) rather than by an edit.
    pub auto: bool,
}

impl DoorSpec {
    /// Whether the door joins `x` and `y` (`None`: outside).
    pub fn joins(&self, x: &str, y: Option<&str>) -> bool {
        (self.a == x && self.b.as_deref() == y)
            || (Some(self.a.as_str()) == y && self.b.as_deref() == Some(x))
    }
}

/// A window in an exterior wall.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct WindowSpec {
    /// Window id, e.g. `window_2`.
    pub id: String,
    /// Room.
    pub room: String,
    /// Side of the room.
    pub side: Side,
    /// Wanted centre along that side, as a fraction of the side from its counter-clockwise
    /// start.
    pub along: f64,
    /// Width, metres.
    pub width: f64,
    /// Height, metres.
    pub height: f64,
    /// Sill height above the floor, metres.
    pub sill: f64,
    /// Placed by the layout rather than by an edit.
    pub auto: bool,
}

/// A stretch of one side of a room: `[lo, hi]` along the side's world axis, and who is on the
/// other side.
#[derive(Debug, Clone, PartialEq)]
pub struct Interval {
    /// Side of the room.
    pub side: Side,
    /// Low end along the axis (x for south/north, y for east/west), metres.
    pub lo: f64,
    /// High end along the axis, metres.
    pub hi: f64,
    /// Neighbour room, `None` outside.
    pub neighbor: Option<String>,
    /// No neighbour and facing the open outside (not an enclosed courtyard).
    pub outside: bool,
}

impl Interval {
    /// Length, metres.
    pub fn len(&self) -> f64 {
        self.hi - self.lo
    }

    /// True for a zero-length interval.
    pub fn is_empty(&self) -> bool {
        self.len() <= 1e-9
    }
}

const EPS: f64 = 1e-6;

/// The intervals of every side of room `id`, counter-clockwise (south, east, north, west; each
/// side in its counter-clockwise direction).
pub fn intervals(placement: &Placement, id: &str) -> Vec<Interval> {
    intervals_with(placement, id, &Outside::of(placement))
}

/// [`intervals`] with the placement's outside already computed.
pub fn intervals_with(placement: &Placement, id: &str, outside: &Outside) -> Vec<Interval> {
    let Some(r) = placement.cells.get(id) else {
        return Vec::new();
    };
    let mut out = Vec::new();
    for side in Side::ALL {
        let (lo, hi) = match side {
            Side::South | Side::North => (r.x0, r.x1),
            Side::East | Side::West => (r.y0, r.y1),
        };
        // Neighbours along this side: (lo, hi, id).
        let mut touching: Vec<(f64, f64, String)> = Vec::new();
        for (k, o) in &placement.cells {
            if k == id {
                continue;
            }
            let on_line = match side {
                Side::South => (o.y1 - r.y0).abs() < EPS,
                Side::North => (o.y0 - r.y1).abs() < EPS,
                Side::East => (o.x0 - r.x1).abs() < EPS,
                Side::West => (o.x1 - r.x0).abs() < EPS,
            };
            if !on_line {
                continue;
            }
            let (olo, ohi) = match side {
                Side::South | Side::North => (o.x0, o.x1),
                Side::East | Side::West => (o.y0, o.y1),
            };
            let (a, b) = (olo.max(lo), ohi.min(hi));
            if b - a > EPS {
                touching.push((a, b, k.clone()));
            }
        }
        touching.sort_by(|a, b| a.0.total_cmp(&b.0));
        let mut pieces = Vec::new();
        let mut cursor = lo;
        for (a, b, k) in touching {
            if a > cursor + EPS {
                pieces.push(Interval {
                    side,
                    lo: cursor,
                    hi: a,
                    neighbor: None,
                    outside: false,
                });
            }
            pieces.push(Interval {
                side,
                lo: a.max(cursor),
                hi: b,
                neighbor: Some(k),
                outside: false,
            });
            cursor = b;
        }
        if hi > cursor + EPS {
            pieces.push(Interval {
                side,
                lo: cursor,
                hi,
                neighbor: None,
                outside: false,
            });
        }
        // Free pieces face the outside unless they face an enclosed courtyard.
        for p in pieces.iter_mut().filter(|p| p.neighbor.is_none()) {
            let m = (p.lo + p.hi) / 2.0;
            let probe = match side {
                Side::South => [m, r.y0 - 1e-3],
                Side::North => [m, r.y1 + 1e-3],
                Side::East => [r.x1 + 1e-3, m],
                Side::West => [r.x0 - 1e-3, m],
            };
            p.outside = outside.is_open(probe);
        }
        // North and west run against the axis when walked counter-clockwise.
        if matches!(side, Side::North | Side::West) {
            pieces.reverse();
        }
        out.extend(pieces.into_iter().filter(|p| !p.is_empty()));
    }
    out
}

/// A door's left/centre/right from the seed and the door's rooms (stable under re-layouts).
fn door_pos(seed: u64, a: &str, b: &str) -> DoorPos {
    let h = blake3::hash(format!("{seed}:{a}:{b}").as_bytes());
    let mut rng = ChaCha8Rng::seed_from_u64(u64::from_le_bytes(
        h.as_bytes()[..8].try_into().unwrap_or([0; 8]),
    ));
    match rng.random_range(0..3u32) {
        0 => DoorPos::Left,
        1 => DoorPos::Center,
        _ => DoorPos::Right,
    }
}

/// Door-graph edges of a plan (rooms joined by doors or open connections).
fn edges(spec: &HouseSpec, doors: &[DoorSpec]) -> Vec<(String, String)> {
    let mut e: Vec<(String, String)> = doors
        .iter()
        .filter_map(|d| d.b.as_ref().map(|b| (d.a.clone(), b.clone())))
        .collect();
    e.extend(
        spec.adjacency
            .iter()
            .filter(|p| p.link == Link::Open)
            .map(|p| (p.a.clone(), p.b.clone())),
    );
    e
}

/// Rooms reachable from the outside through `doors` and open connections.
pub fn reachable(spec: &HouseSpec, doors: &[DoorSpec]) -> Vec<String> {
    let edges = edges(spec, doors);
    let mut seen: Vec<String> = doors
        .iter()
        .filter(|d| d.b.is_none())
        .map(|d| d.a.clone())
        .collect();
    let mut i = 0;
    while i < seen.len() {
        let cur = seen[i].clone();
        for (a, b) in &edges {
            let next = if *a == cur {
                b
            } else if *b == cur {
                a
            } else {
                continue;
            };
            if !seen.contains(next) {
                seen.push(next.clone());
            }
        }
        i += 1;
    }
    seen
}

/// The door plan of a placed house: the exterior door of the entrance, a door from every room
/// to a parent it touches, required pairs, then doors for whatever is still unreachable (never
/// through a bathroom or an en-suite).
pub fn auto_doors(spec: &HouseSpec, placement: &Placement, seed: u64) -> Vec<DoorSpec> {
    let mut doors: Vec<DoorSpec> = Vec::new();
    let mut next = 0usize;
    let mut add = |doors: &mut Vec<DoorSpec>, a: &str, b: Option<&str>, side: Option<Side>| {
        // An exterior door sits at one end of its wall, leaving the rest for windows.
        let pos = match b {
            Some(b) => door_pos(seed, a, b),
            None if spec.room(a).is_some_and(|r| r.windows) => DoorPos::Right,
            None => DoorPos::Center,
        };
        doors.push(DoorSpec {
            id: format!("door_{next}"),
            a: a.to_string(),
            b: b.map(str::to_string),
            pos,
            side,
            width: if b.is_none() {
                EXTERIOR_DOOR_WIDTH
            } else {
                DOOR[0]
            },
            auto: true,
        });
        next += 1;
    };
    if let Some((entrance, side)) = exterior_door_site(spec, placement) {
        add(&mut doors, &entrance, None, Some(side));
    }
    let shared = |a: &str, b: &str| placement.shared(a, b);
    let open = |a: &str, b: &str| spec.pair(a, b).is_some_and(|p| p.link == Link::Open);
    let role = |id: &str| spec.room(id).map(|r| r.role);
    let is_en_suite = |id: &str| spec.room(id).is_some_and(|r| r.owner.is_some());
    for &i in &super::search::order(spec) {
        let r = &spec.rooms[i];
        if r.parents.is_empty() {
            continue;
        }
        if r.parents.iter().any(|p| open(&r.id, p)) {
            continue;
        }
        let parent = r
            .parents
            .iter()
            .find(|p| shared(&r.id, p) >= MIN_SHARED - EPS)
            .cloned();
        if let Some(p) = parent
            && !doors.iter().any(|d| d.joins(&r.id, Some(&p)))
        {
            add(&mut doors, &r.id, Some(&p), None);
        }
    }
    for p in spec.adjacency.iter().filter(|p| p.link == Link::Door) {
        if shared(&p.a, &p.b) >= MIN_SHARED - EPS
            && !doors.iter().any(|d| d.joins(&p.a, Some(&p.b)))
        {
            // An en-suite keeps its single door.
            if is_en_suite(&p.a) || is_en_suite(&p.b) {
                continue;
            }
            add(&mut doors, &p.a, Some(&p.b), None);
        }
    }
    // Whatever is still cut off: a door to a reachable neighbour, passable ones first.
    for _ in 0..spec.rooms.len() {
        let seen = reachable(spec, &doors);
        let Some(lost) = spec.rooms.iter().find(|r| !seen.contains(&r.id)) else {
            break;
        };
        let rank = |id: &str| match role(id) {
            Some(Role::Hub) => 0,
            Some(Role::Entry) => 1,
            Some(Role::Public) => 2,
            Some(Role::Private) => 3,
            Some(Role::Service) => 4,
            _ => 9,
        };
        let mut options: Vec<(&String, f64)> = placement
            .cells
            .keys()
            .filter(|k| seen.contains(k) && !is_en_suite(k))
            .filter(|k| role(k) != Some(Role::Wet))
            .map(|k| (k, shared(&lost.id, k)))
            .filter(|(_, s)| *s >= MIN_SHARED - EPS)
            .collect();
        options.sort_by(|a, b| rank(a.0).cmp(&rank(b.0)).then(b.1.total_cmp(&a.1)));
        match options.first() {
            Some((k, _)) => {
                let k = (*k).clone();
                add(&mut doors, &lost.id, Some(&k), None);
            }
            None => {
                // No reachable neighbour: its own exterior door, when it has an outside wall.
                match longest_exterior(placement, &lost.id) {
                    Some(side) => add(&mut doors, &lost.id, None, Some(side)),
                    None => break,
                }
            }
        }
    }
    doors
}

/// Side of the longest exterior stretch of a room long enough for a door.
fn longest_exterior(placement: &Placement, id: &str) -> Option<Side> {
    intervals(placement, id)
        .into_iter()
        .filter(|iv| iv.outside && iv.len() >= MIN_SHARED)
        .max_by(|a, b| a.len().total_cmp(&b.len()))
        .map(|iv| iv.side)
}

/// Where the exterior door goes: the entrance's longest outside wall, else another passable
/// room's, else any room's.
pub fn exterior_door_site(spec: &HouseSpec, placement: &Placement) -> Option<(String, Side)> {
    if let Some(side) = longest_exterior(placement, &spec.entrance) {
        return Some((spec.entrance.clone(), side));
    }
    let mut rooms: Vec<&super::spec::RoomSpec> = spec.rooms.iter().collect();
    rooms.sort_by_key(|r| !r.role.passable());
    rooms
        .iter()
        .find_map(|r| longest_exterior(placement, &r.id).map(|s| (r.id.clone(), s)))
}

/// Window size of a room: `[width, height]`.
pub fn window_size(sill: f64, wall_height: f64, wet: bool) -> [f64; 2] {
    let width = if wet { 0.6 } else { 1.2 };
    let height = (wall_height - sill - 0.3).clamp(0.4, if wet { 0.6 } else { 1.4 });
    [width, height]
}

/// Windows for every room that wants daylight: one per ~8 m of outside wall (1-3, one for a
/// bathroom), on the longest outside stretches, away from the exterior door's side when
/// possible.
pub fn auto_windows(
    spec: &HouseSpec,
    placement: &Placement,
    doors: &[DoorSpec],
) -> Vec<WindowSpec> {
    let mut out = Vec::new();
    for r in spec.rooms.iter().filter(|r| r.windows) {
        let wet = r.role == Role::Wet;
        let [width, height] = window_size(r.sill, spec.wall_height, wet);
        let door_sides: Vec<Side> = doors
            .iter()
            .filter(|d| d.a == r.id && d.b.is_none())
            .filter_map(|d| d.side)
            .collect();
        // Room for the window, and for the exterior door too on the door's side.
        let need = |iv: &Interval| {
            width
                + 0.6
                + if door_sides.contains(&iv.side) {
                    EXTERIOR_DOOR_WIDTH + 0.8
                } else {
                    0.0
                }
        };
        let mut ext: Vec<Interval> = intervals(placement, &r.id)
            .into_iter()
            .filter(|iv| iv.outside && iv.len() >= need(iv))
            .collect();
        if ext.is_empty() {
            continue;
        }
        let total: f64 = ext.iter().map(Interval::len).sum();
        let count = if wet {
            1
        } else {
            ((total / 8.0).round() as usize).clamp(1, 3)
        };
        ext.sort_by(|a, b| {
            door_sides
                .contains(&a.side)
                .cmp(&door_sides.contains(&b.side))
                .then(b.len().total_cmp(&a.len()))
        });
        let cell = placement.cells[&r.id];
        for iv in ext.iter().take(count) {
            let (lo, len) = side_extent(&cell, iv.side);
            let mid = (iv.lo + iv.hi) / 2.0;
            // Fraction along the side in its counter-clockwise direction.
            let f = match iv.side {
                Side::South | Side::East => (mid - lo) / len,
                Side::North | Side::West => 1.0 - (mid - lo) / len,
            };
            out.push(WindowSpec {
                id: String::new(),
                room: r.id.clone(),
                side: iv.side,
                along: f,
                width,
                height,
                sill: r.sill,
                auto: true,
            });
        }
    }
    for (k, w) in out.iter_mut().enumerate() {
        w.id = format!("window_{k}");
    }
    out
}

/// Low end and length of a side along its world axis.
pub fn side_extent(cell: &Rect, side: Side) -> (f64, f64) {
    match side {
        Side::South | Side::North => (cell.x0, cell.w()),
        Side::East | Side::West => (cell.y0, cell.d()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn intervals_split_at_neighbours() {
        let mut p = Placement::default();
        p.cells.insert("a".into(), Rect::at(0.0, 0.0, 6.0, 4.0));
        p.cells.insert("b".into(), Rect::at(1.0, 4.0, 3.0, 3.0));
        let iv = intervals(&p, "a");
        let north: Vec<&Interval> = iv.iter().filter(|i| i.side == Side::North).collect();
        assert_eq!(north.len(), 3);
        // Counter-clockwise: from high x to low x.
        assert!(north[0].neighbor.is_none() && (north[0].lo - 4.0).abs() < 1e-9);
        assert_eq!(north[1].neighbor.as_deref(), Some("b"));
        assert!((north[2].hi - 1.0).abs() < 1e-9);
        assert_eq!(iv.iter().filter(|i| i.side == Side::South).count(), 1);
    }
}
