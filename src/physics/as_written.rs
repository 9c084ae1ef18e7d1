//! Collision geometry exactly as the scene files hold it.
//!
//! Collision OBJ files store vertices at micrometre precision. The physics steps measure the
//! pieces at that precision too, so a scene built in memory and the same scene read back from
//! its files (`--resume`, `scenesmith eval`) give the same projections and metrics, bit for bit,
//! and Rust measures the geometry Drake loads.

use std::collections::BTreeMap;

use crate::assets::{Asset, Link};
use crate::geometry::ConvexPiece;
use crate::physics::collision::{PosedObject, posed_object};
use crate::scene::Scene;

/// `v` as the OBJ writer prints it (`{:.6}`) and a reader parses it back.
pub fn obj_precision(v: f64) -> f64 {
    format!("{v:.6}").parse().unwrap_or(v)
}

/// The asset's links with collision pieces at file precision (visuals dropped: not needed).
fn as_written(asset: &Asset) -> Asset {
    let links = asset
        .links
        .iter()
        .map(|link| Link {
            name: link.name.clone(),
            model_from_link: link.model_from_link,
            visuals: Vec::new(),
            collisions: link
                .collisions
                .iter()
                .map(|p| ConvexPiece {
                    vertices: p.vertices.iter().map(|v| v.map(obj_precision)).collect(),
                    triangles: p.triangles.clone(),
                })
                .collect(),
            mass: link.mass,
            contact: link.contact,
        })
        .collect();
    Asset {
        id: asset.id.clone(),
        category: asset.category.clone(),
        material: asset.material.clone(),
        links,
        joints: asset.joints.clone(),
        surfaces: Vec::new(),
        is_static: asset.is_static,
        provenance: serde_json::Value::Null,
    }
}

/// Every object of `scene` with its collision pieces posed in the world, vertices at the
/// precision of the written files.
pub fn posed_objects(scene: &Scene, assets: &BTreeMap<String, Asset>) -> Vec<PosedObject> {
    let written: BTreeMap<&String, Asset> = assets
        .iter()
        .filter(|(id, _)| scene.objects.iter().any(|o| &o.asset == *id))
        .map(|(id, a)| (id, as_written(a)))
        .collect();
    scene
        .objects
        .iter()
        .filter_map(|o| {
            let asset = written.get(&o.asset)?;
            Some(posed_object(
                &o.id,
                asset,
                &o.world_from_object,
                &o.joint_positions,
            ))
        })
        .collect()
}
