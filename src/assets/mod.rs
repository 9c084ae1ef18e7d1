//! Assets: what an object is made of — links with visual meshes, convex collision pieces and
//! mass properties, joints, support surfaces, material and provenance.
//!
//! Canonical frame of every asset: Z up, +Y is the front; floor-standing objects and manipulands
//! have their bottom at z = 0 (centred in x and y), wall objects their back at y = 0, ceiling
//! objects their top at z = 0. The first link is the root; its frame is the model frame.

pub mod architecture;
pub mod articulated;
pub mod attributes;
mod builder;
pub mod cache;
pub mod catalog;
pub mod external;
pub mod gltf_read;
pub mod material;
pub mod physical;
pub mod procedural;
pub mod router;
pub mod textures;
pub mod thin;

use serde::{Deserialize, Serialize};

use crate::geometry::{ConvexPiece, GeometryError, MassProps, TriMesh, mesh};
use crate::scene::{AssetRecord, JointRecord, Pose, SurfaceRecord};

pub use builder::LinkBuilder;
pub use material::Material;

/// What can go wrong making an asset.
#[derive(Debug, thiserror::Error)]
pub enum AssetError {
    /// No generator knows the category.
    #[error("no generator for category {0:?}")]
    UnknownCategory(String),
    /// Geometry or mass properties failed validation.
    #[error("asset {asset:?}: {cause}")]
    Geometry {
        /// Asset being built.
        asset: String,
        /// The underlying problem.
        cause: GeometryError,
    },
    /// The asset is structurally wrong (no links, a joint naming a missing link, ...).
    #[error("asset {asset:?} is malformed: {reason}")]
    Malformed {
        /// Asset being built.
        asset: String,
        /// What is wrong.
        reason: String,
    },
}

/// An RGBA8 image used as a base-colour texture.
#[derive(Debug, Clone, PartialEq)]
pub struct Texture {
    /// File stem, unique within an asset (`[a-z0-9_]`), e.g. `rug_pattern`.
    pub name: String,
    /// Width, pixels.
    pub width: u32,
    /// Height, pixels.
    pub height: u32,
    /// Row-major RGBA, 4 bytes per pixel, top row first.
    pub rgba: std::sync::Arc<Vec<u8>>,
}

/// One visual part of a link: a mesh in the link frame with a colour and optional texture.
#[derive(Debug, Clone, PartialEq)]
pub struct VisualPart {
    /// Part name (unique within the link).
    pub name: String,
    /// Mesh in the link frame.
    pub mesh: TriMesh,
    /// Linear RGBA base colour (multiplies the texture when there is one).
    pub color: [f64; 4],
    /// Base-colour texture, sampled with the mesh's `uvs`.
    pub texture: Option<Texture>,
}

/// Contact parameters of a link's colliders (the SDFormat writer declares every collider
/// compliant hydroelastic at [`material::HYDROELASTIC_MODULUS_PA`]).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Contact {
    /// Dynamic friction coefficient.
    pub mu_dynamic: f64,
    /// Static friction coefficient.
    pub mu_static: f64,
    /// Hunt-Crossley dissipation, s/m.
    pub hunt_crossley_dissipation: f64,
}

impl Contact {
    /// Friction as given; the dissipation raised to the project's contact model's minimum
    /// ([`material::MIN_HUNT_CROSSLEY_DISSIPATION`]), so what is written is what is held.
    pub fn new(mu_dynamic: f64, mu_static: f64, hunt_crossley_dissipation: f64) -> Contact {
        Contact {
            mu_dynamic,
            mu_static,
            hunt_crossley_dissipation: hunt_crossley_dissipation
                .max(material::MIN_HUNT_CROSSLEY_DISSIPATION),
        }
    }
}

impl From<&Material> for Contact {
    fn from(m: &Material) -> Self {
        Contact::new(m.mu_dynamic, m.mu_static, m.hunt_crossley_dissipation)
    }
}

/// A rigid link.
#[derive(Debug, Clone, PartialEq)]
pub struct Link {
    /// Link name, unique in the asset.
    pub name: String,
    /// Pose of the link frame in the model frame at zero joint positions.
    pub model_from_link: Pose,
    /// Visual parts, link frame.
    pub visuals: Vec<VisualPart>,
    /// Convex collision pieces, link frame.
    pub collisions: Vec<ConvexPiece>,
    /// Mass properties, link frame.
    pub mass: MassProps,
    /// Contact parameters shared by the link's colliders.
    pub contact: Contact,
}

/// Joint types the project writes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum JointKind {
    /// Rotation about the axis (limits in radians).
    Revolute,
    /// Translation along the axis (limits in metres).
    Prismatic,
}

impl JointKind {
    /// `revolute` / `prismatic`, as SDFormat spells it.
    pub fn as_str(self) -> &'static str {
        match self {
            JointKind::Revolute => "revolute",
            JointKind::Prismatic => "prismatic",
        }
    }
}

/// A joint between two links. The joint frame coincides with the child link frame, so the
/// axis is expressed in the child frame and the parent side is `parent_from_child` at zero
/// joint position.
#[derive(Debug, Clone, PartialEq)]
pub struct Joint {
    /// Joint name, unique in the asset.
    pub name: String,
    /// Revolute or prismatic.
    pub kind: JointKind,
    /// Parent link name.
    pub parent: String,
    /// Child link name.
    pub child: String,
    /// Unit axis in the child (= joint) frame.
    pub axis: [f64; 3],
    /// Lower limit (rad or m).
    pub lower: f64,
    /// Upper limit (rad or m).
    pub upper: f64,
    /// Viscous damping (N m s/rad or N s/m).
    pub damping: f64,
    /// Effort limit (N m or N).
    pub effort: f64,
}

/// A built asset, ready to be written.
#[derive(Debug, Clone, PartialEq)]
pub struct Asset {
    /// Content-addressed id (`<category>_<hash>`).
    pub id: String,
    /// Plain noun.
    pub category: String,
    /// Main material name.
    pub material: String,
    /// Links; the first is the root.
    pub links: Vec<Link>,
    /// Joints between links.
    pub joints: Vec<Joint>,
    /// Surfaces other objects can rest on (model frame).
    pub surfaces: Vec<SurfaceRecord>,
    /// Static models (architecture) are welded to the world by the model itself.
    pub is_static: bool,
    /// How the asset was made (generator, version, parameters, seed, licence).
    pub provenance: serde_json::Value,
}

impl Asset {
    /// Total mass, kg.
    pub fn mass(&self) -> f64 {
        self.links.iter().map(|l| l.mass.mass).sum()
    }

    /// Number of convex collision pieces over all links.
    pub fn collision_pieces(&self) -> usize {
        self.links.iter().map(|l| l.collisions.len()).sum()
    }

    /// The root link.
    pub fn root(&self) -> Option<&Link> {
        self.links.first()
    }

    /// Bounds of all collision and visual geometry in the model frame at zero joint positions.
    pub fn bounds(&self) -> [[f64; 3]; 2] {
        let mut pts: Vec<[f64; 3]> = Vec::new();
        for link in &self.links {
            for piece in &link.collisions {
                pts.extend(piece.transformed(&link.model_from_link).vertices);
            }
            for v in &link.visuals {
                pts.extend(v.mesh.transformed(&link.model_from_link).positions);
            }
        }
        match mesh::bounds_of(&pts) {
            Some((lo, hi)) => [lo, hi],
            None => [[0.0; 3]; 2],
        }
    }

    /// Checks the structure and physics: at least one link, unique names, every link with mass
    /// properties that a real body has, joints naming existing links with ordered limits.
    pub fn validate(&self) -> Result<(), AssetError> {
        let malformed = |reason: String| AssetError::Malformed {
            asset: self.id.clone(),
            reason,
        };
        if self.links.is_empty() {
            return Err(malformed("no links".into()));
        }
        let mut names = std::collections::BTreeSet::new();
        for link in &self.links {
            if !names.insert(link.name.as_str()) {
                return Err(malformed(format!("link name {:?} used twice", link.name)));
            }
            if link.collisions.is_empty() && !self.is_static {
                return Err(malformed(format!("link {:?} has no collision", link.name)));
            }
            if !self.is_static {
                link.mass
                    .validate()
                    .map_err(|source| AssetError::Geometry {
                        asset: self.id.clone(),
                        cause: source,
                    })?;
            }
        }
        for j in &self.joints {
            if !names.contains(j.parent.as_str()) || !names.contains(j.child.as_str()) {
                return Err(malformed(format!(
                    "joint {:?} connects unknown links {:?} -> {:?}",
                    j.name, j.parent, j.child
                )));
            }
            if j.lower.partial_cmp(&j.upper).is_none_or(|o| o.is_gt()) {
                return Err(malformed(format!(
                    "joint {:?} has lower limit {} above upper {}",
                    j.name, j.lower, j.upper
                )));
            }
        }
        Ok(())
    }

    /// Directory of the asset inside a scene directory: `assets/<id>` for objects,
    /// `rooms/<room>` for room architecture.
    pub fn scene_dir(&self) -> String {
        match self.provenance.get("room").and_then(|r| r.as_str()) {
            Some(room) if self.is_static => format!("rooms/{}", crate::scene::sanitize_name(room)),
            _ => format!("assets/{}", self.id),
        }
    }

    /// The summary the scene keeps (`scene.json`).
    pub fn record(&self) -> AssetRecord {
        AssetRecord {
            id: self.id.clone(),
            category: self.category.clone(),
            sdf: format!("{}/model.sdf", self.scene_dir()),
            root_link: self
                .links
                .first()
                .map(|l| l.name.clone())
                .unwrap_or_default(),
            links: self.links.iter().map(|l| l.name.clone()).collect(),
            joints: self
                .joints
                .iter()
                .map(|j| JointRecord {
                    name: j.name.clone(),
                    kind: j.kind.as_str().to_string(),
                    lower: j.lower,
                    upper: j.upper,
                })
                .collect(),
            bounds: self.bounds(),
            mass: self.mass(),
            collision_pieces: self.collision_pieces(),
            material: self.material.clone(),
            surfaces: self.surfaces.clone(),
            provenance: self.provenance.clone(),
        }
    }
}

/// Content-addressed asset id: `<category>_<8 base-36 chars of blake3(key)>`.
pub fn content_id(category: &str, key: &serde_json::Value) -> String {
    let bytes = serde_json::to_vec(key).unwrap_or_default();
    let hash = blake3::hash(&bytes);
    let mut n = 0u64;
    for b in &hash.as_bytes()[..8] {
        n = (n << 8) | u64::from(*b);
    }
    let mut code = crate::scene::ids::base36(n);
    code.truncate(8);
    format!("{}_{code}", crate::scene::sanitize_name(category))
}

/// Pose of every link in the model frame for the given joint positions (missing joints at 0).
///
/// Joint frames coincide with child link frames, so a child's pose is its zero-position pose
/// moved by the joint motion expressed in its own frame; chains are followed parent-first.
pub fn link_poses(
    asset: &Asset,
    joint_positions: &std::collections::BTreeMap<String, f64>,
) -> Vec<Pose> {
    use nalgebra::{Translation3, Unit, UnitQuaternion, Vector3};
    let index = |name: &str| asset.links.iter().position(|l| l.name == name);
    let mut poses: Vec<Option<Pose>> = vec![None; asset.links.len()];
    if let Some(first) = poses.first_mut() {
        *first = Some(asset.links[0].model_from_link);
    }
    // Links not moved by any joint keep their zero pose.
    for (i, link) in asset.links.iter().enumerate() {
        if !asset.joints.iter().any(|j| j.child == link.name) {
            poses[i] = Some(link.model_from_link);
        }
    }
    for _ in 0..asset.links.len() {
        for j in &asset.joints {
            let (Some(pi), Some(ci)) = (index(&j.parent), index(&j.child)) else {
                continue;
            };
            let Some(model_from_parent) = poses[pi] else {
                continue;
            };
            if poses[ci].is_some() {
                continue;
            }
            let parent_zero = asset.links[pi].model_from_link;
            let child_zero = asset.links[ci].model_from_link;
            let parent_from_child = parent_zero.inverse().compose(&child_zero);
            let q = joint_positions.get(&j.name).copied().unwrap_or(0.0);
            let axis = Unit::new_normalize(Vector3::from(j.axis));
            let motion = match j.kind {
                JointKind::Revolute => Pose(nalgebra::Isometry3::from_parts(
                    Translation3::identity(),
                    UnitQuaternion::from_axis_angle(&axis, q),
                )),
                JointKind::Prismatic => {
                    let t = axis.into_inner() * q;
                    Pose::from_xyz(t.x, t.y, t.z)
                }
            };
            poses[ci] = Some(
                model_from_parent
                    .compose(&parent_from_child)
                    .compose(&motion),
            );
        }
    }
    poses
        .into_iter()
        .zip(&asset.links)
        .map(|(p, l)| p.unwrap_or(l.model_from_link))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn content_id_is_stable_and_readable() {
        let key = serde_json::json!({"generator": "table", "seed": 3});
        let a = content_id("Coffee Table", &key);
        let b = content_id("Coffee Table", &key);
        assert_eq!(a, b);
        assert!(a.starts_with("coffee_table_"));
        let other = content_id(
            "Coffee Table",
            &serde_json::json!({"generator": "table", "seed": 4}),
        );
        assert_ne!(a, other);
    }

    #[test]
    fn builder_computes_mass_from_pieces() {
        let wood = material::material_or_default("wood");
        let mut b = LinkBuilder::new("body", Pose::IDENTITY, wood);
        b.add_box([0.0, 0.0, 0.05], [1.0, 1.0, 0.1], wood.color)
            .unwrap();
        let link = b.finish().unwrap();
        assert!((link.mass.mass - 60.0).abs() < 1e-9);
        assert_eq!(link.collisions.len(), 1);
        assert_eq!(link.visuals.len(), 1);
    }
}
