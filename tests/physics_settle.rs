//! Gravity settling through the bridge pool, fallen-object removal, and the pool surviving a
//! killed worker.

mod physics_util;

use std::time::Duration;

use physics_util::*;
use scenesmith::assets::procedural::AssetRequest;
use scenesmith::formats::scene_dir::write_scene_dir;
use scenesmith::physics::as_written::posed_objects;
use scenesmith::physics::collision::penetrating_pairs;
use scenesmith::physics::postprocess::{
    PostProcessOptions, post_process, post_process_placing_again,
};
use scenesmith::physics::protocol::Simulate;
use scenesmith::physics::removal::tilt;
use scenesmith::physics::settle::{SettleOptions, simulate_args};
use scenesmith::scene::{ObjectKind, Pose};
use scenesmith::state::SceneState;

/// A room with a procedural table at (2, 2); returns the state, the table id and its top height.
fn room_with_table() -> (SceneState, String, f64) {
    let mut state = room(4.0, 4.0);
    let table = state.build_asset(&AssetRequest::new("table", 3)).unwrap();
    let top = state.scene.assets[&table].surfaces[0].center[2];
    let id = state.add_object(
        "table",
        ObjectKind::Furniture,
        "room_0",
        &table,
        Pose::from_xyz_yaw(2.0, 2.0, 0.0, 0.0),
        floor(),
    );
    (state, id, top)
}

/// Half the x extent of the table `table`.
fn table_half_x(state: &SceneState, table: &str) -> f64 {
    state.scene.assets[&state.scene.object(table).unwrap().asset].bounds[1][0]
}

/// A tall stick (0.04 x 0.04 x 0.4 m) leaning out over the +x edge of the table at (2, 2):
/// it cannot stand and topples to the floor. Returns its id.
fn leaning_stick(state: &mut SceneState, table: &str, top: f64) -> String {
    let stick = block("stick", Shape::Box([0.04, 0.04, 0.4]), "wood");
    let leaning = Pose::from_xyz_rpy(
        [2.0 + table_half_x(state, table) - 0.05, 2.0, top + 0.001],
        [0.0, 0.45, 0.0],
    );
    place(state, &stick, ObjectKind::Manipuland, leaning, on(table))
}

fn translation(state: &SceneState, id: &str) -> nalgebra::Vector3<f64> {
    state
        .scene
        .object(id)
        .unwrap()
        .world_from_object
        .translation()
}

#[test]
fn a_box_two_centimetres_above_a_table_lands_on_it() {
    let (mut state, table, top) = room_with_table();
    let cube = block("cube", Shape::Box([0.1, 0.1, 0.1]), "wood");
    let id = place(
        &mut state,
        &cube,
        ObjectKind::Manipuland,
        Pose::from_xyz_yaw(2.1, 2.0, top + 0.02, 0.3),
        on(&table),
    );
    let pool = pool(1);
    let report = post_process(&mut state, Some(&pool), &PostProcessOptions::default()).unwrap();
    assert!(state.scene.removed.is_empty(), "{:?}", state.scene.removed);
    let p = translation(&state, &id);
    assert!(
        (p.z - top).abs() < 1e-3,
        "box bottom at {} vs table top {top}",
        p.z
    );
    assert!(
        (p.x - 2.1).abs() < 2e-3 && (p.y - 2.0).abs() < 2e-3,
        "{p:?}"
    );
    let yaw = state.scene.object(&id).unwrap().world_from_object.yaw();
    assert!((yaw - 0.3).abs() < 0.01);
    assert_eq!(
        report.manipuland.settle.len(),
        1,
        "one subset: the table and its box"
    );
    assert!(report.manipuland.settle[0].at_rest);
    // The box sinks into nothing; the table, settled with its load on the compliant floor,
    // rests a fraction of a millimetre into it.
    let posed = posed_objects(&state.scene, &state.assets);
    for pair in penetrating_pairs(&posed, 0.0) {
        let limit = if pair.a == id || pair.b == id {
            1e-4
        } else {
            5e-4
        };
        assert!(pair.depth <= limit, "{pair:?}");
    }
}

#[test]
fn what_cannot_stand_falls_and_is_removed_with_a_reason() {
    let (mut state, table, top) = room_with_table();
    // A tall stick leaning out over the table's edge topples off onto the floor; a cube in the
    // middle of the table stays where it is.
    let cube = block("cube", Shape::Box([0.1, 0.1, 0.1]), "wood");
    let stick_id = leaning_stick(&mut state, &table, top);
    let cube_id = place(
        &mut state,
        &cube,
        ObjectKind::Manipuland,
        Pose::from_xyz_yaw(2.0, 2.0, top + 0.001, 0.0),
        on(&table),
    );
    // A tall narrow cabinet tilted 25 degrees falls over, and the cube on top of it with it.
    let tower = block("tower", Shape::Box([0.25, 0.25, 1.6]), "mdf");
    let tower_id = place(
        &mut state,
        &tower,
        ObjectKind::Furniture,
        Pose::from_xyz_rpy([0.8, 1.0, 0.0], [-0.45, 0.0, 0.0]),
        floor(),
    );
    let rider = place(
        &mut state,
        &cube,
        ObjectKind::Manipuland,
        Pose::from_xyz_rpy([0.8, 1.0, 0.0], [-0.45, 0.0, 0.0])
            .compose(&Pose::from_xyz(0.0, 0.0, 1.601)),
        on(&tower_id),
    );
    let table_before = translation(&state, &table);
    let cube_before = translation(&state, &cube_id);

    let pool = pool(2);
    post_process(&mut state, Some(&pool), &PostProcessOptions::default()).unwrap();

    let reason = |id: &str| {
        state
            .scene
            .removed
            .iter()
            .find(|r| r.object == id)
            .map(|r| (r.stage.clone(), r.reason.clone()))
    };
    let (stage, why) = reason(&stick_id).expect("the stick was removed");
    assert_eq!(stage, "post_process/manipuland");
    assert!(why.contains("fell off") && why.contains(&table), "{why}");
    let (stage, why) = reason(&tower_id).expect("the tower was removed");
    assert_eq!(stage, "post_process/furniture");
    assert!(why.contains("fell over"), "{why}");
    let (_, why) = reason(&rider).expect("its load went with it");
    assert!(why.contains(&tower_id), "{why}");
    for gone in [&stick_id, &tower_id, &rider] {
        assert!(state.scene.object(gone).is_none());
    }
    // The rest stay put.
    assert!((translation(&state, &table) - table_before).norm() < 3e-3);
    let cube_now = translation(&state, &cube_id);
    assert!(
        (cube_now - cube_before).norm() < 3e-3,
        "{cube_now:?} vs {cube_before:?}"
    );
    assert!(tilt(&state.scene.object(&table).unwrap().world_from_object) < 0.01);
}

#[test]
fn an_asked_for_object_that_fell_is_placed_again() {
    // The stick leaning out over the table's edge falls off; the prompt asked for two blocks
    // (both test assets are blocks), so it is stood up again at a free spot of the table,
    // where it rests.
    let (mut state, table, top) = room_with_table();
    let cube = block("cube", Shape::Box([0.1, 0.1, 0.1]), "wood");
    let stick_id = leaning_stick(&mut state, &table, top);
    let half_x = table_half_x(&state, &table);
    let cube_id = place(
        &mut state,
        &cube,
        ObjectKind::Manipuland,
        Pose::from_xyz_yaw(2.0, 2.0, top + 0.001, 0.0),
        on(&table),
    );
    let category = state.scene.object(&stick_id).unwrap().category.clone();
    let pool = pool(1);
    let report = post_process_placing_again(
        &mut state,
        Some(&pool),
        &PostProcessOptions::default(),
        &[(category.clone(), 2)],
        &scenesmith::stages::manipuland::spot_again,
    )
    .unwrap();
    assert_eq!(report.placed_again, vec![stick_id.clone()]);
    assert!(state.scene.removed.iter().all(|r| r.object != stick_id));
    let again = &state.scene.placed_again[0];
    assert_eq!(again.object, stick_id);
    assert!(again.removed_because.contains("fell off"), "{again:?}");
    assert!(again.surface.starts_with(&table), "{again:?}");
    let stood = state.scene.object(&stick_id).expect("in the scene again");
    assert!(tilt(&stood.world_from_object) < 0.05, "upright");
    let p = stood.world_from_object.translation();
    assert!(
        (p.z - top).abs() < 3e-3,
        "bottom at {} on a top at {top}",
        p.z
    );
    assert!(p.x.abs() < 2.0 + half_x, "over the table");
    // The cube it might have landed on is where it was.
    assert!((translation(&state, &cube_id) - nalgebra::Vector3::new(2.0, 2.0, top)).norm() < 5e-3);
    // Without the request it stays removed.
    let (mut plain, table2, top2) = room_with_table();
    let lost = leaning_stick(&mut plain, &table2, top2);
    let report = post_process(&mut plain, Some(&pool), &PostProcessOptions::default()).unwrap();
    assert!(report.placed_again.is_empty());
    assert!(plain.scene.object(&lost).is_none());
}

#[test]
fn what_rested_on_a_removed_object_is_settled_again() {
    // A pad on the table runs under a wall-hung box (which is not in the table's settling
    // subset, so settling leaves the overlap); a cube comes to rest on the pad's other end. The
    // pad is removed at the end for penetrating the box, and the cube must not be left hanging
    // where the pad was.
    let (mut state, table, top) = room_with_table();
    let pad = block("pad", Shape::Box([0.4, 0.3, 0.02]), "wood");
    let hung = block("hung", Shape::Box([0.1, 0.3, 0.3]), "wood");
    let cube = block("cube", Shape::Box([0.08, 0.08, 0.08]), "wood");
    let pad_id = place(
        &mut state,
        &pad,
        ObjectKind::Manipuland,
        Pose::from_xyz_yaw(2.0, 2.0, top + 0.001, 0.0),
        on(&table),
    );
    place(
        &mut state,
        &hung,
        ObjectKind::Wall,
        Pose::from_xyz_yaw(2.17, 2.0, top + 0.006, 0.0),
        floor(),
    );
    let cube_id = place(
        &mut state,
        &cube,
        ObjectKind::Manipuland,
        Pose::from_xyz_yaw(1.9, 2.0, top + 0.022, 0.0),
        on(&table),
    );
    let mut opts = PostProcessOptions::default();
    opts.projection.max_iterations = 0;
    let pool = pool(1);
    let report = post_process(&mut state, Some(&pool), &opts).unwrap();
    assert_eq!(report.removed_penetrating, vec![pad_id.clone()]);
    assert_eq!(report.resettled.len(), 1, "{:?}", report.resettled);
    let p = translation(&state, &cube_id);
    assert!(
        (p.z - top).abs() < 2e-3,
        "the cube's bottom at {} over a table top at {top}",
        p.z
    );
}

#[test]
fn a_worker_killed_during_a_settle_is_replaced_and_the_request_retried() {
    let (mut state, table, top) = room_with_table();
    let cube = block("cube", Shape::Box([0.08, 0.08, 0.08]), "wood");
    for i in 0..6 {
        place(
            &mut state,
            &cube,
            ObjectKind::Manipuland,
            Pose::from_xyz_yaw(1.6 + 0.12 * i as f64, 2.0, top + 0.01, 0.0),
            on(&table),
        );
    }
    let dir = tempfile::tempdir().unwrap();
    write_scene_dir(dir.path(), &state).unwrap();
    let pool = pool(1);
    pool.start_all().unwrap();
    let pid = pool.pids()[0].expect("worker started");
    // A fixed 3 s simulation: long enough to be killed in the middle of it.
    let opts = SettleOptions {
        max_time: 3.0,
        stop_at_rest: false,
        ..SettleOptions::default()
    };
    let args = simulate_args(
        &dir.path().join("scene.dmd.yaml"),
        &dir.path().join("package.xml"),
        &opts,
    );
    let result = std::thread::scope(|s| {
        let request = s.spawn(|| pool.call::<Simulate>(&args));
        std::thread::sleep(Duration::from_millis(800));
        let killed = std::process::Command::new("kill")
            .args(["-9", &pid.to_string()])
            .status()
            .unwrap();
        assert!(killed.success());
        request.join().unwrap()
    });
    let result = result.expect("retried on a fresh worker");
    assert!((result.sim_time - 3.0).abs() < 1e-9);
    assert_eq!(result.free_bodies, 7);
    assert_eq!(pool.restarts(), 1);
    assert_ne!(pool.pids()[0], Some(pid), "a new process serves the pool");
}
