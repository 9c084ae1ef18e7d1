//! Post-processing of a furnished scene: make it physically feasible.
//!
//! Two phases, each *project -> settle -> remove what fell -> project again*:
//! - **furniture**: furniture free (sliding on the floor in the projections), architecture and
//!   wall/ceiling objects fixed, small objects left out; whatever rests on a piece of furniture
//!   moves with it; settling runs one subset scene per group of pieces close together;
//! - **manipuland**: furniture welded, small objects free (3-D projection, each kept over its
//!   support surface); settling runs one subset scene per supporting entity (the entity welded,
//!   its small objects free; small objects on the floor share one subset with all furniture
//!   welded), in parallel over the bridge pool.
//!
//! The projections are native ([`super::projection`]); settling needs the Drake bridge and is
//! skipped without a pool. Objects that still penetrate deeper than
//! `PostProcessOptions::remove_penetrating_above_m` at the very end are removed, so what is
//! written is collision-free. Every removal is recorded in `scene.removed` with its reason.
//! An object the prompt asked for is not lost that way if it can be helped
//! ([`post_process_placing_again`]): it is placed again on another surface, settled there alone
//! with everything around it held, and kept when it rests (`scene.placed_again`).

use std::collections::{BTreeMap, BTreeSet};
use std::time::Instant;

use serde::Serialize;

use super::PhysicsError;
use super::as_written::posed_objects;
use super::collision::penetrating_pairs;
use super::groups::{ISLAND_GAP_M, groups_near, pack_small_groups};
use super::pool::BridgePool;
use super::projection::{
    Movable, ProjectionOptions, ProjectionReport, XyRegion, apply_offsets, project_objects,
};
use super::protocol::Simulate;
use super::removal::{RemovalRules, furniture_verdict, manipuland_verdict};
use super::settle::{SettleOptions, SettleReply, simulate_args};
use super::workspace::{Role, Workspace};
use crate::scene::{ObjectKind, PlacedAgain, Pose, Scene, SceneObject, Support};
use crate::state::SceneState;

/// Options of [`post_process`].
#[derive(Debug, Clone)]
pub struct PostProcessOptions {
    /// Base projection options (each phase sets `xy_only`, `movable` and `regions`).
    pub projection: ProjectionOptions,
    /// Settling options.
    pub settle: SettleOptions,
    /// Settle at all (needs a pool).
    pub settle_enabled: bool,
    /// Fallen-object rules.
    pub rules: RemovalRules,
    /// At the end, objects still penetrating deeper than this are removed (`None`: kept).
    pub remove_penetrating_above_m: Option<f64>,
}

impl Default for PostProcessOptions {
    fn default() -> Self {
        PostProcessOptions {
            projection: ProjectionOptions::default(),
            settle: SettleOptions::default(),
            settle_enabled: true,
            rules: RemovalRules::default(),
            remove_penetrating_above_m: Some(1e-3),
        }
    }
}

/// One settled subset scene.
#[derive(Debug, Clone, Serialize)]
pub struct SubsetReport {
    /// What the subset is: a room id (furniture phase) or a supporting entity (`floor` for
    /// small objects on the floor).
    pub subset: String,
    /// Free bodies simulated.
    pub free_bodies: usize,
    /// Simulated seconds until rest or the cap.
    pub sim_time: f64,
    /// Everything came to rest.
    pub at_rest: bool,
    /// Deepest overlap at the end, metres.
    pub max_penetration_m: f64,
    /// Wall time in the bridge, seconds (not written into scene files).
    #[serde(skip)]
    pub wall_s: f64,
    /// Milliseconds per step (not written into scene files).
    #[serde(skip)]
    pub ms_per_step: f64,
}

/// What one phase did.
#[derive(Debug, Clone, Serialize, Default)]
pub struct PhaseReport {
    /// First projection.
    pub projection: Option<ProjectionReport>,
    /// Settled subsets.
    pub settle: Vec<SubsetReport>,
    /// Projection after settling.
    pub cleanup: Option<ProjectionReport>,
    /// Objects removed in this phase (ids).
    pub removed: Vec<String>,
    /// Wall time of the settle requests (all subsets, in parallel), seconds.
    #[serde(skip)]
    pub settle_seconds: f64,
}

/// What post-processing did.
#[derive(Debug, Clone, Serialize, Default)]
pub struct PostProcessReport {
    /// Furniture phase.
    pub furniture: PhaseReport,
    /// Small-object phase.
    pub manipuland: PhaseReport,
    /// Objects removed at the end because they still penetrated something.
    pub removed_penetrating: Vec<String>,
    /// Subsets settled again after those removals.
    pub resettled: Vec<SubsetReport>,
    /// Asked-for objects removed above and placed again elsewhere (ids).
    pub placed_again: Vec<String>,
    /// Wall time, seconds (not written into scene files).
    #[serde(skip)]
    pub seconds: f64,
}

/// Runs both phases on `state`. Without a pool (or with settling disabled) only the
/// projections and the final penetration check run.
pub fn post_process(
    state: &mut SceneState,
    pool: Option<&BridgePool>,
    opts: &PostProcessOptions,
) -> Result<PostProcessReport, PhysicsError> {
    post_process_placing_again(state, pool, opts, &[], &|_, _, _| None)
}

/// Proposes another place for an object post-processing removed, avoiding the surfaces
/// already tried (`parent/surface` keys): the object posed there, and the surface's key.
pub type Spotter<'a> =
    &'a dyn Fn(&SceneState, &SceneObject, &[String]) -> Option<(SceneObject, String)>;

/// Most places an asked-for object is tried at after post-processing removed it.
pub const PLACE_AGAIN_ATTEMPTS: u32 = 3;

/// [`post_process`], then the small objects it removed that `asked` (noun, count wanted) is
/// now short of are placed again: `spot` proposes a place, the object is settled there alone
/// (its support and neighbours welded) and stays when it rests by the removal rules and
/// penetrates nothing; at most [`PLACE_AGAIN_ATTEMPTS`] places each. Needs a pool.
pub fn post_process_placing_again(
    state: &mut SceneState,
    pool: Option<&BridgePool>,
    opts: &PostProcessOptions,
    asked: &[(String, u32)],
    spot: Spotter,
) -> Result<PostProcessReport, PhysicsError> {
    let t0 = Instant::now();
    let first_removal = state.scene.removed.len();
    // Copies of the small objects only when something was asked for (nothing to place
    // again otherwise).
    let before: BTreeMap<String, SceneObject> = state
        .scene
        .objects
        .iter()
        .filter(|o| !asked.is_empty() && is_free_manipuland(o))
        .map(|o| (o.id.clone(), o.clone()))
        .collect();
    let pool = pool.filter(|_| opts.settle_enabled);
    let mut workspace = match pool {
        Some(_) => Some(Workspace::new(state)?),
        None => None,
    };
    let furniture = furniture_phase(state, pool, workspace.as_mut(), opts)?;
    let manipuland = manipuland_phase(state, pool, workspace.as_mut(), opts)?;
    let entities: BTreeMap<String, String> = state
        .scene
        .objects
        .iter()
        .map(|o| (o.id.clone(), supporting_entity(&state.scene, &o.id)))
        .collect();
    let removed_penetrating = match opts.remove_penetrating_above_m {
        Some(t) => remove_penetrating(state, t)?,
        None => Vec::new(),
    };
    let mut resettled = Vec::new();
    if let (Some(pool), Some(ws), false) =
        (pool, workspace.as_mut(), removed_penetrating.is_empty())
    {
        let touched: BTreeSet<String> = removed_penetrating
            .iter()
            .filter_map(|id| entities.get(id).cloned())
            .collect();
        resettled = resettle(state, pool, ws, &touched, &opts.settle)?;
    }
    let placed_again = match (pool, workspace.as_mut()) {
        (Some(pool), Some(ws)) if !asked.is_empty() => {
            let lost = Lost {
                before: &before,
                first_removal,
                asked,
            };
            place_again(state, pool, ws, opts, &lost, spot)?
        }
        _ => Vec::new(),
    };
    state.prune_assets();
    let projection_s = |r: &Option<ProjectionReport>| r.as_ref().map_or(0.0, |r| r.seconds);
    tracing::info!(
        "post-process: furniture projection {:.1} s, settle {:.1} s, cleanup {:.1} s; small objects projection {:.1} s, settle {:.1} s, cleanup {:.1} s; total {:.1} s",
        projection_s(&furniture.projection),
        furniture.settle_seconds,
        projection_s(&furniture.cleanup),
        projection_s(&manipuland.projection),
        manipuland.settle_seconds,
        projection_s(&manipuland.cleanup),
        t0.elapsed().as_secs_f64()
    );
    Ok(PostProcessReport {
        furniture,
        manipuland,
        removed_penetrating,
        resettled,
        placed_again,
        seconds: t0.elapsed().as_secs_f64(),
    })
}

/// What post-processing took that the prompt asked for: the small objects as they were before
/// it (`before`), the removals it recorded (from `first_removal` on), the asked-for counts.
struct Lost<'a> {
    before: &'a BTreeMap<String, SceneObject>,
    first_removal: usize,
    asked: &'a [(String, u32)],
}

impl Lost<'_> {
    /// Whether the scene has fewer objects that `category` counts for than some asked-for noun
    /// naming it wants.
    fn short_of(&self, scene: &Scene, category: &str) -> bool {
        self.asked.iter().any(|(noun, wanted)| {
            crate::assets::router::naming::names(noun, category)
                && (scene
                    .objects
                    .iter()
                    .filter(|o| crate::assets::router::naming::object_is(scene, noun, o))
                    .count() as u32)
                    < *wanted
        })
    }
}

fn place_again(
    state: &mut SceneState,
    pool: &BridgePool,
    ws: &mut Workspace,
    opts: &PostProcessOptions,
    lost: &Lost,
    spot: Spotter,
) -> Result<Vec<String>, PhysicsError> {
    let mut done = Vec::new();
    let removals =
        state.scene.removed[lost.first_removal.min(state.scene.removed.len())..].to_vec();
    for r in removals {
        let Some(obj) = lost.before.get(&r.object) else {
            continue;
        };
        if !lost.short_of(&state.scene, &r.category) || !state.assets.contains_key(&obj.asset) {
            continue;
        }
        // Its own surface stays a candidate: another pose there (upright, at a free spot) is
        // often all it takes.
        let mut tried: Vec<String> = Vec::new();
        for attempt in 1..=PLACE_AGAIN_ATTEMPTS {
            let Some((placed, key)) = spot(state, obj, &tried) else {
                break;
            };
            tried.push(key.clone());
            state.scene.objects.push(placed.clone());
            if settles_alone(state, pool, ws, opts, &placed)? {
                state.scene.removed.retain(|x| x.object != r.object);
                state.scene.placed_again.push(PlacedAgain {
                    object: r.object.clone(),
                    category: r.category.clone(),
                    removed_because: r.reason.clone(),
                    surface: key,
                    attempts: attempt,
                });
                done.push(r.object.clone());
                break;
            }
            state.scene.objects.retain(|o| o.id != placed.id);
        }
    }
    Ok(done)
}

/// Settles `obj` (already in the scene) with its supporting entity and the entity's other
/// small objects welded; keeps the settled pose and returns true when it rests by the
/// removal rules and penetrates nothing deeper than the end-of-run threshold.
fn settles_alone(
    state: &mut SceneState,
    pool: &BridgePool,
    ws: &mut Workspace,
    opts: &PostProcessOptions,
    obj: &SceneObject,
) -> Result<bool, PhysicsError> {
    let entity = supporting_entity(&state.scene, &obj.id);
    let mut members: BTreeMap<String, Role> =
        ids_where(&state.scene, |o| o.kind == ObjectKind::Architecture)
            .into_iter()
            .map(|a| (a, Role::Welded))
            .collect();
    members.insert(entity.clone(), Role::Welded);
    for o in state.scene.objects.iter().filter(|o| is_free_manipuland(o)) {
        if o.id != obj.id && supporting_entity(&state.scene, &o.id) == entity {
            members.insert(o.id.clone(), Role::Welded);
        }
    }
    members.insert(obj.id.clone(), Role::Free);
    let results = settle_subsets(state, pool, ws, &[(entity, members)], &opts.settle)?;
    let settled = results
        .first()
        .and_then(|r| settled_pose(state, r, &obj.id));
    let (Some(p), Some(asset)) = (settled, state.assets.get(&obj.asset)) else {
        return Ok(false);
    };
    if manipuland_verdict(asset, obj, &obj.world_from_object, &p, &opts.rules).is_some() {
        return Ok(false);
    }
    if let Some(o) = state.scene.objects.iter_mut().find(|o| o.id == obj.id) {
        o.world_from_object = p;
    }
    let threshold = opts.remove_penetrating_above_m.unwrap_or(1e-3);
    let posed = posed_objects(&state.scene, &state.assets);
    Ok(!penetrating_pairs(&posed, threshold)
        .iter()
        .any(|pair| pair.a == obj.id || pair.b == obj.id))
}

/// Ids of every object resting (directly or through others) on `id`.
fn descendants(scene: &Scene, id: &str) -> Vec<String> {
    let mut out: Vec<String> = Vec::new();
    let mut frontier = vec![id.to_string()];
    while let Some(p) = frontier.pop() {
        for o in &scene.objects {
            if matches!(&o.support, Support::Object { parent, .. } if *parent == p)
                && !out.contains(&o.id)
                && o.id != id
            {
                out.push(o.id.clone());
                frontier.push(o.id.clone());
            }
        }
    }
    out
}

/// Moves `id` to `world_from_new` and everything resting on it rigidly with it.
fn move_with_load(state: &mut SceneState, id: &str, world_from_new: Pose) {
    let Some(old) = state.scene.object(id).map(|o| o.world_from_object) else {
        return;
    };
    let delta = world_from_new.compose(&old.inverse());
    let carried = descendants(&state.scene, id);
    for o in &mut state.scene.objects {
        if o.id == id {
            o.world_from_object = world_from_new;
        } else if carried.contains(&o.id) {
            o.world_from_object = delta.compose(&o.world_from_object);
        }
    }
}

fn apply_offsets_with_load(
    state: &mut SceneState,
    offsets: &BTreeMap<String, nalgebra::Vector3<f64>>,
) {
    for (id, d) in offsets {
        let carried = descendants(&state.scene, id);
        let moved: BTreeMap<String, nalgebra::Vector3<f64>> = carried
            .into_iter()
            .filter(|c| !offsets.contains_key(c))
            .map(|c| (c, *d))
            .collect();
        apply_offsets(state, &moved);
    }
    apply_offsets(state, offsets);
}

fn ids_where(scene: &Scene, f: impl Fn(&crate::scene::SceneObject) -> bool) -> Vec<String> {
    scene
        .objects
        .iter()
        .filter(|o| f(o))
        .map(|o| o.id.clone())
        .collect()
}

fn is_free_furniture(o: &crate::scene::SceneObject) -> bool {
    o.kind == ObjectKind::Furniture && !o.welded
}

fn is_free_manipuland(o: &crate::scene::SceneObject) -> bool {
    o.kind == ObjectKind::Manipuland && !o.welded
}

/// Settles each subset on the pool; returns the parsed results in subset order.
fn settle_subsets(
    state: &SceneState,
    pool: &BridgePool,
    workspace: &mut Workspace,
    subsets: &[(String, BTreeMap<String, Role>)],
    opts: &SettleOptions,
) -> Result<Vec<SettleReply>, PhysicsError> {
    let mut requests = Vec::new();
    for (_, members) in subsets {
        let directives = workspace.write_subset(state, members)?;
        requests.push(simulate_args(&directives, &workspace.package_xml(), opts));
    }
    pool.call_all::<Simulate>(&requests)
        .into_iter()
        .map(|r| r.map_err(PhysicsError::from))
        .collect()
}

/// The new `world_from_object` of `id` from a settle result, if the object was free in it.
fn settled_pose(state: &SceneState, result: &SettleReply, id: &str) -> Option<Pose> {
    let obj = state.scene.object(id)?;
    let asset = state.assets.get(&obj.asset)?;
    let root = asset.links.first()?;
    let world_from_body = result.poses.get(id)?.get(&root.name)?;
    Some(world_from_body.compose(&root.model_from_link.inverse()))
}

fn subset_report(subset: &str, r: &SettleReply) -> SubsetReport {
    tracing::info!(
        "settle {subset} ({} free): {:.2} s simulated{} in {:.1} s wall ({:.1} ms/step)",
        r.free_bodies,
        r.sim_time,
        if r.at_rest { ", at rest" } else { "" },
        r.wall_s,
        r.ms_per_step
    );
    SubsetReport {
        subset: subset.to_string(),
        free_bodies: r.free_bodies,
        sim_time: r.sim_time,
        at_rest: r.at_rest,
        max_penetration_m: r.max_penetration_m,
        wall_s: r.wall_s,
        ms_per_step: r.ms_per_step,
    }
}

/// Farthest a piece of furniture may move while settling with its small objects, metres and
/// radians (it sinks and leans a millimetre or so into the compliant floor under the load).
const ENTITY_SHIFT_M: f64 = 0.005;
const ENTITY_TURN_RAD: f64 = 0.01;

const FURNITURE_STAGE: &str = "post_process/furniture";
const MANIPULAND_STAGE: &str = "post_process/manipuland";

/// Furniture phase: project furniture (sliding), settle it per group of pieces close together
/// ([`furniture_subsets`]), remove what fell over, project again.
pub fn furniture_phase(
    state: &mut SceneState,
    pool: Option<&BridgePool>,
    workspace: Option<&mut Workspace>,
    opts: &PostProcessOptions,
) -> Result<PhaseReport, PhysicsError> {
    let mut report = PhaseReport::default();
    let project = |state: &mut SceneState| -> Result<Option<ProjectionReport>, PhysicsError> {
        let free = ids_where(&state.scene, is_free_furniture);
        if free.is_empty() {
            return Ok(None);
        }
        let fixed = ids_where(&state.scene, |o| {
            !is_free_furniture(o) && o.kind != ObjectKind::Manipuland
        });
        let popts = ProjectionOptions {
            xy_only: true,
            movable: Movable::Auto,
            regions: BTreeMap::new(),
            ..opts.projection.clone()
        };
        let (offsets, r) = project_objects(state, &free, &fixed, &popts)?;
        apply_offsets_with_load(state, &offsets);
        Ok(Some(r))
    };
    report.projection = project(state)?;

    if let (Some(pool), Some(ws)) = (pool, workspace) {
        let subsets = furniture_subsets(state);
        let t = Instant::now();
        let results = settle_subsets(state, pool, ws, &subsets, &opts.settle)?;
        report.settle_seconds = t.elapsed().as_secs_f64();
        for ((name, members), result) in subsets.iter().zip(&results) {
            report.settle.push(subset_report(name, result));
            for (id, role) in members {
                if *role != Role::Free {
                    continue;
                }
                if let Some(p) = settled_pose(state, result, id) {
                    move_with_load(state, id, p);
                }
            }
            for (id, role) in members {
                if *role != Role::Free {
                    continue;
                }
                let Some(obj) = state.scene.object(id).cloned() else {
                    continue;
                };
                let Some(asset) = state.assets.get(&obj.asset) else {
                    continue;
                };
                if let Some(reason) =
                    furniture_verdict(asset, &obj, &obj.world_from_object, &opts.rules)
                {
                    state.remove_object(id, FURNITURE_STAGE, &reason);
                    report.removed.push(id.clone());
                }
            }
        }
        report.cleanup = project(state)?;
    }
    Ok(report)
}

/// The furniture phase's subset scenes: per room, one per group of free pieces within
/// [`ISLAND_GAP_M`] of each other (pieces farther apart cannot touch without first moving that
/// far, so the groups settle apart, in parallel, and each faster than the whole room: Drake's
/// cost per step grows faster than the body count), with the room's fixed objects welded.
fn furniture_subsets(state: &SceneState) -> Vec<(String, BTreeMap<String, Role>)> {
    let mut subsets = Vec::new();
    for room in &state.scene.rooms {
        let in_room = |o: &&SceneObject| o.room == room.id;
        let free: Vec<&str> = state
            .scene
            .objects
            .iter()
            .filter(|o| in_room(o) && is_free_furniture(o))
            .map(|o| o.id.as_str())
            .collect();
        let fixed: Vec<&SceneObject> = state
            .scene
            .objects
            .iter()
            .filter(|o| in_room(o) && !is_free_furniture(o) && o.kind != ObjectKind::Manipuland)
            .collect();
        for group in pack_small_groups(groups_near(state, &free, &[], ISLAND_GAP_M)) {
            let name = format!("{}/{}", room.id, group[0]);
            let mut members: BTreeMap<String, Role> =
                fixed.iter().map(|o| (o.id.clone(), Role::Welded)).collect();
            members.extend(group.into_iter().map(|id| (id, Role::Free)));
            subsets.push((name, members));
        }
    }
    subsets
}

/// The furniture (or other non-small object) a small object ultimately rests on, or `floor`.
fn supporting_entity(scene: &Scene, id: &str) -> String {
    let mut cur = id.to_string();
    for _ in 0..scene.objects.len() + 1 {
        let Some(o) = scene.object(&cur) else { break };
        match &o.support {
            Support::Object { parent, .. } => match scene.object(parent) {
                Some(p) if p.kind == ObjectKind::Manipuland => cur = parent.clone(),
                Some(p) => return p.id.clone(),
                None => break,
            },
            _ => break,
        }
    }
    "floor".to_string()
}

/// XY regions keeping each small object's origin over the surface it rests on.
fn surface_regions(state: &SceneState) -> BTreeMap<String, XyRegion> {
    let mut out = BTreeMap::new();
    for o in state.scene.objects.iter().filter(|o| is_free_manipuland(o)) {
        let Support::Object { parent, surface } = &o.support else {
            continue;
        };
        let Some(p) = state.scene.object(parent) else {
            continue;
        };
        let Some(rec) = state.scene.assets.get(&p.asset) else {
            continue;
        };
        let Some(s) = rec.surfaces.iter().find(|s| &s.id == surface) else {
            continue;
        };
        out.insert(
            o.id.clone(),
            XyRegion::rectangle(
                &p.world_from_object,
                [s.center[0], s.center[1]],
                [s.size[0] / 2.0, s.size[1] / 2.0],
                0.0,
            ),
        );
    }
    out
}

/// One settling subset per supporting entity (the entity welded, its small objects free; small
/// objects on the floor share one subset with all furniture welded); only the entities in
/// `only` when given.
fn manipuland_subsets(
    state: &SceneState,
    only: Option<&BTreeSet<String>>,
) -> Vec<(String, BTreeMap<String, Role>)> {
    let mut groups: BTreeMap<String, Vec<String>> = BTreeMap::new();
    for o in state.scene.objects.iter().filter(|o| is_free_manipuland(o)) {
        let entity = supporting_entity(&state.scene, &o.id);
        if only.is_none_or(|set| set.contains(&entity)) {
            groups.entry(entity).or_default().push(o.id.clone());
        }
    }
    let architecture: Vec<String> = ids_where(&state.scene, |o| o.kind == ObjectKind::Architecture);
    let mut subsets = Vec::new();
    for (entity, items) in groups {
        let mut members: BTreeMap<String, Role> = architecture
            .iter()
            .map(|a| (a.clone(), Role::Welded))
            .collect();
        if entity == "floor" {
            for o in
                state.scene.objects.iter().filter(|o| {
                    o.kind != ObjectKind::Manipuland && o.kind != ObjectKind::Architecture
                })
            {
                members.insert(o.id.clone(), Role::Welded);
            }
        } else {
            // Free furniture settles with its load, so the files hold the poses at which the
            // two rest together: welded here, a bookcase would lean a millimetre under its
            // books in every later simulation of the files.
            let free = state.scene.object(&entity).is_some_and(is_free_furniture);
            members.insert(entity.clone(), if free { Role::Free } else { Role::Welded });
        }
        for i in items {
            members.insert(i, Role::Free);
        }
        subsets.push((entity, members));
    }
    subsets
}

/// Settles again the small objects of the entities that lost objects at the very end: a bowl
/// that came to rest on a napkin which was then removed would otherwise hang in the air.
fn resettle(
    state: &mut SceneState,
    pool: &BridgePool,
    workspace: &mut Workspace,
    entities: &BTreeSet<String>,
    opts: &SettleOptions,
) -> Result<Vec<SubsetReport>, PhysicsError> {
    let subsets = manipuland_subsets(state, Some(entities));
    let results = settle_subsets(state, pool, workspace, &subsets, opts)?;
    let mut reports = Vec::new();
    for ((name, members), result) in subsets.iter().zip(&results) {
        reports.push(subset_report(name, result));
        for (id, role) in members {
            if *role != Role::Free {
                continue;
            }
            if let Some(p) = settled_pose(state, result, id)
                && let Some(o) = state.scene.objects.iter_mut().find(|o| &o.id == id)
            {
                o.world_from_object = p;
            }
        }
    }
    Ok(reports)
}

/// Small-object phase: project them (3-D, over their surfaces), settle per supporting entity,
/// remove what fell, project again.
pub fn manipuland_phase(
    state: &mut SceneState,
    pool: Option<&BridgePool>,
    workspace: Option<&mut Workspace>,
    opts: &PostProcessOptions,
) -> Result<PhaseReport, PhysicsError> {
    let mut report = PhaseReport::default();
    let project = |state: &mut SceneState,
                   regions: BTreeMap<String, XyRegion>|
     -> Result<Option<ProjectionReport>, PhysicsError> {
        let free = ids_where(&state.scene, is_free_manipuland);
        if free.is_empty() {
            return Ok(None);
        }
        let fixed = ids_where(&state.scene, |o| !is_free_manipuland(o));
        let popts = ProjectionOptions {
            xy_only: false,
            movable: Movable::Auto,
            regions,
            ..opts.projection.clone()
        };
        let (offsets, r) = project_objects(state, &free, &fixed, &popts)?;
        apply_offsets_with_load(state, &offsets);
        Ok(Some(r))
    };
    let regions = surface_regions(state);
    report.projection = project(state, regions)?;

    if let (Some(pool), Some(ws)) = (pool, workspace) {
        let mut subsets = manipuland_subsets(state, None);
        let before: BTreeMap<String, Pose> = state
            .scene
            .objects
            .iter()
            .map(|o| (o.id.clone(), o.world_from_object))
            .collect();
        let t = Instant::now();
        let mut results = settle_subsets(state, pool, ws, &subsets, &opts.settle)?;
        // A piece of furniture its load moved more than a settle should (a shelf that slid or
        // tipped, a cabinet pushed into the wall) is put back: that subset settles again with
        // the piece welded.
        let threshold = opts.remove_penetrating_above_m.unwrap_or(1e-3);
        let shifted = entities_moved_too_far(state, &subsets, &results, threshold);
        if !shifted.is_empty() {
            let welded: Vec<(String, BTreeMap<String, Role>)> = shifted
                .iter()
                .map(|&i| {
                    let (entity, mut members) = subsets[i].clone();
                    tracing::info!("settle {entity}: moved under its load; again, welded");
                    members.insert(entity.clone(), Role::Welded);
                    (entity, members)
                })
                .collect();
            let again = settle_subsets(state, pool, ws, &welded, &opts.settle)?;
            for ((&i, subset), result) in shifted.iter().zip(welded).zip(again) {
                subsets[i] = subset;
                results[i] = result;
            }
        }
        report.settle_seconds = t.elapsed().as_secs_f64();
        let mut doomed: Vec<(String, String)> = Vec::new();
        for ((name, members), result) in subsets.iter().zip(&results) {
            report.settle.push(subset_report(name, result));
            for (id, role) in members {
                if *role != Role::Free {
                    continue;
                }
                let Some(p) = settled_pose(state, result, id) else {
                    continue;
                };
                if let Some(o) = state.scene.objects.iter_mut().find(|o| &o.id == id) {
                    o.world_from_object = p;
                }
                let (Some(obj), Some(b)) = (state.scene.object(id), before.get(id)) else {
                    continue;
                };
                let Some(asset) = state.assets.get(&obj.asset) else {
                    continue;
                };
                if obj.kind != ObjectKind::Manipuland {
                    continue;
                }
                if let Some(reason) = manipuland_verdict(asset, obj, b, &p, &opts.rules) {
                    doomed.push((id.clone(), reason));
                }
            }
        }
        for (id, reason) in doomed {
            if state.scene.object(&id).is_some() {
                state.remove_object(&id, MANIPULAND_STAGE, &reason);
                report.removed.push(id);
            }
        }
        report.cleanup = project(state, BTreeMap::new())?;
    }
    Ok(report)
}

/// Indices of the subsets whose free entity settled more than [`ENTITY_SHIFT_M`] or
/// [`ENTITY_TURN_RAD`] from where it was, or into another object (deeper than `threshold`
/// into anything but its own load), with every subset's settled poses applied.
fn entities_moved_too_far(
    state: &SceneState,
    subsets: &[(String, BTreeMap<String, Role>)],
    results: &[SettleReply],
    threshold: f64,
) -> Vec<usize> {
    let mut scene = state.scene.clone();
    let mut out = BTreeSet::new();
    for (i, ((entity, members), result)) in subsets.iter().zip(results).enumerate() {
        if members.get(entity) != Some(&Role::Free) {
            continue;
        }
        let (Some(p), Some(b)) = (
            settled_pose(state, result, entity),
            state.scene.object(entity),
        ) else {
            out.insert(i);
            continue;
        };
        let b = b.world_from_object;
        if (p.translation() - b.translation()).norm() > ENTITY_SHIFT_M
            || p.angle_to(&b) > ENTITY_TURN_RAD
        {
            out.insert(i);
        }
        for (id, role) in members {
            if *role == Role::Free
                && let Some(p) = settled_pose(state, result, id)
                && let Some(o) = scene.objects.iter_mut().find(|o| &o.id == id)
            {
                o.world_from_object = p;
            }
        }
    }
    let posed = posed_objects(&scene, &state.assets);
    for pair in penetrating_pairs(&posed, threshold) {
        for (i, (entity, members)) in subsets.iter().enumerate() {
            if members.get(entity) != Some(&Role::Free) {
                continue;
            }
            let other = if pair.a == *entity {
                &pair.b
            } else if pair.b == *entity {
                &pair.a
            } else {
                continue;
            };
            if members.get(other) != Some(&Role::Free) {
                out.insert(i);
            }
        }
    }
    out.into_iter().collect()
}

/// Removes objects that still penetrate another object deeper than `threshold_m`: of each
/// pair the one that is easier to lose (a small object before furniture; never architecture
/// or welded objects). Returns the removed ids.
fn remove_penetrating(
    state: &mut SceneState,
    threshold_m: f64,
) -> Result<Vec<String>, PhysicsError> {
    let mut removed = Vec::new();
    loop {
        let posed = posed_objects(&state.scene, &state.assets);
        let pairs = penetrating_pairs(&posed, threshold_m);
        let rank = |id: &str| -> Option<u8> {
            let o = state.scene.object(id)?;
            if o.welded || o.kind == ObjectKind::Architecture {
                return None;
            }
            Some(if o.kind == ObjectKind::Manipuland {
                0
            } else {
                1
            })
        };
        let mut victim: Option<(String, String, f64)> = None;
        for p in &pairs {
            let pick = match (rank(&p.a), rank(&p.b)) {
                (Some(ra), Some(rb)) => Some(if ra <= rb { (&p.a, &p.b) } else { (&p.b, &p.a) }),
                (Some(_), None) => Some((&p.a, &p.b)),
                (None, Some(_)) => Some((&p.b, &p.a)),
                (None, None) => None,
            };
            if let Some((v, other)) = pick {
                victim = Some((v.clone(), other.clone(), p.depth));
                break;
            }
        }
        let Some((id, other, depth)) = victim else {
            break;
        };
        state.remove_object(
            &id,
            "post_process",
            &format!(
                "still penetrating {other} by {:.1} mm after projection and settling",
                depth * 1e3
            ),
        );
        removed.push(id);
    }
    Ok(removed)
}
