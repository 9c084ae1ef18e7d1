//! The scene as every exporter reads it: each object with its asset, how it is held (static,
//! welded, free), every link's pose at the object's joint positions, the kinematic tree, and
//! names that are safe in every format (XML names, USD prim names, file names).
//!
//! Names: an object keeps its id, a link its name, a joint its name, as long as they already are
//! `[a-z0-9_]`, which every generated scene's are; anything else is reduced with
//! [`sanitize_name`] and made unique. No writer uses a raw name from the scene in a path.

use std::collections::{BTreeMap, BTreeSet};

use nalgebra::{Unit, UnitQuaternion, Vector3};

use super::ExportError;
use crate::assets::{Asset, Texture, link_poses};
use crate::geometry::TriMesh;
use crate::scene::{Pose, Scene, SceneObject, sanitize_name};
use crate::state::SceneState;

/// How an object is attached to the world.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Hold {
    /// Static architecture: colliders fixed in the world, no mass.
    Static,
    /// Welded to the world (wall, ceiling and thin objects, or welded furniture): keeps its mass,
    /// but its root does not move.
    Welded,
    /// A free body (6 DoF root).
    Free,
}

/// Hands out unique, sanitised names within one namespace.
#[derive(Debug, Default, Clone)]
pub struct Namer {
    used: BTreeSet<String>,
}

impl Namer {
    /// The sanitised form of `raw`, suffixed `_1`, `_2`, ... when already taken.
    pub fn name(&mut self, raw: &str) -> String {
        let base = sanitize_name(raw);
        if self.used.insert(base.clone()) {
            return base;
        }
        for k in 1.. {
            let candidate = format!("{base}_{k}");
            if self.used.insert(candidate.clone()) {
                return candidate;
            }
        }
        base
    }
}

/// A render material of an asset: base colour (rounded to 1e-4) and optional texture.
#[derive(Debug, Clone)]
pub struct AssetMaterial<'a> {
    /// Linear RGBA base colour.
    pub color: [f64; 4],
    /// Base-colour texture.
    pub texture: Option<&'a Texture>,
}

/// The visual parts of one link that share a material, merged into one mesh (link frame).
#[derive(Debug, Clone)]
pub struct VisualGroup {
    /// Index into [`AssetView::materials`].
    pub material: usize,
    /// The merged mesh; it has `uvs` when the material is textured.
    pub mesh: TriMesh,
}

fn color_key(c: [f64; 4]) -> [i64; 4] {
    c.map(|v| (v.clamp(0.0, 1.0) * 1e4).round() as i64)
}

/// An asset with the names and tree every writer needs.
#[derive(Debug)]
pub struct AssetView<'a> {
    /// The asset.
    pub asset: &'a Asset,
    /// Safe, scene-unique name (the asset id when it is already safe).
    pub name: String,
    /// Safe link names, unique in the asset, in link order.
    pub link_names: Vec<String>,
    /// Safe joint names, unique in the asset, in joint order.
    pub joint_names: Vec<String>,
    /// Safe file stem of each texture, by the texture's own name.
    pub texture_names: BTreeMap<String, String>,
    /// Per link, the index of the joint whose child it is.
    pub parent_joint: Vec<Option<usize>>,
    /// Per link, its parent link (through a joint, or the root for a link no joint moves);
    /// `None` for the root.
    pub parent_link: Vec<Option<usize>>,
    /// Distinct render materials of the asset.
    pub materials: Vec<AssetMaterial<'a>>,
    /// Per link, its visuals merged by material.
    pub visuals: Vec<Vec<VisualGroup>>,
}

impl<'a> AssetView<'a> {
    fn new(asset: &'a Asset, name: String) -> Self {
        let mut links = Namer::default();
        let link_names: Vec<String> = asset.links.iter().map(|l| links.name(&l.name)).collect();
        let mut joints = Namer::default();
        let joint_names = asset.joints.iter().map(|j| joints.name(&j.name)).collect();
        let mut textures = Namer::default();
        let mut texture_names = BTreeMap::new();
        for v in asset.links.iter().flat_map(|l| &l.visuals) {
            if let Some(t) = &v.texture
                && !texture_names.contains_key(&t.name)
            {
                texture_names.insert(t.name.clone(), textures.name(&t.name));
            }
        }
        let index = |name: &str| asset.links.iter().position(|l| l.name == name);
        let mut parent_joint = vec![None; asset.links.len()];
        let mut parent_link = vec![None; asset.links.len()];
        for (ji, j) in asset.joints.iter().enumerate() {
            if let (Some(p), Some(c)) = (index(&j.parent), index(&j.child))
                && c != 0
                && parent_joint[c].is_none()
            {
                parent_joint[c] = Some(ji);
                parent_link[c] = Some(p);
            }
        }
        for p in parent_link.iter_mut().skip(1) {
            if p.is_none() {
                *p = Some(0);
            }
        }
        // A joint loop would make a link its own ancestor; cut such links to the root.
        for i in 1..asset.links.len() {
            let mut seen = BTreeSet::new();
            let mut k = i;
            while let Some(p) = parent_link[k] {
                if !seen.insert(k) {
                    parent_link[i] = Some(0);
                    parent_joint[i] = None;
                    break;
                }
                k = p;
            }
        }
        let (materials, visuals) = merged_visuals(asset);
        AssetView {
            asset,
            name,
            materials,
            visuals,
            link_names,
            joint_names,
            texture_names,
            parent_joint,
            parent_link,
        }
    }

    /// Children of link `i` in the kinematic tree, in link order.
    pub fn children(&self, i: usize) -> Vec<usize> {
        (0..self.asset.links.len())
            .filter(|&c| self.parent_link[c] == Some(i))
            .collect()
    }

    /// True when the asset has more than one link.
    pub fn is_articulated(&self) -> bool {
        self.asset.links.len() > 1
    }
}

/// Distinct materials and per-link visuals merged by material. A texture counts only on a part
/// whose mesh has texture coordinates.
fn merged_visuals(asset: &Asset) -> (Vec<AssetMaterial<'_>>, Vec<Vec<VisualGroup>>) {
    let mut keys: Vec<([i64; 4], Option<&str>)> = Vec::new();
    let mut materials = Vec::new();
    let mut visuals = Vec::new();
    for link in &asset.links {
        let mut groups: Vec<VisualGroup> = Vec::new();
        for part in link.visuals.iter().filter(|p| !p.mesh.is_empty()) {
            let textured = part.mesh.uvs.len() == part.mesh.positions.len();
            let texture = part.texture.as_ref().filter(|_| textured);
            let key = (color_key(part.color), texture.map(|t| t.name.as_str()));
            let material = match keys.iter().position(|k| *k == key) {
                Some(m) => m,
                None => {
                    keys.push(key);
                    materials.push(AssetMaterial {
                        color: key.0.map(|v| v as f64 / 1e4),
                        texture,
                    });
                    materials.len() - 1
                }
            };
            match groups.iter_mut().find(|g| g.material == material) {
                Some(g) => g.mesh.append(&part.mesh),
                None => groups.push(VisualGroup {
                    material,
                    mesh: part.mesh.clone(),
                }),
            }
        }
        visuals.push(groups);
    }
    (materials, visuals)
}

/// One placed object.
#[derive(Debug)]
pub struct ObjectView<'a> {
    /// The scene object.
    pub object: &'a SceneObject,
    /// Index into [`SceneView::assets`].
    pub asset: usize,
    /// Safe, scene-unique name (the object id when it is already safe).
    pub name: String,
    /// How it is attached.
    pub hold: Hold,
    /// Every link's pose in the model frame at the object's joint positions.
    pub model_from_links: Vec<Pose>,
    /// Every link's pose in the world at the object's joint positions.
    pub world_from_links: Vec<Pose>,
}

/// The whole scene for the writers.
#[derive(Debug)]
pub struct SceneView<'a> {
    /// The scene model.
    pub scene: &'a Scene,
    /// The assets objects use, in asset-id order.
    pub assets: Vec<AssetView<'a>>,
    /// Every object, in scene order.
    pub objects: Vec<ObjectView<'a>>,
}

impl<'a> SceneView<'a> {
    /// The view of `state`; fails when an object's asset is not loaded.
    pub fn new(state: &'a SceneState) -> Result<Self, ExportError> {
        let scene = &state.scene;
        let used: BTreeSet<&str> = scene.objects.iter().map(|o| o.asset.as_str()).collect();
        let mut asset_namer = Namer::default();
        let mut assets = Vec::new();
        let mut asset_index = BTreeMap::new();
        for (id, asset) in &state.assets {
            if !used.contains(id.as_str()) {
                continue;
            }
            asset_index.insert(id.as_str(), assets.len());
            assets.push(AssetView::new(asset, asset_namer.name(id)));
        }
        let mut object_namer = Namer::default();
        let mut objects = Vec::new();
        for object in &scene.objects {
            let ai = *asset_index.get(object.asset.as_str()).ok_or_else(|| {
                ExportError::MissingAsset {
                    object: object.id.clone(),
                    asset: object.asset.clone(),
                }
            })?;
            let asset = assets[ai].asset;
            let hold = if asset.is_static {
                Hold::Static
            } else if object.welded {
                Hold::Welded
            } else {
                Hold::Free
            };
            let model_from_links = link_poses(asset, &object.joint_positions);
            let world_from_links = model_from_links
                .iter()
                .map(|m| object.world_from_object.compose(m))
                .collect();
            objects.push(ObjectView {
                object,
                asset: ai,
                name: object_namer.name(&object.id),
                hold,
                model_from_links,
                world_from_links,
            });
        }
        Ok(SceneView {
            scene,
            assets,
            objects,
        })
    }

    /// The asset view of an object.
    pub fn asset_of(&self, o: &ObjectView<'_>) -> &AssetView<'a> {
        &self.assets[o.asset]
    }

    /// Axis-aligned bounds of every object's visual and collision geometry in the world.
    pub fn bounds(&self) -> Option<([f64; 3], [f64; 3])> {
        let mut lo = [f64::INFINITY; 3];
        let mut hi = [f64::NEG_INFINITY; 3];
        for o in &self.objects {
            let asset = self.asset_of(o).asset;
            for (link, world_from_link) in asset.links.iter().zip(&o.world_from_links) {
                for piece in &link.collisions {
                    for v in piece.transformed(world_from_link).vertices {
                        for k in 0..3 {
                            lo[k] = lo[k].min(v[k]);
                            hi[k] = hi[k].max(v[k]);
                        }
                    }
                }
            }
        }
        lo.iter().all(|v| v.is_finite()).then_some((lo, hi))
    }
}

/// Initial position of joint `j` of an object (rad or m).
pub fn joint_position(object: &SceneObject, asset: &Asset, j: usize) -> f64 {
    asset
        .joints
        .get(j)
        .and_then(|joint| object.joint_positions.get(&joint.name))
        .copied()
        .unwrap_or(0.0)
}

/// A joint frame for formats whose joints turn about a named axis (USD's `X`/`Y`/`Z`): the axis
/// letter and the rotation `child_from_joint` that maps the letter's unit vector onto the
/// joint's axis (child frame). Positive motion keeps its sense: it turns or slides along the
/// joint axis by the right-hand rule, as in Drake.
pub fn axis_frame(axis: [f64; 3]) -> (char, UnitQuaternion<f64>) {
    let a = Vector3::from(axis);
    let a = if a.norm() > 1e-12 {
        a.normalize()
    } else {
        Vector3::z()
    };
    let (k, _) = a
        .iter()
        .enumerate()
        .map(|(k, v)| (k, v.abs()))
        .fold(
            (2, -1.0),
            |best, cur| if cur.1 > best.1 { cur } else { best },
        );
    let letter = ['X', 'Y', 'Z'][k];
    let mut e = Vector3::zeros();
    e[k] = 1.0;
    let rot = UnitQuaternion::rotation_between(&e, &a).unwrap_or_else(|| {
        // Antiparallel: half a turn about an axis perpendicular to e.
        let mut perp = Vector3::zeros();
        perp[(k + 1) % 3] = 1.0;
        UnitQuaternion::from_axis_angle(&Unit::new_normalize(perp), std::f64::consts::PI)
    });
    (letter, rot)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn namer_sanitises_and_dedupes() {
        let mut n = Namer::default();
        assert_eq!(n.name("door"), "door");
        assert_eq!(n.name("Door"), "door_1");
        assert_eq!(n.name("../../etc/passwd"), "etc_passwd");
        assert_eq!(n.name("tür \"x\""), "t_r_x");
    }

    #[test]
    fn axis_frame_maps_letter_onto_axis() {
        for axis in [
            [0.0, 0.0, 1.0],
            [0.0, 0.0, -1.0],
            [1.0, 0.0, 0.0],
            [0.0, -1.0, 0.0],
            [0.3, 0.1, -0.9],
        ] {
            let (letter, rot) = axis_frame(axis);
            let k = match letter {
                'X' => 0,
                'Y' => 1,
                _ => 2,
            };
            let mut e = Vector3::zeros();
            e[k] = 1.0;
            let mapped = rot * e;
            let a = Vector3::from(axis).normalize();
            assert!(
                (mapped - a).norm() < 1e-9,
                "{axis:?} -> {letter} {mapped:?}"
            );
        }
        assert_eq!(axis_frame([0.0, 0.0, -1.0]).0, 'Z');
    }
}
