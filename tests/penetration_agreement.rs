//! A known overlapping pair: parry3d's penetration depth and Drake's agree within 0.5 mm.

mod common;

use std::collections::BTreeMap;

use scenesmith::assets::{Asset, LinkBuilder, material};
use scenesmith::formats::scene_dir::write_scene_dir;
use scenesmith::physics::Bridge;
use scenesmith::physics::collision::{penetrating_pairs, posed_objects};
use scenesmith::physics::protocol::{Penetrations, PenetrationsArgs, SceneFiles};
use scenesmith::scene::{ObjectKind, Pose, Room, Scene, Support};
use scenesmith::state::SceneState;
use serde_json::json;

fn block(id: &str, size: [f64; 3], cylinder: bool) -> Asset {
    let wood = material::material_or_default("wood");
    let mut link = LinkBuilder::new("body", Pose::IDENTITY, wood);
    if cylinder {
        link.add_cylinder([0.0, 0.0], size[0] / 2.0, 0.0, size[2], wood.color)
            .unwrap();
    } else {
        link.add_box([0.0, 0.0, size[2] / 2.0], size, wood.color)
            .unwrap();
    }
    Asset {
        id: id.into(),
        category: "block".into(),
        material: "wood".into(),
        links: vec![link.finish().unwrap()],
        joints: vec![],
        surfaces: vec![],
        is_static: false,
        provenance: json!({}),
    }
}

fn scene_with(pairs: &[(Pose, Pose, bool)]) -> SceneState {
    let mut scene = Scene::new("penetration test", 0, "pen_test");
    scene.rooms.push(Room {
        id: "room_0".into(),
        room_type: "room".into(),
        label: None,
        prompt: String::new(),
        floor_polygon: vec![[0.0, 0.0], [10.0, 0.0], [10.0, 10.0], [0.0, 10.0]],
        wall_height: 2.5,
        walls: vec![],
        floor_material: "oak".into(),
        wall_material: "plaster".into(),
    });
    let mut state = SceneState::new(scene);
    let cube = state.insert_asset(block("cube_a", [0.2, 0.2, 0.2], false));
    let cyl = state.insert_asset(block("cyl_a", [0.16, 0.16, 0.3], true));
    for (a, b, use_cylinder) in pairs {
        state.add_object(
            "block",
            ObjectKind::Manipuland,
            "room_0",
            &cube,
            *a,
            Support::World,
        );
        let asset = if *use_cylinder { &cyl } else { &cube };
        state.add_object(
            "block",
            ObjectKind::Manipuland,
            "room_0",
            asset,
            *b,
            Support::World,
        );
    }
    state
}

#[test]
fn parry_and_drake_agree_on_depth() {
    // Pairs far apart from each other (3 m spacing), each overlapping by a known amount.
    let cases = [
        // Face-to-face, 5 mm overlap along x.
        (
            Pose::from_xyz(1.0, 1.0, 0.0),
            Pose::from_xyz(1.195, 1.0, 0.0),
            false,
        ),
        // Rotated 30 degrees about z, corner pushed into a face.
        (
            Pose::from_xyz(4.0, 1.0, 0.0),
            Pose::from_xyz_yaw(4.23, 1.0, 0.0, 30f64.to_radians()),
            false,
        ),
        // Tilted cube resting into another one from above (edge-face contact).
        (
            Pose::from_xyz(7.0, 1.0, 0.0),
            Pose::from_xyz_rpy([7.0, 1.0, 0.19], [0.0, 45f64.to_radians(), 0.0]),
            false,
        ),
        // Cylinder (16-sided prism) overlapping a cube by 12 mm.
        (
            Pose::from_xyz(1.0, 5.0, 0.0),
            Pose::from_xyz(1.168, 5.0, 0.0),
            true,
        ),
    ];
    let state = scene_with(&cases);
    let objects = posed_objects(&state.scene, &state.assets).unwrap();
    let rust: BTreeMap<(String, String), f64> = penetrating_pairs(&objects, 0.0)
        .into_iter()
        .map(|p| ((p.a, p.b), p.depth))
        .collect();
    assert_eq!(
        rust.len(),
        cases.len(),
        "each case is one penetrating pair: {rust:?}"
    );
    let face = rust[&("block_0".to_string(), "block_1".to_string())];
    assert!((face - 0.005).abs() < 1e-6, "face-to-face depth {face}");

    let dir = tempfile::tempdir().unwrap();
    write_scene_dir(dir.path(), &state).unwrap();
    let mut bridge = Bridge::from_env().unwrap();
    let reply = bridge
        .call::<Penetrations>(&PenetrationsArgs {
            scene: SceneFiles::new(
                dir.path().join("scene.dmd.yaml"),
                dir.path().join("package.xml"),
            ),
            poses: None,
            threshold: None,
        })
        .unwrap();
    let drake: BTreeMap<(String, String), f64> = reply
        .pairs
        .into_iter()
        .map(|p| ((p.a, p.b), p.depth))
        .collect();
    assert_eq!(drake.len(), rust.len(), "drake {drake:?} vs rust {rust:?}");
    for (pair, d_rust) in &rust {
        let d_drake = drake[pair];
        assert!(
            (d_rust - d_drake).abs() <= 0.5e-3,
            "{pair:?}: parry {:.3} mm, drake {:.3} mm",
            d_rust * 1e3,
            d_drake * 1e3
        );
    }
}
