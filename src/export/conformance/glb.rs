//! GLB row of the gate: the file parses, every object is a named root node, visuals in place.

use std::path::Path;

use serde_json::Value;

use super::{ALIGN_TOL_M, CheckRow, ExpObject, Rows, aabb_gap, union};
use crate::export::paths;
use crate::export::view::SceneView;

pub(super) fn check_glb(
    dir: &Path,
    view: &SceneView<'_>,
    exp: &[ExpObject],
    all: &mut Vec<CheckRow>,
) {
    let mut rows = Rows {
        format: "glb",
        rows: all,
    };
    let path = dir.join(paths::GLB_FILE);
    let bytes = match std::fs::read(&path) {
        Ok(b) => b,
        Err(e) => {
            rows.fail("loads", "scene.glb", format!("{}: {e}", path.display()));
            return;
        }
    };
    let parts = match crate::assets::gltf_read::parse(&bytes, None) {
        Ok(p) => p,
        Err(e) => {
            rows.fail("loads", "scene.glb", e);
            return;
        }
    };
    let tris: usize = parts.iter().map(|p| p.mesh.triangles.len()).sum();
    let want_tris: usize = view
        .objects
        .iter()
        .map(|o| {
            view.asset_of(o)
                .visuals
                .iter()
                .flatten()
                .map(|g| g.mesh.triangles.len())
                .sum::<usize>()
        })
        .sum();
    let mut got_box = None;
    for p in &parts {
        got_box = union(got_box, &p.mesh.positions);
    }
    let mut want_box = None;
    for o in exp {
        for l in &o.links {
            if let Some(v) = l.visual {
                want_box = union(want_box, &v);
            }
        }
    }
    let mut problems = Vec::new();
    if tris != want_tris {
        problems.push(format!("{tris} triangles, scene {want_tris}"));
    }
    if let (Some(a), Some(b)) = (got_box, want_box) {
        // glTF stores single-precision vertices.
        let gap = aabb_gap(&a, &b);
        if gap > ALIGN_TOL_M {
            problems.push(format!("scene bounds off by {:.3} mm", gap * 1e3));
        }
    }
    // Root nodes named after the objects.
    let names = glb_root_names(&bytes);
    let want: Vec<&str> = exp.iter().map(|o| o.name.as_str()).collect();
    if names.iter().map(String::as_str).collect::<Vec<_>>() != want {
        problems.push(format!(
            "{} root nodes, names differ from object ids",
            names.len()
        ));
    }
    rows.add(
        "one named node per object, visuals in place",
        format!("{} objects, {want_tris} triangles", exp.len()),
        format!("{} root nodes, {tris} triangles", names.len()),
        problems,
    );
}

fn glb_root_names(bytes: &[u8]) -> Vec<String> {
    let len = bytes
        .get(12..16)
        .and_then(|b| b.try_into().ok())
        .map(u32::from_le_bytes)
        .unwrap_or(0) as usize;
    let Some(doc) = bytes
        .get(20..20 + len)
        .and_then(|j| serde_json::from_slice::<Value>(j).ok())
    else {
        return Vec::new();
    };
    doc["scenes"][0]["nodes"]
        .as_array()
        .map(|a| {
            a.iter()
                .filter_map(|n| {
                    doc["nodes"][n.as_u64()? as usize]["name"]
                        .as_str()
                        .map(str::to_string)
                })
                .collect()
        })
        .unwrap_or_default()
}
