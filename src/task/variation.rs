//! Scene prompts for a task: what the task fixes, in every prompt; what it leaves open, drawn
//! per prompt from the room type's knowledge and the variation words of `tasks.json`.

use rand::rngs::ChaCha8Rng;
use rand::{RngExt, SeedableRng};

use super::analyse::words;
use super::{ScenePrompt, TaskSpec};
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

/// `n` scene prompts for `spec`, deterministic in `seed`. Every prompt names the object to
/// move on something other than the reference, and the reference; the room type cycles over
/// the fitting types; style, size, colour, the start (when the task names none) and one or two
/// more pieces of the room type's furniture vary.
pub fn prompts(spec: &TaskSpec, n: usize, seed: u64) -> Vec<ScenePrompt> {
    let w = words();
    let kb = knowledge();
    (0..n)
        .map(|i| {
            let mut rng =
                ChaCha8Rng::seed_from_u64(seed.wrapping_mul(0x9E37_79B9).wrapping_add(i as u64));
            let room_type = spec.room_types[i % spec.room_types.len().max(1)].clone();
            let room = kb.room(&room_type);
            let room_word = room
                .and_then(|r| r.words.first().cloned())
                .unwrap_or_else(|| room_type.replace('_', " "));
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
            let start = match (&spec.start, room) {
                (Some(s), _) => s.clone(),
                (None, Some(r)) => pick(&mut rng, &holders(r, &spec.target, &used))
                    .map_or_else(|| "table".to_string(), |s| s.to_string()),
                (None, None) => "table".to_string(),
            };
            used.push(start.clone());
            let reference = if is_small(&spec.reference) {
                let host = room
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
            let extras: Vec<String> = match room {
                Some(r) => {
                    let mut pool: Vec<&str> = r
                        .furniture
                        .iter()
                        .map(|i| i.noun.as_str())
                        .filter(|n| !used.iter().any(|u| u == n))
                        .collect();
                    // Distinct nouns, so the draw below always ends.
                    pool.sort_unstable();
                    pool.dedup();
                    let [lo, hi] = w.extra_furniture;
                    let k = rng.random_range(lo..=hi.max(lo)).min(pool.len());
                    let mut chosen: Vec<&str> = Vec::new();
                    while chosen.len() < k {
                        if let Some(p) = pick(&mut rng, &pool)
                            && !chosen.contains(p)
                        {
                            chosen.push(p);
                        }
                    }
                    chosen.into_iter().map(with_article).collect()
                }
                None => Vec::new(),
            };
            let opening = [size.as_str(), style.as_str(), room_word.as_str()]
                .iter()
                .filter(|s| !s.is_empty())
                .copied()
                .collect::<Vec<_>>()
                .join(" ");
            let mut parts = vec![
                reference,
                format!(
                    "{} with {} on it",
                    with_article(&start),
                    with_article(&target)
                ),
            ];
            parts.extend(extras);
            let last = parts.pop().unwrap_or_default();
            let list = if parts.is_empty() {
                last
            } else {
                format!("{}, and {last}", parts.join(", "))
            };
            let opening = with_article(&opening);
            let mut prompt = format!("{opening} with {list}.");
            if let Some(first) = prompt.get(..1) {
                prompt = first.to_uppercase() + &prompt[1..];
            }
            ScenePrompt {
                id: format!("scene_{i:03}"),
                prompt,
                seed: seed.wrapping_add(i as u64),
                room_type,
            }
        })
        .collect()
}
