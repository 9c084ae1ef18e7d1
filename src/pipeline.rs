//! One run end to end: prompt -> layout -> furnishing -> write -> Drake check, and the
//! stand-alone `check` of a scene directory; [`asset`] is the `asset` command's run (route one
//! description, write its asset directories).
//!
//! A run builds everything in a staging directory next to the output and only replaces the
//! output when every step, including the Drake check, succeeded.

pub mod asset;

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::time::Instant;

use serde::Serialize;
use serde_json::json;

use crate::agents::llm::{
    HttpTransport, LlmConfig, LlmError, ReplayTransport, SharedTransport, Transport,
};
use crate::agents::{AgentError, Backend, RunLog, StageSummary};
use crate::assets::AssetError;
use crate::eval::{self, EvalError, EvalOptions, Metrics};
use crate::formats::FormatError;
use crate::formats::scene_dir;
use crate::geometry::GeometryError;
use crate::layout;
use crate::physics::collision;
use crate::physics::postprocess::{self, PostProcessOptions, PostProcessReport};
use crate::physics::{Bridge, BridgeError, BridgePool, CheckSummary, PhysicsError, check_dir};

use crate::scene::{ObjectKind, Scene, sanitize_name};
use crate::stages::checkpoint::{CheckpointStore, DirCheckpoints, NoCheckpoints};
use crate::stages::run::furnish_room_resumable;
use crate::state::SceneState;
use crate::util::fsx::{FsError, StagingDir};

/// The LLM transcript in a scene directory.
const LLM_LOG: &str = "llm_log.jsonl";

/// Longest prompt accepted, in characters.
pub const MAX_PROMPT_CHARS: usize = 8000;

/// What can stop a run.
#[derive(Debug, thiserror::Error)]
pub enum PipelineError {
    /// Nothing to work from.
    #[error(
        "the prompt is empty: describe a room, e.g. \"a kitchen with a table and four chairs\""
    )]
    EmptyPrompt,
    /// A prompt that cannot describe a scene.
    #[error("the prompt cannot describe a scene: {0}")]
    UnusablePrompt(String),
    /// A prompt the built-in reader does not understand.
    #[error(
        "the built-in reader understood no room and no object in the prompt ({0}). It reads \
         English; an LLM backend (--llm-base-url) reads any language. --lenient builds a \
         default room anyway."
    )]
    NotUnderstood(String),
    /// Output location problem.
    #[error(transparent)]
    Fs(#[from] FsError),
    /// Writing files failed.
    #[error(transparent)]
    Format(#[from] FormatError),
    /// An asset could not be built.
    #[error(transparent)]
    Asset(#[from] AssetError),
    /// Geometry failed validation.
    #[error(transparent)]
    Geometry(#[from] GeometryError),
    /// The Drake bridge failed.
    #[error(transparent)]
    Bridge(#[from] BridgeError),
    /// Rendering the views failed.
    #[error(transparent)]
    Render(#[from] crate::render::RenderError),
    /// Post-processing (projection, settling) failed.
    #[error(transparent)]
    Physics(#[from] PhysicsError),
    /// The metrics could not be computed or written.
    #[error(transparent)]
    Eval(#[from] EvalError),
    /// The written scene does not load or is not collision-free.
    #[error("scene check failed: {0}")]
    CheckFailed(String),
    /// The thread running the scene check panicked.
    #[error("scene check failed: its thread stopped unexpectedly")]
    CheckThread,
    /// An export (MJCF, USD, GLB) could not be written.
    #[error(transparent)]
    Export(#[from] crate::export::ExportError),
    /// An agent failed for good (e.g. the LLM endpoint is unreachable after retries).
    #[error(transparent)]
    Agent(#[from] AgentError),
    /// The LLM backend could not be set up.
    #[error(transparent)]
    Llm(#[from] LlmError),
    /// A failure after some stages finished; `--resume` continues from there.
    #[error(
        "{error} ({finished} finished stages were saved; run the same command with --resume to continue)"
    )]
    Resumable {
        /// Stages saved.
        finished: usize,
        /// The failure.
        error: Box<PipelineError>,
    },
    /// A failed run of the LLM backend, whose transcript was kept.
    #[error("{error} (the LLM transcript of this run is kept in {})", transcript.display())]
    TranscriptKept {
        /// The failure.
        error: Box<PipelineError>,
        /// Where `llm_log.jsonl` of the failed run now is.
        transcript: PathBuf,
    },
}

/// Which agents to run.
#[derive(Debug, Clone, Default)]
pub enum BackendChoice {
    /// The built-in offline backend.
    #[default]
    Builtin,
    /// An OpenAI-compatible endpoint.
    Llm(LlmConfig),
    /// Replay a recorded `llm_log.jsonl` without a network.
    Replay(PathBuf),
}

/// Options of `generate`.
#[derive(Debug, Clone)]
pub struct GenerateOptions {
    /// The user's prompt.
    pub prompt: String,
    /// Seed of every random choice.
    pub seed: u64,
    /// Output directory.
    pub out: PathBuf,
    /// Run the Drake check before committing the output.
    pub drake_check: bool,
    /// Write the annotated views into `<out>/renders/`.
    pub render: bool,
    /// Exports written into `export/` (MJCF, USD, GLB; all by default).
    pub exports: crate::export::ExportSet,
    /// Which agents run the stages.
    pub backend: BackendChoice,
    /// Continue after the stages an earlier, failed run of the same request finished.
    pub resume: bool,
    /// Build a default room for a prompt the built-in reader cannot read (another
    /// language, gibberish) instead of refusing it.
    pub lenient: bool,
    /// Run the stability simulations of `metrics.json` (both contact models; most of a run's
    /// time). Without them `stb` and `stb_point` are absent; `scenesmith eval DIR` adds them.
    pub stb: bool,
}

impl GenerateOptions {
    /// What the CLI does by default: seed 0, the Drake check, renders, every export, the
    /// built-in backend, no resume.
    pub fn new(prompt: impl Into<String>, out: impl Into<PathBuf>) -> GenerateOptions {
        GenerateOptions {
            prompt: prompt.into(),
            seed: 0,
            out: out.into(),
            drake_check: true,
            render: true,
            exports: crate::export::ExportSet::all(),
            backend: BackendChoice::Builtin,
            resume: false,
            lenient: false,
            stb: true,
        }
    }
}

/// Identifies a request for checkpoints: the same tool version, prompt, seed and backend.
fn fingerprint(opts: &GenerateOptions) -> String {
    let backend = match &opts.backend {
        BackendChoice::Builtin => "builtin".to_string(),
        BackendChoice::Llm(c) => format!("llm {} {}", c.base_url, c.model),
        BackendChoice::Replay(p) => format!("replay {}", p.display()),
    };
    let key = format!(
        "{}\n{}\n{}\n{backend}",
        env!("CARGO_PKG_VERSION"),
        opts.prompt,
        opts.seed
    );
    blake3::hash(key.as_bytes()).to_hex().to_string()
}

/// Wall time per step, seconds.
pub type Timings = BTreeMap<String, f64>;

/// What a run produced.
#[derive(Debug, Clone, Serialize)]
pub struct GenerateSummary {
    /// Output directory.
    pub out: PathBuf,
    /// Where the directory this run replaced was kept, because it held files scenesmith did
    /// not write.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub kept_previous: Option<PathBuf>,
    /// Room ids and types.
    pub rooms: Vec<(String, String)>,
    /// Object count per kind.
    pub objects_per_kind: BTreeMap<String, usize>,
    /// Object count per category.
    pub objects_per_category: BTreeMap<String, usize>,
    /// Scores kept by every stage run.
    pub stages: Vec<StageSummary>,
    /// The objects the room plans request explicitly (the reader's plan, not the prompt):
    /// (noun, planned, present).
    pub plan_coverage: Vec<(String, u32, u32)>,
    /// Nouns of the prompt no generator knows.
    pub unknown_nouns: Vec<String>,
    /// Every noun the reader read and what became of it.
    pub nouns: Vec<crate::prompt::NounReport>,
    /// What the reader and the room plans capped, in words for the user.
    pub notes: Vec<String>,
    /// Penetrating pairs found by the in-process (parry3d) check.
    pub rust_penetrating_pairs: usize,
    /// Drake check, when run.
    pub check: Option<CheckSummary>,
    /// What post-processing did (projections, settling, removals).
    pub post_process: PostProcessReport,
    /// The metrics written to `metrics.json`.
    pub metrics: Metrics,
    /// Exports written.
    pub exports: Vec<crate::export::WrittenExport>,
    /// Wall time per step, seconds.
    pub timings: Timings,
}

/// Checks a prompt before any work: non-empty, bounded, made of words.
pub fn validate_prompt(prompt: &str) -> Result<(), PipelineError> {
    let trimmed = prompt.trim();
    if trimmed.is_empty() {
        return Err(PipelineError::EmptyPrompt);
    }
    if trimmed.chars().count() > MAX_PROMPT_CHARS {
        return Err(PipelineError::UnusablePrompt(format!(
            "{} characters; the limit is {MAX_PROMPT_CHARS}",
            trimmed.chars().count()
        )));
    }
    if !trimmed.chars().any(char::is_alphabetic) {
        return Err(PipelineError::UnusablePrompt(
            "it contains no words".to_string(),
        ));
    }
    Ok(())
}

/// Package name for a scene written to `out`: the directory name as `[a-z0-9_]`.
pub fn package_name_for(out: &Path) -> String {
    let stem = out
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| "scene".into());
    sanitize_name(&stem)
}

fn timed<T>(timings: &mut Timings, step: &str, f: impl FnOnce() -> T) -> T {
    let t0 = Instant::now();
    let out = f();
    timings.insert(step.to_string(), t0.elapsed().as_secs_f64());
    out
}

/// What [`build_scene`] produced besides the scene.
#[derive(Debug, Clone, Default)]
pub struct BuildReport {
    /// Every tool call, decision and checkpoint.
    pub log: RunLog,
    /// Scores kept by every stage run.
    pub stages: Vec<StageSummary>,
    /// The objects the room plans request explicitly (the reader's plan, not the prompt):
    /// (noun, planned, present).
    pub plan_coverage: Vec<(String, u32, u32)>,
    /// Nouns of the prompt no generator knows.
    pub unknown_nouns: Vec<String>,
    /// Every noun the reader read and what became of it (lexicon, routed, stand-in,
    /// dropped and why).
    pub nouns: Vec<crate::prompt::NounReport>,
    /// What the reader and the room plans capped, in words for the user.
    pub notes: Vec<String>,
}

/// Builds the scene of a prompt in memory (no files): layout, then every placement stage of
/// every room through the agent loop with `backend`.
pub fn build_scene(
    prompt_text: &str,
    seed: u64,
    package_name: &str,
    backend: &Backend,
) -> Result<(SceneState, BuildReport), PipelineError> {
    build_scene_with(prompt_text, seed, package_name, backend, &mut NoCheckpoints)
}

/// [`build_scene`] with stage checkpoints: finished stages found in `store` are skipped, every
/// stage that finishes is saved.
pub fn build_scene_with(
    prompt_text: &str,
    seed: u64,
    package_name: &str,
    backend: &Backend,
    store: &mut dyn CheckpointStore,
) -> Result<(SceneState, BuildReport), PipelineError> {
    validate_prompt(prompt_text)?;
    let mut scene = Scene::new(prompt_text, seed, package_name);
    for role in ["designer", "critic", "orchestrator"] {
        scene
            .provenance
            .backends
            .insert(role.into(), backend.name());
    }
    scene
        .provenance
        .backends
        .insert("assets".into(), "procedural".into());
    scene
        .provenance
        .backends
        .insert("physics".into(), "drake".into());
    let mut report = BuildReport::default();
    let reading = crate::prompt::read(prompt_text);
    report.nouns = reading.nouns;
    report.notes = reading.notes;
    // The layout stage: rooms, walls, doors, windows, materials and per-room prompts.
    let mut state = match store.load("layout") {
        Some((saved, log)) => {
            report.log = log;
            saved
        }
        None => {
            let layout = layout::stage::run_layout(prompt_text, seed, backend, &mut report.log)?;
            let mut state = SceneState::new(scene);
            crate::state::install_rooms(&mut state, &layout.rooms)?;
            report.stages.push(layout.summary);
            store.save("layout", &state, &report.log);
            state
        }
    };
    // Then every room's placement stages, on the room's own prompt.
    let is_house = layout::brief::read(prompt_text).is_house;
    let rooms = state.scene.rooms.clone();
    let mut requested: Vec<(String, u32)> = Vec::new();
    for room in &rooms {
        let plan = layout::spec::room_plan(
            &room.room_type,
            &room.prompt,
            is_house.then_some(prompt_text),
        );
        for n in &plan.notes {
            report.notes.push(format!("{}: {n}", room.id));
        }
        for noun in &plan.unknown {
            if !report.unknown_nouns.contains(noun) {
                report.unknown_nouns.push(noun.clone());
            }
        }
        for (noun, n) in plan.requested() {
            match requested.iter_mut().find(|(x, _)| *x == noun) {
                Some((_, total)) => *total += n,
                None => requested.push((noun, n)),
            }
        }
        let (next, stages) =
            furnish_room_resumable(state, &room.id, plan, backend, &mut report.log, store)?;
        state = next;
        report.stages.extend(stages);
    }
    report.plan_coverage = requested
        .into_iter()
        .map(|(noun, wanted)| {
            let present = state
                .scene
                .objects
                .iter()
                .filter(|o| crate::assets::router::naming::object_is(&state.scene, &noun, o))
                .count() as u32;
            (noun, wanted, present)
        })
        .collect();
    Ok((state, report))
}

/// Sets up the backend of a run; the LLM log goes to `log_dir/llm_log.jsonl`.
fn make_backend(
    choice: &BackendChoice,
    log_dir: &Path,
) -> Result<(Backend, Option<SharedTransport>), PipelineError> {
    let shared = |t: Box<dyn Transport>| -> SharedTransport {
        std::sync::Arc::new(std::sync::Mutex::new(t))
    };
    Ok(match choice {
        BackendChoice::Builtin => (Backend::Builtin, None),
        BackendChoice::Llm(config) => {
            let log = crate::agents::llm::transport::LogWriter::open(&log_dir.join(LLM_LOG))?;
            let t = shared(Box::new(HttpTransport::new(config.clone(), Some(log))?));
            (
                Backend::Llm {
                    transport: t.clone(),
                    config: config.clone(),
                },
                Some(t),
            )
        }
        BackendChoice::Replay(path) => {
            let replay = ReplayTransport::open(path, LlmConfig::default())?;
            let config = LlmConfig {
                model: replay.recorded_model().unwrap_or_default(),
                ..LlmConfig::default()
            };
            // Keep the replayed log with the scene, like a recorded run.
            let _ = std::fs::copy(path, log_dir.join(LLM_LOG));
            let t = shared(Box::new(replay));
            (
                Backend::Llm {
                    transport: t.clone(),
                    config,
                },
                Some(t),
            )
        }
    })
}

/// What [`finish_run`] hands back: the committed scene and everything the summary reports.
struct Finished {
    out: crate::util::fsx::Committed,
    state: SceneState,
    report: BuildReport,
    rust_pairs: Vec<collision::PairPenetration>,
    check: Option<CheckSummary>,
    post_process: PostProcessReport,
    metrics: Metrics,
    exports: Vec<crate::export::WrittenExport>,
}

/// Writes a built scene into the staging directory, checks it in Drake and commits it.
fn finish_run(
    opts: &GenerateOptions,
    staging: StagingDir,
    transport: &Option<SharedTransport>,
    mut state: SceneState,
    report: BuildReport,
    timings: &mut Timings,
) -> Result<Finished, PipelineError> {
    if let Some(t) = transport
        && let Ok(t) = t.lock()
    {
        state.scene.llm_usage = t.usage();
    }

    // --- physics post-processing (projection, settling, fallen-object removal) ---
    // Without the Drake check (`--no-check`) only the native projections run.
    let pool = opts.drake_check.then(BridgePool::from_env);
    // What the prompt asked for: an asked-for object post-processing removes is placed again.
    let asked: Vec<(String, u32)> = report
        .plan_coverage
        .iter()
        .map(|(noun, wanted, _)| (noun.clone(), *wanted))
        .collect();
    let post_process = timed(timings, "post_process", || {
        postprocess::post_process_placing_again(
            &mut state,
            pool.as_ref(),
            &PostProcessOptions::default(),
            &asked,
            &crate::stages::manipuland::spot_again,
        )
    })?;
    // --- end of physics post-processing ---

    let rust_pairs = timed(timings, "rust_collision_check", || {
        collision::posed_objects(&state.scene, &state.assets)
            .map(|objs| collision::penetrating_pairs(&objs, 1e-3))
    })?;

    timed(timings, "write", || -> Result<(), PipelineError> {
        scene_dir::write_scene_dir(staging.path(), &state)?;
        crate::util::fsx::write_atomic(
            &staging.path().join("agent_log.jsonl"),
            report.log.to_jsonl().as_bytes(),
        )?;
        Ok(())
    })?;

    // --- renders (src/render): top.png and per-room views into <out>/renders/ ---
    if opts.render {
        timed(timings, "render", || {
            crate::render::write_standard_views(staging.path(), &state)
        })?;
    }
    // --- end renders ---
    // Exports: MJCF, USD and GLB written from the same state into the staging directory.
    let exports = timed(timings, "export", || {
        crate::export::write_exports(staging.path(), &state, &opts.exports)
    })?;

    // The Drake check of the written files (its own bridge) runs beside the metrics (on the
    // pool): the stability islands leave a core idle towards their end.
    let staged = staging.path().to_path_buf();
    let (check, metrics) = std::thread::scope(|scope| {
        let check = opts.drake_check.then(|| {
            scope.spawn(|| {
                let t0 = Instant::now();
                let summary = Bridge::from_env()
                    .map_err(PipelineError::from)
                    .and_then(|mut bridge| Ok(check_dir(&mut bridge, &staged, 1e-3)?));
                (summary, t0.elapsed().as_secs_f64())
            })
        });
        // --- metrics.json (the same code as `scenesmith eval`; STB needs the bridge) ---
        let metrics = timed(timings, "metrics", || {
            let defaults = EvalOptions::default();
            let eval_opts = EvalOptions {
                stability: defaults.stability.filter(|_| opts.stb),
                ..defaults
            };
            eval::evaluate(&state, pool.as_ref(), &eval_opts)
        });
        let check = check.map(|h| h.join().map_err(|_| PipelineError::CheckThread));
        (check, metrics)
    });
    let check = match check {
        Some(joined) => {
            let (summary, seconds) = joined?;
            timings.insert("drake_check".to_string(), seconds);
            let summary = summary?;
            if !summary.problems.is_empty() {
                return Err(PipelineError::CheckFailed(summary.problems.join("; ")));
            }
            state.scene.checks = Some(json!({ "drake": summary }));
            scene_dir::write_scene_json(staging.path(), &state.scene)?;
            Some(summary)
        }
        None => None,
    };
    let metrics = metrics?;
    eval::write_metrics(staging.path(), &metrics)?;
    // --- end of metrics ---

    let out = staging.commit()?;
    Ok(Finished {
        out,
        state,
        report,
        rust_pairs,
        check,
        post_process,
        metrics,
        exports,
    })
}

/// Runs the whole pipeline and writes the scene directory.
pub fn generate(opts: &GenerateOptions) -> Result<GenerateSummary, PipelineError> {
    validate_prompt(&opts.prompt)?;
    if matches!(opts.backend, BackendChoice::Builtin) {
        let reading = crate::prompt::read(&opts.prompt);
        if !reading.understood() {
            let what = reading.understanding();
            if !opts.lenient {
                return Err(PipelineError::NotUnderstood(what));
            }
            tracing::warn!("building a default room: the reader understood nothing ({what})");
        }
    }
    let mut timings = Timings::new();
    let t_total = Instant::now();
    // Fails before any work when the output cannot be written.
    let mut staging = StagingDir::new(&opts.out)?;
    let transcript = matches!(opts.backend, BackendChoice::Llm(_))
        .then(|| StagingDir::kept_path(staging.target(), LLM_LOG));
    if transcript.is_some() {
        staging.keep_on_failure(LLM_LOG);
    }
    let package = package_name_for(staging.target());
    if opts.drake_check {
        crate::physics::bridge::BridgeConfig::from_env().preflight()?;
    }

    let (backend, transport) = make_backend(&opts.backend, staging.path())?;
    let mut checkpoints = DirCheckpoints::open(staging.target(), &fingerprint(opts), opts.resume);
    let built = timed(&mut timings, "stages", || {
        build_scene_with(
            &opts.prompt,
            opts.seed,
            &package,
            &backend,
            &mut checkpoints,
        )
    });
    // Everything after the stages: a failure keeps the checkpoints for --resume.
    let finished = built.and_then(|(state, report)| {
        finish_run(opts, staging, &transport, state, report, &mut timings)
    });
    let Finished {
        out,
        state,
        report,
        rust_pairs,
        check,
        post_process,
        metrics,
        exports,
    } = match finished {
        Ok(v) => v,
        Err(e) => {
            let e = if checkpoints.finished().is_empty() {
                checkpoints.clear();
                e
            } else {
                PipelineError::Resumable {
                    finished: checkpoints.finished().len(),
                    error: Box::new(e),
                }
            };
            return Err(match transcript {
                // The staging directory is gone by now; its transcript was moved out.
                Some(path) if path.is_file() => PipelineError::TranscriptKept {
                    error: Box::new(e),
                    transcript: path,
                },
                _ => e,
            });
        }
    };
    checkpoints.clear();
    timings.insert("total".into(), t_total.elapsed().as_secs_f64());
    let mut per_kind = BTreeMap::new();
    let mut per_cat = BTreeMap::new();
    for o in &state.scene.objects {
        *per_kind.entry(o.kind.as_str().to_string()).or_insert(0) += 1;
        if o.kind != ObjectKind::Architecture {
            *per_cat.entry(o.category.clone()).or_insert(0) += 1;
        }
    }
    Ok(GenerateSummary {
        out: out.path,
        kept_previous: out.kept_previous,
        rooms: state
            .scene
            .rooms
            .iter()
            .map(|r| (r.id.clone(), r.room_type.clone()))
            .collect(),
        objects_per_kind: per_kind,
        objects_per_category: per_cat,
        stages: report.stages,
        plan_coverage: report.plan_coverage,
        unknown_nouns: report.unknown_nouns,
        nouns: report.nouns,
        notes: report.notes,
        rust_penetrating_pairs: rust_pairs.len(),
        check,
        post_process,
        metrics,
        exports,
        timings,
    })
}
