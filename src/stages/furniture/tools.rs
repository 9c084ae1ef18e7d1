//! The furniture stage's tools: place a piece at coordinates, against a wall, in a corner, in
//! the open middle, around a table or facing a target, each checked against the floor, the
//! other furniture and the keep-out zones of doors and windows.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::agents::{Access, CategorySpec, ToolError, Toolbox};
use crate::scene::{ObjectKind, Pose, Support};
use crate::stages::common::{self, ObjectInfo, object_info};
use crate::stages::placement::{Footprint, against_wall, find_floor_spot, keep_out_zones};
use crate::stages::room::{RoomFrame, room_pose, wall_side, wrap_angle, yaw_facing};
use crate::stages::{RoutedAsset, StageState};

/// Gap kept between furniture footprints, metres.
pub const GAP: f64 = 0.05;
/// Gap between a table's edge and the front of a chair around it, metres (just over [`GAP`]).
const SEAT_GAP: f64 = GAP + 0.02;

/// The furniture stage's critic categories.
pub fn categories() -> Vec<CategorySpec> {
    vec![
        CategorySpec::new(
            "prompt_following",
            "every requested piece is present with the requested count; nothing excluded is present",
        ),
        CategorySpec::new(
            "functionality",
            "pieces are usable: chairs face their table, storage and beds stand against walls, seating faces its focus",
        ),
        CategorySpec::new(
            "spatial_layout",
            "balanced use of the floor: neither empty nor crammed, pieces inside the room, doors and windows clear",
        ),
        CategorySpec::new(
            "reachability",
            "a robot (0.25 m radius) reaches every piece from the door through one connected free region",
        ),
        CategorySpec::new(
            "physical_feasibility",
            "no piece penetrates another piece or a wall",
        ),
    ]
}

/// Optional size override shared by the placement tools.
#[derive(Debug, Deserialize, JsonSchema, Default, Clone, Copy)]
pub struct SizeArg {
    /// Wanted size (width x, depth y, height z) in metres; the generator clamps it to what is
    /// plausible for the category.
    #[serde(default)]
    pub size_m: Option<[f64; 3]>,
}

/// Place at explicit coordinates.
#[derive(Debug, Deserialize, JsonSchema)]
pub struct PlaceArgs {
    /// What to place, e.g. "oak dining table", "office chair".
    pub description: String,
    /// Room x of the object's centre, metres.
    pub x: f64,
    /// Room y of the object's centre, metres.
    pub y: f64,
    /// Rotation, degrees (0: front faces north, 90: west, 180: south, -90: east).
    #[serde(default)]
    pub yaw_deg: f64,
    /// Optional size.
    #[serde(flatten)]
    pub size: SizeArg,
}

/// Place with the back against a wall.
#[derive(Debug, Deserialize, JsonSchema)]
pub struct WallArgs {
    /// What to place.
    pub description: String,
    /// Wall id or side (`north`, `south`, `east`, `west`); any free wall when omitted.
    #[serde(default)]
    pub wall: Option<String>,
    /// Position of the object's centre along the wall from its start, metres; the first free
    /// position when omitted.
    #[serde(default)]
    pub along_m: Option<f64>,
    /// Optional size.
    #[serde(flatten)]
    pub size: SizeArg,
}

/// Place in a corner.
#[derive(Debug, Deserialize, JsonSchema)]
pub struct CornerArgs {
    /// What to place.
    pub description: String,
    /// `north_east`, `north_west`, `south_east` or `south_west`; any free corner when omitted.
    #[serde(default)]
    pub corner: Option<String>,
    /// Optional size.
    #[serde(flatten)]
    pub size: SizeArg,
}

/// Place in the open middle of the room.
#[derive(Debug, Deserialize, JsonSchema)]
pub struct CenterArgs {
    /// What to place.
    pub description: String,
    /// Free space to keep around it, metres (e.g. 0.6 for chairs around a table).
    #[serde(default)]
    pub clearance_m: Option<f64>,
    /// Optional size.
    #[serde(flatten)]
    pub size: SizeArg,
}

/// Place objects around a parent, facing it.
#[derive(Debug, Deserialize, JsonSchema)]
pub struct AroundArgs {
    /// Id of the table, desk or counter to sit around.
    pub parent: String,
    /// What to place, e.g. "dining chair".
    pub description: String,
    /// How many.
    pub count: u32,
}

/// Place an object facing a target.
#[derive(Debug, Deserialize, JsonSchema)]
pub struct FacingArgs {
    /// What to place, e.g. "sofa".
    pub description: String,
    /// Id of the object to face.
    pub target: String,
    /// Distance between the two footprints, metres (default 0.6).
    #[serde(default)]
    pub distance_m: Option<f64>,
}

/// Where a piece goes relative to another object (`place_relative`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum Relation {
    /// At one side of the target (its right first, then its left), the same heading, the
    /// backs in line: a nightstand beside a bed, a lamp next to a sofa.
    Beside,
    /// In front of the target, facing it: a coffee table in front of a sofa.
    InFront,
    /// At the target's back, the same heading: a console table behind a sofa.
    Behind,
    /// Midway between the target and `second`: facing one of them when they face each other
    /// (a coffee table between two sofas), else with their heading (a nightstand between two
    /// beds).
    Between,
}

/// Place a piece relative to one object (or between two).
#[derive(Debug, Deserialize, JsonSchema)]
pub struct RelativeArgs {
    /// What to place, e.g. "nightstand".
    pub description: String,
    /// Id of the object it is placed relative to.
    pub target: String,
    /// beside, in_front, behind or between.
    pub relation: Relation,
    /// Id of the second object, for "between".
    #[serde(default)]
    pub second: Option<String>,
    /// Gap between the footprints, metres (default: beside 0.05, in front 0.4, behind 0.1).
    #[serde(default)]
    pub gap_m: Option<f64>,
}

/// What a placement tool did.
#[derive(Debug, Serialize, JsonSchema, Default)]
pub struct PlaceResult {
    /// The new objects.
    pub placed: Vec<ObjectInfo>,
    /// Remarks (e.g. fewer placed than asked and why).
    pub notes: Vec<String>,
}

/// Footprints placed furniture must keep clear of: other furniture and keep-out zones.
pub fn obstacles(state: &StageState, height: f64) -> Result<Vec<(String, Footprint)>, ToolError> {
    let room = state.room()?;
    let mut out: Vec<(String, Footprint)> = common::floor_footprints(state);
    for zone in keep_out_zones(room) {
        if zone.z[0] < height {
            out.push(("the door or window keep-out zone".to_string(), zone));
        }
    }
    Ok(out)
}

/// Adds a furniture object at `pose` after checking the floor and obstacles.
pub fn try_place(
    state: &mut StageState,
    routed: &RoutedAsset,
    pose: Pose,
) -> Result<String, ToolError> {
    let room = state.room()?.clone();
    let rec = state
        .scene
        .scene
        .assets
        .get(&routed.asset)
        .cloned()
        .ok_or_else(|| ToolError::failed("asset vanished"))?;
    let fp = Footprint::of(&rec, &pose);
    if !fp.inside(&room.floor_polygon) {
        return Err(ToolError::failed(format!(
            "a {} ({:.2} x {:.2} m) does not fit inside the room there",
            routed.category, routed.size[0], routed.size[1]
        )));
    }
    if let Some((id, _)) = obstacles(state, routed.size[2])?
        .iter()
        .find(|(_, o)| o.overlaps(&fp, GAP))
    {
        return Err(ToolError::failed(format!(
            "a {} there would overlap {id}; choose another spot or move {id} first",
            routed.category
        )));
    }
    let room = state.room.clone();
    Ok(state.add_routed(routed, ObjectKind::Furniture, pose, Support::Floor { room }))
}

fn result_for(
    state: &StageState,
    ids: &[String],
    notes: Vec<String>,
) -> Result<PlaceResult, ToolError> {
    let room = state.room()?.clone();
    let frame = RoomFrame::new(&room);
    Ok(PlaceResult {
        placed: ids
            .iter()
            .filter_map(|id| object_info(state, &frame, id))
            .collect(),
        notes,
    })
}

fn place_object(state: &mut StageState, a: PlaceArgs) -> Result<PlaceResult, ToolError> {
    let routed = state.route_asset(&a.description, a.size.size_m)?;
    let room = state.room()?.clone();
    let frame = RoomFrame::new(&room);
    let id = try_place(state, &routed, room_pose(&frame, a.x, a.y, a.yaw_deg))?;
    result_for(state, &[id], routed.notes.clone())
}

/// Free positions along `wall` for an object of bounds `rec`, nearest to `along` first.
fn wall_candidates(
    state: &StageState,
    wall: &crate::scene::Wall,
    rec: &crate::scene::AssetRecord,
    along: Option<f64>,
) -> Result<Option<Pose>, ToolError> {
    let width = rec.bounds[1][0] - rec.bounds[0][0];
    let height = rec.bounds[1][2] - rec.bounds[0][2];
    let len = wall.length();
    let lo = wall.thickness + width / 2.0;
    let hi = len - wall.thickness - width / 2.0;
    if hi < lo {
        return Ok(None);
    }
    let obstacles = obstacles(state, height)?;
    let room = state.room()?;
    let mut positions: Vec<f64> = Vec::new();
    let mut x = lo;
    while x <= hi + 1e-9 {
        positions.push(x);
        x += 0.05;
    }
    let target = along.unwrap_or(lo);
    positions.sort_by(|a, b| (a - target).abs().total_cmp(&(b - target).abs()));
    for x in positions {
        let pose = against_wall(wall, rec, x, 0.01);
        let fp = Footprint::of(rec, &pose);
        if fp.inside(&room.floor_polygon) && !obstacles.iter().any(|(_, o)| o.overlaps(&fp, GAP)) {
            return Ok(Some(pose));
        }
    }
    Ok(None)
}

fn place_against_wall(state: &mut StageState, a: WallArgs) -> Result<PlaceResult, ToolError> {
    let routed = state.route_asset(&a.description, a.size.size_m)?;
    let room = state.room()?.clone();
    let frame = RoomFrame::new(&room);
    let rec = state.scene.scene.assets[&routed.asset].clone();
    let walls: Vec<&crate::scene::Wall> = match &a.wall {
        Some(key) => vec![frame.wall(key).ok_or_else(|| {
            ToolError::bad_args(format!(
                "no wall {key:?}; walls: {}",
                room.walls
                    .iter()
                    .map(|w| format!("{} ({})", w.id, wall_side(w)))
                    .collect::<Vec<_>>()
                    .join(", ")
            ))
        })?],
        None => room.walls.iter().collect(),
    };
    for wall in walls {
        if let Some(pose) = wall_candidates(state, wall, &rec, a.along_m)? {
            let id = try_place(state, &routed, pose)?;
            return result_for(state, &[id], routed.notes.clone());
        }
    }
    Err(ToolError::failed(format!(
        "no free stretch of {} for a {} {:.2} m wide; free space first or try another wall",
        a.wall.as_deref().unwrap_or("any wall"),
        routed.category,
        routed.size[0]
    )))
}

fn place_in_corner(state: &mut StageState, a: CornerArgs) -> Result<PlaceResult, ToolError> {
    let routed = state.route_asset(&a.description, a.size.size_m)?;
    let room = state.room()?.clone();
    let frame = RoomFrame::new(&room);
    let rec = state.scene.scene.assets[&routed.asset].clone();
    let corners = [
        ("south_west", 0.0, 0.0),
        ("south_east", 1.0, 0.0),
        ("north_east", 1.0, 1.0),
        ("north_west", 0.0, 1.0),
    ];
    let wanted: Vec<_> = match &a.corner {
        Some(c) => {
            let c = c.to_ascii_lowercase().replace([' ', '-'], "_");
            let found: Vec<_> = corners.iter().filter(|(n, ..)| *n == c).collect();
            if found.is_empty() {
                return Err(ToolError::bad_args(format!(
                    "unknown corner {c:?}; use north_east, north_west, south_east or south_west"
                )));
            }
            found
        }
        None => corners.iter().collect(),
    };
    let obstacles = obstacles(state, routed.size[2])?;
    let (w, d) = (routed.size[0], routed.size[1]);
    for (_, fx, fy) in wanted {
        let x = if *fx == 0.0 {
            w / 2.0 + 0.02
        } else {
            frame.size[0] - w / 2.0 - 0.02
        };
        let y = if *fy == 0.0 {
            d / 2.0 + 0.02
        } else {
            frame.size[1] - d / 2.0 - 0.02
        };
        // Face out of the corner, towards the room centre, snapped to the nearest wall normal.
        let face = yaw_facing(frame.to_world(x, y), frame.center_world());
        let yaw = (face / std::f64::consts::FRAC_PI_2).round() * std::f64::consts::FRAC_PI_2;
        let mut pose = room_pose(&frame, x, y, yaw.to_degrees());
        // Recentre so the rotated footprint sits in the corner.
        let fp = Footprint::of(&rec, &pose);
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for c in fp.corners() {
            for k in 0..2 {
                lo[k] = lo[k].min(c[k]);
                hi[k] = hi[k].max(c[k]);
            }
        }
        let (hx, hy) = ((hi[0] - lo[0]) / 2.0, (hi[1] - lo[1]) / 2.0);
        let cx = if *fx == 0.0 {
            hx + 0.02
        } else {
            frame.size[0] - hx - 0.02
        };
        let cy = if *fy == 0.0 {
            hy + 0.02
        } else {
            frame.size[1] - hy - 0.02
        };
        let shift = frame.to_world(cx, cy);
        let t = pose.translation();
        pose = pose.with_translation(nalgebra::Vector3::new(
            t.x + shift[0] - fp.center[0],
            t.y + shift[1] - fp.center[1],
            0.0,
        ));
        let fp = Footprint::of(&rec, &pose);
        if fp.inside(&room.floor_polygon) && !obstacles.iter().any(|(_, o)| o.overlaps(&fp, GAP)) {
            let id = try_place(state, &routed, pose)?;
            return result_for(state, &[id], routed.notes.clone());
        }
    }
    Err(ToolError::failed(format!(
        "no free corner for a {}",
        routed.category
    )))
}

fn place_in_center(state: &mut StageState, a: CenterArgs) -> Result<PlaceResult, ToolError> {
    let routed = state.route_asset(&a.description, a.size.size_m)?;
    let room = state.room()?.clone();
    let frame = RoomFrame::new(&room);
    let rec = state.scene.scene.assets[&routed.asset].clone();
    let obstacles: Vec<Footprint> = obstacles(state, routed.size[2])?
        .into_iter()
        .map(|(_, f)| f)
        .collect();
    // Long side along the room's long axis first.
    let long = if frame.size[0] >= frame.size[1] {
        0.0
    } else {
        std::f64::consts::FRAC_PI_2
    };
    let yaws = [long, long + std::f64::consts::FRAC_PI_2];
    let wanted = a.clearance_m.unwrap_or(0.0).clamp(0.0, 2.0);
    let mut clearances = vec![[wanted, wanted], [0.0, wanted], [0.0, 0.0]];
    clearances.dedup();
    for cl in clearances {
        if let Some(pose) = find_floor_spot(
            &room.floor_polygon,
            &obstacles,
            &rec,
            frame.center_world(),
            &yaws,
            cl,
            GAP,
        ) {
            let id = try_place(state, &routed, pose)?;
            let notes = if cl[0] < wanted || cl[1] < wanted {
                vec![format!(
                    "placed with less than {wanted:.2} m of clearance on some sides"
                )]
            } else {
                vec![]
            };
            return result_for(state, &[id], [routed.notes.clone(), notes].concat());
        }
    }
    Err(ToolError::failed(format!(
        "no open floor left for a {}",
        routed.category
    )))
}

/// Seat poses around a table-like parent of footprint `parent_size`, in the parent's frame:
/// `count` seats spread evenly over the two long sides (facing each other), the ends used only
/// when the long sides are full. Fewer poses than `count` when the table is too small.
/// Seat poses around a parent of footprint `parent_size` (its frame: +Y is the front), facing
/// it: first the arrangement for `count` seats (the front side first, so a desk against a wall
/// gets its chair in front; then the back; then the ends), then every other slot as a fallback
/// for seats that do not fit where the arrangement puts them.
fn seats(parent_size: [f64; 2], chair: [f64; 2], count: usize) -> Vec<Pose> {
    let (tw, td) = (parent_size[0], parent_size[1]);
    let (cw, cd) = (chair[0], chair[1]);
    let max_per_side = ((tw / (cw + 0.12)).floor() as usize).max(1);
    let side = |k: usize, n: usize| -> Vec<Pose> {
        let (y, yaw) = if k == 0 {
            (td / 2.0 + cd / 2.0 + SEAT_GAP, std::f64::consts::PI)
        } else {
            (-(td / 2.0 + cd / 2.0 + SEAT_GAP), 0.0)
        };
        (0..n)
            .map(|i| {
                let x = -tw / 2.0 + tw * (i as f64 + 0.5) / n as f64;
                Pose::from_xyz_yaw(x, y, 0.0, yaw)
            })
            .collect()
    };
    let ends = [
        Pose::from_xyz_yaw(
            -(tw / 2.0 + cd / 2.0 + SEAT_GAP),
            0.0,
            0.0,
            -std::f64::consts::FRAC_PI_2,
        ),
        Pose::from_xyz_yaw(
            tw / 2.0 + cd / 2.0 + SEAT_GAP,
            0.0,
            0.0,
            std::f64::consts::FRAC_PI_2,
        ),
    ];
    let on_long = count.min(2 * max_per_side);
    let mut out = side(0, on_long.div_ceil(2));
    out.extend(side(1, on_long / 2));
    let end_fits = td >= cw + 0.05;
    if end_fits {
        out.extend(ends.iter().take(count.saturating_sub(on_long)).copied());
    }
    // Fallbacks: every slot of both sides, then the ends.
    let mut more = side(0, max_per_side);
    more.extend(side(1, max_per_side));
    if end_fits {
        more.extend(ends);
    }
    for p in more {
        let t = p.translation();
        if !out
            .iter()
            .any(|q| (q.translation() - t).norm() < 0.5 * cw.min(cd))
        {
            out.push(p);
        }
    }
    out
}

fn place_around(state: &mut StageState, a: AroundArgs) -> Result<PlaceResult, ToolError> {
    if a.count == 0 || a.count > 24 {
        return Err(ToolError::bad_args("count must be between 1 and 24"));
    }
    let parent = state
        .scene
        .scene
        .object(&a.parent)
        .cloned()
        .ok_or_else(|| {
            ToolError::failed(format!(
                "no object {:?}; observe the room for ids",
                a.parent
            ))
        })?;
    let routed = state.route_asset(&a.description, None)?;
    let prec = state.scene.scene.assets[&parent.asset].clone();
    let [plo, phi] = prec.bounds;
    // Seats relative to the parent's footprint centre.
    let pc = Pose::from_xyz((plo[0] + phi[0]) / 2.0, (plo[1] + phi[1]) / 2.0, 0.0);
    let candidates = seats(
        [phi[0] - plo[0], phi[1] - plo[1]],
        [routed.size[0], routed.size[1]],
        a.count as usize,
    );
    let mut ids = Vec::new();
    let mut notes = Vec::new();
    for seat in candidates {
        if ids.len() as u32 >= a.count {
            break;
        }
        let t = parent
            .world_from_object
            .compose(&pc)
            .compose(&seat)
            .translation();
        // Upright: keep only the yaw of the composed pose.
        let yaw = parent.world_from_object.compose(&seat).yaw();
        let pose = Pose::from_xyz_yaw(t.x, t.y, 0.0, yaw);
        if let Ok(id) = try_place(state, &routed, pose) {
            ids.push(id);
        }
    }
    if (ids.len() as u32) < a.count {
        notes.push(format!(
            "only {} of {} fit around {}; place the rest elsewhere or use a larger {}",
            ids.len(),
            a.count,
            a.parent,
            parent.category
        ));
    }
    if ids.is_empty() {
        return Err(ToolError::failed(notes.join("; ")));
    }
    result_for(state, &ids, [routed.notes.clone(), notes].concat())
}

fn place_facing(state: &mut StageState, a: FacingArgs) -> Result<PlaceResult, ToolError> {
    let tfp = placed_footprint(state, &a.target)?;
    let routed = state.route_asset(&a.description, None)?;
    let gap = a.distance_m.unwrap_or(0.6).clamp(0.1, 4.0);
    let mut tried = Vec::new();
    // Try in front of the target first (straight across, then slid sideways by up to a
    // quarter of the target's width each way), then its other sides.
    let slide = tfp.half[0] / 2.0;
    let spots = [
        (0, 0.0),
        (0, slide / 2.0),
        (0, -slide / 2.0),
        (0, slide),
        (0, -slide),
    ]
    .into_iter()
    .chain((1..4).map(|k| (k, 0.0)));
    for (k, offset) in spots {
        let yaw_t = tfp.yaw + k as f64 * std::f64::consts::FRAC_PI_2;
        let dir = [-yaw_t.sin(), yaw_t.cos()];
        let across = [yaw_t.cos(), yaw_t.sin()];
        let reach = if k % 2 == 0 { tfp.half[1] } else { tfp.half[0] };
        let dist = reach + gap + routed.size[1] / 2.0;
        let p = [
            tfp.center[0] + dir[0] * dist + across[0] * offset,
            tfp.center[1] + dir[1] * dist + across[1] * offset,
        ];
        let yaw = wrap_angle(yaw_t + std::f64::consts::PI);
        let pose = Pose::from_xyz_yaw(p[0], p[1], 0.0, yaw);
        match try_place(state, &routed, pose) {
            Ok(id) => return result_for(state, &[id], routed.notes.clone()),
            Err(e) => tried.push(e.message),
        }
    }
    Err(ToolError::failed(format!(
        "no free side of {} to face it from: {}",
        a.target,
        tried.join("; ")
    )))
}

fn placed_footprint(state: &StageState, id: &str) -> Result<Footprint, ToolError> {
    let obj = state
        .scene
        .scene
        .object(id)
        .ok_or_else(|| ToolError::failed(format!("no object {id:?}")))?;
    let rec = state
        .scene
        .scene
        .assets
        .get(&obj.asset)
        .ok_or_else(|| ToolError::failed(format!("{id} has no asset")))?;
    Ok(Footprint::of(rec, &obj.world_from_object))
}

/// The pose that puts the footprint centre of an asset with bounds `bounds` at `centre` with
/// heading `yaw` (an asset's origin need not be its footprint's centre).
fn pose_for_centre(bounds: &[[f64; 3]; 2], centre: [f64; 2], yaw: f64) -> Pose {
    let [lo, hi] = bounds;
    let (cx, cy) = ((lo[0] + hi[0]) / 2.0, (lo[1] + hi[1]) / 2.0);
    let (s, c) = yaw.sin_cos();
    Pose::from_xyz_yaw(
        centre[0] - (c * cx - s * cy),
        centre[1] - (s * cx + c * cy),
        0.0,
        yaw,
    )
}

fn place_relative(state: &mut StageState, a: RelativeArgs) -> Result<PlaceResult, ToolError> {
    let t = placed_footprint(state, &a.target)?;
    let routed = state.route_asset(&a.description, None)?;
    let bounds = state
        .scene
        .scene
        .assets
        .get(&routed.asset)
        .map(|r| r.bounds)
        .ok_or_else(|| ToolError::failed("asset vanished"))?;
    let own = [
        (bounds[1][0] - bounds[0][0]) / 2.0,
        (bounds[1][1] - bounds[0][1]) / 2.0,
    ];
    // The target's own axes: x to its right, y to its front (a yaw of 0 faces +Y).
    let (s, c) = t.yaw.sin_cos();
    let (x_axis, y_axis) = ([c, s], [-s, c]);
    let at = |along_x: f64, along_y: f64| {
        [
            t.center[0] + x_axis[0] * along_x + y_axis[0] * along_y,
            t.center[1] + x_axis[1] * along_x + y_axis[1] * along_y,
        ]
    };
    let candidates: Vec<([f64; 2], f64)> = match a.relation {
        Relation::Beside => {
            let gap = a.gap_m.unwrap_or(0.05).clamp(0.0, 2.0);
            let back_in_line = -t.half[1] + own[1];
            [1.0, -1.0]
                .iter()
                .map(|side| (at(side * (t.half[0] + gap + own[0]), back_in_line), t.yaw))
                .collect()
        }
        Relation::InFront => {
            let gap = a.gap_m.unwrap_or(0.4).clamp(0.0, 4.0);
            let centre = at(0.0, t.half[1] + gap + own[1]);
            vec![(centre, wrap_angle(yaw_facing(centre, t.center)))]
        }
        Relation::Behind => {
            let gap = a.gap_m.unwrap_or(0.1).clamp(0.0, 4.0);
            vec![(at(0.0, -(t.half[1] + gap + own[1])), t.yaw)]
        }
        Relation::Between => {
            let second = a
                .second
                .as_deref()
                .ok_or_else(|| ToolError::failed("\"between\" needs a second object"))?;
            let u = placed_footprint(state, second)?;
            let centre = [
                (t.center[0] + u.center[0]) / 2.0,
                (t.center[1] + u.center[1]) / 2.0,
            ];
            let facing_each_other =
                wrap_angle(t.yaw - u.yaw).abs() > 3.0 * std::f64::consts::FRAC_PI_4;
            let yaw = if facing_each_other {
                wrap_angle(yaw_facing(centre, t.center))
            } else {
                t.yaw
            };
            vec![(centre, yaw)]
        }
    };
    let mut tried = Vec::new();
    for (centre, yaw) in candidates {
        match try_place(state, &routed, pose_for_centre(&bounds, centre, yaw)) {
            Ok(id) => return result_for(state, &[id], routed.notes.clone()),
            Err(e) => tried.push(e.message),
        }
    }
    Err(ToolError::failed(format!(
        "no room {:?} {}: {}",
        a.relation,
        a.target,
        tried.join("; ")
    )))
}

/// The furniture stage's tools.
pub fn toolbox() -> Toolbox<StageState> {
    let mut t = Toolbox::new();
    common::register(&mut t);
    t.add("place_object", "Place a piece of furniture at room coordinates with a rotation. Fails if it would leave the room, overlap furniture or block a door.", Access::Modify, place_object);
    t.add("place_against_wall", "Place a piece with its back against a wall (by id or side), at a position along the wall or the first free one.", Access::Modify, place_against_wall);
    t.add(
        "place_in_corner",
        "Place a piece in a corner of the room, facing into the room.",
        Access::Modify,
        place_in_corner,
    );
    t.add("place_in_center", "Place a piece in the open middle of the room, keeping the given clearance around it where possible.", Access::Modify, place_in_center);
    t.add(
        "place_around",
        "Place several pieces (e.g. chairs) around a table, desk or counter, each facing it.",
        Access::Modify,
        place_around,
    );
    t.add(
        "place_facing",
        "Place a piece facing a target object at a distance (e.g. a sofa facing a TV stand).",
        Access::Modify,
        place_facing,
    );
    t.add(
        "place_relative",
        "Place a piece beside, in front of or behind an object, or between two objects (e.g. a nightstand beside the bed, a coffee table between two sofas).",
        Access::Modify,
        place_relative,
    );
    t
}
