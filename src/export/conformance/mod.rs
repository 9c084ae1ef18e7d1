//! The conformance gate behind `scenesmith export DIR --check`: loads what the exporters wrote in
//! the real consumers (MuJoCo, usd-core and Drake through the bridge's `mujoco_check`,
//! `usd_check` and `load` ops; the GLB with this crate's glTF reader) and compares each with the
//! scene: object and body counts, masses, collider counts, joints (type, limits, world axis,
//! initial position), where collision and visual geometry sit, USD stage metadata and validator
//! findings, and a MuJoCo run of a few seconds (finite state, nothing falling out of the world,
//! how many free objects stay put).
//!
//! The gate reports; it changes no file. A failed row is an export that a user of that tool
//! would find broken.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::time::Instant;

use serde::Serialize;

mod drake;
mod glb;
mod mujoco;
mod usd;

use super::view::{AssetView, Hold, ObjectView, SceneView};
use super::{ExportError, ExportFormat, ExportSet, mjcf};
use crate::assets::JointKind;
use crate::geometry::mesh::bounds_of;
use crate::physics::protocol::{Aabb, Op, UsdFinding};
use crate::physics::{Bridge, BridgeError};
use crate::state::SceneState;

/// STB: a free object is stable when it moves less than this in the run, metres.
pub const STB_MAX_DISPLACEMENT_M: f64 = 0.01;
/// STB: ... and rotates less than this, radians.
pub const STB_MAX_ROTATION_RAD: f64 = 0.1;
/// Collision and visual bounds must match the scene's within this, metres (OBJ files hold
/// micrometres; MuJoCo and USD store single-precision vertices).
pub const ALIGN_TOL_M: f64 = 2e-5;

/// What can stop the gate (failures of a check are rows, not errors).
#[derive(Debug, thiserror::Error)]
pub enum ConformanceError {
    /// The bridge could not run at all.
    #[error(transparent)]
    Bridge(#[from] BridgeError),
    /// The scene could not be viewed for export.
    #[error(transparent)]
    Export(#[from] ExportError),
}

/// Options of the gate.
#[derive(Debug, Clone)]
pub struct GateOptions {
    /// Simulated time in MuJoCo, seconds.
    pub seconds: f64,
    /// Formats to check (Drake is always checked when the directives exist).
    pub formats: ExportSet,
}

impl Default for GateOptions {
    fn default() -> Self {
        GateOptions {
            seconds: 5.0,
            formats: ExportSet::all(),
        }
    }
}

/// One line of the gate's table.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct CheckRow {
    /// `drake`, `mujoco`, `usd` or `glb`.
    pub format: String,
    /// What was checked.
    pub check: String,
    /// What the scene says.
    pub expected: String,
    /// What the consumer reported (the first problems when it failed).
    pub got: String,
    /// Whether it matched.
    pub pass: bool,
}

/// How still the free objects stayed in the MuJoCo run.
#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct Stability {
    /// Simulated seconds.
    pub seconds: f64,
    /// Free objects.
    pub free_objects: usize,
    /// Free objects that moved less than 1 cm and turned less than 0.1 rad.
    pub stable: usize,
    /// `stable / free_objects` in percent (100 when there are none).
    pub percent: f64,
    /// The state stayed finite.
    pub finite: bool,
    /// Largest displacement of a free object, metres.
    pub max_displacement_m: f64,
    /// Largest rotation of a free object, radians.
    pub max_rotation_rad: f64,
    /// The objects that were not stable: `(id, displacement m, rotation rad)`.
    pub moved: Vec<(String, f64, f64)>,
}

/// Everything the gate found.
#[derive(Debug, Clone, Serialize)]
pub struct ConformanceReport {
    /// Scene directory.
    pub dir: PathBuf,
    /// The checks, in table order.
    pub rows: Vec<CheckRow>,
    /// The MuJoCo run, when MJCF was checked and loaded.
    pub mujoco_stability: Option<Stability>,
    /// Objects, bodies, joints and total mass of the scene (what every format must match).
    pub scene: SceneFacts,
    /// Per-format facts for cross-format comparisons (object count, total mass, joint count).
    pub facts: BTreeMap<String, SceneFacts>,
    /// USD validator findings (warnings included).
    pub usd_findings: Vec<UsdFinding>,
    /// Wall time per format, seconds.
    pub seconds: BTreeMap<String, f64>,
    /// True when every row passed.
    pub passed: bool,
}

/// Counts and mass as one consumer sees a scene.
#[derive(Debug, Clone, Serialize, PartialEq, Default)]
pub struct SceneFacts {
    /// Objects (model instances in Drake, top-level prims in USD, object bodies in MuJoCo).
    pub objects: usize,
    /// Mass of everything that is not static architecture, kg.
    pub mass_kg: f64,
    /// Revolute and prismatic joints.
    pub joints: usize,
    /// Convex collision pieces (colliders).
    pub colliders: usize,
}

#[derive(Debug)]
struct ExpLink {
    mjcf_body: String,
    usd_body: String,
    pieces: usize,
    mass: f64,
    collision: Option<Aabb>,
    visual: Option<Aabb>,
}

#[derive(Debug)]
struct ExpJoint {
    drake_name: String,
    mjcf_name: String,
    usd_path: String,
    kind: JointKind,
    lower: f64,
    upper: f64,
    axis_world: [f64; 3],
    q: f64,
}

#[derive(Debug)]
struct ExpObject {
    id: String,
    name: String,
    hold: Hold,
    mass: f64,
    articulated: bool,
    links: Vec<ExpLink>,
    joints: Vec<ExpJoint>,
}

fn union(a: Option<Aabb>, pts: &[[f64; 3]]) -> Option<Aabb> {
    let (lo, hi) = bounds_of(pts)?;
    Some(match a {
        None => [lo, hi],
        Some([l, h]) => [
            [l[0].min(lo[0]), l[1].min(lo[1]), l[2].min(lo[2])],
            [h[0].max(hi[0]), h[1].max(hi[1]), h[2].max(hi[2])],
        ],
    })
}

fn expect_object(view: &SceneView<'_>, o: &ObjectView<'_>) -> ExpObject {
    let av: &AssetView<'_> = view.asset_of(o);
    let asset = av.asset;
    let mut links = Vec::new();
    for (li, link) in asset.links.iter().enumerate() {
        let w = &o.world_from_links[li];
        let mut collision = None;
        for piece in &link.collisions {
            collision = union(collision, &piece.transformed(w).vertices);
        }
        let mut visual = None;
        for g in &av.visuals[li] {
            visual = union(visual, &g.mesh.transformed(w).positions);
        }
        links.push(ExpLink {
            mjcf_body: mjcf::body_name(o, av, li),
            usd_body: crate::export::usd::body_path(o, av, li),
            pieces: link.collisions.len(),
            mass: link.mass.mass,
            collision,
            visual,
        });
    }
    let mut joints = Vec::new();
    for (ji, j) in asset.joints.iter().enumerate() {
        let Some(c) = asset.links.iter().position(|l| l.name == j.child) else {
            continue;
        };
        if av.parent_joint[c] != Some(ji) {
            continue;
        }
        let axis = o.world_from_links[c]
            .transform_vector(&nalgebra::Vector3::from(j.axis))
            .normalize();
        joints.push(ExpJoint {
            drake_name: j.name.clone(),
            mjcf_name: format!("{}/{}", o.name, av.joint_names[ji]),
            usd_path: format!("/World/{}/Joints/{}", o.name, av.joint_names[ji]),
            kind: j.kind,
            lower: j.lower,
            upper: j.upper,
            axis_world: [axis.x, axis.y, axis.z],
            q: super::view::joint_position(o.object, asset, ji),
        });
    }
    ExpObject {
        id: o.object.id.clone(),
        name: o.name.clone(),
        hold: o.hold,
        mass: if o.hold == Hold::Static {
            0.0
        } else {
            asset.mass()
        },
        articulated: av.is_articulated() && o.hold != Hold::Static,
        links,
        joints,
    }
}

fn scene_facts(exp: &[ExpObject]) -> SceneFacts {
    SceneFacts {
        objects: exp.len(),
        mass_kg: exp.iter().map(|o| o.mass).sum(),
        joints: exp.iter().map(|o| o.joints.len()).sum(),
        colliders: exp.iter().flat_map(|o| &o.links).map(|l| l.pieces).sum(),
    }
}

fn aabb_gap(a: &Aabb, b: &Aabb) -> f64 {
    let mut gap: f64 = 0.0;
    for c in 0..2 {
        for k in 0..3 {
            gap = gap.max((a[c][k] - b[c][k]).abs());
        }
    }
    gap
}

fn close(a: f64, b: f64, rel: f64, abs: f64) -> bool {
    (a - b).abs() <= abs + rel * a.abs().max(b.abs())
}

/// Collects the rows of one format.
struct Rows<'a> {
    format: &'static str,
    rows: &'a mut Vec<CheckRow>,
}

impl Rows<'_> {
    fn add(&mut self, check: &str, expected: String, ok_text: String, problems: Vec<String>) {
        let pass = problems.is_empty();
        let got = if pass {
            ok_text
        } else {
            let mut shown: Vec<String> = problems.iter().take(3).cloned().collect();
            if problems.len() > 3 {
                shown.push(format!("... {} more", problems.len() - 3));
            }
            format!("{} problem(s): {}", problems.len(), shown.join("; "))
        };
        self.rows.push(CheckRow {
            format: self.format.to_string(),
            check: check.to_string(),
            expected,
            got,
            pass,
        });
    }

    fn fail(&mut self, check: &str, expected: &str, why: String) {
        self.add(check, expected.to_string(), String::new(), vec![why]);
    }
}

fn alignment(
    rows: &mut Rows<'_>,
    exp: &[ExpObject],
    lookup: impl Fn(&ExpLink) -> (Option<Aabb>, Option<Aabb>),
) {
    let mut problems = Vec::new();
    let mut worst: f64 = 0.0;
    let mut compared = 0;
    for o in exp {
        for l in &o.links {
            let (coll, vis) = lookup(l);
            for (what, want, got) in [("collision", l.collision, coll), ("visual", l.visual, vis)] {
                match (want, got) {
                    (Some(w), Some(g)) => {
                        let gap = aabb_gap(&w, &g);
                        worst = worst.max(gap);
                        compared += 1;
                        if gap > ALIGN_TOL_M {
                            problems.push(format!(
                                "{} {what} off by {:.2} mm",
                                l.mjcf_body,
                                gap * 1e3
                            ));
                        }
                    }
                    (Some(_), None) => {
                        problems.push(format!("{} has no {what} geometry", l.mjcf_body))
                    }
                    (None, Some(_)) => {
                        problems.push(format!("{} has unexpected {what} geometry", l.mjcf_body))
                    }
                    (None, None) => {}
                }
            }
        }
    }
    rows.add(
        "collision/visual placement",
        format!("bounds within {:.3} mm of the scene", ALIGN_TOL_M * 1e3),
        format!("{compared} bounds, max offset {:.4} mm", worst * 1e3),
        problems,
    );
}

/// Runs the gate on a scene directory whose exports are already written.
pub fn run_gate(
    bridge: &mut Bridge,
    dir: &Path,
    state: &SceneState,
    opts: &GateOptions,
) -> Result<ConformanceReport, ConformanceError> {
    let view = SceneView::new(state)?;
    let exp: Vec<ExpObject> = view
        .objects
        .iter()
        .map(|o| expect_object(&view, o))
        .collect();
    let scene = scene_facts(&exp);
    let mut rows = Vec::new();
    let mut facts = BTreeMap::new();
    let mut seconds = BTreeMap::new();
    let mut stability = None;
    let mut usd_findings = Vec::new();

    let t = Instant::now();
    if let Some(f) = drake::check_drake(bridge, dir, &exp, &mut rows)? {
        facts.insert("drake".to_string(), f);
    }
    seconds.insert("drake".into(), t.elapsed().as_secs_f64());

    if opts.formats.contains(ExportFormat::Mjcf) {
        let t = Instant::now();
        let floor_z = view.bounds().map(|(lo, _)| lo[2]).unwrap_or(0.0);
        if let Some((f, s)) =
            mujoco::check_mujoco(bridge, dir, &exp, opts.seconds, floor_z, &mut rows)?
        {
            facts.insert("mujoco".to_string(), f);
            stability = Some(s);
        }
        seconds.insert("mujoco".into(), t.elapsed().as_secs_f64());
    }
    if opts.formats.contains(ExportFormat::Usd) {
        let t = Instant::now();
        if let Some((f, findings)) = usd::check_usd(bridge, dir, &exp, &mut rows)? {
            facts.insert("usd".to_string(), f);
            usd_findings = findings;
        }
        seconds.insert("usd".into(), t.elapsed().as_secs_f64());
    }
    if opts.formats.contains(ExportFormat::Glb) {
        let t = Instant::now();
        glb::check_glb(dir, &view, &exp, &mut rows);
        seconds.insert("glb".into(), t.elapsed().as_secs_f64());
    }
    cross_format(&scene, &facts, &mut rows);
    let passed = rows.iter().all(|r| r.pass);
    Ok(ConformanceReport {
        dir: dir.to_path_buf(),
        rows,
        mujoco_stability: stability,
        scene,
        facts,
        usd_findings,
        seconds,
        passed,
    })
}

/// The reply to operation `O`, or `None` after recording the consumer's refusal as a failed
/// row.
fn call_or_row<O: Op>(
    bridge: &mut Bridge,
    args: &O::Args,
    rows: &mut Rows<'_>,
    check: &str,
) -> Result<Option<O::Reply>, ConformanceError> {
    match bridge.call::<O>(args) {
        Ok(v) => Ok(Some(v)),
        Err(BridgeError::Remote { message, .. }) => {
            rows.fail(check, "loads", message);
            Ok(None)
        }
        Err(e) => Err(e.into()),
    }
}

fn cross_format(scene: &SceneFacts, facts: &BTreeMap<String, SceneFacts>, all: &mut Vec<CheckRow>) {
    let mut rows = Rows {
        format: "all",
        rows: all,
    };
    let mut problems = Vec::new();
    let mut got = Vec::new();
    for (fmt, f) in facts {
        got.push(format!(
            "{fmt} {}/{:.3} kg/{}",
            f.objects, f.mass_kg, f.joints
        ));
        if f.objects != scene.objects
            || f.joints != scene.joints
            || !close(f.mass_kg, scene.mass_kg, 1e-6, 1e-9)
        {
            problems.push(format!(
                "{fmt}: {} objects, {:.6} kg, {} joints",
                f.objects, f.mass_kg, f.joints
            ));
        }
    }
    rows.add(
        "objects / mass / joints equal across formats",
        format!("{}/{:.3} kg/{}", scene.objects, scene.mass_kg, scene.joints),
        got.join(", "),
        problems,
    );
}

/// The report as a plain-text table.
pub fn table(report: &ConformanceReport) -> String {
    let header = ["format", "check", "expected", "got", "result"];
    let cells: Vec<[String; 5]> = report
        .rows
        .iter()
        .map(|r| {
            [
                r.format.clone(),
                r.check.clone(),
                r.expected.clone(),
                r.got.clone(),
                if r.pass { "ok".into() } else { "FAIL".into() },
            ]
        })
        .collect();
    let mut width = header.map(str::len);
    for c in &cells {
        for k in 0..5 {
            width[k] = width[k].max(c[k].chars().count());
        }
    }
    let line = |c: &[String; 5]| -> String {
        let mut s = String::new();
        for k in 0..5 {
            let pad = width[k].saturating_sub(c[k].chars().count());
            s.push_str(&c[k]);
            if k < 4 {
                s.push_str(&" ".repeat(pad + 2));
            }
        }
        s.trim_end().to_string()
    };
    let mut out = line(&header.map(str::to_string));
    out.push('\n');
    out.push_str(&line(&width.map(|w| "-".repeat(w))));
    out.push('\n');
    for c in &cells {
        out.push_str(&line(c));
        out.push('\n');
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn table_aligns_columns_and_marks_failures() {
        let report = ConformanceReport {
            dir: PathBuf::from("/x"),
            rows: vec![
                CheckRow {
                    format: "mujoco".into(),
                    check: "masses".into(),
                    expected: "1 kg".into(),
                    got: "1 kg".into(),
                    pass: true,
                },
                CheckRow {
                    format: "usd".into(),
                    check: "joints".into(),
                    expected: "2 joints".into(),
                    got: "1 problem(s): tür".into(),
                    pass: false,
                },
            ],
            mujoco_stability: None,
            scene: SceneFacts::default(),
            facts: BTreeMap::new(),
            usd_findings: vec![],
            seconds: BTreeMap::new(),
            passed: false,
        };
        let t = table(&report);
        let lines: Vec<&str> = t.lines().collect();
        assert_eq!(lines.len(), 4);
        assert!(lines[2].ends_with("ok") && lines[3].ends_with("FAIL"));
        // Columns start at the same character offset on every line (unicode counted as chars).
        let col = |l: &str, w: &str| l.chars().collect::<String>().find(w).unwrap();
        assert_eq!(col(lines[2], "1 kg"), col(lines[3], "2 joints"));
    }

    #[test]
    fn aabb_helpers() {
        let a = union(None, &[[0.0, 0.0, 0.0], [1.0, 2.0, 3.0]]).unwrap();
        let b = union(Some(a), &[[-1.0, 0.5, 0.5]]).unwrap();
        assert_eq!(b, [[-1.0, 0.0, 0.0], [1.0, 2.0, 3.0]]);
        assert_eq!(aabb_gap(&a, &b), 1.0);
        assert!(close(1.0, 1.0 + 1e-10, 1e-9, 0.0) && !close(1.0, 1.1, 1e-9, 0.0));
    }
}
