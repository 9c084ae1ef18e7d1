//! Helpers shared by the export tests: scenes with joints of every kind and sign, and bridge
//! shortcuts.
#![allow(dead_code)]

use std::collections::BTreeMap;
use std::path::Path;

use scenesmith::assets::{Asset, Joint, JointKind, LinkBuilder, material};
use scenesmith::export::{ExportSet, write_exports};
use scenesmith::formats::scene_dir::write_scene_dir;
use scenesmith::physics::Bridge;
use scenesmith::physics::protocol::{
    Load, LoadReply, MujocoCheck, MujocoCheckArgs, MujocoCheckReply, SceneFiles, UsdCheck,
    UsdCheckArgs, UsdCheckReply,
};
use scenesmith::pipeline::build_scene;
use scenesmith::scene::{ObjectKind, Pose, SceneObject, Support};
use scenesmith::state::SceneState;
use serde_json::json;

/// A test asset with a drawer sliding along -Y (limits [-0.25, 0]: opening is negative) and a
/// right-hinged door turning about -Z (limits [0, 1.5]).
pub fn drawer_and_door_asset() -> Asset {
    let wood = material::material_or_default("wood");
    let steel = material::material_or_default("steel");
    let mut body = LinkBuilder::new("body", Pose::IDENTITY, wood);
    body.add_box([0.0, 0.0, 0.3], [0.4, 0.4, 0.6], wood.color)
        .unwrap();
    let mut drawer = LinkBuilder::new("drawer", Pose::from_xyz(0.0, 0.21, 0.45), wood);
    drawer
        .add_box([0.0, 0.0, 0.0], [0.3, 0.02, 0.1], wood.color)
        .unwrap();
    let mut door = LinkBuilder::new("right_door", Pose::from_xyz(0.2, 0.21, 0.2), steel);
    door.add_box([-0.1, 0.0, 0.0], [0.19, 0.02, 0.25], steel.color)
        .unwrap();
    let asset = Asset {
        id: "drawer_box_test".into(),
        category: "drawer box".into(),
        material: "wood".into(),
        links: vec![
            body.finish().unwrap(),
            drawer.finish().unwrap(),
            door.finish().unwrap(),
        ],
        joints: vec![
            Joint {
                name: "drawer_slide".into(),
                kind: JointKind::Prismatic,
                parent: "body".into(),
                child: "drawer".into(),
                axis: [0.0, -1.0, 0.0],
                lower: -0.25,
                upper: 0.0,
                damping: 2.0,
                effort: 50.0,
            },
            Joint {
                name: "door_hinge".into(),
                kind: JointKind::Revolute,
                parent: "body".into(),
                child: "right_door".into(),
                axis: [0.0, 0.0, -1.0],
                lower: 0.0,
                upper: 1.5,
                damping: 0.3,
                effort: 10.0,
            },
        ],
        surfaces: vec![],
        is_static: false,
        provenance: json!({"generator": "test"}),
    };
    asset.validate().unwrap();
    asset
}

/// A bedroom with the starter cabinet (free, door closed), plus outside the room: a welded
/// copy of that cabinet with its door 0.6 rad open, and a welded drawer box with its drawer
/// 0.1 m out and its right door 0.3 rad open.
pub fn articulated_state() -> SceneState {
    let (mut state, _) = build_scene(
        "A bedroom with a cabinet",
        3,
        "export_joints",
        &scenesmith::agents::Backend::Builtin,
    )
    .unwrap();
    let cabinet = state
        .scene
        .objects
        .iter()
        .find(|o| o.category == "cabinet")
        .cloned()
        .expect("the starter plans a cabinet");
    let room = cabinet.room.clone();
    let mut welded = cabinet.clone();
    welded.id = "cabinet_welded".into();
    welded.welded = true;
    welded.world_from_object = Pose::from_xyz_yaw(-3.0, 1.0, 0.0, 0.4);
    welded.support = Support::World;
    welded.joint_positions = BTreeMap::from([("door_hinge".to_string(), 0.6)]);
    state.scene.objects.push(welded);

    let asset_id = state.insert_asset(drawer_and_door_asset());
    state.scene.objects.push(SceneObject {
        id: "drawer_box_0".into(),
        category: "drawer box".into(),
        name: None,
        planned: None,
        kind: ObjectKind::Furniture,
        room,
        asset: asset_id,
        world_from_object: Pose::from_xyz_yaw(-3.0, -1.0, 0.0, -0.7),
        support: Support::World,
        welded: true,
        joint_positions: BTreeMap::from([
            ("drawer_slide".to_string(), -0.1),
            ("door_hinge".to_string(), 0.3),
        ]),
    });
    state.scene.validate().unwrap();
    state
}

/// Writes the scene directory and every export.
pub fn write_all(dir: &Path, state: &SceneState) {
    write_scene_dir(dir, state).unwrap();
    write_exports(dir, state, &ExportSet::all()).unwrap();
}

/// `mujoco_check` on the scene's MJCF, pushing each joint in `probe` with a constant force.
pub fn mujoco(
    bridge: &mut Bridge,
    dir: &Path,
    seconds: f64,
    probe: &[(&str, f64)],
) -> MujocoCheckReply {
    let probe_joints = probe.iter().map(|(j, f)| (j.to_string(), *f)).collect();
    bridge
        .call::<MujocoCheck>(&MujocoCheckArgs {
            xml: dir.join("export/mujoco/scene.xml"),
            seconds,
            probe_joints,
        })
        .unwrap()
}

/// `usd_check` on the scene's USD stage.
pub fn usd(bridge: &mut Bridge, dir: &Path) -> UsdCheckReply {
    bridge
        .call::<UsdCheck>(&UsdCheckArgs {
            usd: dir.join("export/usd/scene.usda"),
            static_prims: Vec::new(),
        })
        .unwrap()
}

/// Drake's `load` of the scene directives.
pub fn drake(bridge: &mut Bridge, dir: &Path) -> LoadReply {
    bridge
        .call::<Load>(&SceneFiles::new(
            dir.join("scene.dmd.yaml"),
            dir.join("package.xml"),
        ))
        .unwrap()
}
