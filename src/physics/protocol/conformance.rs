//! The exports as other consumers load them: `mujoco_check` (the `mujoco` wheel) and
//! `usd_check` (usd-core with UsdPhysics) (`drake_bridge/conformance.py`).

use std::collections::BTreeMap;
use std::path::PathBuf;

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use super::{Aabb, op};

op!(
    /// Loads an MJCF file in MuJoCo, describes bodies and joints, and runs it.
    MujocoCheck, "mujoco_check", MujocoCheckArgs, MujocoCheckReply
);
op!(
    /// Opens a USD stage with usd-core and reports what a UsdPhysics consumer sees.
    UsdCheck, "usd_check", UsdCheckArgs, UsdCheckReply
);

fn default_seconds() -> f64 {
    5.0
}

/// Arguments of `mujoco_check`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct MujocoCheckArgs {
    /// The MJCF file.
    pub xml: PathBuf,
    /// Simulated time, seconds (0 to 120).
    #[serde(default = "default_seconds")]
    pub seconds: f64,
    /// Constant generalised force per hinge/slide joint during the run (N or N m).
    #[serde(default)]
    pub probe_joints: BTreeMap<String, f64>,
}

/// Counts of the loaded model.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct MujocoCounts {
    /// Bodies other than the world.
    pub bodies: usize,
    /// Geoms.
    pub geoms: usize,
    /// Joints, free joints included.
    pub joints: usize,
    /// Meshes.
    pub meshes: usize,
}

/// One MuJoCo body.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct MujocoBody {
    /// Body name.
    pub name: String,
    /// Parent body name (`world` at the top).
    pub parent: String,
    /// Mass, kg.
    pub mass: f64,
    /// It has a free joint.
    pub free: bool,
    /// Geoms that collide (contype or conaffinity set).
    pub collision_geoms: usize,
    /// Geoms that do not.
    pub visual_geoms: usize,
    /// World bounds of its colliding geoms at the start.
    pub collision_aabb: Option<Aabb>,
    /// World bounds of its other geoms.
    pub visual_aabb: Option<Aabb>,
    /// Sliding friction of its colliding geoms (distinct values, sorted).
    pub friction: Vec<f64>,
    /// Free bodies: displacement over the run, metres (`None` if the state went non-finite).
    pub displacement_m: Option<f64>,
    /// Free bodies: rotation over the run, radians.
    pub rotation_rad: Option<f64>,
    /// Free bodies: position at the end.
    pub final_pos: Option<[f64; 3]>,
    /// Free bodies: position at the start.
    pub initial_pos: Option<[f64; 3]>,
}

/// One MuJoCo hinge or slide joint.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct MujocoJoint {
    /// Joint name.
    pub name: String,
    /// `hinge`, `slide` or `ball`.
    #[serde(rename = "type")]
    pub kind: String,
    /// Body it moves.
    pub body: String,
    /// Its range is enforced.
    pub limited: bool,
    /// Range (radians or metres).
    pub range: [f64; 2],
    /// Damping.
    pub damping: f64,
    /// Reference position.
    pub qpos0: f64,
    /// Axis in world coordinates at the start.
    pub axis_world: [f64; 3],
}

/// Reply to `mujoco_check`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct MujocoCheckReply {
    /// MuJoCo version.
    pub mujoco: String,
    /// Time to compile the model, seconds.
    pub load_seconds: f64,
    /// Wall time of the run, seconds.
    pub sim_seconds: f64,
    /// Simulated time, seconds.
    pub simulated_seconds: f64,
    /// The model's time step, seconds.
    pub timestep: f64,
    /// Counts.
    pub counts: MujocoCounts,
    /// Bodies other than the world.
    pub bodies: Vec<MujocoBody>,
    /// Joints other than free joints.
    pub joints: Vec<MujocoJoint>,
    /// The state stayed finite.
    pub finite: bool,
    /// MuJoCo's warning counters that fired.
    pub warnings: BTreeMap<String, u64>,
    /// Contacts at the end.
    pub contacts_at_end: usize,
    /// Arena size, bytes.
    pub arena_bytes: u64,
    /// Arena peak use, bytes.
    pub arena_peak_bytes: u64,
    /// Deepest contact at the end, metres.
    pub max_penetration_at_end_m: f64,
    /// Final position of each probed joint.
    pub probe: BTreeMap<String, f64>,
    /// MuJoCo's warning messages.
    pub messages: Vec<String>,
}

/// Arguments of `usd_check`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct UsdCheckArgs {
    /// The USD stage.
    pub usd: PathBuf,
    /// Prims grouping static colliders and visuals (the longest matching one wins; else the
    /// top-level prim).
    #[serde(default)]
    pub static_prims: Vec<String>,
}

/// Stage metadata.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct UsdMetadata {
    /// `metersPerUnit`.
    pub meters_per_unit: f64,
    /// `kilogramsPerUnit`.
    pub kilograms_per_unit: f64,
    /// `upAxis`.
    pub up_axis: String,
    /// `defaultPrim`.
    pub default_prim: Option<String>,
    /// `metersPerUnit` is authored.
    pub has_authored_meters_per_unit: bool,
    /// The root layer's custom data, values as text.
    pub custom_layer_data: BTreeMap<String, String>,
}

/// One finding of usd-core's validators.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct UsdFinding {
    /// Validator name.
    pub validator: String,
    /// `Error`, `Warn`, `Info`.
    pub severity: String,
    /// Its message.
    pub message: String,
    /// Up to five prim or property paths.
    pub sites: Vec<String>,
}

/// One rigid body.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct UsdBody {
    /// `physics:kinematicEnabled`.
    pub kinematic: bool,
    /// `physics:rigidBodyEnabled`.
    pub enabled: bool,
    /// Authored mass, kg.
    pub mass: Option<f64>,
    /// Authored diagonal inertia, kg m^2.
    pub diagonal_inertia: Option<[f64; 3]>,
    /// Authored centre of mass, body frame, metres.
    pub center_of_mass: Option<[f64; 3]>,
    /// Colliders bound to it.
    pub colliders: usize,
    /// World bounds of its mesh colliders.
    pub collision_aabb: Option<Aabb>,
    /// World bounds of its visual meshes.
    pub visual_aabb: Option<Aabb>,
    /// Its filtered-collision targets.
    pub filtered: Vec<String>,
}

/// Colliders outside rigid bodies, grouped by prim.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct UsdStatic {
    /// Colliders in the group.
    pub colliders: usize,
    /// World bounds of its mesh colliders.
    pub collision_aabb: Option<Aabb>,
    /// World bounds of its visual meshes.
    pub visual_aabb: Option<Aabb>,
}

/// One UsdPhysics joint.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct UsdJoint {
    /// Prim path.
    pub path: String,
    /// `revolute`, `prismatic`, `fixed`, `spherical`, `d6`, `distance`.
    #[serde(rename = "type")]
    pub kind: String,
    /// `physics:body0` (empty: the world).
    pub body0: String,
    /// `physics:body1`.
    pub body1: String,
    /// body0 is the world or a rigid body.
    pub body0_ok: bool,
    /// body1 is a rigid body.
    pub body1_ok: bool,
    /// Joint axis letter.
    pub axis: Option<String>,
    /// Axis in world coordinates.
    pub axis_world: Option<[f64; 3]>,
    /// Position implied by the two local frames (metres, or degrees for revolute).
    pub position_measured: Option<f64>,
    /// Angle between the two frames' axes, radians.
    pub off_axis_rad: Option<f64>,
    /// Gap between the frames off the axis, metres.
    pub frame_gap_m: Option<f64>,
    /// The limit is enabled.
    pub limit_enabled: Option<bool>,
    /// Lower limit (metres or degrees).
    pub lower: Option<f64>,
    /// Upper limit.
    pub upper: Option<f64>,
    /// Drive damping.
    pub drive_damping: Option<f64>,
    /// Drive stiffness.
    pub drive_stiffness: Option<f64>,
}

/// One articulation.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct UsdArticulation {
    /// Prim path.
    pub path: String,
    /// Root prims.
    pub roots: Vec<String>,
    /// Articulated bodies.
    pub bodies: Vec<String>,
    /// Articulated joints.
    pub joints: Vec<String>,
}

/// Reply to `usd_check`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct UsdCheckReply {
    /// usd-core version.
    pub usd: String,
    /// Time to open the stage, seconds.
    pub open_seconds: f64,
    /// Time of the whole check, seconds.
    pub seconds: f64,
    /// Stage metadata.
    pub metadata: UsdMetadata,
    /// Composition errors.
    pub composition_errors: Vec<String>,
    /// Validator findings.
    pub findings: Vec<UsdFinding>,
    /// UsdPhysics objects per type.
    pub counts: BTreeMap<String, usize>,
    /// `PhysicsScene` prims.
    pub physics_scenes: usize,
    /// Rigid bodies by prim path.
    pub bodies: BTreeMap<String, UsdBody>,
    /// Static collider groups by prim path.
    #[serde(rename = "static")]
    pub static_groups: BTreeMap<String, UsdStatic>,
    /// Colliders per approximation (mesh colliders) or shape type.
    pub approximations: BTreeMap<String, usize>,
    /// Colliders without a physics material.
    pub colliders_without_material: usize,
    /// Physics materials: `[static, dynamic]` friction by prim path.
    pub materials: BTreeMap<String, [f64; 2]>,
    /// Joints.
    pub joints: Vec<UsdJoint>,
    /// Articulations.
    pub articulations: Vec<UsdArticulation>,
}
