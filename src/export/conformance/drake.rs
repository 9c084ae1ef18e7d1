//! Drake rows of the gate: the directives load with the scene's instances, masses and joints.

use std::collections::BTreeMap;
use std::path::Path;

use serde_json::{Value, json};

use super::{CheckRow, ConformanceError, ExpObject, Rows, SceneFacts, close, num, request_or_row};
use crate::export::view::Hold;
use crate::formats::scene_dir::names;
use crate::physics::Bridge;

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
    let args = json!({"directives": directives, "package_xml": dir.join(names::PACKAGE_XML)});
    let Some(loaded) = request_or_row(bridge, "load", args, &mut rows, "loads")? else {
        return Ok(None);
    };
    let instances: BTreeMap<String, &Value> = loaded["model_instances"]
        .as_array()
        .map(|a| {
            a.iter()
                .filter_map(|m| Some((m["name"].as_str()?.to_string(), m)))
                .collect()
        })
        .unwrap_or_default();
    let mut problems = Vec::new();
    for o in exp {
        if !instances.contains_key(&o.id) {
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
        let Some(m) = instances.get(&o.id) else {
            continue;
        };
        if o.hold != Hold::Static {
            let got = num(&m["mass"]).unwrap_or(f64::NAN);
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
        let Some(m) = instances.get(&o.id) else {
            continue;
        };
        let got: Vec<&Value> = m["joints"]
            .as_array()
            .map(|a| a.iter().collect())
            .unwrap_or_default();
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
            let Some(g) = got.iter().find(|g| g["name"] == j.drake_name.as_str()) else {
                problems.push(format!("{}: joint {} missing", o.id, j.drake_name));
                continue;
            };
            let lo = num(&g["lower"][0]).unwrap_or(f64::NAN);
            let hi = num(&g["upper"][0]).unwrap_or(f64::NAN);
            if !close(lo, j.lower, 0.0, 1e-9) || !close(hi, j.upper, 0.0, 1e-9) {
                problems.push(format!(
                    "{}/{}: limits [{lo}, {hi}], scene [{}, {}]",
                    o.id, j.drake_name, j.lower, j.upper
                ));
            }
            if g["type"] != j.kind.as_str() {
                problems.push(format!("{}/{}: type {}", o.id, j.drake_name, g["type"]));
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
        colliders: loaded["num_collision_geometries"].as_u64().unwrap_or(0) as usize,
    }))
}
