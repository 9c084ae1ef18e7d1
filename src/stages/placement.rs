//! Geometric placement helpers shared by the stages: footprints, overlap tests, keep-out zones,
//! poses against walls and on support surfaces.

use nalgebra::{Point3, Vector2};

use crate::geometry::polygon;
use crate::scene::{AssetRecord, OpeningKind, Pose, Room, SurfaceRecord, Wall};

/// An oriented rectangle on the floor (XY), with the height range it occupies.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Footprint {
    /// Centre, world XY.
    pub center: [f64; 2],
    /// Half extents along the rectangle's own x and y axes.
    pub half: [f64; 2],
    /// Rotation of the rectangle about +Z, radians.
    pub yaw: f64,
    /// Bottom and top heights, metres.
    pub z: [f64; 2],
}

impl Footprint {
    /// Footprint of an asset with bounds `record.bounds` placed at `world_from_object`
    /// (assumed upright).
    pub fn of(record: &AssetRecord, world_from_object: &Pose) -> Footprint {
        let [lo, hi] = record.bounds;
        let local_center = Point3::new((lo[0] + hi[0]) / 2.0, (lo[1] + hi[1]) / 2.0, 0.0);
        let c = world_from_object.transform_point(&local_center);
        let base_z = world_from_object.translation().z;
        Footprint {
            center: [c.x, c.y],
            half: [(hi[0] - lo[0]) / 2.0, (hi[1] - lo[1]) / 2.0],
            yaw: world_from_object.yaw(),
            z: [base_z + lo[2], base_z + hi[2]],
        }
    }

    /// An axis-aligned keep-out box.
    pub fn aabb(lo: [f64; 2], hi: [f64; 2], z: [f64; 2]) -> Footprint {
        Footprint {
            center: [(lo[0] + hi[0]) / 2.0, (lo[1] + hi[1]) / 2.0],
            half: [(hi[0] - lo[0]) / 2.0, (hi[1] - lo[1]) / 2.0],
            yaw: 0.0,
            z,
        }
    }

    fn axes(&self) -> [Vector2<f64>; 2] {
        let (s, c) = self.yaw.sin_cos();
        [Vector2::new(c, s), Vector2::new(-s, c)]
    }

    /// The four corners, counter-clockwise.
    pub fn corners(&self) -> [[f64; 2]; 4] {
        let [ax, ay] = self.axes();
        let c = Vector2::new(self.center[0], self.center[1]);
        let (hx, hy) = (ax * self.half[0], ay * self.half[1]);
        [c - hx - hy, c + hx - hy, c + hx + hy, c - hx + hy].map(|p| [p.x, p.y])
    }

    /// True when the two rectangles (grown by `margin`) overlap in XY and their height ranges
    /// overlap (separating-axis test).
    pub fn overlaps(&self, other: &Footprint, margin: f64) -> bool {
        if self.z[1] <= other.z[0] || other.z[1] <= self.z[0] {
            return false;
        }
        let d = Vector2::new(
            other.center[0] - self.center[0],
            other.center[1] - self.center[1],
        );
        let (a, b) = (self.axes(), other.axes());
        for axis in a.iter().chain(b.iter()) {
            let ra = self.half[0] * a[0].dot(axis).abs() + self.half[1] * a[1].dot(axis).abs();
            let rb = other.half[0] * b[0].dot(axis).abs() + other.half[1] * b[1].dot(axis).abs();
            if d.dot(axis).abs() >= ra + rb + margin {
                return false;
            }
        }
        true
    }

    /// True when all corners lie inside the room's clear floor.
    pub fn inside(&self, floor: &[[f64; 2]]) -> bool {
        self.corners().iter().all(|c| polygon::contains(floor, *c))
    }
}

/// Keep-out zones of a room: the swing and approach area in front of every door (1 m deep),
/// and, for objects taller than a window's sill, the wall strip under every window.
pub fn keep_out_zones(room: &Room) -> Vec<Footprint> {
    let mut zones = Vec::new();
    for wall in &room.walls {
        let world_from_wall = wall.world_from_wall();
        for o in &wall.openings {
            let (depth, z) = match o.kind {
                OpeningKind::Door | OpeningKind::Open => (1.0, [0.0, 10.0]),
                OpeningKind::Window => (0.35, [o.bottom, 10.0]),
            };
            let local = Point3::new(o.center, wall.thickness / 2.0 + depth / 2.0, 0.0);
            let c = world_from_wall.transform_point(&local);
            zones.push(Footprint {
                center: [c.x, c.y],
                half: [o.width / 2.0 + 0.1, depth / 2.0],
                yaw: world_from_wall.yaw(),
                z,
            });
        }
    }
    zones
}

/// Pose of an object standing with its back against the inner face of `wall`, `along` metres
/// from the wall's start (measured to the object's centre), facing into the room.
pub fn against_wall(wall: &Wall, record: &AssetRecord, along: f64, gap: f64) -> Pose {
    let [lo, _hi] = record.bounds;
    // Object +Y is its front: the back face is at y = lo[1] in the model frame.
    let y = wall.thickness / 2.0 + gap - lo[1];
    wall.world_from_wall()
        .compose(&Pose::from_xyz(along, y, 0.0))
}

/// World pose of a point on a support surface of `parent` (placed at `world_from_parent`):
/// `(u, v)` from the surface centre along the parent's x and y, `yaw` relative to the parent,
/// lifted `lift` metres above the surface.
pub fn on_surface(
    world_from_parent: &Pose,
    surface: &SurfaceRecord,
    u: f64,
    v: f64,
    yaw: f64,
    lift: f64,
) -> Pose {
    world_from_parent.compose(&Pose::from_xyz_yaw(
        surface.center[0] + u,
        surface.center[1] + v,
        surface.center[2] + lift,
        yaw,
    ))
}

/// Searches the floor for a free upright pose of an object with bounds `record.bounds`, closest
/// to `preferred` (world XY). Candidates lie on a 5 cm grid, for each yaw in `yaws`; a candidate
/// must fit inside the floor and clear `occupied` by `gap`, with its footprint grown by
/// `clearance` (x, y half-extent increments, e.g. room for chairs) also inside the floor.
pub fn find_floor_spot(
    floor: &[[f64; 2]],
    occupied: &[Footprint],
    record: &AssetRecord,
    preferred: [f64; 2],
    yaws: &[f64],
    clearance: [f64; 2],
    gap: f64,
) -> Option<Pose> {
    let (lo, hi) = polygon::bounds(floor);
    let step = 0.05;
    let mut best: Option<(f64, Pose)> = None;
    let nx = ((hi[0] - lo[0]) / step).floor() as i64;
    let ny = ((hi[1] - lo[1]) / step).floor() as i64;
    for ix in 0..=nx {
        for iy in 0..=ny {
            let x = lo[0] + ix as f64 * step;
            let y = lo[1] + iy as f64 * step;
            let d2 = (x - preferred[0]).powi(2) + (y - preferred[1]).powi(2);
            if best.as_ref().is_some_and(|(b, _)| *b <= d2) {
                continue;
            }
            for &yaw in yaws {
                let pose = Pose::from_xyz_yaw(x, y, 0.0, yaw);
                let fp = Footprint::of(record, &pose);
                let mut grown = fp;
                grown.half[0] += clearance[0];
                grown.half[1] += clearance[1];
                if grown.inside(floor) && !occupied.iter().any(|o| o.overlaps(&grown, gap)) {
                    best = Some((d2, pose));
                    break;
                }
            }
        }
    }
    best.map(|(_, p)| p)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn fp(x: f64, y: f64, yaw: f64) -> Footprint {
        Footprint {
            center: [x, y],
            half: [0.5, 0.25],
            yaw,
            z: [0.0, 1.0],
        }
    }

    #[test]
    fn sat_overlap() {
        assert!(fp(0.0, 0.0, 0.0).overlaps(&fp(0.9, 0.0, 0.0), 0.0));
        assert!(!fp(0.0, 0.0, 0.0).overlaps(&fp(1.1, 0.0, 0.0), 0.0));
        assert!(fp(0.0, 0.0, 0.0).overlaps(&fp(1.1, 0.0, 0.0), 0.2));
        // Rotated by 90 degrees the second box is narrow along x.
        assert!(!fp(0.0, 0.0, 0.0).overlaps(&fp(0.8, 0.0, std::f64::consts::FRAC_PI_2), 0.0));
        // Different heights never overlap.
        let mut high = fp(0.0, 0.0, 0.0);
        high.z = [1.5, 2.0];
        assert!(!fp(0.0, 0.0, 0.0).overlaps(&high, 0.0));
    }

    #[test]
    fn inside_floor() {
        let floor = [[0.0, 0.0], [4.0, 0.0], [4.0, 3.0], [0.0, 3.0]];
        assert!(fp(2.0, 1.5, 0.3).inside(&floor));
        assert!(!fp(3.8, 1.5, 0.0).inside(&floor));
    }
}
