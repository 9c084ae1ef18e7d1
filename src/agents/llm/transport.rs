//! Getting chat completions: over HTTP from any OpenAI-compatible endpoint (with retries,
//! backoff and a per-call timeout), or from a recorded log without any network.
//!
//! Every exchange is appended to `llm_log.jsonl` (request, each failed attempt, response,
//! usage), and a log replays bit for bit: the same requests get the same responses.

use std::collections::{BTreeMap, VecDeque};
use std::io::Write;
use std::path::{Path, PathBuf};
use std::time::Duration;

use serde::{Deserialize, Serialize};
use serde_json::{Value, json};

use super::{LlmConfig, LlmError};
use crate::scene::StageUsage;
use crate::util::http_body::{BodyError, read_limited};

/// Largest chat-completions reply accepted, bytes; a longer one is a failed attempt.
const MAX_REPLY_BYTES: usize = 16 << 20;

/// Which stage and role a request belongs to (for the log and accounting).
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct CallMeta {
    /// Stage name.
    pub stage: String,
    /// `designer`, `critic` or `orchestrator`.
    pub role: String,
}

/// A failed attempt before the one that counted.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Attempt {
    /// HTTP status, when there was a response.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub status: Option<u16>,
    /// What went wrong.
    pub error: String,
}

/// One line of `llm_log.jsonl`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct LogEntry {
    /// Sequence number, from 0.
    pub seq: u64,
    /// Stage and role.
    pub meta: CallMeta,
    /// The request body sent.
    pub request: Value,
    /// Failed attempts before the response (retries).
    #[serde(default)]
    pub failed_attempts: Vec<Attempt>,
    /// The response body.
    pub response: Value,
}

/// A source of chat completions.
pub trait Transport: Send {
    /// Sends one chat-completions request and returns the response body.
    fn complete(&mut self, meta: &CallMeta, request: &Value) -> Result<Value, LlmError>;
    /// Tokens, requests, retries and cost per stage so far.
    fn usage(&self) -> BTreeMap<String, StageUsage>;
}

fn account(usage: &mut BTreeMap<String, StageUsage>, config: &LlmConfig, entry: &LogEntry) {
    let u = usage.entry(entry.meta.stage.clone()).or_default();
    u.requests += 1;
    u.retries += entry.failed_attempts.len() as u64;
    let tokens = &entry.response["usage"];
    let pin = tokens["prompt_tokens"].as_u64().unwrap_or(0);
    let pout = tokens["completion_tokens"].as_u64().unwrap_or(0);
    u.prompt_tokens += pin;
    u.completion_tokens += pout;
    u.cost_usd += (pin as f64 * config.price_input_per_mtok
        + pout as f64 * config.price_output_per_mtok)
        / 1e6;
}

/// Appends log entries to a file, one JSON object per line, flushed per entry so a crash
/// loses nothing already answered.
#[derive(Debug)]
pub struct LogWriter {
    path: PathBuf,
    file: std::fs::File,
}

impl LogWriter {
    /// Opens (appending) or creates `path`.
    pub fn open(path: &Path) -> Result<LogWriter, LlmError> {
        if let Some(parent) = path.parent() {
            std::fs::create_dir_all(parent)
                .map_err(|e| LlmError::Log(format!("{}: {e}", parent.display())))?;
        }
        let file = std::fs::OpenOptions::new()
            .create(true)
            .append(true)
            .open(path)
            .map_err(|e| LlmError::Log(format!("{}: {e}", path.display())))?;
        Ok(LogWriter {
            path: path.to_path_buf(),
            file,
        })
    }

    fn write(&mut self, entry: &LogEntry) -> Result<(), LlmError> {
        let line = serde_json::to_string(entry).map_err(|e| LlmError::Log(e.to_string()))?;
        writeln!(self.file, "{line}")
            .and_then(|_| self.file.flush())
            .map_err(|e| LlmError::Log(format!("{}: {e}", self.path.display())))
    }
}

/// Chat completions over HTTP.
pub struct HttpTransport {
    config: LlmConfig,
    endpoint: String,
    api_key: Option<String>,
    client: reqwest::Client,
    runtime: tokio::runtime::Runtime,
    log: Option<LogWriter>,
    seq: u64,
    usage: BTreeMap<String, StageUsage>,
}

impl HttpTransport {
    /// A transport for `config`, logging to `log` when given.
    pub fn new(config: LlmConfig, log: Option<LogWriter>) -> Result<HttpTransport, LlmError> {
        // reqwest is built with rustls but no provider; install ring once per process.
        let _ = rustls::crypto::ring::default_provider().install_default();
        let api_key = match &config.api_key_env {
            Some(var) if !var.is_empty() => match std::env::var(var) {
                Ok(k) if !k.is_empty() => Some(k),
                _ => return Err(LlmError::MissingKey(var.clone())),
            },
            _ => None,
        };
        let client = reqwest::Client::builder()
            .timeout(Duration::from_secs_f64(config.timeout_s))
            .build()
            .map_err(|e| LlmError::Config(format!("HTTP client: {e}")))?;
        let runtime = tokio::runtime::Builder::new_current_thread()
            .enable_all()
            .build()
            .map_err(|e| LlmError::Config(format!("async runtime: {e}")))?;
        let endpoint = format!("{}/chat/completions", config.base_url.trim_end_matches('/'));
        Ok(HttpTransport {
            config,
            endpoint,
            api_key,
            client,
            runtime,
            log,
            seq: 0,
            usage: BTreeMap::new(),
        })
    }

    fn backoff(&self, attempt: u32, retry_after: Option<f64>) -> Duration {
        let base = self.config.backoff_base_s * 2f64.powi(attempt as i32);
        let wait = retry_after
            .unwrap_or(base)
            .clamp(0.0, self.config.backoff_max_s);
        Duration::from_secs_f64(wait)
    }
}

/// Whether an HTTP status is worth retrying.
fn retryable(status: u16) -> bool {
    status == 429 || status == 408 || (500..=599).contains(&status)
}

impl Transport for HttpTransport {
    fn complete(&mut self, meta: &CallMeta, request: &Value) -> Result<Value, LlmError> {
        let mut failed = Vec::new();
        for attempt in 0..=self.config.max_retries {
            let mut req = self.client.post(&self.endpoint).json(request);
            if let Some(key) = &self.api_key {
                req = req.bearer_auth(key);
            }
            let outcome = self.runtime.block_on(async {
                let resp = req.send().await?;
                let status = resp.status().as_u16();
                let retry_after = resp
                    .headers()
                    .get("retry-after")
                    .and_then(|v| v.to_str().ok())
                    .and_then(|v| v.trim().parse::<f64>().ok());
                let body = read_limited(resp, MAX_REPLY_BYTES).await?;
                let body = String::from_utf8_lossy(&body).into_owned();
                Ok::<_, BodyError>((status, retry_after, body))
            });
            let (error, status, retry_after) = match outcome {
                Ok((200..=299, _, body)) => match serde_json::from_str::<Value>(&body) {
                    Ok(response) => {
                        let entry = LogEntry {
                            seq: self.seq,
                            meta: meta.clone(),
                            request: request.clone(),
                            failed_attempts: failed,
                            response: response.clone(),
                        };
                        self.seq += 1;
                        account(&mut self.usage, &self.config, &entry);
                        if let Some(log) = self.log.as_mut() {
                            log.write(&entry)?;
                        }
                        return Ok(response);
                    }
                    Err(e) => (format!("response is not JSON: {e}"), None, None),
                },
                Ok((status, retry_after, body)) => {
                    let snippet: String = body.chars().take(300).collect();
                    if !retryable(status) {
                        return Err(LlmError::Http {
                            status,
                            body: snippet,
                        });
                    }
                    (
                        format!("HTTP {status}: {snippet}"),
                        Some(status),
                        retry_after,
                    )
                }
                Err(e) if e.is_timeout() => (
                    format!("timed out after {} s", self.config.timeout_s),
                    None,
                    None,
                ),
                Err(e) => (format!("request failed: {e}"), None, None),
            };
            tracing::warn!(
                "LLM request ({} {}) attempt {} failed: {error}",
                meta.stage,
                meta.role,
                attempt + 1
            );
            failed.push(Attempt {
                status,
                error: error.clone(),
            });
            if attempt < self.config.max_retries {
                std::thread::sleep(self.backoff(attempt, retry_after));
            }
        }
        Err(LlmError::GaveUp {
            attempts: failed.len(),
            last: failed.last().map(|a| a.error.clone()).unwrap_or_default(),
        })
    }

    fn usage(&self) -> BTreeMap<String, StageUsage> {
        self.usage.clone()
    }
}

/// Chat completions from a recorded `llm_log.jsonl`, without a network.
#[derive(Debug)]
pub struct ReplayTransport {
    config: LlmConfig,
    entries: VecDeque<LogEntry>,
    usage: BTreeMap<String, StageUsage>,
}

impl ReplayTransport {
    /// Loads a log.
    pub fn open(path: &Path, config: LlmConfig) -> Result<ReplayTransport, LlmError> {
        let text = std::fs::read_to_string(path)
            .map_err(|e| LlmError::Log(format!("{}: {e}", path.display())))?;
        let mut entries = VecDeque::new();
        for (i, line) in text
            .lines()
            .enumerate()
            .filter(|(_, l)| !l.trim().is_empty())
        {
            let e: LogEntry = serde_json::from_str(line)
                .map_err(|e| LlmError::Log(format!("{} line {}: {e}", path.display(), i + 1)))?;
            entries.push_back(e);
        }
        Ok(ReplayTransport {
            config,
            entries,
            usage: BTreeMap::new(),
        })
    }
}

impl ReplayTransport {
    /// The model named in the first recorded request.
    pub fn recorded_model(&self) -> Option<String> {
        self.entries
            .front()
            .and_then(|e| e.request["model"].as_str().map(str::to_string))
    }
}

impl Transport for ReplayTransport {
    fn complete(&mut self, meta: &CallMeta, request: &Value) -> Result<Value, LlmError> {
        let entry = self
            .entries
            .pop_front()
            .ok_or_else(|| LlmError::Replay("the log has no more responses".into()))?;
        if &entry.meta != meta || &entry.request != request {
            return Err(LlmError::Replay(format!(
                "request {} ({} {}) differs from the recorded one ({} {}); the run diverged from the log",
                entry.seq, meta.stage, meta.role, entry.meta.stage, entry.meta.role
            )));
        }
        account(&mut self.usage, &self.config, &entry);
        Ok(entry.response)
    }

    fn usage(&self) -> BTreeMap<String, StageUsage> {
        self.usage.clone()
    }
}

/// The assistant message of a chat-completions response.
pub fn assistant_message(response: &Value) -> Result<Value, LlmError> {
    let msg = &response["choices"][0]["message"];
    if msg.is_object() {
        Ok(msg.clone())
    } else {
        Err(LlmError::Malformed(format!(
            "no choices[0].message in the response: {:.300}",
            response.to_string()
        )))
    }
}

/// A text-only user message.
pub fn user_text(text: &str) -> Value {
    json!({"role": "user", "content": text})
}
