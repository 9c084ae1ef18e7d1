//! Reading a task: the moved object, the relation, the reference, where the object starts,
//! and the room types that fit.

use std::sync::OnceLock;

use serde::Deserialize;

use super::{AcrossRooms, NamedRooms, Predicate, TaskError, TaskSpec};
use crate::knowledge::knowledge;
use crate::knowledge::rooms::RoomType;

/// The task grammar's words (`src/data/tasks.json`).
#[derive(Debug, Deserialize)]
pub(super) struct TaskWords {
    verbs: Vec<String>,
    predicates: Vec<(String, Predicate)>,
    from: Vec<String>,
    pub(super) styles: Vec<String>,
    pub(super) sizes: Vec<String>,
    pub(super) colors: Vec<String>,
    pub(super) extra_furniture: [usize; 2],
}

pub(super) fn words() -> &'static TaskWords {
    static WORDS: OnceLock<TaskWords> = OnceLock::new();
    WORDS.get_or_init(|| {
        // The file is compiled in and checked by a unit test; an empty grammar reads nothing.
        serde_json::from_str(include_str!("../data/tasks.json")).unwrap_or(TaskWords {
            verbs: Vec::new(),
            predicates: Vec::new(),
            from: Vec::new(),
            styles: Vec::new(),
            sizes: Vec::new(),
            colors: Vec::new(),
            extra_furniture: [0, 0],
        })
    })
}

/// Words that open or fill a phrase without naming anything.
const FILLERS: &[&str] = &[
    "the", "a", "an", "this", "that", "these", "those", "my", "your", "its", "their", "some", "it",
    "them", "one", "please", "and", "then", "up",
];

/// A task's words: lower case, punctuation as its own token.
fn split(task: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut word = String::new();
    for c in task.chars() {
        if c.is_alphanumeric() || c == '-' || c == '\'' {
            word.extend(c.to_lowercase());
        } else {
            if !word.is_empty() {
                out.push(std::mem::take(&mut word));
            }
            if matches!(c, ',' | '.' | ';' | ':' | '!' | '?') {
                out.push(c.to_string());
            }
        }
    }
    if !word.is_empty() {
        out.push(word);
    }
    out
}

/// Whether `phrase` (space-separated words) starts at token `at`: its length in tokens.
fn phrase_at(tokens: &[String], at: usize, phrase: &str) -> Option<usize> {
    let words: Vec<&str> = phrase.split_whitespace().collect();
    let fits = words.len() <= tokens.len().saturating_sub(at)
        && words.iter().zip(&tokens[at..]).all(|(w, t)| w == t);
    fits.then_some(words.len())
}

/// The longest of `phrases` starting at `at`, with its length.
fn longest_at<'a>(
    tokens: &[String],
    at: usize,
    phrases: impl Iterator<Item = &'a str>,
) -> Option<(usize, &'a str)> {
    phrases
        .filter_map(|p| phrase_at(tokens, at, p).map(|n| (n, p)))
        .max_by_key(|(n, _)| *n)
}

fn predicate_at(tokens: &[String], at: usize) -> Option<(usize, Predicate)> {
    let w = words();
    let (n, phrase) = longest_at(tokens, at, w.predicates.iter().map(|(p, _)| p.as_str()))?;
    let pred = w.predicates.iter().find(|(p, _)| p == phrase)?.1;
    Some((n, pred))
}

fn is_boundary(t: &str) -> bool {
    t == "and" || t == "then" || t.chars().all(|c| c.is_ascii_punctuation())
}

/// Tokens from `at` up to the next boundary, relation or `from` phrase.
fn phrase_end(tokens: &[String], at: usize) -> usize {
    let w = words();
    (at..tokens.len())
        .find(|&i| {
            is_boundary(&tokens[i])
                || predicate_at(tokens, i).is_some()
                || longest_at(tokens, i, w.from.iter().map(String::as_str)).is_some()
        })
        .unwrap_or(tokens.len())
}

/// A phrase grounded: the reader's canonical noun and the phrase's other content words.
pub(super) struct Grounded {
    pub(super) noun: String,
    pub(super) words: Vec<String>,
}

/// Grounds a phrase through the prompt reader (lexicon, WordNet families); `None` when it
/// names no physical object. A room word ("the kitchen") is no object.
fn ground(phrase: &[String]) -> Option<Grounded> {
    let content: Vec<&str> = phrase
        .iter()
        .map(String::as_str)
        .filter(|w| !FILLERS.contains(w))
        .collect();
    if content.is_empty() {
        return None;
    }
    let text = content.join(" ");
    if knowledge().room_type_of(&text).is_some() {
        return None;
    }
    let reading = crate::prompt::read(&format!("a room with a {text}"));
    let mention = reading.mentions.iter().find(|m| !m.negated)?;
    let a = &mention.attributes;
    let mut words: Vec<String> = Vec::new();
    for w in a.colors.iter().chain(&a.materials).chain(&a.adjectives) {
        if !words.contains(w) {
            words.push(w.clone());
        }
    }
    Some(Grounded {
        noun: mention.category.clone(),
        words,
    })
}

/// The start of an object that lies on the floor ("pick the cup from the floor"): no object,
/// so never required, but every scene puts the object there.
pub const FLOOR: &str = "floor";

/// Whether a phrase names the floor ("the floor", "the ground").
fn names_floor(phrase: &[String]) -> bool {
    let content: Vec<&str> = phrase
        .iter()
        .map(String::as_str)
        .filter(|w| !FILLERS.contains(w))
        .collect();
    matches!(content.as_slice(), ["floor"] | ["ground"])
}

/// The room type a phrase names ("the kitchen"), if any.
fn room_named(phrase: &[String]) -> Option<String> {
    let content: Vec<&str> = phrase
        .iter()
        .map(String::as_str)
        .filter(|w| !FILLERS.contains(w))
        .collect();
    knowledge()
        .room_type_of(&content.join(" "))
        .map(str::to_string)
}

/// Reads a task. See the module documentation.
pub fn analyse(task: &str) -> Result<TaskSpec, TaskError> {
    let tokens = split(task);
    if tokens.iter().all(|t| is_boundary(t)) {
        return Err(TaskError::Empty);
    }
    let w = words();
    // The moved object's phrase starts after the first verb (or at the start).
    let verb_end = (0..tokens.len())
        .find_map(|i| {
            longest_at(&tokens, i, w.verbs.iter().map(String::as_str)).map(|(n, _)| i + n)
        })
        .unwrap_or(0);
    let target_end = phrase_end(&tokens, verb_end);
    let target_phrase = &tokens[verb_end..target_end];
    let target = ground(target_phrase).ok_or_else(|| TaskError::NotAnObject {
        role: "the object to move",
        phrase: target_phrase.join(" "),
    })?;
    // Then, in any order: a `from` phrase, the relation and its reference, rooms. A room in a
    // `from` phrase or before the relation is the object's; one after it is the reference's.
    let (mut start, mut relation, mut reference_on) = (None, None, None);
    let mut rooms = NamedRooms::default();
    let mut i = target_end;
    while i < tokens.len() {
        if let Some((n, _)) = longest_at(&tokens, i, w.from.iter().map(String::as_str)) {
            let end = phrase_end(&tokens, i + n);
            let phrase = &tokens[i + n..end];
            match room_named(phrase) {
                Some(r) => rooms.start = rooms.start.or(Some(r)),
                None if names_floor(phrase) => start = start.or(Some(FLOOR.to_string())),
                None => start = start.or(ground(phrase).map(|g| g.noun)),
            }
            i = end.max(i + 1);
        } else if let Some((n, pred)) = predicate_at(&tokens, i) {
            let end = phrase_end(&tokens, i + n);
            let phrase = &tokens[i + n..end];
            if let Some(r) = room_named(phrase) {
                let slot = if relation.is_none() {
                    &mut rooms.start
                } else {
                    &mut rooms.goal
                };
                *slot = slot.take().or(Some(r));
            } else if relation.is_none() {
                let reference = ground(phrase).ok_or_else(|| TaskError::NotAnObject {
                    role: "the reference",
                    phrase: phrase.join(" "),
                })?;
                relation = Some((pred, reference.noun));
            } else if pred == Predicate::On && reference_on.is_none() {
                // "on a plate on the dining table": where the reference stands.
                reference_on = ground(phrase).map(|g| g.noun);
            }
            i = end.max(i + 1);
        } else {
            i += 1;
        }
    }
    let Some((predicate, reference)) = relation else {
        return Err(TaskError::NoRelation(task.trim().to_string()));
    };
    build_spec(
        task,
        predicate,
        target,
        Reference {
            noun: reference,
            on: reference_on,
        },
        start,
        rooms,
    )
}

/// Grounds a free-text noun phrase ("red apple"), as the LLM reader hands them in.
pub(super) fn ground_text(text: &str) -> Option<Grounded> {
    ground(&split(text))
}

/// The room type a free-text phrase names, if any.
pub(super) fn room_of_text(text: &str) -> Option<String> {
    room_named(&split(text))
}

/// The reference as a task names it: its noun and what it stands on, when the task says
/// ("a plate on the dining table").
pub(super) struct Reference {
    pub(super) noun: String,
    pub(super) on: Option<String>,
}

/// The spec of a read task: rooms, required objects, the initial-state constraint and what
/// may vary.
pub(super) fn build_spec(
    task: &str,
    predicate: Predicate,
    target: Grounded,
    reference: Reference,
    start: Option<String>,
    rooms: NamedRooms,
) -> Result<TaskSpec, TaskError> {
    let Reference {
        noun: reference,
        on: reference_on,
    } = reference;
    let reference_on = reference_on.filter(|h| *h != reference && *h != target.noun);
    if reference == target.noun {
        return Err(TaskError::SameObject(reference));
    }
    let start = start.filter(|s| *s != reference && *s != target.noun);
    let across = match (&rooms.start, &rooms.goal) {
        (Some(a), Some(b)) if a != b => Some(AcrossRooms {
            start_room: a.clone(),
            goal_room: b.clone(),
        }),
        _ => None,
    };
    let room_types = match (&across, rooms.start.or(rooms.goal)) {
        (Some(x), _) => vec![x.start_room.clone(), x.goal_room.clone()],
        (None, Some(r)) => vec![r],
        (None, None) => fitting_rooms(
            &target.noun,
            &reference,
            start.as_deref().or(reference_on.as_deref()),
        ),
    };
    let mut required = vec![target.noun.clone(), reference.clone()];
    required.extend(start.clone().filter(|s| s != FLOOR));
    required.extend(reference_on.clone().filter(|h| !required.contains(h)));
    let initial_state = format!(
        "no {} is {} a {} at the start",
        target.noun,
        predicate.word(),
        reference
    );
    let mut flexible = vec![
        if across.is_some() {
            "the house's other rooms".to_string()
        } else {
            "room type".to_string()
        },
        "style".to_string(),
        "room size".to_string(),
        "other furniture".to_string(),
    ];
    if target.words.is_empty() {
        flexible.push(format!("the {}'s colour", target.noun));
    }
    if start.is_none() {
        flexible.push(format!("where the {} starts", target.noun));
    }
    Ok(TaskSpec {
        task: task.trim().to_string(),
        predicate,
        target: target.noun,
        target_words: target.words,
        reference,
        reference_on,
        start,
        room_types,
        across,
        required,
        initial_state,
        flexible,
    })
}

/// How well a room type's typical contents fit the task: the reference counts most, then the
/// object, then its start.
fn fit(room: &RoomType, target: &str, reference: &str, start: Option<&str>) -> u32 {
    let has_piece =
        |noun: &str| room.item(noun).is_some() || room.surfaces.iter().any(|s| s.parent == noun);
    let has_small = |noun: &str| {
        room.surfaces
            .iter()
            .any(|s| s.items.iter().chain(&s.inside).any(|i| i == noun))
    };
    let mut score = 0;
    if has_piece(reference) || has_small(reference) {
        score += 4;
    }
    if has_small(target) || has_piece(target) {
        score += 2;
    }
    if start.is_some_and(has_piece) {
        score += 1;
    }
    score
}

/// Most room types a task's scenes spread over.
const MAX_ROOM_TYPES: usize = 4;

/// The knowledge base's room types that fit, best first; the living room when none holds
/// the reference or the object.
fn fitting_rooms(target: &str, reference: &str, start: Option<&str>) -> Vec<String> {
    let mut scored: Vec<(u32, &String)> = knowledge()
        .rooms()
        .iter()
        .map(|(key, room)| (fit(room, target, reference, start), key))
        .filter(|(s, _)| *s >= 2)
        .collect();
    scored.sort_by(|a, b| b.0.cmp(&a.0).then(a.1.cmp(b.1)));
    let best = scored.first().map_or(0, |s| s.0);
    let rooms: Vec<String> = scored
        .into_iter()
        .filter(|(s, _)| *s + 1 >= best)
        .take(MAX_ROOM_TYPES)
        .map(|(_, k)| k.clone())
        .collect();
    if rooms.is_empty() {
        vec!["living_room".to_string()]
    } else {
        rooms
    }
}
