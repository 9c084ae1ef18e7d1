//! `export/scene.glb`: the whole scene as one binary glTF for Blender and web viewers.
//!
//! Each object is a root node named by its id (pose `world_from_object`) with one child node per
//! link that has visuals (`<object>/<link>`, pose at the object's joint positions). Meshes,
//! materials and PNG textures are shared by every instance of an asset and embedded in the
//! binary chunk. Node `extras` carry the category, kind, asset and hold of each object; the
//! document's `asset.extras` carry the prompt and seed. Visual geometry only: collision pieces
//! are in the MJCF and USD exports.

use std::collections::BTreeMap;

use serde_json::{Value, json};

use super::view::{Hold, SceneView};
use crate::formats::gltf::GltfBuilder;

/// The GLB bytes of the scene.
pub fn scene_glb(view: &SceneView<'_>) -> Vec<u8> {
    let mut b = GltfBuilder::new_embedded();
    let mut meshes: BTreeMap<(usize, usize), Option<usize>> = BTreeMap::new();
    let mut object_nodes = Vec::new();
    for o in &view.objects {
        let av = view.asset_of(o);
        let mut children = Vec::new();
        for (li, link) in av.asset.links.iter().enumerate() {
            if link.visuals.iter().all(|v| v.mesh.is_empty()) {
                continue;
            }
            let mesh = *meshes.entry((o.asset, li)).or_insert_with(|| {
                Some(b.add_mesh(&format!("{}/{}", av.name, av.link_names[li]), &link.visuals))
            });
            children.push(b.add_node(
                &format!("{}/{}", o.name, av.link_names[li]),
                mesh,
                Some(&o.model_from_links[li]),
                vec![],
            ));
        }
        let node = b.add_node(&o.name, None, Some(&o.object.world_from_object), children);
        b.add_root(node);
        object_nodes.push((node, o));
    }
    let glb = b.to_glb();
    let scene = view.scene;
    with_json(glb, |doc| {
        doc["asset"]["extras"] = json!({
            "prompt": scene.provenance.prompt,
            "seed": scene.provenance.seed,
            "package": scene.package_name,
            "up_axis_of_source": "Z (converted to glTF's +Y up)",
        });
        for (node, o) in &object_nodes {
            let av = view.asset_of(o);
            doc["nodes"][*node]["extras"] = json!({
                "id": o.object.id,
                "category": o.object.category,
                "kind": o.object.kind.as_str(),
                "asset": av.asset.id,
                "hold": match o.hold { Hold::Static => "static", Hold::Welded => "welded", Hold::Free => "free" },
                "mass_kg": if o.hold == Hold::Static { Value::Null } else { json!(av.asset.mass()) },
            });
        }
    })
}

/// Applies `edit` to the JSON chunk of a GLB and re-packs it (chunk padding and lengths
/// recomputed). Returns the input unchanged when it is not a GLB this crate wrote.
fn with_json(glb: Vec<u8>, edit: impl FnOnce(&mut Value)) -> Vec<u8> {
    let read_u32 = |at: usize| -> Option<usize> {
        glb.get(at..at + 4)
            .and_then(|b| b.try_into().ok())
            .map(|b| u32::from_le_bytes(b) as usize)
    };
    let Some(json_len) = read_u32(12) else {
        return glb;
    };
    let Some(json_bytes) = glb.get(20..20 + json_len) else {
        return glb;
    };
    let Ok(mut doc) = serde_json::from_slice::<Value>(json_bytes) else {
        return glb;
    };
    let bin_start = 20 + json_len;
    let bin = match read_u32(bin_start) {
        Some(n) => glb.get(bin_start + 8..bin_start + 8 + n).unwrap_or(&[]),
        None => &[],
    };
    edit(&mut doc);
    let mut json_out = serde_json::to_vec(&doc).unwrap_or_default();
    while !json_out.len().is_multiple_of(4) {
        json_out.push(b' ');
    }
    let total = 12 + 8 + json_out.len() + if bin.is_empty() { 0 } else { 8 + bin.len() };
    let mut out = Vec::with_capacity(total);
    out.extend_from_slice(b"glTF");
    out.extend_from_slice(&2u32.to_le_bytes());
    out.extend_from_slice(&(total as u32).to_le_bytes());
    out.extend_from_slice(&(json_out.len() as u32).to_le_bytes());
    out.extend_from_slice(b"JSON");
    out.extend_from_slice(&json_out);
    if !bin.is_empty() {
        out.extend_from_slice(&(bin.len() as u32).to_le_bytes());
        out.extend_from_slice(b"BIN\0");
        out.extend_from_slice(bin);
    }
    out
}
