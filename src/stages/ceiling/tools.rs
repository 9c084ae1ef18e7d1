//! The ceiling stage's tools: hang an object at room coordinates or above a piece of
//! furniture, keeping head room over the walkable floor.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use crate::agents::{Access, CategorySpec, ToolError, Toolbox};
use crate::scene::{ObjectKind, Pose, Support};
use crate::stages::common::{self, ObjectInfo, floor_footprints, object_info};
use crate::stages::placement::Footprint;
use crate::stages::room::RoomFrame;
use crate::stages::{RoutedAsset, StageState};

/// Clear height kept under ceiling objects over walkable floor, metres.
pub const HEAD_ROOM: f64 = 2.0;

/// Clearance of a ceiling object over the top of furniture below it, metres (what
/// `hang_from_ceiling` enforces).
pub(super) const OVER_FURNITURE_M: f64 = 0.1;

/// The ceiling stage's critic categories.
pub fn categories() -> Vec<CategorySpec> {
    vec![
        CategorySpec::new(
            "prompt_following",
            "every requested ceiling object is present with its count",
        ),
        CategorySpec::new(
            "placement_logic",
            "lights over what they light (tables, beds, seating), head room kept where people walk",
        ),
        CategorySpec::new(
            "coverage",
            "the room is evenly covered; nothing bunched in one corner",
        ),
        CategorySpec::new(
            "physical_feasibility",
            "no ceiling object penetrates furniture, walls or another object",
        ),
    ]
}

/// Hang an object at room coordinates.
#[derive(Debug, Deserialize, JsonSchema)]
pub struct HangArgs {
    /// What to hang, e.g. "pendant light", "ceiling fan".
    pub description: String,
    /// Room x, metres.
    pub x: f64,
    /// Room y, metres.
    pub y: f64,
}

/// Hang an object above a piece of furniture.
#[derive(Debug, Deserialize, JsonSchema)]
pub struct HangAboveArgs {
    /// What to hang.
    pub description: String,
    /// Id of the furniture (table, bed, desk...).
    pub target: String,
}

/// Result of a hanging tool.
#[derive(Debug, Serialize, JsonSchema)]
pub struct HangResult {
    /// The new object.
    pub placed: Option<ObjectInfo>,
    /// Remarks (a generic stand-in for an unknown noun, parts for another stage).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub notes: Vec<String>,
}

fn try_hang(
    state: &mut StageState,
    routed: &RoutedAsset,
    world_xy: [f64; 2],
    over: Option<&str>,
) -> Result<String, ToolError> {
    let room = state.room()?.clone();
    let rec = state.scene.scene.assets[&routed.asset].clone();
    let [lo, hi] = rec.bounds;
    let h = hi[2] - lo[2];
    // Ceiling objects have their top at z = 0 in their own frame.
    let pose = Pose::from_xyz(
        world_xy[0] - (lo[0] + hi[0]) / 2.0,
        world_xy[1] - (lo[1] + hi[1]) / 2.0,
        room.wall_height - hi[2],
    );
    let fp = Footprint::of(&rec, &pose);
    if !fp.inside(&room.floor_polygon) {
        return Err(ToolError::failed(format!(
            "a {} there would stick out of the room",
            routed.category
        )));
    }
    let bottom = room.wall_height - h;
    for (id, f) in floor_footprints(state) {
        if f.overlaps(&fp, 0.0) && f.z[1] + OVER_FURNITURE_M > bottom {
            return Err(ToolError::failed(format!(
                "a {} there would hit {id}",
                routed.category
            )));
        }
    }
    let over_furniture = over.is_some();
    if bottom < HEAD_ROOM && !over_furniture {
        return Err(ToolError::failed(format!(
            "a {} hanging to {:.2} m leaves less than {HEAD_ROOM} m of head room; hang it above furniture instead",
            routed.category, bottom
        )));
    }
    for o in state
        .room_objects()
        .filter(|o| o.kind == ObjectKind::Ceiling)
    {
        if let Some(r) = state.scene.scene.assets.get(&o.asset)
            && Footprint::of(r, &o.world_from_object).overlaps(&fp, 0.1)
        {
            return Err(ToolError::failed(format!("too close to {}", o.id)));
        }
    }
    let room_id = state.room.clone();
    Ok(state.add_routed(
        routed,
        ObjectKind::Ceiling,
        pose,
        Support::Ceiling { room: room_id },
    ))
}

fn hang(state: &mut StageState, a: HangArgs) -> Result<HangResult, ToolError> {
    let routed = state.route_asset(&a.description, None)?;
    let room = state.room()?.clone();
    let frame = RoomFrame::new(&room);
    let id = try_hang(state, &routed, frame.to_world(a.x, a.y), None)?;
    Ok(HangResult {
        placed: object_info(state, &frame, &id),
        notes: routed.notes.clone(),
    })
}

fn hang_above(state: &mut StageState, a: HangAboveArgs) -> Result<HangResult, ToolError> {
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
    let id = try_hang(state, &routed, tfp.center, Some(&a.target))?;
    Ok(HangResult {
        placed: object_info(state, &frame, &id),
        notes: routed.notes.clone(),
    })
}

/// The ceiling stage's tools.
pub fn toolbox() -> Toolbox<StageState> {
    let mut t = Toolbox::new();
    common::register(&mut t);
    t.add("hang_from_ceiling", "Hang an object from the ceiling at room coordinates; refuses spots without head room or above tall furniture.", Access::Modify, hang);
    t.add("hang_above", "Hang an object from the ceiling centred above a piece of furniture (a pendant light above a table).", Access::Modify, hang_above);
    t
}
