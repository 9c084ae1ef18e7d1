//! Manipuland stage: small objects on the surfaces of one supporting entity (a table top, the
//! levels of a shelf, a counter, a bed). Positions are surface-local: `u` along the surface's
//! width, `v` along its depth (towards the front), from its centre; the stage checks that
//! objects lie within the surface, clear of each other and below the free height above it.
//!
//! Composite tools build stacks (items resting on each other at the pitch where they nest),
//! fills (items inside a container's cavity surface), piles (layers of loosely packed items)
//! and place settings (plate, glass and cutlery in front of each seat).

use nalgebra::{UnitQuaternion, Vector3};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use super::common::{self, ObjectInfo, object_info};
use super::room::RoomFrame;
use super::{RoutedAsset, StageState};
use crate::agents::{Access, CategorySpec, ToolError, Toolbox};
use crate::assets::Asset;
use crate::physics::collision::{object_penetration, posed_object};
use crate::scene::{AssetRecord, ObjectKind, Pose, SceneObject, Support, SurfaceRecord};
use crate::state::SceneState;

/// Gap kept between neighbouring small objects, metres.
const GAP: f64 = 0.008;
/// Release height above a surface, metres (settling closes it).
const LIFT: f64 = 0.001;

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

/// A surface of an object in the room.
#[derive(Debug, Clone)]
pub struct SurfaceRef {
    /// Supporting object.
    pub parent: SceneObject,
    /// The surface (asset model frame).
    pub surface: SurfaceRecord,
}

impl SurfaceRef {
    /// `parent_id/surface_id`.
    pub fn key(&self) -> String {
        format!("{}/{}", self.parent.id, self.surface.id)
    }

    /// Behind a door or in a drawer: a surface of a moving link (a drawer), or any surface
    /// but the top of an articulated piece (shelves behind its doors).
    pub fn enclosed(&self, state: &StageState) -> bool {
        state
            .scene
            .scene
            .assets
            .get(&self.parent.asset)
            .is_some_and(|rec| super::clutter::is_enclosed(rec, &self.surface))
    }

    /// World pose of the surface frame (origin at its centre, on the surface).
    pub fn world_from_surface(&self) -> Pose {
        let c = self.surface.center;
        self.parent
            .world_from_object
            .compose(&Pose::from_xyz(c[0], c[1], c[2]))
    }
}

/// Finds `parent/surface` in the room.
pub fn find_surface(state: &StageState, key: &str) -> Result<SurfaceRef, ToolError> {
    let (pid, sid) = key.split_once('/').unwrap_or((key, "top"));
    let parent = state.scene.scene.object(pid).cloned().ok_or_else(|| {
        ToolError::failed(format!(
            "no object {pid:?}; call observe_surfaces for surface ids"
        ))
    })?;
    let rec = state
        .scene
        .scene
        .assets
        .get(&parent.asset)
        .ok_or_else(|| ToolError::failed("asset missing"))?;
    let surface = rec
        .surfaces
        .iter()
        .find(|s| s.id == sid)
        .cloned()
        .ok_or_else(|| {
            ToolError::failed(format!(
                "{pid} has no surface {sid:?}; its surfaces: {}",
                rec.surfaces
                    .iter()
                    .map(|s| s.id.as_str())
                    .collect::<Vec<_>>()
                    .join(", ")
            ))
        })?;
    Ok(SurfaceRef { parent, surface })
}

/// Axis-aligned extent of an asset under a local rotation: (lo, hi) in the rotated frame.
fn rotated_bounds(rec: &AssetRecord, rot: &UnitQuaternion<f64>) -> ([f64; 3], [f64; 3]) {
    let [lo, hi] = rec.bounds;
    let mut out_lo = [f64::INFINITY; 3];
    let mut out_hi = [f64::NEG_INFINITY; 3];
    for x in [lo[0], hi[0]] {
        for y in [lo[1], hi[1]] {
            for z in [lo[2], hi[2]] {
                let p = rot * Vector3::new(x, y, z);
                for k in 0..3 {
                    out_lo[k] = out_lo[k].min(p[k]);
                    out_hi[k] = out_hi[k].max(p[k]);
                }
            }
        }
    }
    (out_lo, out_hi)
}

/// An item's footprint on a surface: rectangle (surface frame) and height range above it.
#[derive(Debug, Clone, Copy)]
struct Slot {
    u: f64,
    v: f64,
    hu: f64,
    hv: f64,
}

impl Slot {
    fn overlaps(&self, o: &Slot) -> bool {
        (self.u - o.u).abs() < self.hu + o.hu + GAP && (self.v - o.v).abs() < self.hv + o.hv + GAP
    }
}

/// Footprints of the objects already resting (directly) on a surface.
fn occupied(scene: &SceneState, s: &SurfaceRef) -> Vec<Slot> {
    let surface_from_world = s.world_from_surface().inverse();
    scene
        .scene
        .objects
        .iter()
        .filter(|o| matches!(&o.support, Support::Object { parent, surface } if *parent == s.parent.id && *surface == s.surface.id))
        .filter_map(|o| {
            let rec = scene.scene.assets.get(&o.asset)?;
            let local = surface_from_world.compose(&o.world_from_object);
            let (lo, hi) = rotated_bounds(rec, &local.rotation());
            let t = local.translation();
            Some(Slot {
                u: t.x + (lo[0] + hi[0]) / 2.0,
                v: t.y + (lo[1] + hi[1]) / 2.0,
                hu: (hi[0] - lo[0]) / 2.0,
                hv: (hi[1] - lo[1]) / 2.0,
            })
        })
        .collect()
}

/// The supporting object's own collision pieces that reach into the free space above `s`
/// (a sideboard's partitions between its bays, a sink's basin over the shelf below), as
/// footprints clipped to the surface: an item placed across one would stand in the wood.
/// Furniture only; a container's cavity has its own fill rules.
fn parent_intrusions(scene: &SceneState, s: &SurfaceRef) -> Vec<Slot> {
    if s.parent.kind != ObjectKind::Furniture || is_cavity(s) {
        return Vec::new();
    }
    let Some(asset) = scene.assets.get(&s.parent.asset) else {
        return Vec::new();
    };
    intrusions(asset, &s.surface, &s.parent.joint_positions)
        .into_iter()
        .map(|[u0, u1, v0, v1]| Slot {
            u: (u0 + u1) / 2.0,
            v: (v0 + v1) / 2.0,
            hu: (u1 - u0) / 2.0,
            hv: (v1 - v0) / 2.0,
        })
        .collect()
}

/// Rectangles `[u0, u1, v0, v1]` (surface frame) of `asset`'s collision pieces that reach more
/// than 2 mm into the box of free space above `surface` (its rectangle, up to its clearance).
pub(crate) fn intrusions(
    asset: &Asset,
    surface: &SurfaceRecord,
    joints: &std::collections::BTreeMap<String, f64>,
) -> Vec<[f64; 4]> {
    const SLACK: f64 = 0.002;
    let model = posed_object("parent", asset, &Pose::IDENTITY, joints);
    let c = surface.center;
    let (su, sv) = (surface.size[0] / 2.0, surface.size[1] / 2.0);
    let (z0, z1) = (c[2] + SLACK, c[2] + surface.clearance - SLACK);
    model
        .pieces
        .iter()
        .filter(|p| p.hi.z > z0 && p.lo.z < z1)
        .filter_map(|p| {
            let [lo, hi] = slab_extent(&p.vertices, z0, z1)?;
            let (u0, u1) = ((lo[0] - c[0]).max(-su), (hi[0] - c[0]).min(su));
            let (v0, v1) = ((lo[1] - c[1]).max(-sv), (hi[1] - c[1]).min(sv));
            (u1 - u0 > SLACK && v1 - v0 > SLACK).then_some([u0, u1, v0, v1])
        })
        .collect()
}

/// Horizontal extent `[lo, hi]` of the part of a convex hull between heights `z0` and `z1`
/// (a slanted leg crosses a shelf's free space only where it passes through it): every segment
/// between two hull vertices lies in the hull, so clipping them all to the slab reaches every
/// corner of the clipped hull.
fn slab_extent(vertices: &[Vector3<f64>], z0: f64, z1: f64) -> Option<[[f64; 2]; 2]> {
    let mut lo = [f64::INFINITY; 2];
    let mut hi = [f64::NEG_INFINITY; 2];
    let mut add = |p: Vector3<f64>| {
        for k in 0..2 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    };
    for (i, a) in vertices.iter().enumerate() {
        if (z0..=z1).contains(&a.z) {
            add(*a);
        }
        for b in &vertices[i + 1..] {
            for z in [z0, z1] {
                if (a.z - z) * (b.z - z) < 0.0 {
                    add(a + (b - a) * ((z - a.z) / (b.z - a.z)));
                }
            }
        }
    }
    (lo[0] <= hi[0]).then_some([lo, hi])
}

/// Local rotation of an item on a surface: yaw, optionally laid on its side first.
fn item_rotation(yaw_deg: f64, lay_flat: bool) -> UnitQuaternion<f64> {
    let yaw = UnitQuaternion::from_axis_angle(&Vector3::z_axis(), yaw_deg.to_radians());
    if lay_flat {
        yaw * UnitQuaternion::from_axis_angle(&Vector3::y_axis(), std::f64::consts::FRAC_PI_2)
    } else {
        yaw
    }
}

/// A size for an item whose footprint overflows `s` that its category allows (no smaller
/// than the category's minimum) and that fits the surface with a small margin; `None` when it
/// fits as it is or no allowed size does.
fn shrunk_to_fit(s: &SurfaceRef, rec: &AssetRecord, rot: &UnitQuaternion<f64>) -> Option<[f64; 3]> {
    let (lo, hi) = rotated_bounds(rec, rot);
    let (w, d) = (hi[0] - lo[0], hi[1] - lo[1]);
    let (sw, sd) = (s.surface.size[0] * 0.97, s.surface.size[1] * 0.97);
    if w <= sw && d <= sd {
        return None;
    }
    let prior = crate::assets::procedural::prior(&rec.category)?;
    let factor = (sw / w).min(sd / d);
    let [bx, by, bz] = [0, 1, 2].map(|i| rec.bounds[1][i] - rec.bounds[0][i]);
    let size = [bx * factor, by * factor, bz * factor];
    let allowed = (0..3).all(|i| size[i] >= prior.min[i] - 1e-9);
    allowed.then_some(size)
}

/// Where an item goes on a surface; `None` when it does not fit.
#[allow(clippy::too_many_arguments)]
fn fit(
    state: &StageState,
    s: &SurfaceRef,
    rec: &AssetRecord,
    rot: &UnitQuaternion<f64>,
    at: Option<(f64, f64)>,
    extra: &[Slot],
) -> Result<(Pose, Slot), String> {
    fit_in(&state.scene, s, rec, rot, at, extra)
}

/// [`fit`] on a scene outside a stage (placing an object again after post-processing).
fn fit_in(
    scene: &SceneState,
    s: &SurfaceRef,
    rec: &AssetRecord,
    rot: &UnitQuaternion<f64>,
    at: Option<(f64, f64)>,
    extra: &[Slot],
) -> Result<(Pose, Slot), String> {
    let (lo, hi) = rotated_bounds(rec, rot);
    let (hu, hv, h) = ((hi[0] - lo[0]) / 2.0, (hi[1] - lo[1]) / 2.0, hi[2] - lo[2]);
    if h > s.surface.clearance - 0.003 {
        return Err(format!(
            "it is {:.2} m tall but {} has {:.2} m of free height",
            h,
            s.key(),
            s.surface.clearance
        ));
    }
    let (su, sv) = (s.surface.size[0] / 2.0, s.surface.size[1] / 2.0);
    if hu > su || hv > sv {
        return Err(format!(
            "it ({:.2} x {:.2} m) is larger than {} ({:.2} x {:.2} m)",
            2.0 * hu,
            2.0 * hv,
            s.key(),
            2.0 * su,
            2.0 * sv
        ));
    }
    let mut taken = occupied(scene, s);
    taken.extend(parent_intrusions(scene, s));
    taken.extend_from_slice(extra);
    let make = |u: f64, v: f64| Slot { u, v, hu, hv };
    let free = |slot: &Slot| {
        slot.u.abs() + slot.hu <= su + 1e-9
            && slot.v.abs() + slot.hv <= sv + 1e-9
            && !taken.iter().any(|o| o.overlaps(slot))
    };
    let slot = match at {
        Some((u, v)) => {
            let slot = make(u, v);
            if !free(&slot) {
                return Err(format!(
                    "({u:.2}, {v:.2}) on {} is taken or off the edge",
                    s.key()
                ));
            }
            slot
        }
        None => {
            // Raster from the back-left corner (the parent's -Y side: a desk's monitor and a
            // counter's appliances stand at the back), rows along u.
            let step = 0.01;
            let mut found = None;
            let mut v = -sv + hv;
            'scan: while v <= sv - hv + 1e-9 {
                let mut u = -su + hu;
                while u <= su - hu + 1e-9 {
                    let slot = make(u, v);
                    if free(&slot) {
                        found = Some(slot);
                        break 'scan;
                    }
                    u += step;
                }
                v += step;
            }
            found.ok_or_else(|| format!("no free spot left on {}", s.key()))?
        }
    };
    // Model origin so that the rotated bounds' centre sits at (u, v) and the bottom on the surface.
    let local = Pose(nalgebra::Isometry3::from_parts(
        nalgebra::Translation3::new(
            slot.u - (lo[0] + hi[0]) / 2.0,
            slot.v - (lo[1] + hi[1]) / 2.0,
            -lo[2] + LIFT,
        ),
        *rot,
    ));
    Ok((s.world_from_surface().compose(&local), slot))
}

/// Another place for `obj`, a small object that post-processing removed: the first free spot,
/// upright, on an open surface of its room that is not in `tried` (`parent/surface` keys).
/// Other surfaces of its own parent come first, then those of pieces of the same category,
/// then the rest, largest first; wet basins, cavities and the surfaces behind doors are left
/// out. Returns the object posed there and the surface's key.
pub fn spot_again(
    scene: &SceneState,
    obj: &SceneObject,
    tried: &[String],
) -> Option<(SceneObject, String)> {
    let rec = scene.scene.assets.get(&obj.asset)?;
    let (old_parent, old_category) = match &obj.support {
        Support::Object { parent, .. } => (
            parent.as_str(),
            scene.scene.object(parent).map(|p| p.category.as_str()),
        ),
        _ => ("", None),
    };
    let mut candidates: Vec<(u8, f64, SurfaceRef)> = Vec::new();
    for o in scene.scene.objects.iter().filter(|o| {
        o.room == obj.room
            && o.id != obj.id
            && !matches!(o.kind, ObjectKind::Manipuland | ObjectKind::Architecture)
    }) {
        let Some(parent_rec) = scene.scene.assets.get(&o.asset) else {
            continue;
        };
        for s in &parent_rec.surfaces {
            let sref = SurfaceRef {
                parent: o.clone(),
                surface: s.clone(),
            };
            if s.id == "basin"
                || is_cavity(&sref)
                || super::clutter::is_enclosed(parent_rec, s)
                || tried.contains(&sref.key())
            {
                continue;
            }
            let rank = if o.id == old_parent {
                0
            } else if Some(o.category.as_str()) == old_category {
                1
            } else {
                2
            };
            candidates.push((rank, -s.size[0] * s.size[1], sref));
        }
    }
    candidates.sort_by(|a, b| a.0.cmp(&b.0).then(a.1.total_cmp(&b.1)));
    let rot = item_rotation(0.0, false);
    candidates.into_iter().find_map(|(_, _, s)| {
        let (pose, _) = fit_in(scene, &s, rec, &rot, None, &[]).ok()?;
        let placed = SceneObject {
            world_from_object: pose,
            support: Support::Object {
                parent: s.parent.id.clone(),
                surface: s.surface.id.clone(),
            },
            ..obj.clone()
        };
        Some((placed, s.key()))
    })
}

/// Adds a manipuland resting on `support`.
fn add_item(
    state: &mut StageState,
    routed: &RoutedAsset,
    pose: Pose,
    parent: &str,
    surface: &str,
) -> String {
    state.add_routed(
        routed,
        ObjectKind::Manipuland,
        pose,
        Support::Object {
            parent: parent.to_string(),
            surface: surface.to_string(),
        },
    )
}

/// Smallest vertical offset at which a second copy of `asset` rests on the first without
/// penetrating it (how far plates or bowls nest), found by bisection on parry3d contacts.
pub fn stack_pitch(asset: &Asset) -> f64 {
    let [lo, hi] = asset.bounds();
    let height = hi[2] - lo[2];
    let none = std::collections::BTreeMap::new();
    let base = posed_object("a", asset, &Pose::IDENTITY, &none);
    let overlaps = |dz: f64| {
        let up = posed_object("b", asset, &Pose::from_xyz(0.0, 0.0, dz), &none);
        object_penetration(&base, &up) > 1e-4
    };
    let (mut low, mut high) = (0.0, height);
    for _ in 0..24 {
        let mid = (low + high) / 2.0;
        if overlaps(mid) {
            low = mid;
        } else {
            high = mid;
        }
    }
    high + 0.0005
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

/// Place settings at a table.
#[derive(Debug, Deserialize, JsonSchema)]
pub struct SettingsArgs {
    /// Table top surface (`object_id/surface_id`).
    pub surface: String,
    /// Items of one setting, e.g. ["plate", "glass", "fork", "knife"].
    pub items: Vec<String>,
    /// Number of settings; one per seat facing the table when omitted.
    #[serde(default)]
    pub settings: Option<u32>,
}

/// What a placement tool did.
#[derive(Debug, Serialize, JsonSchema, Default)]
pub struct PlaceResult {
    /// New objects.
    pub placed: Vec<ObjectInfo>,
    /// Remarks.
    pub notes: Vec<String>,
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

fn place_stack(state: &mut StageState, a: GroupArgs) -> Result<PlaceResult, ToolError> {
    if a.count == 0 || a.count > 40 {
        return Err(ToolError::bad_args("count must be between 1 and 40"));
    }
    let s = find_surface(state, &a.surface)?;
    let routed = state.route_asset(&a.description, None)?;
    let pitch = stack_pitch(&state.scene.assets[&routed.asset]);
    let ids =
        stack_on(state, &s, &routed, pitch, a.count, a.u.zip(a.v)).map_err(ToolError::failed)?;
    let n = ids.len() as u32;
    let notes = if n < a.count {
        vec![format!(
            "only {n} fit under the free height of {}; start another stack",
            s.key()
        )]
    } else {
        vec![]
    };
    result_for(state, &ids, [routed.notes.clone(), notes].concat())
}

/// Copies of a nesting item (plates, bowls) in one heap: at most this many per stack.
const NESTED_PILE: u32 = 4;

/// Whether copies of an asset stacked `pitch` apart lie in one another (plates, bowls)
/// rather than on top.
fn nests(state: &StageState, routed: &RoutedAsset, pitch: f64) -> bool {
    let [lo, hi] = state.scene.assets[&routed.asset].bounds();
    pitch < 0.6 * (hi[2] - lo[2])
}

/// Whether a surface is a container's cavity (things pack in it and heap over its rim).
fn is_cavity(s: &SurfaceRef) -> bool {
    s.surface.id.starts_with("inside")
}

/// One stack of up to `count` copies `pitch` apart on `s` (at `at` or the first free spot),
/// as many as the free height allows.
fn stack_on(
    state: &mut StageState,
    s: &SurfaceRef,
    routed: &RoutedAsset,
    pitch: f64,
    count: u32,
    at: Option<(f64, f64)>,
) -> Result<Vec<String>, String> {
    let rec = state.scene.scene.assets[&routed.asset].clone();
    let (base, _) = fit(state, s, &rec, &item_rotation(0.0, false), at, &[])?;
    let height = rec.bounds[1][2] - rec.bounds[0][2];
    let max = (((s.surface.clearance - height) / pitch).floor() as u32 + 1).max(1);
    let mut ids = vec![add_item(state, routed, base, &s.parent.id, &s.surface.id)];
    for k in 1..count.min(max) {
        let pose = Pose::from_xyz(0.0, 0.0, pitch * k as f64 + LIFT).compose(&base);
        let below = ids[ids.len() - 1].clone();
        ids.push(add_item(state, routed, pose, &below, "stack"));
    }
    Ok(ids)
}

/// Places `count` copies in layers over a surface (piles and fills).
fn place_layers(
    state: &mut StageState,
    s: &SurfaceRef,
    routed: &RoutedAsset,
    count: u32,
) -> Result<Vec<String>, ToolError> {
    let rec = state.scene.scene.assets[&routed.asset].clone();
    let mut ids = Vec::new();
    let mut layer_z = 0.0;
    let height = rec.bounds[1][2] - rec.bounds[0][2];
    // In a container's cavity things pack tight (quarter turns with a little play) and the
    // top layer may heap above the rim; on an open surface a pile turns every piece its own
    // way.
    let cavity = is_cavity(s);
    let heap = if cavity { height } else { 0.0 };
    // A bowl widens upwards: above the bottom layer, things rest on the sloping wall and on
    // each other over the square inscribed in the opening, not only over the flat bottom.
    let opening = state
        .scene
        .scene
        .assets
        .get(&s.parent.asset)
        .map(|r| {
            [
                (0.7 * (r.bounds[1][0] - r.bounds[0][0])).max(s.surface.size[0]),
                (0.7 * (r.bounds[1][1] - r.bounds[0][1])).max(s.surface.size[1]),
            ]
        })
        .unwrap_or(s.surface.size);
    // On an open surface a pile is a heap, not a row over the whole surface: the bottom
    // layer holds about two thirds of it, and each layer above rests over the footprint of
    // the one below.
    let bottom_cap = if cavity || count < 3 {
        count
    } else {
        (2 * count).div_ceil(3)
    };
    let mut region: Option<SurfaceRecord> = if bottom_cap < count {
        pile_patch(state, s, &rec, bottom_cap)
    } else {
        None
    };
    let mut bottom: Vec<Slot> = Vec::new();
    while (ids.len() as u32) < count {
        let mut extra: Vec<Slot> = Vec::new();
        let mut placed_in_layer = 0;
        let layer_cap = if layer_z == 0.0 { bottom_cap } else { count };
        while (ids.len() as u32) < count && placed_in_layer < layer_cap {
            let k = ids.len() as f64;
            let yaw = if cavity {
                90.0 * (k % 2.0) + 4.0 * (k % 3.0)
            } else {
                37.0 * k
            };
            let rot = item_rotation(yaw, false);
            let base = region.clone().unwrap_or_else(|| s.surface.clone());
            let layer = SurfaceRef {
                parent: s.parent.clone(),
                surface: SurfaceRecord {
                    clearance: s.surface.clearance + heap - layer_z,
                    size: if cavity && layer_z > 0.0 {
                        opening
                    } else {
                        base.size
                    },
                    ..base
                },
            };
            // Upper layers ignore the lower layer's footprints (they rest on it).
            let lower_free = if layer_z > 0.0 { &extra[..] } else { &[] };
            let attempt = if layer_z > 0.0 {
                fit_ignoring_surface(state, &layer, &rec, &rot, lower_free)
            } else {
                fit(state, &layer, &rec, &rot, None, &extra).ok()
            };
            let Some((pose, slot)) = attempt else { break };
            let pose = Pose::from_xyz(0.0, 0.0, layer_z).compose(&pose);
            ids.push(add_item(state, routed, pose, &s.parent.id, &s.surface.id));
            extra.push(slot);
            placed_in_layer += 1;
        }
        // A cavity whose bottom is already taken still has room above it.
        if placed_in_layer == 0 && !(cavity && layer_z == 0.0) {
            break;
        }
        if layer_z == 0.0 {
            bottom = extra.clone();
        }
        if !cavity {
            region = footprint_region(region.as_ref().unwrap_or(&s.surface), &extra);
        }
        layer_z += height + 0.002;
        // In a cavity a layer may start anywhere below the rim (a heaped fruit bowl); on an
        // open surface every layer stays under the free height.
        let full = if cavity {
            layer_z >= s.surface.clearance
        } else {
            layer_z + height > s.surface.clearance
        };
        if full {
            break;
        }
    }
    // What the upper layers could not hold spreads on the bottom layer.
    while !cavity && (ids.len() as u32) < count {
        let k = ids.len() as f64;
        let rot = item_rotation(37.0 * k, false);
        let Ok((pose, slot)) = fit(state, s, &rec, &rot, None, &bottom) else {
            break;
        };
        ids.push(add_item(state, routed, pose, &s.parent.id, &s.surface.id));
        bottom.push(slot);
    }
    Ok(ids)
}

/// A free square patch of `s` for the bottom layer of a pile of `n` copies of `rec` (side:
/// about sqrt(n) items turned any way), or None when no such patch is free.
fn pile_patch(
    state: &StageState,
    s: &SurfaceRef,
    rec: &AssetRecord,
    n: u32,
) -> Option<SurfaceRecord> {
    let (wx, wy) = (
        rec.bounds[1][0] - rec.bounds[0][0],
        rec.bounds[1][1] - rec.bounds[0][1],
    );
    let item = wx.hypot(wy) + GAP;
    let side = f64::from(n).sqrt().ceil() * item + GAP;
    let mut patch = rec.clone();
    patch.bounds[0][0] = -side / 2.0;
    patch.bounds[1][0] = side / 2.0;
    patch.bounds[0][1] = -side / 2.0;
    patch.bounds[1][1] = side / 2.0;
    let (_, slot) = fit(state, s, &patch, &UnitQuaternion::identity(), None, &[]).ok()?;
    Some(sub_region(&s.surface, slot.u, slot.v, [side, side]))
}

/// The rectangle of `surface` of `size` centred at (`u`, `v`) in its frame.
fn sub_region(surface: &SurfaceRecord, u: f64, v: f64, size: [f64; 2]) -> SurfaceRecord {
    let mut out = surface.clone();
    out.center[0] += u;
    out.center[1] += v;
    out.size = size;
    out
}

/// The part of `surface` under the footprints of `slots` (the next pile layer rests on
/// them), or None when there are none.
fn footprint_region(surface: &SurfaceRecord, slots: &[Slot]) -> Option<SurfaceRecord> {
    let lo_u = slots.iter().map(|s| s.u - s.hu).reduce(f64::min)?;
    let hi_u = slots.iter().map(|s| s.u + s.hu).reduce(f64::max)?;
    let lo_v = slots.iter().map(|s| s.v - s.hv).reduce(f64::min)?;
    let hi_v = slots.iter().map(|s| s.v + s.hv).reduce(f64::max)?;
    Some(sub_region(
        surface,
        (lo_u + hi_u) / 2.0,
        (lo_v + hi_v) / 2.0,
        [hi_u - lo_u, hi_v - lo_v],
    ))
}

/// Like [`fit`] but only against `extra` (items of the same layer), for upper pile layers.
fn fit_ignoring_surface(
    _state: &StageState,
    s: &SurfaceRef,
    rec: &AssetRecord,
    rot: &UnitQuaternion<f64>,
    extra: &[Slot],
) -> Option<(Pose, Slot)> {
    let (lo, hi) = rotated_bounds(rec, rot);
    let (hu, hv) = ((hi[0] - lo[0]) / 2.0, (hi[1] - lo[1]) / 2.0);
    let (su, sv) = (s.surface.size[0] / 2.0 - hu, s.surface.size[1] / 2.0 - hv);
    if su < 0.0 || sv < 0.0 {
        return None;
    }
    let mut v = sv;
    while v >= -sv - 1e-9 {
        let mut u = -su;
        while u <= su + 1e-9 {
            let slot = Slot { u, v, hu, hv };
            if !extra.iter().any(|o| o.overlaps(&slot)) {
                let local = Pose(nalgebra::Isometry3::from_parts(
                    nalgebra::Translation3::new(
                        u - (lo[0] + hi[0]) / 2.0,
                        v - (lo[1] + hi[1]) / 2.0,
                        -lo[2] + LIFT,
                    ),
                    *rot,
                ));
                return Some((s.world_from_surface().compose(&local), slot));
            }
            u += 0.01;
        }
        v -= 0.01;
    }
    None
}

fn place_pile(state: &mut StageState, a: GroupArgs) -> Result<PlaceResult, ToolError> {
    if a.count == 0 || a.count > 60 {
        return Err(ToolError::bad_args("count must be between 1 and 60"));
    }
    let s = find_surface(state, &a.surface)?;
    let routed = state.route_asset(&a.description, None)?;
    let pitch = stack_pitch(&state.scene.assets[&routed.asset]);
    let ids = if nests(state, &routed, pitch) && !is_cavity(&s) {
        // Plates and bowls in a heap lie in one another: a few short stacks.
        let mut ids = Vec::new();
        while (ids.len() as u32) < a.count {
            let n = (a.count - ids.len() as u32).min(NESTED_PILE);
            let Ok(stack) = stack_on(state, &s, &routed, pitch, n, None) else {
                break;
            };
            ids.extend(stack);
        }
        ids
    } else {
        place_layers(state, &s, &routed, a.count)?
    };
    if ids.is_empty() {
        return Err(ToolError::failed(format!(
            "no room for a pile on {}",
            s.key()
        )));
    }
    let notes = if (ids.len() as u32) < a.count {
        vec![format!(
            "only {} of {} fit on {}",
            ids.len(),
            a.count,
            s.key()
        )]
    } else {
        vec![]
    };
    result_for(state, &ids, [routed.notes.clone(), notes].concat())
}

/// Fill a container.
#[derive(Debug, Deserialize, JsonSchema)]
pub struct FillArgs {
    /// Id of the container object (bowl, bin, basket, box, refrigerator...).
    pub container: String,
    /// What to put in it, e.g. "apple".
    pub description: String,
    /// How many.
    pub count: u32,
}

fn place_inside(state: &mut StageState, a: FillArgs) -> Result<PlaceResult, ToolError> {
    if a.count == 0 || a.count > 60 {
        return Err(ToolError::bad_args("count must be between 1 and 60"));
    }
    let container = state
        .scene
        .scene
        .object(&a.container)
        .cloned()
        .ok_or_else(|| ToolError::failed(format!("no object {:?}", a.container)))?;
    let rec = state.scene.scene.assets[&container.asset].clone();
    if rec.surfaces.is_empty() {
        return Err(ToolError::failed(format!(
            "{} has no inside or top surface to fill",
            a.container
        )));
    }
    // Cavities first (surface ids starting with "inside"), then shelves, then the rest.
    let mut surfaces = rec.surfaces.clone();
    surfaces.sort_by_key(|s| {
        (
            !s.id.starts_with("inside"),
            !s.id.starts_with("shelf"),
            s.id.clone(),
        )
    });
    let fill = |state: &mut StageState,
                size: Option<[f64; 3]>|
     -> Result<(RoutedAsset, Vec<String>), ToolError> {
        let routed = state.route_asset(&a.description, size)?;
        let mut ids = Vec::new();
        for surface in &surfaces {
            if ids.len() as u32 >= a.count {
                break;
            }
            let s = SurfaceRef {
                parent: container.clone(),
                surface: surface.clone(),
            };
            let more = place_layers(state, &s, &routed, a.count - ids.len() as u32)?;
            ids.extend(more);
        }
        Ok((routed, ids))
    };
    // At their typical size first; when fewer fit than asked for ("a bin with at least five
    // stuffed animals"), the smallest plausible size of the same object, if that holds more.
    let mut trial = state.clone();
    let (mut routed, mut ids) = fill(&mut trial, None)?;
    let smallest = crate::assets::router::naming::category_of(&a.description)
        .and_then(crate::assets::procedural::prior)
        .map(|p| p.min);
    if (ids.len() as u32) < a.count
        && let Some(min) = smallest
    {
        let mut small = state.clone();
        if let Ok((r, more)) = fill(&mut small, Some(min))
            && more.len() > ids.len()
        {
            (trial, routed, ids) = (small, r, more);
        }
    }
    *state = trial;
    if ids.is_empty() {
        return Err(ToolError::failed(format!(
            "nothing fits inside {}",
            a.container
        )));
    }
    let notes = if (ids.len() as u32) < a.count {
        vec![format!(
            "only {} of {} fit in {}",
            ids.len(),
            a.count,
            a.container
        )]
    } else {
        vec![]
    };
    result_for(state, &ids, [routed.notes.clone(), notes].concat())
}

/// Item offsets of a place setting: (u across, v towards the table centre) from the edge
/// point in front of the seat, metres; and a yaw for cutlery.
fn setting_offset(noun: &str) -> (f64, f64, f64) {
    match noun {
        "plate" | "dinner plate" | "dish" => (0.0, 0.19, 0.0),
        "fork" => (-0.17, 0.19, 0.0),
        "knife" => (0.17, 0.19, 0.0),
        "spoon" => (0.21, 0.19, 0.0),
        "napkin" => (-0.24, 0.17, 0.0),
        "glass" | "wine glass" | "cup" | "mug" | "teacup" => (0.19, 0.36, 0.0),
        _ => (-0.2, 0.36, 0.0),
    }
}

fn place_settings(state: &mut StageState, a: SettingsArgs) -> Result<PlaceResult, ToolError> {
    let s = find_surface(state, &a.surface)?;
    // Seats: chairs, stools and benches near the table whose front faces it.
    let table_xy = s.world_from_surface().translation();
    let (hw, hd) = (s.surface.size[0] / 2.0, s.surface.size[1] / 2.0);
    let surface_from_world = s.world_from_surface().inverse();
    let mut seats: Vec<(f64, f64, f64)> = Vec::new(); // edge point (u, v) and inward yaw
    for o in state.room_objects() {
        if !matches!(
            state.scene.scene.built_as(o),
            "chair" | "stool" | "bar_stool" | "bar stool" | "bench" | "armchair"
        ) {
            continue;
        }
        let local = surface_from_world.compose(&o.world_from_object);
        let p = local.translation();
        let front = local.transform_vector(&Vector3::y());
        let dist_out_u = p.x.abs() - hw;
        let dist_out_v = p.y.abs() - hd;
        if dist_out_u > 0.8 || dist_out_v > 0.8 || (dist_out_u < 0.0 && dist_out_v < 0.0) {
            continue;
        }
        let to_center = Vector3::new(-p.x, -p.y, 0.0).normalize();
        if front.dot(&to_center) < 0.5 {
            continue;
        }
        // Edge point: project the seat onto the nearest table edge.
        let (eu, ev, inward) = if dist_out_v >= dist_out_u {
            (
                p.x.clamp(-hw, hw),
                hd * p.y.signum(),
                if p.y > 0.0 { std::f64::consts::PI } else { 0.0 },
            )
        } else {
            (
                hw * p.x.signum(),
                p.y.clamp(-hd, hd),
                if p.x > 0.0 {
                    std::f64::consts::FRAC_PI_2
                } else {
                    -std::f64::consts::FRAC_PI_2
                },
            )
        };
        seats.push((eu, ev, inward));
    }
    let _ = table_xy;
    if seats.is_empty() {
        return Err(ToolError::failed(format!(
            "no seats face {}; place chairs first or use place_on_surface",
            s.parent.id
        )));
    }
    let n = a
        .settings
        .map(|n| n as usize)
        .unwrap_or(seats.len())
        .min(seats.len());
    let mut ids = Vec::new();
    let mut notes = Vec::new();
    for &(eu, ev, inward) in seats.iter().take(n) {
        let (sin, cos) = inward.sin_cos();
        for item in &a.items {
            let routed = match state.route_asset(item, None) {
                Ok(r) => r,
                Err(e) => {
                    notes.push(e.message);
                    continue;
                }
            };
            for n in &routed.notes {
                if !notes.contains(n) {
                    notes.push(n.clone());
                }
            }
            let rec = state.scene.scene.assets[&routed.asset].clone();
            let (du, dv, yaw) = setting_offset(&routed.category);
            // Rotate the (across, inward) offset into the surface frame.
            let u = eu + du * cos - dv * sin;
            let v = ev + du * sin + dv * cos;
            match fit(
                state,
                &s,
                &rec,
                &item_rotation(inward.to_degrees() + yaw, false),
                Some((u, v)),
                &[],
            ) {
                Ok((pose, _)) => {
                    ids.push(add_item(state, &routed, pose, &s.parent.id, &s.surface.id))
                }
                Err(e) => notes.push(format!("{item}: {e}")),
            }
        }
    }
    if ids.is_empty() {
        return Err(ToolError::failed(format!(
            "no place setting fits: {}",
            notes.join("; ")
        )));
    }
    result_for(state, &ids, notes)
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

/// All surfaces of the objects in the room (or of one object).
pub fn surfaces(state: &StageState, object: Option<&str>) -> Vec<SurfaceRef> {
    state
        .room_objects()
        .filter(|o| object.is_none_or(|id| o.id == id))
        .filter(|o| o.kind != ObjectKind::Manipuland || object.is_some())
        .flat_map(|o| {
            let rec = state.scene.scene.assets.get(&o.asset);
            rec.into_iter()
                .flat_map(|r| r.surfaces.clone())
                .map(|s| SurfaceRef {
                    parent: o.clone(),
                    surface: s,
                })
        })
        .collect()
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

/// Ids of everything resting (transitively) on `ids`.
fn stacked_on(state: &StageState, ids: &[String]) -> Vec<String> {
    let mut out = Vec::new();
    let mut frontier: Vec<String> = ids.to_vec();
    while let Some(p) = frontier.pop() {
        for o in &state.scene.scene.objects {
            if matches!(&o.support, Support::Object { parent, .. } if *parent == p)
                && !out.contains(&o.id)
                && !ids.contains(&o.id)
            {
                out.push(o.id.clone());
                frontier.push(o.id.clone());
            }
        }
    }
    out
}

/// Every object resting (transitively) on `entity`.
pub fn items_on(state: &StageState, entity: &str) -> Vec<String> {
    stacked_on(state, &[entity.to_string()])
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::assets::procedural::{AssetRequest, SupportClass, build, categories, prior};

    #[test]
    fn plates_nest_books_do_not() {
        let plate = build(&AssetRequest::new("plate", 1)).unwrap();
        let [lo, hi] = plate.bounds();
        let p = stack_pitch(&plate);
        assert!(
            p < 0.5 * (hi[2] - lo[2]),
            "plates should nest: pitch {p}, height {}",
            hi[2] - lo[2]
        );
        let book = build(&AssetRequest::new("book", 1)).unwrap();
        let [lo, hi] = book.bounds();
        let p = stack_pitch(&book);
        assert!(
            (p - (hi[2] - lo[2])).abs() < 0.002,
            "upright books stack by their height: {p}"
        );
    }

    #[test]
    fn rotated_bounds_of_a_laid_flat_book() {
        let book = build(&AssetRequest::new("book", 1)).unwrap();
        let rec = book.record();
        let (lo, hi) = rotated_bounds(&rec, &item_rotation(0.0, true));
        let [blo, bhi] = rec.bounds;
        // Lying on its side, the book's height is its thickness.
        assert!(((hi[2] - lo[2]) - (bhi[0] - blo[0])).abs() < 1e-9);
    }

    /// Over every piece of furniture: the body leaves the space above each of its surfaces
    /// mostly free, apart from dividers (a sideboard's partitions) and fixtures (a sink's basin over
    /// the cabinet shelf) that placement steers around. A surface set below its board, or a shelf
    /// whose clearance runs into the next one, would show here as covered.
    #[test]
    fn furniture_surfaces_have_free_space_above_them() {
        let mut failures = Vec::new();
        let mut partitioned = Vec::new();
        for cat in categories() {
            if prior(cat).is_none_or(|p| p.support != SupportClass::Floor) {
                continue;
            }
            let asset = build(&AssetRequest::new(cat, 3)).unwrap();
            for s in asset
                .surfaces
                .iter()
                .filter(|s| !s.id.starts_with("inside"))
            {
                let area = s.size[0] * s.size[1];
                let rects = intrusions(&asset, s, &Default::default());
                let covered = union_area(&rects, s.size);
                if covered > 0.0 {
                    partitioned.push(format!("{cat}/{}", s.id));
                }
                if covered > 0.7 * area {
                    failures.push(format!(
                        "{cat}/{}: {:.0} % covered {rects:?} {s:?}",
                        s.id,
                        100.0 * covered / area
                    ));
                }
            }
        }
        assert!(failures.is_empty(), "{}", failures.join("\n"));
        assert!(
            partitioned.iter().any(|k| k.starts_with("sideboard/")),
            "the sideboard's partitions are not seen: {partitioned:?}"
        );
    }

    /// Area of the union of rectangles `[u0, u1, v0, v1]` over a `size` surface, on a 2 mm grid.
    fn union_area(rects: &[[f64; 4]], size: [f64; 2]) -> f64 {
        let cell = 0.002;
        let (nu, nv) = ((size[0] / cell) as usize, (size[1] / cell) as usize);
        let mut n = 0usize;
        for i in 0..nu {
            let u = -size[0] / 2.0 + (i as f64 + 0.5) * cell;
            for j in 0..nv {
                let v = -size[1] / 2.0 + (j as f64 + 0.5) * cell;
                if rects
                    .iter()
                    .any(|r| (r[0]..r[1]).contains(&u) && (r[2]..r[3]).contains(&v))
                {
                    n += 1;
                }
            }
        }
        n as f64 * cell * cell
    }
}
