//! Scene metrics (`metrics.json`, `scenesmith eval DIR`) and the requirements score
//! (`requirements_report.json`, `scenesmith eval DIR --requirements FILE`, see [`requirements`]).
//!
//! | metric | meaning |
//! |---|---|
//! | counts | objects in total, per kind, per room, per category (architecture excluded) |
//! | COL | percent of objects penetrating another object or a wall/floor by more than 1 mm; mean and max depth of those pairs (parry3d on the convex collision pieces) |
//! | STB | percent of free objects that move < 1 cm and rotate < 0.1 rad in a 5 s simulation at 1 ms (Drake, scene as written: wall/ceiling objects welded, furniture and small objects free; simulated per island of touching objects, see [`stability`]; [`StabilityOptions::stop_at_rest`] for the early stop) |
//! | MD, XD, MR | mean displacement (mm), max displacement (m), mean rotation (rad) of the free objects in that simulation |
//! | NAV | largest connected free floor region / all free floor, for a round robot (radius configurable) |
//! | OOB | percent of objects with geometry outside their room's floor polygon |
//! | plan | plan coverage: the requirements the prompt reader planned (objects, counts, negations) met by the scene; it measures the reader's plan, not the prompt (see [`requirements`] for a score against requirements written independently) |
//!
//! Everything but STB is computed in-process; STB needs the Drake bridge and is `null` without
//! it. `metrics.json` holds no timings or host data, so the same scene gives the same bytes.

pub mod coverage;
pub mod floor;
pub mod requirements;
pub mod stability;

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::Path;

use serde::{Deserialize, Serialize};

use crate::formats::FormatError;
use crate::formats::scene_dir;
use crate::physics::as_written::posed_objects;
use crate::physics::collision::penetrating_pairs;
use crate::physics::settle::{ContactModel, ContactOptions};
use crate::physics::{BridgePool, PhysicsError};
use crate::prompt;
use crate::scene::ObjectKind;
use crate::state::SceneState;
use crate::util::fsx::write_atomic;

pub use coverage::{PlanCoverage, PlannedRequirement};
pub use floor::{Nav, NavRoom, Oob};
pub use stability::{stabilities, stability};

/// Version of the `metrics.json` layout.
pub const METRICS_VERSION: u32 = 1;

/// File name of the metrics in a scene directory.
pub const METRICS_JSON: &str = "metrics.json";

/// What can stop an evaluation.
#[derive(Debug, thiserror::Error)]
pub enum EvalError {
    /// The scene directory could not be read or the metrics not written.
    #[error(transparent)]
    Format(#[from] FormatError),
    /// The simulation failed.
    #[error(transparent)]
    Physics(#[from] PhysicsError),
    /// Collision geometry could not be built.
    #[error(transparent)]
    Geometry(#[from] crate::geometry::GeometryError),
}

/// Options of the stability simulation.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct StabilityOptions {
    /// Simulated seconds.
    pub duration_s: f64,
    /// Time step, seconds.
    pub time_step_s: f64,
    /// Stable: moved less than this, metres ...
    pub max_displacement_m: f64,
    /// ... and turned less than this, radians.
    pub max_rotation_rad: f64,
    /// Contact configuration.
    pub contact: ContactOptions,
    /// End an island's simulation early once every free body has stayed below `rest_speed`
    /// and `rest_angular_speed` for `rest_time`, or once no body's verdict can change: its
    /// last two `rest_time` windows, extrapolated to the end (from the larger window, growing
    /// each window as much as the last one grew), keep it under half of both thresholds (or it
    /// is past one by more than that could bring back). The stable/unstable decision adds to
    /// every object's displacement and rotation what the rest of the duration could still add
    /// (at the rest speeds, or that extrapolation), so the early stop can only make STB
    /// stricter; MD, XD and MR report the motion actually simulated.
    pub stop_at_rest: bool,
    /// Rest speed for the early stop, m/s.
    pub rest_speed: f64,
    /// Rest angular speed for the early stop, rad/s.
    pub rest_angular_speed: f64,
    /// How long everything must rest before the early stop, seconds.
    pub rest_time: f64,
}

impl Default for StabilityOptions {
    fn default() -> Self {
        StabilityOptions {
            duration_s: 5.0,
            time_step_s: 1e-3,
            max_displacement_m: 0.01,
            max_rotation_rad: 0.1,
            contact: ContactOptions::default(),
            stop_at_rest: true,
            rest_speed: 5e-4,
            rest_angular_speed: 5e-3,
            rest_time: 0.5,
        }
    }
}

/// Options of an evaluation.
#[derive(Debug, Clone)]
pub struct EvalOptions {
    /// Penetration that counts as a collision, metres.
    pub col_threshold_m: f64,
    /// Robot radius for NAV, metres.
    pub robot_radius_m: f64,
    /// Geometry up to this height blocks the robot, metres.
    pub robot_height_m: f64,
    /// OOB tolerance, metres.
    pub oob_tolerance_m: f64,
    /// Stability simulation (`None`: skipped); its `contact` is set per protocol.
    pub stability: Option<StabilityOptions>,
    /// The contact models STB is simulated with: Drake's defaults on the files as written
    /// (`Metrics::stb`) and point contact (`Metrics::stb_point`, SceneEval's protocol).
    pub stb_contacts: Vec<ContactModel>,
}

impl Default for EvalOptions {
    fn default() -> Self {
        EvalOptions {
            col_threshold_m: 1e-3,
            robot_radius_m: 0.25,
            robot_height_m: 1.5,
            oob_tolerance_m: 0.01,
            stability: Some(StabilityOptions::default()),
            stb_contacts: vec![ContactModel::AsWritten, ContactModel::Point],
        }
    }
}

/// Object counts.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Counts {
    /// Objects (architecture excluded).
    pub total: usize,
    /// Per kind.
    pub per_kind: BTreeMap<String, usize>,
    /// Per room.
    pub per_room: BTreeMap<String, usize>,
    /// Per category.
    pub per_category: BTreeMap<String, usize>,
}

/// What post-processing removed (projection that could not separate an object, a fall while
/// settling), so that COL and STB are read next to what they no longer count.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct Removed {
    /// Objects the stages placed: those in the scene plus those removed.
    pub placed: usize,
    /// Objects removed.
    pub removed: usize,
    /// `removed` as a percent of `placed`.
    pub percent: f64,
    /// Each removal with its stage and reason (from `scene.json`).
    pub removals: Vec<crate::scene::Removal>,
    /// Categories the prompt asked for whose count the removals left short, with how many
    /// of each were removed ("mug": 1).
    pub lost: BTreeMap<String, usize>,
    /// Asked-for objects post-processing removed and then placed again elsewhere (counted in
    /// `placed`, not in `removed`; `scene.json` says where, and why they were moved).
    #[serde(default)]
    pub placed_again: usize,
}

/// COL.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Col {
    /// Threshold, metres.
    pub threshold_m: f64,
    /// Objects counted (architecture excluded).
    pub objects: usize,
    /// Objects in at least one pair deeper than the threshold.
    pub colliding: Vec<String>,
    /// Percent of objects colliding.
    pub percent: f64,
    /// Mean depth of the pairs deeper than the threshold, mm (0 without any).
    pub mean_depth_mm: f64,
    /// Deepest pair, mm.
    pub max_depth_mm: f64,
    /// The pairs `(a, b, depth_mm)`.
    pub pairs: Vec<(String, String, f64)>,
}

/// An object that failed the stability test (after an early stop, with the remaining-time
/// bound added).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Unstable {
    /// Object id.
    pub id: String,
    /// Displacement, metres.
    pub displacement_m: f64,
    /// Rotation, radians.
    pub rotation_rad: f64,
}

/// STB, MD, XD, MR.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Stability {
    /// The simulation.
    pub options: StabilityOptions,
    /// Free objects simulated.
    pub free_objects: usize,
    /// Of those, stable.
    pub stable: usize,
    /// STB: percent stable.
    pub percent: f64,
    /// MD: mean displacement over the simulated time, mm.
    pub md_mm: f64,
    /// XD: max displacement, m.
    pub xd_m: f64,
    /// MR: mean rotation, rad.
    pub mr_rad: f64,
    /// Everything was at rest at the end.
    pub at_rest_at_end: bool,
    /// Seconds actually simulated (less than the duration after an early stop at rest); the
    /// longest island.
    pub simulated_s: f64,
    /// Islands simulated separately (free objects that touch or rest on each other).
    #[serde(default)]
    pub islands: usize,
    /// Islands the wall-clock cap stopped before the duration; their objects count as
    /// unstable.
    #[serde(default)]
    pub timed_out_islands: usize,
    /// Islands whose simulation went non-finite (Drake's solver diverged); their objects
    /// count as unstable.
    #[serde(default)]
    pub diverged_islands: usize,
    /// The objects that failed.
    pub unstable: Vec<Unstable>,
}

/// All metrics of a scene (`metrics.json`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Metrics {
    /// [`METRICS_VERSION`].
    pub version: u32,
    /// Object counts.
    pub counts: Counts,
    /// Collisions.
    pub col: Col,
    /// Stability under Drake's default plant on the files as written (`null` when not
    /// simulated).
    pub stb: Option<Stability>,
    /// Stability under point contact, SceneEval's protocol, for comparison with published
    /// figures (`null` when not simulated).
    #[serde(default)]
    pub stb_point: Option<Stability>,
    /// Navigability.
    pub nav: Nav,
    /// Out of bounds.
    pub oob: Oob,
    /// Plan coverage: the prompt reader's planned requirements met by the scene (read from
    /// older files under its former name `prompt`).
    #[serde(alias = "prompt")]
    pub plan_coverage: PlanCoverage,
    /// Objects removed by post-processing, and asked-for objects lost that way.
    #[serde(default)]
    pub removed: Removed,
}

/// The removals recorded in the scene, and which of them the prompt asked for: a removed
/// object whose category names a planned requirement that the scene no longer meets.
fn removed(state: &SceneState, coverage: &PlanCoverage) -> Removed {
    let removals = state.scene.removed.clone();
    let present = state
        .scene
        .objects
        .iter()
        .filter(|o| o.kind != ObjectKind::Architecture)
        .count();
    let placed = present + removals.len();
    let mut lost: BTreeMap<String, usize> = BTreeMap::new();
    for r in &removals {
        let short = coverage.requirements.iter().find(|q| {
            q.kind != "none"
                && q.present < q.required
                && crate::assets::router::naming::names(&q.category, &r.category)
        });
        if let Some(q) = short {
            *lost.entry(q.category.clone()).or_default() += 1;
        }
    }
    Removed {
        placed,
        placed_again: state.scene.placed_again.len(),
        removed: removals.len(),
        percent: if placed == 0 {
            0.0
        } else {
            100.0 * removals.len() as f64 / placed as f64
        },
        removals,
        lost,
    }
}

fn counts(state: &SceneState) -> Counts {
    let mut c = Counts {
        total: 0,
        per_kind: BTreeMap::new(),
        per_room: BTreeMap::new(),
        per_category: BTreeMap::new(),
    };
    for o in state
        .scene
        .objects
        .iter()
        .filter(|o| o.kind != ObjectKind::Architecture)
    {
        c.total += 1;
        *c.per_kind.entry(o.kind.as_str().to_string()).or_insert(0) += 1;
        *c.per_room.entry(o.room.clone()).or_insert(0) += 1;
        *c.per_category.entry(o.category.clone()).or_insert(0) += 1;
    }
    c
}

fn col(
    state: &SceneState,
    posed: &[crate::physics::collision::PosedObject],
    threshold: f64,
) -> Col {
    let pairs = penetrating_pairs(posed, threshold);
    let objects: Vec<&str> = state
        .scene
        .objects
        .iter()
        .filter(|o| o.kind != ObjectKind::Architecture)
        .map(|o| o.id.as_str())
        .collect();
    let mut colliding: Vec<String> = pairs
        .iter()
        .flat_map(|p| [p.a.as_str(), p.b.as_str()])
        .filter(|id| objects.contains(id))
        .map(str::to_string)
        .collect();
    colliding.sort();
    colliding.dedup();
    let depths: Vec<f64> = pairs.iter().map(|p| p.depth).collect();
    Col {
        threshold_m: threshold,
        objects: objects.len(),
        percent: if objects.is_empty() {
            0.0
        } else {
            100.0 * colliding.len() as f64 / objects.len() as f64
        },
        colliding,
        mean_depth_mm: if depths.is_empty() {
            0.0
        } else {
            1e3 * depths.iter().sum::<f64>() / depths.len() as f64
        },
        max_depth_mm: 1e3 * depths.iter().copied().fold(0.0, f64::max),
        pairs: pairs
            .into_iter()
            .map(|p| (p.a, p.b, p.depth * 1e3))
            .collect(),
    }
}

/// Metrics of a scene held in memory (STB needs a pool and `opts.stability`).
pub fn evaluate(
    state: &SceneState,
    pool: Option<&BridgePool>,
    opts: &EvalOptions,
) -> Result<Metrics, EvalError> {
    let posed = posed_objects(&state.scene, &state.assets);
    let reading = prompt::read(&state.scene.provenance.prompt);
    let plan_coverage = coverage::plan_coverage(&reading, &state.scene);
    let models: Vec<ContactModel> = [ContactModel::AsWritten, ContactModel::Point]
        .into_iter()
        .filter(|m| opts.stb_contacts.contains(m))
        .collect();
    let mut runs = match (pool, &opts.stability) {
        (Some(pool), Some(s)) if !models.is_empty() => {
            let each: Vec<StabilityOptions> = models
                .iter()
                .map(|&model| StabilityOptions {
                    contact: ContactOptions { model },
                    ..*s
                })
                .collect();
            models
                .iter()
                .copied()
                .zip(stabilities(state, pool, &each)?)
                .collect()
        }
        _ => Vec::new(),
    };
    let mut take = |m: ContactModel| {
        runs.iter()
            .position(|(k, _)| *k == m)
            .map(|i| runs.remove(i).1)
    };
    let stb = take(ContactModel::AsWritten);
    let stb_point = take(ContactModel::Point);
    Ok(Metrics {
        version: METRICS_VERSION,
        counts: counts(state),
        col: col(state, &posed, opts.col_threshold_m),
        stb,
        stb_point,
        nav: floor::nav(
            &state.scene,
            &posed,
            opts.robot_radius_m,
            opts.robot_height_m,
        ),
        oob: floor::oob(&state.scene, &posed, opts.oob_tolerance_m),
        removed: removed(state, &plan_coverage),
        plan_coverage,
    })
}

/// Loads the scene directory `dir` and evaluates it.
pub fn evaluate_dir(
    dir: &Path,
    pool: Option<&BridgePool>,
    opts: &EvalOptions,
) -> Result<Metrics, EvalError> {
    let state = scene_dir::load_state(dir)?;
    evaluate(&state, pool, opts)
}

/// Writes `metrics.json` into `dir` atomically.
pub fn write_metrics(dir: &Path, metrics: &Metrics) -> Result<(), EvalError> {
    let mut text = serde_json::to_string_pretty(metrics).map_err(|e| FormatError::SceneJson {
        path: dir.join(METRICS_JSON),
        reason: e.to_string(),
    })?;
    text.push('\n');
    write_atomic(&dir.join(METRICS_JSON), text.as_bytes()).map_err(FormatError::from)?;
    Ok(())
}

fn join_counts(m: &BTreeMap<String, usize>) -> String {
    m.iter()
        .map(|(k, v)| format!("{v} {k}"))
        .collect::<Vec<_>>()
        .join(", ")
}

/// The STB row of the table: percent, protocol, thresholds, islands and how they ended.
fn stb_row(s: &Stability) -> String {
    let ending = if s.timed_out_islands + s.diverged_islands > 0 {
        format!(
            "; {} islands stopped by the wall-clock cap and {} diverged (non-finite), their objects counted unstable",
            s.timed_out_islands, s.diverged_islands
        )
    } else if s.simulated_s + 1e-9 < s.options.duration_s {
        format!(
            "; every island stopped by {:.2} s, at rest or with no verdict left to change, the rest of the duration added at each object's pace",
            s.simulated_s
        )
    } else {
        String::new()
    };
    format!(
        "{:.1} % of {} free objects stable over {:.1} s, {} (< {:.0} mm, < {:.2} rad; {} islands){ending}",
        s.percent,
        s.free_objects,
        s.options.duration_s,
        s.options.contact.model.label(),
        s.options.max_displacement_m * 1e3,
        s.options.max_rotation_rad,
        s.islands,
    )
}

/// The metrics as a two-column text table.
pub fn table(m: &Metrics) -> String {
    let mut rows: Vec<(String, String)> = vec![
        (
            "objects".into(),
            format!("{} ({})", m.counts.total, join_counts(&m.counts.per_kind)),
        ),
        ("per room".into(), join_counts(&m.counts.per_room)),
        ("per category".into(), join_counts(&m.counts.per_category)),
        (
            "COL".into(),
            format!(
                "{:.2} % of {} objects penetrate > {:.1} mm; mean depth {:.2} mm, max {:.2} mm",
                m.col.percent,
                m.col.objects,
                m.col.threshold_m * 1e3,
                m.col.mean_depth_mm,
                m.col.max_depth_mm
            ),
        ),
    ];
    let simulated = [("STB", &m.stb), ("STB point", &m.stb_point)];
    for (name, stb) in simulated.iter().filter(|(_, s)| s.is_some()) {
        let Some(s) = stb else { continue };
        let suffix = if *name == "STB" { "" } else { " point" };
        rows.push((name.to_string(), stb_row(s)));
        rows.push((format!("MD{suffix}"), format!("{:.2} mm", s.md_mm)));
        rows.push((format!("XD{suffix}"), format!("{:.4} m", s.xd_m)));
        rows.push((format!("MR{suffix}"), format!("{:.4} rad", s.mr_rad)));
    }
    if simulated.iter().all(|(_, s)| s.is_none()) {
        rows.push(("STB".into(), "not simulated (no Drake bridge)".into()));
    }
    rows.push((
        "removed".into(),
        format!(
            "{} of {} placed objects ({:.1} %) removed by post-processing{}{}",
            m.removed.removed,
            m.removed.placed,
            m.removed.percent,
            if m.removed.placed_again == 0 {
                String::new()
            } else {
                format!(
                    "; {} asked-for objects it removed placed again elsewhere",
                    m.removed.placed_again
                )
            },
            if m.removed.lost.is_empty() {
                String::new()
            } else {
                let lost: Vec<String> = m
                    .removed
                    .lost
                    .iter()
                    .map(|(c, n)| format!("{c} {n}"))
                    .collect();
                format!("; asked for and lost: {}", lost.join(", "))
            }
        ),
    ));
    rows.push((
        "NAV".into(),
        format!(
            "{:.3} (robot radius {:.2} m; {})",
            m.nav.ratio,
            m.nav.robot_radius_m,
            m.nav
                .rooms
                .iter()
                .map(|r| format!("{} {:.3} of {:.1} m2", r.room, r.ratio, r.free_area_m2))
                .collect::<Vec<_>>()
                .join(", ")
        ),
    ));
    rows.push((
        "OOB".into(),
        format!("{:.2} % of {} objects", m.oob.percent, m.oob.objects),
    ));
    rows.push((
        "plan".into(),
        format!(
            "{:.0} % of the reader's {} planned requirements met, {:.0} % of the planned objects present",
            m.plan_coverage.percent,
            m.plan_coverage.requirements.len(),
            m.plan_coverage.count_percent
        ),
    ));
    let w = rows.iter().map(|(k, _)| k.len()).max().unwrap_or(0);
    let mut out = String::new();
    for (k, v) in rows {
        let _ = writeln!(out, "  {k:<w$}  {v}");
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The plan coverage was called `prompt` until it was renamed to say what it measures;
    /// `metrics.json` files written before still load.
    #[test]
    fn metrics_written_under_the_old_name_still_load() {
        let scene = crate::scene::Scene::new("A room with a table and no chair.", 0, "t");
        let state = SceneState::new(scene);
        let opts = EvalOptions {
            stability: None,
            ..EvalOptions::default()
        };
        let m = evaluate(&state, None, &opts).expect("an empty scene evaluates");
        assert!(!m.plan_coverage.requirements.is_empty());
        let mut v = serde_json::to_value(&m).expect("metrics serialise");
        let fields = v.as_object_mut().expect("an object");
        let coverage = fields
            .remove("plan_coverage")
            .expect("the new name is written");
        fields.insert("prompt".into(), coverage);
        let old: Metrics = serde_json::from_value(v).expect("the old name loads");
        assert_eq!(old, m);
        assert!(table(&m).contains("of the reader's"), "{}", table(&m));
    }

    #[test]
    fn removals_are_counted_and_asked_for_ones_named_lost() {
        let mut scene = crate::scene::Scene::new("A room with a table and two mugs.", 0, "t");
        for (object, category) in [("mug_0", "mug"), ("book_0", "book")] {
            scene.removed.push(crate::scene::Removal {
                object: object.into(),
                category: category.into(),
                stage: "manipuland".into(),
                reason: "fell 0.5 m while settling".into(),
            });
        }
        let state = SceneState::new(scene);
        let opts = EvalOptions {
            stability: None,
            ..EvalOptions::default()
        };
        let m = evaluate(&state, None, &opts).expect("evaluates");
        assert_eq!((m.removed.placed, m.removed.removed), (2, 2));
        assert_eq!(m.removed.percent, 100.0);
        // Two mugs were asked for and none is left; nobody asked for the book.
        assert_eq!(m.removed.lost, BTreeMap::from([("mug".to_string(), 1)]));
        assert!(
            table(&m).contains("asked for and lost: mug 1"),
            "{}",
            table(&m)
        );
    }
}
