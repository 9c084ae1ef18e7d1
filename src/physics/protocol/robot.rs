//! The robot operations (`drake_bridge/robot_ops.py`): one pick-and-place episode of the mobile
//! iiwa (`drake_bridge/policy/`), and the built-in evaluator's verdicts on a scene's directives
//! (`drake_bridge/evaluator/`).

use std::collections::BTreeMap;
use std::path::PathBuf;

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

use super::op;

op!(
    /// Plans and simulates one pick-and-place episode on a scene directory.
    PolicyEpisode, "policy_episode", EpisodeArgs, EpisodeReply
);
op!(
    /// Judges a predicate between bound objects on a scene's directives (or an after-file).
    JudgeTask, "judge_task", JudgeArgs, JudgeReply
);
op!(
    /// Runs one of the evaluator's state or vision tools on a scene's directives (what an LLM
    /// evaluator calls).
    EvaluatorTool, "evaluator_tool", EvalToolArgs, EvalToolReply
);

/// The relation a task asks for, as the bridge spells it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum TaskPredicate {
    /// On the reference's top or a shelf of it.
    On,
    /// Inside the reference.
    Inside,
    /// Within 15 cm of the reference.
    Near,
}

/// Which policy an episode runs.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum PolicyKind {
    /// Carrying clearance and gripper speed and acceleration limits.
    Standard,
    /// Neither.
    Degraded,
}

impl PolicyKind {
    /// The name in files and tables.
    pub fn name(self) -> &'static str {
        match self {
            PolicyKind::Standard => "standard",
            PolicyKind::Degraded => "degraded",
        }
    }
}

/// Arguments of `policy_episode`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct EpisodeArgs {
    /// The scene directory (`scene.dmd.yaml`, `package.xml`, `scene.json`).
    pub scene_dir: PathBuf,
    /// The relation to bring about.
    pub predicate: TaskPredicate,
    /// Model instance of the free object to move.
    pub target: String,
    /// Model instance of the reference.
    pub reference: String,
    /// The policy.
    pub policy: PolicyKind,
    /// Where the episode's files go.
    pub out_dir: PathBuf,
    /// Seed of the sampling (grasps, RRT).
    pub seed: u64,
    /// Render the PNG frames and the flipbook.
    pub frames: bool,
}

/// Reply to `policy_episode`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct EpisodeReply {
    /// The episode executed: a plan was found and the rollout released the object without
    /// dropping it (whether the goal holds is the evaluator's call).
    pub success: bool,
    /// `no_base_pose`, `no_grasp`, `ik`, `planning`, `dropped` or `timeout`.
    pub failure_reason: Option<String>,
    /// What happened, in words.
    pub message: String,
    /// Wall seconds per phase.
    pub timings_s: BTreeMap<String, f64>,
    /// Simulated seconds of the rollout.
    pub simulated_s: f64,
    /// Largest planned gripper speed, m/s.
    pub max_gripper_speed: f64,
    /// Free bodies welded for speed.
    pub welded: usize,
    /// The scene instances the carried object hit: touched between the grasp and the release,
    /// but neither at the grasp (its support, its neighbours) nor at the release (where it was
    /// put).
    pub carry_hits: Vec<String>,
    /// The scene's directives with the final poses (`after_<policy>.dmd.yaml`), when written.
    pub after: Option<PathBuf>,
    /// Every file the episode wrote.
    pub files: Vec<PathBuf>,
}

/// Arguments of `judge_task`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct JudgeArgs {
    /// The scene directory.
    pub scene_dir: PathBuf,
    /// The directives judged (`scene.dmd.yaml` or an after-file), absolute or relative to
    /// `scene_dir`.
    pub directives: PathBuf,
    /// The relation.
    pub predicate: TaskPredicate,
    /// Candidate objects to move (model instances).
    pub targets: Vec<String>,
    /// Candidate references (model instances).
    pub references: Vec<String>,
}

/// The verdict on one (target, reference) pair.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct PairVerdict {
    /// The object.
    pub target: String,
    /// The reference.
    pub reference: String,
    /// Whether the relation holds.
    pub holds: bool,
    /// Why, in words.
    pub reason: String,
    /// The numeric measurements used (metres, fractions, degrees).
    pub evidence: BTreeMap<String, f64>,
}

/// Reply to `judge_task`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct JudgeReply {
    /// One verdict per candidate pair.
    pub pairs: Vec<PairVerdict>,
    /// The thresholds the verdicts used.
    pub thresholds: BTreeMap<String, f64>,
}

/// The evaluator's tools, as an LLM evaluator calls them.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "snake_case")]
pub enum EvalTool {
    /// Objects of the scene (optionally of one category): id, category, kind, free or welded.
    ListObjects,
    /// One object: category, pose, size, its support.
    GetObjectInfo,
    /// Signed distance between two objects (Drake, metres; negative when penetrating).
    GetDistance,
    /// Where `other_id` is relative to `object_id`: gaps per axis in the reference's frame,
    /// overlap, above / below / inside.
    GetSpatialRelation,
    /// What holds an object up: contacts and the surface overlap percentage.
    GetSupport,
    /// Images of the whole scene.
    ObserveScene,
    /// Images framing `object_ids`.
    ObserveObjects,
}

/// Arguments of `evaluator_tool`: the tool and the arguments it takes (the others absent).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct EvalToolArgs {
    /// The scene directory.
    pub scene_dir: PathBuf,
    /// The directives observed (`scene.dmd.yaml` or an after-file), absolute or relative to
    /// `scene_dir`.
    pub directives: PathBuf,
    /// The tool.
    pub tool: EvalTool,
    /// The object (get_object_info, get_support; the first of get_distance and
    /// get_spatial_relation, the reference of the latter).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub object_id: Option<String>,
    /// The second object (get_distance, get_spatial_relation).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub other_id: Option<String>,
    /// A category filter (list_objects).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub category: Option<String>,
    /// The objects to frame (observe_objects).
    #[serde(default)]
    pub object_ids: Vec<String>,
}

/// A rendered image.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct ToolImage {
    /// What it shows ("top", "front", ...).
    pub name: String,
    /// The PNG, base64.
    pub png_base64: String,
}

/// Reply to `evaluator_tool`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct EvalToolReply {
    /// The tool's result as JSON text (an object; `{"error": ...}` for a bad argument such as
    /// an unknown object id, which the caller shows the model rather than failing).
    pub result_json: String,
    /// Images (the vision tools).
    pub images: Vec<ToolImage>,
}
