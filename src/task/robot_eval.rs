//! Robot policy evaluation: a task's scenes, the initial state judged, each policy's episode
//! run on the bridge pool, the final state judged, success rates with 95 % intervals.
//!
//! Per usable scene the task is bound to one (object, reference) pair: the first object that
//! may be bound (the goal false for it at the start, [`super::SceneCheck::bindable`]) and the
//! first reference for which the built-in evaluator (`judge_task`) confirms the goal is false
//! on `scene.dmd.yaml`. Each policy then runs one episode (`policy_episode`), all episodes in
//! parallel over the pool, and the evaluator judges the pair on the episode's
//! `after_<policy>.dmd.yaml`. An episode's outcome is `success`, `placed_wrong` (executed, the
//! goal does not hold), or the policy's failure reason (`no_base_pose`, `no_grasp`, `ik`,
//! `planning`, `dropped`, `timeout`); a bridge error is `error`.
//!
//! With an LLM evaluator ([`LlmJudge`], [`super::llm_judge`]) the model also judges the bound
//! pair's initial state and every executed episode's final state over the same tools; its
//! verdict then decides `success` / `placed_wrong`, and the built-in verdict is kept next to it
//! (`builtin_holds`), so the two can be compared.

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use super::llm_judge::{JudgedState, LlmVerdict, judge_with_llm};
use super::scenes::{SceneBuildOptions, TaskScene, build_scenes};
use super::{Predicate, ScenePrompt, TaskSpec};
use crate::agents::llm::transport::Transport;
use crate::physics::pool::{BridgePool, Job};
use crate::physics::protocol::{
    EpisodeArgs, EpisodeReply, JudgeArgs, JudgeReply, JudgeTask, PolicyEpisode, PolicyKind,
    TaskPredicate,
};

/// Options of [`robot_eval`].
#[derive(Debug, Clone)]
pub struct RobotEvalOptions {
    /// Policies to run on every scene.
    pub policies: Vec<PolicyKind>,
    /// Scene generation.
    pub scenes: SceneBuildOptions,
    /// Render each episode's frames and flipbook.
    pub frames: bool,
    /// Seed of the episodes, added to each scene's seed (both policies of a scene get the
    /// same).
    pub seed: u64,
}

/// The binding of one scene and its initial-state verdict.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Binding {
    /// Scene id.
    pub scene: String,
    /// The object to move, when one could be bound.
    pub target: Option<String>,
    /// The reference.
    pub reference: Option<String>,
    /// The evaluator's reason for the initial state of the bound pair (or why nothing was
    /// bound).
    pub initial: String,
    /// The LLM evaluator's verdict on the initial state (with an LLM evaluator).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub llm_initial: Option<LlmVerdict>,
}

/// One episode.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct EpisodeRow {
    /// Scene id.
    pub scene: String,
    /// Policy name.
    pub policy: String,
    /// The bound object.
    pub target: String,
    /// The bound reference.
    pub reference: String,
    /// `success`, `placed_wrong`, a policy failure reason, or `error`.
    pub outcome: String,
    /// Why, in words (the evaluator's reason or the policy's message).
    pub reason: String,
    /// Wall seconds of the episode (planning and rollout).
    pub seconds: f64,
    /// Largest planned gripper speed, m/s.
    pub max_gripper_speed: f64,
    /// The scene instances the carried object hit (touched between the grasp and the release,
    /// neither at the one nor at the other).
    #[serde(default)]
    pub hit: Vec<String>,
    /// The episode's directory.
    pub dir: PathBuf,
    /// The built-in evaluator's verdict on the final state (executed episodes).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub builtin_holds: Option<bool>,
    /// The LLM evaluator's verdict on the final state (with an LLM evaluator).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub llm: Option<LlmVerdict>,
}

impl EpisodeRow {
    /// The goal holds after the episode.
    pub fn succeeded(&self) -> bool {
        self.outcome == "success"
    }
}

/// Success rate of one policy.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct PolicySummary {
    /// Policy name.
    pub policy: String,
    /// Episodes run.
    pub episodes: usize,
    /// Episodes whose goal holds at the end.
    pub successes: usize,
    /// successes / episodes (0 when none ran).
    pub rate: f64,
    /// 95 % Wilson score interval of the rate.
    pub ci95: [f64; 2],
    /// Episodes in which the carried object hit something (`EpisodeRow::hit`).
    #[serde(default)]
    pub hits: usize,
}

/// Everything a run produced (`results.json`).
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct RobotEvalResults {
    /// The task read.
    pub task: TaskSpec,
    /// The scenes, usable or not.
    pub scenes: Vec<TaskScene>,
    /// The binding and initial-state verdict per usable scene.
    pub bindings: Vec<Binding>,
    /// Every episode.
    pub episodes: Vec<EpisodeRow>,
    /// Per policy.
    pub summary: Vec<PolicySummary>,
}

/// A language model judging states next to the built-in evaluator.
pub struct LlmJudge<'a> {
    /// Where requests go.
    pub transport: &'a mut dyn Transport,
    /// The model name sent.
    pub model: String,
}

impl LlmJudge<'_> {
    fn judge(
        &mut self,
        pool: &BridgePool,
        spec: &TaskSpec,
        state: JudgedState<'_>,
    ) -> Result<LlmVerdict, String> {
        judge_with_llm(self.transport, &self.model, pool, spec, state).map_err(|e| e.to_string())
    }
}

/// The 95 % Wilson score interval of `k` successes in `n` trials.
pub fn wilson95(k: usize, n: usize) -> [f64; 2] {
    if n == 0 {
        return [0.0, 1.0];
    }
    let z = 1.959_963_984_540_054_f64;
    let (n, p) = (n as f64, k as f64 / n as f64);
    let denom = 1.0 + z * z / n;
    let centre = (p + z * z / (2.0 * n)) / denom;
    let half = z * (p * (1.0 - p) / n + z * z / (4.0 * n * n)).sqrt() / denom;
    [(centre - half).max(0.0), (centre + half).min(1.0)]
}

fn wire(p: Predicate) -> TaskPredicate {
    match p {
        Predicate::On => TaskPredicate::On,
        Predicate::Inside => TaskPredicate::Inside,
        Predicate::Near => TaskPredicate::Near,
    }
}

fn judge(
    pool: &BridgePool,
    dir: &Path,
    directives: &Path,
    p: Predicate,
    targets: &[String],
    references: &[String],
) -> Result<JudgeReply, String> {
    pool.call::<JudgeTask>(&JudgeArgs {
        scene_dir: dir.to_path_buf(),
        directives: directives.to_path_buf(),
        predicate: wire(p),
        targets: targets.to_vec(),
        references: references.to_vec(),
    })
    .map_err(|e| e.to_string())
}

/// Binds a usable scene: the first bindable object and the first reference the evaluator
/// confirms the goal is false for.
fn bind(pool: &BridgePool, spec: &TaskSpec, scene: &TaskScene) -> Binding {
    let none = |why: String| Binding {
        scene: scene.id.clone(),
        target: None,
        reference: None,
        initial: why,
        llm_initial: None,
    };
    let Some(target) = scene.check.bindable.first() else {
        return none("no object to move".into());
    };
    let verdict = match judge(
        pool,
        &scene.dir,
        Path::new("scene.dmd.yaml"),
        spec.predicate,
        std::slice::from_ref(target),
        &scene.check.references,
    ) {
        Ok(v) => v,
        Err(e) => return none(format!("the evaluator failed: {e}")),
    };
    match verdict.pairs.iter().find(|p| !p.holds) {
        Some(p) => Binding {
            scene: scene.id.clone(),
            target: Some(p.target.clone()),
            reference: Some(p.reference.clone()),
            initial: p.reason.clone(),
            llm_initial: None,
        },
        None => none(format!(
            "the goal already holds for {target} with every reference"
        )),
    }
}

/// Runs the evaluation: scenes under `out/scenes/`, episodes under
/// `out/episodes/<scene>/<policy>/`. `progress` hears each line worth printing.
pub fn robot_eval(
    spec: &TaskSpec,
    prompts: &[ScenePrompt],
    out: &Path,
    pool: &BridgePool,
    opts: &RobotEvalOptions,
    mut llm: Option<LlmJudge<'_>>,
    progress: &mut dyn FnMut(String),
) -> RobotEvalResults {
    let scenes = build_scenes(spec, prompts, out, &opts.scenes, &mut |row| {
        progress(match &row.failure {
            None => format!("scene {}: usable", row.id),
            Some(why) => format!("scene {}: unusable: {why}", row.id),
        });
    });
    let mut bindings: Vec<Binding> = scenes
        .iter()
        .filter(|s| s.passed())
        .map(|s| bind(pool, spec, s))
        .collect();
    if let Some(judge) = llm.as_mut() {
        for b in &mut bindings {
            let (Some(t), Some(r)) = (&b.target, &b.reference) else {
                continue;
            };
            let Some(scene) = scenes.iter().find(|s| s.id == b.scene) else {
                continue;
            };
            let state = JudgedState {
                scene_dir: &scene.dir,
                directives: Path::new("scene.dmd.yaml"),
                target: t,
                reference: r,
            };
            match judge.judge(pool, spec, state) {
                Ok(v) => b.llm_initial = Some(v),
                Err(e) => progress(format!("scene {}: the LLM evaluator failed: {e}", b.scene)),
            }
        }
    }
    // Every (scene, policy) episode, in parallel over the pool.
    let mut planned = Vec::new();
    for b in &bindings {
        let (Some(t), Some(r)) = (&b.target, &b.reference) else {
            progress(format!("scene {}: nothing bound ({})", b.scene, b.initial));
            continue;
        };
        let Some(scene) = scenes.iter().find(|s| s.id == b.scene) else {
            continue;
        };
        for &policy in &opts.policies {
            let args = EpisodeArgs {
                scene_dir: scene.dir.clone(),
                predicate: wire(spec.predicate),
                target: t.clone(),
                reference: r.clone(),
                policy,
                out_dir: out.join("episodes").join(&b.scene).join(policy.name()),
                // Both policies of a scene share it; the scenes differ (their pose-estimate
                // errors, the planners' random choices).
                seed: opts.seed.wrapping_add(scene.seed),
                frames: opts.frames,
            };
            planned.push((scene, args));
        }
    }
    let encoded: Vec<Result<Job, String>> = planned
        .iter()
        .map(|(_, a)| Job::of::<PolicyEpisode>(a).map_err(|e| e.to_string()))
        .collect();
    let jobs: Vec<Job> = encoded.iter().filter_map(|j| j.clone().ok()).collect();
    let mut replies = pool.run_all(jobs).into_iter();
    let mut episodes = Vec::new();
    for ((scene, args), job) in planned.iter().zip(encoded) {
        let decoded = job.and_then(|_| {
            replies
                .next()
                .ok_or_else(|| "the pool gave no reply".to_string())?
                .map_err(|e| e.to_string())
                .and_then(|v| serde_json::from_value::<EpisodeReply>(v).map_err(|e| e.to_string()))
        });
        let row = episode_row(pool, spec, scene, args, decoded, llm.as_mut());
        progress(format!(
            "scene {} {}: {} ({})",
            row.scene, row.policy, row.outcome, row.reason
        ));
        episodes.push(row);
    }
    let summary = opts
        .policies
        .iter()
        .map(|p| {
            let rows: Vec<&EpisodeRow> = episodes.iter().filter(|e| e.policy == p.name()).collect();
            let k = rows.iter().filter(|e| e.succeeded()).count();
            PolicySummary {
                policy: p.name().to_string(),
                episodes: rows.len(),
                successes: k,
                rate: if rows.is_empty() {
                    0.0
                } else {
                    k as f64 / rows.len() as f64
                },
                ci95: wilson95(k, rows.len()),
                hits: rows.iter().filter(|e| !e.hit.is_empty()).count(),
            }
        })
        .collect();
    RobotEvalResults {
        task: spec.clone(),
        scenes,
        bindings,
        episodes,
        summary,
    }
}

fn episode_row(
    pool: &BridgePool,
    spec: &TaskSpec,
    scene: &TaskScene,
    args: &EpisodeArgs,
    reply: Result<EpisodeReply, String>,
    llm: Option<&mut LlmJudge<'_>>,
) -> EpisodeRow {
    let mut row = EpisodeRow {
        scene: scene.id.clone(),
        policy: args.policy.name().to_string(),
        target: args.target.clone(),
        reference: args.reference.clone(),
        outcome: "error".into(),
        reason: String::new(),
        seconds: 0.0,
        max_gripper_speed: 0.0,
        hit: Vec::new(),
        dir: args.out_dir.clone(),
        builtin_holds: None,
        llm: None,
    };
    let r = match reply {
        Ok(r) => r,
        Err(e) => {
            row.reason = e;
            return row;
        }
    };
    row.seconds = r.timings_s.values().sum();
    row.max_gripper_speed = r.max_gripper_speed;
    row.hit = r.carry_hits.clone();
    if !r.success {
        row.outcome = r.failure_reason.unwrap_or_else(|| "error".into());
        row.reason = r.message;
        return row;
    }
    let Some(after) = r.after else {
        row.reason = "the episode wrote no after-file".into();
        return row;
    };
    match judge(
        pool,
        &scene.dir,
        &after,
        spec.predicate,
        std::slice::from_ref(&args.target),
        std::slice::from_ref(&args.reference),
    ) {
        Ok(v) => match v.pairs.first() {
            Some(p) => {
                row.outcome = if p.holds { "success" } else { "placed_wrong" }.into();
                row.reason = p.reason.clone();
                row.builtin_holds = Some(p.holds);
            }
            None => row.reason = "the evaluator judged no pair".into(),
        },
        Err(e) => row.reason = format!("the evaluator failed: {e}"),
    }
    if let Some(judge) = llm {
        let state = JudgedState {
            scene_dir: &scene.dir,
            directives: &after,
            target: &args.target,
            reference: &args.reference,
        };
        match judge.judge(pool, spec, state) {
            Ok(v) => {
                row.outcome = if v.holds { "success" } else { "placed_wrong" }.into();
                row.reason = format!("LLM evaluator: {}", v.reason);
                row.llm = Some(v);
            }
            Err(e) => {
                row.outcome = "error".into();
                row.reason = format!("the LLM evaluator failed: {e}");
            }
        }
    }
    row
}

/// States both evaluators judged, and on how many they agree (with an LLM evaluator).
pub fn agreement(results: &RobotEvalResults) -> Option<(usize, usize)> {
    let initial = results.bindings.iter().filter_map(|b| {
        // The binding needs the built-in evaluator to call the initial state false.
        b.llm_initial.as_ref().map(|v| !v.holds)
    });
    let finals = results
        .episodes
        .iter()
        .filter_map(|e| Some(e.llm.as_ref()?.holds == e.builtin_holds?));
    let agree: Vec<bool> = initial.chain(finals).collect();
    (!agree.is_empty()).then(|| (agree.iter().filter(|a| **a).count(), agree.len()))
}

/// The table of success rates, Markdown.
pub fn table(results: &RobotEvalResults) -> String {
    let mut out = String::from(
        "| policy | episodes | successes | rate | 95 % CI | carried object hit something |\n\
         |---|---|---|---|---|---|\n",
    );
    for s in &results.summary {
        out.push_str(&format!(
            "| {} | {} | {} | {:.0} % | {:.0}-{:.0} % | {} |\n",
            s.policy,
            s.episodes,
            s.successes,
            100.0 * s.rate,
            100.0 * s.ci95[0],
            100.0 * s.ci95[1],
            s.hits
        ));
    }
    if let Some((k, n)) = agreement(results) {
        out.push_str(&format!(
            "\nThe LLM evaluator agrees with the built-in one on {k} of {n} judged states.\n"
        ));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::wilson95;

    #[test]
    fn the_wilson_interval_matches_known_values() {
        // 8 of 10: 0.490-0.943 (Wilson, z = 1.96).
        let [lo, hi] = wilson95(8, 10);
        assert!(
            (lo - 0.4902).abs() < 1e-3 && (hi - 0.9433).abs() < 1e-3,
            "{lo} {hi}"
        );
        assert_eq!(wilson95(0, 0), [0.0, 1.0]);
        let [lo, hi] = wilson95(0, 5);
        assert!(lo == 0.0 && (hi - 0.4345).abs() < 1e-3, "{hi}");
    }
}
