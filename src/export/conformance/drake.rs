//! Drake rows of the gate: the directives load with the scene's instances, masses and joints.

use std::collections::BTreeMap;
use std::path::Path;

use super::{CheckRow, ConformanceError, ExpObject, Rows, SceneFacts, call_or_row, close};
use crate::export::view::Hold;
use crate::formats::scene_dir::names;
use crate::physics::Bridge;
use crate::physics::protocol::{Load, LoadedInstance, SceneFiles};

pub(super) fn check_drake(
    bridge: &mut Bridge,
    dir: &Path,
    exp: &[ExpObject],
    all: &mut Vec<CheckRow>,
) -> Result<Option<SceneFacts>, ConformanceError> {
    let mut rows = Rows {
        format: "drake",
        rows: all,
    };
    let directives = dir.join(names::DIRECTIVES);
    if !directives.is_file() {
        rows.fail(
            "loads",
            "scene.dmd.yaml",
            format!("{} is missing", directives.display()),
        );
        return Ok(None);
    }
    let files = SceneFiles::new(directives, dir.join(names::PACKAGE_XML));
    let Some(loaded) = call_or_row::<Load>(bridge, &files, &mut rows, "loads")? else {
        return Ok(None);
    };
    let instances: BTreeMap<&str, &LoadedInstance> = loaded
        .model_instances
        .iter()
        .map(|m| (m.name.as_str(), m))
        .collect();
    let mut problems = Vec::new();
    for o in exp {
        if !instances.contains_key(o.id.as_str()) {
            problems.push(format!("{} missing", o.id));
        }
    }
    if instances.len() != exp.len() {
        problems.push(format!("{} model instances", instances.len()));
    }
    rows.add(
        "model instances",
        exp.len().to_string(),
        instances.len().to_string(),
        problems,
    );

    let mut problems = Vec::new();
    let mut mass = 0.0;
    let mut joints = 0;
    for o in exp {
        let Some(m) = instances.get(o.id.as_str()) else {
            continue;
        };
        if o.hold != Hold::Static {
            let got = m.mass;
            mass += got;
            if !close(got, o.mass, 1e-9, 1e-12) {
                problems.push(format!("{}: {got} kg, scene {} kg", o.id, o.mass));
            }
        }
    }
    let total: f64 = exp.iter().map(|o| o.mass).sum();
    rows.add(
        "masses",
        format!("{total:.4} kg"),
        format!("{mass:.4} kg"),
        problems,
    );

    let mut problems = Vec::new();
    for o in exp {
        let Some(m) = instances.get(o.id.as_str()) else {
            continue;
        };
        let got = &m.joints;
        joints += got.len();
        if got.len() != o.joints.len() {
            problems.push(format!(
                "{}: {} joints, scene {}",
                o.id,
                got.len(),
                o.joints.len()
            ));
        }
        for j in &o.joints {
            let Some(g) = got.iter().find(|g| g.name == j.drake_name) else {
                problems.push(format!("{}: joint {} missing", o.id, j.drake_name));
                continue;
            };
            // A joint without limits compares as NaN: never close to the scene's.
            let lo = g.lower.first().copied().unwrap_or(f64::NAN);
            let hi = g.upper.first().copied().unwrap_or(f64::NAN);
            if !close(lo, j.lower, 0.0, 1e-9) || !close(hi, j.upper, 0.0, 1e-9) {
                problems.push(format!(
                    "{}/{}: limits [{lo}, {hi}], scene [{}, {}]",
                    o.id, j.drake_name, j.lower, j.upper
                ));
            }
            if g.kind != j.kind.as_str() {
                problems.push(format!("{}/{}: type {}", o.id, j.drake_name, g.kind));
            }
        }
    }
    let n_joints: usize = exp.iter().map(|o| o.joints.len()).sum();
    rows.add(
        "joints and limits",
        format!("{n_joints} joints"),
        format!("{joints} joints, limits equal"),
        problems,
    );
    Ok(Some(SceneFacts {
        objects: instances.len(),
        mass_kg: mass,
        joints,
        colliders: loaded.num_collision_geometries,
    }))
}
