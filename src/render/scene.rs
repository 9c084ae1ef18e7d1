//! The render scene: every visual part of a [`SceneState`] (or of one [`Asset`]) posed in the
//! world as flat triangle meshes, tagged with the object it belongs to and, for architecture,
//! with its role (floor, a given wall, ceiling) so views can cut walls away or drop ceilings.
//!
//! This module does not draw; [`super::raster`] does.

use nalgebra::{Point3, Vector3};

use super::RenderError;
use crate::assets::{self, Asset, Texture};
use crate::geometry::TriMesh;
use crate::scene::{ObjectKind, Pose, Room};
use crate::state::SceneState;

/// What a mesh is, for architecture; everything else is [`Role::Object`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Role {
    /// Part of a placed object (furniture, small object, wall- or ceiling-mounted item).
    Object,
    /// Floor slab.
    Floor,
    /// A wall piece: index of the room and of the wall in that room's `walls`.
    Wall {
        /// Index into [`RenderScene::rooms`].
        room: usize,
        /// Index into that room's walls.
        wall: usize,
    },
    /// Ceiling slab (left out of plans and room views).
    Ceiling,
    /// Other architecture geometry.
    Other,
}

/// One posed mesh, world frame, single precision (houses are tens of metres; f32 keeps
/// micrometres there).
#[derive(Debug, Clone)]
pub struct RenderMesh {
    /// Vertex positions, world, metres.
    pub positions: Vec<[f32; 3]>,
    /// Unit vertex normals, world.
    pub normals: Vec<[f32; 3]>,
    /// Texture coordinates (empty when untextured).
    pub uvs: Vec<[f32; 2]>,
    /// Triangles, counter-clockwise from outside.
    pub triangles: Vec<[u32; 3]>,
    /// Linear RGB base colour.
    pub color: [f32; 3],
    /// Base-colour texture (sRGB texels), multiplied by `color`.
    pub texture: Option<Texture>,
    /// Index into [`RenderScene::objects`], if the mesh belongs to an object.
    pub object: Option<usize>,
    /// Architecture role.
    pub role: Role,
}

impl RenderMesh {
    /// A mesh from a [`TriMesh`] mapped into the world by `world_from_mesh`.
    pub fn from_trimesh(
        mesh: &TriMesh,
        world_from_mesh: &Pose,
        color: [f64; 4],
        texture: Option<Texture>,
    ) -> RenderMesh {
        let positions = mesh
            .positions
            .iter()
            .map(|p| {
                let q = world_from_mesh.transform_point(&Point3::new(p[0], p[1], p[2]));
                [q.x as f32, q.y as f32, q.z as f32]
            })
            .collect();
        let normals = mesh
            .normals
            .iter()
            .map(|n| {
                let m = world_from_mesh
                    .transform_vector(&Vector3::new(n[0], n[1], n[2]))
                    .try_normalize(1e-12)
                    .unwrap_or(Vector3::z());
                [m.x as f32, m.y as f32, m.z as f32]
            })
            .collect();
        let has_uvs = texture.is_some() && mesh.uvs.len() == mesh.positions.len();
        let uvs = if has_uvs {
            mesh.uvs
                .iter()
                .map(|t| [t[0] as f32, t[1] as f32])
                .collect()
        } else {
            Vec::new()
        };
        let n = mesh.positions.len() as u32;
        RenderMesh {
            positions,
            normals,
            uvs,
            // Indices that point past the vertices would be a broken input mesh: drop them.
            triangles: mesh
                .triangles
                .iter()
                .copied()
                .filter(|t| t.iter().all(|&i| i < n))
                .collect(),
            color: [color[0] as f32, color[1] as f32, color[2] as f32],
            texture: if has_uvs { texture } else { None },
            object: None,
            role: Role::Object,
        }
    }

    /// World bounds `(min, max)`; `None` when empty.
    pub fn bounds(&self) -> Option<([f64; 3], [f64; 3])> {
        let mut it = self.triangles.iter().flatten();
        let first = self.positions.get(*it.next()? as usize)?;
        let mut lo = first.map(f64::from);
        let mut hi = lo;
        for &i in self.triangles.iter().flatten() {
            if let Some(p) = self.positions.get(i as usize) {
                for k in 0..3 {
                    lo[k] = lo[k].min(f64::from(p[k]));
                    hi[k] = hi[k].max(f64::from(p[k]));
                }
            }
        }
        Some((lo, hi))
    }

    /// The sub-mesh made of the triangles `keep` selects (vertices re-indexed).
    fn subset(&self, keep: &[usize]) -> RenderMesh {
        let mut map = vec![u32::MAX; self.positions.len()];
        let mut out = RenderMesh {
            positions: Vec::new(),
            normals: Vec::new(),
            uvs: Vec::new(),
            triangles: Vec::with_capacity(keep.len()),
            color: self.color,
            texture: self.texture.clone(),
            object: self.object,
            role: self.role,
        };
        for &t in keep {
            let tri = self.triangles[t];
            let mut idx = [0u32; 3];
            for (k, &v) in tri.iter().enumerate() {
                let v = v as usize;
                if map[v] == u32::MAX {
                    map[v] = out.positions.len() as u32;
                    out.positions.push(self.positions[v]);
                    out.normals
                        .push(self.normals.get(v).copied().unwrap_or([0.0, 0.0, 1.0]));
                    if !self.uvs.is_empty() {
                        out.uvs.push(self.uvs.get(v).copied().unwrap_or([0.0, 0.0]));
                    }
                }
                idx[k] = map[v];
            }
            out.triangles.push(idx);
        }
        out
    }
}

/// An object as the views need it: what to call it and where it is.
#[derive(Debug, Clone)]
pub struct RenderObject {
    /// Object id (the label).
    pub id: String,
    /// Category noun.
    pub category: String,
    /// Role of the object.
    pub kind: ObjectKind,
    /// Room id.
    pub room: String,
    /// World bounds of its visual geometry `[min, max]`.
    pub bounds: [[f64; 3]; 2],
    /// World position of the object frame.
    pub origin: [f64; 3],
}

impl RenderObject {
    /// Centre of the bounds.
    pub fn center(&self) -> [f64; 3] {
        let [lo, hi] = self.bounds;
        [
            (lo[0] + hi[0]) / 2.0,
            (lo[1] + hi[1]) / 2.0,
            (lo[2] + hi[2]) / 2.0,
        ]
    }
}

/// Everything a view draws.
#[derive(Debug, Clone, Default)]
pub struct RenderScene {
    /// Posed meshes.
    pub meshes: Vec<RenderMesh>,
    /// Objects (architecture included) by index.
    pub objects: Vec<RenderObject>,
    /// Rooms (for cut-aways and plan annotations).
    pub rooms: Vec<Room>,
}

impl RenderScene {
    /// Poses every object of `state`: its asset's visuals at the link poses its joint
    /// positions give, moved by `world_from_object`. Architecture triangles are split by role.
    pub fn from_state(state: &SceneState) -> Result<RenderScene, RenderError> {
        let mut out = RenderScene {
            meshes: Vec::new(),
            objects: Vec::new(),
            rooms: state.scene.rooms.clone(),
        };
        for o in &state.scene.objects {
            let asset = state
                .assets
                .get(&o.asset)
                .ok_or_else(|| RenderError::MissingAsset {
                    object: o.id.clone(),
                    asset: o.asset.clone(),
                })?;
            let index = out.objects.len();
            let meshes = posed_meshes(asset, &o.world_from_object, &o.joint_positions);
            let mut bounds: Option<([f64; 3], [f64; 3])> = None;
            for mut m in meshes {
                m.object = Some(index);
                if let Some((lo, hi)) = m.bounds() {
                    bounds = Some(match bounds {
                        None => (lo, hi),
                        Some((a, b)) => (
                            [a[0].min(lo[0]), a[1].min(lo[1]), a[2].min(lo[2])],
                            [b[0].max(hi[0]), b[1].max(hi[1]), b[2].max(hi[2])],
                        ),
                    });
                }
                if o.kind == ObjectKind::Architecture {
                    out.meshes.extend(split_architecture(&m, &out.rooms));
                } else {
                    out.meshes.push(m);
                }
            }
            let t = o.world_from_object.translation();
            let origin = [t.x, t.y, t.z];
            let (lo, hi) = bounds.unwrap_or((origin, origin));
            out.objects.push(RenderObject {
                id: o.id.clone(),
                category: o.category.clone(),
                kind: o.kind,
                room: o.room.clone(),
                bounds: [lo, hi],
                origin,
            });
        }
        Ok(out)
    }

    /// One asset at the origin (zero joint positions), as its only object.
    pub fn from_asset(asset: &Asset) -> RenderScene {
        let meshes: Vec<RenderMesh> = posed_meshes(asset, &Pose::IDENTITY, &Default::default())
            .into_iter()
            .map(|mut m| {
                m.object = Some(0);
                m
            })
            .collect();
        let b = asset.bounds();
        RenderScene {
            meshes,
            objects: vec![RenderObject {
                id: asset.id.clone(),
                category: asset.category.clone(),
                kind: ObjectKind::Furniture,
                room: String::new(),
                bounds: b,
                origin: [0.0; 3],
            }],
            rooms: Vec::new(),
        }
    }

    /// Number of triangles over all meshes.
    pub fn triangle_count(&self) -> usize {
        self.meshes.iter().map(|m| m.triangles.len()).sum()
    }

    /// World bounds of all meshes passing `keep`.
    pub fn bounds_where(&self, keep: impl Fn(&RenderMesh) -> bool) -> Option<([f64; 3], [f64; 3])> {
        let mut out: Option<([f64; 3], [f64; 3])> = None;
        for m in self.meshes.iter().filter(|m| keep(m)) {
            if let Some((lo, hi)) = m.bounds() {
                out = Some(match out {
                    None => (lo, hi),
                    Some((a, b)) => (
                        [a[0].min(lo[0]), a[1].min(lo[1]), a[2].min(lo[2])],
                        [b[0].max(hi[0]), b[1].max(hi[1]), b[2].max(hi[2])],
                    ),
                });
            }
        }
        out
    }
}

/// The visuals of `asset` posed at `world_from_object` with the given joint positions.
fn posed_meshes(
    asset: &Asset,
    world_from_object: &Pose,
    joint_positions: &std::collections::BTreeMap<String, f64>,
) -> Vec<RenderMesh> {
    let model_from_links = assets::link_poses(asset, joint_positions);
    let mut out = Vec::new();
    for (link, model_from_link) in asset.links.iter().zip(&model_from_links) {
        let world_from_link = world_from_object.compose(model_from_link);
        for v in &link.visuals {
            if v.mesh.is_empty() {
                continue;
            }
            out.push(RenderMesh::from_trimesh(
                &v.mesh,
                &world_from_link,
                v.color,
                v.texture.clone(),
            ));
        }
    }
    out
}

/// Tolerance of the architecture classification, metres.
const ARCH_TOL: f64 = 2e-3;

/// The wall (room, wall) whose slab contains all three corners, if any. Corners of a room
/// lie in two slabs, so the test is per triangle, not per vertex.
fn wall_containing(rooms: &[Room], tri: &[[f32; 3]; 3]) -> Option<(usize, usize)> {
    for (ri, room) in rooms.iter().enumerate() {
        for (wi, wall) in room.walls.iter().enumerate() {
            let wall_from_world = wall.world_from_wall().inverse();
            let half_t = wall.thickness / 2.0 + ARCH_TOL;
            let len = wall.length();
            let inside = tri.iter().all(|p| {
                let q = wall_from_world.transform_point(&Point3::new(
                    f64::from(p[0]),
                    f64::from(p[1]),
                    f64::from(p[2]),
                ));
                q.y.abs() <= half_t && q.x >= -half_t && q.x <= len + half_t
            });
            if inside {
                return Some((ri, wi));
            }
        }
    }
    None
}

/// Splits an architecture mesh by role: a triangle whose three corners lie inside one wall's
/// slab is that wall; a horizontal triangle at ceiling height is ceiling; one at or below the
/// floor is floor. Classifying geometry, not part names, keeps this independent of how the
/// layout stage builds its meshes.
fn split_architecture(mesh: &RenderMesh, rooms: &[Room]) -> Vec<RenderMesh> {
    let ceiling_z = rooms
        .iter()
        .map(|r| r.wall_height)
        .fold(f64::INFINITY, f64::min);
    let mut groups: std::collections::BTreeMap<(u8, usize, usize), Vec<usize>> = Default::default();
    for (t, tri) in mesh.triangles.iter().enumerate() {
        let p = tri.map(|i| mesh.positions[i as usize]);
        let key = match wall_containing(rooms, &p) {
            Some((room, wall)) => (1, room, wall),
            None => {
                let zmin = p
                    .iter()
                    .map(|q| f64::from(q[2]))
                    .fold(f64::INFINITY, f64::min);
                let zmax = p
                    .iter()
                    .map(|q| f64::from(q[2]))
                    .fold(f64::NEG_INFINITY, f64::max);
                if zmax <= ARCH_TOL {
                    (0, 0, 0)
                } else if ceiling_z.is_finite() && zmin >= ceiling_z - ARCH_TOL {
                    (2, 0, 0)
                } else {
                    (3, 0, 0)
                }
            }
        };
        groups.entry(key).or_default().push(t);
    }
    groups
        .into_iter()
        .map(|((kind, room, wall), tris)| {
            let mut m = mesh.subset(&tris);
            m.role = match kind {
                0 => Role::Floor,
                1 => Role::Wall { room, wall },
                2 => Role::Ceiling,
                _ => Role::Other,
            };
            m
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::assets::architecture::build_room_asset;
    use crate::scene::{Scene, SceneObject, Support, rectangle_walls};

    fn room() -> Room {
        Room {
            id: "room_0".into(),
            room_type: "room".into(),
            label: None,
            prompt: String::new(),
            floor_polygon: vec![[0.0, 0.0], [3.0, 0.0], [3.0, 2.0], [0.0, 2.0]],
            wall_height: 2.5,
            walls: rectangle_walls("room_0", [0.0, 0.0], 3.0, 2.0, 0.1),
            floor_material: "oak".into(),
            wall_material: "plaster".into(),
        }
    }

    #[test]
    fn architecture_splits_into_floor_and_four_walls() {
        let room = room();
        let asset = build_room_asset(&room, "arch").unwrap();
        let mut scene = Scene::new("a room", 0, "t");
        scene.rooms.push(room);
        let mut state = SceneState::new(scene);
        let id = state.insert_asset(asset);
        state.scene.objects.push(SceneObject {
            id: "room_0_architecture".into(),
            category: "room_architecture".into(),
            name: None,
            planned: None,
            kind: ObjectKind::Architecture,
            room: "room_0".into(),
            asset: id,
            world_from_object: Pose::IDENTITY,
            support: Support::World,
            welded: true,
            joint_positions: Default::default(),
        });
        let rs = RenderScene::from_state(&state).unwrap();
        let floors = rs.meshes.iter().filter(|m| m.role == Role::Floor).count();
        assert!(floors >= 1);
        let mut walls: Vec<usize> = rs
            .meshes
            .iter()
            .filter_map(|m| match m.role {
                Role::Wall { wall, .. } => Some(wall),
                _ => None,
            })
            .collect();
        walls.sort();
        walls.dedup();
        assert_eq!(walls, vec![0, 1, 2, 3]);
        assert!(rs.meshes.iter().all(|m| m.role != Role::Other));
        let b = rs.objects[0].bounds;
        assert!((b[1][2] - 2.5).abs() < 1e-6 && b[0][2] < -0.05);
    }
}
