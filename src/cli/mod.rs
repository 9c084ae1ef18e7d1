//! The command line, split the way clap wants it: [`args`] says what is accepted (subcommands,
//! value enums, parsers), [`commands`] does each subcommand, and [`run`] dispatches and maps an
//! error to the exit code in one place (2 for a [`args::UsageError`], 1 for anything else).

pub mod args;
pub mod batch;
pub mod commands;
pub mod task;

use std::process::ExitCode;

use args::{Cli, Command, JudgeArg, UsageError};
use batch::{BatchRun, run_batch_command, run_view};
use commands::*;
use scenesmith::pipeline::BackendChoice;
use scenesmith::pipeline::GenerateOptions;
use task::{EvalJudge, TaskRun, run_robot_eval, run_task};

/// Runs one parsed command line; prints an error once, with its causes, and returns the exit
/// code.
pub fn run(cli: Cli) -> ExitCode {
    let result = match cli.command {
        Command::Generate {
            prompt,
            out,
            seed,
            no_check,
            no_render,
            resume,
            lenient,
            no_stb,
            llm,
            export,
        } => llm.choice().and_then(|backend| {
            run_generate(
                cli.json,
                GenerateOptions {
                    prompt,
                    seed,
                    out,
                    drake_check: !no_check,
                    render: !no_render,
                    exports: export,
                    backend,
                    resume,
                    lenient,
                    stb: !no_stb,
                },
            )
        }),
        Command::Export {
            dir,
            formats,
            check,
            no_write,
            seconds,
        } => run_export(cli.json, dir, formats, check, no_write, seconds),
        Command::Check {
            dir,
            threshold,
            max_col,
        } => run_check(cli.json, dir, threshold, max_col),
        Command::Doctor => run_doctor(cli.json),
        Command::Render { dir, out } => run_render(cli.json, dir, out),
        Command::Asset {
            description,
            out,
            stage,
            size,
            seed,
        } => run_asset(cli.json, description, out, stage, size, seed),
        Command::Gallery {
            out,
            only,
            columns,
            seed,
        } => run_gallery(cli.json, out, only, columns, seed),
        Command::Eval {
            dir,
            requirements: Some(file),
            ..
        } => run_requirements(cli.json, dir, file),
        Command::Eval {
            dir,
            requirements: None,
            robot_radius,
            no_stb,
            contact,
            full_stb,
        } => run_eval(cli.json, dir, robot_radius, no_stb, contact, full_stb),
        Command::Layout { prompt, seed, png } => run_layout(cli.json, &prompt, seed, png),
        Command::Task {
            task,
            scenes,
            out,
            seed,
            generate,
            attempts,
            no_stb,
            llm,
        } => llm.choice().and_then(|backend| {
            run_task(
                cli.json,
                &task,
                &out,
                TaskRun {
                    scenes,
                    seed,
                    generate,
                    attempts,
                    stb: !no_stb,
                    scene_backend: backend.clone(),
                    backend,
                },
            )
        }),
        Command::RobotEval {
            task,
            scenes,
            policy,
            out,
            seed,
            attempts,
            no_frames,
            judge,
            builtin_scenes,
            llm,
        } => llm.choice().and_then(|backend| {
            run_robot_eval(
                cli.json,
                &task,
                &out,
                TaskRun {
                    scenes,
                    seed,
                    generate: true,
                    attempts,
                    stb: false,
                    scene_backend: if builtin_scenes {
                        BackendChoice::Builtin
                    } else {
                        backend.clone()
                    },
                    backend,
                },
                policy.into_iter().map(Into::into).collect(),
                !no_frames,
                match judge {
                    JudgeArg::Builtin => EvalJudge::Builtin,
                    JudgeArg::Llm => EvalJudge::Llm,
                },
            )
        }),
        Command::Batch {
            prompts,
            out,
            workers,
            only,
            summary_only,
            no_check,
            no_render,
            no_stb,
            llm,
            export,
        } => llm.choice().and_then(|backend| {
            let mut generate = GenerateOptions::new(String::new(), &out);
            generate.drake_check = !no_check;
            generate.render = !no_render;
            generate.stb = !no_stb;
            generate.exports = export;
            generate.backend = backend;
            run_batch_command(
                cli.json,
                BatchRun {
                    prompts,
                    out,
                    workers,
                    only,
                    summary_only,
                    generate,
                },
            )
        }),
        Command::View { dir, port } => run_view(&dir, port),
    };
    match result {
        Ok(code) => code,
        Err(e) => {
            eprintln!("error: {e:#}");
            if e.downcast_ref::<UsageError>().is_some() {
                ExitCode::from(2)
            } else {
                ExitCode::from(1)
            }
        }
    }
}
