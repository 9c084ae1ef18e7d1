//! In-loop collision checks in Rust on the same convex pieces Drake uses: every object's
//! pieces posed in the world and the penetrating pairs of a scene. Depths are exact
//! separating-axis depths ([`crate::geometry::penetration`]).

use std::collections::BTreeMap;

use crate::assets::{Asset, link_poses};
use crate::geometry::GeometryError;
use crate::geometry::penetration::{PosedPiece, sat_penetration};
use crate::scene::{Pose, Scene};

/// The convex pieces of one object, posed in the world.
#[derive(Debug, Clone)]
pub struct PosedObject {
    /// Object id.
    pub id: String,
    /// Static geometry (architecture).
    pub is_static: bool,
    /// Pieces in the world.
    pub pieces: Vec<PosedPiece>,
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
        out.push(posed_object(
            &obj.id,
            asset,
            &obj.world_from_object,
            &obj.joint_positions,
        ));
    }
    Ok(out)
}

/// Poses the pieces of one asset instance.
pub fn posed_object(
    id: &str,
    asset: &Asset,
    world_from_object: &Pose,
    joints: &BTreeMap<String, f64>,
) -> PosedObject {
    let model_from_links = link_poses(asset, joints);
    let mut pieces = Vec::new();
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for (link, model_from_link) in asset.links.iter().zip(&model_from_links) {
        let world_from_link = world_from_object.compose(model_from_link);
        for piece in &link.collisions {
            let p = PosedPiece::new(piece, &world_from_link);
            for k in 0..3 {
                lo[k] = lo[k].min(p.lo[k]);
                hi[k] = hi[k].max(p.hi[k]);
            }
            pieces.push(p);
        }
    }
    PosedObject {
        id: id.to_string(),
        is_static: asset.is_static,
        pieces,
        bounds: (lo, hi),
    }
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

/// Deepest penetration between two posed objects (0 when apart).
pub fn object_penetration(a: &PosedObject, b: &PosedObject) -> f64 {
    let overlap = (0..3).all(|k| a.bounds.0[k] <= b.bounds.1[k] && b.bounds.0[k] <= a.bounds.1[k]);
    if !overlap {
        return 0.0;
    }
    let mut deepest: f64 = 0.0;
    for pa in &a.pieces {
        for pb in &b.pieces {
            if let Some((d, _)) = sat_penetration(pa, pb) {
                deepest = deepest.max(d);
            }
        }
    }
    deepest
}

/// Every object pair penetrating deeper than `threshold` metres (static-static pairs skipped).
pub fn penetrating_pairs(objects: &[PosedObject], threshold: f64) -> Vec<PairPenetration> {
    let mut out = Vec::new();
    for (i, a) in objects.iter().enumerate() {
        for b in &objects[i + 1..] {
            if a.is_static && b.is_static {
                continue;
            }
            let depth = object_penetration(a, b);
            if depth > threshold {
                out.push(PairPenetration {
                    a: a.id.clone(),
                    b: b.id.clone(),
                    depth,
                });
            }
        }
    }
    out
}
