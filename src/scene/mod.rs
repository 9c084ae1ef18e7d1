//! The scene model: the one structure every stage edits and every writer reads.
//!
//! `Scene -> rooms (architecture: floor polygon, volumetric walls with openings, wall height)`
//! and a flat list of objects, each an instance of an asset at a pose in the world with a support
//! relation. `scene.json` is this structure serialised (versioned by [`SCHEMA_VERSION`]).

pub mod ids;
pub mod pose;

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

pub use ids::{IdAllocator, sanitize_name};
pub use pose::Pose;

/// Version of the `scene.json` schema. Bump on any incompatible change.
pub const SCHEMA_VERSION: u32 = 1;

/// A whole generated scene: rooms, objects, the assets they instantiate, and where it came from.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct Scene {
    /// [`SCHEMA_VERSION`] of the writer.
    pub schema_version: u32,
    /// Inputs and backends that produced the scene.
    pub provenance: Provenance,
    /// ROS-style package name used in every `package://` URI of the scene directory.
    pub package_name: String,
    /// The rooms with their architecture.
    pub rooms: Vec<Room>,
    /// Every object, architecture included.
    pub objects: Vec<SceneObject>,
    /// Summary of each asset the objects instantiate, by asset id.
    pub assets: BTreeMap<String, AssetRecord>,
    /// Objects taken out by a stage or post-processing, with the reason.
    #[serde(default)]
    pub removed: Vec<Removal>,
    /// Objects the prompt asked for that post-processing removed and then placed again
    /// elsewhere (they are in `objects`, not in `removed`).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub placed_again: Vec<PlacedAgain>,
    /// Id counters, so edits after a reload never reuse an id.
    #[serde(default)]
    pub ids: IdAllocator,
    /// Results of the physics checks run on the written scene.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub checks: Option<serde_json::Value>,
    /// Language-model usage per stage (empty for the built-in backend).
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub llm_usage: BTreeMap<String, StageUsage>,
}

/// Requests, retries, tokens and cost of one stage's language-model calls.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct StageUsage {
    /// Successful requests.
    pub requests: u64,
    /// Failed attempts that were retried.
    pub retries: u64,
    /// Input tokens reported by the endpoint.
    pub prompt_tokens: u64,
    /// Output tokens reported by the endpoint.
    pub completion_tokens: u64,
    /// Cost at the configured prices, USD.
    pub cost_usd: f64,
}

/// Where a scene came from. Deliberately holds no timestamps or host names: the same prompt,
/// seed and backends give the same bytes.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct Provenance {
    /// Version of the `scenesmith` crate that wrote the scene.
    pub tool_version: String,
    /// The user's prompt, verbatim.
    pub prompt: String,
    /// The seed driving every random choice.
    pub seed: u64,
    /// Names of the backends per role (`designer`, `critic`, `assets`, `physics`).
    pub backends: BTreeMap<String, String>,
}

/// One room: its floor, walls, openings and the prompt text that concerns it.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct Room {
    /// Readable id, e.g. `kitchen_0`.
    pub id: String,
    /// Room type noun, e.g. `kitchen`.
    pub room_type: String,
    /// The prompt's own name for the room ("exam room", "master bedroom"), when known. Older
    /// scene files have none.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub label: Option<String>,
    /// The part of the prompt that concerns this room.
    pub prompt: String,
    /// Clear interior floor (inside faces of the walls), world XY, counter-clockwise, metres.
    pub floor_polygon: Vec<[f64; 2]>,
    /// Floor to ceiling, metres.
    pub wall_height: f64,
    /// Every wall around the room's floor, each facing into this room. A wall shared with a
    /// neighbour is listed in both rooms but built by one: the other room's copy names it in
    /// [`Wall::mirror_of`].
    pub walls: Vec<Wall>,
    /// Floor material name (see the material table).
    pub floor_material: String,
    /// Wall material name.
    pub wall_material: String,
}

/// A volumetric wall: a straight centre line, a thickness and the openings cut through it.
///
/// The wall frame (`world_from_wall`) has its origin on the centre line at `start`, floor level,
/// +X along the wall towards `end`, +Z up and +Y pointing into the owning room.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct Wall {
    /// Readable id, e.g. `kitchen_0_wall_2`.
    pub id: String,
    /// Start of the centre line, world XY.
    pub start: [f64; 2],
    /// End of the centre line, world XY.
    pub end: [f64; 2],
    /// Thickness, metres.
    pub thickness: f64,
    /// Room on the other side, if the wall is shared.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub neighbor: Option<String>,
    /// Doors, windows and open connections cut through the wall.
    #[serde(default)]
    pub openings: Vec<Opening>,
    /// For this room's side of a shared wall whose geometry the neighbour builds: the id of the
    /// neighbour's wall (same centre line, reversed, openings mirrored). `None`: this room
    /// builds the wall.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub mirror_of: Option<String>,
}

impl Wall {
    /// Length of the centre line, metres.
    pub fn length(&self) -> f64 {
        ((self.end[0] - self.start[0]).powi(2) + (self.end[1] - self.start[1]).powi(2)).sqrt()
    }

    /// Pose of the wall frame in the world (see [`Wall`]).
    pub fn world_from_wall(&self) -> Pose {
        let yaw = (self.end[1] - self.start[1]).atan2(self.end[0] - self.start[0]);
        Pose::from_xyz_yaw(self.start[0], self.start[1], 0.0, yaw)
    }

    /// True when no room lies on the other side.
    pub fn is_exterior(&self) -> bool {
        self.neighbor.is_none()
    }
}

/// What an opening in a wall is.
#[derive(Debug, Clone, Copy, Serialize, Deserialize, PartialEq, Eq, PartialOrd, Ord, Hash)]
#[serde(rename_all = "snake_case")]
pub enum OpeningKind {
    /// A doorway (bottom at the floor; a lintel spans above it).
    Door,
    /// A window (sill above the floor; wall below and above).
    Window,
    /// An open connection: the wall is absent over the opening's width, floor to ceiling.
    Open,
}

/// A rectangular hole through a wall, in wall coordinates.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct Opening {
    /// Readable id, e.g. `door_0`.
    pub id: String,
    /// Door, window or open connection.
    pub kind: OpeningKind,
    /// Centre of the opening along the wall, metres from the wall's start.
    pub center: f64,
    /// Width along the wall, metres.
    pub width: f64,
    /// Height of the bottom edge above the floor (0 for doors), metres.
    pub bottom: f64,
    /// Height of the opening, metres.
    pub height: f64,
}

/// The role an object plays; decides how it is written (welded or free) and which stage owns it.
#[derive(Debug, Clone, Copy, Serialize, Deserialize, PartialEq, Eq, PartialOrd, Ord, Hash)]
#[serde(rename_all = "snake_case")]
pub enum ObjectKind {
    /// Floors and walls.
    Architecture,
    /// Floor-standing furniture.
    Furniture,
    /// Mounted on a wall.
    Wall,
    /// Hanging from the ceiling.
    Ceiling,
    /// Small, separately manipulable objects.
    Manipuland,
    /// Rugs, posters, tablecloths: thin geometry lying on a surface.
    ThinCovering,
}

impl ObjectKind {
    /// Whether objects of this kind are welded to the world in `scene.dmd.yaml`.
    pub fn welded_by_default(self) -> bool {
        matches!(
            self,
            ObjectKind::Architecture
                | ObjectKind::Wall
                | ObjectKind::Ceiling
                | ObjectKind::ThinCovering
        )
    }

    /// Plain name used in tables and file names.
    pub fn as_str(self) -> &'static str {
        match self {
            ObjectKind::Architecture => "architecture",
            ObjectKind::Furniture => "furniture",
            ObjectKind::Wall => "wall",
            ObjectKind::Ceiling => "ceiling",
            ObjectKind::Manipuland => "manipuland",
            ObjectKind::ThinCovering => "thin_covering",
        }
    }
}

/// What holds an object up.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
#[serde(tag = "type", rename_all = "snake_case")]
pub enum Support {
    /// Stands on the floor of a room.
    Floor {
        /// Room id.
        room: String,
    },
    /// Mounted on a wall.
    Wall {
        /// Wall id.
        wall: String,
    },
    /// Hangs from the ceiling of a room.
    Ceiling {
        /// Room id.
        room: String,
    },
    /// Rests on a support surface of another object.
    Object {
        /// Id of the supporting object.
        parent: String,
        /// Id of the surface on the parent's asset (e.g. `top`, `shelf_1`).
        surface: String,
    },
    /// Fixed to the world (architecture).
    World,
}

/// One placed object: an instance of an asset at a pose.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct SceneObject {
    /// Readable id (name + base-36 counter); also the Drake model instance name.
    pub id: String,
    /// Plain noun, e.g. `nightstand`.
    pub category: String,
    /// The prompt's own noun for the object ("couch" where the category is `sofa`), when
    /// known. Older scene files have none.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub name: Option<String>,
    /// The plan's noun the object was placed for ("record player" for "a gramophone with a
    /// great flared horn"), when a stage placed it for an item of the plan: what counts it
    /// against that item whatever it is called. Older scene files have none.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub planned: Option<String>,
    /// Role of the object.
    pub kind: ObjectKind,
    /// Id of the room the object is in.
    pub room: String,
    /// Id of the asset this object instantiates.
    pub asset: String,
    /// Pose of the asset's model frame in the world.
    pub world_from_object: Pose,
    /// What holds the object up.
    pub support: Support,
    /// Welded to the world in `scene.dmd.yaml` (free otherwise).
    pub welded: bool,
    /// Initial joint positions of articulated assets (rad or m), by joint name.
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub joint_positions: BTreeMap<String, f64>,
}

/// Summary of a built asset as the scene needs it (the meshes live in `assets/<id>/`).
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct AssetRecord {
    /// Content-addressed id, e.g. `table_3kx9q2`.
    pub id: String,
    /// Plain noun.
    pub category: String,
    /// Path of the SDFormat file relative to the scene directory.
    pub sdf: String,
    /// Name of the root (first) link.
    pub root_link: String,
    /// Link names.
    pub links: Vec<String>,
    /// Joint summaries.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub joints: Vec<JointRecord>,
    /// Bounds of the asset in its model frame at zero joint positions: `[min, max]`.
    pub bounds: [[f64; 3]; 2],
    /// Total mass, kg.
    pub mass: f64,
    /// Number of convex collision pieces.
    pub collision_pieces: usize,
    /// Main material name.
    pub material: String,
    /// Surfaces other objects can rest on.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub surfaces: Vec<SurfaceRecord>,
    /// How the asset was made.
    pub provenance: serde_json::Value,
}

/// A joint as the scene needs to know it.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct JointRecord {
    /// Joint name inside the model.
    pub name: String,
    /// `revolute` or `prismatic`.
    pub kind: String,
    /// Lower limit (rad or m).
    pub lower: f64,
    /// Upper limit (rad or m).
    pub upper: f64,
}

/// A horizontal rectangle objects can rest on, in the asset's model frame.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct SurfaceRecord {
    /// Surface id, unique in the asset (`top`, `shelf_0`, ...).
    pub id: String,
    /// Link the surface belongs to.
    pub link: String,
    /// Centre of the rectangle (x, y) and its height z, model frame, metres.
    pub center: [f64; 3],
    /// Extent along x and y, metres.
    pub size: [f64; 2],
    /// Free height above the surface (up to the next shelf or a default cap), metres.
    pub clearance: f64,
}

/// An object taken out of the scene, and why.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct Removal {
    /// The removed object's id.
    pub object: String,
    /// Its category.
    pub category: String,
    /// The stage that removed it.
    pub stage: String,
    /// Why, in words a user can act on.
    pub reason: String,
}

/// An asked-for object that post-processing removed, placed again on another surface.
#[derive(Debug, Clone, Serialize, Deserialize, PartialEq)]
pub struct PlacedAgain {
    /// The object's id (unchanged).
    pub object: String,
    /// Its category.
    pub category: String,
    /// Why it was removed from where the stage put it.
    pub removed_because: String,
    /// `parent/surface` where it rests now.
    pub surface: String,
    /// Places tried, this one included.
    pub attempts: u32,
}

/// What can be wrong with a scene as a whole.
#[derive(Debug, thiserror::Error)]
pub enum SceneError {
    /// Two objects share an id.
    #[error("object id {0:?} is used twice")]
    DuplicateId(String),
    /// An object names an asset the scene does not have.
    #[error("object {object:?} refers to unknown asset {asset:?}")]
    UnknownAsset {
        /// Object id.
        object: String,
        /// Missing asset id.
        asset: String,
    },
    /// An object names a room the scene does not have.
    #[error("object {object:?} refers to unknown room {room:?}")]
    UnknownRoom {
        /// Object id.
        object: String,
        /// Missing room id.
        room: String,
    },
    /// A pose with NaN or infinity.
    #[error("object {0:?} has a non-finite pose")]
    NonFinitePose(String),
    /// `scene.json` from a newer or older writer.
    #[error("scene.json has schema version {found}, this build reads {expected}")]
    SchemaVersion {
        /// Version in the file.
        found: u32,
        /// Version this build writes.
        expected: u32,
    },
}

impl Scene {
    /// An empty scene for `prompt` and `seed`.
    pub fn new(prompt: &str, seed: u64, package_name: &str) -> Scene {
        Scene {
            schema_version: SCHEMA_VERSION,
            provenance: Provenance {
                tool_version: env!("CARGO_PKG_VERSION").to_string(),
                prompt: prompt.to_string(),
                seed,
                backends: BTreeMap::new(),
            },
            package_name: package_name.to_string(),
            rooms: Vec::new(),
            objects: Vec::new(),
            assets: BTreeMap::new(),
            removed: Vec::new(),
            placed_again: Vec::new(),
            ids: IdAllocator::new(),
            checks: None,
            llm_usage: BTreeMap::new(),
        }
    }

    /// The library category an object is built as (its asset's; an object's own `category`
    /// is what the prompt calls it, "manicure_table" for a `table`).
    pub fn built_as<'a>(&'a self, o: &'a SceneObject) -> &'a str {
        self.assets
            .get(&o.asset)
            .map_or(o.category.as_str(), |a| a.category.as_str())
    }

    /// The object with id `id`.
    pub fn object(&self, id: &str) -> Option<&SceneObject> {
        self.objects.iter().find(|o| o.id == id)
    }

    /// The room with id `id`.
    pub fn room(&self, id: &str) -> Option<&Room> {
        self.rooms.iter().find(|r| r.id == id)
    }

    /// Checks references and poses: unique ids, known assets and rooms, finite poses.
    pub fn validate(&self) -> Result<(), SceneError> {
        if self.schema_version != SCHEMA_VERSION {
            return Err(SceneError::SchemaVersion {
                found: self.schema_version,
                expected: SCHEMA_VERSION,
            });
        }
        let mut seen = std::collections::BTreeSet::new();
        for o in &self.objects {
            if !seen.insert(o.id.as_str()) {
                return Err(SceneError::DuplicateId(o.id.clone()));
            }
            if !self.assets.contains_key(&o.asset) {
                return Err(SceneError::UnknownAsset {
                    object: o.id.clone(),
                    asset: o.asset.clone(),
                });
            }
            if self.room(&o.room).is_none() {
                return Err(SceneError::UnknownRoom {
                    object: o.id.clone(),
                    room: o.room.clone(),
                });
            }
            if !o.world_from_object.is_finite() {
                return Err(SceneError::NonFinitePose(o.id.clone()));
            }
        }
        Ok(())
    }

    /// Objects of one kind, in scene order.
    pub fn objects_of_kind(&self, kind: ObjectKind) -> impl Iterator<Item = &SceneObject> {
        self.objects.iter().filter(move |o| o.kind == kind)
    }
}

/// Four walls around a `w x d` clear floor whose lower-left interior corner is at `origin`.
///
/// Walls run counter-clockwise (south, east, north, west) with centre lines `thickness / 2`
/// outside the clear floor, so every wall frame's +Y points into the room.
pub fn rectangle_walls(
    room_id: &str,
    origin: [f64; 2],
    w: f64,
    d: f64,
    thickness: f64,
) -> Vec<Wall> {
    let h = thickness / 2.0;
    let (x0, y0) = (origin[0] - h, origin[1] - h);
    let (x1, y1) = (origin[0] + w + h, origin[1] + d + h);
    let corners = [[x0, y0], [x1, y0], [x1, y1], [x0, y1]];
    (0..4)
        .map(|i| Wall {
            id: format!("{room_id}_wall_{i}"),
            start: corners[i],
            end: corners[(i + 1) % 4],
            thickness,
            neighbor: None,
            openings: Vec::new(),
            mirror_of: None,
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tiny_scene() -> Scene {
        let mut s = Scene::new("a room", 7, "scene_test");
        s.rooms.push(Room {
            id: "room_0".into(),
            room_type: "room".into(),
            label: None,
            prompt: "a room".into(),
            floor_polygon: vec![[0.0, 0.0], [3.0, 0.0], [3.0, 3.0], [0.0, 3.0]],
            wall_height: 2.5,
            walls: vec![],
            floor_material: "wood".into(),
            wall_material: "plaster".into(),
        });
        s.assets.insert(
            "box_1".into(),
            AssetRecord {
                id: "box_1".into(),
                category: "box".into(),
                sdf: "assets/box_1/model.sdf".into(),
                root_link: "body".into(),
                links: vec!["body".into()],
                joints: vec![],
                bounds: [[-0.1; 3], [0.1; 3]],
                mass: 1.0,
                collision_pieces: 1,
                material: "wood".into(),
                surfaces: vec![],
                provenance: serde_json::json!({}),
            },
        );
        s.objects.push(SceneObject {
            id: "box_0".into(),
            category: "box".into(),
            name: None,
            planned: None,
            kind: ObjectKind::Manipuland,
            room: "room_0".into(),
            asset: "box_1".into(),
            world_from_object: Pose::from_xyz_yaw(1.0, 1.0, 0.1, 0.3),
            support: Support::Floor {
                room: "room_0".into(),
            },
            welded: false,
            joint_positions: BTreeMap::new(),
        });
        s
    }

    #[test]
    fn scene_json_round_trip() {
        let s = tiny_scene();
        s.validate().unwrap();
        let text = serde_json::to_string_pretty(&s).unwrap();
        let back: Scene = serde_json::from_str(&text).unwrap();
        assert_eq!(back, s);
        assert!(text.contains("\"type\": \"floor\""));
    }

    #[test]
    fn validate_catches_dangling_asset() {
        let mut s = tiny_scene();
        s.objects[0].asset = "nope".into();
        assert!(matches!(s.validate(), Err(SceneError::UnknownAsset { .. })));
    }

    #[test]
    fn wall_frame_points_into_room() {
        // Counter-clockwise room: the wall along +X at y=0 has the room on its left (+Y).
        let w = Wall {
            id: "w".into(),
            start: [0.0, 0.0],
            end: [4.0, 0.0],
            thickness: 0.1,
            neighbor: None,
            openings: vec![],
            mirror_of: None,
        };
        let inward = w
            .world_from_wall()
            .transform_vector(&nalgebra::Vector3::y());
        assert!((inward.y - 1.0).abs() < 1e-12);
        assert!((w.length() - 4.0).abs() < 1e-12);
    }
}
