//! Many scenes from one file of prompts: `scenesmith batch prompts.jsonl --out DIR`.
//!
//! Each line of the file is one scene, `{"id": ..., "prompt": ..., "seed": ...}` (`id` and
//! `seed` optional). Scene `id` goes to `DIR/<id>/`, its outcome to `DIR/results/<id>.json`
//! (written atomically when the scene ends), and the whole batch to `DIR/summary.jsonl`. A
//! result file is what makes a scene finished: a rerun skips every scene whose result says it
//! succeeded with the same prompt and seed, and runs the rest, continuing a scene that was cut
//! off halfway from its last stage checkpoint. A scene that fails is tried once more (same seed,
//! from its checkpoints, so a transient failure such as a killed bridge heals and a scene stays
//! reproducible from its line) and then reported as failed.
//!
//! Several scenes run at once on worker threads (`workers`); every scene still uses the Drake
//! bridge pool the way `generate` does. The result files keep the layout independent of who ran
//! the scenes: `scripts/ray_batch.py` runs one scene per Ray task with `--only` and then writes the
//! summary with `--summary-only`.

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};
use std::sync::Mutex;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Instant;

use serde::{Deserialize, Serialize};

use crate::pipeline::{self, GenerateOptions};
use crate::util::fsx::write_atomic;

/// Attempts per scene: the first and one retry.
pub const ATTEMPTS: u32 = 2;

/// Why a batch could not run.
#[derive(Debug, thiserror::Error)]
pub enum BatchError {
    /// The prompts file could not be read.
    #[error("cannot read {path}: {source}")]
    Read {
        /// The file.
        path: PathBuf,
        /// The cause.
        source: std::io::Error,
    },
    /// A line of the prompts file is not a scene.
    #[error("{path}:{line}: {message}")]
    Line {
        /// The file.
        path: PathBuf,
        /// 1-based line number.
        line: usize,
        /// What is wrong with it.
        message: String,
    },
    /// The file has no scene at all.
    #[error("{0} holds no prompts (one JSON object per line: {{\"id\", \"prompt\", \"seed\"}})")]
    Empty(PathBuf),
    /// `--only` named scenes the file does not have.
    #[error("no line of the prompts file has the id(s) {0}")]
    UnknownIds(String),
    /// A result or the summary could not be written.
    #[error(transparent)]
    Write(#[from] crate::util::fsx::FsError),
}

/// One line of the prompts file.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct BatchItem {
    /// Scene name: the directory under the output directory.
    pub id: String,
    /// The prompt.
    pub prompt: String,
    /// Seed of the scene.
    pub seed: u64,
}

/// The line as written: every field but `prompt` optional; other fields (a category, a note)
/// are ignored, so files such as the evaluation prompt sets run as they are.
#[derive(Deserialize)]
struct Line {
    id: Option<String>,
    prompt: String,
    seed: Option<u64>,
}

/// A scene id must be one plain directory name.
fn valid_id(id: &str) -> bool {
    !id.is_empty()
        && id.len() <= 100
        && !id.starts_with('.')
        && id != "results"
        && id
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || matches!(c, '_' | '-' | '.'))
}

/// Reads the prompts file: one JSON object per non-blank line; a line without `id` is
/// `scene_<NNN>` by its position among the scenes, without `seed` seed 0. Ids must be unique
/// directory names (letters, digits, `_`, `-`, `.`; not `results`).
pub fn read_items(path: &Path) -> Result<Vec<BatchItem>, BatchError> {
    let text = std::fs::read_to_string(path).map_err(|source| BatchError::Read {
        path: path.to_path_buf(),
        source,
    })?;
    let mut items = Vec::new();
    let mut seen = BTreeSet::new();
    for (k, raw) in text.lines().enumerate() {
        let raw = raw.trim();
        if raw.is_empty() {
            continue;
        }
        let bad = |message: String| BatchError::Line {
            path: path.to_path_buf(),
            line: k + 1,
            message,
        };
        let line: Line = serde_json::from_str(raw).map_err(|e| {
            bad(format!(
                "not a scene ({e}); expected {{\"id\": \"...\", \"prompt\": \"...\", \"seed\": 0}}"
            ))
        })?;
        let id = line
            .id
            .unwrap_or_else(|| format!("scene_{:03}", items.len()));
        if !valid_id(&id) {
            return Err(bad(format!(
                "id {id:?} is not a plain directory name (letters, digits, '_', '-', '.')"
            )));
        }
        if !seen.insert(id.clone()) {
            return Err(bad(format!("id {id:?} is used by an earlier line")));
        }
        pipeline::validate_prompt(&line.prompt).map_err(|e| bad(e.to_string()))?;
        items.push(BatchItem {
            id,
            prompt: line.prompt,
            seed: line.seed.unwrap_or(0),
        });
    }
    if items.is_empty() {
        return Err(BatchError::Empty(path.to_path_buf()));
    }
    Ok(items)
}

/// How a scene ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Status {
    /// The scene was written.
    Ok,
    /// Every attempt failed.
    Failed,
    /// Not run yet (only in a summary written before the batch finished).
    Pending,
}

/// The outcome of one scene: its result file and its line in `summary.jsonl`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SceneResult {
    /// Scene id.
    pub id: String,
    /// The prompt.
    pub prompt: String,
    /// The seed.
    pub seed: u64,
    /// How it ended.
    pub status: Status,
    /// Attempts made by the run that wrote this result.
    pub attempts: u32,
    /// Objects in the scene (architecture included), from `metrics.json`.
    pub objects: Option<usize>,
    /// COL: percentage of objects in collision.
    pub col_percent: Option<f64>,
    /// STB: percentage of free objects stable under Drake's default plant (absent when the
    /// stability simulations were skipped).
    pub stb_percent: Option<f64>,
    /// Objects post-processing removed.
    pub removed: Option<usize>,
    /// Wall time of the scene (all attempts), seconds.
    pub seconds: f64,
    /// Why the last attempt failed.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub error: Option<String>,
    /// The scene directory, relative to the batch directory.
    pub dir: String,
}

impl SceneResult {
    fn pending(item: &BatchItem) -> SceneResult {
        SceneResult {
            id: item.id.clone(),
            prompt: item.prompt.clone(),
            seed: item.seed,
            status: Status::Pending,
            attempts: 0,
            objects: None,
            col_percent: None,
            stb_percent: None,
            removed: None,
            seconds: 0.0,
            error: None,
            dir: item.id.clone(),
        }
    }

    /// This result is for `item` as the file says it now.
    fn is_for(&self, item: &BatchItem) -> bool {
        self.id == item.id && self.prompt == item.prompt && self.seed == item.seed
    }
}

/// Options of [`run_batch`].
#[derive(Debug, Clone)]
pub struct BatchOptions {
    /// Scenes generated at once.
    pub workers: usize,
    /// Options of every scene; `prompt`, `seed`, `out` and `resume` are set per scene.
    pub generate: GenerateOptions,
    /// Run only these scenes (all when `None`).
    pub only: Option<Vec<String>>,
}

/// One finished scene, for a progress display.
#[derive(Debug)]
pub struct Progress<'a> {
    /// Scenes finished by this run so far, this one included.
    pub done: usize,
    /// Scenes this run has to do.
    pub total: usize,
    /// Seconds since the run started.
    pub elapsed: f64,
    /// The scene.
    pub result: &'a SceneResult,
}

/// What a batch run did.
#[derive(Debug, Clone, Serialize)]
pub struct BatchReport {
    /// Every scene of the file, in its order (finished, failed or pending).
    pub scenes: Vec<SceneResult>,
    /// Scenes this run generated (skipped ones not counted).
    pub ran: usize,
    /// Scenes skipped because an earlier run finished them.
    pub skipped: usize,
    /// Wall time of this run, seconds.
    pub wall_seconds: f64,
    /// Workers.
    pub workers: usize,
}

impl BatchReport {
    /// Scenes with the given status.
    pub fn count(&self, status: Status) -> usize {
        self.scenes.iter().filter(|s| s.status == status).count()
    }

    /// Scenes this run finished successfully per hour of wall time.
    pub fn scenes_per_hour(&self) -> Option<f64> {
        let ran_ok = self
            .scenes
            .iter()
            .filter(|s| s.status == Status::Ok && s.attempts > 0)
            .count();
        (self.ran > 0 && self.wall_seconds > 0.0)
            .then(|| ran_ok as f64 * 3600.0 / self.wall_seconds)
    }
}

fn result_path(out: &Path, id: &str) -> PathBuf {
    out.join("results").join(format!("{id}.json"))
}

/// The result an earlier run left for `item`, if it is for the same prompt and seed.
fn stored_result(out: &Path, item: &BatchItem) -> Option<SceneResult> {
    let text = std::fs::read_to_string(result_path(out, &item.id)).ok()?;
    let r: SceneResult = serde_json::from_str(&text).ok()?;
    r.is_for(item).then_some(r)
}

/// Generates the scenes of `items` under `out` that no earlier run finished (see the module
/// doc), `opts.workers` at a time, then writes `summary.jsonl`. `progress` hears each scene as
/// it ends, from the worker thread that ran it.
pub fn run_batch(
    items: &[BatchItem],
    out: &Path,
    opts: &BatchOptions,
    progress: &(dyn Fn(Progress<'_>) + Sync),
) -> Result<BatchReport, BatchError> {
    let start = Instant::now();
    let chosen: Vec<&BatchItem> = match &opts.only {
        None => items.iter().collect(),
        Some(ids) => {
            let unknown: Vec<&str> = ids
                .iter()
                .filter(|id| !items.iter().any(|it| &it.id == *id))
                .map(String::as_str)
                .collect();
            if !unknown.is_empty() {
                return Err(BatchError::UnknownIds(unknown.join(", ")));
            }
            items.iter().filter(|it| ids.contains(&it.id)).collect()
        }
    };
    let todo: Vec<&BatchItem> = chosen
        .iter()
        .copied()
        .filter(|it| stored_result(out, it).is_none_or(|r| r.status != Status::Ok))
        .collect();
    let skipped = chosen.len() - todo.len();
    let next = AtomicUsize::new(0);
    let done = AtomicUsize::new(0);
    let write_error: Mutex<Option<BatchError>> = Mutex::new(None);
    let workers = opts.workers.clamp(1, todo.len().max(1));
    std::thread::scope(|s| {
        for _ in 0..workers {
            s.spawn(|| {
                loop {
                    let k = next.fetch_add(1, Ordering::SeqCst);
                    let Some(item) = todo.get(k) else { break };
                    let result = run_scene(item, out, &opts.generate);
                    if let Err(e) = write_result(out, &result)
                        && let Ok(mut slot) = write_error.lock()
                    {
                        slot.get_or_insert(e);
                    }
                    let n = done.fetch_add(1, Ordering::SeqCst) + 1;
                    progress(Progress {
                        done: n,
                        total: todo.len(),
                        elapsed: start.elapsed().as_secs_f64(),
                        result: &result,
                    });
                }
            });
        }
    });
    if let Some(e) = write_error.into_inner().ok().flatten() {
        return Err(e);
    }
    let mut report = summarize(items, out)?;
    report.ran = todo.len();
    report.skipped = skipped;
    report.wall_seconds = start.elapsed().as_secs_f64();
    report.workers = workers;
    Ok(report)
}

/// Collects the result of every scene of `items` (pending where none is stored) and writes
/// `summary.jsonl`, one line per scene in the file's order.
pub fn summarize(items: &[BatchItem], out: &Path) -> Result<BatchReport, BatchError> {
    let scenes: Vec<SceneResult> = items
        .iter()
        .map(|it| stored_result(out, it).unwrap_or_else(|| SceneResult::pending(it)))
        .collect();
    let mut lines = Vec::new();
    for s in &scenes {
        // A SceneResult is plain data: serialising it cannot fail.
        lines.extend(serde_json::to_vec(s).unwrap_or_default());
        lines.push(b'\n');
    }
    write_atomic(&out.join("summary.jsonl"), &lines)?;
    Ok(BatchReport {
        scenes,
        ran: 0,
        skipped: 0,
        wall_seconds: 0.0,
        workers: 0,
    })
}

fn write_result(out: &Path, result: &SceneResult) -> Result<(), BatchError> {
    let bytes = serde_json::to_vec_pretty(result).unwrap_or_default();
    write_atomic(&result_path(out, &result.id), &bytes)?;
    Ok(())
}

/// Generates one scene: up to [`ATTEMPTS`] runs, each resuming from the previous one's
/// checkpoints. A panic inside the pipeline counts as a failed attempt, not a lost batch.
fn run_scene(item: &BatchItem, out: &Path, template: &GenerateOptions) -> SceneResult {
    let start = Instant::now();
    let mut opts = template.clone();
    opts.prompt = item.prompt.clone();
    opts.seed = item.seed;
    opts.out = out.join(&item.id);
    opts.resume = true;
    let mut result = SceneResult::pending(item);
    for attempt in 1..=ATTEMPTS {
        result.attempts = attempt;
        let outcome =
            std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| pipeline::generate(&opts)));
        match outcome {
            Ok(Ok(summary)) => {
                let m = &summary.metrics;
                result.status = Status::Ok;
                result.objects = Some(m.counts.total);
                result.col_percent = Some(m.col.percent);
                result.stb_percent = m.stb.as_ref().map(|s| s.percent);
                result.removed = Some(m.removed.removed);
                result.error = None;
                break;
            }
            Ok(Err(e)) => {
                result.status = Status::Failed;
                result.error = Some(e.to_string());
                if !retry_helps(&e) {
                    break;
                }
            }
            Err(panic) => {
                result.status = Status::Failed;
                let what = panic
                    .downcast_ref::<String>()
                    .map(String::as_str)
                    .or_else(|| panic.downcast_ref::<&str>().copied())
                    .unwrap_or("unknown panic");
                result.error = Some(format!("internal error: {what}"));
            }
        }
    }
    result.seconds = start.elapsed().as_secs_f64();
    result
}

/// A refused prompt fails the same way every time; anything else may be transient.
fn retry_helps(e: &pipeline::PipelineError) -> bool {
    !matches!(
        e,
        pipeline::PipelineError::EmptyPrompt
            | pipeline::PipelineError::UnusablePrompt(_)
            | pipeline::PipelineError::NotUnderstood(_)
    )
}

fn opt(v: Option<f64>, digits: usize) -> String {
    v.map(|x| format!("{x:.digits$}"))
        .unwrap_or_else(|| "-".into())
}

/// The summary table: one row per scene, then totals.
pub fn table(report: &BatchReport) -> String {
    let mut s = format!(
        "{:<24} {:<7} {:>7} {:>7} {:>7} {:>7} {:>8} {:>4}\n",
        "scene", "status", "objects", "COL %", "STB %", "removed", "time s", "try"
    );
    for r in &report.scenes {
        let status = match r.status {
            Status::Ok => "ok",
            Status::Failed => "FAILED",
            Status::Pending => "pending",
        };
        s += &format!(
            "{:<24} {:<7} {:>7} {:>7} {:>7} {:>7} {:>8.1} {:>4}\n",
            r.id,
            status,
            r.objects
                .map(|n| n.to_string())
                .unwrap_or_else(|| "-".into()),
            opt(r.col_percent, 2),
            opt(r.stb_percent, 1),
            r.removed
                .map(|n| n.to_string())
                .unwrap_or_else(|| "-".into()),
            r.seconds,
            r.attempts
        );
    }
    if report.workers == 0 {
        // A summary of the results on disk: no run to describe.
        s += &format!(
            "{} ok, {} failed, {} pending (results on disk)\n",
            report.count(Status::Ok),
            report.count(Status::Failed),
            report.count(Status::Pending)
        );
        return s + &failures(report);
    }
    s += &format!(
        "{} ok, {} failed, {} pending; this run: {} generated, {} skipped (finished earlier), {:.0} s wall, {} worker(s)",
        report.count(Status::Ok),
        report.count(Status::Failed),
        report.count(Status::Pending),
        report.ran,
        report.skipped,
        report.wall_seconds,
        report.workers
    );
    if let Some(rate) = report.scenes_per_hour() {
        s += &format!(", {rate:.1} scenes/hour");
    }
    s.push('\n');
    s + &failures(report)
}

/// One line per failed scene with its reason.
fn failures(report: &BatchReport) -> String {
    report
        .scenes
        .iter()
        .filter(|r| r.status == Status::Failed)
        .map(|r| {
            format!(
                "  {} failed: {}\n",
                r.id,
                r.error.as_deref().unwrap_or("no reason recorded")
            )
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn file(text: &str) -> (tempfile::TempDir, PathBuf) {
        let dir = tempfile::tempdir().expect("temp dir");
        let path = dir.path().join("prompts.jsonl");
        std::fs::write(&path, text).expect("write prompts");
        (dir, path)
    }

    #[test]
    fn lines_become_items_with_default_ids_and_seeds() {
        let (_d, path) = file(
            "{\"id\": \"bed\", \"prompt\": \"a bedroom\", \"seed\": 7}\n\n{\"prompt\": \"a kitchen\", \"category\": \"x\"}\n",
        );
        let items = read_items(&path).expect("items");
        assert_eq!(items.len(), 2);
        assert_eq!(
            (items[0].id.as_str(), items[0].seed),
            ("bed", 7),
            "{items:?}"
        );
        assert_eq!((items[1].id.as_str(), items[1].seed), ("scene_001", 0));
    }

    #[test]
    fn bad_lines_are_named_by_number() {
        for (text, needle) in [
            ("{\"prompt\": \"a bedroom\"}\nnot json\n", ":2:"),
            ("{\"promt\": \"a bedroom\"}\n", "missing field `prompt`"),
            (
                "{\"id\": \"../x\", \"prompt\": \"a bedroom\"}\n",
                "directory name",
            ),
            (
                "{\"id\": \"results\", \"prompt\": \"a bedroom\"}\n",
                "directory name",
            ),
            (
                "{\"id\": \"a\", \"prompt\": \"a bedroom\"}\n{\"id\": \"a\", \"prompt\": \"a den\"}\n",
                "earlier line",
            ),
            ("{\"prompt\": \"   \"}\n", ":1:"),
        ] {
            let (_d, path) = file(text);
            let err = read_items(&path).expect_err(text).to_string();
            assert!(err.contains(needle), "{text:?}: {err}");
        }
        let (_d, path) = file("\n\n");
        assert!(matches!(read_items(&path), Err(BatchError::Empty(_))));
    }

    #[test]
    fn stored_results_count_only_for_the_same_prompt_and_seed() {
        let dir = tempfile::tempdir().expect("temp dir");
        let item = BatchItem {
            id: "a".into(),
            prompt: "a bedroom".into(),
            seed: 3,
        };
        let mut r = SceneResult::pending(&item);
        r.status = Status::Ok;
        r.attempts = 1;
        write_result(dir.path(), &r).expect("write");
        assert_eq!(stored_result(dir.path(), &item), Some(r));
        let changed = BatchItem {
            seed: 4,
            ..item.clone()
        };
        assert_eq!(stored_result(dir.path(), &changed), None);
        let report = summarize(&[item, changed], dir.path()).expect("summary");
        assert_eq!(report.count(Status::Ok), 1);
        let text = std::fs::read_to_string(dir.path().join("summary.jsonl")).expect("summary");
        assert_eq!(text.lines().count(), 2);
        assert!(text.contains("\"pending\""), "{text}");
    }
}
