//! Tools every placement stage has: observe the room, move / rotate / remove an object, check
//! collisions and reachability. Positions in and out are room coordinates (metres, origin at
//! the south-west corner of the clear floor), yaw in degrees.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use super::placement::Footprint;
use super::room::{FloorGrid, Reachability, RoomFrame, wall_side};
use super::{StageKind, StageState};
use crate::agents::{Access, ToolError, Toolbox};
use crate::physics::collision;
use crate::scene::{ObjectKind, OpeningKind, Pose, Support};

/// No arguments.
#[derive(Debug, Deserialize, JsonSchema, Default)]
pub struct NoArgs {}

/// An opening in a wall.
#[derive(Debug, Serialize, JsonSchema)]
pub struct OpeningInfo {
    /// `door`, `window` or `open`.
    pub kind: String,
    /// Centre along the wall from its start, metres.
    pub center_m: f64,
    /// Width, metres.
    pub width_m: f64,
    /// Bottom above the floor, metres.
    pub bottom_m: f64,
    /// Height, metres.
    pub height_m: f64,
}

/// A wall of the room.
#[derive(Debug, Serialize, JsonSchema)]
pub struct WallInfo {
    /// Wall id.
    pub id: String,
    /// `north`, `south`, `east` or `west`.
    pub side: String,
    /// Length, metres.
    pub length_m: f64,
    /// Doors, windows, open connections.
    pub openings: Vec<OpeningInfo>,
}

/// An object in the room.
#[derive(Debug, Serialize, JsonSchema, Clone)]
pub struct ObjectInfo {
    /// Object id.
    pub id: String,
    /// Category.
    pub category: String,
    /// `furniture`, `wall`, `ceiling`, `manipuland`, `thin_covering`.
    pub kind: String,
    /// Room coordinates of the model origin, metres.
    pub x: f64,
    /// Room coordinates, metres.
    pub y: f64,
    /// Height of the model origin, metres.
    pub z: f64,
    /// Rotation about the vertical axis, degrees (0: front faces north).
    pub yaw_deg: f64,
    /// Size (x, y, z), metres.
    pub size_m: [f64; 3],
    /// What holds it (`floor`, a wall id, or `parent/surface`).
    pub support: String,
}

/// What was asked for and how much of it is there.
#[derive(Debug, Serialize, JsonSchema)]
pub struct Requested {
    /// Noun.
    pub noun: String,
    /// Count asked for.
    pub wanted: u32,
    /// Count present in the room.
    pub present: u32,
}

/// The room as the agents see it.
#[derive(Debug, Serialize, JsonSchema)]
pub struct RoomObservation {
    /// Room id.
    pub room: String,
    /// Room type.
    pub room_type: String,
    /// The part of the prompt about this room.
    pub prompt: String,
    /// Clear floor size (x, y), metres.
    pub size_m: [f64; 2],
    /// Wall height, metres.
    pub wall_height_m: f64,
    /// Walls with their openings.
    pub walls: Vec<WallInfo>,
    /// Objects in the room.
    pub objects: Vec<ObjectInfo>,
    /// Explicitly requested objects vs present.
    pub requested: Vec<Requested>,
    /// Nouns the prompt excluded.
    pub excluded: Vec<String>,
}

/// Describes one object in room coordinates.
pub fn object_info(state: &StageState, frame: &RoomFrame<'_>, id: &str) -> Option<ObjectInfo> {
    let o = state.scene.scene.object(id)?;
    let rec = state.scene.scene.assets.get(&o.asset)?;
    let t = o.world_from_object.translation();
    let p = frame.to_room([t.x, t.y]);
    let [lo, hi] = rec.bounds;
    Some(ObjectInfo {
        id: o.id.clone(),
        category: o.category.clone(),
        kind: o.kind.as_str().to_string(),
        x: round3(p[0]),
        y: round3(p[1]),
        z: round3(t.z),
        yaw_deg: round3(o.world_from_object.yaw().to_degrees()),
        size_m: [
            round3(hi[0] - lo[0]),
            round3(hi[1] - lo[1]),
            round3(hi[2] - lo[2]),
        ],
        support: match &o.support {
            Support::Floor { .. } => "floor".into(),
            Support::Wall { wall } => wall.clone(),
            Support::Ceiling { .. } => "ceiling".into(),
            Support::Object { parent, surface } => format!("{parent}/{surface}"),
            Support::World => "world".into(),
        },
    })
}

/// Rounds to millimetres for agent-facing numbers.
pub fn round3(v: f64) -> f64 {
    (v * 1000.0).round() / 1000.0
}

/// Counts of present objects per plan noun in the room.
pub fn present_count(state: &StageState, noun: &str) -> u32 {
    state
        .room_objects()
        .filter(|o| crate::assets::router::naming::object_is(&state.scene.scene, noun, o))
        .count() as u32
}

/// The `observe_room` tool.
pub fn observe_room(state: &mut StageState, _: NoArgs) -> Result<RoomObservation, ToolError> {
    let room = state.room()?.clone();
    let frame = RoomFrame::new(&room);
    let walls = room
        .walls
        .iter()
        .map(|w| WallInfo {
            id: w.id.clone(),
            side: wall_side(w).to_string(),
            length_m: round3(w.length()),
            openings: w
                .openings
                .iter()
                .map(|o| OpeningInfo {
                    kind: match o.kind {
                        OpeningKind::Door => "door",
                        OpeningKind::Window => "window",
                        OpeningKind::Open => "open",
                    }
                    .into(),
                    center_m: round3(o.center),
                    width_m: round3(o.width),
                    bottom_m: round3(o.bottom),
                    height_m: round3(o.height),
                })
                .collect(),
        })
        .collect();
    let ids: Vec<String> = state.room_objects().map(|o| o.id.clone()).collect();
    let objects = ids
        .iter()
        .filter_map(|id| object_info(state, &frame, id))
        .collect();
    let requested = state
        .plan
        .requested()
        .into_iter()
        .map(|(noun, wanted)| Requested {
            present: present_count(state, &noun),
            noun,
            wanted,
        })
        .collect();
    Ok(RoomObservation {
        room: room.id.clone(),
        room_type: room.room_type.clone(),
        prompt: room.prompt.clone(),
        size_m: [round3(frame.size[0]), round3(frame.size[1])],
        wall_height_m: room.wall_height,
        walls,
        objects,
        requested,
        excluded: state.plan.excluded.clone(),
    })
}

/// Arguments naming an object.
#[derive(Debug, Deserialize, JsonSchema)]
pub struct ObjectArg {
    /// Object id.
    pub id: String,
}

/// Move an object.
#[derive(Debug, Deserialize, JsonSchema)]
pub struct MoveArgs {
    /// Object id.
    pub id: String,
    /// New room x of its origin, metres.
    pub x: f64,
    /// New room y of its origin, metres.
    pub y: f64,
}

/// Rotate an object.
#[derive(Debug, Deserialize, JsonSchema)]
pub struct RotateArgs {
    /// Object id.
    pub id: String,
    /// New rotation about the vertical axis, degrees (0: front faces north, 90: west).
    pub yaw_deg: f64,
}

/// Result of an edit.
#[derive(Debug, Serialize, JsonSchema)]
pub struct EditResult {
    /// The object after the edit (absent after a removal).
    pub object: Option<ObjectInfo>,
    /// Objects moved or removed along with it (things resting on it).
    pub also: Vec<String>,
}

fn check_editable(state: &StageState, id: &str) -> Result<(), ToolError> {
    let o =
        state.scene.scene.object(id).ok_or_else(|| {
            ToolError::failed(format!("no object {id:?}; observe the room for ids"))
        })?;
    if o.room != state.room {
        return Err(ToolError::failed(format!(
            "{id} is in room {}, not {}",
            o.room, state.room
        )));
    }
    if o.kind != state.kind.object_kind() {
        return Err(ToolError::failed(format!(
            "{id} is a {} object; the {} stage may only edit {} objects",
            o.kind.as_str(),
            state.kind.as_str(),
            state.kind.object_kind().as_str()
        )));
    }
    Ok(())
}

/// Moves `id` by `world_from_new * world_from_old^-1`, carrying everything resting on it.
pub fn transform_object(state: &mut StageState, id: &str, new_pose: Pose) -> Vec<String> {
    let Some(old) = state.scene.scene.object(id).map(|o| o.world_from_object) else {
        return vec![];
    };
    let delta = new_pose.compose(&old.inverse());
    let mut moved = Vec::new();
    let mut frontier = vec![id.to_string()];
    while let Some(parent) = frontier.pop() {
        for o in state.scene.scene.objects.iter_mut() {
            let on_parent = matches!(&o.support, Support::Object { parent: p, .. } if *p == parent);
            if o.id == parent || on_parent {
                if moved.contains(&o.id) {
                    continue;
                }
                o.world_from_object = delta.compose(&o.world_from_object);
                moved.push(o.id.clone());
                if on_parent {
                    frontier.push(o.id.clone());
                }
            }
        }
    }
    moved.retain(|m| m != id);
    moved
}

fn move_object(state: &mut StageState, a: MoveArgs) -> Result<EditResult, ToolError> {
    check_editable(state, &a.id)?;
    let room = state.room()?.clone();
    let frame = RoomFrame::new(&room);
    let w = frame.to_world(a.x, a.y);
    if !frame.contains(w) && state.kind != StageKind::Wall {
        return Err(ToolError::failed(format!(
            "({:.2}, {:.2}) is outside the room (size {:.2} x {:.2} m)",
            a.x, a.y, frame.size[0], frame.size[1]
        )));
    }
    let old = state
        .scene
        .scene
        .object(&a.id)
        .map(|o| o.world_from_object)
        .unwrap_or_default();
    let t = old.translation();
    let new_pose = old.with_translation(nalgebra::Vector3::new(w[0], w[1], t.z));
    let also = transform_object(state, &a.id, new_pose);
    Ok(EditResult {
        object: object_info(state, &frame, &a.id),
        also,
    })
}

fn rotate_object(state: &mut StageState, a: RotateArgs) -> Result<EditResult, ToolError> {
    check_editable(state, &a.id)?;
    let room = state.room()?.clone();
    let frame = RoomFrame::new(&room);
    let old = state
        .scene
        .scene
        .object(&a.id)
        .map(|o| o.world_from_object)
        .unwrap_or_default();
    let t = old.translation();
    let new_pose = Pose::from_xyz_yaw(t.x, t.y, t.z, a.yaw_deg.to_radians());
    let also = transform_object(state, &a.id, new_pose);
    Ok(EditResult {
        object: object_info(state, &frame, &a.id),
        also,
    })
}

fn remove_object(state: &mut StageState, a: ObjectArg) -> Result<EditResult, ToolError> {
    check_editable(state, &a.id)?;
    let before: Vec<String> = state
        .scene
        .scene
        .objects
        .iter()
        .map(|o| o.id.clone())
        .collect();
    let stage = state.kind.as_str();
    state
        .scene
        .remove_object(&a.id, stage, "removed by the designer");
    // A designer's removal is an edit, not a loss to report.
    state
        .scene
        .scene
        .removed
        .retain(|r| r.stage != stage || !before.contains(&r.object));
    let after: Vec<String> = state
        .scene
        .scene
        .objects
        .iter()
        .map(|o| o.id.clone())
        .collect();
    let also = before
        .into_iter()
        .filter(|id| !after.contains(id) && *id != a.id)
        .collect();
    state.scene.prune_assets();
    Ok(EditResult { object: None, also })
}

/// One penetrating pair.
#[derive(Debug, Serialize, JsonSchema, Clone, PartialEq)]
pub struct Collision {
    /// First object.
    pub a: String,
    /// Second object (may be the room architecture).
    pub b: String,
    /// Penetration depth, millimetres.
    pub depth_mm: f64,
}

/// Collisions in the room.
#[derive(Debug, Serialize, JsonSchema)]
pub struct CollisionReport {
    /// Pairs penetrating more than 1 mm.
    pub collisions: Vec<Collision>,
}

/// Penetrating pairs (> 1 mm) that involve objects of the room in focus.
pub fn room_collisions(state: &StageState) -> Vec<Collision> {
    let scene = &state.scene.scene;
    let relevant = |id: &str| scene.object(id).is_some_and(|o| o.room == state.room);
    let Ok(objects) = collision::posed_objects(scene, &state.scene.assets) else {
        return vec![];
    };
    let objects: Vec<_> = objects.into_iter().filter(|o| relevant(&o.id)).collect();
    collision::penetrating_pairs(&objects, 1e-3)
        .into_iter()
        .map(|p| Collision {
            a: p.a,
            b: p.b,
            depth_mm: round3(p.depth * 1e3),
        })
        .collect()
}

fn check_collisions(state: &mut StageState, _: NoArgs) -> Result<CollisionReport, ToolError> {
    Ok(CollisionReport {
        collisions: room_collisions(state),
    })
}

/// Reachability arguments.
#[derive(Debug, Deserialize, JsonSchema)]
pub struct ReachArgs {
    /// Radius of the robot base, metres (default 0.25).
    #[serde(default)]
    pub robot_radius_m: Option<f64>,
}

/// Floor footprints of the room's floor-standing objects.
pub fn floor_footprints(state: &StageState) -> Vec<(String, Footprint)> {
    state
        .room_objects()
        .filter(|o| matches!(o.kind, ObjectKind::Furniture))
        .filter_map(|o| {
            let rec = state.scene.scene.assets.get(&o.asset)?;
            Some((o.id.clone(), Footprint::of(rec, &o.world_from_object)))
        })
        .collect()
}

/// Reachability of the room's furniture from its entrance.
pub fn reachability(state: &StageState, radius: f64) -> Result<Reachability, ToolError> {
    let room = state.room()?.clone();
    let frame = RoomFrame::new(&room);
    let obstacles = floor_footprints(state);
    let grid = FloorGrid::new(&room, &obstacles, radius, 0.05);
    Ok(grid.reachability(&frame.entrances(), &obstacles, 0.35))
}

fn check_reachability(state: &mut StageState, a: ReachArgs) -> Result<Reachability, ToolError> {
    let r = a.robot_radius_m.unwrap_or(0.25);
    if !(0.05..=1.0).contains(&r) {
        return Err(ToolError::bad_args(
            "robot_radius_m must be between 0.05 and 1.0",
        ));
    }
    reachability(state, r)
}

/// Arguments of `render_room_image`.
#[derive(Debug, Deserialize, JsonSchema, Default)]
pub struct ImageArgs {
    /// `plan` (top-down, the default) or `corner_0` .. `corner_3` (perspective from a room
    /// corner at eye height, near walls cut away).
    #[serde(default)]
    pub view: Option<String>,
}

fn render_room_image(
    state: &mut StageState,
    a: ImageArgs,
) -> Result<crate::agents::ImageObservation, ToolError> {
    let view = a.view.as_deref().unwrap_or("plan");
    let failed = |e: crate::render::RenderError| ToolError::failed(e.to_string());
    let (description, image) = if view == "plan" {
        (
            "top-down plan: walls, doors with their swing, windows, every object labelled \
             with its id, scale bar in metres"
                .to_string(),
            crate::render::top_view(&state.scene).map_err(failed)?,
        )
    } else {
        let k: usize = view
            .strip_prefix("corner_")
            .and_then(|k| k.parse().ok())
            .ok_or_else(|| ToolError::bad_args("view must be plan or corner_0 .. corner_3"))?;
        let opts = crate::render::views::RoomViewOptions {
            width: 800,
            height: 600,
            ..Default::default()
        };
        let views =
            crate::render::room_views_of(&state.scene, &state.room, &opts).map_err(failed)?;
        let (name, image) = views
            .into_iter()
            .nth(k)
            .ok_or_else(|| ToolError::bad_args(format!("the room has no corner view {k}")))?;
        (
            format!("{name}: perspective from a room corner, objects labelled with their ids"),
            image,
        )
    };
    let png = image.encode_png().map_err(failed)?;
    Ok(crate::agents::ImageObservation::new(description, &png))
}

/// Registers the shared tools.
pub fn register(t: &mut Toolbox<StageState>) {
    t.add(
        "observe_room",
        "Describe the room: size, walls with their doors and windows, every object with id, category, \
         position (room metres), rotation and size, and which requested objects are present.",
        Access::Observe,
        observe_room,
    );
    t.add(
        "render_room_image",
        "A picture of the room (PNG): the top-down plan with every object labelled, or a \
         perspective view from one of the room's corners.",
        Access::Observe,
        render_room_image,
    );
    t.add(
        "move_object",
        "Move an object of this stage to a new room position (metres), keeping its height and rotation. \
         Objects resting on it move with it.",
        Access::Modify,
        move_object,
    );
    t.add(
        "rotate_object",
        "Rotate an object of this stage about the vertical axis to yaw_deg (0: front faces north).",
        Access::Modify,
        rotate_object,
    );
    t.add(
        "remove_object",
        "Remove an object of this stage (and everything resting on it).",
        Access::Modify,
        remove_object,
    );
    t.add(
        "check_collisions",
        "List pairs of objects in this room that penetrate each other or the walls by more than 1 mm.",
        Access::Verify,
        check_collisions,
    );
    t.add(
        "check_reachability",
        "Check that a robot of the given radius can reach every piece of furniture from the door: \
         reachable and total free floor area, NAV (largest connected free region / all free floor) \
         and the ids of unreachable objects.",
        Access::Verify,
        check_reachability,
    );
}
