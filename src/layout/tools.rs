//! The layout stage's tools, with the names the design uses so an LLM designer can drive them:
//! `generate_room_specs`, `resize_room`, `add_adjacency`, `remove_adjacency`,
//! `add_open_connection`, `remove_open_connection`, `set_wall_height`, `add_door`,
//! `remove_door`, `add_window`, `remove_window`, `get_material`, `set_room_materials`,
//! `validate`, `render_ascii`, `observe_scene`. Sizes in metres; rooms by id.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use super::brief::{HouseBrief, RoomRequest};
use super::connect::{self, DoorPos, DoorSpec, Side, WindowSpec, intervals};
use super::knowledge::{self, Role, room_words};
use super::search::{MIN_SHARED, SearchStats};
use super::spec::{self, Adjacency, Link};
use super::state::{LayoutState, LayoutSummary};
use super::validate::Validation;
use super::{ascii, materials};
use crate::agents::{Access, CategorySpec, ToolError, Toolbox};
use crate::scene::OpeningKind;

/// The layout critic's categories.
pub fn categories() -> Vec<CategorySpec> {
    vec![
        CategorySpec::new(
            "room_proportions",
            "rooms have usable shapes (long side at most twice the short side, except corridors) and sizes that fit their use and contents",
        ),
        CategorySpec::new(
            "spatial_flow",
            "every room is reachable from the exterior door; en-suites only through their bedroom; no room only through a bathroom; corridors and hallways serve as hubs; the kitchen is next to the dining room",
        ),
        CategorySpec::new(
            "natural_lighting",
            "rooms people spend time in have windows on exterior walls, sized for the room",
        ),
        CategorySpec::new(
            "material_consistency",
            "floor and wall materials suit each room's use (water-resistant floors in wet rooms) and follow the prompt",
        ),
        CategorySpec::new(
            "prompt_following",
            "every room the prompt names exists with its count; asked-for open plans, heights and materials are there",
        ),
    ]
}

/// No arguments.
#[derive(Debug, Deserialize, JsonSchema, Default)]
pub struct NoArgs {}

fn fail(msg: impl Into<String>) -> ToolError {
    ToolError::failed(msg)
}

fn room_exists(state: &LayoutState, id: &str) -> Result<(), ToolError> {
    let spec = state.spec().map_err(fail)?;
    if spec.room(id).is_none() {
        return Err(ToolError::bad_args(format!(
            "no room {id:?}; rooms: {}",
            spec.rooms
                .iter()
                .map(|r| r.id.as_str())
                .collect::<Vec<_>>()
                .join(", ")
        )));
    }
    Ok(())
}

/// One room for `generate_room_specs`.
#[derive(Debug, Deserialize, JsonSchema)]
pub struct RoomArg {
    /// Room type in words, e.g. "exam room", "kitchen", "corridor".
    pub room_type: String,
    /// How many rooms of this type (default 1).
    #[serde(default)]
    pub count: Option<u32>,
    /// Clear width (long side), metres; from the type's prior and contents when omitted.
    #[serde(default)]
    pub width_m: Option<f64>,
    /// Clear depth (short side), metres.
    #[serde(default)]
    pub depth_m: Option<f64>,
    /// What the room contains, in words (becomes the room's prompt).
    #[serde(default)]
    pub prompt: Option<String>,
    /// For an en-suite bathroom: the index (0-based, in this list, counts expanded) of the
    /// bedroom it belongs to.
    #[serde(default)]
    pub en_suite_of: Option<usize>,
}

/// Arguments of `generate_room_specs`.
#[derive(Debug, Deserialize, JsonSchema, Default)]
pub struct GenerateArgs {
    /// The rooms; read from the prompt when omitted.
    #[serde(default)]
    pub rooms: Option<Vec<RoomArg>>,
    /// Floor-to-ceiling height, metres.
    #[serde(default)]
    pub wall_height_m: Option<f64>,
}

fn type_key(words: &str) -> String {
    let toks = crate::prompt::tokenize(words);
    let key = words.trim().to_lowercase().replace([' ', '-'], "_");
    if knowledge::knowledge().room_types.contains_key(&key) {
        return key;
    }
    for (w, ty) in room_words() {
        let n = w.len();
        if toks.len() >= n {
            for i in 0..=toks.len() - n {
                let mut cand: Vec<String> = toks[i..i + n].to_vec();
                if let Some(last) = cand.last_mut() {
                    *last = crate::prompt::singular(last);
                }
                if &cand == w {
                    return ty.clone();
                }
            }
        }
    }
    "room".to_string()
}

fn generate_room_specs(s: &mut LayoutState, a: GenerateArgs) -> Result<LayoutSummary, ToolError> {
    if let Some(h) = a.wall_height_m
        && !(2.2..=6.0).contains(&h)
    {
        return Err(ToolError::bad_args(
            "wall_height_m must be between 2.2 and 6.0",
        ));
    }
    let mut sizes: Vec<Option<[f64; 2]>> = Vec::new();
    if let Some(rooms) = a.rooms {
        if rooms.is_empty() || rooms.len() > 40 {
            return Err(ToolError::bad_args("give between 1 and 40 room entries"));
        }
        let total: u32 = rooms.iter().map(|r| r.count.unwrap_or(1)).sum();
        if total == 0 || total > 30 {
            return Err(ToolError::bad_args(
                "the house must have between 1 and 30 rooms",
            ));
        }
        let mut requests = Vec::new();
        for r in &rooms {
            let n = r.count.unwrap_or(1) as usize;
            let size = match (r.width_m, r.depth_m) {
                (Some(w), Some(d)) => {
                    if !(1.0..=40.0).contains(&w) || !(1.0..=40.0).contains(&d) {
                        return Err(ToolError::bad_args(format!(
                            "{}: sizes must be between 1 and 40 m",
                            r.room_type
                        )));
                    }
                    Some([w.max(d), w.min(d)])
                }
                (None, None) => None,
                _ => {
                    return Err(ToolError::bad_args(format!(
                        "{}: give both width_m and depth_m, or neither",
                        r.room_type
                    )));
                }
            };
            let key = type_key(&r.room_type);
            for i in 0..n {
                sizes.push(size);
                requests.push(RoomRequest {
                    room_type: if r.en_suite_of.is_some() {
                        "en_suite".into()
                    } else {
                        key.clone()
                    },
                    label: r.room_type.trim().to_lowercase(),
                    ordinal: [i + 1, n],
                    text: r.prompt.clone().into_iter().collect(),
                    size_scale: 1.0,
                    owner: r.en_suite_of.map(|o| o + i),
                    floor_material: None,
                    wall_material: None,
                });
            }
        }
        for (i, r) in requests.iter().enumerate() {
            if let Some(o) = r.owner
                && (o >= requests.len() || o == i)
            {
                return Err(ToolError::bad_args(format!(
                    "en_suite_of {o} does not name another room of the list"
                )));
            }
        }
        let base = &s.brief;
        s.brief = HouseBrief {
            is_house: requests.len() > 1 || base.is_house,
            rooms: requests,
            open_pairs: Vec::new(),
            ..base.clone()
        };
    }
    if let Some(h) = a.wall_height_m {
        s.brief.wall_height = Some(h);
    }
    let mut spec = spec::house_spec(&s.brief);
    for (r, size) in spec.rooms.iter_mut().zip(&sizes) {
        if let Some(size) = size {
            r.size = *size;
            r.min_side = r.min_side.min(size[1]);
        }
    }
    if !sizes.is_empty() {
        spec::connect(&mut spec);
    }
    s.doors.clear();
    s.windows.clear();
    s.placement = Default::default();
    s.install(spec, false);
    Ok(s.summary(Vec::new()))
}

/// Arguments of `resize_room`.
#[derive(Debug, Deserialize, JsonSchema)]
pub struct ResizeArgs {
    /// Room id.
    pub room: String,
    /// New clear width, metres.
    pub width_m: f64,
    /// New clear depth, metres.
    pub depth_m: f64,
}

fn resize_room(s: &mut LayoutState, a: ResizeArgs) -> Result<LayoutSummary, ToolError> {
    room_exists(s, &a.room)?;
    for v in [a.width_m, a.depth_m] {
        if !(1.0..=40.0).contains(&v) {
            return Err(ToolError::bad_args("sizes must be between 1 and 40 m"));
        }
    }
    let mut spec = s.spec().map_err(fail)?.clone();
    if let Some(r) = spec.rooms.iter_mut().find(|r| r.id == a.room) {
        r.size = [a.width_m.max(a.depth_m), a.width_m.min(a.depth_m)];
        r.min_side = r.min_side.min(r.size[1]);
    }
    let moved = s.install(spec, true);
    Ok(s.summary(moved))
}

/// Two rooms.
#[derive(Debug, Deserialize, JsonSchema)]
pub struct PairArgs {
    /// One room id.
    pub room_a: String,
    /// The other room id.
    pub room_b: String,
}

fn check_pair(s: &LayoutState, a: &PairArgs) -> Result<(), ToolError> {
    room_exists(s, &a.room_a)?;
    room_exists(s, &a.room_b)?;
    if a.room_a == a.room_b {
        return Err(ToolError::bad_args("give two different rooms"));
    }
    Ok(())
}

fn set_link(
    s: &mut LayoutState,
    a: &PairArgs,
    link: Option<Link>,
) -> Result<LayoutSummary, ToolError> {
    check_pair(s, a)?;
    let mut spec = s.spec().map_err(fail)?.clone();
    spec.adjacency.retain(|p| !p.joins(&a.room_a, &a.room_b));
    if let Some(link) = link {
        spec.adjacency.push(Adjacency {
            a: a.room_a.clone(),
            b: a.room_b.clone(),
            link,
        });
    }
    let adjacent = s.placement.shared(&a.room_a, &a.room_b) >= MIN_SHARED - 1e-6;
    let moved = if link.is_some_and(|l| l != Link::Preferred) && !adjacent {
        s.install(spec, true)
    } else {
        s.spec = Some(spec);
        s.replan_openings();
        Vec::new()
    };
    Ok(s.summary(moved))
}

fn add_adjacency(s: &mut LayoutState, a: PairArgs) -> Result<LayoutSummary, ToolError> {
    let link = match s.spec().map_err(fail)?.pair(&a.room_a, &a.room_b) {
        Some(p) if p.link == Link::Open => Link::Open,
        _ => Link::Door,
    };
    set_link(s, &a, Some(link))
}

fn remove_adjacency(s: &mut LayoutState, a: PairArgs) -> Result<LayoutSummary, ToolError> {
    check_pair(s, &a)?;
    if s.spec().map_err(fail)?.pair(&a.room_a, &a.room_b).is_none() {
        return Err(fail(format!(
            "{} and {} have no adjacency requirement",
            a.room_a, a.room_b
        )));
    }
    set_link(s, &a, None)
}

fn add_open_connection(s: &mut LayoutState, a: PairArgs) -> Result<LayoutSummary, ToolError> {
    check_pair(s, &a)?;
    let spec = s.spec().map_err(fail)?;
    let wet = [&a.room_a, &a.room_b].iter().any(|id| {
        spec.room(id)
            .is_some_and(|r| matches!(r.role, Role::Wet | Role::Service))
    });
    if wet {
        return Err(fail(
            "bathrooms, storage and technical rooms keep their walls; connect them with a door",
        ));
    }
    set_link(s, &a, Some(Link::Open))
}

fn remove_open_connection(s: &mut LayoutState, a: PairArgs) -> Result<LayoutSummary, ToolError> {
    check_pair(s, &a)?;
    match s.spec().map_err(fail)?.pair(&a.room_a, &a.room_b) {
        Some(p) if p.link == Link::Open => set_link(s, &a, Some(Link::Door)),
        _ => Err(fail(format!(
            "{} and {} are not openly connected",
            a.room_a, a.room_b
        ))),
    }
}

/// Arguments of `set_wall_height`.
#[derive(Debug, Deserialize, JsonSchema)]
pub struct HeightArgs {
    /// Floor-to-ceiling height for every room, metres (2.2 - 6.0).
    pub height_m: f64,
}

fn set_wall_height(s: &mut LayoutState, a: HeightArgs) -> Result<LayoutSummary, ToolError> {
    if !(2.2..=6.0).contains(&a.height_m) {
        return Err(ToolError::bad_args("height_m must be between 2.2 and 6.0"));
    }
    let mut spec = s.spec().map_err(fail)?.clone();
    spec.wall_height = a.height_m;
    s.brief.wall_height = Some(a.height_m);
    for w in &mut s.windows {
        w.height = w.height.min(a.height_m - w.sill - 0.2).max(0.3);
    }
    s.spec = Some(spec);
    Ok(s.summary(Vec::new()))
}

/// Arguments of `add_door`.
#[derive(Debug, Deserialize, JsonSchema)]
pub struct DoorArgs {
    /// Room id.
    pub room_a: String,
    /// The neighbouring room id, or "outside" for an exterior door.
    pub room_b: String,
    /// `left`, `center` or `right` along the shared wall (default center).
    #[serde(default)]
    pub position: Option<DoorPos>,
    /// For an exterior door: side of room_a (`north`, `east`, `south`, `west`); the longest
    /// outside wall when omitted.
    #[serde(default)]
    pub side: Option<String>,
    /// Width, metres (0.7 - 2.0, default 0.9; 1.0 outside).
    #[serde(default)]
    pub width_m: Option<f64>,
}

/// A door or window that was added.
#[derive(Debug, Serialize, JsonSchema)]
pub struct Added {
    /// Its id.
    pub id: String,
    /// Remarks (empty: it is in place as asked).
    pub notes: Vec<String>,
}

fn add_door(s: &mut LayoutState, a: DoorArgs) -> Result<Added, ToolError> {
    room_exists(s, &a.room_a)?;
    let outside = matches!(
        a.room_b.trim().to_lowercase().as_str(),
        "outside" | "exterior" | "none"
    );
    let width = a.width_m.unwrap_or(if outside { 1.0 } else { 0.9 });
    if !(0.7..=2.0).contains(&width) {
        return Err(ToolError::bad_args("width_m must be between 0.7 and 2.0"));
    }
    let side = match &a.side {
        Some(x) => Some(Side::parse(x).ok_or_else(|| {
            ToolError::bad_args(format!(
                "unknown side {x:?}; use north, east, south or west"
            ))
        })?),
        None => None,
    };
    let ivs = intervals(&s.placement, &a.room_a);
    let (b, side) = if outside {
        let fits: Vec<_> = ivs
            .iter()
            .filter(|iv| iv.outside && iv.len() >= width + 0.35)
            .filter(|iv| side.is_none_or(|sd| iv.side == sd))
            .collect();
        let best = fits
            .iter()
            .max_by(|x, y| x.len().total_cmp(&y.len()))
            .ok_or_else(|| {
                fail(format!(
                    "{} has no outside wall{} long enough for a {width:.2} m door",
                    a.room_a,
                    side.map(|s| format!(" on the {} side", s.as_str()))
                        .unwrap_or_default()
                ))
            })?;
        (None, Some(best.side))
    } else {
        room_exists(s, &a.room_b)?;
        let shared = s.placement.shared(&a.room_a, &a.room_b);
        if shared < width + 0.35 {
            return Err(fail(format!(
                "{} and {} share {shared:.2} m of wall; a {width:.2} m door needs {:.2} m \
                 (add_adjacency to move them together)",
                a.room_a,
                a.room_b,
                width + 0.35
            )));
        }
        let spec = s.spec().map_err(fail)?;
        for (x, y) in [(&a.room_a, &a.room_b), (&a.room_b, &a.room_a)] {
            if let Some(owner) = spec.room(x).and_then(|r| r.owner.clone())
                && owner != *y
            {
                return Err(fail(format!(
                    "{x} is the en-suite of {owner}; it is entered only from there"
                )));
            }
        }
        (Some(a.room_b.clone()), None)
    };
    if s.doors
        .iter()
        .any(|d| d.joins(&a.room_a, b.as_deref()) && b.is_some())
    {
        return Err(fail(format!(
            "{} and {} already have a door",
            a.room_a, a.room_b
        )));
    }
    let id = s.next_id("door");
    s.doors.push(DoorSpec {
        id: id.clone(),
        a: a.room_a.clone(),
        b,
        pos: a.position.unwrap_or(DoorPos::Center),
        side,
        width,
        auto: false,
    });
    let (_, notes) = s.rooms();
    if let Some(n) = notes.notes.iter().find(|n| n.starts_with(&id)) {
        let n = n.clone();
        s.doors.retain(|d| d.id != id);
        return Err(fail(n));
    }
    Ok(Added {
        notes: Vec::new(),
        id,
    })
}

/// An id.
#[derive(Debug, Deserialize, JsonSchema)]
pub struct IdArgs {
    /// Door or window id.
    pub id: String,
}

fn remove_door(s: &mut LayoutState, a: IdArgs) -> Result<LayoutSummary, ToolError> {
    let before = s.doors.len();
    s.doors.retain(|d| d.id != a.id);
    if s.doors.len() == before {
        return Err(ToolError::bad_args(format!(
            "no door {:?}; doors: {}",
            a.id,
            s.doors
                .iter()
                .map(|d| d.id.as_str())
                .collect::<Vec<_>>()
                .join(", ")
        )));
    }
    Ok(s.summary(Vec::new()))
}

/// Arguments of `add_window`.
#[derive(Debug, Deserialize, JsonSchema)]
pub struct WindowArgs {
    /// Room id.
    pub room: String,
    /// Side of the room (`north`, `east`, `south`, `west`); its longest outside wall when
    /// omitted.
    #[serde(default)]
    pub side: Option<String>,
    /// Width, metres (0.4 - 4.0, default 1.2).
    #[serde(default)]
    pub width_m: Option<f64>,
    /// Sill height, metres (default from the room type).
    #[serde(default)]
    pub sill_m: Option<f64>,
    /// Height, metres.
    #[serde(default)]
    pub height_m: Option<f64>,
}

fn add_window(s: &mut LayoutState, a: WindowArgs) -> Result<Added, ToolError> {
    room_exists(s, &a.room)?;
    let spec = s.spec().map_err(fail)?.clone();
    let Some(r) = spec.room(&a.room) else {
        return Err(ToolError::bad_args("no such room"));
    };
    let [dw, dh] = connect::window_size(r.sill, spec.wall_height, r.role == Role::Wet);
    let width = a.width_m.unwrap_or(dw);
    let sill = a.sill_m.unwrap_or(r.sill);
    let height = a.height_m.unwrap_or(dh);
    if !(0.4..=4.0).contains(&width)
        || !(0.0..=2.0).contains(&sill)
        || !(0.3..=3.0).contains(&height)
    {
        return Err(ToolError::bad_args(
            "width_m 0.4-4.0, sill_m 0-2.0, height_m 0.3-3.0",
        ));
    }
    if sill + height > spec.wall_height - 0.1 {
        return Err(ToolError::bad_args(format!(
            "sill + height must stay 0.1 m under the {:.2} m ceiling",
            spec.wall_height
        )));
    }
    let want = match &a.side {
        Some(x) => Some(Side::parse(x).ok_or_else(|| {
            ToolError::bad_args(format!(
                "unknown side {x:?}; use north, east, south or west"
            ))
        })?),
        None => None,
    };
    let iv = intervals(&s.placement, &a.room)
        .into_iter()
        .filter(|iv| iv.outside && iv.len() >= width + 0.4)
        .filter(|iv| want.is_none_or(|sd| iv.side == sd))
        .max_by(|x, y| x.len().total_cmp(&y.len()))
        .ok_or_else(|| {
            fail(format!(
                "{} has no outside wall{} long enough for a {width:.2} m window",
                a.room,
                want.map(|s| format!(" on the {} side", s.as_str()))
                    .unwrap_or_default()
            ))
        })?;
    let cell = s.placement.cells[&a.room];
    let (lo, len) = connect::side_extent(&cell, iv.side);
    let mid = (iv.lo + iv.hi) / 2.0;
    let along = match iv.side {
        Side::South | Side::East => (mid - lo) / len,
        Side::North | Side::West => 1.0 - (mid - lo) / len,
    };
    let id = s.next_id("window");
    s.windows.push(WindowSpec {
        id: id.clone(),
        room: a.room.clone(),
        side: iv.side,
        along,
        width,
        height,
        sill,
        auto: false,
    });
    let (_, notes) = s.rooms();
    if let Some(n) = notes.notes.iter().find(|n| n.starts_with(&id)) {
        let n = n.clone();
        s.windows.retain(|w| w.id != id);
        return Err(fail(n));
    }
    Ok(Added {
        notes: Vec::new(),
        id,
    })
}

fn remove_window(s: &mut LayoutState, a: IdArgs) -> Result<LayoutSummary, ToolError> {
    let before = s.windows.len();
    s.windows.retain(|w| w.id != a.id);
    if s.windows.len() == before {
        return Err(ToolError::bad_args(format!("no window {:?}", a.id)));
    }
    Ok(s.summary(Vec::new()))
}

/// Arguments of `get_material`.
#[derive(Debug, Deserialize, JsonSchema)]
pub struct MaterialArgs {
    /// Words describing the material, e.g. "light hardwood", "polished concrete".
    pub description: String,
}

fn get_material(
    _: &mut LayoutState,
    a: MaterialArgs,
) -> Result<materials::MaterialInfo, ToolError> {
    materials::lookup(&a.description).ok_or_else(|| {
        fail(format!(
            "no material matches {:?}; known: {}",
            a.description,
            crate::assets::material::names().join(", ")
        ))
    })
}

/// Arguments of `set_room_materials`.
#[derive(Debug, Deserialize, JsonSchema)]
pub struct SetMaterialsArgs {
    /// Room id, or "all".
    pub room: String,
    /// Floor material (a name or words such as "hardwood").
    #[serde(default)]
    pub floor: Option<String>,
    /// Wall material.
    #[serde(default)]
    pub wall: Option<String>,
}

fn set_room_materials(
    s: &mut LayoutState,
    a: SetMaterialsArgs,
) -> Result<LayoutSummary, ToolError> {
    let resolve = |d: &Option<String>| -> Result<Option<String>, ToolError> {
        match d {
            None => Ok(None),
            Some(x) => materials::lookup(x)
                .map(|m| Some(m.material))
                .ok_or_else(|| fail(format!("no material matches {x:?}"))),
        }
    };
    let (floor, wall) = (resolve(&a.floor)?, resolve(&a.wall)?);
    if floor.is_none() && wall.is_none() {
        return Err(ToolError::bad_args("give floor, wall or both"));
    }
    let all = a.room.trim().eq_ignore_ascii_case("all");
    if !all {
        room_exists(s, &a.room)?;
    }
    let mut spec = s.spec().map_err(fail)?.clone();
    for r in spec.rooms.iter_mut().filter(|r| all || r.id == a.room) {
        if let Some(f) = &floor {
            r.floor_material = f.clone();
        }
        if let Some(w) = &wall {
            r.wall_material = w.clone();
        }
    }
    s.spec = Some(spec);
    Ok(s.summary(Vec::new()))
}

fn validate(s: &mut LayoutState, _: NoArgs) -> Result<Validation, ToolError> {
    Ok(s.validation())
}

/// The ASCII floor plan.
#[derive(Debug, Serialize, JsonSchema)]
pub struct AsciiPlan {
    /// The plan and the wall legend.
    pub text: String,
}

fn render_ascii(s: &mut LayoutState, _: NoArgs) -> Result<AsciiPlan, ToolError> {
    let (rooms, _) = s.rooms();
    Ok(AsciiPlan {
        text: ascii::render(&rooms),
    })
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

fn round2(v: f64) -> f64 {
    (v * 100.0).round() / 100.0
}

fn observe_scene(s: &mut LayoutState, _: NoArgs) -> Result<LayoutObservation, ToolError> {
    observe(s)
}

/// The layout stage's tools.
pub fn toolbox() -> Toolbox<LayoutState> {
    let mut t = Toolbox::new();
    t.add("generate_room_specs", "Create the rooms and place them: from the prompt when `rooms` is omitted, or from the given list (room types, counts, optional sizes and contents, en-suites). Replaces the current layout.", Access::Modify, generate_room_specs);
    t.add("resize_room", "Set a room's clear size (metres) and re-place the house, keeping the other rooms where they were as far as possible.", Access::Modify, resize_room);
    t.add("add_adjacency", "Require two rooms to share a wall long enough for a door (re-places the house if they do not yet).", Access::Modify, add_adjacency);
    t.add(
        "remove_adjacency",
        "Drop the requirement that two rooms share a wall.",
        Access::Modify,
        remove_adjacency,
    );
    t.add("add_open_connection", "Remove the wall between two rooms (open plan); they are moved together if needed. Not for bathrooms or storage.", Access::Modify, add_open_connection);
    t.add(
        "remove_open_connection",
        "Put the wall back between two openly connected rooms (with a door).",
        Access::Modify,
        remove_open_connection,
    );
    t.add(
        "set_wall_height",
        "Set the floor-to-ceiling height of every room, metres.",
        Access::Modify,
        set_wall_height,
    );
    t.add("add_door", "Add a door between two rooms that share a wall (left, center or right along it), or an exterior door (room_b = \"outside\").", Access::Modify, add_door);
    t.add(
        "remove_door",
        "Remove a door by id.",
        Access::Modify,
        remove_door,
    );
    t.add(
        "add_window",
        "Add a window to an outside wall of a room (side, width, sill height).",
        Access::Modify,
        add_window,
    );
    t.add(
        "remove_window",
        "Remove a window by id.",
        Access::Modify,
        remove_window,
    );
    t.add("get_material", "Find the material table entry for words such as \"light hardwood\" or \"polished concrete\": name, colour, friction.", Access::Observe, get_material);
    t.add(
        "set_room_materials",
        "Set the floor and/or wall material of a room (or \"all\" rooms).",
        Access::Modify,
        set_room_materials,
    );
    t.add("validate", "Check the layout: every room reachable from the exterior door, en-suites only through their bedroom, no room only through a bathroom, required neighbours, overlaps, doors and windows that fit.", Access::Verify, validate);
    t.add("render_ascii", "The floor plan as text: walls, doors (D, E outside), windows (W), open connections (.), room ids and sizes, and every wall segment with its openings.", Access::Observe, render_ascii);
    t.add("observe_scene", "Every room with position, size, role, neighbours, doors, windows, materials and its prompt; requested rooms vs present; search statistics; validation errors.", Access::Observe, observe_scene);
    t
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::agents::Role as AgentRole;
    use serde_json::json;

    const FLAT: &str = "A two-bedroom apartment with a master bedroom, a second bedroom, a living room, a hallway, and a bathroom.";

    #[test]
    fn tool_names_are_the_ones_the_design_uses() {
        let t = toolbox();
        for name in [
            "generate_room_specs",
            "resize_room",
            "add_adjacency",
            "remove_adjacency",
            "add_open_connection",
            "remove_open_connection",
            "set_wall_height",
            "add_door",
            "remove_door",
            "add_window",
            "remove_window",
            "get_material",
            "set_room_materials",
            "validate",
            "render_ascii",
            "observe_scene",
        ] {
            assert!(t.spec(name).is_some(), "missing {name}");
        }
        assert_eq!(t.len(), 16);
        // The critic may look and verify, never edit.
        let critic: Vec<&str> = t
            .specs_for(AgentRole::Critic)
            .iter()
            .map(|s| s.name.as_str())
            .collect();
        assert!(critic.contains(&"validate") && !critic.contains(&"resize_room"));
    }

    #[test]
    fn edits_through_tools() {
        let t = toolbox();
        let mut s = LayoutState::new(FLAT, 1);
        let d = AgentRole::Designer;
        // Nothing generated yet: a clear error.
        let e = t
            .call(
                &mut s,
                d,
                "resize_room",
                json!({"room": "x", "width_m": 3, "depth_m": 3}),
            )
            .unwrap_err();
        assert!(e.message.contains("generate_room_specs"), "{e:?}");
        t.call(&mut s, d, "generate_room_specs", json!({})).unwrap();
        let v = t.call(&mut s, d, "validate", json!({})).unwrap();
        assert_eq!(v["ok"], true, "{v}");
        let obs = t.call(&mut s, d, "observe_scene", json!({})).unwrap();
        assert_eq!(obs["rooms"].as_array().unwrap().len(), 5);
        // Open plan between the living room and the hallway.
        t.call(
            &mut s,
            d,
            "add_open_connection",
            json!({"room_a": "living_room_0", "room_b": "hallway_0"}),
        )
        .unwrap();
        let (rooms, _) = s.rooms();
        assert!(
            rooms
                .iter()
                .flat_map(|r| &r.walls)
                .flat_map(|w| &w.openings)
                .any(|o| o.kind == OpeningKind::Open)
        );
        // Bathrooms keep their walls.
        let e = t
            .call(
                &mut s,
                d,
                "add_open_connection",
                json!({"room_a": "bathroom_0", "room_b": "hallway_0"}),
            )
            .unwrap_err();
        assert_eq!(e.kind, crate::agents::ToolErrorKind::Failed);
        // Materials by words.
        t.call(
            &mut s,
            d,
            "set_room_materials",
            json!({"room": "living_room_0", "floor": "polished concrete"}),
        )
        .unwrap();
        assert_eq!(
            s.spec
                .as_ref()
                .unwrap()
                .room("living_room_0")
                .unwrap()
                .floor_material,
            "concrete"
        );
        // Windows and doors: add and remove.
        let w = t
            .call(&mut s, d, "add_window", json!({"room": "living_room_0"}))
            .unwrap();
        let id = w["id"].as_str().unwrap().to_string();
        t.call(&mut s, d, "remove_window", json!({"id": id}))
            .unwrap();
        let e = t
            .call(
                &mut s,
                d,
                "add_door",
                json!({"room_a": "bathroom_0", "room_b": "nowhere"}),
            )
            .unwrap_err();
        assert_eq!(e.kind, crate::agents::ToolErrorKind::BadArguments);
        let text = t.call(&mut s, d, "render_ascii", json!({})).unwrap();
        assert!(text["text"].as_str().unwrap().contains("living_room_0"));
        t.call(&mut s, d, "set_wall_height", json!({"height_m": 3.0}))
            .unwrap();
        assert!(
            s.rooms()
                .0
                .iter()
                .all(|r| (r.wall_height - 3.0).abs() < 1e-12)
        );
    }
}
