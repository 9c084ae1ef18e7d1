//! Loading a written scene directory in Drake: does it load as `scene.json` says (instances,
//! welds, poses), and how deep do its objects penetrate (COL)?

use std::path::Path;

use serde::Serialize;
use serde_json::json;

use super::{Bridge, PhysicsError};
use crate::formats::scene_dir::{self, names};
use crate::scene::ObjectKind;

/// Result of checking a scene directory with Drake.
#[derive(Debug, Clone, Serialize, serde::Deserialize, PartialEq)]
pub struct CheckSummary {
    /// Drake version that loaded the scene.
    pub drake: String,
    /// Model instances loaded.
    pub model_instances: usize,
    /// Objects in `scene.json`.
    pub scene_objects: usize,
    /// Bodies in the plant.
    pub bodies: usize,
    /// Free bodies.
    pub free_bodies: usize,
    /// Objects counted for COL (architecture excluded).
    pub col_objects: usize,
    /// COL: percent of objects penetrating deeper than the threshold.
    pub col_percent: f64,
    /// Mean depth of the penetrating pairs, metres.
    pub mean_depth_m: f64,
    /// Deepest penetration, metres.
    pub max_depth_m: f64,
    /// Threshold, metres.
    pub threshold_m: f64,
    /// The penetrating pairs `(a, b, depth_m)`.
    pub pairs: Vec<(String, String, f64)>,
    /// Mismatches between `scene.json` and what Drake loaded.
    pub problems: Vec<String>,
}

impl CheckSummary {
    /// True when the scene loaded as written and COL is within `max_col_percent`.
    pub fn passed(&self, max_col_percent: f64) -> bool {
        self.problems.is_empty() && self.col_percent <= max_col_percent + 1e-9
    }
}

/// Loads a scene directory in Drake through `bridge` and measures collisions; compares what
/// Drake loaded against `scene.json`.
pub fn check_dir(
    bridge: &mut Bridge,
    dir: &Path,
    threshold_m: f64,
) -> Result<CheckSummary, PhysicsError> {
    let scene = scene_dir::read_scene(dir)?;
    let directives = dir.join(names::DIRECTIVES);
    let package_xml = dir.join(names::PACKAGE_XML);
    let args = json!({
        "directives": directives,
        "package_xml": package_xml,
    });
    let loaded = bridge.request("load", args.clone())?;
    let static_ids: Vec<String> = scene
        .objects_of_kind(ObjectKind::Architecture)
        .map(|o| o.id.clone())
        .collect();
    let mut report_args = args;
    report_args["threshold"] = json!(threshold_m);
    report_args["static_instances"] = json!(static_ids);
    let report = bridge.request("collision_report", report_args)?;

    let instances = loaded["model_instances"]
        .as_array()
        .cloned()
        .unwrap_or_default();
    let mut problems = Vec::new();
    let loaded_names: std::collections::BTreeSet<String> = instances
        .iter()
        .filter_map(|m| m["name"].as_str().map(str::to_string))
        .collect();
    for o in &scene.objects {
        if !loaded_names.contains(&o.id) {
            problems.push(format!("object {} is not a model instance in Drake", o.id));
        }
    }
    let mut free_bodies = 0;
    for m in &instances {
        let name = m["name"].as_str().unwrap_or_default();
        let Some(obj) = scene.object(name) else {
            problems.push(format!("Drake has an unexpected model instance {name}"));
            continue;
        };
        let free = m["free_bodies"].as_object().cloned().unwrap_or_default();
        free_bodies += free.len();
        if obj.welded && !free.is_empty() {
            problems.push(format!("{name} should be welded but Drake has it free"));
        }
        if !obj.welded && free.is_empty() {
            problems.push(format!("{name} should be free but Drake has it welded"));
        }
        if let Some((_, pose)) = free.iter().next() {
            let xyz: Vec<f64> = pose["xyz"]
                .as_array()
                .map(|a| a.iter().filter_map(|v| v.as_f64()).collect())
                .unwrap_or_default();
            let p = obj.world_from_object.translation();
            if xyz.len() == 3
                && ((xyz[0] - p.x).abs() > 1e-6
                    || (xyz[1] - p.y).abs() > 1e-6
                    || (xyz[2] - p.z).abs() > 1e-6)
            {
                problems.push(format!(
                    "{name}: Drake pose {xyz:?} differs from scene.json [{}, {}, {}]",
                    p.x, p.y, p.z
                ));
            }
        }
    }
    let pairs = report["pairs"]
        .as_array()
        .map(|a| {
            a.iter()
                .map(|p| {
                    (
                        p["a"].as_str().unwrap_or_default().to_string(),
                        p["b"].as_str().unwrap_or_default().to_string(),
                        p["depth"].as_f64().unwrap_or(0.0),
                    )
                })
                .collect()
        })
        .unwrap_or_default();
    Ok(CheckSummary {
        drake: bridge.hello().drake.clone(),
        model_instances: instances.len(),
        scene_objects: scene.objects.len(),
        bodies: loaded["num_bodies"].as_u64().unwrap_or(0) as usize,
        free_bodies,
        col_objects: report["objects"].as_u64().unwrap_or(0) as usize,
        col_percent: report["col_percent"].as_f64().unwrap_or(f64::NAN),
        mean_depth_m: report["mean_depth_m"].as_f64().unwrap_or(f64::NAN),
        max_depth_m: report["max_depth_m"].as_f64().unwrap_or(f64::NAN),
        threshold_m,
        pairs,
        problems,
    })
}
