//! Hand-built scenes for the physics tests and the physics benchmark: a walled room, blocks
//! of mixed convex shapes, and heaps of overlapping blocks.
#![allow(dead_code)]

use std::collections::BTreeMap;

use rand::rngs::ChaCha8Rng;
use rand::{RngExt, SeedableRng};
use serde_json::json;

use scenesmith::assets::architecture;
use scenesmith::assets::{Asset, LinkBuilder, material};
use scenesmith::geometry::ConvexPiece;
use scenesmith::physics::collision::{penetrating_pairs, posed_objects};
use scenesmith::physics::{BridgeConfig, BridgePool};
use scenesmith::scene::rectangle_walls;
use scenesmith::scene::{ObjectKind, Pose, Room, Scene, SceneObject, Support, SurfaceRecord};
use scenesmith::state::SceneState;

/// Shapes of test blocks; every block has its bottom at z = 0 and a `top` surface.
#[derive(Debug, Clone, Copy)]
pub enum Shape {
    /// Full extents.
    Box([f64; 3]),
    /// Radius and height (a 16-sided prism).
    Cylinder(f64, f64),
    /// Convex hull of 40 seeded points on an ellipsoid with these radii.
    Blob([f64; 3], u64),
}

/// A one-link block asset of `shape` made of `material`.
pub fn block(id: &str, shape: Shape, material_name: &str) -> Asset {
    let mat = material::material_or_default(material_name);
    let mut link = LinkBuilder::new("body", Pose::IDENTITY, mat);
    let (top, size_xy) = match shape {
        Shape::Box(s) => {
            link.add_box([0.0, 0.0, s[2] / 2.0], s, mat.color).unwrap();
            (s[2], [s[0], s[1]])
        }
        Shape::Cylinder(r, h) => {
            link.add_cylinder([0.0, 0.0], r, 0.0, h, mat.color).unwrap();
            (h, [2.0 * r, 2.0 * r])
        }
        Shape::Blob(radii, seed) => {
            let mut rng = ChaCha8Rng::seed_from_u64(seed);
            let pts: Vec<[f64; 3]> = (0..40)
                .map(|_| {
                    let (u, v): (f64, f64) =
                        (rng.random_range(-1.0..1.0), rng.random_range(0.0..1.0));
                    let phi = std::f64::consts::TAU * v;
                    let s = (1.0 - u * u).sqrt();
                    [
                        radii[0] * s * phi.cos(),
                        radii[1] * s * phi.sin(),
                        radii[2] * (u + 1.0),
                    ]
                })
                .collect();
            link.add_collision(ConvexPiece::from_points(&pts).unwrap());
            (2.0 * radii[2], [radii[0], radii[1]])
        }
    };
    Asset {
        id: id.into(),
        category: "block".into(),
        material: material_name.into(),
        links: vec![link.finish().unwrap()],
        joints: vec![],
        surfaces: vec![SurfaceRecord {
            id: "top".into(),
            link: "body".into(),
            center: [0.0, 0.0, top],
            size: size_xy,
            clearance: 1.0,
        }],
        is_static: false,
        provenance: json!({"generator": "physics test block"}),
    }
}

/// A walled `w x d` room (`room_0`, floor top at z = 0) with nothing in it.
pub fn room(w: f64, d: f64) -> SceneState {
    let mut scene = Scene::new("a test room", 0, "physics_test");
    let room = Room {
        id: "room_0".into(),
        room_type: "room".into(),
        label: None,
        prompt: String::new(),
        floor_polygon: vec![[0.0, 0.0], [w, 0.0], [w, d], [0.0, d]],
        wall_height: 2.5,
        walls: rectangle_walls("room_0", [0.0, 0.0], w, d, 0.1),
        floor_material: "oak".into(),
        wall_material: "plaster".into(),
    };
    scene.rooms.push(room.clone());
    let mut state = SceneState::new(scene);
    let arch = architecture::build_room_asset(&room, "room_0_architecture").unwrap();
    let asset = state.insert_asset(arch);
    state.scene.ids.reserve("room_0_architecture");
    state.scene.objects.push(SceneObject {
        id: "room_0_architecture".into(),
        category: "room_architecture".into(),
        name: None,
        planned: None,
        kind: ObjectKind::Architecture,
        room: "room_0".into(),
        asset,
        world_from_object: Pose::IDENTITY,
        support: Support::World,
        welded: true,
        joint_positions: BTreeMap::new(),
    });
    state
}

/// Places an object of `asset` (registered with `state` first).
pub fn place(
    state: &mut SceneState,
    asset: &Asset,
    kind: ObjectKind,
    world_from_object: Pose,
    support: Support,
) -> String {
    let asset_id = state.insert_asset(asset.clone());
    let category = asset.category.clone();
    state.add_object(
        &category,
        kind,
        "room_0",
        &asset_id,
        world_from_object,
        support,
    )
}

/// On the floor of `room_0`.
pub fn floor() -> Support {
    Support::Floor {
        room: "room_0".into(),
    }
}

/// On the `top` surface of `parent`.
pub fn on(parent: &str) -> Support {
    Support::Object {
        parent: parent.into(),
        surface: "top".into(),
    }
}

/// Deepest penetration between any two objects of the scene, metres.
pub fn max_penetration(state: &SceneState) -> f64 {
    let posed = posed_objects(&state.scene, &state.assets).unwrap();
    penetrating_pairs(&posed, 0.0)
        .iter()
        .map(|p| p.depth)
        .fold(0.0, f64::max)
}

/// A pool of `n` bridge workers from this checkout.
pub fn pool(n: usize) -> BridgePool {
    BridgePool::new(BridgeConfig::from_env(), n)
}

/// `n` free blocks of mixed shapes (boxes, cylinders, blobs; random yaw) heaped into a
/// `side x side` patch of a large room so that most of them overlap; on the floor.
pub fn overlapping_heap(n: usize, seed: u64) -> SceneState {
    let side = (n as f64).sqrt() * 0.13;
    let mut state = room(side + 3.0, side + 3.0);
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let shapes = [
        block("box_s", Shape::Box([0.12, 0.09, 0.08]), "wood"),
        block("box_l", Shape::Box([0.18, 0.12, 0.10]), "wood"),
        block("cyl", Shape::Cylinder(0.05, 0.12), "ceramic"),
        block("blob_a", Shape::Blob([0.07, 0.06, 0.05], 1), "plastic"),
        block("blob_b", Shape::Blob([0.05, 0.08, 0.04], 2), "plastic"),
    ];
    for i in 0..n {
        let a = &shapes[i % shapes.len()];
        let x = 1.5 + rng.random_range(0.0..side);
        let y = 1.5 + rng.random_range(0.0..side);
        let yaw = rng.random_range(0.0..std::f64::consts::TAU);
        place(
            &mut state,
            a,
            ObjectKind::Manipuland,
            Pose::from_xyz_yaw(x, y, 0.0, yaw),
            floor(),
        );
    }
    state
}
