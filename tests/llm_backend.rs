//! The LLM backend against a loopback mock of the chat-completions API (real HTTP, scripted
//! answers): tool calls including invalid ones, a critic's scores, a rollback after a score
//! drop, retries on 429/500, replay without a network, and a malformed endpoint.

mod common;

use std::sync::{Arc, Mutex};

use common::mock_llm::{MockServer, Reply, Script, text, tool_calls};
use common::{scenesmith, text as out_text};
use scenesmith::agents::Backend;
use scenesmith::agents::LogEvent;
use scenesmith::agents::ToolErrorKind;
use scenesmith::agents::llm::{HttpTransport, LlmConfig, Transport};
use scenesmith::pipeline::build_scene;
use serde_json::json;

const PROMPT: &str = "A dining room with a table, two chairs and a shelf.";

fn config(base_url: &str) -> LlmConfig {
    LlmConfig {
        base_url: base_url.into(),
        model: "mock-model".into(),
        backoff_base_s: 0.01,
        backoff_max_s: 0.05,
        ..LlmConfig::default()
    }
}

fn backend(server: &MockServer) -> Backend {
    let cfg = config(&server.base_url);
    let t: Box<dyn Transport> = Box::new(HttpTransport::new(cfg.clone(), None).unwrap());
    Backend::Llm {
        transport: Arc::new(Mutex::new(t)),
        config: cfg,
    }
}

/// The furniture stage: design (with a call to a tool that does not exist and one with bad
/// arguments), a good critique, a change that makes it worse (automatic rollback), a
/// different change that is still worse than the first design, finish.
fn furniture_script() -> Script {
    let mut s = Script::default();
    let orch = |name: &str, args: &str| tool_calls(&[(name, args)]);
    for d in [
        orch("request_initial_design", "{}"),
        orch("request_critique", "{}"),
        orch(
            "request_design_change",
            "{\"instruction\": \"add a shelf\"}",
        ),
        orch("request_critique", "{}"),
        orch(
            "request_design_change",
            "{\"instruction\": \"try the shelf on another wall\"}",
        ),
        orch("request_critique", "{}"),
        orch("finish", "{\"reason\": \"done\"}"),
    ] {
        s.push("furniture", "orchestrator", d);
    }
    for d in [
        tool_calls(&[
            ("observe_room", "{}"),
            (
                "place_in_center",
                "{\"description\": \"dining table\", \"clearance_m\": 0.6}",
            ),
        ]),
        tool_calls(&[
            (
                "place_around",
                "{\"parent\": \"dining_table_0\", \"description\": \"chair\", \"count\": 2}",
            ),
            ("teleport_object", "{\"id\": \"dining_table_0\"}"),
            (
                "place_object",
                "{\"description\": \"chair\", \"x\": \"left\"}",
            ),
            ("place_object", "{not json"),
        ]),
        text("Placed the table and two chairs."),
        tool_calls(&[("remove_object", "{\"id\": \"chair_1\"}")]),
        text("Removed a chair."),
        tool_calls(&[(
            "place_against_wall",
            "{\"description\": \"shelf\", \"wall\": \"north\"}",
        )]),
        text("Added a shelf."),
    ] {
        s.push("furniture", "designer", d);
    }
    let crit = |v: u8| {
        let cats = [
            "prompt_following",
            "functionality",
            "spatial_layout",
            "reachability",
            "physical_feasibility",
        ];
        let scores: Vec<_> = cats
            .iter()
            .map(|c| json!({"category": c, "score": v, "reason": format!("{v}")}))
            .collect();
        tool_calls(&[(
            "submit_critique",
            &json!({"scores": scores, "issues": [{"objects": ["dining_table_0"], "description": "fine"}]})
                .to_string(),
        )])
    };
    // First critique: the critic also inspects (and looks at a picture), and first submits an
    // invalid critique.
    s.push(
        "furniture",
        "critic",
        tool_calls(&[
            ("check_collisions", "{}"),
            ("render_room_image", "{\"view\": \"plan\"}"),
        ]),
    );
    s.push(
        "furniture",
        "critic",
        tool_calls(&[(
            "submit_critique",
            "{\"scores\": [{\"category\": \"prompt_following\", \"score\": 8, \"reason\": \"x\"}]}",
        )]),
    );
    s.push("furniture", "critic", crit(8));
    s.push("furniture", "critic", crit(5));
    s.push("furniture", "critic", crit(7));
    s
}

#[test]
fn scripted_designer_critic_orchestrator_keep_the_best_checkpoint() {
    let server = MockServer::start(furniture_script());
    let (state, report) = build_scene(PROMPT, 1, "llm_mock", &backend(&server)).unwrap();
    let count = |cat: &str| {
        state
            .scene
            .objects
            .iter()
            .filter(|o| o.category == cat)
            .count()
    };
    // The best checkpoint (first design, scores 8) is kept: table and two chairs, no shelf.
    assert_eq!(count("dining_table"), 1);
    assert_eq!(
        count("chair"),
        2,
        "the rolled-back removal must not survive"
    );
    assert_eq!(
        count("shelf"),
        0,
        "the later, lower-scoring design must not be kept"
    );
    let furniture = report
        .stages
        .iter()
        .find(|s| s.stage == "furniture")
        .unwrap();
    assert_eq!(furniture.critique.as_ref().unwrap().total(), 40);
    assert_eq!(furniture.rounds, 3);

    // Invalid calls came back to the model as structured errors, in the same log as good calls.
    let errors: Vec<ToolErrorKind> = report
        .log
        .events
        .iter()
        .filter_map(|e| match e {
            LogEvent::ToolCall(c) => c.error.as_ref().map(|e| e.kind.clone()),
            _ => None,
        })
        .collect();
    assert!(errors.contains(&ToolErrorKind::UnknownTool), "{errors:?}");
    assert!(errors.contains(&ToolErrorKind::BadArguments), "{errors:?}");
    assert!(
        report
            .log
            .events
            .iter()
            .any(|e| matches!(e, LogEvent::Rollback { stage, .. } if stage == "furniture"))
    );

    // The model saw the errors: a tool message with the unknown-tool error went back to it.
    let script = server.script.lock().unwrap();
    // Tool results travel as JSON text inside the messages.
    let sent: String = script
        .received
        .iter()
        .flat_map(|r| r["messages"].as_array().cloned().unwrap_or_default())
        .filter_map(|m| m["content"].as_str().map(str::to_string))
        .collect::<Vec<_>>()
        .join("\n");
    assert!(
        sent.contains("there is no tool \\\"teleport_object\\\""),
        "error text reaches the model"
    );
    assert!(sent.contains("arguments are not valid JSON"));
    assert!(
        sent.contains("missing a score for category"),
        "an invalid critique is rejected back to the critic"
    );
    // The picture reached the critic as an image message, not as tool text.
    let images: Vec<&str> = script
        .received
        .iter()
        .flat_map(|r| r["messages"].as_array().cloned().unwrap_or_default())
        .filter_map(|m| m["content"].as_array().cloned())
        .flatten()
        .filter_map(|part| part["image_url"]["url"].as_str().map(str::to_string))
        .map(|url| {
            if url.starts_with("data:image/png;base64,iVBOR") {
                "png"
            } else {
                "other"
            }
        })
        .collect();
    assert!(images.contains(&"png"), "{images:?}");
    assert!(
        !sent.contains("image_png_base64"),
        "the PNG left the tool message"
    );
    // Tools were offered with JSON schemas.
    let first = &script.received[0];
    assert!(
        first["tools"]
            .as_array()
            .unwrap()
            .iter()
            .any(|t| t["function"]["name"] == "request_critique")
    );
}

#[test]
fn retries_on_429_and_500_then_succeed_and_are_logged() {
    let mut script = Script::default();
    script.preface.push_back(Reply::status(429, "slow down"));
    script.preface.push_back(Reply::status(500, "oops"));
    let server = MockServer::start(script);
    let dir = tempfile::tempdir().unwrap();
    let log =
        scenesmith::agents::llm::transport::LogWriter::open(&dir.path().join("llm_log.jsonl"))
            .unwrap();
    let cfg = config(&server.base_url);
    let t: Box<dyn Transport> = Box::new(HttpTransport::new(cfg.clone(), Some(log)).unwrap());
    let transport = Arc::new(Mutex::new(t));
    let backend = Backend::Llm {
        transport: transport.clone(),
        config: cfg,
    };
    let (_, report) = build_scene("A bedroom with a cabinet.", 2, "llm_retry", &backend).unwrap();
    // Every stage ran to a kept, critiqued checkpoint after the first request's retries.
    assert!(report.stages.iter().all(|s| s.critique.is_some()));
    let usage = transport.lock().unwrap().usage();
    let total_retries: u64 = usage.values().map(|u| u.retries).sum();
    assert_eq!(total_retries, 2);
    let first: serde_json::Value = serde_json::from_str(
        std::fs::read_to_string(dir.path().join("llm_log.jsonl"))
            .unwrap()
            .lines()
            .next()
            .unwrap(),
    )
    .unwrap();
    let statuses: Vec<u64> = first["failed_attempts"]
        .as_array()
        .unwrap()
        .iter()
        .map(|a| a["status"].as_u64().unwrap())
        .collect();
    assert_eq!(statuses, vec![429, 500]);
}

#[test]
fn replay_reproduces_scene_json_without_a_network() {
    let server = MockServer::start(furniture_script());
    let root = tempfile::tempdir().unwrap();
    let recorded = root.path().join("recorded/scene");
    let g = scenesmith(
        &[
            "generate",
            PROMPT,
            "--out",
            recorded.to_str().unwrap(),
            "--seed",
            "1",
            "--no-check",
            "--llm-base-url",
            &server.base_url,
            "--llm-model",
            "mock-model",
        ],
        &[],
    );
    assert!(g.status.success(), "{}", out_text(&g));
    let log = recorded.join("llm_log.jsonl");
    assert!(log.is_file());
    drop(server);
    // Replay with every proxy pointing nowhere: nothing may reach a network.
    let replayed = root.path().join("replayed/scene");
    let r = scenesmith(
        &[
            "generate",
            PROMPT,
            "--out",
            replayed.to_str().unwrap(),
            "--seed",
            "1",
            "--no-check",
            "--replay",
            log.to_str().unwrap(),
        ],
        &[
            ("HTTP_PROXY", "http://127.0.0.1:9"),
            ("HTTPS_PROXY", "http://127.0.0.1:9"),
            ("ALL_PROXY", "http://127.0.0.1:9"),
        ],
    );
    assert!(r.status.success(), "{}", out_text(&r));
    let a = std::fs::read(recorded.join("scene.json")).unwrap();
    let b = std::fs::read(replayed.join("scene.json")).unwrap();
    assert_eq!(a, b, "replayed scene.json differs from the recorded run");
    let scene: serde_json::Value = serde_json::from_slice(&a).unwrap();
    assert_eq!(
        scene["provenance"]["backends"]["designer"],
        "llm:mock-model"
    );
    assert!(
        scene["llm_usage"]["furniture"]["requests"]
            .as_u64()
            .unwrap()
            > 5
    );

    // A replay of a different prompt diverges and says so, writing nothing.
    let other = root.path().join("other/scene");
    let r = scenesmith(
        &[
            "generate",
            "A garage with a workbench.",
            "--out",
            other.to_str().unwrap(),
            "--no-check",
            "--replay",
            log.to_str().unwrap(),
        ],
        &[],
    );
    assert_eq!(r.status.code(), Some(1), "{}", out_text(&r));
    assert!(String::from_utf8_lossy(&r.stderr).contains("diverged"));
    assert!(!other.exists());
}

#[test]
fn malformed_or_unreachable_endpoint_is_a_clear_error() {
    let mut script = Script::default();
    for _ in 0..10 {
        script.preface.push_back(Reply {
            status: 200,
            body: "<html>not json</html>".into(),
        });
    }
    let server = MockServer::start(script);
    let cfg = LlmConfig {
        max_retries: 2,
        ..config(&server.base_url)
    };
    let t: Box<dyn Transport> = Box::new(HttpTransport::new(cfg.clone(), None).unwrap());
    let backend = Backend::Llm {
        transport: Arc::new(Mutex::new(t)),
        config: cfg,
    };
    let err = build_scene(PROMPT, 1, "llm_bad", &backend)
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("failed 3 times") && err.contains("not JSON"),
        "{err}"
    );

    let root = tempfile::tempdir().unwrap();
    let out = root.path().join("scene");
    let g = scenesmith(
        &[
            "generate",
            PROMPT,
            "--out",
            out.to_str().unwrap(),
            "--no-check",
            "--llm-base-url",
            "http://127.0.0.1:9/v1",
            "--llm-model",
            "m",
            "--llm-config",
            "/nonexistent.json",
        ],
        &[],
    );
    assert_eq!(g.status.code(), Some(1));
    assert!(String::from_utf8_lossy(&g.stderr).contains("nonexistent.json"));
    assert!(!out.exists());
}

/// Loop detection: a designer repeating the same failing call is stopped after
/// `loop_limit` (3) attempts; its next scripted reply is never requested in that turn.
#[test]
fn the_same_failing_call_repeated_ends_the_designer_turn() {
    let mut script = Script::default();
    let bad = || tool_calls(&[("teleport_object", "{\"id\": \"no_such_object\"}")]);
    for _ in 0..3 {
        script.push("furniture", "designer", bad());
    }
    script.push(
        "furniture",
        "designer",
        tool_calls(&[("place_in_center", "{\"description\": \"table\"}")]),
    );
    let server = MockServer::start(script);
    let (scene, _) = build_scene(
        "A dining room with a table.",
        1,
        "llm_loop",
        &backend(&server),
    )
    .unwrap();
    let s = server.script.lock().unwrap();
    let designer_requests: Vec<&serde_json::Value> = s
        .received
        .iter()
        .filter(|r| common::mock_llm::stage_and_role(r) == ("furniture".into(), "designer".into()))
        .collect();
    // The first turn: three requests, each answered with the failing call; the third failure
    // ends the turn without a fourth request in the same conversation.
    let first_turn_len = designer_requests[0]["messages"].as_array().unwrap().len();
    let same_turn = designer_requests
        .iter()
        .take_while(|r| {
            r["messages"].as_array().unwrap()[..first_turn_len]
                == designer_requests[0]["messages"].as_array().unwrap()[..]
        })
        .count();
    assert_eq!(
        same_turn,
        3,
        "{} designer requests",
        designer_requests.len()
    );
    let errors = designer_requests[2]["messages"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|m| m["role"] == "tool" && m["content"].as_str().unwrap_or("").contains("error"))
        .count();
    assert_eq!(errors, 2, "the third request carries the first two errors");
    // The scripted table placement was never reached in that turn: no table unless a later
    // design turn asked for it.
    let later_turns = designer_requests.len() - same_turn;
    let tables = scene
        .scene
        .objects
        .iter()
        .filter(|o| o.category.contains("table"))
        .count();
    assert_eq!(tables > 0, later_turns > 0);
}

/// An endpoint that only ever answers in prose: the run fails cleanly, writes no scene, and
/// keeps the transcript of what the model said next to the output, naming it in the error.
#[test]
fn a_failed_run_keeps_its_transcript_and_says_where() {
    let mut script = Script::default();
    for _ in 0..400 {
        script
            .preface
            .push_back(Reply::ok(text("I would put a sofa by the window.")));
    }
    let server = MockServer::start(script);
    let root = tempfile::tempdir().unwrap();
    let out = root.path().join("scene");
    let g = scenesmith(
        &[
            "generate",
            PROMPT,
            "--out",
            out.to_str().unwrap(),
            "--no-check",
            "--llm-base-url",
            &server.base_url,
            "--llm-model",
            "mock-model",
        ],
        &[],
    );
    assert_eq!(g.status.code(), Some(1), "{}", out_text(&g));
    assert!(!out.exists());
    let kept = root.path().join("scene.llm_log.jsonl");
    let stderr = String::from_utf8_lossy(&g.stderr);
    assert!(stderr.contains(kept.to_str().unwrap()), "{stderr}");
    let log = std::fs::read_to_string(&kept).unwrap();
    assert!(log.lines().count() >= 1);
    assert!(log.contains("I would put a sofa"), "{log}");
}
