//! The manipuland stage's tool set: the critic's categories, the tools an agent calls (the
//! single-item tools and observe_surfaces here, the composites in their own files) and the
//! argument and result types they share.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use super::fill::place_inside;
use super::fit::{add_item, fit, item_rotation, occupied, shrunk_to_fit};
use super::pile::place_pile;
use super::settings::place_settings;
use super::stack::place_stack;
use super::surface::{find_surface, stacked_on, surfaces};
use crate::agents::{Access, CategorySpec, ToolError, Toolbox};
use crate::scene::Support;
use crate::stages::StageState;
use crate::stages::common::{self, ObjectInfo, object_info};
use crate::stages::room::RoomFrame;

/// The manipuland stage's critic categories.
pub fn categories() -> Vec<CategorySpec> {
    vec![
        CategorySpec::new(
            "prompt_following",
            "every requested small object is present on this entity with the requested count",
        ),
        CategorySpec::new(
            "realism",
            "objects are plausible where they are: upright, related items together, nothing absurd",
        ),
        CategorySpec::new(
            "arrangement",
            "objects sit inside the surface, evenly spaced, nothing hanging over an edge",
        ),
        CategorySpec::new(
            "physical_feasibility",
            "no object penetrates another object or its support",
        ),
    ]
}

/// Place one object.
#[derive(Debug, Deserialize, JsonSchema)]
pub struct PlaceArgs {
    /// What to place, e.g. "red mug", "hardcover book".
    pub description: String,
    /// Surface id as `object_id/surface_id` (e.g. `table_0/top`, `shelf_1/shelf_0`).
    pub surface: String,
    /// Position along the surface's width from its centre, metres; automatic when omitted.
    #[serde(default)]
    pub u: Option<f64>,
    /// Position along the surface's depth (+ towards its front), metres; automatic when omitted.
    #[serde(default)]
    pub v: Option<f64>,
    /// Rotation relative to the supporting object, degrees.
    #[serde(default)]
    pub yaw_deg: f64,
    /// Lay the object on its side (books lying flat).
    #[serde(default)]
    pub lay_flat: bool,
}

/// A composite of identical objects.
#[derive(Debug, Deserialize, JsonSchema)]
pub struct GroupArgs {
    /// What to place.
    pub description: String,
    /// How many.
    pub count: u32,
    /// Surface id (`object_id/surface_id`).
    pub surface: String,
    /// Position along the width, metres; automatic when omitted.
    #[serde(default)]
    pub u: Option<f64>,
    /// Position along the depth, metres; automatic when omitted.
    #[serde(default)]
    pub v: Option<f64>,
}

/// What a placement tool did.
#[derive(Debug, Serialize, JsonSchema, Default)]
pub struct PlaceResult {
    /// New objects.
    pub placed: Vec<ObjectInfo>,
    /// Remarks.
    pub notes: Vec<String>,
}

pub(super) fn result_for(
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

fn place_on_surface(state: &mut StageState, a: PlaceArgs) -> Result<PlaceResult, ToolError> {
    let s = find_surface(state, &a.surface)?;
    let mut routed = state.route_asset(&a.description, None)?;
    let mut rec = state.scene.scene.assets[&routed.asset].clone();
    let at = match (a.u, a.v) {
        (Some(u), Some(v)) => Some((u, v)),
        (None, None) => None,
        _ => return Err(ToolError::bad_args("give both u and v, or neither")),
    };
    let rot = item_rotation(a.yaw_deg, a.lay_flat);
    // A typical-sized item a little larger than the surface ("a printer on a small side
    // table"): the same item at a size that fits, within its category's range.
    if let Some(size) = shrunk_to_fit(&s, &rec, &rot) {
        let smaller = state.route_asset(&a.description, Some(size))?;
        routed = smaller;
        rec = state.scene.scene.assets[&routed.asset].clone();
    }
    let (pose, _) = fit(state, &s, &rec, &rot, at, &[]).map_err(ToolError::failed)?;
    let id = add_item(state, &routed, pose, &s.parent.id, &s.surface.id);
    result_for(state, &[id], routed.notes.clone())
}

/// A surface as the agents see it.
#[derive(Debug, Serialize, JsonSchema)]
pub struct SurfaceInfo {
    /// `object_id/surface_id`.
    pub surface: String,
    /// Supporting object's category.
    pub category: String,
    /// Size along u and v, metres.
    pub size_m: [f64; 2],
    /// Height above the floor, metres.
    pub height_m: f64,
    /// Free height above it, metres.
    pub clearance_m: f64,
    /// Objects on it (directly or stacked).
    pub objects: Vec<String>,
    /// Fraction of its area covered.
    pub occupancy: f64,
    /// Behind a door or in a drawer (out of sight; a robot opens it first).
    pub enclosed: bool,
}

/// Surfaces to inspect.
#[derive(Debug, Deserialize, JsonSchema, Default)]
pub struct SurfacesArgs {
    /// Object id; the stage's supporting entity (or every object of the room) when omitted.
    #[serde(default)]
    pub object: Option<String>,
}

fn observe_surfaces(
    state: &mut StageState,
    a: SurfacesArgs,
) -> Result<Vec<SurfaceInfo>, ToolError> {
    let focus = a.object.or_else(|| state.entity.clone());
    let list = surfaces(state, focus.as_deref());
    Ok(list
        .iter()
        .map(|s| {
            let slots = occupied(&state.scene, s);
            let covered: f64 = slots.iter().map(|sl| 4.0 * sl.hu * sl.hv).sum();
            let area = s.surface.size[0] * s.surface.size[1];
            let mut objects: Vec<String> = state
                .scene
                .scene
                .objects
                .iter()
                .filter(|o| matches!(&o.support, Support::Object { parent, surface } if *parent == s.parent.id && *surface == s.surface.id))
                .map(|o| o.id.clone())
                .collect();
            objects.extend(stacked_on(state, &objects));
            SurfaceInfo {
                surface: s.key(),
                category: s.parent.category.clone(),
                size_m: [common::round3(s.surface.size[0]), common::round3(s.surface.size[1])],
                height_m: common::round3(s.world_from_surface().translation().z),
                clearance_m: common::round3(s.surface.clearance),
                occupancy: common::round3((covered / area.max(1e-9)).min(1.0)),
                enclosed: s.enclosed(state),
                objects,
            }
        })
        .collect())
}

/// The manipuland stage's tools.
pub fn toolbox() -> Toolbox<StageState> {
    let mut t = Toolbox::new();
    common::register(&mut t);
    t.add("observe_surfaces", "List the support surfaces (of the stage's entity, or one object) with size, height, free height, occupancy and the objects on them.", Access::Observe, observe_surfaces);
    t.add("place_on_surface", "Place one small object on a surface at (u, v) or at the first free spot; lay_flat lays it on its side.", Access::Modify, place_on_surface);
    t.add("place_stack", "Stack several identical objects (plates, bowls, books, boxes) at one spot; they nest where their shape allows.", Access::Modify, place_stack);
    t.add(
        "place_pile",
        "Pile several identical objects loosely in layers on a surface (blocks, fruit, towels).",
        Access::Modify,
        place_pile,
    );
    t.add("place_inside", "Put several identical objects inside a container object (bowl, bin, basket, box, refrigerator).", Access::Modify, place_inside);
    t.add("place_settings", "Lay place settings on a table top: the given items in front of every seat facing the table (or the given number of settings).", Access::Modify, place_settings);
    t
}
