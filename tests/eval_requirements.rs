//! `scenesmith eval DIR --requirements FILE`: a scene scored against requirements written by
//! hand, independently of the prompt reader, from `scene.json` alone (the fixture scene has no
//! assets on disk, so nothing but `scene.json` can be read).

mod common;

use std::path::{Path, PathBuf};

use common::{home, scenesmith, text};
use scenesmith::eval::requirements::{
    REQUIREMENTS_REPORT_JSON, RequirementsReport, Tally, requirements_from_value, score,
};

fn fixture(name: &str) -> PathBuf {
    home().join("tests/fixtures/eval_requirements").join(name)
}

/// A copy of the fixture scene directory, so the report is written outside the repository.
fn scene_copy(root: &Path) -> PathBuf {
    let dir = root.join("scene");
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::copy(fixture("scene/scene.json"), dir.join("scene.json")).unwrap();
    dir
}

fn eval(dir: &Path, file: &Path, json: bool) -> std::process::Output {
    let mut args = vec![
        "eval",
        dir.to_str().unwrap(),
        "--requirements",
        file.to_str().unwrap(),
    ];
    if json {
        args.push("--json");
    }
    scenesmith(&args, &[])
}

#[test]
fn the_table_the_json_and_the_report_file() {
    let root = tempfile::tempdir().unwrap();
    let dir = scene_copy(root.path());
    let file = fixture("requirements.jsonl");

    let out = eval(&dir, &file, false);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out));
    let table = String::from_utf8_lossy(&out.stderr);
    let row = |needle: &str| {
        table
            .lines()
            .find(|l| l.contains(needle))
            .unwrap_or_else(|| panic!("no row {needle:?} in\n{table}"))
            .to_string()
    };
    for (requirement, found, met) in [
        (r#"room "living room" =1"#, "1: living_room_0", "yes"),
        (r#"room "bedrooms" =1"#, "1: bedroom_0", "yes"),
        (
            r#"object "couch" =1 in room "living room""#,
            "1: sofa_0",
            "yes",
        ),
        (r#"object "television" =1"#, "1: tv_0", "yes"),
        (
            r#"object "chair" =1 in room "bedroom""#,
            "1: chair_0",
            "yes",
        ),
        (
            r#"object "books" several"#,
            "7: book_0, book_1, book_2, book_3, book_4, +2 more",
            "yes",
        ),
        (r#"absent "bed" in room "living room""#, "0", "yes"),
        (
            r#"object "dining chair" >=3"#,
            "2: dining_chair_0, dining_chair_1",
            "no",
        ),
        (r#"absent "tv""#, "1: tv_0", "no"),
        (r#"room "kitchen" >=1"#, "0", "no"),
    ] {
        let line = row(requirement);
        assert!(line.contains(found), "{line:?} lacks {found:?}");
        assert!(line.trim_end().ends_with(met), "{line:?} is not {met}");
    }
    for summary in [
        "objects  5 / 6 met (83 %), the label-based count score",
        "absents  1 / 2 met (50 %)",
        "rooms    2 / 3 met (67 %)",
        "all      8 / 11 met (73 %)",
    ] {
        assert!(table.contains(summary), "{summary:?} missing in\n{table}");
    }

    // The report file, written atomically next to scene.json; nothing else is written.
    let written: RequirementsReport = serde_json::from_slice(
        &std::fs::read(dir.join(REQUIREMENTS_REPORT_JSON)).expect("the report is written"),
    )
    .expect("the report parses");
    assert_eq!(written.rows.len(), 11);
    assert_eq!(written.summary.objects, Tally { met: 5, total: 6 });
    assert_eq!(written.summary.all, Tally { met: 8, total: 11 });
    assert_eq!(written.rows[6].ids.len(), 7, "the file lists every id");
    let mut names: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    assert_eq!(names, ["requirements_report.json", "scene.json"]);

    // --json prints the same report on stdout.
    let out = eval(&dir, &file, true);
    assert_eq!(out.status.code(), Some(0), "{}", text(&out));
    let printed: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(printed, serde_json::to_value(&written).unwrap());
    assert_eq!(
        printed["rows"][2]["requirement"],
        serde_json::json!({"object": "couch", "room": "living room", "count": "=1"})
    );
    assert_eq!(printed["rows"][2]["met"], true);
    assert_eq!(
        printed["summary"]["rooms"],
        serde_json::json!({"met": 2, "total": 3})
    );
}

#[test]
fn a_bad_requirements_file_is_a_usage_error_naming_the_line() {
    let root = tempfile::tempdir().unwrap();
    let dir = scene_copy(root.path());
    for (content, says) in [
        (
            "# ok so far\n{\"absent\": \"tv\"}\n{\"object\": \"chair\", \"count\": \"about 3\"}\n",
            "line 3: \"count\" must be",
        ),
        (
            "{\"absent\": \"tv\"}\n\n{\"object\": \"chair\", \"count\": \"=1\", \"colour\": \"red\"}\n",
            "line 3: unknown field `colour`",
        ),
        ("{\"object\": \"chair\"}\n", "line 1: \"count\" is missing"),
        ("{\"object\": \"chair\", \"count\": \"=1\"\n", "line 1: EOF"),
        ("# only a comment\n", "no requirements"),
    ] {
        let file = root.path().join("bad.jsonl");
        std::fs::write(&file, content).unwrap();
        let out = eval(&dir, &file, false);
        assert_eq!(out.status.code(), Some(2), "{content:?}: {}", text(&out));
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains(says), "{content:?}: {err}");
        assert!(!err.contains("panicked"), "{err}");
        assert!(!dir.join(REQUIREMENTS_REPORT_JSON).exists());
    }
    let missing = root.path().join("missing.jsonl");
    let out = eval(&dir, &missing, false);
    assert_eq!(out.status.code(), Some(2), "{}", text(&out));
    assert!(String::from_utf8_lossy(&out.stderr).contains("missing.jsonl"));

    // The metrics' options do not apply to the requirements score.
    let out = scenesmith(
        &[
            "eval",
            dir.to_str().unwrap(),
            "--requirements",
            fixture("requirements.jsonl").to_str().unwrap(),
            "--no-stb",
        ],
        &[],
    );
    assert_eq!(out.status.code(), Some(2), "{}", text(&out));
}

#[test]
fn an_unreadable_scene_dir_exits_1() {
    let root = tempfile::tempdir().unwrap();
    let out = eval(
        &root.path().join("nothing"),
        &fixture("requirements.jsonl"),
        false,
    );
    assert_eq!(out.status.code(), Some(1), "{}", text(&out));
    assert!(
        String::from_utf8_lossy(&out.stderr).contains("scene.json"),
        "{}",
        text(&out)
    );
    // A scene.json that does not parse is the scene's fault, not the file's.
    let dir = root.path().join("broken");
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("scene.json"), "{\"schema_version\": 1}").unwrap();
    let out = eval(&dir, &fixture("requirements.jsonl"), false);
    assert_eq!(out.status.code(), Some(1), "{}", text(&out));
}

#[test]
fn requirements_embedded_in_a_fixture_score_through_the_library() {
    let fixtures: serde_json::Value =
        serde_json::from_slice(&std::fs::read(fixture("requirements_by_prompt.json")).unwrap())
            .unwrap();
    let scene = scenesmith::formats::scene_dir::read_scene(&fixture("scene")).unwrap();
    let entry = &fixtures["prompts"][0];
    assert_eq!(entry["prompt"], scene.provenance.prompt.as_str());
    let reqs = requirements_from_value(&entry["requirements"]).unwrap();
    let report = score(&scene, &reqs);
    assert_eq!(report.summary.all, Tally { met: 4, total: 4 }, "{report:?}");
    // "chair" counts both dining chairs and the bedroom chair.
    assert_eq!(
        report.rows[2].ids,
        ["dining_chair_0", "dining_chair_1", "chair_0"]
    );
}
