//! `scenesmith task`: a pick-and-place task -> varied scene prompts -> generated scenes that
//! hold the objects with the goal false at the start; bad tasks refused with a reason.

mod common;

use common::mock_llm::{MockServer, Script, text as llm_text, tool_calls};
use common::{generate_quick, json_lines, scenesmith, text};
use scenesmith::formats::scene_dir::read_scene;
use scenesmith::physics::protocol::{JudgeArgs, JudgeTask, TaskPredicate};
use scenesmith::physics::{Bridge, BridgeConfig};
use scenesmith::scene::Support;
use scenesmith::task::{TaskSpec, check_scene};

#[test]
fn a_task_gives_prompts_and_bad_tasks_exit_2_with_a_reason() {
    let root = tempfile::tempdir().unwrap();
    let out = root.path().join("t");
    let o = out.to_str().unwrap();
    let r = scenesmith(
        &[
            "task",
            "Move the book next to the lamp",
            "--scenes",
            "6",
            "--out",
            o,
        ],
        &[],
    );
    assert!(r.status.success(), "{}", text(&r));
    let spec: TaskSpec =
        serde_json::from_slice(&std::fs::read(out.join("task.json")).unwrap()).unwrap();
    assert_eq!(spec.target, "book");
    let prompts = json_lines(&out.join("prompts.jsonl"));
    assert_eq!(prompts.len(), 6);
    let rooms: std::collections::BTreeSet<&str> = prompts
        .iter()
        .filter_map(|p| p["room_type"].as_str())
        .collect();
    assert!(rooms.len() >= 2, "room types vary: {rooms:?}");
    for (task, says) in [
        ("", "empty"),
        ("pick up the mug", "no goal relation"),
        ("put the sadness on the shelf", "names no object"),
    ] {
        let r = scenesmith(&["task", task, "--out", o], &[]);
        assert_eq!(r.status.code(), Some(2), "{task:?}: {}", text(&r));
        assert!(text(&r).contains(says), "{task:?}: {}", text(&r));
    }
}

#[test]
fn generated_task_scenes_hold_the_objects_with_the_goal_false_and_are_kept_on_a_rerun() {
    let root = tempfile::tempdir().unwrap();
    let out = root.path().join("t");
    let o = out.to_str().unwrap();
    let args = [
        "task",
        "put the mug on the coffee table",
        "--scenes",
        "1",
        "--out",
        o,
        "--generate",
        "--no-stb",
    ];
    let r = scenesmith(&args, &[]);
    assert!(r.status.success(), "{}", text(&r));
    let rows = json_lines(&out.join("scenes.jsonl"));
    assert_eq!(rows.len(), 1);
    assert!(rows[0]["failure"].is_null(), "{}", rows[0]);
    let spec: TaskSpec =
        serde_json::from_slice(&std::fs::read(out.join("task.json")).unwrap()).unwrap();
    let dir = out.join("scenes/scene_000");
    let mut scene = read_scene(&dir).expect("the scene was written");
    let check = check_scene(&spec, &scene);
    assert!(check.passed(), "{check:?}");
    // The built-in evaluator in Drake agrees: the mug is on what it was placed on, not on the
    // coffee table.
    let mug = scene
        .object(&check.bindable[0])
        .expect("the bindable mug is an object");
    let Support::Object { parent, .. } = &mug.support else {
        panic!("the mug rests on an object: {:?}", mug.support);
    };
    let mut bridge = Bridge::start(BridgeConfig::from_env()).expect("the Drake bridge starts");
    let verdict = bridge
        .call::<JudgeTask>(&JudgeArgs {
            scene_dir: dir.clone(),
            directives: "scene.dmd.yaml".into(),
            predicate: TaskPredicate::On,
            targets: vec![mug.id.clone()],
            references: vec![parent.clone(), check.references[0].clone()],
        })
        .expect("judge_task");
    let holds: Vec<(&str, bool)> = verdict
        .pairs
        .iter()
        .map(|p| (p.reference.as_str(), p.holds))
        .collect();
    assert_eq!(
        holds,
        [
            (parent.as_str(), true),
            (check.references[0].as_str(), false)
        ],
        "{verdict:?}"
    );
    // The check can fail: put every mug on the coffee table and the goal holds at the start.
    let table = check.references[0].clone();
    for o in scene
        .objects
        .iter_mut()
        .filter(|o| check.targets.contains(&o.id))
    {
        o.support = Support::Object {
            parent: table.clone(),
            surface: "top".into(),
        };
    }
    let moved = check_scene(&spec, &scene);
    assert!(
        !moved.passed() && moved.reason().contains("already holds"),
        "{moved:?}"
    );
    // A second run finds the scene on disk and keeps it.
    let again = scenesmith(&args, &[]);
    assert!(again.status.success(), "{}", text(&again));
    let rows = json_lines(&out.join("scenes.jsonl"));
    assert_eq!(rows[0]["attempts"].as_u64(), Some(0), "{}", rows[0]);
}

#[test]
fn robot_eval_binds_judges_and_runs_an_episode_per_policy() {
    let root = tempfile::tempdir().unwrap();
    let out = root.path().join("r");
    let o = out.to_str().unwrap();
    let r = scenesmith(
        &[
            "robot-eval",
            "put the mug on the coffee table",
            "--scenes",
            "1",
            "--policy",
            "standard",
            "--out",
            o,
            "--no-frames",
            "--json",
        ],
        &[],
    );
    assert!(r.status.success(), "{}", text(&r));
    let results: serde_json::Value =
        serde_json::from_slice(&std::fs::read(out.join("results.json")).unwrap()).unwrap();
    let binding = &results["bindings"][0];
    assert!(
        binding["target"].is_string() && binding["reference"].is_string(),
        "{binding}"
    );
    let episodes = results["episodes"].as_array().expect("episodes");
    assert_eq!(episodes.len(), 1);
    let outcome = episodes[0]["outcome"].as_str().unwrap_or_default();
    let known = [
        "success",
        "placed_wrong",
        "no_base_pose",
        "no_grasp",
        "ik",
        "planning",
        "dropped",
        "timeout",
    ];
    assert!(known.contains(&outcome), "{}", episodes[0]);
    assert!(
        !episodes[0]["reason"]
            .as_str()
            .unwrap_or_default()
            .is_empty()
    );
    // What the carried object hit, counted in the summary.
    let hit = episodes[0]["hit"].as_array().expect("hit");
    let summary = &results["summary"][0];
    assert_eq!(summary["policy"], "standard");
    assert_eq!(summary["episodes"], 1);
    assert_eq!(summary["hits"].as_u64(), Some(u64::from(!hit.is_empty())));
    let ci = summary["ci95"].as_array().expect("ci95");
    let (lo, hi) = (ci[0].as_f64().unwrap(), ci[1].as_f64().unwrap());
    let rate = summary["rate"].as_f64().unwrap();
    assert!(lo <= rate && rate <= hi && hi - lo > 0.5, "{summary}");
    // An executed episode wrote the after-file the evaluator judged.
    if outcome == "success" || outcome == "placed_wrong" {
        let after = out.join("episodes/scene_000/standard/after_standard.dmd.yaml");
        assert!(after.exists(), "{}", after.display());
    }
}

#[test]
fn an_llm_reads_a_task_the_grammar_cannot_and_its_words_are_grounded_the_same_way() {
    // The grammar needs a relation phrase; the model reads one the grammar cannot.
    let task = "Shelve the mug where the books are";
    let root = tempfile::tempdir().unwrap();
    let out = root.path().join("t");
    let o = out.to_str().unwrap();
    let builtin = scenesmith(&["task", task, "--out", o], &[]);
    assert_eq!(builtin.status.code(), Some(2), "{}", text(&builtin));
    let mut script = Script::default();
    // First a reply without the tool (retried with the reason), then the reading.
    script.push("task", "analyst", llm_text("It goes on the shelf."));
    script.push(
        "task",
        "analyst",
        tool_calls(&[(
            "submit_task",
            r#"{"predicate": "on", "target": "mugs", "reference": "book shelf", "room": "office"}"#,
        )]),
    );
    let server = MockServer::start(script);
    let r = scenesmith(
        &[
            "task",
            task,
            "--out",
            o,
            "--scenes",
            "2",
            "--llm-base-url",
            &server.base_url,
            "--llm-model",
            "mock-model",
        ],
        &[],
    );
    assert!(r.status.success(), "{}", text(&r));
    let spec: TaskSpec =
        serde_json::from_slice(&std::fs::read(out.join("task.json")).unwrap()).unwrap();
    assert_eq!(
        (spec.target.as_str(), spec.reference.as_str()),
        ("mug", "bookshelf")
    );
    assert_eq!(spec.room_types, ["office"]);
    let received = server.script.lock().unwrap().received.len();
    assert_eq!(received, 2, "one retry after the reply without the tool");
    // A model that names no object is refused like the grammar's reading.
    let mut script = Script::default();
    for _ in 0..2 {
        script.push(
            "task",
            "analyst",
            tool_calls(&[(
                "submit_task",
                r#"{"predicate": "on", "target": "happiness", "reference": "shelf"}"#,
            )]),
        );
    }
    let server = MockServer::start(script);
    let r = scenesmith(
        &[
            "task",
            task,
            "--out",
            o,
            "--llm-base-url",
            &server.base_url,
            "--llm-model",
            "m",
        ],
        &[],
    );
    assert_eq!(r.status.code(), Some(2), "{}", text(&r));
    assert!(text(&r).contains("names no object"), "{}", text(&r));
}

#[test]
fn an_llm_evaluator_judges_a_state_over_the_bridge_tools() {
    use scenesmith::agents::llm::LlmConfig;
    use scenesmith::agents::llm::transport::HttpTransport;
    use scenesmith::physics::BridgePool;
    use scenesmith::task::llm_judge::{JudgedState, judge_with_llm};

    let root = tempfile::tempdir().unwrap();
    let dir = root.path().join("scene");
    generate_quick(
        "a living room with a sofa, a coffee table and a mug on the coffee table",
        &dir,
    );
    let scene = read_scene(&dir).unwrap();
    let mug = scene
        .objects
        .iter()
        .find(|o| o.category == "mug")
        .expect("a mug");
    let Support::Object { parent, .. } = &mug.support else {
        panic!("the mug stands on an object: {:?}", mug.support);
    };
    let mut script = Script::default();
    script.push(
        "task",
        "evaluator",
        tool_calls(&[("list_objects", r#"{"category": "mug"}"#)]),
    );
    let both = serde_json::json!({"object_ids": [mug.id, parent]}).to_string();
    let support = serde_json::json!({"object_id": mug.id}).to_string();
    script.push(
        "task",
        "evaluator",
        tool_calls(&[("get_support", &support), ("observe_objects", &both)]),
    );
    script.push(
        "task",
        "evaluator",
        tool_calls(&[(
            "submit_verdict",
            r#"{"holds": true, "reason": "its whole footprint is on the table"}"#,
        )]),
    );
    let server = MockServer::start(script);
    let config = LlmConfig {
        base_url: server.base_url.clone(),
        model: "mock-model".into(),
        ..LlmConfig::default()
    };
    let mut transport = HttpTransport::new(config, None).unwrap();
    let spec = scenesmith::task::analyse("put the mug on the coffee table").unwrap();
    let pool = BridgePool::from_env();
    let state = JudgedState {
        scene_dir: &dir,
        directives: std::path::Path::new("scene.dmd.yaml"),
        target: &mug.id,
        reference: parent,
    };
    let verdict = judge_with_llm(&mut transport, "mock-model", &pool, &spec, state).unwrap();
    assert!(verdict.holds);
    let tools: Vec<&str> = verdict.tools.iter().map(|t| t.tool.as_str()).collect();
    assert_eq!(tools, ["list_objects", "get_support", "observe_objects"]);
    // The model was shown the bridge's real answers: the mug in the list, its supporter, and
    // rendered images.
    assert!(
        verdict.tools[0].result.contains(&mug.id),
        "{:?}",
        verdict.tools[0]
    );
    assert!(
        verdict.tools[1].result.contains(parent.as_str()),
        "{:?}",
        verdict.tools[1]
    );
    assert!(verdict.tools[2].images >= 1, "{:?}", verdict.tools[2]);
    let received = server.script.lock().unwrap().received.clone();
    assert_eq!(received.len(), 3);
    let last = received[2]["messages"].to_string();
    assert!(
        last.contains("data:image/png;base64,iVBOR"),
        "a PNG went to the model"
    );
}
