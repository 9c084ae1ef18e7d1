//! The interfaces every backend implements (designer, critic, orchestrator), the context they
//! act through, the run log every tool call lands in, which backend runs the stages and what a
//! stage kept.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};
use serde_json::Value;

use super::critique::{CategorySpec, Critique};
use super::llm::{LlmConfig, SharedTransport};
use super::tool::{Role, ToolCallRecord, ToolError, Toolbox};

/// How precisely objects are aligned: `perfect` snaps to walls and grids, `natural` allows the
/// small offsets and angles of a lived-in room.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema, Default)]
#[serde(rename_all = "snake_case")]
pub enum PlacementStyle {
    /// Small random offsets and rotations, like a room people use.
    #[default]
    Natural,
    /// Exact alignment, like a showroom.
    Perfect,
}

/// What the orchestrator asks the designer to do.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum DesignRequest {
    /// First design of the stage.
    Initial,
    /// Improve the current design.
    Change {
        /// What to change.
        instruction: String,
    },
    /// The last change made things worse and was rolled back; try a different approach.
    AfterRollback {
        /// Why it was rolled back.
        reason: String,
        /// What to change instead.
        instruction: String,
    },
}

/// One entry of the run log (`agent_log.jsonl`): the same for every backend.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "event", rename_all = "snake_case")]
pub enum LogEvent {
    /// A tool call by a designer or critic.
    ToolCall(ToolCallRecord),
    /// An orchestrator decision.
    Decision {
        /// Stage.
        stage: String,
        /// The decision as JSON (`{"tool": ..., "args": ...}`).
        decision: Value,
    },
    /// A critique was recorded as a checkpoint.
    Checkpoint {
        /// Stage.
        stage: String,
        /// Checkpoint index.
        index: usize,
        /// Sum of scores.
        total: u32,
        /// The critique.
        critique: Critique,
    },
    /// The state was restored from a checkpoint.
    Rollback {
        /// Stage.
        stage: String,
        /// Restored checkpoint.
        to: usize,
        /// Why.
        reason: String,
    },
    /// The stage ended.
    StageEnd {
        /// Stage.
        stage: String,
        /// The checkpoint kept as the stage's result (`None`: never critiqued).
        kept: Option<usize>,
        /// Its total score.
        total: Option<u32>,
        /// Critique rounds run.
        rounds: usize,
    },
}

/// Everything that happened in a run, in order.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct RunLog {
    /// The events.
    pub events: Vec<LogEvent>,
}

impl RunLog {
    /// JSON lines, one event per line.
    pub fn to_jsonl(&self) -> String {
        let mut out = String::new();
        for e in &self.events {
            out.push_str(&serde_json::to_string(e).unwrap_or_default());
            out.push('\n');
        }
        out
    }

    /// Tool calls of one stage and role.
    pub fn calls<'a>(
        &'a self,
        stage: &'a str,
        role: Role,
    ) -> impl Iterator<Item = &'a ToolCallRecord> + 'a {
        self.events.iter().filter_map(move |e| match e {
            LogEvent::ToolCall(c) if c.stage == stage && c.role == role => Some(c),
            _ => None,
        })
    }
}

/// What an agent acts through: the stage's tools, its categories, the log, the style.
pub struct AgentCx<'a, S> {
    /// Stage name.
    pub stage: &'a str,
    /// The stage's tools.
    pub toolbox: &'a Toolbox<S>,
    /// The stage's critic categories.
    pub categories: &'a [CategorySpec],
    /// Text describing the task of this stage (prompt, room, constraints) for prompts.
    pub brief: &'a str,
    /// Placement style chosen by the orchestrator.
    pub style: PlacementStyle,
    /// Design attempt number within the stage (0 for the initial design).
    pub attempt: u32,
    /// The run log.
    pub log: &'a mut RunLog,
}

impl<S> AgentCx<'_, S> {
    /// Calls a tool as `role`, logging the call and its outcome.
    pub fn call(
        &mut self,
        state: &mut S,
        role: Role,
        tool: &str,
        args: Value,
    ) -> Result<Value, ToolError> {
        let result = self.toolbox.call(state, role, tool, args.clone());
        self.log.events.push(LogEvent::ToolCall(ToolCallRecord {
            stage: self.stage.to_string(),
            role,
            tool: tool.to_string(),
            args,
            result: result.as_ref().ok().cloned(),
            error: result.as_ref().err().cloned(),
        }));
        result
    }
}

/// Errors that end an agent's turn.
#[derive(Debug, thiserror::Error)]
pub enum AgentError {
    /// The language-model endpoint failed for good.
    #[error(transparent)]
    Llm(#[from] super::llm::LlmError),
    /// The agent produced nothing usable (e.g. a critic that never scores).
    #[error("{role} in stage {stage}: {message}")]
    Unusable {
        /// Role.
        role: &'static str,
        /// Stage.
        stage: String,
        /// What went wrong.
        message: String,
    },
}

/// Proposes edits through tools.
pub trait Designer<S> {
    /// Runs one design turn on `state`.
    fn design(
        &mut self,
        state: &mut S,
        request: &DesignRequest,
        cx: &mut AgentCx<'_, S>,
    ) -> Result<String, AgentError>;
    /// Forgets everything (between stages).
    fn reset(&mut self) {}
}

/// Scores the current state using observe and verify tools.
pub trait Critic<S> {
    /// Critiques `state` against the stage's categories.
    fn critique(&mut self, state: &mut S, cx: &mut AgentCx<'_, S>) -> Result<Critique, AgentError>;
    /// Forgets everything (between stages).
    fn reset(&mut self) {}
}

/// Which agents run the stages.
#[derive(Clone)]
pub enum Backend {
    /// The offline rule-based designers and measurement-based critics.
    Builtin,
    /// An OpenAI-compatible chat model for every role.
    Llm {
        /// Shared transport (HTTP or replay).
        transport: SharedTransport,
        /// Model settings.
        config: LlmConfig,
    },
}

impl Backend {
    /// Name recorded in `scene.json`.
    pub fn name(&self) -> String {
        match self {
            Backend::Builtin => "builtin".into(),
            Backend::Llm { config, .. } => format!("llm:{}", config.model),
        }
    }
}

/// What a stage kept, for the run summary.
#[derive(Debug, Clone, serde::Serialize)]
pub struct StageSummary {
    /// Stage name.
    pub stage: String,
    /// Room.
    pub room: String,
    /// Supporting entity (manipuland stage).
    pub entity: Option<String>,
    /// Scores of the kept checkpoint.
    pub critique: Option<Critique>,
    /// Critique rounds run.
    pub rounds: usize,
    /// Wall time of the stage (agents and tools), seconds; not written to `scene.json`.
    pub seconds: f64,
}
