//! Tools: typed functions over a stage's state that designers, critics and orchestrators call.
//!
//! A tool has a typed argument struct and a typed result, both with a JSON schema generated from
//! the types, a one-paragraph description an LLM reads, and an access class. Calls arrive as
//! JSON (from an LLM or from the built-in designer, through the same path); bad arguments,
//! unknown tools, tools outside the caller's role and even a panicking tool come back as a
//! structured [`ToolError`], never as a crash.

use std::panic::AssertUnwindSafe;

use schemars::JsonSchema;
use schemars::generate::SchemaSettings;
use serde::de::DeserializeOwned;
use serde::{Deserialize, Serialize};
use serde_json::{Value, json};

/// The result of an observation tool that returns a picture (a plan, a room view), for agents
/// with image input. The LLM backend moves the PNG out of the tool result into an image
/// message (tool messages carry text only); the built-in agents do not ask for pictures.
#[derive(Debug, Serialize, JsonSchema)]
pub struct ImageObservation {
    /// What the picture shows.
    pub description: String,
    /// The PNG, base64 (the key is [`crate::agents::llm::IMAGE_KEY`]).
    pub image_png_base64: String,
}

impl ImageObservation {
    /// A picture from PNG bytes.
    pub fn new(description: impl Into<String>, png: &[u8]) -> ImageObservation {
        ImageObservation {
            description: description.into(),
            image_png_base64: crate::util::base64::encode(png),
        }
    }
}

/// What a tool may do, which decides who may call it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Hash, PartialOrd, Ord)]
#[serde(rename_all = "snake_case")]
pub enum Access {
    /// Reads the state (lists, renders, measurements).
    Observe,
    /// Changes the state.
    Modify,
    /// Checks feasibility (collisions, reachability) without changing anything.
    Verify,
    /// Drives the stage loop (orchestrator only).
    Control,
}

/// Who is calling.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, Hash, PartialOrd, Ord)]
#[serde(rename_all = "snake_case")]
pub enum Role {
    /// Proposes edits: observe + modify + verify.
    Designer,
    /// Scores: observe + verify.
    Critic,
    /// Decides: control.
    Orchestrator,
}

impl Role {
    /// Whether this role may call tools of `access`.
    pub fn allows(self, access: Access) -> bool {
        match self {
            Role::Designer => matches!(access, Access::Observe | Access::Modify | Access::Verify),
            Role::Critic => matches!(access, Access::Observe | Access::Verify),
            Role::Orchestrator => access == Access::Control,
        }
    }

    /// `designer`, `critic`, `orchestrator`.
    pub fn as_str(self) -> &'static str {
        match self {
            Role::Designer => "designer",
            Role::Critic => "critic",
            Role::Orchestrator => "orchestrator",
        }
    }
}

/// Why a call failed; returned to the caller (an LLM reads `message`).
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize, Hash)]
#[serde(rename_all = "snake_case")]
pub enum ToolErrorKind {
    /// No tool by that name.
    UnknownTool,
    /// The caller's role may not use the tool.
    NotAllowed,
    /// Arguments are not valid JSON or do not match the schema.
    BadArguments,
    /// The tool ran and refused (e.g. no room for the object there).
    Failed,
    /// The tool crashed; a bug, reported instead of taking the run down.
    Internal,
}

/// A structured tool error.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize, thiserror::Error)]
#[error("{kind:?}: {message}")]
pub struct ToolError {
    /// Category.
    pub kind: ToolErrorKind,
    /// What went wrong and, where possible, what to do instead.
    pub message: String,
}

impl ToolError {
    /// A refusal by the tool itself.
    pub fn failed(message: impl Into<String>) -> Self {
        ToolError {
            kind: ToolErrorKind::Failed,
            message: message.into(),
        }
    }

    /// Arguments that make no sense (beyond what the schema can say).
    pub fn bad_args(message: impl Into<String>) -> Self {
        ToolError {
            kind: ToolErrorKind::BadArguments,
            message: message.into(),
        }
    }
}

/// Name, description, access and schemas of a tool.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ToolSpec {
    /// Unique name (`snake_case`).
    pub name: String,
    /// What the tool does, for the model.
    pub description: String,
    /// Access class.
    pub access: Access,
    /// JSON schema of the arguments object.
    pub parameters: Value,
    /// JSON schema of the result.
    pub result: Value,
}

type Handler<S> = Box<dyn Fn(&mut S, Value) -> Result<Value, ToolError> + Send + Sync>;

/// The tools of one stage over state `S`.
pub struct Toolbox<S> {
    tools: Vec<(ToolSpec, Handler<S>)>,
}

impl<S> Default for Toolbox<S> {
    fn default() -> Self {
        Toolbox { tools: Vec::new() }
    }
}

impl<S> std::fmt::Debug for Toolbox<S> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_list()
            .entries(self.tools.iter().map(|(s, _)| &s.name))
            .finish()
    }
}

/// JSON schema of `T` with sub-schemas inlined and the keys chat APIs reject removed.
pub fn schema_of<T: JsonSchema>() -> Value {
    let generator = SchemaSettings::draft07()
        .with(|s| s.inline_subschemas = true)
        .into_generator();
    let mut v = generator.into_root_schema_for::<T>().to_value();
    strip_schema(&mut v);
    v
}

/// Removes `$schema`, `format` and `title` from every (sub)schema, but never a property that
/// happens to be called `format` or `title`.
fn strip_schema(v: &mut Value) {
    match v {
        Value::Object(map) => {
            map.remove("$schema");
            map.remove("format");
            map.remove("title");
            for (key, child) in map.iter_mut() {
                match (key.as_str(), child) {
                    ("properties" | "$defs" | "definitions", Value::Object(named)) => {
                        named.values_mut().for_each(strip_schema);
                    }
                    (_, child) => strip_schema(child),
                }
            }
        }
        Value::Array(items) => items.iter_mut().for_each(strip_schema),
        _ => {}
    }
}

impl<S> Toolbox<S> {
    /// An empty toolbox.
    pub fn new() -> Self {
        Self::default()
    }

    /// Registers a tool. `A` is the argument struct (deserialised from the call's JSON object),
    /// `R` the result.
    pub fn add<A, R, F>(&mut self, name: &str, description: &str, access: Access, f: F)
    where
        A: DeserializeOwned + JsonSchema + 'static,
        R: Serialize + JsonSchema + 'static,
        F: Fn(&mut S, A) -> Result<R, ToolError> + Send + Sync + 'static,
    {
        let spec = ToolSpec {
            name: name.to_string(),
            description: description.to_string(),
            access,
            parameters: schema_of::<A>(),
            result: schema_of::<R>(),
        };
        let handler: Handler<S> = Box::new(move |state, args| {
            // A missing or null arguments object means "no arguments".
            let args = if args.is_null() { json!({}) } else { args };
            let parsed: A = serde_json::from_value(args).map_err(|e| ToolError {
                kind: ToolErrorKind::BadArguments,
                message: format!("arguments do not match the schema: {e}"),
            })?;
            let out = f(state, parsed)?;
            serde_json::to_value(out).map_err(|e| ToolError {
                kind: ToolErrorKind::Internal,
                message: format!("result could not be serialised: {e}"),
            })
        });
        self.tools.retain(|(s, _)| s.name != name);
        self.tools.push((spec, handler));
    }

    /// The spec of a tool.
    pub fn spec(&self, name: &str) -> Option<&ToolSpec> {
        self.tools
            .iter()
            .find(|(s, _)| s.name == name)
            .map(|(s, _)| s)
    }

    /// Specs of the tools `role` may call, in registration order.
    pub fn specs_for(&self, role: Role) -> Vec<&ToolSpec> {
        self.tools
            .iter()
            .map(|(s, _)| s)
            .filter(|s| role.allows(s.access))
            .collect()
    }

    /// The tools `role` may call in the chat-completions `tools` format.
    pub fn openai_tools(&self, role: Role) -> Value {
        Value::Array(
            self.specs_for(role)
                .into_iter()
                .map(|s| {
                    json!({
                        "type": "function",
                        "function": {
                            "name": s.name,
                            "description": s.description,
                            "parameters": s.parameters,
                        }
                    })
                })
                .collect(),
        )
    }

    /// Calls a tool by name with JSON arguments on behalf of `role`.
    pub fn call(
        &self,
        state: &mut S,
        role: Role,
        name: &str,
        args: Value,
    ) -> Result<Value, ToolError> {
        let Some((spec, handler)) = self.tools.iter().find(|(s, _)| s.name == name) else {
            let known: Vec<&str> = self
                .specs_for(role)
                .into_iter()
                .map(|s| s.name.as_str())
                .collect();
            return Err(ToolError {
                kind: ToolErrorKind::UnknownTool,
                message: format!("there is no tool {name:?}; available: {}", known.join(", ")),
            });
        };
        if !role.allows(spec.access) {
            return Err(ToolError {
                kind: ToolErrorKind::NotAllowed,
                message: format!(
                    "the {} may not call {name:?} ({:?} tool)",
                    role.as_str(),
                    spec.access
                ),
            });
        }
        match std::panic::catch_unwind(AssertUnwindSafe(|| handler(state, args))) {
            Ok(result) => result,
            Err(panic) => {
                let what = panic
                    .downcast_ref::<&str>()
                    .map(|s| s.to_string())
                    .or_else(|| panic.downcast_ref::<String>().cloned())
                    .unwrap_or_else(|| "unknown panic".into());
                tracing::error!("tool {name} panicked: {what}");
                Err(ToolError {
                    kind: ToolErrorKind::Internal,
                    message: format!("tool {name} failed internally: {what}"),
                })
            }
        }
    }

    /// Number of tools.
    pub fn len(&self) -> usize {
        self.tools.len()
    }

    /// True when empty.
    pub fn is_empty(&self) -> bool {
        self.tools.is_empty()
    }
}

/// One executed tool call, as every backend logs it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ToolCallRecord {
    /// Stage name.
    pub stage: String,
    /// Caller.
    pub role: Role,
    /// Tool name.
    pub tool: String,
    /// Arguments as given.
    pub args: Value,
    /// Result, when it succeeded.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub result: Option<Value>,
    /// Error, when it failed.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub error: Option<ToolError>,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(Default)]
    struct Counter {
        n: i64,
    }

    /// Add to the counter.
    #[derive(Deserialize, JsonSchema)]
    struct AddArgs {
        /// Amount to add.
        amount: i64,
    }

    #[derive(Serialize, JsonSchema)]
    struct Total {
        total: i64,
    }

    #[derive(Deserialize, JsonSchema)]
    struct NoArgs {}

    fn toolbox() -> Toolbox<Counter> {
        let mut t = Toolbox::new();
        t.add(
            "add",
            "Adds an amount.",
            Access::Modify,
            |s: &mut Counter, a: AddArgs| {
                if a.amount > 100 {
                    return Err(ToolError::failed("amount too large; use at most 100"));
                }
                s.n += a.amount;
                Ok(Total { total: s.n })
            },
        );
        t.add(
            "read",
            "Reads the total.",
            Access::Observe,
            |s: &mut Counter, _: NoArgs| Ok(Total { total: s.n }),
        );
        t.add(
            "boom",
            "Crashes.",
            Access::Verify,
            |_: &mut Counter, _: NoArgs| -> Result<Total, ToolError> { panic!("kaboom") },
        );
        t
    }

    #[test]
    fn calls_and_roles() {
        let t = toolbox();
        let mut s = Counter::default();
        let r = t
            .call(&mut s, Role::Designer, "add", json!({"amount": 5}))
            .unwrap();
        assert_eq!(r, json!({"total": 5}));
        let e = t
            .call(&mut s, Role::Critic, "add", json!({"amount": 5}))
            .unwrap_err();
        assert_eq!(e.kind, ToolErrorKind::NotAllowed);
        assert_eq!(s.n, 5, "a refused call changes nothing");
        assert!(t.call(&mut s, Role::Critic, "read", Value::Null).is_ok());
    }

    #[test]
    fn bad_calls_are_structured_errors() {
        let t = toolbox();
        let mut s = Counter::default();
        let e = t
            .call(&mut s, Role::Designer, "add", json!({"amount": "five"}))
            .unwrap_err();
        assert_eq!(e.kind, ToolErrorKind::BadArguments);
        let e = t
            .call(&mut s, Role::Designer, "fly", json!({}))
            .unwrap_err();
        assert_eq!(e.kind, ToolErrorKind::UnknownTool);
        assert!(
            e.message.contains("add"),
            "lists the real tools: {}",
            e.message
        );
        let e = t
            .call(&mut s, Role::Designer, "add", json!({"amount": 1000}))
            .unwrap_err();
        assert_eq!(e.kind, ToolErrorKind::Failed);
        let e = t
            .call(&mut s, Role::Designer, "boom", json!({}))
            .unwrap_err();
        assert_eq!(e.kind, ToolErrorKind::Internal);
        assert!(e.message.contains("kaboom"));
    }

    #[test]
    fn schemas_are_chat_api_ready() {
        let t = toolbox();
        let tools = t.openai_tools(Role::Designer);
        let add = &tools[0]["function"];
        assert_eq!(add["name"], "add");
        assert_eq!(add["parameters"]["type"], "object");
        assert_eq!(add["parameters"]["properties"]["amount"]["type"], "integer");
        assert_eq!(
            add["parameters"]["properties"]["amount"]["description"],
            "Amount to add."
        );
        assert!(add["parameters"].get("$schema").is_none());
        assert_eq!(
            t.openai_tools(Role::Orchestrator).as_array().unwrap().len(),
            0
        );
    }
}
