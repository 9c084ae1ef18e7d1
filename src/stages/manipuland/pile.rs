//! Piles and layers: copies of one item loosely packed in layers, a heap on an open surface
//! (each layer over the footprint of the one below) or packed into a container's cavity
//! ([`place_layers`], which [`super::fill`] uses as well); nesting items pile as short stacks.

use nalgebra::UnitQuaternion;

use super::fit::{GAP, LIFT, Slot, add_item, fit_packed, item_rotation, rotated_bounds};
use super::stack::{stack_on, stack_pitch};
use super::surface::{SurfaceRef, find_surface, is_cavity};
use super::tools::{GroupArgs, PlaceResult, result_for};
use crate::agents::ToolError;
use crate::scene::{AssetRecord, Pose, SurfaceRecord};
use crate::stages::{RoutedAsset, StageState};

/// Copies of a nesting item (plates, bowls) in one heap: at most this many per stack.
const NESTED_PILE: u32 = 4;

/// Whether copies of an asset stacked `pitch` apart lie in one another (plates, bowls)
/// rather than on top.
fn nests(state: &StageState, routed: &RoutedAsset, pitch: f64) -> bool {
    let [lo, hi] = state.scene.assets[&routed.asset].bounds();
    pitch < 0.6 * (hi[2] - lo[2])
}

/// Places `count` copies in layers over a surface (piles and fills).
pub(super) fn place_layers(
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
                fit_packed(state, &layer, &rec, &rot, &extra).ok()
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
        let Ok((pose, slot)) = fit_packed(state, s, &rec, &rot, &bottom) else {
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
    let (_, slot) = fit_packed(state, s, &patch, &UnitQuaternion::identity(), &[]).ok()?;
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

pub(super) fn place_pile(state: &mut StageState, a: GroupArgs) -> Result<PlaceResult, ToolError> {
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
