//! The architecture of a generated house in Drake: it loads (one static model per room, every
//! shared wall built once), and a sphere dropped over each room lands on that room's floor.

use scenesmith::agents::Backend;
use scenesmith::agents::RunLog;
use scenesmith::formats::scene_dir::write_scene_dir;
use scenesmith::geometry::polygon;
use scenesmith::layout::stage::run_layout;
use scenesmith::physics::Bridge;
use scenesmith::physics::protocol::{DropSpheres, DropSpheresArgs, Load, SceneFiles, SphereDrop};
use scenesmith::scene::Scene;
use scenesmith::state::SceneState;
use scenesmith::state::install_rooms;

const HOUSE: &str = "A large family home with a master bedroom, two kids bedrooms, a living \
    room, a kitchen, a dining room, a hallway, and two bathrooms. The kitchen is open to the \
    dining room.";

#[test]
fn house_architecture_loads_and_floors_catch_spheres() {
    let out = run_layout(HOUSE, 5, &Backend::Builtin, &mut RunLog::default()).unwrap();
    assert!(out.validation.ok, "{:?}", out.validation.errors);
    assert_eq!(out.rooms.len(), 9);
    let mut state = SceneState::new(Scene::new(HOUSE, 5, "layout_drake"));
    install_rooms(&mut state, &out.rooms).unwrap();
    let dir = tempfile::tempdir().unwrap();
    write_scene_dir(dir.path(), &state).unwrap();
    let files = SceneFiles::new(
        dir.path().join("scene.dmd.yaml"),
        dir.path().join("package.xml"),
    );
    let mut bridge = Bridge::from_env().unwrap();
    let loaded = bridge.call::<Load>(&files).unwrap();
    let instances = &loaded.model_instances;
    assert_eq!(instances.len(), 9, "one architecture model per room");
    assert!(instances.iter().all(|m| m.welded));

    // The open connection between kitchen and dining room has no wall in it.
    let open = out
        .rooms
        .iter()
        .flat_map(|r| &r.walls)
        .flat_map(|w| &w.openings)
        .filter(|o| o.kind == scenesmith::scene::OpeningKind::Open)
        .count();
    assert!(open >= 2, "seen from both rooms");

    // A sphere over the middle of every room lands on its floor (top at z = 0) and stays in
    // the room.
    let radius = 0.1;
    let spheres: Vec<SphereDrop> = out
        .rooms
        .iter()
        .map(|r| {
            let (lo, hi) = polygon::bounds(&r.floor_polygon);
            SphereDrop {
                name: format!("ball_{}", r.id),
                xyz: [(lo[0] + hi[0]) / 2.0, (lo[1] + hi[1]) / 2.0, 1.0],
                radius,
            }
        })
        .collect();
    let result = bridge
        .call::<DropSpheres>(&DropSpheresArgs {
            scene: files,
            spheres,
            duration: 1.5,
        })
        .unwrap();
    for (room, s) in out.rooms.iter().zip(&result.spheres) {
        let xyz = s.xyz;
        assert!(
            (xyz[2] - radius).abs() < 5e-3,
            "{}: the sphere ended at z = {}",
            room.id,
            xyz[2]
        );
        assert!(
            polygon::contains(&room.floor_polygon, [xyz[0], xyz[1]]),
            "{}: the sphere left the room",
            room.id
        );
        assert!(s.speed < 0.05, "{}: still moving", room.id);
    }
}
