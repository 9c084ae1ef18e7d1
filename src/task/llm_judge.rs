//! The LLM evaluator: a language model (any OpenAI-compatible endpoint with tool calling and
//! image input) judges whether a task's relation holds between two bound objects in one state
//! of a scene, using the same state and vision tools as the built-in evaluator, run by the
//! Drake bridge (`evaluator_tool`). Tool results go back as tool messages; images from the
//! vision tools follow as a user message with `image_url` parts. The model ends with
//! `submit_verdict`; a reply without any tool call, or a malformed verdict, is answered with
//! the reason and counts against [`MAX_TURNS`].

use std::path::Path;

use serde::{Deserialize, Serialize};
use serde_json::{Value, json};

use super::llm::ask;
use super::{Predicate, TaskError, TaskSpec};
use crate::agents::llm::transport::{CallMeta, Transport};
use crate::physics::pool::BridgePool;
use crate::physics::protocol::{EvalTool, EvalToolArgs, EvalToolReply, EvaluatorTool};

const SYSTEM: &str = include_str!("../../prompts/task_evaluator.md");

/// Requests per verdict, tool rounds and retries together.
pub const MAX_TURNS: usize = 12;

/// Characters of a tool result kept in the verdict's record.
const RECORD_CHARS: usize = 600;

/// One tool call the model made, as recorded with the verdict.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ToolUse {
    /// Tool name.
    pub tool: String,
    /// Its arguments (JSON text as the model sent them).
    pub arguments: String,
    /// The start of the result (JSON text), or the error.
    pub result: String,
    /// Images the tool returned.
    pub images: usize,
}

/// The LLM evaluator's verdict on one pair.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct LlmVerdict {
    /// Whether the relation holds.
    pub holds: bool,
    /// The model's reason.
    pub reason: String,
    /// The tool calls it made, in order: its evidence.
    pub tools: Vec<ToolUse>,
}

/// Runs one tool: the bridge's `evaluator_tool`, or a test double.
pub trait ToolRunner {
    /// The reply to `args`, or why the bridge could not answer.
    fn run(&self, args: &EvalToolArgs) -> Result<EvalToolReply, String>;
}

impl ToolRunner for BridgePool {
    fn run(&self, args: &EvalToolArgs) -> Result<EvalToolReply, String> {
        self.call::<EvaluatorTool>(args).map_err(|e| e.to_string())
    }
}

fn tools() -> Value {
    let f = |name: &str, description: &str, properties: Value, required: &[&str]| {
        json!({"type": "function", "function": {
            "name": name,
            "description": description,
            "parameters": {"type": "object", "properties": properties,
                           "required": required, "additionalProperties": false}
        }})
    };
    let id = json!({"type": "string"});
    json!([
        f(
            "list_objects",
            "The scene's objects (id, category, kind), optionally of one category.",
            json!({"category": id}),
            &[]
        ),
        f(
            "get_object_info",
            "Category, pose, size and support of one object.",
            json!({"object_id": id}),
            &["object_id"]
        ),
        f(
            "get_distance",
            "Signed distance between two objects in metres (negative: penetrating).",
            json!({"object_id": id, "other_id": id}),
            &["object_id", "other_id"]
        ),
        f(
            "get_spatial_relation",
            "Where other_id is relative to object_id (the reference): per-axis gaps in the reference's frame, overlap, above/below/inside.",
            json!({"object_id": id, "other_id": id}),
            &["object_id", "other_id"]
        ),
        f(
            "get_support",
            "What holds an object up: contacts and footprint overlap per surface.",
            json!({"object_id": id}),
            &["object_id"]
        ),
        f(
            "observe_scene",
            "Images of the whole scene.",
            json!({}),
            &[]
        ),
        f(
            "observe_objects",
            "Images framing the given objects.",
            json!({"object_ids": {"type": "array", "items": id}}),
            &["object_ids"]
        ),
        f(
            "submit_verdict",
            "Hand in the verdict.",
            json!({"holds": {"type": "boolean"}, "reason": id}),
            &["holds", "reason"]
        ),
    ])
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Call {
    #[serde(default)]
    object_id: Option<String>,
    #[serde(default)]
    other_id: Option<String>,
    #[serde(default)]
    category: Option<String>,
    #[serde(default)]
    object_ids: Vec<String>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct Verdict {
    holds: bool,
    reason: String,
}

fn tool_of(name: &str) -> Option<EvalTool> {
    Some(match name {
        "list_objects" => EvalTool::ListObjects,
        "get_object_info" => EvalTool::GetObjectInfo,
        "get_distance" => EvalTool::GetDistance,
        "get_spatial_relation" => EvalTool::GetSpatialRelation,
        "get_support" => EvalTool::GetSupport,
        "observe_scene" => EvalTool::ObserveScene,
        "observe_objects" => EvalTool::ObserveObjects,
        _ => return None,
    })
}

fn relation_words(p: Predicate) -> &'static str {
    match p {
        Predicate::On => "on",
        Predicate::Inside => "inside",
        Predicate::Near => "near",
    }
}

/// The state a verdict is about.
#[derive(Debug, Clone, Copy)]
pub struct JudgedState<'a> {
    /// The scene directory.
    pub scene_dir: &'a Path,
    /// The directives of the state (`scene.dmd.yaml` or an episode's after-file).
    pub directives: &'a Path,
    /// The object to move.
    pub target: &'a str,
    /// The reference.
    pub reference: &'a str,
}

/// Asks the model (through `transport`, model name `model`) whether `spec`'s relation holds
/// for the pair in `state`; the tools run through `runner`. See the module documentation.
pub fn judge_with_llm(
    transport: &mut dyn Transport,
    model: &str,
    runner: &dyn ToolRunner,
    spec: &TaskSpec,
    state: JudgedState<'_>,
) -> Result<LlmVerdict, TaskError> {
    let meta = CallMeta {
        stage: "task".into(),
        role: "evaluator".into(),
    };
    let rel = relation_words(spec.predicate);
    let mut messages = vec![
        json!({"role": "system", "content": SYSTEM}),
        json!({"role": "user", "content": format!(
            "Task: {task}\nRelation: {rel}\nTarget (the object to move): {t}\nReference: {r}\n\
             Does `{t}` {rel} `{r}` hold in this state? Inspect it with the tools, then call \
             submit_verdict.",
            task = spec.task, t = state.target, r = state.reference
        )}),
    ];
    let mut record = Vec::new();
    let mut last_problem = String::from("no reply");
    for _ in 0..MAX_TURNS {
        let message = ask(transport, &meta, model, &messages, tools())?;
        let calls = message["tool_calls"]
            .as_array()
            .cloned()
            .unwrap_or_default();
        messages.push(message);
        if calls.is_empty() {
            last_problem = "a reply without a tool call".into();
            messages.push(json!({"role": "user", "content":
                "Call one of the tools, or submit_verdict with holds and reason."}));
            continue;
        }
        let mut images = Vec::new();
        for call in &calls {
            let name = call["function"]["name"].as_str().unwrap_or_default();
            let raw = call["function"]["arguments"].as_str().unwrap_or("{}");
            let call_id = call["id"].as_str().unwrap_or_default().to_string();
            if name == "submit_verdict" {
                match serde_json::from_str::<Verdict>(raw) {
                    Ok(v) => {
                        return Ok(LlmVerdict {
                            holds: v.holds,
                            reason: v.reason,
                            tools: record,
                        });
                    }
                    Err(e) => {
                        last_problem = format!("submit_verdict arguments: {e}");
                        messages.push(tool_message(&call_id, &json!({"error": last_problem})));
                        continue;
                    }
                }
            }
            let (content, shots) = run_call(runner, state, name, raw);
            record.push(ToolUse {
                tool: name.to_string(),
                arguments: raw.to_string(),
                result: content.chars().take(RECORD_CHARS).collect(),
                images: shots.len(),
            });
            messages.push(json!({"role": "tool", "tool_call_id": call_id, "content": content}));
            images.extend(shots);
        }
        if !images.is_empty() {
            let mut parts = vec![
                json!({"type": "text", "text": "Images from the vision tools, in call order:"}),
            ];
            for (name, b64) in images {
                parts.push(json!({"type": "text", "text": name}));
                parts.push(json!({"type": "image_url",
                                  "image_url": {"url": format!("data:image/png;base64,{b64}")}}));
            }
            messages.push(json!({"role": "user", "content": parts}));
        }
    }
    Err(TaskError::Llm(format!(
        "no verdict after {MAX_TURNS} requests (last problem: {last_problem})"
    )))
}

fn tool_message(call_id: &str, content: &Value) -> Value {
    json!({"role": "tool", "tool_call_id": call_id, "content": content.to_string()})
}

/// Runs one call: its result as JSON text (an `{"error"}` object for anything the model got
/// wrong or the bridge could not do, so the model can correct itself) and its images.
fn run_call(
    runner: &dyn ToolRunner,
    state: JudgedState<'_>,
    name: &str,
    raw: &str,
) -> (String, Vec<(String, String)>) {
    let error = |e: String| (json!({"error": e}).to_string(), Vec::new());
    let Some(tool) = tool_of(name) else {
        return error(format!("there is no tool {name:?}"));
    };
    let call: Call = match serde_json::from_str(raw) {
        Ok(c) => c,
        Err(e) => return error(format!("arguments of {name}: {e}")),
    };
    let args = EvalToolArgs {
        scene_dir: state.scene_dir.to_path_buf(),
        directives: state.directives.to_path_buf(),
        tool,
        object_id: call.object_id,
        other_id: call.other_id,
        category: call.category,
        object_ids: call.object_ids,
    };
    match runner.run(&args) {
        Ok(reply) => (
            reply.result_json,
            reply
                .images
                .into_iter()
                .map(|i| (i.name, i.png_base64))
                .collect(),
        ),
        Err(e) => error(format!("the tool failed: {e}")),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::agents::llm::LlmError;
    use crate::physics::protocol::ToolImage;
    use std::cell::RefCell;
    use std::collections::VecDeque;

    /// Replies in order; records every request.
    struct Scripted {
        replies: VecDeque<Value>,
        seen: Vec<Value>,
    }

    impl Transport for Scripted {
        fn complete(&mut self, _meta: &CallMeta, request: &Value) -> Result<Value, LlmError> {
            self.seen.push(request.clone());
            let message = self
                .replies
                .pop_front()
                .ok_or_else(|| LlmError::Malformed("script exhausted".into()))?;
            Ok(json!({"choices": [{"message": message}]}))
        }

        fn usage(&self) -> std::collections::BTreeMap<String, crate::scene::StageUsage> {
            Default::default()
        }
    }

    /// Answers every tool with its name and arguments; observe_* with one image.
    struct Echo(RefCell<Vec<EvalTool>>);

    impl ToolRunner for Echo {
        fn run(&self, args: &EvalToolArgs) -> Result<EvalToolReply, String> {
            self.0.borrow_mut().push(args.tool);
            let images = if matches!(args.tool, EvalTool::ObserveObjects) {
                vec![ToolImage {
                    name: "top".into(),
                    png_base64: "iVBORw0KGgo=".into(),
                }]
            } else {
                Vec::new()
            };
            Ok(EvalToolReply {
                result_json: json!({"tool": format!("{:?}", args.tool), "id": args.object_id})
                    .to_string(),
                images,
            })
        }
    }

    fn calls(list: &[(&str, &str)]) -> Value {
        let calls: Vec<Value> = list
            .iter()
            .enumerate()
            .map(|(k, (n, a))| {
                json!({"id": format!("c{k}"), "type": "function",
                                      "function": {"name": n, "arguments": a}})
            })
            .collect();
        json!({"role": "assistant", "content": null, "tool_calls": calls})
    }

    fn mug_on_table() -> JudgedState<'static> {
        JudgedState {
            scene_dir: Path::new("/s"),
            directives: Path::new("scene.dmd.yaml"),
            target: "mug_0",
            reference: "table_0",
        }
    }

    fn spec() -> TaskSpec {
        crate::task::analyse("put the mug on the table").expect("a task")
    }

    #[test]
    fn tools_run_results_and_images_go_back_and_the_verdict_is_kept() {
        let mut t = Scripted {
            replies: VecDeque::from([
                json!({"role": "assistant", "content": "Let me think."}),
                calls(&[
                    ("get_support", r#"{"object_id": "mug_0"}"#),
                    ("observe_objects", r#"{"object_ids": ["mug_0", "table_0"]}"#),
                ]),
                calls(&[("submit_verdict", r#"{"holds": "yes"}"#)]),
                calls(&[(
                    "submit_verdict",
                    r#"{"holds": true, "reason": "100 % of the footprint on table_0"}"#,
                )]),
            ]),
            seen: Vec::new(),
        };
        let runner = Echo(RefCell::new(Vec::new()));
        let state = mug_on_table();
        let v = judge_with_llm(&mut t, "m", &runner, &spec(), state).expect("a verdict");
        assert!(v.holds);
        assert_eq!(v.tools.len(), 2);
        assert_eq!(v.tools[1].images, 1);
        assert_eq!(
            *runner.0.borrow(),
            [EvalTool::GetSupport, EvalTool::ObserveObjects]
        );
        // The third request carries the tool results and the image.
        let third = t.seen[2]["messages"].to_string();
        assert!(
            third.contains("GetSupport") && third.contains("data:image/png;base64,"),
            "{third}"
        );
        // The malformed verdict was answered with its error.
        let fourth = t.seen[3]["messages"].to_string();
        assert!(fourth.contains("submit_verdict arguments"), "{fourth}");
    }

    #[test]
    fn bad_calls_are_shown_to_the_model_and_endless_talk_ends_in_an_error() {
        let mut replies = VecDeque::from([calls(&[("teleport", "{}"), ("get_distance", "{bad")])]);
        for _ in 0..MAX_TURNS {
            replies.push_back(json!({"role": "assistant", "content": "hmm"}));
        }
        let mut t = Scripted {
            replies,
            seen: Vec::new(),
        };
        let runner = Echo(RefCell::new(Vec::new()));
        let state = mug_on_table();
        let err = judge_with_llm(&mut t, "m", &runner, &spec(), state).expect_err("no verdict");
        assert!(err.to_string().contains("no verdict"), "{err}");
        assert!(
            runner.0.borrow().is_empty(),
            "neither bad call reached the bridge"
        );
        let second = t.seen[1]["messages"].to_string();
        assert!(
            second.contains("no tool") && second.contains("arguments of get_distance"),
            "{second}"
        );
    }
}
