//! The agent loop every stage runs: a designer edits the scene through typed tools, a critic
//! scores it, an orchestrator decides (initial design, change, critique, rollback, finish).
//!
//! Built once here; each stage brings only its tools, categories and prompts. Two backends
//! implement the roles: LLM-backed ([`llm`]) over any OpenAI-compatible endpoint, and the
//! built-in rule-based backend of each stage (the offline default). Both call the same tools
//! through [`backend::AgentCx`], so their work lands in the same run log.

pub mod backend;
pub mod critique;
pub mod llm;
pub mod memory;
pub mod orchestrator;
pub mod prompts;
pub mod tool;

pub use backend::{
    AgentCx, AgentError, Backend, Critic, DesignRequest, Designer, LogEvent, PlacementStyle,
    RunLog, StageSummary,
};
pub use critique::{CategorySpec, Critique, Issue, Score};
pub use orchestrator::{
    BuiltinOrchestrator, Decision, Orchestrator, StageConfig, StageOutcome, StageSpec, run_stage,
};
pub use tool::{Access, ImageObservation, Role, ToolCallRecord, ToolError, ToolErrorKind, Toolbox};
