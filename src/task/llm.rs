//! Reading a task with a language model (any OpenAI-compatible endpoint): the model calls
//! `submit_task` with the relation and the noun phrases; the phrases are then grounded by the
//! prompt reader exactly as the built-in grammar's are, so a model's reading yields the same
//! kind of spec (canonical nouns, room types of the knowledge base) and a reply that names no
//! object is refused the same way. A malformed reply is retried once with the reason.

use serde::Deserialize;
use serde_json::{Value, json};

use super::NamedRooms;
use super::analyse::{Reference, build_spec, ground_text, room_of_text};
use super::{Predicate, TaskError, TaskSpec};
use crate::agents::llm::transport::{CallMeta, Transport, assistant_message};

const SYSTEM: &str = include_str!("../../prompts/task_analyst.md");

/// Attempts at a well-formed reply.
const ATTEMPTS: usize = 2;

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct Submitted {
    predicate: Predicate,
    target: String,
    reference: String,
    #[serde(default)]
    start: Option<String>,
    #[serde(default)]
    room: Option<String>,
    #[serde(default)]
    start_room: Option<String>,
    #[serde(default)]
    reference_on: Option<String>,
}

fn submit_tool() -> Value {
    json!([{
        "type": "function",
        "function": {
            "name": "submit_task",
            "description": "Hand in the reading of the task.",
            "parameters": {
                "type": "object",
                "properties": {
                    "predicate": {"type": "string", "enum": ["on", "inside", "near"]},
                    "target": {"type": "string"},
                    "reference": {"type": "string"},
                    "start": {"type": "string"},
                    "room": {"type": "string"},
                    "start_room": {"type": "string"},
                    "reference_on": {"type": "string"}
                },
                "required": ["predicate", "target", "reference"],
                "additionalProperties": false
            }
        }
    }])
}

/// The `submit_task` arguments of an assistant message, or why there are none.
fn submitted(message: &Value) -> Result<Submitted, String> {
    let call = message["tool_calls"]
        .as_array()
        .and_then(|calls| {
            calls
                .iter()
                .find(|c| c["function"]["name"] == "submit_task")
        })
        .ok_or("the reply does not call submit_task")?;
    let raw = call["function"]["arguments"]
        .as_str()
        .ok_or("submit_task has no arguments")?;
    serde_json::from_str(raw).map_err(|e| format!("submit_task arguments: {e}"))
}

/// One deterministic chat request of the task stage with `tools`: the assistant's message.
pub(super) fn ask(
    transport: &mut dyn Transport,
    meta: &CallMeta,
    model: &str,
    messages: &[Value],
    tools: Value,
) -> Result<Value, TaskError> {
    let request = json!({
        "model": model,
        "messages": messages,
        "tools": tools,
        "tool_choice": "auto",
        "temperature": 0.0,
    });
    let response = transport
        .complete(meta, &request)
        .map_err(|e| TaskError::Llm(e.to_string()))?;
    assistant_message(&response).map_err(|e| TaskError::Llm(e.to_string()))
}

/// Reads `task` through `transport` (model `model`). See the module documentation.
pub fn analyse_with_llm(
    transport: &mut dyn Transport,
    model: &str,
    task: &str,
) -> Result<TaskSpec, TaskError> {
    if task.trim().is_empty() {
        return Err(TaskError::Empty);
    }
    let meta = CallMeta {
        stage: "task".into(),
        role: "analyst".into(),
    };
    let mut messages = vec![
        json!({"role": "system", "content": SYSTEM}),
        json!({"role": "user", "content": task}),
    ];
    let mut last = String::new();
    for _ in 0..ATTEMPTS {
        let message = ask(transport, &meta, model, &messages, submit_tool())?;
        match submitted(&message) {
            Ok(s) => return spec_of(task, s),
            Err(why) => {
                last = why.clone();
                messages.push(message);
                messages.push(json!({"role": "user", "content": format!(
                    "That was not usable: {why}. Call submit_task with predicate, target and reference."
                )}));
            }
        }
    }
    Err(TaskError::Llm(format!(
        "no usable reading after {ATTEMPTS} replies: {last}"
    )))
}

fn spec_of(task: &str, s: Submitted) -> Result<TaskSpec, TaskError> {
    let target = ground_text(&s.target).ok_or_else(|| TaskError::NotAnObject {
        role: "the object to move",
        phrase: s.target.clone(),
    })?;
    let reference = Reference {
        noun: ground_text(&s.reference)
            .ok_or_else(|| TaskError::NotAnObject {
                role: "the reference",
                phrase: s.reference.clone(),
            })?
            .noun,
        on: s
            .reference_on
            .as_deref()
            .and_then(ground_text)
            .map(|g| g.noun),
    };
    let start = s.start.as_deref().and_then(ground_text).map(|g| g.noun);
    let rooms = NamedRooms {
        start: s.start_room.as_deref().and_then(room_of_text),
        goal: s.room.as_deref().and_then(room_of_text),
    };
    build_spec(task, s.predicate, target, reference, start, rooms)
}
