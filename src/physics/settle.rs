//! Gravity settling through the bridge: the request (`settle` / `simulate` ops, see
//! `drake_bridge/settle.py`) and its typed reply.
//!
//! The bridge simulates a directives file as written (Drake's default plant at 1 ms steps)
//! until every free body has been slower than the rest thresholds for `rest_time`, or the time
//! cap. Which objects are free and which welded is decided by whoever wrote the directives
//! (see [`super::workspace`] and [`super::postprocess`]).

use std::collections::BTreeMap;
use std::path::Path;

use serde::{Deserialize, Serialize};
use serde_json::{Value, json};

use super::PhysicsError;
use crate::scene::Pose;

/// Contact model of a simulation.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ContactModel {
    /// Drake's default plant (`MultibodyPlantConfig()`: hydroelastic with point fallback) on
    /// the files as written, which declare every collider compliant hydroelastic
    /// ([`crate::assets::material::HYDROELASTIC_MODULUS_PA`]): what a user who loads
    /// `scene.dmd.yaml` the README's way gets. The default.
    #[serde(alias = "hydroelastic")]
    AsWritten,
    /// Point contact on the same files: SceneEval's protocol, for comparison with published
    /// figures.
    Point,
}

impl ContactModel {
    /// How reports name it.
    pub fn label(self) -> &'static str {
        match self {
            ContactModel::AsWritten => "Drake defaults, files as written",
            ContactModel::Point => "point contact (SceneEval)",
        }
    }
}

/// Contact configuration sent with each simulation request. The bridge injects no contact
/// properties: the files carry them.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct ContactOptions {
    /// Contact model.
    pub model: ContactModel,
}

impl Default for ContactOptions {
    fn default() -> Self {
        ContactOptions {
            model: ContactModel::AsWritten,
        }
    }
}

/// Options of a settle (or fixed-length simulation).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SettleOptions {
    /// Simulated-time cap, seconds.
    pub max_time: f64,
    /// Discrete time step, seconds.
    pub time_step: f64,
    /// A body is at rest below this speed, m/s.
    pub rest_speed: f64,
    /// ... and below this angular speed, rad/s.
    pub rest_angular_speed: f64,
    /// Everything must stay at rest this long, seconds.
    pub rest_time: f64,
    /// Stop at rest (settling) or run the whole `max_time` (stability).
    pub stop_at_rest: bool,
    /// Wall-clock cap per request, seconds.
    pub wall_limit: f64,
    /// Contact configuration.
    pub contact: ContactOptions,
    /// Floor height; bodies more than 0.5 m below it are ignored by the rest test.
    pub floor_z: Option<f64>,
}

impl Default for SettleOptions {
    fn default() -> Self {
        SettleOptions {
            max_time: 3.0,
            time_step: 1e-3,
            rest_speed: 2e-3,
            rest_angular_speed: 2e-2,
            rest_time: 0.25,
            stop_at_rest: true,
            wall_limit: 300.0,
            contact: ContactOptions::default(),
            floor_z: Some(0.0),
        }
    }
}

/// How far one model instance moved during a simulation.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Motion {
    /// Largest displacement of any of its free bodies, metres.
    pub displacement_m: f64,
    /// Largest rotation of any of its free bodies, radians.
    pub rotation_rad: f64,
    /// Height of the (first) free body at the start, metres.
    pub start_z: f64,
    /// ... and at the end.
    pub end_z: f64,
}

/// The bridge's reply to `settle` / `simulate`.
#[derive(Debug, Clone, Deserialize)]
pub struct SettleResult {
    /// Final free-body poses: instance -> body -> `world_from_body`.
    pub poses: BTreeMap<String, BTreeMap<String, Pose>>,
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
    /// Deepest overlap at the end between different instances, metres.
    pub max_penetration_m: f64,
    /// Free bodies simulated.
    pub free_bodies: usize,
    /// Wall time of the request in the bridge, seconds.
    pub wall_s: f64,
    /// Time spent building the plant (0 on a cache hit), seconds.
    pub build_s: f64,
    /// Mean wall time per step, milliseconds.
    pub ms_per_step: f64,
}

/// Arguments of a `settle` (or, with `stop_at_rest: false`, `simulate`) request.
pub fn request_args(
    directives: &Path,
    package_xml: &Path,
    opts: &SettleOptions,
) -> (String, Value) {
    let op = if opts.stop_at_rest {
        "settle"
    } else {
        "simulate"
    };
    let duration_key = if opts.stop_at_rest {
        "max_time"
    } else {
        "duration"
    };
    let mut args = json!({
        "directives": directives,
        "package_xml": package_xml,
        "time_step": opts.time_step,
        "rest_speed": opts.rest_speed,
        "rest_angular_speed": opts.rest_angular_speed,
        "rest_time": opts.rest_time,
        "stop_at_rest": opts.stop_at_rest,
        "wall_limit": opts.wall_limit,
        "contact": { "model": opts.contact.model },
        "floor_z": opts.floor_z,
    });
    args[duration_key] = json!(opts.max_time);
    (op.to_string(), args)
}

/// Parses a `settle` / `simulate` reply.
pub fn parse_result(op: &str, reply: Value) -> Result<SettleResult, PhysicsError> {
    serde_json::from_value(reply).map_err(|e| PhysicsError::Reply {
        op: op.to_string(),
        detail: e.to_string(),
    })
}
