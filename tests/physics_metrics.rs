//! Scene metrics on hand-built scenes with known answers, and `scenesmith eval` / `generate`
//! writing `metrics.json`.

mod common;
mod physics_util;

use common::{dev_prompt, scenesmith, text};
use physics_util::*;
use scenesmith::eval::{EvalOptions, evaluate, evaluate_dir};
use scenesmith::formats::scene_dir::write_scene_dir;
use scenesmith::scene::{ObjectKind, Pose};

fn no_stb() -> EvalOptions {
    EvalOptions {
        stability: None,
        ..EvalOptions::default()
    }
}

#[test]
fn col_counts_a_known_penetration() {
    let mut state = room(3.0, 3.0);
    let cube = block("cube", Shape::Box([0.2, 0.2, 0.2]), "wood");
    place(
        &mut state,
        &cube,
        ObjectKind::Furniture,
        Pose::from_xyz(1.0, 1.0, 0.0),
        floor(),
    );
    // 5 mm into the first cube along x.
    place(
        &mut state,
        &cube,
        ObjectKind::Furniture,
        Pose::from_xyz(1.195, 1.0, 0.0),
        floor(),
    );
    place(
        &mut state,
        &cube,
        ObjectKind::Furniture,
        Pose::from_xyz(2.0, 2.0, 0.0),
        floor(),
    );
    // 3 mm into the west wall (inner face at x = 0).
    place(
        &mut state,
        &cube,
        ObjectKind::Furniture,
        Pose::from_xyz(0.097, 2.0, 0.5),
        floor(),
    );
    let m = evaluate(&state, None, &no_stb()).unwrap();
    assert_eq!(m.col.objects, 4);
    assert_eq!(m.col.colliding, vec!["block_0", "block_1", "block_3"]);
    assert!((m.col.percent - 75.0).abs() < 1e-9);
    assert!((m.col.max_depth_mm - 5.0).abs() < 0.05, "{:?}", m.col);
    assert!((m.col.mean_depth_mm - 4.0).abs() < 0.05, "{:?}", m.col);
    assert_eq!(m.counts.total, 4);
    assert_eq!(m.counts.per_kind["furniture"], 4);
    assert!(m.stb.is_none());
}

#[test]
fn nav_sees_a_room_cut_in_two_and_oob_sees_an_object_through_the_wall() {
    let mut state = room(4.0, 3.0);
    let open = evaluate(&state, None, &no_stb()).unwrap();
    assert!((open.nav.ratio - 1.0).abs() < 1e-9);
    let free = open.nav.rooms[0].free_area_m2;
    // Eroded by 0.25 m: (4 - 0.5) x (3 - 0.5).
    assert!((free - 3.5 * 2.5).abs() < 0.01, "{free}");

    // A wall of cabinets across the room at x = 1.5 splits the floor 1.5 : 2.5 (minus margins).
    let cabinet = block("cabinet", Shape::Box([0.3, 0.5, 0.9]), "mdf");
    for i in 0..6 {
        place(
            &mut state,
            &cabinet,
            ObjectKind::Furniture,
            Pose::from_xyz(1.5, 0.25 + 0.5 * i as f64, 0.0),
            floor(),
        );
    }
    let cut = evaluate(&state, None, &no_stb()).unwrap();
    let room = &cut.nav.rooms[0];
    assert_eq!(room.regions, 2, "{room:?}");
    // Left part x in [0.25, 1.1], right part [1.9, 3.75]; both 2.5 m deep.
    let (left, right) = (0.85 * 2.5, 1.85 * 2.5);
    assert!((room.largest_region_m2 - right).abs() < 0.02, "{room:?}");
    assert!(
        (cut.nav.ratio - right / (left + right)).abs() < 0.01,
        "{:?}",
        cut.nav
    );
    assert!(cut.nav.ratio < 1.0);
    assert_eq!(cut.oob.outside.len(), 0);

    // Half of a cube beyond the east wall.
    let cube = block("cube", Shape::Box([0.2, 0.2, 0.2]), "wood");
    let out = place(
        &mut state,
        &cube,
        ObjectKind::Furniture,
        Pose::from_xyz(4.0, 1.5, 0.0),
        floor(),
    );
    let m = evaluate(&state, None, &no_stb()).unwrap();
    assert_eq!(m.oob.outside, vec![out]);
    assert!((m.oob.percent - 100.0 / 7.0).abs() < 1e-9);
}

#[test]
fn stb_flags_the_object_that_falls_and_plan_coverage_counts() {
    let mut state = room(3.0, 3.0);
    state.scene.provenance.prompt = "A room with two blocks and a table, but no chair.".into();
    let cube = block("cube", Shape::Box([0.1, 0.1, 0.1]), "wood");
    place(
        &mut state,
        &cube,
        ObjectKind::Manipuland,
        Pose::from_xyz(1.0, 1.0, 0.0),
        floor(),
    );
    place(
        &mut state,
        &cube,
        ObjectKind::Manipuland,
        Pose::from_xyz(1.5, 1.0, 0.0),
        floor(),
    );
    // A stick standing on one edge, leaning 26 degrees: it falls over.
    let stick = block("stick", Shape::Box([0.04, 0.04, 0.5]), "wood");
    let fallen = place(
        &mut state,
        &stick,
        ObjectKind::Manipuland,
        Pose::from_xyz_rpy([2.0, 2.0, 0.0091], [0.45, 0.0, 0.0]),
        floor(),
    );
    let dir = tempfile::tempdir().unwrap();
    write_scene_dir(dir.path(), &state).unwrap();
    let pool = pool(1);
    let m = evaluate_dir(dir.path(), Some(&pool), &EvalOptions::default()).unwrap();
    let stb = m.stb.as_ref().expect("simulated");
    assert_eq!(stb.free_objects, 3);
    assert_eq!(stb.stable, 2, "{stb:?}");
    assert_eq!(stb.unstable.len(), 1);
    assert_eq!(stb.unstable[0].id, fallen);
    assert!(stb.unstable[0].rotation_rad > 1.0, "{stb:?}");
    assert!(stb.xd_m > 0.01, "{stb:?}");
    assert!((stb.percent - 200.0 / 3.0).abs() < 1e-9);

    // "two blocks" is not a category the reader knows; "a table" and "no chair" are.
    let req: Vec<(&str, &str, u32, bool)> = m
        .plan_coverage
        .requirements
        .iter()
        .map(|r| (r.category.as_str(), r.kind.as_str(), r.present, r.satisfied))
        .collect();
    assert!(req.contains(&("table", "exactly", 0, false)), "{req:?}");
    assert!(req.contains(&("chair", "none", 0, true)), "{req:?}");
}

#[test]
fn eval_writes_metrics_and_generate_writes_them_too() {
    let root = tempfile::tempdir().unwrap();
    let out = root.path().join("scene");
    let prompt = dev_prompt("object_density_07");
    let g = scenesmith(
        &[
            "generate",
            &prompt,
            "--out",
            out.to_str().unwrap(),
            "--json",
        ],
        &[],
    );
    assert!(g.status.success(), "{}", text(&g));
    let summary: serde_json::Value = serde_json::from_slice(&g.stdout).unwrap();
    let written: serde_json::Value =
        serde_json::from_slice(&std::fs::read(out.join("metrics.json")).unwrap()).unwrap();
    assert_eq!(summary["metrics"], written);
    assert_eq!(written["col"]["percent"], 0.0);
    assert_eq!(written["stb"]["percent"], 100.0, "{}", written["stb"]);
    assert!(
        summary["post_process"]["manipuland"]["settle"]
            .as_array()
            .is_some()
    );

    std::fs::remove_file(out.join("metrics.json")).unwrap();
    let e = scenesmith(&["eval", out.to_str().unwrap(), "--no-stb"], &[]);
    assert!(e.status.success(), "{}", text(&e));
    let table = String::from_utf8_lossy(&e.stderr);
    for row in ["COL", "STB", "NAV", "OOB", "plan"] {
        assert!(table.contains(row), "{table}");
    }
    let again: serde_json::Value =
        serde_json::from_slice(&std::fs::read(out.join("metrics.json")).unwrap()).unwrap();
    assert_eq!(again["col"], written["col"]);
    assert!(again["stb"].is_null());

    let bad = scenesmith(
        &["eval", root.path().join("nothing").to_str().unwrap()],
        &[],
    );
    assert_eq!(bad.status.code(), Some(1));
    assert!(
        String::from_utf8_lossy(&bad.stderr).contains("scene.json"),
        "{}",
        text(&bad)
    );
}
