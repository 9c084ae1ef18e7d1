//! Scene prompts for a task: what the task fixes, in every prompt; what it leaves open, drawn
//! per prompt from the room type's knowledge and the variation words of `tasks.json`.

use rand::rngs::ChaCha8Rng;
use rand::{RngExt, SeedableRng};

use super::analyse::words;
use super::{FLOOR, ScenePrompt, TaskSpec};
use crate::knowledge::knowledge;
use crate::knowledge::rooms::RoomType;
use crate::words::{Support, lexicon};

fn article(word: &str) -> &'static str {
    match word.chars().next() {
        Some('a' | 'e' | 'i' | 'o' | 'u') => "an",
        _ => "a",
    }
}

fn with_article(phrase: &str) -> String {
    format!("{} {phrase}", article(phrase))
}

fn pick<'a, T>(rng: &mut ChaCha8Rng, items: &'a [T]) -> Option<&'a T> {
    (!items.is_empty()).then(|| &items[rng.random_range(0..items.len())])
}

/// Floor furniture of the room type that carries small objects, other than `except`: the
/// pieces `small` usually rests on (its lexicon entry's `rests_on`, or a surface rule of the
/// room that lists it) when the room has any, else every piece with a surface rule.
fn holders<'a>(room: &'a RoomType, small: &str, except: &[String]) -> Vec<&'a str> {
    let usual = lexicon()
        .lookup(small)
        .map(|e| e.rests_on.clone())
        .unwrap_or_default();
    let pieces: Vec<&str> = room
        .furniture
        .iter()
        .map(|i| i.noun.as_str())
        .filter(|n| !except.iter().any(|e| e == n))
        .filter(|n| room.surfaces.iter().any(|s| s.parent == *n))
        .collect();
    let preferred: Vec<&str> = pieces
        .iter()
        .copied()
        .filter(|n| {
            usual.iter().any(|u| u == n)
                || room
                    .surface_rule(n)
                    .is_some_and(|s| s.items.iter().chain(&s.inside).any(|i| i == small))
        })
        .collect();
    if preferred.is_empty() {
        pieces
    } else {
        preferred
    }
}

/// Whether a colour suits the noun: not food, a plant or an animal (the lexicographer file of
/// its heaviest WordNet sense).
fn colourable(noun: &str) -> bool {
    crate::words::ground::noun_info(noun).is_none_or(|i| {
        !matches!(
            i.lexname.as_str(),
            "noun.food" | "noun.plant" | "noun.animal"
        )
    })
}

/// Whether the reference is a small object (it then needs a piece of furniture to stand on).
fn is_small(noun: &str) -> bool {
    lexicon()
        .lookup(noun)
        .is_some_and(|e| e.support == Support::Surface)
}

/// `k` (drawn from `tasks.json`'s `extra_furniture`) more pieces of `room`'s furniture, none
/// of them in `used`.
fn extras(rng: &mut ChaCha8Rng, room: Option<&RoomType>, used: &[String]) -> Vec<String> {
    let Some(r) = room else {
        return Vec::new();
    };
    let mut pool: Vec<&str> = r
        .furniture
        .iter()
        .map(|i| i.noun.as_str())
        .filter(|n| !used.iter().any(|u| u == n))
        .collect();
    // Distinct nouns, so the draw below always ends.
    pool.sort_unstable();
    pool.dedup();
    let [lo, hi] = words().extra_furniture;
    let k = rng.random_range(lo..=hi.max(lo)).min(pool.len());
    let mut chosen: Vec<&str> = Vec::new();
    while chosen.len() < k {
        if let Some(p) = pick(rng, &pool)
            && !chosen.contains(p)
        {
            chosen.push(p);
        }
    }
    chosen.into_iter().map(with_article).collect()
}

/// "a", "a and b", "a, b, and c".
fn listed(mut parts: Vec<String>) -> String {
    let last = parts.pop().unwrap_or_default();
    match parts.len() {
        0 => last,
        1 => format!("{} and {last}", parts[0]),
        _ => format!("{}, and {last}", parts.join(", ")),
    }
}

/// The non-empty words, joined by spaces.
fn spaced(words: &[&str]) -> String {
    words
        .iter()
        .filter(|w| !w.is_empty())
        .copied()
        .collect::<Vec<_>>()
        .join(" ")
}

fn capitalised(text: &str) -> String {
    let mut chars = text.chars();
    chars
        .next()
        .map_or_else(String::new, |c| c.to_uppercase().chain(chars).collect())
}

/// A room type's word in prompts ("living room").
fn room_word(room_type: &str) -> String {
    knowledge()
        .room(room_type)
        .and_then(|r| r.words.first().cloned())
        .unwrap_or_else(|| room_type.replace('_', " "))
}

/// `n` scene prompts for `spec`, deterministic in `seed`. Every prompt names the object to
/// move on something other than the reference, and the reference; the room type cycles over
/// the fitting types; style, size, colour, the start (when the task names none) and one or two
/// more pieces of the room type's furniture vary. For a task across rooms every prompt is a
/// house with the two rooms, both large, the object and its start in the one, the reference in
/// the other.
pub fn prompts(spec: &TaskSpec, n: usize, seed: u64) -> Vec<ScenePrompt> {
    let w = words();
    let kb = knowledge();
    (0..n)
        .map(|i| {
            let mut rng =
                ChaCha8Rng::seed_from_u64(seed.wrapping_mul(0x9E37_79B9).wrapping_add(i as u64));
            let (start_type, goal_type) = match &spec.across {
                Some(x) => (x.start_room.clone(), x.goal_room.clone()),
                None => {
                    let t = spec.room_types[i % spec.room_types.len().max(1)].clone();
                    (t.clone(), t)
                }
            };
            let (start_room, goal_room) = (kb.room(&start_type), kb.room(&goal_type));
            let style = pick(&mut rng, &w.styles).cloned().unwrap_or_default();
            let size = pick(&mut rng, &w.sizes).cloned().unwrap_or_default();
            let target = if spec.target_words.is_empty() && colourable(&spec.target) {
                let colour = pick(&mut rng, &w.colors).cloned().unwrap_or_default();
                format!("{colour} {}", spec.target).trim().to_string()
            } else {
                format!("{} {}", spec.target_words.join(" "), spec.target)
                    .trim()
                    .to_string()
            };
            let mut used: Vec<String> = vec![spec.reference.clone()];
            let start = match (&spec.start, start_room) {
                (Some(s), _) => s.clone(),
                (None, Some(r)) => pick(&mut rng, &holders(r, &spec.target, &used))
                    .map_or_else(|| "table".to_string(), |s| s.to_string()),
                (None, None) => "table".to_string(),
            };
            used.push(start.clone());
            let reference = if let Some(host) = &spec.reference_on {
                used.push(host.clone());
                format!(
                    "{} with {} on it",
                    with_article(host),
                    with_article(&spec.reference)
                )
            } else if is_small(&spec.reference) {
                let host = goal_room
                    .and_then(|r| {
                        pick(&mut rng, &holders(r, &spec.reference, &used)).map(|s| s.to_string())
                    })
                    .unwrap_or_else(|| "side table".to_string());
                let phrase = format!(
                    "{} with {} on it",
                    with_article(&host),
                    with_article(&spec.reference)
                );
                used.push(host);
                phrase
            } else {
                with_article(&spec.reference)
            };
            let start_part = if start == FLOOR {
                format!("{} on the floor", with_article(&target))
            } else {
                format!(
                    "{} with {} on it",
                    with_article(&start),
                    with_article(&target)
                )
            };
            let (prompt, room_type) = if spec.across.is_some() {
                let mut start_parts = vec![start_part];
                start_parts.extend(extras(&mut rng, start_room, &used));
                let mut goal_parts = vec![reference];
                goal_parts.extend(extras(&mut rng, goal_room, &used));
                let (a, b) = (room_word(&start_type), room_word(&goal_type));
                let opening = spaced(&[style.as_str(), "house"]);
                // Large rooms: a mobile robot needs floor in front of what it reaches for, and
                // the rooms of a house come out smaller than a room of its own.
                let prompt = format!(
                    "{} with a large {a} and a large {b}. The {a} has {}. The {b} has {}.",
                    capitalised(&with_article(&opening)),
                    listed(start_parts),
                    listed(goal_parts)
                );
                (prompt, "house".to_string())
            } else {
                let mut parts = vec![reference, start_part];
                parts.extend(extras(&mut rng, start_room, &used));
                let opening = spaced(&[
                    size.as_str(),
                    style.as_str(),
                    room_word(&start_type).as_str(),
                ]);
                let prompt = format!(
                    "{} with {}.",
                    capitalised(&with_article(&opening)),
                    listed(parts)
                );
                (prompt, start_type)
            };
            ScenePrompt {
                id: format!("scene_{i:03}"),
                prompt,
                seed: seed.wrapping_add(i as u64),
                room_type,
            }
        })
        .collect()
}
