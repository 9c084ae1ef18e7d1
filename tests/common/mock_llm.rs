//! A loopback mock of the chat-completions API: a real HTTP/1.1 server on 127.0.0.1 whose
//! answers come from a script, so the LLM backend is tested over real HTTP without a model.
#![allow(dead_code)]

use std::collections::{BTreeMap, VecDeque};
use std::io::{BufRead, BufReader, Read, Write};
use std::net::{TcpListener, TcpStream};
use std::sync::{Arc, Mutex};
use std::thread::JoinHandle;

use serde_json::{Value, json};

/// A scripted reply: HTTP status and body.
#[derive(Debug, Clone)]
pub struct Reply {
    pub status: u16,
    pub body: String,
}

impl Reply {
    pub fn ok(body: Value) -> Reply {
        Reply {
            status: 200,
            body: body.to_string(),
        }
    }
    pub fn status(status: u16, text: &str) -> Reply {
        Reply {
            status,
            body: json!({"error": {"message": text}}).to_string(),
        }
    }
}

/// An assistant message calling tools: `(name, arguments-as-raw-string)`.
pub fn tool_calls(calls: &[(&str, &str)]) -> Value {
    let calls: Vec<Value> = calls
        .iter()
        .enumerate()
        .map(|(i, (name, args))| json!({"id": format!("call_{i}"), "type": "function", "function": {"name": name, "arguments": args}}))
        .collect();
    completion(json!({"role": "assistant", "content": null, "tool_calls": calls}))
}

/// An assistant message with text only.
pub fn text(t: &str) -> Value {
    completion(json!({"role": "assistant", "content": t}))
}

fn completion(message: Value) -> Value {
    json!({
        "id": "chatcmpl-mock",
        "object": "chat.completion",
        "model": "mock",
        "choices": [{"index": 0, "message": message, "finish_reason": "stop"}],
        "usage": {"prompt_tokens": 100, "completion_tokens": 10, "total_tokens": 110}
    })
}

/// Scripted replies per (stage, role), taken in order; a fallback answers anything unscripted.
#[derive(Default)]
pub struct Script {
    pub queues: BTreeMap<(String, String), VecDeque<Reply>>,
    /// Replies served before any scripted one (e.g. 429 then 500), regardless of stage.
    pub preface: VecDeque<Reply>,
    /// Every request body received, in order.
    pub received: Vec<Value>,
}

impl Script {
    pub fn push(&mut self, stage: &str, role: &str, reply: Value) {
        self.queues
            .entry((stage.into(), role.into()))
            .or_default()
            .push_back(Reply::ok(reply));
    }
}

/// Stage and role of a request, read from its system prompt ("You are the designer of the
/// furniture stage ...").
pub fn stage_and_role(request: &Value) -> (String, String) {
    let system = request["messages"][0]["content"]
        .as_str()
        .unwrap_or_default();
    let words: Vec<&str> = system.split_whitespace().collect();
    let role = words.get(3).copied().unwrap_or_default().to_string();
    let stage = words.get(6).copied().unwrap_or_default().to_string();
    (stage, role)
}

/// The default behaviour for unscripted requests: orchestrators design, critique, finish;
/// designers stop; critics give 9 in every category of the request's submit tool.
fn fallback(request: &Value) -> Value {
    let (_, role) = stage_and_role(request);
    match role.as_str() {
        "orchestrator" => {
            let user = request["messages"]
                .as_array()
                .and_then(|m| m.iter().rev().find(|x| x["role"] == "user"))
                .and_then(|m| m["content"].as_str())
                .unwrap_or_default()
                .to_string();
            let json_start = user.find('{').unwrap_or(0);
            let json_end = user.rfind('}').map(|i| i + 1).unwrap_or(user.len());
            let view: Value =
                serde_json::from_str(&user[json_start..json_end]).unwrap_or(Value::Null);
            if view["has_design"] == false {
                tool_calls(&[("request_initial_design", "{}")])
            } else if view["changed_since_critique"] == true {
                tool_calls(&[("request_critique", "{}")])
            } else {
                tool_calls(&[("finish", "{\"reason\": \"good enough\"}")])
            }
        }
        "critic" => {
            // Score every category named in the system prompt's category list.
            let system = request["messages"][0]["content"]
                .as_str()
                .unwrap_or_default();
            let cats: Vec<String> = system
                .split("## Categories")
                .nth(1)
                .unwrap_or_default()
                .split("## ")
                .next()
                .unwrap_or_default()
                .lines()
                .filter_map(|l| l.strip_prefix("- "))
                .filter_map(|l| l.split(':').next())
                .map(str::to_string)
                .collect();
            let scores: Vec<Value> = cats
                .iter()
                .map(|c| json!({"category": c, "score": 9, "reason": "fine"}))
                .collect();
            tool_calls(&[(
                "submit_critique",
                &json!({"scores": scores, "issues": []}).to_string(),
            )])
        }
        _ => text("Nothing to change."),
    }
}

/// The running server.
pub struct MockServer {
    pub base_url: String,
    pub script: Arc<Mutex<Script>>,
    _thread: JoinHandle<()>,
}

fn read_request(stream: &mut TcpStream) -> Option<Value> {
    let mut reader = BufReader::new(stream.try_clone().ok()?);
    let mut len = 0usize;
    loop {
        let mut line = String::new();
        if reader.read_line(&mut line).ok()? == 0 {
            return None;
        }
        let l = line.trim();
        if l.is_empty() {
            break;
        }
        if let Some(v) = l.to_ascii_lowercase().strip_prefix("content-length:") {
            len = v.trim().parse().ok()?;
        }
    }
    let mut body = vec![0; len];
    reader.read_exact(&mut body).ok()?;
    serde_json::from_slice(&body).ok()
}

impl MockServer {
    pub fn start(script: Script) -> MockServer {
        let listener = TcpListener::bind("127.0.0.1:0").expect("bind loopback");
        let port = listener.local_addr().unwrap().port();
        let script = Arc::new(Mutex::new(script));
        let shared = script.clone();
        let thread = std::thread::spawn(move || {
            for stream in listener.incoming() {
                let Ok(mut stream) = stream else { continue };
                let Some(request) = read_request(&mut stream) else {
                    continue;
                };
                let reply = {
                    let mut s = shared.lock().unwrap();
                    s.received.push(request.clone());
                    if let Some(r) = s.preface.pop_front() {
                        r
                    } else {
                        let key = stage_and_role(&request);
                        match s.queues.get_mut(&key).and_then(|q| q.pop_front()) {
                            Some(r) => r,
                            None => Reply::ok(fallback(&request)),
                        }
                    }
                };
                let reason = if reply.status == 200 { "OK" } else { "Error" };
                let head = format!(
                    "HTTP/1.1 {} {reason}\r\nContent-Type: application/json\r\nContent-Length: {}\r\nConnection: close\r\n\r\n",
                    reply.status,
                    reply.body.len()
                );
                let _ = stream.write_all(head.as_bytes());
                let _ = stream.write_all(reply.body.as_bytes());
                let _ = stream.flush();
            }
        });
        MockServer {
            base_url: format!("http://127.0.0.1:{port}/v1"),
            script,
            _thread: thread,
        }
    }
}
