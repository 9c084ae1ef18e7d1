//! Gravity settling through the bridge: the options and the `simulate` request built from them
//! (`drake_bridge/settle.py`; the reply is [`SettleReply`]).
//!
//! The bridge simulates a directives file as written (Drake's default plant at 1 ms steps)
//! until every free body has been slower than the rest thresholds for `rest_time`, or the time
//! cap. Which objects are free and which welded is decided by whoever wrote the directives
//! (see [`super::workspace`] and [`super::postprocess`]).

use std::path::Path;

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use super::protocol::{ContactArgs, SceneFiles, SimulateArgs, SimulationArgs, VerdictBound};
pub use super::protocol::{Motion, SettleReply};

/// Simulated time between the bridge's rest checks, seconds.
const CHECK_INTERVAL_S: f64 = 0.01;

/// Contact model of a simulation.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
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
    /// Stability thresholds: with `stop_at_rest`, also stop once no verdict can change.
    pub verdict: Option<VerdictBound>,
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
            verdict: None,
        }
    }
}

/// The `simulate` request for a directives file: the whole `max_time`, or stopping at rest
/// when `opts.stop_at_rest` (the two differ only in that flag, so every caller uses one op).
pub fn simulate_args(directives: &Path, package_xml: &Path, opts: &SettleOptions) -> SimulateArgs {
    SimulateArgs {
        sim: SimulationArgs {
            scene: SceneFiles::new(directives, package_xml),
            poses: None,
            time_step: opts.time_step,
            rest_speed: opts.rest_speed,
            rest_angular_speed: opts.rest_angular_speed,
            rest_time: opts.rest_time,
            check_interval: CHECK_INTERVAL_S,
            wall_limit: opts.wall_limit,
            contact: ContactArgs {
                model: opts.contact.model,
                approximation: None,
            },
            floor_z: opts.floor_z,
            verdict: opts.verdict,
        },
        duration: opts.max_time,
        stop_at_rest: opts.stop_at_rest,
    }
}
