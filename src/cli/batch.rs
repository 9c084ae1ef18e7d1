//! `scenesmith batch` (many scenes from a prompts file) and `scenesmith view` (a scene in the
//! browser).

use std::io::{IsTerminal, Write};
use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::Context;

use super::args::usage;
use super::commands::print_json;
use scenesmith::batch::{
    BatchError, BatchItem, BatchOptions, Progress, Status, read_items, run_batch, summarize, table,
};
use scenesmith::pipeline::GenerateOptions;

/// `scenesmith batch`.
pub(crate) struct BatchRun {
    pub(crate) prompts: PathBuf,
    pub(crate) out: PathBuf,
    pub(crate) workers: usize,
    pub(crate) only: Option<Vec<String>>,
    pub(crate) summary_only: bool,
    /// Options of every scene (prompt, seed and directory are set per scene).
    pub(crate) generate: GenerateOptions,
}

fn usage_or(e: BatchError) -> anyhow::Error {
    match e {
        BatchError::Write(_) => anyhow::Error::new(e),
        other => usage(other),
    }
}

pub(crate) fn run_batch_command(cli_json: bool, run: BatchRun) -> anyhow::Result<ExitCode> {
    let items = read_items(&run.prompts).map_err(usage_or)?;
    if run.workers == 0 {
        return Err(usage(anyhow::anyhow!("--workers must be at least 1")));
    }
    let only = run.only;
    let report = if run.summary_only {
        summarize(&items, &run.out).map_err(usage_or)?
    } else {
        eprintln!(
            "scenesmith: batch of {} scene(s) from {} -> {} ({} worker(s))",
            items.len(),
            run.prompts.display(),
            run.out.display(),
            run.workers
        );
        let bar = ProgressBar::new(&items);
        let opts = BatchOptions {
            workers: run.workers,
            generate: run.generate,
            only: only.clone(),
        };
        let report = run_batch(&items, &run.out, &opts, &|p| bar.show(p)).map_err(usage_or)?;
        bar.finish();
        report
    };
    if cli_json {
        print_json(&serde_json::to_value(&report).context("batch report")?)?;
    } else {
        eprint!("{}", table(&report));
        eprintln!("wrote {}", run.out.join("summary.jsonl").display());
    }
    // Exit status 1 when a scene of this invocation's selection failed.
    let selected = |id: &str| only.as_ref().is_none_or(|ids| ids.iter().any(|i| i == id));
    let failed = report
        .scenes
        .iter()
        .any(|s| s.status == Status::Failed && selected(&s.id));
    Ok(if failed {
        ExitCode::FAILURE
    } else {
        ExitCode::SUCCESS
    })
}

/// Progress on stderr: a bar redrawn in place on a terminal, one line per scene otherwise (a
/// log file then keeps every scene's outcome).
struct ProgressBar {
    terminal: bool,
    id_width: usize,
}

impl ProgressBar {
    const WIDTH: usize = 24;

    fn new(items: &[BatchItem]) -> ProgressBar {
        ProgressBar {
            terminal: std::io::stderr().is_terminal(),
            id_width: items.iter().map(|i| i.id.len()).max().unwrap_or(8).min(32),
        }
    }

    fn show(&self, p: Progress<'_>) {
        let filled = Self::WIDTH * p.done / p.total.max(1);
        let eta = p.elapsed / p.done as f64 * (p.total - p.done) as f64;
        let r = p.result;
        let outcome = match r.status {
            Status::Ok => format!("ok, {} objects, {:.0} s", r.objects.unwrap_or(0), r.seconds),
            _ => format!(
                "FAILED after {} attempt(s): {}",
                r.attempts,
                r.error.as_deref().unwrap_or("?")
            ),
        };
        let line = format!(
            "[{}{}] {}/{} {:<w$} {}  (elapsed {:.0} s, eta {:.0} s)",
            "#".repeat(filled),
            ".".repeat(Self::WIDTH - filled),
            p.done,
            p.total,
            r.id,
            outcome,
            p.elapsed,
            eta,
            w = self.id_width
        );
        let mut err = std::io::stderr().lock();
        // A lost progress line is no reason to stop a batch.
        let _ = if self.terminal {
            write!(err, "\r\x1b[2K{line}")
        } else {
            writeln!(err, "{line}")
        };
        let _ = err.flush();
    }

    fn finish(&self) {
        if self.terminal {
            eprintln!();
        }
    }
}

/// `scenesmith view DIR`: writes the GLB export first when the scene has none, then serves the
/// page until interrupted.
pub(crate) fn run_view(dir: &std::path::Path, port: u16) -> anyhow::Result<ExitCode> {
    use scenesmith::export::{self, ExportSet};
    use scenesmith::view::{Viewer, bundle_dir};
    let viewer = Viewer::bind(dir, &bundle_dir(), port).map_err(|e| match e {
        scenesmith::view::ViewError::Listen { .. } => anyhow::Error::new(e),
        other => usage(other),
    })?;
    if !dir.join("export/scene.glb").is_file() {
        let state = scenesmith::formats::scene_dir::load_state(dir)
            .with_context(|| format!("reading the scene in {}", dir.display()))?;
        let glb = ExportSet::parse("glb").context("the GLB export")?;
        export::write_exports(dir, &state, &glb)
            .with_context(|| format!("writing {}/export/scene.glb", dir.display()))?;
        eprintln!(
            "wrote {}/export/scene.glb (the scene had no GLB export)",
            dir.display()
        );
    }
    let addr = viewer.addr().context("the viewer's address")?;
    // The one line on stdout: scripts and tests read the address from it.
    println!("http://{addr}/");
    std::io::stdout().flush().context("stdout")?;
    eprintln!(
        "scenesmith: showing {} at http://{addr}/ (Ctrl-C stops)",
        dir.display()
    );
    viewer.serve();
    Ok(ExitCode::SUCCESS)
}
