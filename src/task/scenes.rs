//! Generating a task's scenes: one per prompt, each checked against the task and generated
//! again with another seed when it fails; resumable (a scene already on disk that passes is
//! kept).

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use super::{SceneCheck, ScenePrompt, TaskSpec, check_scene};
use crate::formats::scene_dir::read_scene;
use crate::pipeline::{self, GenerateOptions};

/// Seed offset between two attempts at one scene.
pub const RESEED_STEP: u64 = 1000;

/// One generated scene of a task.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct TaskScene {
    /// Prompt identifier.
    pub id: String,
    /// The scene prompt.
    pub prompt: String,
    /// Seed of the kept attempt.
    pub seed: u64,
    /// Scene directory.
    pub dir: PathBuf,
    /// Attempts made (1 when the first one passed; 0 when found on disk).
    pub attempts: u32,
    /// The check of the kept attempt.
    pub check: SceneCheck,
    /// Why the last attempt failed, when none passed (the scene is then not usable).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub failure: Option<String>,
}

impl TaskScene {
    /// Usable for the task.
    pub fn passed(&self) -> bool {
        self.failure.is_none() && self.check.passed()
    }
}

/// Options of [`build_scenes`].
#[derive(Debug, Clone)]
pub struct SceneBuildOptions {
    /// Attempts per scene (seeds `seed`, `seed + RESEED_STEP`, ...).
    pub attempts: u32,
    /// Run the stability simulations of `metrics.json` (the scenes are settled either way).
    pub stb: bool,
    /// Write the annotated views.
    pub render: bool,
    /// Who runs the scenes' stages.
    pub backend: crate::pipeline::BackendChoice,
}

/// Generates (or finds on disk) the scene of each prompt under `out/scenes/<id>`, checks it
/// against `spec`, and tries another seed while it fails, at most `opts.attempts` times.
/// `progress` hears each finished scene. A prompt the pipeline refuses or a run that fails
/// counts as a failed attempt; the row says why.
pub fn build_scenes(
    spec: &TaskSpec,
    prompts: &[ScenePrompt],
    out: &Path,
    opts: &SceneBuildOptions,
    progress: &mut dyn FnMut(&TaskScene),
) -> Vec<TaskScene> {
    let mut rows = Vec::new();
    for p in prompts {
        let dir = out.join("scenes").join(&p.id);
        let row = on_disk(spec, p, &dir).unwrap_or_else(|| attempt_all(spec, p, &dir, opts));
        progress(&row);
        rows.push(row);
    }
    rows
}

/// The scene already in `dir`, when it passes the check.
fn on_disk(spec: &TaskSpec, p: &ScenePrompt, dir: &Path) -> Option<TaskScene> {
    let scene = read_scene(dir).ok()?;
    (scene.provenance.prompt == p.prompt).then_some(())?;
    let check = check_scene(spec, &scene);
    check.passed().then(|| TaskScene {
        id: p.id.clone(),
        prompt: p.prompt.clone(),
        seed: scene.provenance.seed,
        dir: dir.to_path_buf(),
        attempts: 0,
        check,
        failure: None,
    })
}

fn attempt_all(
    spec: &TaskSpec,
    p: &ScenePrompt,
    dir: &Path,
    opts: &SceneBuildOptions,
) -> TaskScene {
    let mut last = None;
    for k in 0..opts.attempts.max(1) {
        let seed = p.seed.wrapping_add(u64::from(k) * RESEED_STEP);
        let mut gen_opts = GenerateOptions::new(p.prompt.clone(), dir);
        gen_opts.seed = seed;
        gen_opts.render = opts.render;
        gen_opts.exports = crate::export::ExportSet::none();
        gen_opts.stb = opts.stb;
        gen_opts.backend = opts.backend.clone();
        let result = pipeline::generate(&gen_opts)
            .map_err(|e| e.to_string())
            .and_then(|_| read_scene(dir).map_err(|e| e.to_string()));
        let row = |check: SceneCheck, failure: Option<String>| TaskScene {
            id: p.id.clone(),
            prompt: p.prompt.clone(),
            seed,
            dir: dir.to_path_buf(),
            attempts: k + 1,
            check,
            failure,
        };
        match result {
            Ok(scene) => {
                let check = check_scene(spec, &scene);
                if check.passed() {
                    return row(check, None);
                }
                let why = check.reason();
                last = Some(row(check, Some(why)));
            }
            Err(e) => last = Some(row(empty_check(), Some(e))),
        }
    }
    last.unwrap_or_else(|| TaskScene {
        id: p.id.clone(),
        prompt: p.prompt.clone(),
        seed: p.seed,
        dir: dir.to_path_buf(),
        attempts: 0,
        check: empty_check(),
        failure: Some("no attempt was made".to_string()),
    })
}

fn empty_check() -> SceneCheck {
    SceneCheck {
        missing: Vec::new(),
        targets: Vec::new(),
        references: Vec::new(),
        goal_holds_for: Vec::new(),
        bindable: Vec::new(),
    }
}
