//! The Drake projection (`project` op, `drake_bridge/projection.py`): SNOPT on one
//! `DistanceConstraint` per candidate pair, IPOPT when SNOPT fails, a push-out along the
//! penetration normals as the last resort, under a wall-clock limit. It is the reference the
//! native projection ([`super::projection`]) is measured against; the pipeline uses the native
//! one.

use std::collections::BTreeMap;
use std::path::Path;

use super::PhysicsError;
use super::pool::BridgePool;
use super::projection::XyRegion;
use super::protocol::{Project, ProjectArgs, SceneFiles};
pub use super::protocol::{ProjectReply, ProjectSolver};

/// Options of the Drake projection.
#[derive(Debug, Clone)]
pub struct DrakeProjectionOptions {
    /// SNOPT then IPOPT then push-out, or one of them.
    pub solver: ProjectSolver,
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
            solver: ProjectSolver::Auto,
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

/// Arguments of a `project` request.
pub fn project_args(
    directives: &Path,
    package_xml: &Path,
    opts: &DrakeProjectionOptions,
) -> ProjectArgs {
    ProjectArgs {
        scene: SceneFiles::new(directives, package_xml),
        poses: None,
        solver: opts.solver,
        min_distance: opts.min_distance,
        tolerance: opts.tolerance,
        candidate_distance: opts.candidate_distance,
        time_limit: opts.time_limit,
        xy_only: opts.xy_only,
        floor_z: opts.floor_z,
        movable: opts.movable.clone(),
        regions: opts
            .regions
            .iter()
            .map(|(k, r)| (k.clone(), r.halfplanes.clone()))
            .collect(),
    }
}

/// Runs the Drake projection of a directives file on the pool.
pub fn project_drake(
    pool: &BridgePool,
    directives: &Path,
    package_xml: &Path,
    opts: &DrakeProjectionOptions,
) -> Result<ProjectReply, PhysicsError> {
    Ok(pool.call::<Project>(&project_args(directives, package_xml, opts))?)
}
