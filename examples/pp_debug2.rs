#[path = "../tests/physics_util/mod.rs"]
mod physics_util;
use physics_util::*;
use scenesmith::assets::procedural::AssetRequest;
use scenesmith::physics::postprocess::{PostProcessOptions, post_process};
use scenesmith::scene::{ObjectKind, Pose};
fn main() {
    let mut state = room(4.0, 4.0);
    let table = state.build_asset(&AssetRequest::new("table", 3)).unwrap();
    let top = state.scene.assets[&table].surfaces[0].center[2];
    let t = state.add_object(
        "table",
        ObjectKind::Furniture,
        "room_0",
        &table,
        Pose::from_xyz_yaw(2.0, 2.0, 0.0, 0.0),
        floor(),
    );
    let cube = block("cube", Shape::Box([0.1, 0.1, 0.1]), "wood");
    let which = std::env::args().nth(1).unwrap_or_default();
    if which == "box" {
        place(
            &mut state,
            &cube,
            ObjectKind::Manipuland,
            Pose::from_xyz_yaw(2.1, 2.0, top + 0.02, 0.3),
            on(&t),
        );
    } else {
        let tower = block("tower", Shape::Box([0.25, 0.25, 1.6]), "mdf");
        place(
            &mut state,
            &tower,
            ObjectKind::Furniture,
            Pose::from_xyz_rpy([0.8, 1.0, 0.0], [-0.45, 0.0, 0.0]),
            floor(),
        );
    }
    if let Ok(d) = std::env::var("WRITE") {
        scenesmith::formats::scene_dir::write_scene_dir(std::path::Path::new(&d), &state).unwrap();
        return;
    }
    let pool = pool(1);
    let before = state.scene.clone();
    let r = post_process(&mut state, Some(&pool), &PostProcessOptions::default()).unwrap();
    println!("{}", serde_json::to_string_pretty(&r).unwrap());
    for o in &state.scene.objects {
        let b = before.object(&o.id).unwrap();
        println!(
            "{} {:?} -> {:?} rot {:.3}",
            o.id,
            b.world_from_object.translation().as_slice(),
            o.world_from_object.translation().as_slice(),
            o.world_from_object.angle_to(&b.world_from_object)
        );
    }
    println!("{:?}", state.scene.removed);
}
