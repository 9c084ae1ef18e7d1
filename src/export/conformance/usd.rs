//! USD rows of the gate: stage metadata, validators, rigid bodies, colliders, joints,
//! articulations and placement, as usd-core's UsdPhysics parser sees them.

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

use super::{
    CheckRow, ConformanceError, ExpLink, ExpObject, Rows, SceneFacts, alignment, call_or_row, close,
};
use crate::assets::JointKind;
use crate::export::paths;
use crate::export::view::Hold;
use crate::physics::Bridge;
use crate::physics::protocol::{
    UsdBody, UsdCheck, UsdCheckArgs, UsdCheckReply, UsdFinding, UsdJoint,
};

pub(super) fn check_usd(
    bridge: &mut Bridge,
    dir: &Path,
    exp: &[ExpObject],
    all: &mut Vec<CheckRow>,
) -> Result<Option<(SceneFacts, Vec<UsdFinding>)>, ConformanceError> {
    let mut rows = Rows {
        format: "usd",
        rows: all,
    };
    let file = dir.join(paths::USD_FILE);
    if !file.is_file() {
        rows.fail(
            "loads",
            "scene.usda",
            format!("{} is missing", file.display()),
        );
        return Ok(None);
    }
    let static_prims: Vec<String> = exp
        .iter()
        .filter(|o| o.hold == Hold::Static)
        .flat_map(|o| o.links.iter().map(|l| l.usd_body.clone()))
        .collect();
    let args = UsdCheckArgs {
        usd: file,
        static_prims,
    };
    let Some(r) = call_or_row::<UsdCheck>(bridge, &args, &mut rows, "loads")? else {
        return Ok(None);
    };
    let findings = stage_rows(&mut rows, &r);
    let bodies = &r.bodies;
    let (objects, mass) = body_rows(&mut rows, exp, &r, bodies);
    let colliders = collider_rows(&mut rows, exp, &r, bodies);
    let movable = joint_rows(&mut rows, exp, &r);
    articulation_rows(&mut rows, exp, &r, bodies);
    alignment(&mut rows, exp, |l| {
        if let Some(b) = bodies.get(&l.usd_body) {
            (b.collision_aabb, b.visual_aabb)
        } else {
            // Static geometry is grouped per link prim (`static_prims`).
            let s = r.static_groups.get(&l.usd_body);
            (
                s.and_then(|s| s.collision_aabb),
                s.and_then(|s| s.visual_aabb),
            )
        }
    });
    Ok(Some((
        SceneFacts {
            objects,
            mass_kg: mass,
            joints: movable,
            colliders,
        },
        findings,
    )))
}

/// Stage metadata, composition errors and validator findings; returns the findings.
fn stage_rows(rows: &mut Rows<'_>, r: &UsdCheckReply) -> Vec<UsdFinding> {
    let md = &r.metadata;
    let mut problems = Vec::new();
    if md.meters_per_unit != 1.0 {
        problems.push(format!("metersPerUnit {}", md.meters_per_unit));
    }
    if md.kilograms_per_unit != 1.0 {
        problems.push(format!("kilogramsPerUnit {}", md.kilograms_per_unit));
    }
    if md.up_axis != "Z" {
        problems.push(format!("upAxis {}", md.up_axis));
    }
    if md.default_prim.as_deref() != Some("/World") {
        problems.push(format!("defaultPrim {:?}", md.default_prim));
    }
    if r.physics_scenes != 1 {
        problems.push(format!("{} PhysicsScene prims", r.physics_scenes));
    }
    for e in &r.composition_errors {
        problems.push(format!("composition: {e}"));
    }
    rows.add(
        "stage: metres, kg, Z up, /World, one PhysicsScene",
        "metersPerUnit 1, kilogramsPerUnit 1, upAxis Z".into(),
        format!("usd-core {} opened in {:.2} s", r.usd, r.open_seconds),
        problems,
    );

    let findings = r.findings.clone();
    let errors: Vec<String> = findings
        .iter()
        .filter(|f| f.severity.contains("Error"))
        .map(|f| format!("{}: {}", f.validator, f.message))
        .collect();
    rows.add(
        "UsdValidation (all validators incl. UsdPhysics)",
        "no errors".into(),
        format!("{} findings, 0 errors", findings.len()),
        errors,
    );

    findings
}

/// Rigid bodies: one per link of every non-static object, with mass and a collider;
/// returns (objects present, total mass).
fn body_rows(
    rows: &mut Rows<'_>,
    exp: &[ExpObject],
    r: &UsdCheckReply,
    bodies: &BTreeMap<String, UsdBody>,
) -> (usize, f64) {
    let mut problems = Vec::new();
    let mut expected_bodies = BTreeSet::new();
    let mut mass = 0.0;
    let mut objects = 0;
    for o in exp {
        let mut present = true;
        if o.hold == Hold::Static {
            for l in o.links.iter().filter(|l| l.pieces > 0) {
                if !r.static_groups.contains_key(&l.usd_body) {
                    problems.push(format!("{} has no colliders", l.usd_body));
                    present = false;
                }
            }
        } else {
            let mut m = 0.0;
            for l in &o.links {
                expected_bodies.insert(l.usd_body.clone());
                match bodies.get(&l.usd_body) {
                    None => {
                        problems.push(format!("{} is not a rigid body", l.usd_body));
                        present = false;
                    }
                    Some(b) => {
                        let got = b.mass;
                        match got {
                            Some(g) if close(g, l.mass, 1e-6, 1e-9) => {}
                            _ => problems
                                .push(format!("{}: mass {:?}, scene {}", l.usd_body, got, l.mass)),
                        }
                        m += got.unwrap_or(0.0);
                        if b.colliders == 0 {
                            problems.push(format!("{} has no collider", l.usd_body));
                        }
                        let kinematic = b.kinematic;
                        let want = o.hold == Hold::Welded && !o.articulated;
                        if kinematic != want {
                            problems.push(format!("{}: kinematic {kinematic}", l.usd_body));
                        }
                    }
                }
            }
            mass += m;
        }
        if present {
            objects += 1;
        }
    }
    for b in bodies.keys() {
        if !expected_bodies.contains(b) {
            problems.push(format!("unexpected rigid body {b}"));
        }
    }
    let total: f64 = exp.iter().map(|o| o.mass).sum();
    rows.add(
        "rigid bodies with mass and colliders",
        format!("{} bodies, {total:.4} kg", expected_bodies.len()),
        format!("{} bodies, {mass:.4} kg", bodies.len()),
        problems,
    );

    (objects, mass)
}

/// Colliders: one convexHull mesh per piece, each bound to a physics material; returns the
/// collider count.
fn collider_rows(
    rows: &mut Rows<'_>,
    exp: &[ExpObject],
    r: &UsdCheckReply,
    bodies: &BTreeMap<String, UsdBody>,
) -> usize {
    let mut problems = Vec::new();
    let mut colliders = 0;
    for o in exp {
        if o.hold == Hold::Static {
            for l in &o.links {
                let got = r.static_groups.get(&l.usd_body).map_or(0, |s| s.colliders);
                colliders += got;
                if got != l.pieces {
                    problems.push(format!(
                        "{}: {got} colliders, {} pieces",
                        l.usd_body, l.pieces
                    ));
                }
            }
            continue;
        }
        for l in &o.links {
            let got = bodies.get(&l.usd_body).map_or(0, |b| b.colliders);
            colliders += got;
            if got != l.pieces {
                problems.push(format!(
                    "{}: {got} colliders, {} pieces",
                    l.usd_body, l.pieces
                ));
            }
        }
    }
    let pieces: usize = exp.iter().flat_map(|o| &o.links).map(|l| l.pieces).sum();
    for (k, n) in &r.approximations {
        if k != "convexHull" {
            problems.push(format!("{n} colliders with approximation {k}"));
        }
    }
    if r.colliders_without_material != 0 {
        problems.push(format!(
            "{} colliders without a physics material",
            r.colliders_without_material
        ));
    }
    rows.add(
        "convexHull collider per piece, friction bound",
        format!("{pieces} pieces"),
        format!("{colliders} colliders"),
        problems,
    );

    colliders
}

/// Joints: targets resolve, limits in degrees / metres, world axis, initial position, welds;
/// returns the number of revolute and prismatic joints.
fn joint_rows(rows: &mut Rows<'_>, exp: &[ExpObject], r: &UsdCheckReply) -> usize {
    let joints: BTreeMap<&str, &UsdJoint> = r.joints.iter().map(|j| (j.path.as_str(), j)).collect();
    let mut problems = Vec::new();
    let mut movable = 0;
    for j in joints.values() {
        if !j.body0_ok || !j.body1_ok {
            problems.push(format!(
                "{}: body0 {} / body1 {} do not resolve to rigid bodies",
                j.path, j.body0, j.body1
            ));
        }
        if j.frame_gap_m.is_none_or(|g| g > 1e-5) {
            problems.push(format!(
                "{}: joint frames {:?} m apart",
                j.path, j.frame_gap_m
            ));
        }
        if matches!(j.kind.as_str(), "revolute" | "prismatic") {
            movable += 1;
        }
    }
    for o in exp {
        for e in &o.joints {
            let Some(g) = joints.get(e.usd_path.as_str()) else {
                problems.push(format!("joint {} missing", e.usd_path));
                continue;
            };
            let (want, lo, hi, q, tol) = match e.kind {
                JointKind::Revolute => (
                    "revolute",
                    e.lower.to_degrees(),
                    e.upper.to_degrees(),
                    e.q.to_degrees(),
                    1e-3,
                ),
                JointKind::Prismatic => ("prismatic", e.lower, e.upper, e.q, 1e-6),
            };
            if g.kind != want {
                problems.push(format!("{}: type {}, want {want}", e.usd_path, g.kind));
            }
            // A missing limit compares as NaN: never close to the scene's.
            let glo = g.lower.unwrap_or(f64::NAN);
            let ghi = g.upper.unwrap_or(f64::NAN);
            if g.limit_enabled != Some(true)
                || !close(glo, lo, 1e-6, tol)
                || !close(ghi, hi, 1e-6, tol)
            {
                problems.push(format!(
                    "{}: limits [{glo}, {ghi}], scene [{lo}, {hi}]",
                    e.usd_path
                ));
            }
            if glo.partial_cmp(&ghi).is_none_or(|o| o.is_gt())
                || (e.kind == JointKind::Revolute && (glo < -360.0 || ghi > 360.0))
            {
                problems.push(format!(
                    "{}: limits [{glo}, {ghi}] out of range",
                    e.usd_path
                ));
            }
            let axis = g.axis_world.unwrap_or([0.0; 3]);
            let dot: f64 = (0..3).map(|k| axis[k] * e.axis_world[k]).sum();
            if dot < 1.0 - 1e-5 {
                problems.push(format!(
                    "{}: world axis {axis:?}, scene {:?}",
                    e.usd_path, e.axis_world
                ));
            }
            let pos = g.position_measured.unwrap_or(f64::NAN);
            if !close(pos, q, 0.0, tol.max(1e-4)) || g.off_axis_rad.is_none_or(|a| a > 1e-4) {
                problems.push(format!(
                    "{}: bodies sit at joint position {pos}, scene {q}",
                    e.usd_path
                ));
            }
        }
        if o.articulated && o.hold == Hold::Welded {
            let weld = format!("/World/{}/world_weld", o.name);
            match joints.get(weld.as_str()) {
                Some(g) if g.kind == "fixed" => {}
                _ => problems.push(format!("{weld}: no fixed joint to the world")),
            }
        }
    }
    let n_joints: usize = exp.iter().map(|o| o.joints.len()).sum();
    if movable != n_joints {
        problems.push(format!(
            "{movable} revolute/prismatic joints, scene {n_joints}"
        ));
    }
    rows.add(
        "joints: targets resolve, limits (deg / m), axis sign, initial position",
        format!("{n_joints} joints"),
        format!("{movable} joints match"),
        problems,
    );

    movable
}

/// Articulation roots where the UsdPhysics spec wants them, self-collision filtered.
fn articulation_rows(
    rows: &mut Rows<'_>,
    exp: &[ExpObject],
    r: &UsdCheckReply,
    bodies: &BTreeMap<String, UsdBody>,
) {
    let arts = &r.articulations;
    let mut problems = Vec::new();
    let want_arts = exp.iter().filter(|o| o.articulated).count();
    if arts.len() != want_arts {
        problems.push(format!("{} articulations, scene {want_arts}", arts.len()));
    }
    for o in exp.iter().filter(|o| o.articulated) {
        let root = match o.hold {
            Hold::Free => o
                .links
                .first()
                .map(|l| l.usd_body.clone())
                .unwrap_or_default(),
            _ => format!("/World/{}", o.name),
        };
        if !arts.iter().any(|a| a.path == root) {
            problems.push(format!("no articulation root at {root}"));
        }
        // Every pair of links of the object is filtered.
        for (i, a) in o.links.iter().enumerate() {
            for b in &o.links[i + 1..] {
                let filtered = |x: &ExpLink, y: &ExpLink| {
                    bodies
                        .get(&x.usd_body)
                        .is_some_and(|v| v.filtered.contains(&y.usd_body))
                };
                if !filtered(a, b) && !filtered(b, a) {
                    problems.push(format!("{} / {} may collide", a.usd_body, b.usd_body));
                }
            }
        }
    }
    rows.add(
        "articulation roots, self-collision filtered",
        format!("{want_arts} articulations"),
        format!("{} articulations", arts.len()),
        problems,
    );
}
