//! Helpers shared by the integration tests.
#![allow(dead_code)]

pub mod mock_llm;

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// The repository root.
pub fn home() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// The venv interpreter the README's commands set up (`scripts/setup.sh`).
pub fn python() -> PathBuf {
    let p = home().join(".venv/bin/python");
    assert!(
        p.exists(),
        "{} is missing: run scripts/setup.sh (scripts/test.sh does)",
        p.display()
    );
    p
}

/// Runs the `scenesmith` binary with `args` and extra environment.
pub fn scenesmith(args: &[&str], env: &[(&str, &str)]) -> Output {
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_scenesmith"));
    cmd.args(args).env("SCENESMITH_HOME", home());
    for (k, v) in env {
        cmd.env(k, v);
    }
    cmd.output().expect("the scenesmith binary runs")
}

/// Stdout and stderr as one string, for assertion messages.
pub fn text(out: &Output) -> String {
    format!(
        "status {:?}\nstdout:\n{}\nstderr:\n{}",
        out.status.code(),
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    )
}

/// Runs a Python snippet with the venv interpreter; returns stdout, panics with stderr.
pub fn run_python(code: &str, args: &[&Path]) -> String {
    let mut cmd = Command::new(python());
    cmd.arg("-c").arg(code);
    for a in args {
        cmd.arg(a);
    }
    let out = cmd.output().expect("python runs");
    assert!(
        out.status.success(),
        "python failed:\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8_lossy(&out.stdout).into_owned()
}

/// The dev prompts (a copy of the shared evaluation set in `tests/fixtures/`).
pub fn dev_prompts() -> Vec<(String, String)> {
    let path = home().join("tests/fixtures/dev_prompts.jsonl");
    let text = std::fs::read_to_string(&path).expect("tests/fixtures/dev_prompts.jsonl");
    text.lines()
        .filter(|l| !l.trim().is_empty())
        .map(|l| {
            let v: serde_json::Value = serde_json::from_str(l).expect("jsonl line");
            (
                v["id"].as_str().unwrap_or_default().to_string(),
                v["prompt"].as_str().unwrap_or_default().to_string(),
            )
        })
        .collect()
}

/// One dev prompt by id.
pub fn dev_prompt(id: &str) -> String {
    dev_prompts()
        .into_iter()
        .find(|(i, _)| i == id)
        .map(|(_, p)| p)
        .unwrap_or_else(|| panic!("no dev prompt {id}"))
}

/// Generates `prompt` into `out` the quick way (no stability simulations, no renders, no
/// exports) and asserts it succeeded.
pub fn generate_quick(prompt: &str, out: &Path) {
    let r = scenesmith(
        &[
            "generate",
            prompt,
            "--out",
            out.to_str().expect("a UTF-8 path"),
            "--no-stb",
            "--no-render",
            "--export",
            "none",
        ],
        &[],
    );
    assert!(r.status.success(), "{}", text(&r));
}

/// The JSON values of a JSON-lines file.
pub fn json_lines(path: &Path) -> Vec<serde_json::Value> {
    std::fs::read_to_string(path)
        .unwrap_or_else(|e| panic!("{}: {e}", path.display()))
        .lines()
        .map(|l| serde_json::from_str(l).expect("a JSON line"))
        .collect()
}
