//! Simulation and projection: `settle`, `simulate` (`drake_bridge/settle.py`) and `project`
//! (`drake_bridge/projection.py`).

use std::collections::BTreeMap;

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use super::{CacheStats, Poses, SceneFiles, op};
use crate::physics::settle::ContactModel;

op!(
    /// Simulates until every free body is at rest (or `max_time`); final poses and motions.
    Settle, "settle", SettleArgs, SettleReply
);
op!(
    /// Simulates a fixed `duration` (the STB metric); final poses and motions.
    Simulate, "simulate", SimulateArgs, SettleReply
);
op!(
    /// Moves free bodies to the nearest non-penetrating translations (SNOPT, IPOPT, push-out).
    Project, "project", ProjectArgs, ProjectReply
);

/// Drake's discrete contact approximations (`MultibodyPlantConfig::discrete_contact_approximation`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum DiscreteApproximation {
    /// SAP with lagged friction.
    Lagged,
    /// SAP's "similar" model.
    Similar,
    /// SAP.
    Sap,
    /// TAMSI.
    Tamsi,
}

/// The contact configuration of a simulation.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct ContactArgs {
    /// Contact model.
    pub model: ContactModel,
    /// Discrete contact approximation; `None`: Drake's default.
    #[serde(default)]
    pub approximation: Option<DiscreteApproximation>,
}

fn default_time_step() -> f64 {
    1e-3
}
fn default_rest_speed() -> f64 {
    2e-3
}
fn default_rest_angular_speed() -> f64 {
    2e-2
}
fn default_rest_time() -> f64 {
    0.25
}
fn default_check_interval() -> f64 {
    0.01
}
fn default_wall_limit() -> f64 {
    600.0
}
fn default_contact() -> ContactArgs {
    ContactArgs {
        model: ContactModel::AsWritten,
        approximation: None,
    }
}
fn default_max_time() -> f64 {
    3.0
}
fn default_duration() -> f64 {
    5.0
}
fn yes() -> bool {
    true
}

/// What `settle` and `simulate` share.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct SimulationArgs {
    /// The scene.
    #[serde(flatten)]
    pub scene: SceneFiles,
    /// Free-body poses to start from instead of the defaults.
    #[serde(default)]
    pub poses: Option<Poses>,
    /// Discrete time step, seconds (1e-4 to 1e-2).
    #[serde(default = "default_time_step")]
    pub time_step: f64,
    /// A body is at rest below this speed, m/s.
    #[serde(default = "default_rest_speed")]
    pub rest_speed: f64,
    /// ... and below this angular speed, rad/s.
    #[serde(default = "default_rest_angular_speed")]
    pub rest_angular_speed: f64,
    /// Everything must stay at rest this long, seconds.
    #[serde(default = "default_rest_time")]
    pub rest_time: f64,
    /// Simulated time between rest checks, seconds.
    #[serde(default = "default_check_interval")]
    pub check_interval: f64,
    /// Wall-clock cap of the request, seconds.
    #[serde(default = "default_wall_limit")]
    pub wall_limit: f64,
    /// Contact configuration.
    #[serde(default = "default_contact")]
    pub contact: ContactArgs,
    /// Floor height; bodies more than 0.5 m below it are ignored by the rest test. `None`: no
    /// floor test.
    #[serde(default)]
    pub floor_z: Option<f64>,
    /// The verdict thresholds of a stability run: with `stop_at_rest`, the simulation also
    /// stops once the rest of the duration cannot change any body's verdict (`bounded`).
    #[serde(default)]
    pub verdict: Option<VerdictBound>,
}

/// A stability verdict's thresholds: stable below both.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct VerdictBound {
    /// Displacement, metres.
    pub max_displacement_m: f64,
    /// Rotation, radians.
    pub max_rotation_rad: f64,
}

/// Arguments of `settle`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct SettleArgs {
    /// Scene and simulation settings.
    #[serde(flatten)]
    pub sim: SimulationArgs,
    /// Simulated-time cap, seconds.
    #[serde(default = "default_max_time")]
    pub max_time: f64,
    /// Stop once everything is at rest.
    #[serde(default = "yes")]
    pub stop_at_rest: bool,
}

/// Arguments of `simulate`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct SimulateArgs {
    /// Scene and simulation settings.
    #[serde(flatten)]
    pub sim: SimulationArgs,
    /// Simulated time, seconds.
    #[serde(default = "default_duration")]
    pub duration: f64,
    /// Stop once everything is at rest (the remaining time is then accounted by the caller).
    #[serde(default)]
    pub stop_at_rest: bool,
}

/// How far one model instance moved during a simulation.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct Motion {
    /// Largest displacement of any of its free bodies, metres.
    pub displacement_m: f64,
    /// Largest rotation of any of its free bodies, radians.
    pub rotation_rad: f64,
    /// Height of the (first) free body at the start, metres.
    pub start_z: f64,
    /// ... and at the end.
    pub end_z: f64,
    /// After a `bounded` stop: what the rest of the duration could still add to its
    /// displacement (its last two rest windows extrapolated, growing as they grew), per second
    /// of the time left, m/s; else 0.
    #[serde(default)]
    pub speed_bound: f64,
    /// ... and turned, rad/s.
    #[serde(default)]
    pub angular_speed_bound: f64,
}

/// The bridge's reply to `settle` / `simulate`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct SettleReply {
    /// Final free-body poses: instance -> body -> `world_from_body`.
    pub poses: Poses,
    /// Motion per instance.
    pub motion: BTreeMap<String, Motion>,
    /// Simulated time, seconds.
    pub sim_time: f64,
    /// Steps taken.
    pub steps: u64,
    /// Every free body was at rest at the end.
    pub at_rest: bool,
    /// Stopped by the wall-clock cap.
    pub timed_out: bool,
    /// Largest body speed at the last check, m/s.
    pub max_speed: f64,
    /// Largest body angular speed at the last check, rad/s.
    pub max_angular_speed: f64,
    /// Deepest overlap at the end between different instances, metres.
    pub max_penetration_m: f64,
    /// Free bodies simulated.
    pub free_bodies: usize,
    /// The contact configuration used.
    pub contact: ContactArgs,
    /// Time step used, seconds.
    pub time_step: f64,
    /// Time spent building the plant (0 on a cache hit), seconds.
    pub build_s: f64,
    /// Time spent simulating, seconds.
    pub sim_s: f64,
    /// Wall time of the request in the bridge, seconds.
    pub wall_s: f64,
    /// Mean wall time per step, milliseconds.
    pub ms_per_step: f64,
    /// The simulation plant cache after this request.
    pub cache: CacheStats,
    /// A body's state went non-finite (Drake's solver diverged): the simulation stopped, and
    /// the poses and motion are those at the start of the last rest window.
    #[serde(default)]
    pub diverged: bool,
    /// Stopped before the duration because no body's verdict could change any more (see
    /// `SimulationArgs::verdict`); each motion then carries its speed bounds.
    #[serde(default)]
    pub bounded: bool,
}

/// The projection's solver choice.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum ProjectSolver {
    /// SNOPT, then IPOPT, then the push-out.
    #[default]
    Auto,
    /// SNOPT, then the push-out.
    Snopt,
    /// IPOPT, then the push-out.
    Ipopt,
    /// Only the push-out along penetration normals.
    PushOut,
}

fn default_min_distance() -> f64 {
    1e-5
}
fn default_tolerance() -> f64 {
    1e-4
}
fn default_candidate_distance() -> f64 {
    0.05
}
fn default_time_limit() -> f64 {
    60.0
}
fn floor_at_zero() -> Option<f64> {
    Some(0.0)
}

/// Arguments of `project`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct ProjectArgs {
    /// The scene.
    #[serde(flatten)]
    pub scene: SceneFiles,
    /// Free-body poses to start from instead of the defaults.
    #[serde(default)]
    pub poses: Option<Poses>,
    /// Which solvers to try.
    #[serde(default)]
    pub solver: ProjectSolver,
    /// Lower bound on every candidate pair's signed distance, metres.
    #[serde(default = "default_min_distance")]
    pub min_distance: f64,
    /// Largest penetration accepted, metres.
    #[serde(default = "default_tolerance")]
    pub tolerance: f64,
    /// Pairs closer than this at the start get a constraint, metres.
    #[serde(default = "default_candidate_distance")]
    pub candidate_distance: f64,
    /// Wall-clock limit for the solvers, seconds.
    #[serde(default = "default_time_limit")]
    pub time_limit: f64,
    /// Slide in XY only (z only rises to the floor).
    #[serde(default)]
    pub xy_only: bool,
    /// Floor top, metres; `None` turns the floor bound off.
    #[serde(default = "floor_at_zero")]
    pub floor_z: Option<f64>,
    /// Instances allowed to move; `None`: every free one (only colliding ones above 100).
    #[serde(default)]
    pub movable: Option<Vec<String>>,
    /// Per instance, half-planes `[a, b, c]` (`a x + b y <= c`) its origin must stay in.
    #[serde(default)]
    pub regions: BTreeMap<String, Vec<[f64; 3]>>,
}

/// One solver run of a projection.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct SolverAttempt {
    /// `snopt` or `ipopt`.
    pub solver: String,
    /// The solver's status, or `unavailable`.
    pub status: String,
    /// The solver reported success (`None` when it did not run).
    pub success: Option<bool>,
    /// Distance constraints in the program.
    pub pairs: Option<usize>,
    /// Wall time of the run, seconds.
    pub seconds: Option<f64>,
    /// Deepest penetration at its solution, metres (`None` without a finite solution).
    pub max_penetration_m: Option<f64>,
}

/// The bridge's reply to `project`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct ProjectReply {
    /// Free-body poses after projection: instance -> body -> `world_from_body`.
    pub poses: Poses,
    /// The instances that were allowed to move.
    pub movable: Vec<String>,
    /// Which method produced the poses: `none`, `snopt`, `ipopt` or `push_out`.
    pub solver: String,
    /// Deepest penetration before, metres.
    pub initial_max_penetration_m: f64,
    /// Deepest penetration after, metres.
    pub max_penetration_m: f64,
    /// Mean displacement of the movable bodies, metres.
    pub mean_displacement_m: f64,
    /// Largest displacement, metres.
    pub max_displacement_m: f64,
    /// Distance constraints in the last program.
    pub pairs: usize,
    /// Solver runs with their statuses.
    pub attempts: Vec<SolverAttempt>,
    /// Iterations of the push-out, when it ran.
    pub push_out_iterations: Option<usize>,
    /// Wall time in the bridge, seconds.
    pub wall_s: f64,
}
