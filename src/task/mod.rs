//! Robot tasks -> scene prompts: what a pick-and-place task needs of a scene, N varied scene
//! prompts that hold it, and the check of a generated scene against it.
//!
//! [`analyse`] reads a task such as "pick up the mug from the table and place it on the shelf"
//! with a small grammar whose words are data (`src/data/tasks.json`): a verb starts the moved
//! object's phrase, a predicate phrase ("on", "into", "next to") ends it and starts the
//! reference's, a `from` phrase names where the object starts. Each phrase is grounded by the
//! prompt reader (lexicon and WordNet), so any noun the reader knows works. The room types
//! that fit are the knowledge base's types whose typical contents hold the reference, the
//! object and its start, best first. [`prompts`] writes N scene prompts varying what the
//! task leaves open (the room type, style, size, the object's colour, where it starts, extra
//! furniture), always with the object away from the reference so the goal does not hold at
//! the start. [`check_scene`] says whether a generated scene has the objects and whether the
//! goal is already true in it.

mod analyse;
mod check;
pub mod llm;
pub mod llm_judge;
pub mod robot_eval;
pub mod scenes;
mod variation;

use serde::{Deserialize, Serialize};

pub use analyse::{FLOOR, analyse};
pub use check::{SceneCheck, check_scene, goal_holds};
pub use variation::prompts;

/// The relation a task asks for between the moved object and the reference.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Predicate {
    /// Resting on the reference (on its top or a shelf of it).
    On,
    /// Inside the reference (a container, a drawer, a cabinet).
    Inside,
    /// Within [`NEAR_M`] of the reference.
    Near,
}

impl Predicate {
    /// The predicate's word in prompts and messages.
    pub fn word(self) -> &'static str {
        match self {
            Predicate::On => "on",
            Predicate::Inside => "inside",
            Predicate::Near => "near",
        }
    }
}

/// Largest gap between the moved object and the reference that counts as "near", metres
/// (between their bounding boxes).
pub const NEAR_M: f64 = 0.15;

/// What a task needs of a scene.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TaskSpec {
    /// The task as written.
    pub task: String,
    /// The relation asked for.
    pub predicate: Predicate,
    /// The object to move: the reader's canonical noun ("mug").
    pub target: String,
    /// Words the task binds to the object ("red"), kept in every prompt.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub target_words: Vec<String>,
    /// Where the object should end up: canonical noun ("shelf").
    pub reference: String,
    /// What the reference stands on when the task says ("a plate on the dining table").
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub reference_on: Option<String>,
    /// Where the object starts when the task says ("from the table"); [`FLOOR`] for "from
    /// the floor".
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub start: Option<String>,
    /// Room-type keys of the knowledge base that fit, best first; for a task across rooms,
    /// the start room's type and the goal room's.
    pub room_types: Vec<String>,
    /// For a task across rooms ("bring the bottle from the kitchen to the coffee table in the
    /// living room"): every scene is a house with both rooms, the object starts in one and the
    /// reference stands in the other.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub across: Option<AcrossRooms>,
    /// Objects every scene must hold (the target, the reference, the start if named).
    pub required: Vec<String>,
    /// The initial-state constraint, in words: the goal must not hold at the start.
    pub initial_state: String,
    /// What the scenes may vary.
    pub flexible: Vec<String>,
}

/// The two rooms of a task across rooms (room-type keys of the knowledge base).
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct AcrossRooms {
    /// Where the object to move starts ("kitchen").
    pub start_room: String,
    /// Where the reference stands ("living_room").
    pub goal_room: String,
}

/// The rooms a task names, by role: the object's ("from the kitchen", "the mug in the
/// kitchen") and the reference's ("to the coffee table in the living room").
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct NamedRooms {
    /// The room the object starts in.
    pub start: Option<String>,
    /// The room the reference stands in.
    pub goal: Option<String>,
}

/// One scene prompt written for a task.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ScenePrompt {
    /// Identifier (`scene_000`, ...).
    pub id: String,
    /// The scene prompt.
    pub prompt: String,
    /// Seed for `generate`.
    pub seed: u64,
    /// Room type the prompt asks for (`house` for a task across rooms).
    pub room_type: String,
}

/// Why a task could not be read.
#[derive(Debug, thiserror::Error, PartialEq)]
pub enum TaskError {
    /// Nothing to read.
    #[error("the task is empty")]
    Empty,
    /// No "on" / "into" / "next to" phrase.
    #[error(
        "no goal relation in {0:?}: say where the object should go, e.g. \"put the mug on the shelf\", \"into the bowl\", \"next to the lamp\""
    )]
    NoRelation(String),
    /// A phrase names no object the reader grounds.
    #[error("{role} {phrase:?} names no object the reader knows")]
    NotAnObject {
        /// "the object to move", "the reference", "the start".
        role: &'static str,
        /// The phrase.
        phrase: String,
    },
    /// The object and the reference are the same noun.
    #[error("the task moves a {0} relative to a {0}; name two different objects")]
    SameObject(String),
    /// The language model could not be reached or gave no usable reading.
    #[error("reading the task with the LLM: {0}")]
    Llm(String),
}

#[cfg(test)]
mod tests;
