//! Tools that change rooms: generate, resize, adjacency and open connections, wall height,
//! materials.

use schemars::JsonSchema;
use serde::Deserialize;

use super::{fail, room_exists};
use crate::agents::ToolError;
use crate::layout::brief::{HouseBrief, RoomRequest};
use crate::layout::knowledge::{self, Role, room_words};
use crate::layout::materials;
use crate::layout::search::MIN_SHARED;
use crate::layout::spec::{self, Adjacency, Link};
use crate::layout::state::{LayoutState, LayoutSummary};

/// One room for `generate_room_specs`.
#[derive(Debug, Deserialize, JsonSchema)]
pub struct RoomArg {
    /// Room type in words, e.g. "exam room", "kitchen", "corridor".
    pub room_type: String,
    /// How many rooms of this type (default 1).
    #[serde(default)]
    pub count: Option<u32>,
    /// Clear width (long side), metres; from the type's typical size and contents when omitted.
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

pub(super) fn type_key(words: &str) -> String {
    let toks = crate::words::tokenize(words);
    let key = words.trim().to_lowercase().replace([' ', '-'], "_");
    if knowledge::knowledge().get(&key).is_some() {
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

pub(super) fn generate_room_specs(
    s: &mut LayoutState,
    a: GenerateArgs,
) -> Result<LayoutSummary, ToolError> {
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

pub(super) fn resize_room(s: &mut LayoutState, a: ResizeArgs) -> Result<LayoutSummary, ToolError> {
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

pub(super) fn check_pair(s: &LayoutState, a: &PairArgs) -> Result<(), ToolError> {
    room_exists(s, &a.room_a)?;
    room_exists(s, &a.room_b)?;
    if a.room_a == a.room_b {
        return Err(ToolError::bad_args("give two different rooms"));
    }
    Ok(())
}

pub(super) fn set_link(
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

pub(super) fn add_adjacency(s: &mut LayoutState, a: PairArgs) -> Result<LayoutSummary, ToolError> {
    let link = match s.spec().map_err(fail)?.pair(&a.room_a, &a.room_b) {
        Some(p) if p.link == Link::Open => Link::Open,
        _ => Link::Door,
    };
    set_link(s, &a, Some(link))
}

pub(super) fn remove_adjacency(
    s: &mut LayoutState,
    a: PairArgs,
) -> Result<LayoutSummary, ToolError> {
    check_pair(s, &a)?;
    if s.spec().map_err(fail)?.pair(&a.room_a, &a.room_b).is_none() {
        return Err(fail(format!(
            "{} and {} have no adjacency requirement",
            a.room_a, a.room_b
        )));
    }
    set_link(s, &a, None)
}

pub(super) fn add_open_connection(
    s: &mut LayoutState,
    a: PairArgs,
) -> Result<LayoutSummary, ToolError> {
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

pub(super) fn remove_open_connection(
    s: &mut LayoutState,
    a: PairArgs,
) -> Result<LayoutSummary, ToolError> {
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

pub(super) fn set_wall_height(
    s: &mut LayoutState,
    a: HeightArgs,
) -> Result<LayoutSummary, ToolError> {
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

/// Arguments of `get_material`.
#[derive(Debug, Deserialize, JsonSchema)]
pub struct MaterialArgs {
    /// Words describing the material, e.g. "light hardwood", "polished concrete".
    pub description: String,
}

pub(super) fn get_material(
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

pub(super) fn set_room_materials(
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
