//! Loading a written scene directory in Drake: does it load as `scene.json` says (instances,
//! welds, poses), and how deep do its objects penetrate (COL)?

use std::path::Path;

use serde::Serialize;

use super::protocol::{CollisionReport, CollisionReportArgs, Load, SceneFiles};
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
    let files = SceneFiles::new(dir.join(names::DIRECTIVES), dir.join(names::PACKAGE_XML));
    let loaded = bridge.call::<Load>(&files)?;
    let static_instances: Vec<String> = scene
        .objects_of_kind(ObjectKind::Architecture)
        .map(|o| o.id.clone())
        .collect();
    let report = bridge.call::<CollisionReport>(&CollisionReportArgs {
        scene: files,
        poses: None,
        threshold: Some(threshold_m),
        static_instances,
    })?;

    let mut problems = Vec::new();
    let loaded_names: std::collections::BTreeSet<&str> = loaded
        .model_instances
        .iter()
        .map(|m| m.name.as_str())
        .collect();
    for o in &scene.objects {
        if !loaded_names.contains(o.id.as_str()) {
            problems.push(format!("object {} is not a model instance in Drake", o.id));
        }
    }
    let mut free_bodies = 0;
    for m in &loaded.model_instances {
        let name = &m.name;
        let Some(obj) = scene.object(name) else {
            problems.push(format!("Drake has an unexpected model instance {name}"));
            continue;
        };
        free_bodies += m.free_bodies.len();
        if obj.welded && !m.free_bodies.is_empty() {
            problems.push(format!("{name} should be welded but Drake has it free"));
        }
        if !obj.welded && m.free_bodies.is_empty() {
            problems.push(format!("{name} should be free but Drake has it welded"));
        }
        if let Some(pose) = m.free_bodies.values().next() {
            let xyz = pose.translation();
            let p = obj.world_from_object.translation();
            if (xyz - p).abs().max() > 1e-6 {
                problems.push(format!(
                    "{name}: Drake pose [{}, {}, {}] differs from scene.json [{}, {}, {}]",
                    xyz.x, xyz.y, xyz.z, p.x, p.y, p.z
                ));
            }
        }
    }
    let pairs = report
        .pairs
        .iter()
        .map(|p| (p.a.clone(), p.b.clone(), p.depth))
        .collect();
    Ok(CheckSummary {
        drake: bridge.hello().drake.clone(),
        model_instances: loaded.model_instances.len(),
        scene_objects: scene.objects.len(),
        bodies: loaded.num_bodies,
        free_bodies,
        col_objects: report.objects,
        col_percent: report.col_percent,
        mean_depth_m: report.mean_depth_m,
        max_depth_m: report.max_depth_m,
        threshold_m,
        pairs,
        problems,
    })
}
