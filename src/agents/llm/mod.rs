//! The LLM backend: designer, critic and orchestrator driven by any OpenAI-compatible
//! chat-completions endpoint with tool calling (OpenAI, vLLM, Ollama, llama.cpp server).

mod agents;
pub mod transport;

use std::path::Path;

use serde::{Deserialize, Serialize};

pub use agents::{IMAGE_KEY, LlmCritic, LlmDesigner, LlmOrchestrator, SharedTransport};
pub use transport::{HttpTransport, ReplayTransport, Transport};

/// What can go wrong talking to a model.
#[derive(Debug, thiserror::Error)]
pub enum LlmError {
    /// The environment variable meant to hold the API key is unset or empty.
    #[error("environment variable {0} (the LLM API key) is not set")]
    MissingKey(String),
    /// Bad configuration.
    #[error("LLM configuration: {0}")]
    Config(String),
    /// A non-retryable HTTP error (400, 401, 404, ...).
    #[error("LLM endpoint answered HTTP {status}: {body}")]
    Http {
        /// Status code.
        status: u16,
        /// Start of the body.
        body: String,
    },
    /// Retries exhausted.
    #[error("LLM endpoint failed {attempts} times; last error: {last}")]
    GaveUp {
        /// Attempts made.
        attempts: usize,
        /// Last error.
        last: String,
    },
    /// A response without the expected structure.
    #[error("malformed LLM response: {0}")]
    Malformed(String),
    /// The log could not be written or read.
    #[error("LLM log: {0}")]
    Log(String),
    /// Replay found a request that was not recorded.
    #[error("replay: {0}")]
    Replay(String),
}

/// How to reach the model and what it costs.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct LlmConfig {
    /// Base URL including the API version, e.g. `https://api.openai.com/v1` or
    /// `http://localhost:11434/v1`; requests go to `<base_url>/chat/completions`.
    pub base_url: String,
    /// Model name.
    pub model: String,
    /// Name of the environment variable holding the API key (none for local servers).
    pub api_key_env: Option<String>,
    /// Per-call timeout, seconds.
    pub timeout_s: f64,
    /// Retries after the first attempt on 429, 5xx, timeouts and connection errors.
    pub max_retries: u32,
    /// First backoff, seconds (doubles per retry).
    pub backoff_base_s: f64,
    /// Longest single backoff, seconds.
    pub backoff_max_s: f64,
    /// Sampling temperature.
    pub temperature: f64,
    /// Most model calls per designer/critic turn.
    pub max_steps_per_turn: usize,
    /// The same failing tool call this many times ends the turn.
    pub loop_limit: usize,
    /// USD per million input tokens (for the cost column).
    pub price_input_per_mtok: f64,
    /// USD per million output tokens.
    pub price_output_per_mtok: f64,
}

impl Default for LlmConfig {
    fn default() -> Self {
        LlmConfig {
            base_url: "http://localhost:11434/v1".into(),
            model: String::new(),
            api_key_env: None,
            timeout_s: 120.0,
            max_retries: 4,
            backoff_base_s: 1.0,
            backoff_max_s: 30.0,
            temperature: 0.0,
            max_steps_per_turn: 40,
            loop_limit: 3,
            price_input_per_mtok: 0.0,
            price_output_per_mtok: 0.0,
        }
    }
}

impl LlmConfig {
    /// Reads a JSON config file (missing fields take defaults).
    pub fn from_file(path: &Path) -> Result<LlmConfig, LlmError> {
        let text = std::fs::read_to_string(path)
            .map_err(|e| LlmError::Config(format!("{}: {e}", path.display())))?;
        serde_json::from_str(&text)
            .map_err(|e| LlmError::Config(format!("{}: {e}", path.display())))
    }
}
