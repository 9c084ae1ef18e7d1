//! The surfaces of a room and what rests on them: a surface by its `parent/surface` key, every
//! surface of the room, the objects resting on an entity, the supporting object's own pieces
//! that reach into the space above a surface, and another surface for an object that
//! post-processing removed ([`spot_again`]).

use nalgebra::Vector3;

use super::fit::{fit_in, item_rotation};
use crate::agents::ToolError;
use crate::assets::Asset;
use crate::physics::collision::posed_object;
use crate::scene::{ObjectKind, Pose, SceneObject, Support, SurfaceRecord};
use crate::stages::StageState;
use crate::state::SceneState;

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
            .is_some_and(|rec| crate::stages::clutter::is_enclosed(rec, &self.surface))
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
                || crate::stages::clutter::is_enclosed(parent_rec, s)
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

/// Whether a surface is a container's cavity (things pack in it and heap over its rim).
pub(super) fn is_cavity(s: &SurfaceRef) -> bool {
    s.surface.id.starts_with("inside")
}

/// Whether things go into the surface rather than onto it: a cavity or a sink's basin.
pub(super) fn is_receptacle(s: &SurfaceRef) -> bool {
    is_cavity(s) || s.surface.id == "basin"
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

/// Ids of everything resting (transitively) on `ids`.
pub(super) fn stacked_on(state: &StageState, ids: &[String]) -> Vec<String> {
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::assets::procedural::{AssetRequest, SupportClass, build, categories, prior};

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
