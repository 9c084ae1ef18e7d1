//! In-loop collision checks in Rust (parry3d) on the same convex pieces Drake uses.

use std::collections::BTreeMap;

use nalgebra::Point3;
use parry3d_f64::math::{Pose as PPose, Rotation as PRot, Vector as PVec};
use parry3d_f64::shape::ConvexPolyhedron;

use crate::assets::{Asset, link_poses};
use crate::geometry::GeometryError;
use crate::scene::{Pose, Scene};

/// Converts a pose to parry's (glam) representation.
pub fn to_parry_pose(pose: &Pose) -> PPose {
    let t = pose.translation();
    let q = pose.rotation();
    PPose::from_parts(
        PVec::new(t.x, t.y, t.z),
        PRot::from_xyzw(q.i, q.j, q.k, q.w),
    )
}

/// Penetration depth (m, positive when overlapping) of two posed convex shapes, or `None` when
/// they are apart.
pub fn penetration(
    a: &ConvexPolyhedron,
    world_from_a: &Pose,
    b: &ConvexPolyhedron,
    world_from_b: &Pose,
) -> Option<f64> {
    let c = parry3d_f64::query::contact(
        &to_parry_pose(world_from_a),
        a,
        &to_parry_pose(world_from_b),
        b,
        0.0,
    )
    .ok()
    .flatten()?;
    (c.dist < 0.0).then_some(-c.dist)
}

/// The convex pieces of one object, posed in the world.
#[derive(Debug)]
pub struct PosedObject {
    /// Object id.
    pub id: String,
    /// Static geometry (architecture).
    pub is_static: bool,
    /// Pieces with their world poses.
    pub pieces: Vec<(ConvexPolyhedron, Pose)>,
    /// World bounds of all pieces.
    pub bounds: ([f64; 3], [f64; 3]),
}

/// Poses every convex piece of every object of `scene` in the world.
pub fn posed_objects(
    scene: &Scene,
    assets: &BTreeMap<String, Asset>,
) -> Result<Vec<PosedObject>, GeometryError> {
    let mut out = Vec::new();
    for obj in &scene.objects {
        let Some(asset) = assets.get(&obj.asset) else {
            continue;
        };
        let model_from_links = link_poses(asset, &obj.joint_positions);
        let mut pieces = Vec::new();
        let mut lo = [f64::INFINITY; 3];
        let mut hi = [f64::NEG_INFINITY; 3];
        for (link, model_from_link) in asset.links.iter().zip(&model_from_links) {
            let world_from_link = obj.world_from_object.compose(model_from_link);
            for piece in &link.collisions {
                for v in &piece.vertices {
                    let w = world_from_link.transform_point(&Point3::new(v[0], v[1], v[2]));
                    for i in 0..3 {
                        lo[i] = lo[i].min(w[i]);
                        hi[i] = hi[i].max(w[i]);
                    }
                }
                pieces.push((piece.to_parry()?, world_from_link));
            }
        }
        out.push(PosedObject {
            id: obj.id.clone(),
            is_static: asset.is_static,
            pieces,
            bounds: (lo, hi),
        });
    }
    Ok(out)
}

/// A penetrating object pair.
#[derive(Debug, Clone, PartialEq)]
pub struct PairPenetration {
    /// First object id (scene order).
    pub a: String,
    /// Second object id.
    pub b: String,
    /// Deepest penetration between any of their pieces, metres.
    pub depth: f64,
}

/// Every object pair penetrating deeper than `threshold` metres (static-static pairs skipped).
pub fn penetrating_pairs(objects: &[PosedObject], threshold: f64) -> Vec<PairPenetration> {
    let mut out = Vec::new();
    for (i, a) in objects.iter().enumerate() {
        for b in &objects[i + 1..] {
            if a.is_static && b.is_static {
                continue;
            }
            let overlap =
                (0..3).all(|k| a.bounds.0[k] <= b.bounds.1[k] && b.bounds.0[k] <= a.bounds.1[k]);
            if !overlap {
                continue;
            }
            let mut deepest: f64 = 0.0;
            for (pa, xa) in &a.pieces {
                for (pb, xb) in &b.pieces {
                    if let Some(d) = penetration(pa, xa, pb, xb) {
                        deepest = deepest.max(d);
                    }
                }
            }
            if deepest > threshold {
                out.push(PairPenetration {
                    a: a.id.clone(),
                    b: b.id.clone(),
                    depth: deepest,
                });
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::ConvexPiece;

    #[test]
    fn overlapping_boxes_report_depth() {
        let a = ConvexPiece::cuboid([0.0; 3], [1.0; 3])
            .unwrap()
            .to_parry()
            .unwrap();
        let b = ConvexPiece::cuboid([0.0; 3], [1.0; 3])
            .unwrap()
            .to_parry()
            .unwrap();
        let d = penetration(&a, &Pose::IDENTITY, &b, &Pose::from_xyz(0.97, 0.0, 0.0)).unwrap();
        assert!((d - 0.03).abs() < 1e-9, "{d}");
        assert!(penetration(&a, &Pose::IDENTITY, &b, &Pose::from_xyz(1.01, 0.0, 0.0)).is_none());
        let rotated = Pose::from_xyz_yaw(0.0, 0.0, 1.6, 0.7);
        assert!(penetration(&a, &Pose::IDENTITY, &b, &rotated).is_none());
    }
}
