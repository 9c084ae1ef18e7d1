//! Operations on a loaded scene: `ping`, `versions`, `load`, `penetrations`,
//! `collision_report`, `drop_spheres` (`drake_bridge/ops.py`, `layout_checks.py`).

use std::collections::BTreeMap;

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use super::{CacheStats, NoArgs, Poses, SceneFiles, op};
use crate::scene::Pose;

op!(
    /// Liveness and versions of the running bridge.
    Ping, "ping", NoArgs, PingReply
);
op!(
    /// Versions of Python, Drake and the Python packages, and which solvers Drake has.
    Versions, "versions", NoArgs, VersionsReply
);
op!(
    /// Parses a directives file into a plant (cached by content) and describes it.
    Load, "load", SceneFiles, LoadReply
);
op!(
    /// Model-instance pairs penetrating deeper than a threshold.
    Penetrations, "penetrations", PenetrationsArgs, PenetrationsReply
);
op!(
    /// COL: the share of objects penetrating another deeper than a threshold.
    CollisionReport, "collision_report", CollisionReportArgs, CollisionReportReply
);
op!(
    /// Drops spheres into a scene and reports where they came to rest.
    DropSpheres, "drop_spheres", DropSpheresArgs, DropSpheresReply
);

/// Reply to `ping`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct PingReply {
    /// Always true.
    pub pong: bool,
    /// Protocol version the bridge speaks.
    pub protocol: u64,
    /// Bridge package version.
    pub bridge: String,
    /// Drake version.
    pub drake: String,
}

/// Whether Drake has a solver and may use it.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct SolverStatus {
    /// Compiled in.
    pub available: bool,
    /// Licensed / enabled.
    pub enabled: bool,
}

/// Reply to `versions`; a package that is not installed is `None`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct VersionsReply {
    /// Python version.
    pub python: String,
    /// Drake version.
    pub drake: String,
    /// numpy version.
    pub numpy: Option<String>,
    /// mujoco version.
    pub mujoco: Option<String>,
    /// usd-core version.
    pub usd_core: Option<String>,
    /// SNOPT in this Drake.
    pub snopt: SolverStatus,
    /// IPOPT in this Drake.
    pub ipopt: SolverStatus,
}

/// A one-degree-of-freedom joint as Drake loaded it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct LoadedJoint {
    /// Joint name.
    pub name: String,
    /// Drake's type name (`revolute`, `prismatic`).
    #[serde(rename = "type")]
    pub kind: String,
    /// Lower position limits (radians or metres).
    pub lower: Vec<f64>,
    /// Upper position limits.
    pub upper: Vec<f64>,
}

/// One model instance as Drake loaded it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct LoadedInstance {
    /// Model instance name (the scene's object id).
    pub name: String,
    /// Its bodies.
    pub bodies: Vec<String>,
    /// Total mass of its bodies, kg.
    pub mass: f64,
    /// Its revolute and prismatic joints.
    pub joints: Vec<LoadedJoint>,
    /// Its floating bodies with their default `world_from_body`.
    pub free_bodies: BTreeMap<String, Pose>,
    /// No body of it floats.
    pub welded: bool,
}

/// Reply to `load`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct LoadReply {
    /// The directives file loaded (absolute).
    pub directives: String,
    /// Model instances other than the world and default ones.
    pub num_model_instances: usize,
    /// Bodies other than the world body.
    pub num_bodies: usize,
    /// Generalised positions.
    pub num_positions: usize,
    /// Geometries with the proximity role.
    pub num_collision_geometries: usize,
    /// Every model instance.
    pub model_instances: Vec<LoadedInstance>,
    /// The plant cache after this request.
    pub cache: CacheStats,
}

/// Arguments of `penetrations`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct PenetrationsArgs {
    /// The scene.
    #[serde(flatten)]
    pub scene: SceneFiles,
    /// Free-body poses to check instead of the defaults.
    #[serde(default)]
    pub poses: Option<Poses>,
    /// Report pairs deeper than this, metres.
    #[serde(default)]
    pub threshold: Option<f64>,
}

/// The deepest contact between two model instances.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct PenetrationPair {
    /// First instance (in name order).
    pub a: String,
    /// Second instance.
    pub b: String,
    /// Body of `a` in the deepest contact.
    pub body_a: String,
    /// Body of `b`.
    pub body_b: String,
    /// Penetration depth, metres.
    pub depth: f64,
    /// Contact normal pointing from `b` into `a`, world frame.
    pub normal: [f64; 3],
}

/// Reply to `penetrations`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct PenetrationsReply {
    /// Pairs deeper than the threshold, deepest first.
    pub pairs: Vec<PenetrationPair>,
}

/// Arguments of `collision_report`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct CollisionReportArgs {
    /// The scene.
    #[serde(flatten)]
    pub scene: SceneFiles,
    /// Free-body poses to check instead of the defaults.
    #[serde(default)]
    pub poses: Option<Poses>,
    /// An object counts as penetrating beyond this depth, metres (the bridge's default 1 mm).
    #[serde(default)]
    pub threshold: Option<f64>,
    /// Instances that are not objects (architecture): never counted, on either side.
    #[serde(default)]
    pub static_instances: Vec<String>,
}

/// Reply to `collision_report`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct CollisionReportReply {
    /// Objects counted (instances other than the static ones).
    pub objects: usize,
    /// Objects penetrating another deeper than the threshold.
    pub penetrating_objects: Vec<String>,
    /// COL, percent.
    pub col_percent: f64,
    /// Mean depth of the pairs counted, metres.
    pub mean_depth_m: f64,
    /// Largest depth, metres.
    pub max_depth_m: f64,
    /// Threshold used, metres.
    pub threshold_m: f64,
    /// The pairs deeper than the threshold.
    pub pairs: Vec<PenetrationPair>,
}

/// A sphere to drop.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct SphereDrop {
    /// Name of its model instance.
    pub name: String,
    /// Start position, world frame, metres.
    pub xyz: [f64; 3],
    /// Radius, metres (0.01 to 1).
    #[serde(default = "default_radius")]
    pub radius: f64,
}

fn default_radius() -> f64 {
    0.1
}

/// Arguments of `drop_spheres`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct DropSpheresArgs {
    /// The scene.
    #[serde(flatten)]
    pub scene: SceneFiles,
    /// The spheres (unique names).
    pub spheres: Vec<SphereDrop>,
    /// Simulated time, seconds (0.05 to 10).
    #[serde(default = "default_drop_duration")]
    pub duration: f64,
}

fn default_drop_duration() -> f64 {
    1.5
}

/// Where a dropped sphere ended.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct DroppedSphere {
    /// Its name.
    pub name: String,
    /// Start position, metres.
    pub start: [f64; 3],
    /// End position, metres.
    pub xyz: [f64; 3],
    /// Radius, metres.
    pub radius: f64,
    /// Speed at the end, m/s.
    pub speed: f64,
}

/// Reply to `drop_spheres`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct DropSpheresReply {
    /// The spheres, in request order.
    pub spheres: Vec<DroppedSphere>,
    /// Simulated time, seconds.
    pub duration: f64,
}
