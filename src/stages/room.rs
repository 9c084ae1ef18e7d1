//! A room as the placement stages see it: its frame (origin at the south-west corner of the
//! clear floor), walls named by side, free-floor grids for reachability, and text summaries
//! for agents.

use nalgebra::{Point3, Vector3};
use serde::Serialize;

use super::placement::Footprint;
use crate::geometry::polygon;
use crate::scene::{OpeningKind, Pose, Room, Wall};

/// Side of a rectangular room a wall is on, from the direction its inside face points.
pub fn wall_side(wall: &Wall) -> &'static str {
    let inward = wall.world_from_wall().transform_vector(&Vector3::y());
    if inward.y > 0.7 {
        "south"
    } else if inward.y < -0.7 {
        "north"
    } else if inward.x > 0.7 {
        "west"
    } else if inward.x < -0.7 {
        "east"
    } else {
        "diagonal"
    }
}

/// Room-frame helpers.
#[derive(Debug, Clone)]
pub struct RoomFrame<'a> {
    /// The room.
    pub room: &'a Room,
    /// World XY of the room origin (south-west corner of the clear floor's bounds).
    pub origin: [f64; 2],
    /// Extent of the clear floor's bounds, metres.
    pub size: [f64; 2],
}

impl<'a> RoomFrame<'a> {
    /// The frame of `room`.
    pub fn new(room: &'a Room) -> Self {
        let (lo, hi) = polygon::bounds(&room.floor_polygon);
        RoomFrame {
            room,
            origin: lo,
            size: [hi[0] - lo[0], hi[1] - lo[1]],
        }
    }

    /// World XY of a room-frame point.
    pub fn to_world(&self, x: f64, y: f64) -> [f64; 2] {
        [self.origin[0] + x, self.origin[1] + y]
    }

    /// Room-frame XY of a world point.
    pub fn to_room(&self, p: [f64; 2]) -> [f64; 2] {
        [p[0] - self.origin[0], p[1] - self.origin[1]]
    }

    /// Centre of the room in world XY.
    pub fn center_world(&self) -> [f64; 2] {
        self.to_world(self.size[0] / 2.0, self.size[1] / 2.0)
    }

    /// A wall by id or by side name (`north`, `south`, `east`, `west`).
    pub fn wall(&self, key: &str) -> Option<&'a Wall> {
        let key = key.trim().to_ascii_lowercase();
        self.room
            .walls
            .iter()
            .find(|w| w.id == key)
            .or_else(|| self.room.walls.iter().find(|w| wall_side(w) == key))
    }

    /// Whether a world point is inside the clear floor.
    pub fn contains(&self, p: [f64; 2]) -> bool {
        polygon::contains(&self.room.floor_polygon, p)
    }

    /// The walls with a door or open connection (where people enter).
    pub fn entrances(&self) -> Vec<[f64; 2]> {
        let mut out = Vec::new();
        for w in &self.room.walls {
            for o in &w.openings {
                if matches!(o.kind, OpeningKind::Door | OpeningKind::Open) {
                    // A point just inside the room in front of the opening.
                    let p = w.world_from_wall().transform_point(&Point3::new(
                        o.center,
                        w.thickness / 2.0 + 0.35,
                        0.0,
                    ));
                    out.push([p.x, p.y]);
                }
            }
        }
        out
    }
}

/// Yaw (radians) that turns an object's front (+Y) from `from` towards `to` (world XY).
pub fn yaw_facing(from: [f64; 2], to: [f64; 2]) -> f64 {
    let (dx, dy) = (to[0] - from[0], to[1] - from[1]);
    // Front is +Y: a yaw of 0 faces +Y, so the heading angle minus 90 degrees.
    dy.atan2(dx) - std::f64::consts::FRAC_PI_2
}

/// Normalises an angle to (-pi, pi].
pub fn wrap_angle(a: f64) -> f64 {
    let mut a = a % std::f64::consts::TAU;
    if a <= -std::f64::consts::PI {
        a += std::f64::consts::TAU;
    } else if a > std::f64::consts::PI {
        a -= std::f64::consts::TAU;
    }
    a
}

/// Free-floor occupancy grid for reachability: cells inside the clear floor, at least
/// `radius` from walls, not covered by any obstacle footprint grown by `radius`.
#[derive(Debug, Clone)]
pub struct FloorGrid {
    origin: [f64; 2],
    cell: f64,
    nx: usize,
    ny: usize,
    free: Vec<bool>,
}

/// Reachability summary of a room.
#[derive(Debug, Clone, Serialize, PartialEq, schemars::JsonSchema)]
pub struct Reachability {
    /// Free floor area reachable from the entrance, m^2.
    pub reachable_area_m2: f64,
    /// All free floor area, m^2.
    pub free_area_m2: f64,
    /// Largest connected free region / all free floor (1 = one connected region).
    pub nav: f64,
    /// Objects with no reachable free floor next to them.
    pub unreachable: Vec<String>,
}

impl FloorGrid {
    /// Rasterises `room` at `cell` metres with `obstacles` (id, footprint) for a robot of
    /// `radius` metres.
    pub fn new(
        room: &Room,
        obstacles: &[(String, Footprint)],
        radius: f64,
        cell: f64,
    ) -> FloorGrid {
        let (lo, hi) = polygon::bounds(&room.floor_polygon);
        let nx = ((hi[0] - lo[0]) / cell).ceil().max(1.0) as usize;
        let ny = ((hi[1] - lo[1]) / cell).ceil().max(1.0) as usize;
        let mut free = vec![false; nx * ny];
        for iy in 0..ny {
            for ix in 0..nx {
                let p = [
                    lo[0] + (ix as f64 + 0.5) * cell,
                    lo[1] + (iy as f64 + 0.5) * cell,
                ];
                let probe = Footprint {
                    center: p,
                    half: [radius, radius],
                    yaw: 0.0,
                    z: [0.0, 0.5],
                };
                let inside = probe.inside(&room.floor_polygon);
                let blocked = obstacles.iter().any(|(_, f)| f.overlaps(&probe, 0.0));
                free[iy * nx + ix] = inside && !blocked;
            }
        }
        FloorGrid {
            origin: lo,
            cell,
            nx,
            ny,
            free,
        }
    }

    fn index(&self, p: [f64; 2]) -> Option<usize> {
        let ix = ((p[0] - self.origin[0]) / self.cell).floor();
        let iy = ((p[1] - self.origin[1]) / self.cell).floor();
        if ix < 0.0 || iy < 0.0 || ix as usize >= self.nx || iy as usize >= self.ny {
            return None;
        }
        Some(iy as usize * self.nx + ix as usize)
    }

    /// Connected components (4-neighbour) of free cells: a label per cell (`usize::MAX` for
    /// blocked cells) and the size of each component.
    fn components(&self) -> (Vec<usize>, Vec<usize>) {
        let mut label = vec![usize::MAX; self.free.len()];
        let mut sizes = Vec::new();
        for start in 0..self.free.len() {
            if !self.free[start] || label[start] != usize::MAX {
                continue;
            }
            let id = sizes.len();
            let mut stack = vec![start];
            label[start] = id;
            let mut n = 0;
            while let Some(c) = stack.pop() {
                n += 1;
                let (x, y) = (c % self.nx, c / self.nx);
                let mut visit = |nc: usize| {
                    if self.free[nc] && label[nc] == usize::MAX {
                        label[nc] = id;
                        stack.push(nc);
                    }
                };
                if x > 0 {
                    visit(c - 1);
                }
                if x + 1 < self.nx {
                    visit(c + 1);
                }
                if y > 0 {
                    visit(c - self.nx);
                }
                if y + 1 < self.ny {
                    visit(c + self.nx);
                }
            }
            sizes.push(n);
        }
        (label, sizes)
    }

    /// Reachability from the nearest free cell to any of `entrances`; an object counts as
    /// reachable when a reachable cell lies within `reach` metres of its footprint.
    pub fn reachability(
        &self,
        entrances: &[[f64; 2]],
        objects: &[(String, Footprint)],
        reach: f64,
    ) -> Reachability {
        let (label, sizes) = self.components();
        let area = self.cell * self.cell;
        let free_cells: usize = sizes.iter().sum();
        let largest = sizes.iter().copied().max().unwrap_or(0);
        // The entrance component: the free cell closest to an entrance point.
        let mut entry: Option<usize> = None;
        let mut best = f64::INFINITY;
        for e in entrances {
            for (i, &l) in label.iter().enumerate() {
                if l == usize::MAX {
                    continue;
                }
                let (x, y) = (i % self.nx, i / self.nx);
                let c = [
                    self.origin[0] + (x as f64 + 0.5) * self.cell,
                    self.origin[1] + (y as f64 + 0.5) * self.cell,
                ];
                let d = (c[0] - e[0]).hypot(c[1] - e[1]);
                if d < best {
                    best = d;
                    entry = Some(l);
                }
            }
        }
        let reachable_label = entry.or_else(|| (0..sizes.len()).max_by_key(|&i| sizes[i]));
        let reachable_cells = reachable_label.map(|l| sizes[l]).unwrap_or(0);
        let mut unreachable = Vec::new();
        for (id, fp) in objects {
            let mut grown = *fp;
            grown.half[0] += reach;
            grown.half[1] += reach;
            let corners = grown.corners();
            let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
            for c in corners {
                for k in 0..2 {
                    lo[k] = lo[k].min(c[k]);
                    hi[k] = hi[k].max(c[k]);
                }
            }
            let mut ok = false;
            let mut y = lo[1];
            'scan: while y <= hi[1] {
                let mut x = lo[0];
                while x <= hi[0] {
                    if let Some(i) = self.index([x, y])
                        && Some(label[i]) == reachable_label
                        && label[i] != usize::MAX
                    {
                        let probe = Footprint {
                            center: [x, y],
                            half: [0.01, 0.01],
                            yaw: 0.0,
                            z: fp.z,
                        };
                        if grown.overlaps(&probe, 0.0) {
                            ok = true;
                            break 'scan;
                        }
                    }
                    x += self.cell;
                }
                y += self.cell;
            }
            if !ok {
                unreachable.push(id.clone());
            }
        }
        Reachability {
            reachable_area_m2: reachable_cells as f64 * area,
            free_area_m2: free_cells as f64 * area,
            nav: if free_cells == 0 {
                0.0
            } else {
                largest as f64 / free_cells as f64
            },
            unreachable,
        }
    }
}

/// World pose of a room-frame placement (x, y in metres, yaw in degrees about +Z).
pub fn room_pose(frame: &RoomFrame<'_>, x: f64, y: f64, yaw_deg: f64) -> Pose {
    let w = frame.to_world(x, y);
    Pose::from_xyz_yaw(w[0], w[1], 0.0, yaw_deg.to_radians())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Opening;
    use crate::scene::rectangle_walls;

    fn room() -> Room {
        let mut walls = rectangle_walls("r", [0.0, 0.0], 4.0, 3.0, 0.1);
        walls[0].openings.push(Opening {
            id: "d".into(),
            kind: OpeningKind::Door,
            center: 1.0,
            width: 0.9,
            bottom: 0.0,
            height: 2.1,
        });
        Room {
            id: "r".into(),
            room_type: "room".into(),
            label: None,
            prompt: String::new(),
            floor_polygon: vec![[0.0, 0.0], [4.0, 0.0], [4.0, 3.0], [0.0, 3.0]],
            wall_height: 2.5,
            walls,
            floor_material: "oak".into(),
            wall_material: "plaster".into(),
        }
    }

    #[test]
    fn sides_and_facing() {
        let r = room();
        let f = RoomFrame::new(&r);
        assert_eq!(wall_side(f.wall("south").unwrap()), "south");
        assert_eq!(f.wall("north").unwrap().id, "r_wall_2");
        // Facing +X from the origin is a yaw of -90 degrees.
        assert!((yaw_facing([0.0, 0.0], [1.0, 0.0]) + std::f64::consts::FRAC_PI_2).abs() < 1e-12);
        assert!(yaw_facing([0.0, 0.0], [0.0, 1.0]).abs() < 1e-12);
    }

    #[test]
    fn a_wall_of_furniture_cuts_the_room() {
        let r = room();
        let wall_of_shelves = Footprint {
            center: [2.0, 1.5],
            half: [0.1, 1.5],
            yaw: 0.0,
            z: [0.0, 2.0],
        };
        let objs = vec![("shelves".to_string(), wall_of_shelves)];
        let grid = FloorGrid::new(&r, &objs, 0.25, 0.05);
        let f = RoomFrame::new(&r);
        let far_table = Footprint {
            center: [3.3, 1.5],
            half: [0.3, 0.3],
            yaw: 0.0,
            z: [0.0, 0.7],
        };
        let reach = grid.reachability(&f.entrances(), &[("table".into(), far_table)], 0.3);
        assert!(reach.nav < 0.7, "{reach:?}");
        assert_eq!(reach.unreachable, vec!["table".to_string()]);
        let open = FloorGrid::new(&r, &[], 0.25, 0.05).reachability(
            &f.entrances(),
            &[("table".into(), far_table)],
            0.3,
        );
        assert!((open.nav - 1.0).abs() < 1e-12 && open.unreachable.is_empty());
    }
}
