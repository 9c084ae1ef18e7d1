//! What the command line accepts: the subcommands and their options, the value enums and
//! parsers clap applies, and the usage error (exit code 2) for input that parses but cannot be
//! used.

use std::path::PathBuf;

use clap::{Parser, Subcommand};

use scenesmith::agents::llm::LlmConfig;
use scenesmith::export::ExportSet;
use scenesmith::pipeline::BackendChoice;

/// Text prompt -> simulation-ready indoor scene (SDFormat + Drake model directives).
#[derive(Parser)]
#[command(name = "scenesmith", version, about)]
pub(crate) struct Cli {
    /// Print a machine-readable JSON summary on stdout.
    #[arg(long, global = true)]
    pub(crate) json: bool,
    #[command(subcommand)]
    pub(crate) command: Command,
}

#[derive(Subcommand)]
pub(crate) enum Command {
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
    /// Turn a pick-and-place task into scene prompts: read the task (object to move, goal
    /// relation on / inside / near, reference, start), pick the room types that fit, write
    /// DIR/task.json and N varied prompts to DIR/prompts.jsonl. With --generate, also build
    /// each scene under DIR/scenes/<id>, check it (required objects present, goal false at the
    /// start), try another seed when it fails, and write DIR/scenes.jsonl; finished scenes
    /// are kept when run again.
    Task {
        /// The task, e.g. "pick up the mug from the table and put it on the shelf".
        task: String,
        /// How many scene prompts.
        #[arg(long, default_value_t = 5)]
        scenes: usize,
        /// Output directory.
        #[arg(long)]
        out: PathBuf,
        /// Seed of the prompts (and of the first attempt at each scene).
        #[arg(long, default_value_t = 0)]
        seed: u64,
        /// Generate and check the scenes too.
        #[arg(long)]
        generate: bool,
        /// Attempts per scene before it is reported unusable.
        #[arg(long, default_value_t = 3)]
        attempts: u32,
        /// Skip the stability simulations of each scene's metrics.json.
        #[arg(long)]
        no_stb: bool,
        #[command(flatten)]
        llm: LlmArgs,
    },
    /// Evaluate robot policies on a task: the task's scenes (as `task --generate`), each bound
    /// to one object and reference with the goal judged false at the start, one episode per
    /// policy (the mobile iiwa, planned and simulated in Drake) in parallel on the bridge pool,
    /// the final state judged by the built-in evaluator. Writes DIR/results.json and prints
    /// success rates with 95 % intervals and a row per episode with its outcome.
    RobotEval {
        /// The task, e.g. "put the mug on the coffee table".
        task: String,
        /// How many scenes.
        #[arg(long, default_value_t = 3)]
        scenes: usize,
        /// Policies: a comma-separated list of standard, degraded.
        #[arg(
            long,
            value_enum,
            value_delimiter = ',',
            default_value = "standard,degraded"
        )]
        policy: Vec<PolicyArg>,
        /// Output directory.
        #[arg(long)]
        out: PathBuf,
        /// Seed of the prompts, the scenes and the episodes.
        #[arg(long, default_value_t = 0)]
        seed: u64,
        /// Attempts per scene before it is reported unusable.
        #[arg(long, default_value_t = 3)]
        attempts: u32,
        /// Skip the rendered frames and flipbook of each episode.
        #[arg(long)]
        no_frames: bool,
        /// Who judges the initial and final states: the built-in geometric evaluator, or also
        /// a language model over the same tools (needs --llm-base-url and --llm-model; its
        /// verdict then decides success, the built-in one is kept next to it).
        #[arg(long, value_enum, default_value = "builtin")]
        judge: JudgeArg,
        /// Generate the scenes with the built-in backend even when an LLM is given (for the
        /// task reading and --judge llm).
        #[arg(long)]
        builtin_scenes: bool,
        #[command(flatten)]
        llm: LlmArgs,
    },
    /// Generate many scenes from a JSON-lines file, one scene per line ({"id", "prompt",
    /// "seed"}; id and seed optional) into DIR/<id>/, with DIR/results/<id>.json per scene and
    /// DIR/summary.jsonl. Resumable: finished scenes are skipped; a failed scene is tried once
    /// more (from its checkpoints) and reported.
    Batch {
        /// The prompts file.
        prompts: PathBuf,
        /// Output directory.
        #[arg(long)]
        out: PathBuf,
        /// Scenes generated at once.
        #[arg(long, default_value_t = 1)]
        workers: usize,
        /// Run only these scene ids (comma-separated); the summary still lists every line.
        #[arg(long, value_delimiter = ',')]
        only: Option<Vec<String>>,
        /// Write summary.jsonl and print the table from the results on disk; generate nothing.
        #[arg(long, conflicts_with = "only")]
        summary_only: bool,
        /// Skip loading each result in Drake before writing it.
        #[arg(long)]
        no_check: bool,
        /// Skip the annotated views of each scene.
        #[arg(long)]
        no_render: bool,
        /// Skip the stability simulations of metrics.json (STB is then blank).
        #[arg(long)]
        no_stb: bool,
        #[command(flatten)]
        llm: LlmArgs,
        /// Exports per scene: a comma-separated list of mjcf, usd, glb, or all / none.
        #[arg(long, default_value = "all", value_parser = parse_exports)]
        export: ExportSet,
    },
    /// Show a scene in the browser: serves a page with the scene's export/scene.glb (orbit
    /// controls, object picking, hide/show by kind, focus per room, metrics) on localhost until
    /// interrupted. Nothing is fetched from the internet.
    View {
        /// Scene directory.
        dir: PathBuf,
        /// Port on 127.0.0.1 (0 picks a free one).
        #[arg(long, default_value_t = 8765)]
        port: u16,
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
pub(crate) struct UsageError(pub(crate) String);

/// Returns `e` as a usage error (exit code 2).
pub(crate) fn usage(e: impl std::fmt::Display) -> anyhow::Error {
    UsageError(e.to_string()).into()
}

/// `--policy` of `robot-eval`.
#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum PolicyArg {
    Standard,
    Degraded,
}

/// `--judge`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub(crate) enum JudgeArg {
    /// The built-in geometric evaluator.
    Builtin,
    /// A language model over the evaluator's tools, next to the built-in evaluator.
    Llm,
}

impl From<PolicyArg> for scenesmith::physics::protocol::PolicyKind {
    fn from(p: PolicyArg) -> Self {
        match p {
            PolicyArg::Standard => Self::Standard,
            PolicyArg::Degraded => Self::Degraded,
        }
    }
}

/// `--stage` of `asset`.
#[derive(clap::ValueEnum, Clone, Copy, Debug)]
pub(crate) enum StageArg {
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
pub(crate) enum ContactArg {
    /// Drake's default plant on the files as written, and point contact.
    Both,
    /// Drake's default plant on the files as written (`stb`).
    AsWritten,
    /// Point contact as in SceneEval (`stb_point`).
    Point,
}

/// `--export` of `generate`: a list of formats, `all` or `none`.
pub(crate) fn parse_exports(s: &str) -> Result<ExportSet, String> {
    ExportSet::parse(s).map_err(|e| e.to_string())
}

/// `--formats` of `export`: a list of formats or `all`; selecting nothing is an error.
pub(crate) fn parse_formats(s: &str) -> Result<ExportSet, String> {
    let set = parse_exports(s)?;
    if set.is_empty() {
        return Err("selects nothing".into());
    }
    Ok(set)
}

/// `--size W,D,H`: three positive numbers in metres.
pub(crate) fn parse_size(s: &str) -> Result<[f64; 3], String> {
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
pub(crate) struct LlmArgs {
    /// Base URL of an OpenAI-compatible API, including the version (e.g. http://localhost:11434/v1).
    #[arg(long)]
    pub(crate) llm_base_url: Option<String>,
    /// Model name at that endpoint.
    #[arg(long)]
    pub(crate) llm_model: Option<String>,
    /// Name of the environment variable holding the API key (none for local servers).
    #[arg(long)]
    pub(crate) llm_api_key_env: Option<String>,
    /// JSON file with LLM settings (base_url, model, api_key_env, timeout_s, max_retries,
    /// prices, ...); flags override it.
    #[arg(long)]
    pub(crate) llm_config: Option<PathBuf>,
    /// Re-run from a recorded llm_log.jsonl without any network.
    #[arg(long, conflicts_with_all = ["llm_base_url", "llm_config"])]
    pub(crate) replay: Option<PathBuf>,
}

impl LlmArgs {
    pub(crate) fn choice(&self) -> anyhow::Result<BackendChoice> {
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
