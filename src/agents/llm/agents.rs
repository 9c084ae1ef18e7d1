//! LLM-backed designer, critic and orchestrator: tool-calling conversations over a
//! [`Transport`], with per-stage memory, structured tool errors fed back to the model, and
//! loop detection.

use std::collections::BTreeMap;
use std::sync::{Arc, Mutex};

use schemars::JsonSchema;
use serde::Deserialize;
use serde_json::{Value, json};

use super::transport::{CallMeta, assistant_message, user_text};
use super::{LlmConfig, LlmError, Transport};
use crate::agents::backend::{
    AgentCx, AgentError, Critic, DesignRequest, Designer, PlacementStyle,
};
use crate::agents::critique::Critique;
use crate::agents::memory::Memory;
use crate::agents::orchestrator::{Decision, LoopView, Orchestrator};
use crate::agents::prompts;
use crate::agents::tool::{Role, schema_of};

/// One transport shared by every agent of a run (so logs and usage are in one place).
pub type SharedTransport = Arc<Mutex<Box<dyn Transport>>>;

/// Key an image-returning observation tool puts its PNG under (base64). The image is moved out
/// of the tool result into a user message, since tool messages carry text only.
pub const IMAGE_KEY: &str = "image_png_base64";

struct Core {
    transport: SharedTransport,
    config: LlmConfig,
    memory: Memory,
}

impl Core {
    fn complete(&self, stage: &str, role: Role, request: &Value) -> Result<Value, AgentError> {
        let meta = CallMeta {
            stage: stage.to_string(),
            role: role.as_str().to_string(),
        };
        let mut t = self
            .transport
            .lock()
            .map_err(|_| LlmError::Config("transport lock poisoned".into()))?;
        Ok(t.complete(&meta, request)?)
    }

    fn request(&self, system: &str, tools: Value) -> Value {
        let mut messages = vec![json!({"role": "system", "content": system})];
        messages.extend(self.memory.messages());
        let mut req = json!({
            "model": self.config.model,
            "messages": messages,
            "temperature": self.config.temperature,
        });
        if tools.as_array().is_some_and(|a| !a.is_empty()) {
            req["tools"] = tools;
            req["tool_choice"] = json!("auto");
        }
        req
    }
}

/// How a conversation turn ended.
enum TurnEnd {
    /// The model stopped calling tools; its final text.
    Text(String),
    /// The model called the submit tool with valid arguments.
    Submitted(Value),
}

/// A tool the model calls to hand in its result (the critic's `submit_critique`).
struct Submit<'a> {
    name: &'a str,
    description: &'a str,
    parameters: Value,
    validate: &'a dyn Fn(&Value) -> Result<(), String>,
}

/// Runs tool calls until the model stops, submits, loops or runs out of steps.
fn tool_turn<S>(
    core: &mut Core,
    role: Role,
    system: &str,
    state: &mut S,
    cx: &mut AgentCx<'_, S>,
    submit: Option<&Submit<'_>>,
) -> Result<TurnEnd, AgentError> {
    let mut tools = cx.toolbox.openai_tools(role);
    if let (Some(s), Some(arr)) = (submit, tools.as_array_mut()) {
        arr.push(json!({"type": "function", "function": {
            "name": s.name, "description": s.description, "parameters": s.parameters}}));
    }
    let mut failures: BTreeMap<String, usize> = BTreeMap::new();
    let mut nudged = false;
    for _ in 0..core.config.max_steps_per_turn {
        let request = core.request(system, tools.clone());
        let response = core.complete(cx.stage, role, &request)?;
        let message = assistant_message(&response)?;
        core.memory.push(message.clone());
        let calls = message["tool_calls"]
            .as_array()
            .cloned()
            .unwrap_or_default();
        if calls.is_empty() {
            let text = message["content"].as_str().unwrap_or_default().to_string();
            match submit {
                Some(s) if !nudged => {
                    nudged = true;
                    core.memory.push(user_text(&format!(
                        "You have not called {} yet. Call it now with your result.",
                        s.name
                    )));
                    continue;
                }
                _ => return Ok(TurnEnd::Text(text)),
            }
        }
        let mut images = Vec::new();
        let mut submitted: Option<Value> = None;
        for call in &calls {
            let id = call["id"].as_str().unwrap_or_default().to_string();
            let name = call["function"]["name"]
                .as_str()
                .unwrap_or_default()
                .to_string();
            let raw = call["function"]["arguments"].as_str().unwrap_or("{}");
            if submitted.is_some() {
                // Every tool call needs an answer, even after the result was handed in.
                core.memory.push(json!({"role": "tool", "tool_call_id": id,
                    "content": "{\"error\": \"ignored: the result was already submitted\"}"}));
                continue;
            }
            let (content, failed) = match serde_json::from_str::<Value>(raw) {
                Err(e) => (
                    json!({"error": {"kind": "bad_arguments",
                        "message": format!("arguments are not valid JSON ({e}); send a JSON object")}}),
                    true,
                ),
                Ok(args) => match submit {
                    Some(s) if s.name == name => match (s.validate)(&args) {
                        Ok(()) => {
                            core.memory.push(json!({"role": "tool", "tool_call_id": id, "content": "{\"ok\": true}"}));
                            submitted = Some(args);
                            continue;
                        }
                        Err(why) => (
                            json!({"error": {"kind": "bad_arguments", "message": why}}),
                            true,
                        ),
                    },
                    _ => match cx.call(state, role, &name, args) {
                        Ok(mut result) => {
                            if let Some(png) =
                                result.as_object_mut().and_then(|m| m.remove(IMAGE_KEY))
                            {
                                images.push(png);
                            }
                            (json!({"ok": result}), false)
                        }
                        Err(e) => (json!({"error": e}), true),
                    },
                },
            };
            if failed {
                let key = format!("{name} {raw}");
                let n = failures.entry(key).or_insert(0);
                *n += 1;
                if *n >= core.config.loop_limit {
                    core.memory.push(
                        json!({"role": "tool", "tool_call_id": id, "content": content.to_string()}),
                    );
                    tracing::warn!(
                        "{} {}: the same failing call {name} repeated {} times; ending the turn",
                        cx.stage,
                        role.as_str(),
                        n
                    );
                    return Ok(TurnEnd::Text(format!(
                        "stopped: {name} kept failing with the same arguments"
                    )));
                }
            }
            core.memory
                .push(json!({"role": "tool", "tool_call_id": id, "content": content.to_string()}));
        }
        if let Some(v) = submitted {
            return Ok(TurnEnd::Submitted(v));
        }
        if !images.is_empty() {
            let mut parts =
                vec![json!({"type": "text", "text": "Observation images from the tools above:"})];
            for png in images {
                let b64 = png.as_str().unwrap_or_default();
                parts.push(json!({"type": "image_url", "image_url": {"url": format!("data:image/png;base64,{b64}")}}));
            }
            core.memory.push(json!({"role": "user", "content": parts}));
        }
    }
    Ok(TurnEnd::Text("stopped: step limit reached".into()))
}

/// The system prompt of a role in a stage, rendered with the stage's brief and tools.
fn system_prompt<S>(role: Role, cx: &AgentCx<'_, S>) -> String {
    let tools = cx
        .toolbox
        .specs_for(role)
        .iter()
        .map(|s| format!("- {}: {}", s.name, s.description))
        .collect::<Vec<_>>()
        .join("\n");
    let categories = cx
        .categories
        .iter()
        .map(|c| format!("- {}: {}", c.id, c.description))
        .collect::<Vec<_>>()
        .join("\n");
    prompts::render(
        cx.stage,
        role,
        &[
            ("stage", cx.stage),
            ("brief", cx.brief),
            ("tools", &tools),
            ("categories", &categories),
            (
                "style",
                match cx.style {
                    PlacementStyle::Natural => "natural",
                    PlacementStyle::Perfect => "perfect",
                },
            ),
        ],
    )
}

/// A designer backed by a chat model.
pub struct LlmDesigner {
    core: Core,
}

impl LlmDesigner {
    /// A designer on `transport`.
    pub fn new(transport: SharedTransport, config: LlmConfig) -> Self {
        LlmDesigner {
            core: Core {
                transport,
                config,
                memory: Memory::default(),
            },
        }
    }
}

impl<S> Designer<S> for LlmDesigner {
    fn design(
        &mut self,
        state: &mut S,
        request: &DesignRequest,
        cx: &mut AgentCx<'_, S>,
    ) -> Result<String, AgentError> {
        let system = system_prompt(Role::Designer, cx);
        let instruction = match request {
            DesignRequest::Initial => "Create the initial design for this stage using your tools. \
                Stop calling tools when the design is complete."
                .to_string(),
            DesignRequest::Change { instruction } => {
                format!("Improve the current design. Requested changes: {instruction}")
            }
            DesignRequest::AfterRollback {
                reason,
                instruction,
            } => format!(
                "Your last change made the design worse ({reason}) and was undone; the scene is \
                 back to the earlier checkpoint. Try a different approach. Requested changes: {instruction}"
            ),
        };
        self.core.memory.begin_turn();
        self.core.memory.push(user_text(&instruction));
        let end = tool_turn(&mut self.core, Role::Designer, &system, state, cx, None)?;
        let summary = match end {
            TurnEnd::Text(t) | TurnEnd::Submitted(Value::String(t)) => t,
            TurnEnd::Submitted(v) => v.to_string(),
        };
        self.core
            .memory
            .end_turn(&format!("{instruction:.160} -> {summary:.200}"));
        Ok(summary)
    }

    fn reset(&mut self) {
        self.core.memory.reset();
    }
}

/// A critic backed by a chat model; it hands in scores with `submit_critique`.
pub struct LlmCritic {
    core: Core,
}

impl LlmCritic {
    /// A critic on `transport`.
    pub fn new(transport: SharedTransport, config: LlmConfig) -> Self {
        LlmCritic {
            core: Core {
                transport,
                config,
                memory: Memory::default(),
            },
        }
    }
}

impl<S> Critic<S> for LlmCritic {
    fn critique(&mut self, state: &mut S, cx: &mut AgentCx<'_, S>) -> Result<Critique, AgentError> {
        let system = system_prompt(Role::Critic, cx);
        let categories = cx.categories.to_vec();
        let validate = move |v: &Value| -> Result<(), String> {
            let c: Critique =
                serde_json::from_value(v.clone()).map_err(|e| format!("not a critique: {e}"))?;
            c.validate(&categories).map_err(|e| e.to_string())
        };
        let submit = Submit {
            name: "submit_critique",
            description: "Hand in your critique: a 0-10 score with a reason for every category, and concrete issues naming object ids.",
            parameters: schema_of::<Critique>(),
            validate: &validate,
        };
        self.core.memory.begin_turn();
        self.core.memory.push(user_text(
            "Critique the current state of this stage. Inspect it with your tools, then call submit_critique.",
        ));
        let end = tool_turn(
            &mut self.core,
            Role::Critic,
            &system,
            state,
            cx,
            Some(&submit),
        )?;
        match end {
            TurnEnd::Submitted(v) => {
                let c: Critique = serde_json::from_value(v).map_err(|e| AgentError::Unusable {
                    role: "critic",
                    stage: cx.stage.to_string(),
                    message: e.to_string(),
                })?;
                self.core
                    .memory
                    .end_turn(&format!("scored {}", c.summary()));
                Ok(c)
            }
            TurnEnd::Text(t) => Err(AgentError::Unusable {
                role: "critic",
                stage: cx.stage.to_string(),
                message: format!("never submitted a valid critique ({t})"),
            }),
        }
    }

    fn reset(&mut self) {
        self.core.memory.reset();
    }
}

#[derive(Deserialize, JsonSchema)]
struct NoArgs {}
#[derive(Deserialize, JsonSchema)]
struct ChangeArgs {
    /// What to change, concretely (object ids, directions, counts).
    #[allow(dead_code)]
    instruction: String,
}
#[derive(Deserialize, JsonSchema)]
struct ResetArgs {
    /// Why the state is restored.
    #[allow(dead_code)]
    reason: String,
    /// Checkpoint index (the previous one when omitted).
    #[allow(dead_code)]
    checkpoint: Option<usize>,
}
#[derive(Deserialize, JsonSchema)]
struct StyleArgs {
    /// `natural` (small random offsets, lived-in) or `perfect` (exact alignment, showroom).
    #[allow(dead_code)]
    style: PlacementStyle,
}
#[derive(Deserialize, JsonSchema)]
struct FinishArgs {
    /// Why the stage is done.
    #[allow(dead_code)]
    reason: String,
}

/// The orchestrator's control tools in chat-completions format.
pub fn control_tools() -> Value {
    let tool = |name: &str, description: &str, parameters: Value| json!({"type": "function", "function": {"name": name, "description": description, "parameters": parameters}});
    json!([
        tool(
            "request_initial_design",
            "Ask the designer for the first design of this stage.",
            schema_of::<NoArgs>()
        ),
        tool(
            "request_design_change",
            "Ask the designer to change the current design as instructed.",
            schema_of::<ChangeArgs>()
        ),
        tool(
            "request_critique",
            "Ask the critic to score the current design; this records a checkpoint.",
            schema_of::<NoArgs>()
        ),
        tool(
            "reset_scene_to_checkpoint",
            "Restore an earlier checkpoint (when a change made things worse).",
            schema_of::<ResetArgs>()
        ),
        tool(
            "select_placement_style",
            "Choose natural or perfect alignment for the designer.",
            schema_of::<StyleArgs>()
        ),
        tool(
            "finish",
            "End the stage; the best-scoring checkpoint is kept.",
            schema_of::<FinishArgs>()
        ),
    ])
}

/// An orchestrator backed by a chat model; it answers each decision with one control tool.
pub struct LlmOrchestrator {
    core: Core,
    stage: String,
    brief: String,
}

impl LlmOrchestrator {
    /// An orchestrator on `transport`.
    pub fn new(transport: SharedTransport, config: LlmConfig) -> Self {
        LlmOrchestrator {
            core: Core {
                transport,
                config,
                memory: Memory::default(),
            },
            stage: String::new(),
            brief: String::new(),
        }
    }

    /// Sets the stage and brief used in the system prompt (called before each stage).
    pub fn set_stage(&mut self, stage: &str, brief: &str) {
        self.stage = stage.to_string();
        self.brief = brief.to_string();
    }
}

impl Orchestrator for LlmOrchestrator {
    fn decide(&mut self, view: &LoopView) -> Result<Decision, AgentError> {
        let system = prompts::render(
            &view.stage,
            Role::Orchestrator,
            &[
                ("stage", &view.stage),
                ("brief", &self.brief),
                ("max_rounds", &view.config.max_rounds.to_string()),
                (
                    "early_finish",
                    &view.config.early_finish_min_score.to_string(),
                ),
            ],
        );
        self.core.memory.begin_turn();
        self.core.memory.push(user_text(&format!(
            "Current loop state:\n{}\nCall exactly one control tool.",
            serde_json::to_string_pretty(view).unwrap_or_default()
        )));
        for _ in 0..3 {
            let request = self.core.request(&system, control_tools());
            let response = self
                .core
                .complete(&view.stage, Role::Orchestrator, &request)?;
            let message = assistant_message(&response)?;
            self.core.memory.push(message.clone());
            let call = &message["tool_calls"][0];
            let id = call["id"].as_str().unwrap_or_default().to_string();
            let name = call["function"]["name"].as_str().unwrap_or_default();
            let args: Result<Value, _> =
                serde_json::from_str(call["function"]["arguments"].as_str().unwrap_or("{}"));
            let parsed = args.map_err(|e| e.to_string()).and_then(|a| {
                serde_json::from_value::<Decision>(json!({"tool": name, "args": a}))
                    .map_err(|e| e.to_string())
            });
            match parsed {
                Ok(d) if !name.is_empty() => {
                    self.core.memory.push(
                        json!({"role": "tool", "tool_call_id": id, "content": "{\"ok\": true}"}),
                    );
                    // One decision per turn: answer any further calls as ignored.
                    for extra in message["tool_calls"]
                        .as_array()
                        .into_iter()
                        .flatten()
                        .skip(1)
                    {
                        let eid = extra["id"].as_str().unwrap_or_default();
                        self.core
                            .memory
                            .push(json!({"role": "tool", "tool_call_id": eid,
                            "content": "{\"error\": \"ignored: one decision per turn\"}"}));
                    }
                    self.core.memory.end_turn(&format!("decided {name}"));
                    return Ok(d);
                }
                other => {
                    let why = match other {
                        Err(e) => e,
                        Ok(_) => "no tool called".into(),
                    };
                    let msg = format!(
                        "Not a valid control decision ({why}). Call exactly one control tool."
                    );
                    if id.is_empty() {
                        self.core.memory.push(user_text(&msg));
                    } else {
                        self.core.memory.push(json!({"role": "tool", "tool_call_id": id, "content": json!({"error": msg}).to_string()}));
                    }
                }
            }
        }
        Err(AgentError::Unusable {
            role: "orchestrator",
            stage: view.stage.clone(),
            message: "no valid control decision after 3 tries".into(),
        })
    }

    fn rejected(&mut self, decision: &Decision, why: &str) {
        self.core.memory.push(user_text(&format!(
            "Your decision {} could not be carried out: {why}",
            serde_json::to_string(decision).unwrap_or_default()
        )));
    }

    fn reset(&mut self) {
        self.core.memory.reset();
    }
}
