//! Where an item fits on a surface: its footprint under a rotation, the footprints already
//! taken there (other items, the supporting object's own pieces), the free height above, and
//! the first free spot (or the asked-for one) in surface coordinates.

use nalgebra::{UnitQuaternion, Vector3};

use super::surface::{SurfaceRef, intrusions, is_cavity, is_receptacle};
use crate::scene::{AssetRecord, ObjectKind, Pose, Support};
use crate::stages::{RoutedAsset, StageState};
use crate::state::SceneState;

/// Gap kept between neighbouring small objects, metres.
pub(super) const GAP: f64 = 0.008;
/// Release height above a surface, metres (settling closes it).
pub(super) const LIFT: f64 = 0.001;

/// Axis-aligned extent of an asset under a local rotation: (lo, hi) in the rotated frame.
pub(super) fn rotated_bounds(rec: &AssetRecord, rot: &UnitQuaternion<f64>) -> ([f64; 3], [f64; 3]) {
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
pub(super) struct Slot {
    pub(super) u: f64,
    pub(super) v: f64,
    pub(super) hu: f64,
    pub(super) hv: f64,
}

impl Slot {
    pub(super) fn overlaps(&self, o: &Slot) -> bool {
        (self.u - o.u).abs() < self.hu + o.hu + GAP && (self.v - o.v).abs() < self.hv + o.hv + GAP
    }
}

/// Footprints of the objects already resting (directly) on a surface.
pub(super) fn occupied(scene: &SceneState, s: &SurfaceRef) -> Vec<Slot> {
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

/// Other objects of the room that reach into the free space above `s` (a wall cabinet over a
/// counter, a shelf's overhang, a pendant low over a table), as footprints clipped to the
/// surface with the height above it where each begins: an item taller than that would stand in
/// it. Objects on `s` itself, the supporting piece (its own pieces are
/// [`parent_intrusions`]), architecture and thin things at the surface's level are left out.
fn foreign_intrusions(scene: &SceneState, s: &SurfaceRef) -> Vec<(Slot, f64)> {
    const SLACK: f64 = 0.002;
    let (su, sv) = (s.surface.size[0] / 2.0, s.surface.size[1] / 2.0);
    let surface_from_world = s.world_from_surface().inverse();
    scene
        .scene
        .objects
        .iter()
        .filter(|o| o.id != s.parent.id && o.room == s.parent.room)
        .filter(|o| o.kind != ObjectKind::Architecture)
        .filter(|o| {
            !matches!(&o.support, Support::Object { parent, surface }
                if *parent == s.parent.id && *surface == s.surface.id)
        })
        .filter_map(|o| {
            let rec = scene.scene.assets.get(&o.asset)?;
            let local = surface_from_world.compose(&o.world_from_object);
            let (lo, hi) = rotated_bounds(rec, &local.rotation());
            let t = local.translation();
            let (z0, z1) = (t.z + lo[2], t.z + hi[2]);
            if z1 < 0.01 || z0 > s.surface.clearance - SLACK {
                return None;
            }
            let (u0, u1) = ((t.x + lo[0]).max(-su), (t.x + hi[0]).min(su));
            let (v0, v1) = ((t.y + lo[1]).max(-sv), (t.y + hi[1]).min(sv));
            (u1 - u0 > SLACK && v1 - v0 > SLACK).then(|| {
                let slot = Slot {
                    u: (u0 + u1) / 2.0,
                    v: (v0 + v1) / 2.0,
                    hu: (u1 - u0) / 2.0,
                    hv: (v1 - v0) / 2.0,
                };
                (slot, z0.max(0.0))
            })
        })
        .collect()
}

/// Local rotation of an item on a surface: yaw, optionally laid on its side first.
pub(super) fn item_rotation(yaw_deg: f64, lay_flat: bool) -> UnitQuaternion<f64> {
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
pub(super) fn shrunk_to_fit(
    s: &SurfaceRef,
    rec: &AssetRecord,
    rot: &UnitQuaternion<f64>,
) -> Option<[f64; 3]> {
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
pub(super) fn fit(
    state: &StageState,
    s: &SurfaceRef,
    rec: &AssetRecord,
    rot: &UnitQuaternion<f64>,
    at: Option<(f64, f64)>,
    extra: &[Slot],
) -> Result<(Pose, Slot), String> {
    fit_in(&state.scene, s, rec, rot, at, extra)
}

/// [`fit`] packing from the back-left corner even on an empty surface (a pile's patch and its
/// layers, which must stay together).
pub(super) fn fit_packed(
    state: &StageState,
    s: &SurfaceRef,
    rec: &AssetRecord,
    rot: &UnitQuaternion<f64>,
    extra: &[Slot],
) -> Result<(Pose, Slot), String> {
    fit_with(&state.scene, s, rec, rot, None, extra, false)
}

/// [`fit`] on a scene outside a stage (placing an object again after post-processing).
pub(super) fn fit_in(
    scene: &SceneState,
    s: &SurfaceRef,
    rec: &AssetRecord,
    rot: &UnitQuaternion<f64>,
    at: Option<(f64, f64)>,
    extra: &[Slot],
) -> Result<(Pose, Slot), String> {
    fit_with(scene, s, rec, rot, at, extra, true)
}

fn fit_with(
    scene: &SceneState,
    s: &SurfaceRef,
    rec: &AssetRecord,
    rot: &UnitQuaternion<f64>,
    at: Option<(f64, f64)>,
    extra: &[Slot],
    centre_first: bool,
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
    taken.extend(
        foreign_intrusions(scene, s)
            .into_iter()
            .filter(|&(_, bottom)| bottom < h + GAP)
            .map(|(slot, _)| slot),
    );
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
            // The first item on an open surface stands nearest its centre at least
            // EDGE_MARGIN from its edges: where a reader expects "a shelf with a can on it",
            // away from a shelf's panels (a gripper's body needs room beside an item) and
            // from a table's edge (one nudge from the floor). Otherwise, and when that fails,
            // a raster from the back-left corner packs the surface (the parent's -Y side: a
            // desk's monitor and a counter's appliances stand at the back), rows along u; a
            // basin or a bowl is packed from the start.
            // Centred, it must not cost the surface a second item of its size: a folded towel
            // in the middle of a 0.9 m shelf left 0.29 m either side, too little for the next.
            let first = centre_first
                && taken.is_empty()
                && !is_receptacle(s)
                && !centre_spoils_a_second(su, sv, hu, hv);
            let fits_margin = hu + EDGE_MARGIN <= su && hv + EDGE_MARGIN <= sv;
            (first && fits_margin)
                .then(|| nearest_centre(su - EDGE_MARGIN, sv - EDGE_MARGIN, hu, hv, free, make))
                .flatten()
                .or_else(|| raster(su, sv, hu, hv, |u, v| Some(make(u, v)).filter(&free)))
                .ok_or_else(|| format!("no free spot left on {}", s.key()))?
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

/// Whether an item of half-extents `(hu, hv)` centred on a surface of half-extents `(su, sv)`
/// leaves no room beside it for a second of its size, where packed from a corner two would fit.
fn centre_spoils_a_second(su: f64, sv: f64, hu: f64, hv: f64) -> bool {
    let beside = |s: f64, h: f64| s - h >= 2.0 * h + GAP;
    let two = |s: f64, h: f64| 2.0 * s >= 4.0 * h + GAP;
    (two(su, hu) || two(sv, hv)) && !(beside(su, hu) || beside(sv, hv))
}

/// How far the first raster pass keeps an item from its surface's edges (m).
const EDGE_MARGIN: f64 = 0.035;

/// The free slot nearest the centre on a 1 cm grid of centres over the rectangle
/// `[-au, au] x [-av, av]` shrunk by the item's half-extents.
fn nearest_centre(
    au: f64,
    av: f64,
    hu: f64,
    hv: f64,
    free: impl Fn(&Slot) -> bool,
    make: impl Fn(f64, f64) -> Slot,
) -> Option<Slot> {
    const STEP: f64 = 0.01;
    let steps = |a: f64, h: f64| ((a - h).max(0.0) / STEP + 1e-9).floor() as i64;
    let (nu, nv) = (steps(au, hu), steps(av, hv));
    let mut grid: Vec<(i64, i64)> = (-nu..=nu)
        .flat_map(|i| (-nv..=nv).map(move |j| (i, j)))
        .collect();
    grid.sort_by_key(|&(i, j)| (i * i + j * j, j, i));
    grid.into_iter()
        .map(|(i, j)| make(i as f64 * STEP, j as f64 * STEP))
        .find(|slot| free(slot))
}

/// The first slot `try_at` accepts, scanning centres at 1 cm steps over the rectangle
/// `[-au, au] x [-av, av]` shrunk by the item's half-extents, rows along u from -v.
fn raster(
    au: f64,
    av: f64,
    hu: f64,
    hv: f64,
    mut try_at: impl FnMut(f64, f64) -> Option<Slot>,
) -> Option<Slot> {
    const STEP: f64 = 0.01;
    let mut v = -av + hv;
    while v <= av - hv + 1e-9 {
        let mut u = -au + hu;
        while u <= au - hu + 1e-9 {
            if let Some(slot) = try_at(u, v) {
                return Some(slot);
            }
            u += STEP;
        }
        v += STEP;
    }
    None
}

/// Adds a manipuland resting on `support`.
pub(super) fn add_item(
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::assets::procedural::{AssetRequest, build};

    #[test]
    fn the_first_pass_takes_the_free_slot_nearest_the_centre_and_the_raster_the_back_left() {
        let make = |u: f64, v: f64| Slot {
            u,
            v,
            hu: 0.05,
            hv: 0.05,
        };
        let inside =
            |s: &Slot, a: f64| s.u.abs() + s.hu <= a + 1e-9 && s.v.abs() + s.hv <= a + 1e-9;
        let empty = |s: &Slot| inside(s, 0.3);
        let centre = nearest_centre(0.3, 0.3, 0.05, 0.05, empty, make).expect("room");
        assert!(centre.u.abs() < 1e-9 && centre.v.abs() < 1e-9, "{centre:?}");
        // Something at the centre: the nearest free slot touches it, inside the rectangle.
        let blocker = make(0.0, 0.0);
        let around = |s: &Slot| inside(s, 0.3) && !blocker.overlaps(s);
        let next = nearest_centre(0.3, 0.3, 0.05, 0.05, around, make).expect("room");
        let d = next.u.abs().max(next.v.abs());
        assert!((0.099..=0.111).contains(&d), "{next:?}");
        let first = raster(0.3, 0.3, 0.05, 0.05, |u, v| {
            Some(make(u, v)).filter(&around)
        })
        .expect("room");
        assert!(
            (first.u + 0.25).abs() < 1e-9 && (first.v + 0.25).abs() < 1e-9,
            "{first:?}"
        );
        // Nothing fits: both say so.
        assert!(nearest_centre(0.3, 0.3, 0.05, 0.05, |_: &Slot| false, make).is_none());
        assert!(raster(0.3, 0.3, 0.05, 0.05, |_, _| None).is_none());
    }

    /// A first item goes to the centre unless that leaves no room for a second of its size.
    #[test]
    fn centring_keeps_room_for_a_second_item() {
        // A 0.33 m towel on a 0.90 x 0.32 m shelf: centred, 0.29 m either side; packed, two fit.
        assert!(centre_spoils_a_second(0.45, 0.16, 0.165, 0.11));
        // A can on the same shelf, a plate on a table: room beside it either way.
        assert!(!centre_spoils_a_second(0.45, 0.16, 0.033, 0.033));
        assert!(!centre_spoils_a_second(0.8, 0.45, 0.135, 0.135));
        // A board as wide as most of the shelf: only one fits anyway, so it is centred.
        assert!(!centre_spoils_a_second(0.45, 0.16, 0.3, 0.1));
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
}
