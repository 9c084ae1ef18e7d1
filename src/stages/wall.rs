//! Wall stage: objects mounted on the walls of one room, placed in wall coordinates (`along_m`
//! from the wall's start, `height_m` of the object's centre), clear of doors, windows, other
//! wall objects and furniture standing in front. Includes the built-in designer and critic.

use nalgebra::Point3;
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};
use serde_json::json;

use super::common::{self, ObjectInfo, object_info};
use super::placement::Footprint;
use super::room::{RoomFrame, wall_side};
use super::{RoutedAsset, StageState};
use crate::agents::{
    Access, AgentCx, AgentError, CategorySpec, Critic, Critique, DesignRequest, Designer, Issue,
    Role, Score, ToolError, Toolbox,
};
use crate::plan::Arrangement;
use crate::scene::{ObjectKind, Pose, Support, Wall};

/// The wall stage's critic categories.
pub fn categories() -> Vec<CategorySpec> {
    vec![
        CategorySpec::new(
            "prompt_following",
            "every requested wall object is present with its count",
        ),
        CategorySpec::new(
            "placement_logic",
            "sensible heights, centred over related furniture, clear of doors, windows and tall furniture",
        ),
        CategorySpec::new(
            "aesthetics",
            "objects spaced evenly, walls neither bare nor cluttered",
        ),
        CategorySpec::new(
            "physical_feasibility",
            "no wall object penetrates furniture, walls or another object",
        ),
    ]
}

/// A rectangle in a wall's plane.
#[derive(Debug, Clone, Copy)]
struct Rect {
    x0: f64,
    x1: f64,
    z0: f64,
    z1: f64,
}

impl Rect {
    fn overlaps(&self, o: &Rect, gap: f64) -> bool {
        self.x0 < o.x1 + gap && o.x0 < self.x1 + gap && self.z0 < o.z1 + gap && o.z0 < self.z1 + gap
    }
}

/// Default centre height of a wall object of height `h`.
fn default_height(category: &str, h: f64, wall_height: f64) -> f64 {
    let c: f64 = match category {
        "tv" | "television" | "wall-mounted tv" => 1.3,
        "clock" | "wall clock" | "sconce" => 1.9,
        "whiteboard" | "chalkboard" | "projector screen" => 1.45,
        "wall cabinet" | "medicine cabinet" => 1.65,
        _ => 1.55,
    };
    c.min(wall_height - 0.1 - h / 2.0).max(h / 2.0 + 0.3)
}

/// The blocked rectangles of a wall: openings, existing wall objects, furniture in front.
fn blocked(state: &StageState, wall: &Wall, ignore: Option<&str>) -> Vec<(String, Rect)> {
    let mut out = Vec::new();
    for o in &wall.openings {
        out.push((
            format!("the {:?} {}", o.kind, o.id).to_lowercase(),
            Rect {
                x0: o.center - o.width / 2.0,
                x1: o.center + o.width / 2.0,
                z0: o.bottom,
                z1: o.bottom + o.height,
            },
        ));
    }
    let wall_from_world = wall.world_from_wall().inverse();
    for o in state.room_objects() {
        if Some(o.id.as_str()) == ignore {
            continue;
        }
        let Some(rec) = state.scene.scene.assets.get(&o.asset) else {
            continue;
        };
        let on_this_wall = matches!(&o.support, Support::Wall { wall: w } if *w == wall.id);
        let near_furniture = o.kind == ObjectKind::Furniture;
        if !on_this_wall && !near_furniture {
            continue;
        }
        // Project the object's bounds into the wall frame.
        let [lo, hi] = rec.bounds;
        let (mut x0, mut x1, mut y0, mut z0, mut z1) = (
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
        );
        for x in [lo[0], hi[0]] {
            for y in [lo[1], hi[1]] {
                for z in [lo[2], hi[2]] {
                    let p = wall_from_world.transform_point(
                        &o.world_from_object.transform_point(&Point3::new(x, y, z)),
                    );
                    x0 = x0.min(p.x);
                    x1 = x1.max(p.x);
                    y0 = y0.min(p.y);
                    z0 = z0.min(p.z);
                    z1 = z1.max(p.z);
                }
            }
        }
        // Furniture counts when it stands within 0.5 m of the wall's face.
        if near_furniture && y0 > wall.thickness / 2.0 + 0.5 {
            continue;
        }
        out.push((o.id.clone(), Rect { x0, x1, z0, z1 }));
    }
    out
}

/// Pose of a wall object whose bounds' centre sits at (`along`, `height`) on `wall`.
fn wall_pose(wall: &Wall, rec: &crate::scene::AssetRecord, along: f64, height: f64) -> Pose {
    let [lo, hi] = rec.bounds;
    wall.world_from_wall().compose(&Pose::from_xyz(
        along - (lo[0] + hi[0]) / 2.0,
        wall.thickness / 2.0 + 0.003 - lo[1],
        height - (lo[2] + hi[2]) / 2.0,
    ))
}

fn try_mount(
    state: &mut StageState,
    routed: &RoutedAsset,
    wall: &Wall,
    along: Option<f64>,
    height: Option<f64>,
    min_bottom: Option<f64>,
) -> Result<String, ToolError> {
    let rec = state.scene.scene.assets[&routed.asset].clone();
    let room = state.room()?.clone();
    let [w, _, h] = routed.size;
    let mut z = height.unwrap_or_else(|| default_height(&routed.category, h, room.wall_height));
    if let Some(b) = min_bottom {
        z = z.max(b + h / 2.0);
    }
    if z + h / 2.0 > room.wall_height - 0.02 || z - h / 2.0 < 0.05 {
        return Err(ToolError::failed(format!(
            "a {} {:.2} m tall does not fit between floor and ceiling at {:.2} m",
            routed.category, h, z
        )));
    }
    let (lo, hi) = (
        wall.thickness + w / 2.0,
        wall.length() - wall.thickness - w / 2.0,
    );
    if hi < lo {
        return Err(ToolError::failed(format!(
            "wall {} is too short for a {:.2} m wide {}",
            wall.id, w, routed.category
        )));
    }
    let blocks = blocked(state, wall, None);
    let mut xs: Vec<f64> = Vec::new();
    let mut x = lo;
    while x <= hi + 1e-9 {
        xs.push(x);
        x += 0.05;
    }
    let target = along.unwrap_or((lo + hi) / 2.0);
    if along.is_some() {
        xs.retain(|x| (x - target).abs() < 0.026);
        if xs.is_empty() {
            return Err(ToolError::failed(format!(
                "along_m {target:.2} is off wall {} (valid {lo:.2}..{hi:.2})",
                wall.id
            )));
        }
    }
    xs.sort_by(|a, b| (a - target).abs().total_cmp(&(b - target).abs()));
    let mut reason = String::new();
    for x in xs {
        let r = Rect {
            x0: x - w / 2.0,
            x1: x + w / 2.0,
            z0: z - h / 2.0,
            z1: z + h / 2.0,
        };
        match blocks.iter().find(|(_, b)| b.overlaps(&r, 0.05)) {
            Some((who, _)) => reason = format!("it would overlap {who}"),
            None => {
                let pose = wall_pose(wall, &rec, x, z);
                return Ok(state.add_routed(
                    routed,
                    ObjectKind::Wall,
                    pose,
                    Support::Wall {
                        wall: wall.id.clone(),
                    },
                ));
            }
        }
    }
    Err(ToolError::failed(format!(
        "no room on wall {} for a {} at {z:.2} m: {reason}",
        wall.id, routed.category
    )))
}

/// Mount an object on a wall.
#[derive(Debug, Deserialize, JsonSchema)]
pub struct MountArgs {
    /// What to mount, e.g. "framed painting", "round mirror".
    pub description: String,
    /// Wall id or side (`north`, `south`, `east`, `west`); the wall with most free space when omitted.
    #[serde(default)]
    pub wall: Option<String>,
    /// Centre along the wall from its start, metres; the free spot nearest the middle when omitted.
    #[serde(default)]
    pub along_m: Option<f64>,
    /// Height of the centre above the floor, metres; a typical height for the object when omitted.
    #[serde(default)]
    pub height_m: Option<f64>,
}

/// Mount an object on the wall above a piece of furniture.
#[derive(Debug, Deserialize, JsonSchema)]
pub struct AboveArgs {
    /// What to mount.
    pub description: String,
    /// Id of the furniture to hang above (bed, sofa, desk, sink, TV stand...).
    pub target: String,
    /// Gap between the furniture's top and the object's bottom, metres (default 0.25).
    #[serde(default)]
    pub gap_m: Option<f64>,
}

/// Result of a mounting tool.
#[derive(Debug, Serialize, JsonSchema)]
pub struct MountResult {
    /// The new object.
    pub placed: Option<ObjectInfo>,
    /// Remarks (a generic stand-in for an unknown noun, parts for another stage).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub notes: Vec<String>,
}

fn free_length(state: &StageState, wall: &Wall) -> f64 {
    let blocks = blocked(state, wall, None);
    let used: f64 = blocks.iter().map(|(_, r)| (r.x1 - r.x0).max(0.0)).sum();
    wall.length() - used
}

fn mount(state: &mut StageState, a: MountArgs) -> Result<MountResult, ToolError> {
    let routed = state.route_asset(&a.description, None)?;
    let room = state.room()?.clone();
    let frame = RoomFrame::new(&room);
    let mut walls: Vec<Wall> = match &a.wall {
        Some(k) => vec![frame.wall(k).cloned().ok_or_else(|| {
            ToolError::bad_args(format!(
                "no wall {k:?}; walls: {}",
                room.walls
                    .iter()
                    .map(|w| format!("{} ({})", w.id, wall_side(w)))
                    .collect::<Vec<_>>()
                    .join(", ")
            ))
        })?],
        None => room.walls.clone(),
    };
    if a.wall.is_none() {
        walls.sort_by(|x, y| free_length(state, y).total_cmp(&free_length(state, x)));
    }
    let mut last = None;
    for w in &walls {
        match try_mount(state, &routed, w, a.along_m, a.height_m, None) {
            Ok(id) => {
                return Ok(MountResult {
                    placed: object_info(state, &frame, &id),
                    notes: routed.notes.clone(),
                });
            }
            Err(e) => last = Some(e),
        }
    }
    Err(last.unwrap_or_else(|| ToolError::failed("no walls")))
}

fn mount_above(state: &mut StageState, a: AboveArgs) -> Result<MountResult, ToolError> {
    let target = state
        .scene
        .scene
        .object(&a.target)
        .cloned()
        .ok_or_else(|| ToolError::failed(format!("no object {:?}", a.target)))?;
    let routed = state.route_asset(&a.description, None)?;
    let room = state.room()?.clone();
    let frame = RoomFrame::new(&room);
    let trec = state.scene.scene.assets[&target.asset].clone();
    let tfp = Footprint::of(&trec, &target.world_from_object);
    // The wall behind the target: nearest wall face to the footprint centre.
    let mut best: Option<(&Wall, f64, f64)> = None;
    for w in &room.walls {
        let p = w.world_from_wall().inverse().transform_point(&Point3::new(
            tfp.center[0],
            tfp.center[1],
            0.0,
        ));
        let dist = p.y - w.thickness / 2.0;
        if dist > 0.0 && p.x > 0.0 && p.x < w.length() && best.is_none_or(|(_, d, _)| dist < d) {
            best = Some((w, dist, p.x));
        }
    }
    let (wall, dist, along) =
        best.ok_or_else(|| ToolError::failed(format!("{} is not in front of a wall", a.target)))?;
    if dist > tfp.half[0].max(tfp.half[1]) + 0.6 {
        return Err(ToolError::failed(format!(
            "{} stands {:.2} m from the nearest wall; mount it on a wall instead",
            a.target, dist
        )));
    }
    let top = tfp.z[1];
    let id = try_mount(
        state,
        &routed,
        &wall.clone(),
        Some(along),
        None,
        Some(top + a.gap_m.unwrap_or(0.25)),
    )?;
    Ok(MountResult {
        placed: object_info(state, &frame, &id),
        notes: routed.notes.clone(),
    })
}

/// The wall stage's tools.
pub fn toolbox() -> Toolbox<StageState> {
    let mut t = Toolbox::new();
    common::register(&mut t);
    t.add("mount_on_wall", "Mount an object on a wall at a position and height, or at the best free spot; refuses spots over doors, windows, other wall objects or tall furniture.", Access::Modify, mount);
    t.add("mount_above", "Mount an object on the wall above a piece of furniture (a painting above the sofa, a mirror above the sink), centred on it.", Access::Modify, mount_above);
    t
}

/// Targets of an `Above` want present in the room.
fn targets(state: &StageState, noun: &str) -> Vec<String> {
    state
        .room_objects()
        .filter(|o| {
            crate::assets::router::naming::object_is(&state.scene.scene, noun, o)
                && o.kind == ObjectKind::Furniture
        })
        .map(|o| o.id.clone())
        .collect()
}

/// The built-in wall designer.
#[derive(Debug, Default)]
pub struct BuiltinWallDesigner;

impl Designer<StageState> for BuiltinWallDesigner {
    fn design(
        &mut self,
        state: &mut StageState,
        _request: &DesignRequest,
        cx: &mut AgentCx<'_, StageState>,
    ) -> Result<String, AgentError> {
        let _ = cx.call(state, Role::Designer, "observe_room", json!({}));
        for want in state.plan.wall.clone() {
            let have = common::present_count(state, &want.noun);
            let mut need = want.count.saturating_sub(have);
            if let Arrangement::Above { target } = &want.arrangement {
                for t in targets(state, target) {
                    if need == 0 {
                        break;
                    }
                    if cx
                        .call(
                            state,
                            Role::Designer,
                            "mount_above",
                            json!({"description": want.description, "target": t}),
                        )
                        .is_ok()
                    {
                        need -= 1;
                    }
                }
            }
            for _ in 0..need {
                if cx
                    .call(
                        state,
                        Role::Designer,
                        "mount_on_wall",
                        json!({"description": want.description}),
                    )
                    .is_err()
                {
                    break;
                }
            }
        }
        let n = state
            .room_objects()
            .filter(|o| o.kind == ObjectKind::Wall)
            .count();
        Ok(format!("{n} wall objects"))
    }
}

/// The built-in wall critic.
#[derive(Debug, Default)]
pub struct BuiltinWallCritic;

fn requested_score(
    state: &StageState,
    wants: &[crate::plan::Want],
    issues: &mut Vec<Issue>,
) -> (f64, String) {
    let (mut wanted, mut got) = (0u32, 0u32);
    for w in wants.iter().filter(|w| w.explicit) {
        let have = common::present_count(state, &w.noun);
        wanted += w.count;
        got += have.min(w.count);
        if have < w.count {
            issues.push(Issue {
                objects: vec![],
                description: format!("add {} more {}", w.count - have, w.noun),
            });
        }
    }
    let cov = if wanted == 0 {
        1.0
    } else {
        f64::from(got) / f64::from(wanted)
    };
    (10.0 * cov, format!("{got} of {wanted} requested present"))
}

/// Penetrating pairs involving an object of `kind`, each an issue. A collision check that
/// fails makes the critique unusable: it is never counted as no collisions.
fn collisions_of(
    state: &mut StageState,
    cx: &mut AgentCx<'_, StageState>,
    kind: ObjectKind,
    issues: &mut Vec<Issue>,
) -> Result<usize, AgentError> {
    let v = cx
        .call(state, Role::Critic, "check_collisions", json!({}))
        .map_err(|e| AgentError::Unusable {
            role: "critic",
            stage: kind.as_str().into(),
            message: format!("the collision check failed: {}", e.message),
        })?;
    let mut n = 0;
    for p in v["collisions"].as_array().into_iter().flatten() {
        let ids: Vec<String> = ["a", "b"]
            .iter()
            .filter_map(|k| p[*k].as_str().map(str::to_string))
            .collect();
        if ids
            .iter()
            .any(|id| state.scene.scene.object(id).is_some_and(|o| o.kind == kind))
        {
            n += 1;
            issues.push(Issue {
                objects: ids.clone(),
                description: format!("{} overlap; move one", ids.join(" and ")),
            });
        }
    }
    Ok(n)
}

/// Closest edge-to-edge gap at which two wall objects at overlapping heights still read as
/// separate pieces, metres.
const WALL_GAP_M: f64 = 0.08;

/// Pairs of the room's wall objects closer than [`WALL_GAP_M`], each an issue.
fn crowded_wall_pairs(state: &StageState, issues: &mut Vec<Issue>) -> usize {
    let mounted: Vec<(String, Footprint)> = state
        .room_objects()
        .filter(|o| o.kind == ObjectKind::Wall)
        .filter_map(|o| {
            let rec = state.scene.scene.assets.get(&o.asset)?;
            Some((o.id.clone(), Footprint::of(rec, &o.world_from_object)))
        })
        .collect();
    let mut n = 0;
    for (i, (a, fa)) in mounted.iter().enumerate() {
        for (b, fb) in &mounted[i + 1..] {
            if fa.overlaps(fb, WALL_GAP_M) {
                n += 1;
                issues.push(Issue {
                    objects: vec![a.clone(), b.clone()],
                    description: format!(
                        "{a} and {b} are closer than {:.0} cm; space them",
                        WALL_GAP_M * 100.0
                    ),
                });
            }
        }
    }
    n
}

fn clamp_score(c: &str, v: f64, r: String) -> Score {
    Score {
        category: c.into(),
        score: v.round().clamp(0.0, 10.0) as u8,
        reason: r,
    }
}

impl Critic<StageState> for BuiltinWallCritic {
    fn critique(
        &mut self,
        state: &mut StageState,
        cx: &mut AgentCx<'_, StageState>,
    ) -> Result<Critique, AgentError> {
        let _ = cx.call(state, Role::Critic, "observe_room", json!({}));
        let mut issues = Vec::new();
        let wants = state.plan.wall.clone();
        let (pf, pf_reason) = requested_score(state, &wants, &mut issues);
        let mounted: Vec<(String, f64, f64)> = state
            .room_objects()
            .filter(|o| o.kind == ObjectKind::Wall)
            .filter_map(|o| {
                let rec = state.scene.scene.assets.get(&o.asset)?;
                let c = o.world_from_object.translation().z
                    + (rec.bounds[0][2] + rec.bounds[1][2]) / 2.0;
                Some((o.id.clone(), c, rec.bounds[1][2] - rec.bounds[0][2]))
            })
            .collect();
        let mut odd = 0;
        for (id, c, _) in &mounted {
            if !(0.9..=2.3).contains(c) {
                odd += 1;
                issues.push(Issue {
                    objects: vec![id.clone()],
                    description: format!(
                        "{id} hangs with its centre at {c:.2} m; 1.3-1.7 m reads best"
                    ),
                });
            }
        }
        let logic = if mounted.is_empty() {
            10.0
        } else {
            10.0 - 10.0 * odd as f64 / mounted.len() as f64
        };
        // Aesthetics, measured: crowding (pieces closer than a hand's width) and a wall left
        // bare when wall objects were planned.
        let crowded = crowded_wall_pairs(state, &mut issues);
        let bare = mounted.is_empty() && !wants.is_empty();
        let aesthetics = 10.0 - 3.0 * crowded as f64 - if bare { 6.0 } else { 0.0 };
        let n = collisions_of(state, cx, ObjectKind::Wall, &mut issues)?;
        Ok(Critique {
            scores: vec![
                clamp_score("prompt_following", pf, pf_reason),
                clamp_score(
                    "placement_logic",
                    logic,
                    format!("{odd} of {} at unusual heights", mounted.len()),
                ),
                clamp_score(
                    "aesthetics",
                    aesthetics,
                    format!(
                        "{} wall objects, {crowded} pairs closer than {:.0} cm{}",
                        mounted.len(),
                        WALL_GAP_M * 100.0,
                        if bare {
                            ", none of the planned ones hung"
                        } else {
                            ""
                        }
                    ),
                ),
                clamp_score(
                    "physical_feasibility",
                    10.0 - 3.0 * n as f64,
                    format!("{n} penetrating pairs"),
                ),
            ],
            issues,
        })
    }
}

/// Shared by the ceiling critic.
pub(crate) fn requested_and_collisions(
    state: &mut StageState,
    cx: &mut AgentCx<'_, StageState>,
    wants: &[crate::plan::Want],
    kind: ObjectKind,
    issues: &mut Vec<Issue>,
) -> Result<(Score, Score), AgentError> {
    let (pf, r) = requested_score(state, wants, issues);
    let n = collisions_of(state, cx, kind, issues)?;
    Ok((
        clamp_score("prompt_following", pf, r),
        clamp_score(
            "physical_feasibility",
            10.0 - 3.0 * n as f64,
            format!("{n} penetrating pairs"),
        ),
    ))
}
