//! Stacks: copies of one item resting on each other at the pitch where they nest (plates,
//! bowls) or by their height (books, boxes), as many as the free height allows.

use super::fit::{LIFT, add_item, fit, item_rotation};
use super::surface::{SurfaceRef, find_surface};
use super::tools::{GroupArgs, PlaceResult, result_for};
use crate::agents::ToolError;
use crate::assets::Asset;
use crate::physics::collision::{object_penetration, posed_object};
use crate::scene::Pose;
use crate::stages::{RoutedAsset, StageState};

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

pub(super) fn place_stack(state: &mut StageState, a: GroupArgs) -> Result<PlaceResult, ToolError> {
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

/// One stack of up to `count` copies `pitch` apart on `s` (at `at` or the first free spot),
/// as many as the free height allows.
pub(super) fn stack_on(
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::assets::procedural::{AssetRequest, build};

    #[test]
    fn nested_plates_rest_base_on_base_with_their_rims_clear() {
        // A flat base-on-base contact, not a ring of rim pieces wedged in the rim below
        // (which cost Drake's contact solver several times as much per step).
        let none = std::collections::BTreeMap::new();
        let plate = build(&AssetRequest::new("plate", 1)).unwrap();
        let mut rim_only = plate.clone();
        rim_only.links[0].collisions.remove(0);
        let pitch = stack_pitch(&plate);
        let below = posed_object("a", &plate, &Pose::IDENTITY, &none);
        // Pressed 0.5 mm past touching (the pitch keeps a 0.5 mm gap).
        let dz = pitch - 0.001;
        let whole = posed_object("b", &plate, &Pose::from_xyz(0.0, 0.0, dz), &none);
        let rims = posed_object("b", &rim_only, &Pose::from_xyz(0.0, 0.0, dz), &none);
        assert!(object_penetration(&below, &whole) > 1e-4);
        assert_eq!(object_penetration(&below, &rims), 0.0, "pitch {pitch}");
        // On a board only the base touches: the rim stands clear of the ground.
        let rim_bottom = posed_object("r", &rim_only, &Pose::IDENTITY, &none)
            .bounds
            .0[2];
        assert!(rim_bottom > 1e-3, "rim bottom {rim_bottom}");
    }

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
}
