//! The Drake projection (`project` op, `drake_bridge/projection.py`): SNOPT on one
//! `DistanceConstraint` per candidate pair, IPOPT when SNOPT fails, a push-out along the
//! penetration normals as the last resort, under a wall-clock limit. It is the reference the
//! native projection ([`super::projection`]) is measured against; the pipeline uses the native
//! one.

use std::collections::BTreeMap;
use std::path::Path;

use serde::Deserialize;
use serde_json::{Value, json};

use super::PhysicsError;
use super::pool::BridgePool;
use super::projection::XyRegion;
use crate::scene::Pose;

/// Options of the Drake projection.
#[derive(Debug, Clone)]
pub struct DrakeProjectionOptions {
    /// `auto` (SNOPT then IPOPT then push-out), `snopt`, `ipopt` or `push_out`.
    pub solver: String,
    /// Lower bound on every candidate pair's signed distance, metres.
    pub min_distance: f64,
    /// Largest penetration accepted, metres.
    pub tolerance: f64,
    /// Pairs closer than this at the start get a constraint, metres.
    pub candidate_distance: f64,
    /// Wall-clock limit for the solvers, seconds.
    pub time_limit: f64,
    /// Slide in XY only (z only rises to the floor).
    pub xy_only: bool,
    /// Floor top; `None` turns the floor bound off.
    pub floor_z: Option<f64>,
    /// Instances allowed to move (`None`: all free ones, or only colliding ones above 100).
    pub movable: Option<Vec<String>>,
    /// XY regions per instance.
    pub regions: BTreeMap<String, XyRegion>,
}

impl Default for DrakeProjectionOptions {
    fn default() -> Self {
        DrakeProjectionOptions {
            solver: "auto".into(),
            min_distance: 1e-5,
            tolerance: 1e-4,
            candidate_distance: 0.05,
            time_limit: 60.0,
            xy_only: false,
            floor_z: Some(0.0),
            movable: None,
            regions: BTreeMap::new(),
        }
    }
}

/// The bridge's reply to `project`.
#[derive(Debug, Clone, Deserialize)]
pub struct DrakeProjectionResult {
    /// Free-body poses after projection: instance -> body -> `world_from_body`.
    pub poses: BTreeMap<String, BTreeMap<String, Pose>>,
    /// Which method produced them: `none`, `snopt`, `ipopt` or `push_out`.
    pub solver: String,
    /// Deepest penetration before, metres.
    pub initial_max_penetration_m: f64,
    /// Deepest penetration after, metres.
    pub max_penetration_m: f64,
    /// Mean displacement of the movable bodies, metres.
    pub mean_displacement_m: f64,
    /// Largest displacement, metres.
    pub max_displacement_m: f64,
    /// Distance constraints in the program.
    pub pairs: usize,
    /// Solver attempts with their statuses.
    pub attempts: Vec<Value>,
    /// Wall time in the bridge, seconds.
    pub wall_s: f64,
}

/// Arguments of a `project` request.
pub fn request_args(directives: &Path, package_xml: &Path, opts: &DrakeProjectionOptions) -> Value {
    let regions: BTreeMap<&String, &Vec<[f64; 3]>> = opts
        .regions
        .iter()
        .map(|(k, r)| (k, &r.halfplanes))
        .collect();
    json!({
        "directives": directives,
        "package_xml": package_xml,
        "solver": opts.solver,
        "min_distance": opts.min_distance,
        "tolerance": opts.tolerance,
        "candidate_distance": opts.candidate_distance,
        "time_limit": opts.time_limit,
        "xy_only": opts.xy_only,
        "floor_z": opts.floor_z,
        "movable": opts.movable,
        "regions": regions,
    })
}

/// Runs the Drake projection of a directives file on the pool.
pub fn project_drake(
    pool: &BridgePool,
    directives: &Path,
    package_xml: &Path,
    opts: &DrakeProjectionOptions,
) -> Result<DrakeProjectionResult, PhysicsError> {
    let reply = pool.request("project", request_args(directives, package_xml, opts))?;
    serde_json::from_value(reply).map_err(|e| PhysicsError::Reply {
        op: "project".into(),
        detail: e.to_string(),
    })
}
