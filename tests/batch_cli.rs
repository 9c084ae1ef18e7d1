//! `scenesmith batch`: many scenes from a JSON-lines file, two at a time, a result per scene
//! and a summary; a rerun skips what is finished and tries the failed scene again; bad files
//! exit 2 naming the line.

mod common;

use common::{json_lines, scenesmith, text};

const FAST: [&str; 5] = ["--no-stb", "--no-render", "--export", "none", "--workers"];

#[test]
fn a_batch_runs_resumes_and_reports_a_failed_scene() {
    let root = tempfile::tempdir().unwrap();
    let prompts = root.path().join("prompts.jsonl");
    std::fs::write(
        &prompts,
        concat!(
            "{\"id\": \"bath\", \"prompt\": \"a bathroom with a toilet and a sink\", \"seed\": 3}\n",
            "\n",
            "{\"prompt\": \"a small office with a desk and a chair\"}\n",
            "{\"id\": \"nonsense\", \"prompt\": \"blorptastic frumious wabe\"}\n",
        ),
    )
    .unwrap();
    let out = root.path().join("out");
    let (p, o) = (prompts.to_str().unwrap(), out.to_str().unwrap());
    let mut args = vec!["batch", p, "--out", o];
    args.extend(FAST);
    args.push("2");
    let r = scenesmith(&args, &[]);
    // One scene failed: the batch says so with its exit status, after doing the others.
    assert_eq!(r.status.code(), Some(1), "{}", text(&r));
    let summary = json_lines(&out.join("summary.jsonl"));
    let ids: Vec<&str> = summary.iter().filter_map(|s| s["id"].as_str()).collect();
    assert_eq!(ids, ["bath", "scene_001", "nonsense"], "file order");
    for s in &summary[..2] {
        assert_eq!(s["status"], "ok", "{s}");
        assert!(s["objects"].as_u64().is_some_and(|n| n >= 3), "{s}");
        assert_eq!(s["col_percent"].as_f64(), Some(0.0), "{s}");
        let dir = out.join(s["dir"].as_str().unwrap());
        assert!(dir.join("scene.dmd.yaml").is_file(), "{}", dir.display());
    }
    assert_eq!(summary[0]["seed"], 3);
    let bad = &summary[2];
    assert_eq!(bad["status"], "failed");
    // A prompt the reader refuses fails the same way every time: no second attempt.
    assert_eq!(bad["attempts"], 1, "{bad}");
    assert!(
        bad["error"].as_str().is_some_and(|e| !e.is_empty()),
        "{bad}"
    );
    let table = text(&r);
    assert!(table.contains("2 ok, 1 failed, 0 pending"), "{table}");
    assert!(table.contains("nonsense failed:"), "{table}");

    // A rerun generates nothing that finished: the finished scenes' result files are untouched.
    let stamp = |id: &str| {
        std::fs::metadata(out.join("results").join(format!("{id}.json")))
            .and_then(|m| m.modified())
            .unwrap()
    };
    let before = (stamp("bath"), stamp("scene_001"));
    let r = scenesmith(&args, &[]);
    assert_eq!(r.status.code(), Some(1), "{}", text(&r));
    assert!(text(&r).contains("1 generated, 2 skipped"), "{}", text(&r));
    assert_eq!(before, (stamp("bath"), stamp("scene_001")));

    // --summary-only reads the results back; --only runs one scene.
    let r = scenesmith(&["batch", p, "--out", o, "--summary-only"], &[]);
    assert!(text(&r).contains("2 ok, 1 failed"), "{}", text(&r));
    let r = scenesmith(&["batch", p, "--out", o, "--only", "bath"], &[]);
    assert!(r.status.success(), "{}", text(&r));
    assert!(text(&r).contains("0 generated, 1 skipped"), "{}", text(&r));
}

#[test]
fn bad_prompt_files_exit_2_naming_the_line() {
    let root = tempfile::tempdir().unwrap();
    let out = root.path().join("out");
    for (body, says) in [
        (
            "{\"prompt\": \"a den\"}\n{\"prompt\": 3}\n",
            "prompts.jsonl:2:",
        ),
        (
            "{\"id\": \"../up\", \"prompt\": \"a den\"}\n",
            "directory name",
        ),
        ("\n", "holds no prompts"),
    ] {
        let prompts = root.path().join("prompts.jsonl");
        std::fs::write(&prompts, body).unwrap();
        let r = scenesmith(
            &[
                "batch",
                prompts.to_str().unwrap(),
                "--out",
                out.to_str().unwrap(),
            ],
            &[],
        );
        assert_eq!(r.status.code(), Some(2), "{body:?}: {}", text(&r));
        assert!(text(&r).contains(says), "{body:?}: {}", text(&r));
    }
    let r = scenesmith(
        &[
            "batch",
            "/nonexistent/p.jsonl",
            "--out",
            out.to_str().unwrap(),
        ],
        &[],
    );
    assert_eq!(r.status.code(), Some(2), "{}", text(&r));
    assert!(!out.join("summary.jsonl").exists(), "nothing written");
}
