//! `scenesmith task`: a pick-and-place task -> scene prompts (and, with --generate, checked
//! scenes).

use std::path::Path;
use std::process::ExitCode;

use anyhow::Context;

use super::args::usage;
use super::commands::print_json;
use scenesmith::task::scenes::{SceneBuildOptions, build_scenes};
use scenesmith::task::{analyse, prompts};
use scenesmith::util::fsx::write_atomic;

/// Options of [`run_task`] besides the task and the directory.
pub(crate) struct TaskRun {
    pub(crate) scenes: usize,
    pub(crate) seed: u64,
    pub(crate) generate: bool,
    pub(crate) attempts: u32,
    pub(crate) stb: bool,
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
    let spec = analyse(task).map_err(usage)?;
    if run.scenes == 0 {
        return Err(usage("--scenes must be at least 1"));
    }
    let prompts = prompts(&spec, run.scenes, run.seed);
    write_atomic(&out.join("task.json"), &serde_json::to_vec_pretty(&spec)?)
        .context("writing task.json")?;
    write_atomic(&out.join("prompts.jsonl"), &json_lines(&prompts)?)
        .context("writing prompts.jsonl")?;
    eprintln!(
        "task: {} the {} {} the {}{}; rooms: {}",
        match spec.predicate {
            scenesmith::task::Predicate::Near => "move",
            _ => "put",
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
