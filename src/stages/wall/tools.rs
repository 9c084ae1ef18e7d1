//! The wall stage's tools: mount an object at wall coordinates or above a piece of furniture,
//! clear of doors, windows, other wall objects and furniture standing in front.

use nalgebra::Point3;
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::agents::{Access, CategorySpec, ToolError, Toolbox};
use crate::scene::{ObjectKind, Pose, Support, Wall};
use crate::stages::common::{self, ObjectInfo, object_info};
use crate::stages::placement::Footprint;
use crate::stages::room::{RoomFrame, wall_side};
use crate::stages::{RoutedAsset, StageState};

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
    let mut routed = routed;
    // When no wall has room at the typical size, smaller versions (down to the category's
    // minimum, where the router clamps) before giving up: a whiteboard between two windows.
    for scale in SHRINK_STEPS {
        if scale < 1.0 {
            let size = routed.size.map(|v| v * scale);
            routed = state.route_asset(&a.description, Some(size))?;
        }
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
    }
    Err(last.unwrap_or_else(|| ToolError::failed("no walls")))
}

/// Sizes a wall object is tried at, as shares of the size before (typical first).
const SHRINK_STEPS: [f64; 3] = [1.0, 0.75, 0.75];

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
