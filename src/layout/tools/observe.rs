//! Tools that look: the layout as data, the text floor plan, validation.

use schemars::JsonSchema;
use serde::Serialize;

use super::{NoArgs, fail};
use crate::agents::ImageObservation;
use crate::agents::ToolError;
use crate::layout::ascii;
use crate::layout::search::SearchStats;
use crate::layout::spec::{Adjacency, Link};
use crate::layout::state::LayoutState;
use crate::layout::validate::Validation;
use crate::scene::OpeningKind;

pub(super) fn validate(s: &mut LayoutState, _: NoArgs) -> Result<Validation, ToolError> {
    Ok(s.validation())
}

/// The ASCII floor plan.
#[derive(Debug, Serialize, JsonSchema)]
pub struct AsciiPlan {
    /// The plan and the wall legend.
    pub text: String,
}

pub(super) fn render_ascii(s: &mut LayoutState, _: NoArgs) -> Result<AsciiPlan, ToolError> {
    let (rooms, _) = s.rooms();
    Ok(AsciiPlan {
        text: ascii::render(&rooms),
    })
}

pub(super) fn render_plan_image(
    s: &mut LayoutState,
    _: NoArgs,
) -> Result<ImageObservation, ToolError> {
    let (rooms, _) = s.rooms();
    let png =
        crate::render::plan_png(&s.prompt, s.seed, &rooms).map_err(|e| fail(e.to_string()))?;
    Ok(ImageObservation::new(
        format!(
            "top-down plan of {} rooms: names, sizes and materials, walls, doors with their \
             swing, windows (blue), scale bar in metres",
            rooms.len()
        ),
        &png,
    ))
}

/// One room as the agents see it.
#[derive(Debug, Serialize, JsonSchema)]
pub struct RoomInfo {
    /// Room id.
    pub id: String,
    /// Room type.
    pub room_type: String,
    /// What the prompt calls it.
    pub label: String,
    /// `hub`, `entry`, `public`, `private`, `wet` or `service`.
    pub role: String,
    /// South-west corner of the clear floor, metres.
    pub origin_m: [f64; 2],
    /// Clear size (x, y), metres.
    pub size_m: [f64; 2],
    /// Clear floor area, m^2.
    pub area_m2: f64,
    /// Floor material.
    pub floor: String,
    /// Wall material.
    pub wall: String,
    /// Rooms sharing a wall with it, with the shared length in metres.
    pub neighbors: Vec<(String, f64)>,
    /// Rooms it may be entered from.
    pub parents: Vec<String>,
    /// Outside wall length, metres.
    pub exterior_wall_m: f64,
    /// Door ids (with where they lead).
    pub doors: Vec<String>,
    /// Window count.
    pub windows: usize,
    /// Whether it wants windows.
    pub wants_windows: bool,
    /// The room's prompt for the later stages.
    pub prompt: String,
}

/// A room type the prompt asks for and how many exist.
#[derive(Debug, Serialize, JsonSchema)]
pub struct RequestedRoom {
    /// Room type.
    pub room_type: String,
    /// Count asked for.
    pub wanted: usize,
    /// Count present.
    pub present: usize,
}

/// The layout as the agents see it.
#[derive(Debug, Serialize, JsonSchema)]
pub struct LayoutObservation {
    /// The prompt.
    pub prompt: String,
    /// Rooms.
    pub rooms: Vec<RoomInfo>,
    /// Open connections (pairs of rooms without a wall between them).
    pub open_connections: Vec<(String, String)>,
    /// Required and preferred neighbours.
    pub adjacency: Vec<Adjacency>,
    /// The room the exterior door should open into.
    pub entrance: String,
    /// Wall height, metres.
    pub wall_height_m: f64,
    /// Room area / bounding-box area.
    pub compactness: f64,
    /// Rooms asked for vs present.
    pub requested: Vec<RequestedRoom>,
    /// Wall height asked for, metres.
    pub requested_wall_height_m: Option<f64>,
    /// Materials the prompt names per room (room id, floor, wall).
    pub requested_materials: Vec<(String, Option<String>, Option<String>)>,
    /// Last search statistics.
    pub search: SearchStats,
    /// Validation errors.
    pub errors: Vec<String>,
}

/// The observation of a layout state.
pub fn observe(s: &LayoutState) -> Result<LayoutObservation, ToolError> {
    let spec = s.spec().map_err(fail)?;
    let (rooms, _) = s.rooms();
    let t = s.config.wall_thickness;
    let mut infos = Vec::new();
    for r in &spec.rooms {
        let cell = s.placement.cells.get(&r.id).copied();
        let built = rooms.iter().find(|x| x.id == r.id);
        let openings = built
            .map(|b| {
                b.walls
                    .iter()
                    .flat_map(|w| w.openings.iter().map(move |o| (w, o)))
                    .collect::<Vec<_>>()
            })
            .unwrap_or_default();
        let neighbors = s
            .placement
            .cells
            .keys()
            .filter(|k| **k != r.id)
            .map(|k| (k.clone(), round2(s.placement.shared(&r.id, k))))
            .filter(|(_, l)| *l > 0.0)
            .collect();
        infos.push(RoomInfo {
            id: r.id.clone(),
            room_type: r.room_type.clone(),
            label: r.label.clone(),
            role: r.role.as_str().to_string(),
            origin_m: cell
                .map(|c| [round2(c.x0 + t / 2.0), round2(c.y0 + t / 2.0)])
                .unwrap_or_default(),
            size_m: cell
                .map(|c| [round2(c.w() - t), round2(c.d() - t)])
                .unwrap_or(r.size),
            area_m2: cell
                .map(|c| round2((c.w() - t) * (c.d() - t)))
                .unwrap_or(r.area()),
            floor: r.floor_material.clone(),
            wall: r.wall_material.clone(),
            neighbors,
            parents: r.parents.clone(),
            exterior_wall_m: round2(s.placement.exterior_length(&r.id)),
            doors: openings
                .iter()
                .filter(|(_, o)| o.kind == OpeningKind::Door)
                .map(|(w, o)| format!("{} -> {}", o.id, w.neighbor.as_deref().unwrap_or("outside")))
                .collect(),
            windows: openings
                .iter()
                .filter(|(_, o)| o.kind == OpeningKind::Window)
                .count(),
            wants_windows: r.windows,
            prompt: r.prompt.clone(),
        });
    }
    let mut requested: Vec<RequestedRoom> = Vec::new();
    for r in &s.brief.rooms {
        match requested.iter_mut().find(|q| q.room_type == r.room_type) {
            Some(q) => q.wanted += 1,
            None => requested.push(RequestedRoom {
                room_type: r.room_type.clone(),
                wanted: 1,
                present: 0,
            }),
        }
    }
    for q in &mut requested {
        q.present = spec
            .rooms
            .iter()
            .filter(|r| r.room_type == q.room_type)
            .count();
    }
    let requested_materials = s
        .brief
        .rooms
        .iter()
        .enumerate()
        .filter(|(_, r)| r.floor_material.is_some() || r.wall_material.is_some())
        .filter_map(|(i, r)| {
            spec.rooms.get(i).map(|x| {
                (
                    x.id.clone(),
                    r.floor_material.clone(),
                    r.wall_material.clone(),
                )
            })
        })
        .collect();
    Ok(LayoutObservation {
        prompt: s.prompt.clone(),
        rooms: infos,
        open_connections: spec
            .adjacency
            .iter()
            .filter(|p| p.link == Link::Open)
            .map(|p| (p.a.clone(), p.b.clone()))
            .collect(),
        adjacency: spec.adjacency.clone(),
        entrance: spec.entrance.clone(),
        wall_height_m: spec.wall_height,
        compactness: round2(s.placement.compactness()),
        requested,
        requested_wall_height_m: s.brief.wall_height,
        requested_materials,
        search: s.stats.clone(),
        errors: s.validation().errors,
    })
}

pub(super) fn round2(v: f64) -> f64 {
    (v * 100.0).round() / 100.0
}

pub(super) fn observe_scene(
    s: &mut LayoutState,
    _: NoArgs,
) -> Result<LayoutObservation, ToolError> {
    observe(s)
}
