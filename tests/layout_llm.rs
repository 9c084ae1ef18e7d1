//! The layout stage driven by a language model over a loopback chat-completions mock: the
//! model inspects the layout, resizes a room, makes a bad call that comes back as a structured
//! error, and the critic's scores decide; what it did is in the kept layout.

mod common;

use std::sync::{Arc, Mutex};

use common::mock_llm::{MockServer, Script, text, tool_calls};
use scenesmith::agents::Backend;
use scenesmith::agents::llm::{HttpTransport, LlmConfig, Transport};
use scenesmith::agents::{LogEvent, RunLog, ToolErrorKind};
use scenesmith::layout::stage::run_layout;

const PROMPT: &str = "A one-bedroom apartment with a bedroom, a living room, and a bathroom.";

#[test]
fn an_llm_designer_edits_the_layout_through_the_tools() {
    let mut s = Script::default();
    for d in [
        tool_calls(&[("request_initial_design", "{}")]),
        tool_calls(&[("request_critique", "{}")]),
        tool_calls(&[("finish", "{\"reason\": \"done\"}")]),
    ] {
        s.push("layout", "orchestrator", d);
    }
    s.push(
        "layout",
        "designer",
        tool_calls(&[
            ("observe_scene", "{}"),
            ("render_ascii", "{}"),
            (
                "resize_room",
                "{\"room\": \"bedroom_0\", \"width_m\": 5.0, \"depth_m\": 4.0}",
            ),
            (
                "add_door",
                "{\"room_a\": \"bedroom_0\", \"room_b\": \"attic_9\"}",
            ),
            ("validate", "{}"),
        ]),
    );
    s.push("layout", "designer", text("Made the bedroom larger."));
    let server = MockServer::start(s);
    let cfg = LlmConfig {
        base_url: server.base_url.clone(),
        model: "mock-model".into(),
        backoff_base_s: 0.01,
        backoff_max_s: 0.05,
        ..LlmConfig::default()
    };
    let t: Box<dyn Transport> = Box::new(HttpTransport::new(cfg.clone(), None).unwrap());
    let backend = Backend::Llm {
        transport: Arc::new(Mutex::new(t)),
        config: cfg,
    };
    let mut log = RunLog::default();
    let out = run_layout(PROMPT, 1, &backend, &mut log).unwrap();

    // The resize is in the kept layout, and the house is still valid.
    let bed = out.rooms.iter().find(|r| r.id == "bedroom_0").unwrap();
    let (lo, hi) = scenesmith::geometry::polygon::bounds(&bed.floor_polygon);
    let mut size = [hi[0] - lo[0], hi[1] - lo[1]];
    size.sort_by(f64::total_cmp);
    assert!(
        (size[0] - 4.0).abs() < 1e-6 && (size[1] - 5.0).abs() < 1e-6,
        "{size:?}"
    );
    assert!(out.validation.ok, "{:?}", out.validation.errors);
    // The critic's scores (9 from the mock) were kept.
    assert_eq!(out.summary.critique.as_ref().unwrap().min_score(), 9);

    // The bad call came back as a structured error, in the same log as the good ones.
    let errors: Vec<ToolErrorKind> = log
        .events
        .iter()
        .filter_map(|e| match e {
            LogEvent::ToolCall(c) => c.error.as_ref().map(|e| e.kind.clone()),
            _ => None,
        })
        .collect();
    assert_eq!(errors, vec![ToolErrorKind::BadArguments]);
    let script = server.script.lock().unwrap();
    let first = &script.received[0];
    let system = first["messages"][0]["content"].as_str().unwrap();
    assert!(system.contains("orchestrator of the layout stage"));
    // The designer was offered the layout tools with their schemas.
    let designer = script
        .received
        .iter()
        .find(|r| {
            r["messages"][0]["content"]
                .as_str()
                .unwrap()
                .starts_with("You are the designer of the layout stage")
        })
        .unwrap();
    let names: Vec<&str> = designer["tools"]
        .as_array()
        .unwrap()
        .iter()
        .map(|t| t["function"]["name"].as_str().unwrap())
        .collect();
    assert!(names.contains(&"generate_room_specs") && names.contains(&"add_open_connection"));
    // The 16 tools the design names plus the plan as a picture.
    assert!(names.contains(&"render_plan_image"));
    assert_eq!(names.len(), 17);
}
