//! `scripts/ray_batch.py`: the batch layout produced by Ray tasks on a local two-CPU Ray
//! instance (`ray.init(num_cpus=2)`), one `scenesmith batch --only <id>` per task; a second run
//! submits nothing.

mod common;

use std::process::Command;

use common::{home, python, text};

#[test]
fn ray_runs_a_batch_with_the_same_layout_and_resumes() {
    let root = tempfile::tempdir().unwrap();
    let prompts = root.path().join("prompts.jsonl");
    std::fs::write(
        &prompts,
        concat!(
            "{\"id\": \"den\", \"prompt\": \"a den with a sofa and a coffee table\"}\n",
            "{\"id\": \"bath\", \"prompt\": \"a bathroom with a toilet and a sink\", \"seed\": 5}\n",
        ),
    )
    .unwrap();
    let out = root.path().join("out");
    let run = || {
        Command::new(python())
            .arg(home().join("scripts/ray_batch.py"))
            .arg(&prompts)
            .args(["--out", out.to_str().unwrap(), "--workers", "2", "--"])
            .args(["--no-stb", "--no-render", "--export", "none"])
            .env("SCENESMITH_BIN", env!("CARGO_BIN_EXE_scenesmith"))
            .env("SCENESMITH_HOME", home())
            // Keep Ray's session files inside the test's directory.
            .env("RAY_TMPDIR", root.path())
            .output()
            .expect("ray_batch.py runs")
    };
    let r = run();
    assert!(r.status.success(), "{}", text(&r));
    assert!(text(&r).contains("2 scene(s) to run"), "{}", text(&r));
    assert!(text(&r).contains("2 of 2 scene(s) ok"), "{}", text(&r));
    let summary = std::fs::read_to_string(out.join("summary.jsonl")).unwrap();
    let rows: Vec<serde_json::Value> = summary
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    assert_eq!(rows.len(), 2);
    for (row, id) in rows.iter().zip(["den", "bath"]) {
        assert_eq!(row["id"], id);
        assert_eq!(row["status"], "ok", "{row}");
        assert!(out.join(id).join("scene.dmd.yaml").is_file());
        assert!(out.join("results").join(format!("{id}.json")).is_file());
    }
    assert_eq!(rows[1]["seed"], 5);
    let r = run();
    assert!(r.status.success(), "{}", text(&r));
    assert!(text(&r).contains("0 scene(s) to run"), "{}", text(&r));
}
