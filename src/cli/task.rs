//! `scenesmith task`: a pick-and-place task -> scene prompts (and, with --generate, checked
//! scenes).

use std::path::Path;
use std::process::ExitCode;

use anyhow::Context;

use super::args::usage;
use super::commands::print_json;
use scenesmith::agents::llm::LlmConfig;
use scenesmith::agents::llm::transport::{HttpTransport, ReplayTransport, Transport};
use scenesmith::physics::pool::BridgePool;
use scenesmith::physics::protocol::PolicyKind;
use scenesmith::pipeline::BackendChoice;
use scenesmith::task::llm::analyse_with_llm;
use scenesmith::task::robot_eval::{LlmJudge, RobotEvalOptions, robot_eval, table as robot_table};
use scenesmith::task::scenes::{SceneBuildOptions, build_scenes};
use scenesmith::task::{Predicate, ScenePrompt, TaskError, TaskSpec, analyse, prompts};
use scenesmith::util::fsx::write_atomic;

/// Options of [`run_task`] besides the task and the directory.
pub(crate) struct TaskRun {
    pub(crate) scenes: usize,
    pub(crate) seed: u64,
    pub(crate) generate: bool,
    pub(crate) attempts: u32,
    pub(crate) stb: bool,
    /// Who reads the task (and judges states with `--judge llm`).
    pub(crate) backend: BackendChoice,
    /// Who runs the scenes' stages.
    pub(crate) scene_backend: BackendChoice,
}

/// Who judges the states of `robot-eval`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum EvalJudge {
    /// The built-in geometric evaluator only.
    Builtin,
    /// A language model over the evaluator's tools, next to the built-in evaluator.
    Llm,
}

/// The model endpoint of an LLM backend and the model name, or None for the built-in one.
fn transport_of(backend: &BackendChoice) -> anyhow::Result<Option<(Box<dyn Transport>, String)>> {
    Ok(match backend {
        BackendChoice::Builtin => None,
        BackendChoice::Llm(config) => Some((
            Box::new(HttpTransport::new(config.clone(), None)?),
            config.model.clone(),
        )),
        BackendChoice::Replay(path) => {
            let t = ReplayTransport::open(path, LlmConfig::default())?;
            let model = t.recorded_model().unwrap_or_default();
            Some((Box::new(t), model))
        }
    })
}

/// Reads the task with the chosen backend.
fn read_task(task: &str, backend: &BackendChoice) -> anyhow::Result<TaskSpec> {
    let spec = match transport_of(backend)? {
        None => analyse(task),
        Some((mut t, model)) => analyse_with_llm(t.as_mut(), &model, task),
    };
    spec.map_err(|e| match e {
        TaskError::Llm(_) => anyhow::Error::new(e),
        other => usage(other),
    })
}

fn json_lines<T: serde::Serialize>(rows: &[T]) -> anyhow::Result<Vec<u8>> {
    let mut out = Vec::new();
    for r in rows {
        serde_json::to_writer(&mut out, r)?;
        out.push(b'\n');
    }
    Ok(out)
}

pub(crate) fn run_task(
    cli_json: bool,
    task: &str,
    out: &Path,
    run: TaskRun,
) -> anyhow::Result<ExitCode> {
    let (spec, prompts) = task_files(task, out, &run)?;
    eprintln!(
        "task: {} the {} {} the {}{}; rooms: {}",
        if spec.predicate == Predicate::Near {
            "move"
        } else {
            "put"
        },
        spec.target,
        spec.predicate.word(),
        spec.reference,
        spec.start
            .as_ref()
            .map_or_else(String::new, |s| format!(" (from the {s})")),
        spec.room_types.join(", ")
    );
    eprintln!("  initial state: {}", spec.initial_state);
    for p in &prompts {
        eprintln!("  {}  {}", p.id, p.prompt);
    }
    eprintln!("wrote {}/task.json and prompts.jsonl", out.display());
    if !run.generate {
        if cli_json {
            print_json(&serde_json::json!({"task": spec, "prompts": prompts}))?;
        }
        return Ok(ExitCode::SUCCESS);
    }
    let opts = SceneBuildOptions {
        attempts: run.attempts,
        stb: run.stb,
        render: false,
        backend: run.scene_backend.clone(),
    };
    let total = prompts.len();
    let mut done = 0;
    let rows = build_scenes(&spec, &prompts, out, &opts, &mut |row| {
        done += 1;
        let status = match &row.failure {
            None => format!(
                "ok ({} attempt{}; to move {}, reference {})",
                row.attempts,
                if row.attempts == 1 { "" } else { "s" },
                row.check.bindable.join(" "),
                row.check.references.join(" ")
            ),
            Some(why) => format!("UNUSABLE after {} attempts: {why}", row.attempts),
        };
        eprintln!("  [{done}/{total}] {}: {status}", row.id);
    });
    write_atomic(&out.join("scenes.jsonl"), &json_lines(&rows)?).context("writing scenes.jsonl")?;
    let usable = rows.iter().filter(|r| r.passed()).count();
    eprintln!(
        "{usable} of {total} scenes usable; wrote {}/scenes.jsonl",
        out.display()
    );
    if cli_json {
        print_json(&serde_json::json!({"task": spec, "prompts": prompts, "scenes": rows}))?;
    }
    Ok(if usable == total {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    })
}

/// Reads the task, writes task.json and prompts.jsonl; the spec and the prompts.
fn task_files(
    task: &str,
    out: &Path,
    run: &TaskRun,
) -> anyhow::Result<(TaskSpec, Vec<ScenePrompt>)> {
    let spec = read_task(task, &run.backend)?;
    if run.scenes == 0 {
        return Err(usage("--scenes must be at least 1"));
    }
    let prompts = prompts(&spec, run.scenes, run.seed);
    write_atomic(&out.join("task.json"), &serde_json::to_vec_pretty(&spec)?)
        .context("writing task.json")?;
    write_atomic(&out.join("prompts.jsonl"), &json_lines(&prompts)?)
        .context("writing prompts.jsonl")?;
    Ok((spec, prompts))
}

pub(crate) fn run_robot_eval(
    cli_json: bool,
    task: &str,
    out: &Path,
    run: TaskRun,
    policies: Vec<PolicyKind>,
    frames: bool,
    judge: EvalJudge,
) -> anyhow::Result<ExitCode> {
    if policies.is_empty() {
        return Err(usage("--policy names no policy"));
    }
    let mut judge_transport = match judge {
        EvalJudge::Builtin => None,
        EvalJudge::Llm => Some(transport_of(&run.backend)?.ok_or_else(|| {
            usage("--judge llm needs a model: --llm-base-url URL --llm-model M (or --llm-config, --replay)")
        })?),
    };
    let (spec, prompts) = task_files(task, out, &run)?;
    eprintln!(
        "robot-eval: {} the {} {} the {}; {} scenes x {} policies",
        if spec.predicate == Predicate::Near {
            "move"
        } else {
            "put"
        },
        spec.target,
        spec.predicate.word(),
        spec.reference,
        prompts.len(),
        policies.len()
    );
    let pool = BridgePool::from_env();
    let opts = RobotEvalOptions {
        policies,
        scenes: SceneBuildOptions {
            attempts: run.attempts,
            stb: run.stb,
            render: false,
            backend: run.scene_backend.clone(),
        },
        frames,
        seed: run.seed,
    };
    let llm = judge_transport.as_mut().map(|(t, model)| LlmJudge {
        transport: t.as_mut(),
        model: model.clone(),
    });
    let results = robot_eval(&spec, &prompts, out, &pool, &opts, llm, &mut |line| {
        eprintln!("  {line}");
    });
    write_atomic(&out.join("scenes.jsonl"), &json_lines(&results.scenes)?)
        .context("writing scenes.jsonl")?;
    write_atomic(
        &out.join("results.json"),
        &serde_json::to_vec_pretty(&results)?,
    )
    .context("writing results.json")?;
    if cli_json {
        print_json(&serde_json::to_value(&results)?)?;
    } else {
        eprintln!();
        eprint!("{}", robot_table(&results));
        eprintln!("wrote {}/results.json", out.display());
    }
    Ok(if results.episodes.is_empty() {
        ExitCode::FAILURE
    } else {
        ExitCode::SUCCESS
    })
}
