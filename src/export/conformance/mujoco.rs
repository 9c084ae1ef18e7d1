//! MuJoCo rows of the gate: bodies, masses, colliders, joints, placement and a short run.

use std::collections::BTreeMap;
use std::path::Path;

use super::{
    CheckRow, ConformanceError, ExpObject, Rows, STB_MAX_DISPLACEMENT_M, STB_MAX_ROTATION_RAD,
    SceneFacts, Stability, alignment, call_or_row, close,
};
use crate::assets::JointKind;
use crate::export::paths;
use crate::export::view::Hold;
use crate::physics::Bridge;
use crate::physics::protocol::{
    MujocoBody, MujocoCheck, MujocoCheckArgs, MujocoCheckReply, MujocoJoint,
};

pub(super) fn check_mujoco(
    bridge: &mut Bridge,
    dir: &Path,
    exp: &[ExpObject],
    seconds: f64,
    floor_z: f64,
    all: &mut Vec<CheckRow>,
) -> Result<Option<(SceneFacts, Stability)>, ConformanceError> {
    let mut rows = Rows {
        format: "mujoco",
        rows: all,
    };
    let xml = dir.join(paths::MJCF_FILE);
    if !xml.is_file() {
        rows.fail(
            "loads",
            "scene.xml",
            format!("{} is missing", xml.display()),
        );
        return Ok(None);
    }
    let args = MujocoCheckArgs {
        xml,
        seconds,
        probe_joints: BTreeMap::new(),
    };
    let Some(r) = call_or_row::<MujocoCheck>(bridge, &args, &mut rows, "loads")? else {
        return Ok(None);
    };
    let bodies: BTreeMap<&str, &MujocoBody> =
        r.bodies.iter().map(|b| (b.name.as_str(), b)).collect();
    rows.add(
        "loads",
        format!("MuJoCo loads {}", paths::MJCF_FILE),
        format!(
            "MuJoCo {} in {:.2} s: {} bodies, {} meshes",
            r.mujoco,
            r.load_seconds,
            bodies.len(),
            r.counts.meshes
        ),
        vec![],
    );

    let (objects, mass, colliders) = body_rows(&mut rows, exp, &bodies);
    let joints: BTreeMap<&str, &MujocoJoint> =
        r.joints.iter().map(|j| (j.name.as_str(), j)).collect();
    joint_rows(&mut rows, exp, &joints);
    alignment(&mut rows, exp, |l| {
        let b = bodies.get(l.mjcf_body.as_str());
        (
            b.and_then(|b| b.collision_aabb),
            b.and_then(|b| b.visual_aabb),
        )
    });

    let stab = run_rows(&mut rows, exp, &r, &bodies, seconds, floor_z);
    Ok(Some((
        SceneFacts {
            objects,
            mass_kg: mass,
            joints: joints.len(),
            colliders,
        },
        stab,
    )))
}

/// Bodies per link, free/welded, masses and collider counts; returns (objects, mass, colliders).
fn body_rows(
    rows: &mut Rows<'_>,
    exp: &[ExpObject],
    bodies: &BTreeMap<&str, &MujocoBody>,
) -> (usize, f64, usize) {
    let n_links: usize = exp.iter().map(|o| o.links.len()).sum();
    let mut problems = Vec::new();
    let mut objects = 0;
    for o in exp {
        let mut present = true;
        for l in &o.links {
            if !bodies.contains_key(l.mjcf_body.as_str()) {
                problems.push(format!("body {} missing", l.mjcf_body));
                present = false;
            }
        }
        if present {
            objects += 1;
        }
        let free = o
            .links
            .first()
            .and_then(|l| bodies.get(l.mjcf_body.as_str()))
            .is_some_and(|b| b.free);
        if free != (o.hold == Hold::Free) {
            problems.push(format!(
                "{}: {} but the scene has it {}",
                o.id,
                if free { "free" } else { "fixed" },
                match o.hold {
                    Hold::Free => "free",
                    Hold::Welded => "welded",
                    Hold::Static => "static",
                }
            ));
        }
    }
    if bodies.len() != n_links {
        problems.push(format!(
            "{} bodies, scene has {n_links} links",
            bodies.len()
        ));
    }
    rows.add(
        "one body per link, free/welded",
        format!("{} objects, {n_links} bodies", exp.len()),
        format!("{objects} objects, {} bodies", bodies.len()),
        problems,
    );

    let mut problems = Vec::new();
    let mut mass = 0.0;
    for o in exp.iter().filter(|o| o.hold != Hold::Static) {
        let got: f64 = o
            .links
            .iter()
            .filter_map(|l| bodies.get(l.mjcf_body.as_str()))
            .map(|b| b.mass)
            .sum();
        mass += got;
        if !close(got, o.mass, 1e-9, 1e-12) {
            problems.push(format!("{}: {got} kg, scene {} kg", o.id, o.mass));
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
    let mut colliders = 0;
    for o in exp {
        for l in &o.links {
            let got = bodies
                .get(l.mjcf_body.as_str())
                .map_or(0, |b| b.collision_geoms);
            colliders += got;
            if got != l.pieces {
                problems.push(format!(
                    "{}: {got} collision geoms, {} pieces",
                    l.mjcf_body, l.pieces
                ));
            }
        }
    }
    let pieces: usize = exp.iter().flat_map(|o| &o.links).map(|l| l.pieces).sum();
    rows.add(
        "one collision geom per convex piece",
        format!("{pieces} pieces"),
        format!("{colliders} collision geoms"),
        problems,
    );

    (objects, mass, colliders)
}

/// Hinges and slides: type, range in radians, world axis (sign), initial position.
fn joint_rows(rows: &mut Rows<'_>, exp: &[ExpObject], joints: &BTreeMap<&str, &MujocoJoint>) {
    let mut problems = Vec::new();
    let n_joints: usize = exp.iter().map(|o| o.joints.len()).sum();
    for o in exp {
        for j in &o.joints {
            let Some(g) = joints.get(j.mjcf_name.as_str()) else {
                problems.push(format!("joint {} missing", j.mjcf_name));
                continue;
            };
            let want = match j.kind {
                JointKind::Revolute => "hinge",
                JointKind::Prismatic => "slide",
            };
            if g.kind != want {
                problems.push(format!("{}: type {}, want {want}", j.mjcf_name, g.kind));
            }
            let [lo, hi] = g.range;
            if !g.limited || !close(lo, j.lower, 0.0, 1e-9) || !close(hi, j.upper, 0.0, 1e-9) {
                problems.push(format!(
                    "{}: range [{lo}, {hi}], scene [{}, {}] rad",
                    j.mjcf_name, j.lower, j.upper
                ));
            }
            let axis = g.axis_world;
            let dot: f64 = (0..3).map(|k| axis[k] * j.axis_world[k]).sum();
            if dot < 1.0 - 1e-6 {
                problems.push(format!(
                    "{}: world axis {axis:?}, scene {:?}",
                    j.mjcf_name, j.axis_world
                ));
            }
            if !close(g.qpos0, j.q, 0.0, 1e-9) {
                problems.push(format!(
                    "{}: initial position {}, scene {}",
                    j.mjcf_name, g.qpos0, j.q
                ));
            }
        }
    }
    rows.add(
        "hinge/slide joints: range (rad), axis sign, initial position",
        format!("{n_joints} joints"),
        format!("{} joints match", joints.len()),
        problems,
    );
}

/// The run: finite state, nothing falling out of the world, and STB of the free objects.
fn run_rows(
    rows: &mut Rows<'_>,
    exp: &[ExpObject],
    r: &MujocoCheckReply,
    bodies: &BTreeMap<&str, &MujocoBody>,
    seconds: f64,
    floor_z: f64,
) -> Stability {
    let finite = r.finite;
    let warnings = &r.warnings;
    let mut problems = Vec::new();
    if !finite {
        problems.push("state became non-finite".to_string());
    }
    for (w, n) in warnings {
        if w.contains("BADQ") {
            problems.push(format!("{w} x{n}"));
        }
    }
    let mut stab = Stability {
        seconds: r.simulated_seconds,
        free_objects: 0,
        stable: 0,
        percent: 100.0,
        finite,
        max_displacement_m: 0.0,
        max_rotation_rad: 0.0,
        moved: Vec::new(),
    };
    for o in exp.iter().filter(|o| o.hold == Hold::Free) {
        stab.free_objects += 1;
        let Some(b) = o
            .links
            .first()
            .and_then(|l| bodies.get(l.mjcf_body.as_str()))
        else {
            continue;
        };
        // A free body without a motion is one whose state went non-finite: it did not stay.
        let d = b.displacement_m.unwrap_or(f64::INFINITY);
        let a = b.rotation_rad.unwrap_or(f64::INFINITY);
        stab.max_displacement_m = stab.max_displacement_m.max(d);
        stab.max_rotation_rad = stab.max_rotation_rad.max(a);
        if d < STB_MAX_DISPLACEMENT_M && a < STB_MAX_ROTATION_RAD {
            stab.stable += 1;
        } else {
            stab.moved.push((o.id.clone(), d, a));
        }
        if let Some([_, _, z]) = b.final_pos
            && z < floor_z - 1.0
        {
            problems.push(format!("{} fell out of the world (z = {z:.1} m)", o.id));
        }
    }
    if stab.free_objects > 0 {
        stab.percent = 100.0 * stab.stable as f64 / stab.free_objects as f64;
    }
    rows.add(
        "simulate: finite, nothing falls out of the world",
        format!("{seconds} s stable"),
        format!(
            "{:.1} s in {:.2} s wall, {} contacts at the end",
            stab.seconds, r.sim_seconds, r.contacts_at_end
        ),
        problems,
    );
    // STB is reported, not gated: an object that slides in MuJoCo also slides in Drake when the
    // scene itself is unsettled, which is the settling stage's business, not the exporter's.
    rows.rows.push(CheckRow {
        format: "mujoco".into(),
        check: "STB (free objects moving < 1 cm, turning < 0.1 rad)".into(),
        expected: "report".into(),
        got: format!(
            "{}/{} ({:.1}%), max {:.2} mm / {:.3} rad",
            stab.stable,
            stab.free_objects,
            stab.percent,
            stab.max_displacement_m * 1e3,
            stab.max_rotation_rad
        ),
        pass: true,
    });
    stab
}
