//! Client of the Drake bridge: a long-lived `python -m drake_bridge` subprocess speaking JSON
//! lines over stdio (see `drake_bridge/__init__.py` for the protocol).
//!
//! The client starts the process, checks the handshake, times requests out, and when the
//! process dies mid-request restarts it once and retries the request once.

use std::collections::VecDeque;
use std::io::{BufRead, BufReader, Write};
use std::path::{Path, PathBuf};
use std::process::{Child, ChildStdin, Command, Stdio};
use std::sync::mpsc::{Receiver, RecvTimeoutError, channel};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use serde::Deserialize;
use serde_json::{Value, json};

use super::protocol::Op;

/// Protocol version this client speaks.
pub const PROTOCOL: u64 = 1;

/// The command that installs the Python side.
pub const SETUP_HINT: &str = "run `scripts/setup.sh` (the README's commands run it for you)";

/// What can go wrong talking to the bridge.
#[derive(Debug, thiserror::Error)]
pub enum BridgeError {
    /// The Python interpreter is not there.
    #[error(
        "Python for the Drake bridge not found at {path}: {SETUP_HINT}, or set SCENESMITH_PYTHON"
    )]
    PythonMissing {
        /// Interpreter path that was tried.
        path: PathBuf,
    },
    /// The process could not be started.
    #[error("could not start the Drake bridge ({python}): {cause}")]
    Spawn {
        /// Interpreter.
        python: PathBuf,
        /// OS error.
        cause: std::io::Error,
    },
    /// The process started but did not say hello (pydrake missing, wrong version, crash).
    #[error("the Drake bridge did not start: {detail}\n{stderr}")]
    Handshake {
        /// What went wrong, with a hint.
        detail: String,
        /// Last lines the bridge wrote to stderr.
        stderr: String,
    },
    /// The process died while handling a request, also after one restart.
    #[error(
        "the Drake bridge died during `{op}` (after one restart and retry){}",
        if stderr.is_empty() { String::new() } else { format!("; its last output:\n{stderr}") }
    )]
    Died {
        /// Operation in flight.
        op: String,
        /// Last lines the bridge wrote to stderr.
        stderr: String,
    },
    /// No reply in time.
    #[error("the Drake bridge did not answer `{op}` within {seconds:.0} s")]
    Timeout {
        /// Operation in flight.
        op: String,
        /// Timeout used.
        seconds: f64,
    },
    /// The bridge answered with an error.
    #[error("Drake bridge `{op}` failed ({kind}): {message}")]
    Remote {
        /// Operation.
        op: String,
        /// Error type (`bad_request`, `file_missing`, `model_error`, `internal`).
        kind: String,
        /// Message from the bridge.
        message: String,
    },
    /// A reply that does not follow the protocol.
    #[error("Drake bridge protocol error: {0}")]
    Protocol(String),
    /// A successful reply whose result does not parse as the operation's reply type.
    #[error("the Drake bridge's reply to `{op}` does not follow the protocol: {cause}")]
    BadReply {
        /// Operation.
        op: String,
        /// What did not parse.
        cause: String,
    },
}

/// How to start the bridge.
#[derive(Debug, Clone)]
pub struct BridgeConfig {
    /// Python interpreter with pydrake installed.
    pub python: PathBuf,
    /// Directory containing the `drake_bridge` package (the repository root).
    pub home: PathBuf,
    /// Time allowed for the process to start and say hello.
    pub startup_timeout: Duration,
    /// Time allowed per request.
    pub request_timeout: Duration,
    /// Extra environment variables for the process.
    pub env: Vec<(String, String)>,
}

/// The repository root: `SCENESMITH_HOME` or the directory the crate was built from.
pub fn project_home() -> PathBuf {
    std::env::var_os("SCENESMITH_HOME")
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from(env!("CARGO_MANIFEST_DIR")))
}

impl BridgeConfig {
    /// Configuration from the environment: `SCENESMITH_PYTHON` or `<home>/.venv/bin/python`.
    pub fn from_env() -> BridgeConfig {
        let home = project_home();
        let python = std::env::var_os("SCENESMITH_PYTHON")
            .map(PathBuf::from)
            .unwrap_or_else(|| home.join(".venv/bin/python"));
        BridgeConfig {
            python,
            home,
            startup_timeout: Duration::from_secs(120),
            request_timeout: Duration::from_secs(600),
            env: Vec::new(),
        }
    }

    /// Fails fast, before any work, when the interpreter the bridge needs is missing.
    pub fn preflight(&self) -> Result<(), BridgeError> {
        if self.python.exists() {
            Ok(())
        } else {
            Err(BridgeError::PythonMissing {
                path: self.python.clone(),
            })
        }
    }
}

/// The bridge's handshake line.
#[derive(Debug, Clone, Deserialize, PartialEq)]
pub struct Hello {
    /// Protocol version.
    pub protocol: u64,
    /// Bridge package version.
    pub bridge: String,
    /// Drake version.
    pub drake: String,
    /// Python version.
    pub python: String,
}

#[derive(Deserialize)]
struct HelloLine {
    hello: Hello,
}

struct Process {
    child: Child,
    stdin: ChildStdin,
    lines: Receiver<String>,
    stderr: Arc<Mutex<VecDeque<String>>>,
}

impl Process {
    fn stderr_tail(&self) -> String {
        self.stderr
            .lock()
            .map(|q| q.iter().cloned().collect::<Vec<_>>().join("\n"))
            .unwrap_or_default()
    }

    fn kill(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

/// A running bridge.
pub struct Bridge {
    config: BridgeConfig,
    process: Option<Process>,
    hello: Hello,
    next_id: u64,
    restarts: u32,
}

fn spawn(config: &BridgeConfig) -> Result<(Process, Hello), BridgeError> {
    config.preflight()?;
    let mut cmd = Command::new(&config.python);
    cmd.arg("-m")
        .arg("drake_bridge")
        .current_dir(&config.home)
        .env("PYTHONPATH", prepend_path(&config.home))
        .env("PYTHONUNBUFFERED", "1")
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped());
    for (k, v) in &config.env {
        cmd.env(k, v);
    }
    let mut child = cmd.spawn().map_err(|source| BridgeError::Spawn {
        python: config.python.clone(),
        cause: source,
    })?;
    let (Some(stdin), Some(stdout), Some(stderr_pipe)) =
        (child.stdin.take(), child.stdout.take(), child.stderr.take())
    else {
        let _ = child.kill();
        return Err(BridgeError::Protocol(
            "could not open the bridge's pipes".into(),
        ));
    };
    let (tx, rx) = channel();
    std::thread::spawn(move || {
        for line in BufReader::new(stdout).lines() {
            let Ok(line) = line else { break };
            if tx.send(line).is_err() {
                break;
            }
        }
    });
    let stderr = Arc::new(Mutex::new(VecDeque::new()));
    let sink = Arc::clone(&stderr);
    std::thread::spawn(move || {
        for line in BufReader::new(stderr_pipe).lines() {
            let Ok(line) = line else { break };
            tracing::debug!(target: "drake_bridge", "{line}");
            if let Ok(mut q) = sink.lock() {
                q.push_back(line);
                while q.len() > 40 {
                    q.pop_front();
                }
            }
        }
    });
    let mut process = Process {
        child,
        stdin,
        lines: rx,
        stderr,
    };
    let hello_line = match process.lines.recv_timeout(config.startup_timeout) {
        Ok(line) => line,
        Err(e) => {
            // Give the stderr reader a moment to collect the traceback.
            std::thread::sleep(Duration::from_millis(200));
            let stderr = process.stderr_tail();
            process.kill();
            let detail = match e {
                RecvTimeoutError::Timeout => format!(
                    "no handshake within {:.0} s",
                    config.startup_timeout.as_secs_f64()
                ),
                RecvTimeoutError::Disconnected if stderr.contains("No module named") => {
                    format!("a Python module is missing; {SETUP_HINT}")
                }
                RecvTimeoutError::Disconnected => "the process exited".to_string(),
            };
            return Err(BridgeError::Handshake { detail, stderr });
        }
    };
    let hello = match serde_json::from_str::<HelloLine>(&hello_line) {
        Ok(h) => h.hello,
        Err(e) => {
            process.kill();
            return Err(BridgeError::Handshake {
                detail: format!("unexpected first line {hello_line:?}: {e}"),
                stderr: String::new(),
            });
        }
    };
    if hello.protocol != PROTOCOL {
        process.kill();
        return Err(BridgeError::Handshake {
            detail: format!(
                "bridge speaks protocol {}, this binary speaks {PROTOCOL}; rebuild or {SETUP_HINT}",
                hello.protocol
            ),
            stderr: String::new(),
        });
    }
    Ok((process, hello))
}

fn prepend_path(home: &Path) -> std::ffi::OsString {
    let mut paths = vec![home.to_path_buf()];
    if let Some(existing) = std::env::var_os("PYTHONPATH") {
        paths.extend(std::env::split_paths(&existing));
    }
    std::env::join_paths(paths).unwrap_or_else(|_| home.as_os_str().to_os_string())
}

enum Attempt {
    Reply(Value),
    Died,
}

impl Bridge {
    /// Starts the bridge and waits for its handshake.
    pub fn start(config: BridgeConfig) -> Result<Bridge, BridgeError> {
        let (process, hello) = spawn(&config)?;
        tracing::info!(
            "Drake bridge up: drake {} on Python {}",
            hello.drake,
            hello.python
        );
        Ok(Bridge {
            config,
            process: Some(process),
            hello,
            next_id: 1,
            restarts: 0,
        })
    }

    /// Starts a bridge configured from the environment.
    pub fn from_env() -> Result<Bridge, BridgeError> {
        Self::start(BridgeConfig::from_env())
    }

    /// The handshake of the running process.
    pub fn hello(&self) -> &Hello {
        &self.hello
    }

    /// How many times the process was restarted after dying.
    pub fn restarts(&self) -> u32 {
        self.restarts
    }

    /// OS process id of the running bridge (for tests and diagnostics).
    pub fn pid(&self) -> Option<u32> {
        self.process.as_ref().map(|p| p.child.id())
    }

    fn attempt(&mut self, op: &str, args: &Value) -> Result<Attempt, BridgeError> {
        let Some(process) = self.process.as_mut() else {
            return Ok(Attempt::Died);
        };
        let id = self.next_id;
        self.next_id += 1;
        let line = json!({"id": id, "op": op, "args": args}).to_string();
        if writeln!(process.stdin, "{line}")
            .and_then(|_| process.stdin.flush())
            .is_err()
        {
            return Ok(Attempt::Died);
        }
        let deadline = Instant::now() + self.config.request_timeout;
        loop {
            let left = deadline.saturating_duration_since(Instant::now());
            match process.lines.recv_timeout(left) {
                Ok(reply) => {
                    let v: Value = serde_json::from_str(&reply).map_err(|e| {
                        BridgeError::Protocol(format!("reply is not JSON ({e}): {reply:.200}"))
                    })?;
                    if v.get("id").and_then(Value::as_u64) != Some(id) {
                        // A stale reply from an earlier timed-out request: skip it.
                        continue;
                    }
                    return Ok(Attempt::Reply(v));
                }
                Err(RecvTimeoutError::Timeout) => {
                    process.kill();
                    self.process = None;
                    return Err(BridgeError::Timeout {
                        op: op.to_string(),
                        seconds: self.config.request_timeout.as_secs_f64(),
                    });
                }
                Err(RecvTimeoutError::Disconnected) => return Ok(Attempt::Died),
            }
        }
    }

    fn restart(&mut self) -> Result<(), BridgeError> {
        if let Some(mut p) = self.process.take() {
            p.kill();
        }
        let (process, hello) = spawn(&self.config)?;
        self.process = Some(process);
        self.hello = hello;
        self.restarts += 1;
        Ok(())
    }

    /// Runs operation `O`: sends its arguments, parses its reply. If the process dies, it is
    /// restarted and the request retried once.
    pub fn call<O: Op>(&mut self, args: &O::Args) -> Result<O::Reply, BridgeError> {
        let args = encode_args::<O>(args)?;
        let result = self.request(O::NAME, args)?;
        decode_reply::<O>(result)
    }

    /// Sends one request as JSON and returns its result as JSON, for requests that are not
    /// an [`Op`] (tests of the protocol's error handling). If the process dies, it is restarted
    /// and the request retried once.
    pub fn request(&mut self, op: &str, args: Value) -> Result<Value, BridgeError> {
        let mut reply = None;
        for attempt in 0..2 {
            if self.process.is_none() {
                self.restart()?;
            }
            match self.attempt(op, &args)? {
                Attempt::Reply(v) => {
                    reply = Some(v);
                    break;
                }
                Attempt::Died => {
                    std::thread::sleep(Duration::from_millis(100));
                    let stderr = self
                        .process
                        .as_ref()
                        .map(Process::stderr_tail)
                        .unwrap_or_default();
                    if let Some(mut p) = self.process.take() {
                        p.kill();
                    }
                    if attempt == 1 {
                        return Err(BridgeError::Died {
                            op: op.to_string(),
                            stderr,
                        });
                    }
                    tracing::warn!(
                        "Drake bridge died during `{op}`; restarting it and retrying once"
                    );
                }
            }
        }
        let reply = reply.ok_or_else(|| BridgeError::Died {
            op: op.to_string(),
            stderr: String::new(),
        })?;
        if reply.get("ok").and_then(Value::as_bool) == Some(true) {
            Ok(reply.get("result").cloned().unwrap_or(Value::Null))
        } else {
            let err = reply.get("error").cloned().unwrap_or(Value::Null);
            Err(BridgeError::Remote {
                op: op.to_string(),
                kind: err
                    .get("type")
                    .and_then(Value::as_str)
                    .unwrap_or("unknown")
                    .to_string(),
                message: err
                    .get("message")
                    .and_then(Value::as_str)
                    .unwrap_or("no message")
                    .to_string(),
            })
        }
    }
}

/// `O`'s arguments as the JSON the bridge reads.
pub(crate) fn encode_args<O: Op>(args: &O::Args) -> Result<Value, BridgeError> {
    serde_json::to_value(args).map_err(|e| {
        BridgeError::Protocol(format!("arguments of `{}` do not serialise: {e}", O::NAME))
    })
}

/// `O`'s reply from the JSON the bridge sent: a missing or mistyped field is an error naming
/// the operation.
pub(crate) fn decode_reply<O: Op>(result: Value) -> Result<O::Reply, BridgeError> {
    serde_json::from_value(result).map_err(|e| BridgeError::BadReply {
        op: O::NAME.to_string(),
        cause: e.to_string(),
    })
}

impl Drop for Bridge {
    fn drop(&mut self) {
        if let Some(mut p) = self.process.take() {
            // Closing stdin ends the server loop; kill in case it is busy.
            p.kill();
        }
    }
}
