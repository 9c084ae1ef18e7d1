//! `scenesmith._native`: the Rust library behind the Python package `scenesmith`.
//!
//! Three functions, each the library call the CLI's subcommand makes, with the GIL released
//! while it works (a scene takes tens of seconds; other Python threads keep running). Results
//! cross as JSON text, which `scenesmith/__init__.py` turns into a `Scene` or plain dicts, so
//! the Python side reads the same fields as `--json` and the files on disk. Errors become
//! `PromptError` (a prompt the reader refuses: the CLI's exit status 2) or `ScenesmithError`
//! (anything else), with the CLI's message.

use std::path::PathBuf;

use pyo3::create_exception;
use pyo3::exceptions::PyException;
use pyo3::prelude::*;

use scenesmith::eval::{self, EvalOptions, StabilityOptions};
use scenesmith::export::{ExportSet, write_exports};
use scenesmith::physics::BridgePool;
use scenesmith::pipeline::{self, GenerateOptions, PipelineError};

create_exception!(
    _native,
    ScenesmithError,
    PyException,
    "A scenesmith operation failed; the message is the CLI's."
);
create_exception!(
    _native,
    PromptError,
    ScenesmithError,
    "The prompt was refused (empty, not words, or nothing in it the reader understands)."
);

/// `error: cause: cause ...`, the way the CLI prints an error with its causes.
fn chain(context: &str, e: &dyn std::error::Error) -> String {
    let mut text = format!("{context}: {e}");
    let mut source = e.source();
    while let Some(s) = source {
        let s_text = s.to_string();
        if !text.contains(&s_text) {
            text += &format!(": {s_text}");
        }
        source = s.source();
    }
    text
}

fn failed(context: &str, e: &dyn std::error::Error) -> PyErr {
    ScenesmithError::new_err(chain(context, e))
}

fn to_json<T: serde::Serialize>(value: &T) -> PyResult<String> {
    serde_json::to_string(value).map_err(|e| failed("encoding the result", &e))
}

/// Generates a scene into `out`; returns the run's summary as JSON (what `generate --json`
/// prints).
#[pyfunction]
#[pyo3(signature = (prompt, out, seed=0, render=true, stb=true, drake_check=true, exports="all", lenient=false, resume=false))]
#[allow(clippy::too_many_arguments)]
fn generate(
    py: Python<'_>,
    prompt: String,
    out: PathBuf,
    seed: u64,
    render: bool,
    stb: bool,
    drake_check: bool,
    exports: &str,
    lenient: bool,
    resume: bool,
) -> PyResult<String> {
    let mut opts = GenerateOptions::new(prompt, out);
    opts.seed = seed;
    opts.render = render;
    opts.stb = stb;
    opts.drake_check = drake_check;
    opts.exports = ExportSet::parse(exports).map_err(|e| failed("exports", &e))?;
    opts.lenient = lenient;
    opts.resume = resume;
    match py.detach(|| pipeline::generate(&opts)) {
        Ok(summary) => to_json(&summary),
        Err(
            e @ (PipelineError::EmptyPrompt
            | PipelineError::UnusablePrompt(_)
            | PipelineError::NotUnderstood(_)),
        ) => Err(PromptError::new_err(e.to_string())),
        Err(e) => Err(failed(
            "generate failed; the output directory was left as it was",
            &e,
        )),
    }
}

/// Computes the metrics of the scene in `dir`, writes `metrics.json` and returns it as JSON
/// (what `scenesmith eval DIR` does; `stb=False` skips the stability simulations).
#[pyfunction]
#[pyo3(signature = (dir, stb=true))]
fn evaluate(py: Python<'_>, dir: PathBuf, stb: bool) -> PyResult<String> {
    let opts = EvalOptions {
        stability: stb.then(StabilityOptions::default),
        ..EvalOptions::default()
    };
    let metrics = py.detach(|| {
        let pool = stb.then(BridgePool::from_env);
        let metrics = eval::evaluate_dir(&dir, pool.as_ref(), &opts)?;
        eval::write_metrics(&dir, &metrics)?;
        Ok::<_, eval::EvalError>(metrics)
    });
    match metrics {
        Ok(m) => to_json(&m),
        Err(e) => Err(failed(&format!("evaluating {}", dir.display()), &e)),
    }
}

/// Writes the exports `formats` ("mjcf,usd,glb", "all") of the scene in `dir`; returns the
/// written exports as JSON.
#[pyfunction]
#[pyo3(signature = (dir, formats="all"))]
fn export(py: Python<'_>, dir: PathBuf, formats: &str) -> PyResult<String> {
    let set = ExportSet::parse(formats).map_err(|e| failed("formats", &e))?;
    let written = py.detach(|| {
        let state = scenesmith::formats::scene_dir::load_state(&dir)
            .map_err(|e| chain(&format!("reading the scene in {}", dir.display()), &e))?;
        write_exports(&dir, &state, &set)
            .map_err(|e| chain(&format!("exporting {}", dir.display()), &e))
    });
    match written {
        Ok(w) => to_json(&w),
        Err(message) => Err(ScenesmithError::new_err(message)),
    }
}

#[pymodule]
fn _native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(generate, m)?)?;
    m.add_function(wrap_pyfunction!(evaluate, m)?)?;
    m.add_function(wrap_pyfunction!(export, m)?)?;
    m.add("ScenesmithError", m.py().get_type::<ScenesmithError>())?;
    m.add("PromptError", m.py().get_type::<PromptError>())?;
    Ok(())
}
