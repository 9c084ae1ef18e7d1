//! The `scenesmith` command line.

use std::path::PathBuf;
use std::process::ExitCode;

use anyhow::Context;
use clap::{Parser, Subcommand};
use serde_json::json;

use scenesmith::agents::llm::LlmConfig;
use scenesmith::export::ExportSet;
use scenesmith::physics::protocol::{NoArgs, Versions};
use scenesmith::physics::{self, Bridge};
use scenesmith::pipeline::{self, BackendChoice, GenerateOptions, PipelineError};

/// Text prompt -> simulation-ready indoor scene (SDFormat + Drake model directives).
#[derive(Parser)]
#[command(name = "scenesmith", version, about)]
struct Cli {
    /// Print a machine-readable JSON summary on stdout.
    #[arg(long, global = true)]
    json: bool,
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Generate a scene directory from a prompt.
    ///
    /// Every placement stage (furniture, wall, ceiling, small objects per supporting entity)
    /// runs through the designer / critic / orchestrator loop: the built-in offline agents by
    /// default, an OpenAI-compatible model with --llm-base-url and --llm-model. The layout
    /// stage runs first: the rooms the prompt names (one room, or a house of up to 15+ rooms),
    /// placed edge to edge with doors, windows, open connections and materials.
    Generate {
        /// What the scene should be, e.g. "a kitchen with a table and four chairs".
        prompt: String,
        /// Output directory (replaced if it holds a previous scene).
        #[arg(long, short)]
        out: PathBuf,
        /// Seed for every random choice; same prompt + seed = same scene, byte for byte.
        #[arg(long, default_value_t = 0)]
        seed: u64,
        /// Skip loading the result in Drake before writing it.
        #[arg(long)]
        no_check: bool,
        /// Skip writing the annotated views (`renders/`).
        #[arg(long)]
        no_render: bool,
        /// Continue a failed run of the same command after its last finished stage.
        #[arg(long)]
        resume: bool,
        /// Build a default room when the built-in reader understands no room and no object
        /// of the prompt (another language, gibberish) instead of exiting with status 2.
        #[arg(long)]
        lenient: bool,
        /// Skip the stability simulations of metrics.json (most of a run's time); the scene
        /// is post-processed and settled all the same, and `scenesmith eval DIR` adds them.
        #[arg(long)]
        no_stb: bool,
        #[command(flatten)]
        llm: LlmArgs,
        /// Exports to write into DIR/export: a comma-separated list of mjcf, usd, glb, or
        /// all / none.
        #[arg(long, default_value = "all", value_parser = parse_exports)]
        export: ExportSet,
    },
    /// Write MuJoCo (MJCF), USD (UsdPhysics) and GLB exports of a scene directory; with
    /// --check, load them in MuJoCo, usd-core and Drake and fail on any mismatch.
    Export {
        /// Scene directory.
        dir: PathBuf,
        /// Formats: a comma-separated list of mjcf, usd, glb, or all.
        #[arg(long, default_value = "all", value_parser = parse_formats)]
        formats: ExportSet,
        /// Run the conformance gate (MuJoCo simulation, USD physics schema, Drake load).
        #[arg(long)]
        check: bool,
        /// Check the exports already in DIR/export instead of writing them first.
        #[arg(long, requires = "check")]
        no_write: bool,
        /// Simulated time of the MuJoCo run, seconds.
        #[arg(long, default_value_t = 5.0)]
        seconds: f64,
    },
    /// Load a scene directory in Drake and report collisions; fails on any problem.
    Check {
        /// Scene directory.
        dir: PathBuf,
        /// Penetration depth that counts as a collision, metres.
        #[arg(long, default_value_t = 1e-3)]
        threshold: f64,
        /// Highest acceptable COL (percent of objects in collision).
        #[arg(long, default_value_t = 0.0)]
        max_col: f64,
    },
    /// Report versions of the tool, Python, pydrake, solvers, MuJoCo and usd-core.
    Doctor,
    /// Render a scene directory: the annotated plan (top.png) and per-room corner views.
    Render {
        /// Scene directory.
        dir: PathBuf,
        /// Where to write the PNGs (default DIR/renders).
        #[arg(long, short)]
        out: Option<PathBuf>,
    },
    /// Make one asset from a description: SDFormat + glTF visuals + convex collisions +
    /// asset.json (and composite parts under parts/), through the asset router.
    ///
    /// Uses the asset cache (SCENESMITH_ASSET_CACHE, default ~/.cache/scenesmith/assets, "off"
    /// to disable) and the external sources configured in the environment
    /// (SCENESMITH_ARTICULATED_DIR, SCENESMITH_MESH_DIR, SCENESMITH_TEXT_TO_3D_URL).
    Asset {
        /// What to make, e.g. "a red oak dining table" or "a bowl with 6 apples".
        description: String,
        /// Output directory (replaced if it holds a previous asset).
        #[arg(long, short)]
        out: PathBuf,
        /// Stage to route for (guessed from the noun when absent).
        #[arg(long, value_enum)]
        stage: Option<StageArg>,
        /// Target size "W,D,H" in metres.
        #[arg(long, value_parser = parse_size)]
        size: Option<[f64; 3]>,
        /// Seed.
        #[arg(long, default_value_t = 0)]
        seed: u64,
    },
    /// Build every category of the procedural library at its typical size and lay the
    /// previews out on contact sheets: DIR/gallery_{floor,wall,ceiling,surface}.png plus
    /// DIR/gallery.json (size, mass, hull count, joints per category).
    Gallery {
        /// Output directory.
        #[arg(long, short)]
        out: PathBuf,
        /// Only categories whose name contains this text.
        #[arg(long)]
        only: Option<String>,
        /// Previews per row.
        #[arg(long, default_value_t = 12)]
        columns: usize,
        /// Seed of every generator.
        #[arg(long, default_value_t = 0)]
        seed: u64,
    },
    /// Compute a scene's metrics (counts, COL, STB, MD/XD/MR, NAV, OOB, plan coverage),
    /// write DIR/metrics.json and print a table.
    ///
    /// With --requirements FILE, score the scene against requirements written independently of
    /// the prompt reader instead (from DIR/scene.json alone; no assets, no Drake), write
    /// DIR/requirements_report.json and print a table. Exit 2 for a bad FILE.
    Eval {
        /// Scene directory.
        dir: PathBuf,
        /// JSON Lines of requirements: {"object": LABEL, "count": OP[, "room": LABEL]},
        /// {"absent": LABEL[, "room": LABEL]} or {"room": LABEL, "count": OP}; OP is =N, >=N,
        /// <=N, >N, <N or several.
        #[arg(
            long,
            value_name = "FILE",
            conflicts_with_all = ["robot_radius", "no_stb", "contact", "full_stb"]
        )]
        requirements: Option<PathBuf>,
        /// Robot radius for NAV, metres.
        #[arg(long, default_value_t = 0.25)]
        robot_radius: f64,
        /// Skip the 5 s stability simulation (then no Drake is needed).
        #[arg(long)]
        no_stb: bool,
        /// Contact model(s) of the stability simulation: Drake's default plant on the files as
        /// written (metrics `stb`), point contact as in SceneEval (`stb_point`), or both.
        #[arg(long, value_enum, default_value_t = ContactArg::Both)]
        contact: ContactArg,
        /// Simulate the whole 5 s even when everything is at rest earlier.
        #[arg(long)]
        full_stb: bool,
    },
    /// Lay out the rooms of a prompt (no furniture, no files): print the floor plan and the
    /// validation (with --json: every room, door, window and the checks).
    Layout {
        /// The prompt, e.g. "a flat with a kitchen, a living room, two bedrooms and a bathroom".
        prompt: String,
        /// Seed for every random choice.
        #[arg(long, default_value_t = 0)]
        seed: u64,
        /// Also write the top-down plan as a PNG (rooms with names, sizes and materials,
        /// textured floors, walls, doors with their swing, windows).
        #[arg(long)]
        png: Option<PathBuf>,
    },
}

/// An error in what the user asked for (a bad prompt, a file of requirements that does not
/// parse, a request no stage can place): printed once by `main`, exit code 2. Every other
/// error exits 1.
#[derive(Debug, thiserror::Error)]
#[error("{0}")]
struct UsageError(String);

/// Returns `e` as a usage error (exit code 2).
fn usage(e: impl std::fmt::Display) -> anyhow::Error {
    UsageError(e.to_string()).into()
}

/// `--stage` of `asset`.
#[derive(clap::ValueEnum, Clone, Copy, Debug)]
enum StageArg {
    Furniture,
    Wall,
    Ceiling,
    Manipuland,
}

impl From<StageArg> for scenesmith::assets::router::Stage {
    fn from(s: StageArg) -> Self {
        use scenesmith::assets::router::Stage;
        match s {
            StageArg::Furniture => Stage::Furniture,
            StageArg::Wall => Stage::Wall,
            StageArg::Ceiling => Stage::Ceiling,
            StageArg::Manipuland => Stage::Manipuland,
        }
    }
}

/// `--contact` of `eval`: which stability simulations to run.
#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq)]
enum ContactArg {
    /// Drake's default plant on the files as written, and point contact.
    Both,
    /// Drake's default plant on the files as written (`stb`).
    AsWritten,
    /// Point contact as in SceneEval (`stb_point`).
    Point,
}

/// `--export` of `generate`: a list of formats, `all` or `none`.
fn parse_exports(s: &str) -> Result<ExportSet, String> {
    ExportSet::parse(s).map_err(|e| e.to_string())
}

/// `--formats` of `export`: a list of formats or `all`; selecting nothing is an error.
fn parse_formats(s: &str) -> Result<ExportSet, String> {
    let set = parse_exports(s)?;
    if set.is_empty() {
        return Err("selects nothing".into());
    }
    Ok(set)
}

/// `--size W,D,H`: three positive numbers in metres.
fn parse_size(s: &str) -> Result<[f64; 3], String> {
    let v: Vec<f64> = s
        .split(',')
        .map(|x| x.trim().parse::<f64>())
        .collect::<Result<_, _>>()
        .map_err(|_| "three numbers in metres, e.g. 1.2,0.8,0.75".to_string())?;
    let size: [f64; 3] = v
        .try_into()
        .map_err(|_| "exactly three numbers, W,D,H".to_string())?;
    if size.iter().any(|x| !x.is_finite() || *x <= 0.0) {
        return Err("sizes must be positive".into());
    }
    Ok(size)
}

/// Language-model backend options (the built-in offline backend is used without them).
#[derive(clap::Args, Debug, Default)]
struct LlmArgs {
    /// Base URL of an OpenAI-compatible API, including the version (e.g. http://localhost:11434/v1).
    #[arg(long)]
    llm_base_url: Option<String>,
    /// Model name at that endpoint.
    #[arg(long)]
    llm_model: Option<String>,
    /// Name of the environment variable holding the API key (none for local servers).
    #[arg(long)]
    llm_api_key_env: Option<String>,
    /// JSON file with LLM settings (base_url, model, api_key_env, timeout_s, max_retries,
    /// prices, ...); flags override it.
    #[arg(long)]
    llm_config: Option<PathBuf>,
    /// Re-run from a recorded llm_log.jsonl without any network.
    #[arg(long, conflicts_with_all = ["llm_base_url", "llm_config"])]
    replay: Option<PathBuf>,
}

impl LlmArgs {
    fn choice(&self) -> anyhow::Result<BackendChoice> {
        if let Some(path) = &self.replay {
            return Ok(BackendChoice::Replay(path.clone()));
        }
        if self.llm_base_url.is_none() && self.llm_config.is_none() && self.llm_model.is_none() {
            return Ok(BackendChoice::Builtin);
        }
        let mut config = match &self.llm_config {
            Some(p) => LlmConfig::from_file(p)?,
            None => LlmConfig::default(),
        };
        if let Some(u) = &self.llm_base_url {
            config.base_url = u.clone();
        }
        if let Some(m) = &self.llm_model {
            config.model = m.clone();
        }
        if let Some(k) = &self.llm_api_key_env {
            config.api_key_env = Some(k.clone());
        }
        if config.model.is_empty() {
            anyhow::bail!(
                "--llm-model (or \"model\" in --llm-config) is required with an LLM endpoint"
            );
        }
        Ok(BackendChoice::Llm(config))
    }
}

fn init_logging() {
    let filter = tracing_subscriber::EnvFilter::try_from_env("SCENESMITH_LOG")
        .unwrap_or_else(|_| tracing_subscriber::EnvFilter::new("warn"));
    tracing_subscriber::fmt()
        .with_env_filter(filter)
        .with_writer(std::io::stderr)
        .with_target(false)
        .init();
}

fn print_json(v: &serde_json::Value) -> anyhow::Result<()> {
    println!("{}", serde_json::to_string_pretty(v)?);
    Ok(())
}

fn run_generate(cli_json: bool, opts: GenerateOptions) -> anyhow::Result<ExitCode> {
    eprintln!(
        "scenesmith: generating {:?} -> {}",
        opts.prompt,
        opts.out.display()
    );
    let summary = match pipeline::generate(&opts) {
        Ok(s) => s,
        Err(
            e @ (PipelineError::EmptyPrompt
            | PipelineError::UnusablePrompt(_)
            | PipelineError::NotUnderstood(_)),
        ) => {
            return Err(usage(e));
        }
        Err(e) => {
            return Err(e).context("generate failed; the output directory was left as it was");
        }
    };
    if cli_json {
        print_json(&serde_json::to_value(&summary)?)?;
    } else {
        eprintln!("wrote {}", summary.out.display());
        if let Some(kept) = &summary.kept_previous {
            eprintln!(
                "  the directory it replaced held files scenesmith did not write: kept as {}",
                kept.display()
            );
        }
        for (id, ty) in &summary.rooms {
            eprintln!("  room {id} ({ty})");
        }
        let cats: Vec<String> = summary
            .objects_per_category
            .iter()
            .map(|(c, n)| format!("{n} {c}"))
            .collect();
        eprintln!("  objects: {}", cats.join(", "));
        for (noun, planned, present) in &summary.plan_coverage {
            if present < planned {
                eprintln!("  note: the plan has {planned} {noun}, placed {present}");
            }
        }
        for noun in &summary.unknown_nouns {
            eprintln!("  note: no asset generator knows {noun:?}; it was left out");
        }
        for line in scenesmith::prompt::report::summary_lines(&summary.nouns) {
            eprintln!("  {line}");
        }
        for n in &summary.notes {
            eprintln!("  note: {n}");
        }
        for st in &summary.stages {
            if let Some(c) = &st.critique {
                let scores: Vec<String> = c
                    .scores
                    .iter()
                    .map(|s| format!("{} {}", s.category, s.score))
                    .collect();
                eprintln!(
                    "  {} {}{}: {}",
                    st.stage,
                    st.room,
                    st.entity
                        .as_ref()
                        .map(|e| format!("/{e}"))
                        .unwrap_or_default(),
                    scores.join(", ")
                );
            }
        }
        let pp = &summary.post_process;
        let removed: Vec<&String> = pp
            .furniture
            .removed
            .iter()
            .chain(&pp.manipuland.removed)
            .chain(&pp.removed_penetrating)
            .collect();
        if !removed.is_empty() {
            eprintln!(
                "  post-processing removed {} objects (reasons in scene.json)",
                removed.len()
            );
        }
        eprint!("{}", scenesmith::eval::table(&summary.metrics));
        if let Some(c) = &summary.check {
            eprintln!(
                "  drake {}: {} model instances, {} free bodies, COL {:.2}% (max depth {:.2} mm)",
                c.drake,
                c.model_instances,
                c.free_bodies,
                c.col_percent,
                c.max_depth_m * 1e3
            );
        }
        let t: Vec<String> = summary
            .timings
            .iter()
            .map(|(k, v)| format!("{k} {v:.2}s"))
            .collect();
        eprintln!("  time: {}", t.join(", "));
    }
    Ok(ExitCode::SUCCESS)
}

fn run_check(
    cli_json: bool,
    dir: PathBuf,
    threshold: f64,
    max_col: f64,
) -> anyhow::Result<ExitCode> {
    let mut bridge = Bridge::from_env()?;
    let t0 = std::time::Instant::now();
    let summary = physics::check_dir(&mut bridge, &dir, threshold)
        .with_context(|| format!("checking {}", dir.display()))?;
    let passed = summary.passed(max_col);
    if cli_json {
        let mut v = serde_json::to_value(&summary)?;
        v["passed"] = json!(passed);
        v["seconds"] = json!(t0.elapsed().as_secs_f64());
        print_json(&v)?;
    } else {
        eprintln!("check {} with drake {}", dir.display(), summary.drake);
        eprintln!(
            "  model instances {} (scene objects {}), bodies {}, free bodies {}",
            summary.model_instances, summary.scene_objects, summary.bodies, summary.free_bodies
        );
        eprintln!(
            "  COL {:.2}% of {} objects (> {:.1} mm), mean depth {:.2} mm, max {:.2} mm",
            summary.col_percent,
            summary.col_objects,
            summary.threshold_m * 1e3,
            summary.mean_depth_m * 1e3,
            summary.max_depth_m * 1e3
        );
        for (a, b, d) in &summary.pairs {
            eprintln!("  penetrating: {a} / {b}: {:.2} mm", d * 1e3);
        }
        for p in &summary.problems {
            eprintln!("  problem: {p}");
        }
        eprintln!(
            "  {} in {:.2}s",
            if passed { "PASS" } else { "FAIL" },
            t0.elapsed().as_secs_f64()
        );
    }
    Ok(if passed {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(1)
    })
}

fn run_render(cli_json: bool, dir: PathBuf, out: Option<PathBuf>) -> anyhow::Result<ExitCode> {
    let t0 = std::time::Instant::now();
    let out = out.unwrap_or_else(|| dir.join("renders"));
    let files = scenesmith::render::render_scene_dir(&dir, Some(&out))
        .with_context(|| format!("rendering {} into {}", dir.display(), out.display()))?;
    if cli_json {
        print_json(&json!({ "files": files, "seconds": t0.elapsed().as_secs_f64() }))?;
    } else {
        for f in &files {
            eprintln!("wrote {}", f.display());
        }
        eprintln!(
            "  {} images in {:.2}s",
            files.len(),
            t0.elapsed().as_secs_f64()
        );
    }
    Ok(ExitCode::SUCCESS)
}

fn run_eval(
    cli_json: bool,
    dir: PathBuf,
    robot_radius: f64,
    no_stb: bool,
    contact: ContactArg,
    full_stb: bool,
) -> anyhow::Result<ExitCode> {
    use scenesmith::eval::{self, EvalOptions, StabilityOptions};
    use scenesmith::physics::settle::ContactModel;
    let stb_contacts = match contact {
        ContactArg::AsWritten => vec![ContactModel::AsWritten],
        ContactArg::Point => vec![ContactModel::Point],
        ContactArg::Both => vec![ContactModel::AsWritten, ContactModel::Point],
    };
    let opts = EvalOptions {
        robot_radius_m: robot_radius,
        stability: (!no_stb).then(|| StabilityOptions {
            stop_at_rest: !full_stb,
            ..StabilityOptions::default()
        }),
        stb_contacts,
        ..EvalOptions::default()
    };
    let pool = (!no_stb).then(scenesmith::physics::BridgePool::from_env);
    let metrics = eval::evaluate_dir(&dir, pool.as_ref(), &opts)
        .with_context(|| format!("evaluating {}", dir.display()))?;
    eval::write_metrics(&dir, &metrics)?;
    if cli_json {
        print_json(&serde_json::to_value(&metrics)?)?;
    } else {
        eprintln!("metrics of {} (written to metrics.json)", dir.display());
        eprint!("{}", eval::table(&metrics));
    }
    Ok(ExitCode::SUCCESS)
}

fn run_requirements(cli_json: bool, dir: PathBuf, file: PathBuf) -> anyhow::Result<ExitCode> {
    use scenesmith::eval::requirements::{
        REQUIREMENTS_REPORT_JSON, parse_requirements, score, table, write_report,
    };
    let reqs = match std::fs::read_to_string(&file)
        .map_err(|e| e.to_string())
        .and_then(|text| parse_requirements(&text).map_err(|e| e.to_string()))
    {
        Ok(r) => r,
        Err(e) => {
            return Err(usage(format!("requirements file {}: {e}", file.display())));
        }
    };
    let scene = scenesmith::formats::scene_dir::read_scene(&dir)
        .with_context(|| format!("reading the scene in {}", dir.display()))?;
    let report = score(&scene, &reqs);
    write_report(&dir, &report)
        .with_context(|| format!("writing {REQUIREMENTS_REPORT_JSON} in {}", dir.display()))?;
    if cli_json {
        print_json(&serde_json::to_value(&report)?)?;
    } else {
        eprintln!(
            "requirements of {} from {} (written to {REQUIREMENTS_REPORT_JSON})",
            dir.display(),
            file.display()
        );
        eprint!("{}", table(&report));
    }
    Ok(ExitCode::SUCCESS)
}

fn run_export(
    cli_json: bool,
    dir: PathBuf,
    set: ExportSet,
    check: bool,
    no_write: bool,
    seconds: f64,
) -> anyhow::Result<ExitCode> {
    use scenesmith::export::{self, conformance};
    let state = scenesmith::formats::scene_dir::load_state(&dir)
        .with_context(|| format!("reading the scene in {}", dir.display()))?;
    let mut out = json!({ "dir": dir });
    if !no_write {
        let written = export::write_exports(&dir, &state, &set)
            .with_context(|| format!("exporting {}", dir.display()))?;
        for w in &written {
            if !cli_json {
                eprintln!(
                    "wrote {} ({} files, {:.1} kB)",
                    dir.join(&w.main_file).display(),
                    w.files,
                    w.bytes as f64 / 1e3
                );
            }
        }
        out["written"] = serde_json::to_value(&written)?;
    }
    let mut passed = true;
    if check {
        let mut bridge = Bridge::from_env()?;
        let opts = conformance::GateOptions {
            seconds,
            formats: set,
        };
        let report = conformance::run_gate(&mut bridge, &dir, &state, &opts)
            .with_context(|| format!("checking the exports of {}", dir.display()))?;
        passed = report.passed;
        if cli_json {
            out["check"] = serde_json::to_value(&report)?;
        } else {
            eprint!("{}", conformance::table(&report));
            if let Some(s) = &report.mujoco_stability {
                for (id, d, a) in &s.moved {
                    eprintln!("  moved in MuJoCo: {id}: {:.1} mm, {:.3} rad", d * 1e3, a);
                }
            }
            eprintln!("  {}", if passed { "PASS" } else { "FAIL" });
        }
    }
    if cli_json {
        out["passed"] = json!(passed);
        print_json(&out)?;
    }
    Ok(if passed {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(1)
    })
}

fn run_layout(
    cli_json: bool,
    prompt: &str,
    seed: u64,
    png: Option<PathBuf>,
) -> anyhow::Result<ExitCode> {
    use scenesmith::layout;
    if let Err(e) = pipeline::validate_prompt(prompt) {
        return Err(usage(e));
    }
    let mut log = scenesmith::agents::RunLog::default();
    let out = layout::stage::run_layout(
        prompt,
        seed,
        &scenesmith::agents::Backend::Builtin,
        &mut log,
    )?;
    if let Some(path) = &png {
        let bytes = scenesmith::render::plan_png(prompt, seed, &out.rooms)?;
        scenesmith::util::fsx::write_atomic(path, &bytes)?;
        eprintln!("wrote {}", path.display());
    }
    if cli_json {
        let obs = layout::tools::observe(&out.state).map_err(|e| anyhow::anyhow!(e.message))?;
        let mut v = serde_json::to_value(&obs)?;
        v["validation"] = serde_json::to_value(&out.validation)?;
        v["critique"] = serde_json::to_value(&out.summary.critique)?;
        print_json(&v)?;
    } else {
        print!("{}", layout::ascii::render(&out.rooms));
        for e in &out.validation.errors {
            eprintln!("  error: {e}");
        }
        for w in &out.validation.warnings {
            eprintln!("  warning: {w}");
        }
        let s = &out.state.stats;
        eprintln!(
            "  {} rooms, compactness {:.2}, search {} nodes in {:.2}s{}{}",
            out.rooms.len(),
            s.compactness,
            s.nodes,
            s.seconds,
            if s.relaxed { ", relaxed" } else { "" },
            if s.timed_out { ", timed out" } else { "" }
        );
    }
    Ok(if out.validation.ok {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(1)
    })
}

fn run_doctor(cli_json: bool) -> anyhow::Result<ExitCode> {
    let config = scenesmith::physics::BridgeConfig::from_env();
    let (home, python) = (config.home.clone(), config.python.clone());
    let versions = Bridge::start(config).and_then(|mut b| b.call::<Versions>(&NoArgs {}));
    let ok = versions.is_ok();
    if cli_json {
        let mut report = json!({
            "scenesmith": env!("CARGO_PKG_VERSION"),
            "home": home,
            "python": python,
        });
        match &versions {
            Ok(v) => report["bridge"] = serde_json::to_value(v)?,
            Err(e) => report["bridge_error"] = json!(e.to_string()),
        }
        print_json(&report)?;
    } else {
        eprintln!("scenesmith {}", env!("CARGO_PKG_VERSION"));
        eprintln!("  home:    {}", home.display());
        eprintln!("  python:  {}", python.display());
        match &versions {
            Ok(b) => {
                let missing = |v: &Option<String>| v.clone().unwrap_or_else(|| "missing".into());
                eprintln!("  Python {}", b.python);
                eprintln!("  drake {}", b.drake);
                eprintln!(
                    "  SNOPT available {} enabled {}; IPOPT available {}",
                    b.snopt.available, b.snopt.enabled, b.ipopt.available
                );
                eprintln!("  numpy {}", missing(&b.numpy));
                eprintln!("  mujoco {}", missing(&b.mujoco));
                eprintln!("  usd-core {}", missing(&b.usd_core));
            }
            Err(e) => eprintln!("  bridge: {e}"),
        }
    }
    Ok(if ok {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(1)
    })
}

fn run_asset(
    cli_json: bool,
    description: String,
    out: PathBuf,
    stage: Option<StageArg>,
    size: Option<[f64; 3]>,
    seed: u64,
) -> anyhow::Result<ExitCode> {
    use scenesmith::assets::router;
    use scenesmith::pipeline::asset as command;
    let opts = command::AssetOptions {
        description,
        out,
        stage: stage.map(Into::into),
        size,
        seed,
    };
    let ctx = router::RouterContext::from_env();
    let preview = |asset: &scenesmith::assets::Asset| {
        scenesmith::render::asset_preview(asset, 480, 360)
            .and_then(|image| image.encode_png())
            .ok()
    };
    let report = match command::make_asset(&opts, &ctx, Some(&preview)) {
        Ok(r) => r,
        Err(command::AssetCommandError::Route(e)) => {
            return Err(usage(e));
        }
        Err(e) => return Err(e.into()),
    };
    if cli_json {
        print_json(&serde_json::to_value(&report)?)?;
    } else {
        for a in &report.assets {
            eprintln!(
                "wrote {} ({} x{}, {:?}, {:.2} x {:.2} x {:.2} m, {:.2} kg, {} hulls{})",
                a.dir.display(),
                a.category,
                a.count,
                a.strategy,
                a.size_m[0],
                a.size_m[1],
                a.size_m[2],
                a.mass_kg,
                a.collision_pieces,
                if a.joints.is_empty() {
                    String::new()
                } else {
                    format!(", joints {}", a.joints.join(" "))
                }
            );
        }
        for n in &report.notes {
            eprintln!("  note: {n}");
        }
    }
    Ok(ExitCode::SUCCESS)
}

fn run_gallery(
    cli_json: bool,
    out: PathBuf,
    only: Option<String>,
    columns: usize,
    seed: u64,
) -> anyhow::Result<ExitCode> {
    use scenesmith::render::gallery::{GalleryError, GalleryOptions, write_gallery};
    let mut opts = GalleryOptions::new(out);
    opts.filter = only;
    opts.columns = columns.max(1);
    opts.seed = seed;
    let report = match write_gallery(&opts) {
        Ok(r) => r,
        Err(e @ GalleryError::NothingMatches(_)) => {
            return Err(usage(e));
        }
        Err(e) => return Err(e.into()),
    };
    if cli_json {
        print_json(&serde_json::to_value(&report)?)?;
    } else {
        for sheet in &report.sheets {
            eprintln!("wrote {}", sheet.display());
        }
        eprintln!("{} categories", report.entries.len());
        for (category, reason) in &report.failed {
            eprintln!("  failed: {category}: {reason}");
        }
    }
    Ok(if report.failed.is_empty() {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    })
}

fn main() -> ExitCode {
    init_logging();
    let cli = Cli::parse();
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

#[cfg(test)]
mod tests {
    use super::*;
    use clap::error::ErrorKind;

    #[test]
    fn option_values_are_parsed_by_clap_and_bad_ones_are_usage_errors() {
        assert_eq!(parse_size("1.2, 0.8,0.75"), Ok([1.2, 0.8, 0.75]));
        for bad in ["1,2", "1,2,3,4", "a,b,c", "1,-2,3", "1,inf,3"] {
            assert!(parse_size(bad).is_err(), "{bad}");
        }
        let parse = |args: &[&str]| Cli::try_parse_from(["scenesmith"].iter().chain(args));
        let usage = |args: &[&str]| parse(args).err().map(|e| e.kind());
        assert_eq!(
            usage(&["asset", "a lamp", "--out", "x", "--stage", "floor"]),
            Some(ErrorKind::InvalidValue)
        );
        assert_eq!(
            usage(&["asset", "a lamp", "--out", "x", "--size", "1,2"]),
            Some(ErrorKind::ValueValidation)
        );
        assert_eq!(
            usage(&["export", "d", "--formats", "none"]),
            Some(ErrorKind::ValueValidation)
        );
        assert_eq!(
            usage(&["generate", "a room", "--out", "d", "--export", "fbx"]),
            Some(ErrorKind::ValueValidation)
        );
        let Ok(Cli {
            command: Command::Eval { contact, .. },
            ..
        }) = parse(&["eval", "d", "--contact", "as-written"])
        else {
            panic!("eval parses");
        };
        assert_eq!(contact, ContactArg::AsWritten);
        let Ok(Cli {
            command: Command::Asset { stage, size, .. },
            ..
        }) = parse(&[
            "asset", "a lamp", "--out", "x", "--stage", "ceiling", "--size", "1,1,1",
        ])
        else {
            panic!("asset parses");
        };
        assert!(matches!(stage, Some(StageArg::Ceiling)));
        assert_eq!(size, Some([1.0, 1.0, 1.0]));
    }
}
