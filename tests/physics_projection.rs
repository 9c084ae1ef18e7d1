//! Non-penetration projection, native and Drake, on hand-built scenes: deep overlaps are
//! resolved, orientations kept, objects that did not penetrate stay put, the options hold,
//! and the two paths agree.

mod physics_util;

use std::collections::{BTreeMap, BTreeSet};

use physics_util::*;
use scenesmith::formats::scene_dir::write_scene_dir;
use scenesmith::physics::drake_projection::{DrakeProjectionOptions, project_drake};
use scenesmith::physics::projection::{
    Movable, ProjectionOptions, ProjectionStatus, XyRegion, apply_offsets, project_objects,
};
use scenesmith::scene::{ObjectKind, Pose};
use scenesmith::state::SceneState;

fn free_and_fixed(state: &SceneState) -> (Vec<String>, Vec<String>) {
    let (free, fixed): (Vec<_>, Vec<_>) = state
        .scene
        .objects
        .iter()
        .partition(|o| o.kind != ObjectKind::Architecture);
    (
        free.into_iter().map(|o| o.id.clone()).collect(),
        fixed.into_iter().map(|o| o.id.clone()).collect(),
    )
}

/// Seven blocks: five piled into each other (depths up to 5 cm), two well apart.
fn pile() -> (SceneState, Vec<String>) {
    let mut s = room(3.0, 3.0);
    let cube = block("cube", Shape::Box([0.1, 0.1, 0.1]), "wood");
    let cyl = block("cyl", Shape::Cylinder(0.05, 0.1), "ceramic");
    let blob = block("blob", Shape::Blob([0.06, 0.05, 0.05], 7), "plastic");
    let mut ids = Vec::new();
    for (asset, x, y, yaw) in [
        (&cube, 1.00, 1.00, 0.0),
        (&cyl, 1.06, 1.01, 0.0),
        (&blob, 1.02, 1.07, 0.7),
        (&cube, 1.05, 1.05, 0.4),
        (&cube, 0.96, 1.04, 1.1),
    ] {
        ids.push(place(
            &mut s,
            asset,
            ObjectKind::Manipuland,
            Pose::from_xyz_yaw(x, y, 0.0, yaw),
            floor(),
        ));
    }
    for (x, y) in [(2.0, 2.0), (0.5, 2.2)] {
        ids.push(place(
            &mut s,
            &cube,
            ObjectKind::Manipuland,
            Pose::from_xyz_yaw(x, y, 0.0, 0.3),
            floor(),
        ));
    }
    (s, ids)
}

#[test]
fn native_projection_resolves_a_deep_pile_and_leaves_the_rest() {
    let (mut state, ids) = pile();
    assert!(max_penetration(&state) > 0.04);
    let before = state.scene.clone();
    let (free, fixed) = free_and_fixed(&state);
    let (offsets, report) =
        project_objects(&state, &free, &fixed, &ProjectionOptions::default()).unwrap();
    assert_eq!(report.status, ProjectionStatus::Converged, "{report:?}");
    apply_offsets(&mut state, &offsets);
    assert!(
        max_penetration(&state) <= 1e-4,
        "{}",
        max_penetration(&state)
    );
    for o in &state.scene.objects {
        let b = before.object(&o.id).unwrap();
        assert!(
            o.world_from_object.angle_to(&b.world_from_object) < 1e-12,
            "{} turned",
            o.id
        );
        // Nothing below the floor.
        assert!(
            o.world_from_object.translation().z >= -1e-9,
            "{} sank",
            o.id
        );
    }
    for far in &ids[5..] {
        let (a, b) = (
            state.scene.object(far).unwrap(),
            before.object(far).unwrap(),
        );
        let moved = (a.world_from_object.translation() - b.world_from_object.translation()).norm();
        assert!(moved <= 1e-4, "{far} moved {moved} m");
    }
    assert!(report.max_displacement_m < 0.2, "{report:?}");
}

#[test]
fn native_projection_options_hold() {
    let (state, ids) = pile();
    let (free, fixed) = free_and_fixed(&state);
    // xy_only: everything slides, nothing rises.
    let xy = ProjectionOptions {
        xy_only: true,
        ..ProjectionOptions::default()
    };
    let (offsets, report) = project_objects(&state, &free, &fixed, &xy).unwrap();
    assert_eq!(report.status, ProjectionStatus::Converged, "{report:?}");
    assert!(offsets.values().all(|d| d.z.abs() < 1e-12));
    let mut moved = state.clone();
    apply_offsets(&mut moved, &offsets);
    assert!(max_penetration(&moved) <= 1e-4);

    // A subset: only the last two pile members may move; the others stay exactly.
    let only: BTreeSet<String> = ids[3..5].iter().cloned().collect();
    let sub = ProjectionOptions {
        movable: Movable::Only(only.clone()),
        ..ProjectionOptions::default()
    };
    let (offsets, _) = project_objects(&state, &free, &fixed, &sub).unwrap();
    assert!(offsets.keys().all(|k| only.contains(k)), "{offsets:?}");

    // A region: the first cube's origin must stay left of x = 1.0 (it starts on the line).
    let mut regions = BTreeMap::new();
    regions.insert(
        ids[0].clone(),
        XyRegion {
            halfplanes: vec![[1.0, 0.0, 1.0]],
        },
    );
    let reg = ProjectionOptions {
        regions,
        ..ProjectionOptions::default()
    };
    let (offsets, report) = project_objects(&state, &free, &fixed, &reg).unwrap();
    assert_eq!(report.status, ProjectionStatus::Converged);
    let x = 1.0 + offsets.get(&ids[0]).map(|d| d.x).unwrap_or(0.0);
    assert!(x <= 1.0 + 1e-6, "region broken: x = {x}");
}

#[test]
fn xy_only_slides_a_chair_out_from_under_a_table() {
    // A vertical penetration normal (seat under the top) would never slide the chair out.
    let mut state = room(4.0, 4.0);
    let table = state
        .build_asset(&scenesmith::assets::procedural::AssetRequest::new(
            "table", 1,
        ))
        .unwrap();
    let chair = state
        .build_asset(&scenesmith::assets::procedural::AssetRequest::new(
            "chair", 1,
        ))
        .unwrap();
    let t = state.add_object(
        "table",
        ObjectKind::Furniture,
        "room_0",
        &table,
        Pose::from_xyz_yaw(2.0, 2.0, 0.0, 0.0),
        floor(),
    );
    let c = state.add_object(
        "chair",
        ObjectKind::Furniture,
        "room_0",
        &chair,
        Pose::from_xyz_yaw(2.1, 2.05, 0.0, 0.0),
        floor(),
    );
    let opts = ProjectionOptions {
        xy_only: true,
        ..ProjectionOptions::default()
    };
    let fixed = vec!["room_0_architecture".to_string()];
    let (offsets, report) = project_objects(&state, &[t, c], &fixed, &opts).unwrap();
    assert_eq!(report.status, ProjectionStatus::Converged, "{report:?}");
    apply_offsets(&mut state, &offsets);
    assert!(max_penetration(&state) <= 1e-4);
}

#[test]
fn drake_and_native_projection_agree_on_the_same_pile() {
    let (state, _) = pile();
    let dir = tempfile::tempdir().unwrap();
    write_scene_dir(dir.path(), &state).unwrap();
    let pool = pool(1);
    let drake = project_drake(
        &pool,
        &dir.path().join("scene.dmd.yaml"),
        &dir.path().join("package.xml"),
        &DrakeProjectionOptions::default(),
    )
    .unwrap();
    assert!(drake.max_penetration_m <= 1e-4, "{drake:?}");
    assert_eq!(drake.solver, "snopt", "{:?}", drake.attempts);

    // Apply Drake's poses and measure with parry: the reference is collision-free here too.
    let mut by_drake = state.clone();
    for o in &mut by_drake.scene.objects {
        if let Some(p) = drake.poses.get(&o.id).and_then(|b| b.get("body")) {
            o.world_from_object = *p;
        }
    }
    assert!(
        max_penetration(&by_drake) <= 2e-4,
        "{}",
        max_penetration(&by_drake)
    );

    let (free, fixed) = free_and_fixed(&state);
    let (_, native) =
        project_objects(&state, &free, &fixed, &ProjectionOptions::default()).unwrap();
    eprintln!(
        "native {native:?}\ndrake {} {} {} {:?}",
        drake.mean_displacement_m, drake.max_penetration_m, drake.wall_s, drake.attempts
    );
    // Same problem, same objective: the native answer moves things about as far as Drake's.
    assert!(
        native.mean_displacement_m <= 1.25 * drake.mean_displacement_m + 0.005,
        "native {} vs drake {}",
        native.mean_displacement_m,
        drake.mean_displacement_m
    );
    assert!(native.max_penetration_m <= 1e-4);
}

#[test]
fn nearly_coincident_identical_boxes_are_separated() {
    // Deep overlaps of identical boxes are where an EPA-based depth goes wrong; the projection
    // uses the exact separating-axis depth for overlapping pieces.
    let mut state = room(3.0, 3.0);
    let cube = block("cube", Shape::Box([0.2, 0.2, 0.2]), "wood");
    for (x, y, yaw) in [
        (1.0, 1.0, 0.0),
        (1.01, 1.005, 0.0),
        (1.0, 1.0, 0.3),
        (1.02, 0.99, 0.0),
    ] {
        place(
            &mut state,
            &cube,
            ObjectKind::Furniture,
            Pose::from_xyz_yaw(x, y, 0.0, yaw),
            floor(),
        );
    }
    assert!(max_penetration(&state) > 0.15);
    let (free, fixed) = free_and_fixed(&state);
    for xy_only in [false, true] {
        let opts = ProjectionOptions {
            xy_only,
            ..ProjectionOptions::default()
        };
        let (offsets, report) = project_objects(&state, &free, &fixed, &opts).unwrap();
        assert_eq!(report.status, ProjectionStatus::Converged, "{report:?}");
        let mut s = state.clone();
        apply_offsets(&mut s, &offsets);
        assert!(
            max_penetration(&s) <= 1e-4,
            "xy_only {xy_only}: {}",
            max_penetration(&s)
        );
    }
}
