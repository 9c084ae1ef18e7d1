//! Floor-plan metrics: NAV (how connected the free floor is for a round robot) and OOB
//! (objects outside their room's floor polygon), from the objects' convex collision pieces
//! projected onto the floor.

use std::collections::BTreeMap;

use geo::{
    Area, BooleanOps, Buffer, Contains, ConvexHull, Coord, LineString, MultiPoint, MultiPolygon,
    Point, Polygon,
};
use serde::{Deserialize, Serialize};

use crate::physics::collision::PosedObject;
use crate::scene::{ObjectKind, Scene};

/// NAV of one room.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct NavRoom {
    /// Room id.
    pub room: String,
    /// Floor the robot's centre can reach anywhere, m^2.
    pub free_area_m2: f64,
    /// Largest connected part of it, m^2.
    pub largest_region_m2: f64,
    /// Connected parts.
    pub regions: usize,
    /// `largest_region / free_area` (0 when nothing is free).
    pub ratio: f64,
}

/// NAV over the scene.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Nav {
    /// Robot radius, metres.
    pub robot_radius_m: f64,
    /// Obstacles are objects with geometry between 2 cm and this height, metres.
    pub robot_height_m: f64,
    /// Per room.
    pub rooms: Vec<NavRoom>,
    /// Sum of largest regions over sum of free areas.
    pub ratio: f64,
}

/// OOB over the scene.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Oob {
    /// Objects checked (architecture excluded).
    pub objects: usize,
    /// Objects with geometry outside their room's floor polygon (by more than the tolerance).
    pub outside: Vec<String>,
    /// Percent outside.
    pub percent: f64,
    /// Tolerance, metres.
    pub tolerance_m: f64,
}

fn ring(points: &[[f64; 2]]) -> Polygon<f64> {
    Polygon::new(
        LineString::from(points.iter().map(|p| (p[0], p[1])).collect::<Vec<_>>()),
        vec![],
    )
}

/// World vertices of each collision piece of an object.
fn piece_vertices(o: &PosedObject) -> Vec<Vec<[f64; 3]>> {
    o.pieces
        .iter()
        .map(|p| p.vertices.iter().map(|v| [v.x, v.y, v.z]).collect())
        .collect()
}

/// Floor footprint of the pieces of `o` that reach into `[z_lo, z_hi]`: a union of the convex
/// hulls of their XY projections.
fn footprint(o: &PosedObject, z_lo: f64, z_hi: f64) -> Vec<Polygon<f64>> {
    piece_vertices(o)
        .into_iter()
        .filter(|vs| {
            let lo = vs.iter().map(|v| v[2]).fold(f64::INFINITY, f64::min);
            let hi = vs.iter().map(|v| v[2]).fold(f64::NEG_INFINITY, f64::max);
            hi >= z_lo && lo <= z_hi
        })
        .map(|vs| {
            MultiPoint::from(
                vs.iter()
                    .map(|v| Point::new(v[0], v[1]))
                    .collect::<Vec<_>>(),
            )
            .convex_hull()
        })
        .filter(|p| p.unsigned_area() > 1e-10)
        .collect()
}

/// NAV: per room, the floor eroded by the robot radius minus the obstacles grown by it; the
/// largest connected part over the whole.
pub fn nav(scene: &Scene, posed: &[PosedObject], robot_radius: f64, robot_height: f64) -> Nav {
    let mut rooms = Vec::new();
    for room in &scene.rooms {
        if room.floor_polygon.len() < 3 {
            continue;
        }
        let floor = ring(&room.floor_polygon);
        let reachable = if robot_radius > 0.0 {
            floor.buffer(-robot_radius)
        } else {
            MultiPolygon::new(vec![floor])
        };
        let ids: BTreeMap<&str, ObjectKind> = scene
            .objects
            .iter()
            .filter(|o| o.room == room.id)
            .map(|o| (o.id.as_str(), o.kind))
            .collect();
        let obstacles: Vec<Polygon<f64>> = posed
            .iter()
            .filter(|p| {
                ids.get(p.id.as_str())
                    .is_some_and(|k| *k != ObjectKind::Architecture)
            })
            .flat_map(|p| footprint(p, 0.02, robot_height))
            .collect();
        let mut blocked = MultiPolygon::new(vec![]);
        for o in &obstacles {
            let grown = if robot_radius > 0.0 {
                o.buffer(robot_radius)
            } else {
                MultiPolygon::new(vec![o.clone()])
            };
            blocked = blocked.union(&grown);
        }
        let free = reachable.difference(&blocked);
        let areas: Vec<f64> = free.0.iter().map(|p| p.unsigned_area()).collect();
        let total: f64 = areas.iter().sum();
        let largest = areas.iter().copied().fold(0.0, f64::max);
        rooms.push(NavRoom {
            room: room.id.clone(),
            free_area_m2: total,
            largest_region_m2: largest,
            regions: areas.iter().filter(|a| **a > 1e-6).count(),
            ratio: if total > 0.0 { largest / total } else { 0.0 },
        });
    }
    let total: f64 = rooms.iter().map(|r| r.free_area_m2).sum();
    let largest: f64 = rooms.iter().map(|r| r.largest_region_m2).sum();
    Nav {
        robot_radius_m: robot_radius,
        robot_height_m: robot_height,
        rooms,
        ratio: if total > 0.0 { largest / total } else { 0.0 },
    }
}

/// OOB: objects whose collision geometry leaves their room's floor polygon grown by
/// `tolerance` (seen from above).
pub fn oob(scene: &Scene, posed: &[PosedObject], tolerance: f64) -> Oob {
    let floors: BTreeMap<&str, MultiPolygon<f64>> = scene
        .rooms
        .iter()
        .filter(|r| r.floor_polygon.len() >= 3)
        .map(|r| (r.id.as_str(), ring(&r.floor_polygon).buffer(tolerance)))
        .collect();
    let mut outside = Vec::new();
    let mut objects = 0;
    for p in posed {
        let Some(obj) = scene.object(&p.id) else {
            continue;
        };
        if obj.kind == ObjectKind::Architecture {
            continue;
        }
        objects += 1;
        let inside = floors.get(obj.room.as_str()).is_some_and(|floor| {
            piece_vertices(p)
                .iter()
                .flatten()
                .all(|v| floor.contains(&Coord { x: v[0], y: v[1] }))
        });
        if !inside {
            outside.push(p.id.clone());
        }
    }
    Oob {
        objects,
        percent: if objects == 0 {
            0.0
        } else {
            100.0 * outside.len() as f64 / objects as f64
        },
        outside,
        tolerance_m: tolerance,
    }
}
