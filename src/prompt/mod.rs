//! Reading a prompt: which room, how big, which objects with which counts, what is excluded.
//!
//! This is the deterministic reader the built-in designer relies on. It matches phrases from
//! data tables (room-type words, asset categories and aliases, number words), so adding a noun
//! is a data change.

use std::collections::BTreeMap;
use std::sync::OnceLock;

use serde::{Deserialize, Serialize};

use crate::assets::procedural;

/// How many of something the prompt asks for.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(tag = "kind", content = "n", rename_all = "snake_case")]
pub enum Count {
    /// "exactly five", or a plain number ("two chairs").
    Exactly(u32),
    /// "at least ten", "10+".
    AtLeast(u32),
    /// A plural without a number ("chairs", "some books", "multiple").
    Several,
}

impl Count {
    /// The smallest number that satisfies the count.
    pub fn minimum(self) -> u32 {
        match self {
            Count::Exactly(n) | Count::AtLeast(n) => n,
            Count::Several => 2,
        }
    }
}

/// One object the prompt names.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Mention {
    /// The asset category the noun maps to.
    pub category: String,
    /// The words as written (singular form).
    pub noun: String,
    /// How many.
    pub count: Count,
    /// True for "no TV", "without a rug".
    pub negated: bool,
}

/// What the reader took from a prompt.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Reading {
    /// Room type key (see `src/data/room_types.json`); `room` when nothing matched.
    pub room_type: String,
    /// Size factor from words such as "small" (0.8) or "large" (1.3).
    pub size_scale: f64,
    /// Named objects in prompt order.
    pub mentions: Vec<Mention>,
}

/// Room-type prior.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct RoomTypeInfo {
    /// Clear interior size (x, y), metres.
    pub size: [f64; 2],
    /// Wall height, metres.
    pub wall_height: f64,
    /// Default floor material.
    pub floor: String,
    /// Default wall material.
    pub wall: String,
    /// Words naming the type.
    pub words: Vec<String>,
    /// Starter objects (category -> count) used when the prompt names none.
    #[serde(default)]
    pub defaults: BTreeMap<String, u32>,
}

#[derive(Deserialize)]
struct RoomTable {
    room_types: BTreeMap<String, RoomTypeInfo>,
}

/// The room-type table.
pub fn room_types() -> &'static BTreeMap<String, RoomTypeInfo> {
    static TABLE: OnceLock<BTreeMap<String, RoomTypeInfo>> = OnceLock::new();
    TABLE.get_or_init(|| {
        serde_json::from_str::<RoomTable>(include_str!("../data/room_types.json"))
            .map(|t| t.room_types)
            .unwrap_or_default()
    })
}

/// Lowercase word tokens; anything but letters, digits and inner hyphens separates words
/// ("three-level" stays one word, so its number is not read as a count).
pub fn tokenize(text: &str) -> Vec<String> {
    text.to_lowercase()
        .split(|c: char| !(c.is_alphanumeric() || c == '-'))
        .map(|w| w.trim_matches('-'))
        .filter(|w| !w.is_empty())
        .map(str::to_string)
        .collect()
}

/// Singular form of an English noun (enough for furniture and household words).
pub fn singular(word: &str) -> String {
    const WHOLE: [(&str, &str); 6] = [
        ("people", "person"),
        ("children", "child"),
        ("mice", "mouse"),
        ("feet", "foot"),
        ("teeth", "tooth"),
        ("geese", "goose"),
    ];
    const SUFFIX: [(&str, &str); 12] = [
        ("shelves", "shelf"),
        ("knives", "knife"),
        ("leaves", "leaf"),
        ("loaves", "loaf"),
        ("ches", "ch"),
        ("shes", "sh"),
        ("sses", "ss"),
        ("xes", "x"),
        ("toes", "to"),
        ("oes", "o"),
        ("ies", "y"),
        ("zes", "z"),
    ];
    if let Some((_, s)) = WHOLE.iter().find(|(p, _)| *p == word) {
        return s.to_string();
    }
    for (plural, single) in SUFFIX {
        if let Some(stem) = word.strip_suffix(plural)
            && (stem.len() > 1 || plural.len() >= 6)
        {
            return format!("{stem}{single}");
        }
    }
    if word.ends_with("ss") || word.ends_with("us") || word.ends_with("is") || word.len() <= 3 {
        return word.to_string();
    }
    word.strip_suffix('s').unwrap_or(word).to_string()
}

fn number_word(w: &str) -> Option<u32> {
    const WORDS: [&str; 21] = [
        "zero",
        "one",
        "two",
        "three",
        "four",
        "five",
        "six",
        "seven",
        "eight",
        "nine",
        "ten",
        "eleven",
        "twelve",
        "thirteen",
        "fourteen",
        "fifteen",
        "sixteen",
        "seventeen",
        "eighteen",
        "nineteen",
        "twenty",
    ];
    if let Some(i) = WORDS.iter().position(|x| *x == w) {
        return Some(i as u32);
    }
    match w {
        "thirty" => Some(30),
        "forty" => Some(40),
        "fifty" => Some(50),
        "a" | "an" | "single" => Some(1),
        "pair" | "couple" => Some(2),
        "dozen" => Some(12),
        _ => w.parse::<u32>().ok().filter(|n| *n <= 1000),
    }
}

/// Reads the count written just before token `at` (the first word of a noun phrase), skipping
/// up to three adjectives.
fn count_before(tokens: &[String], at: usize, plural: bool) -> Count {
    let lo = at.saturating_sub(4);
    for i in (lo..at).rev() {
        let w = tokens[i].as_str();
        if let Some(n) = number_word(w) {
            let prev = if i >= 1 { tokens[i - 1].as_str() } else { "" };
            let prev2 = if i >= 2 { tokens[i - 2].as_str() } else { "" };
            if (prev2 == "at" && prev == "least") || prev == "minimum" {
                return Count::AtLeast(n);
            }
            if n == 1 && plural {
                // "a pair of", "a set of" handled by caller; "a few chairs" is several.
                return Count::Several;
            }
            return Count::Exactly(n);
        }
        if matches!(w, "some" | "several" | "multiple" | "many" | "few") {
            return Count::Several;
        }
        if matches!(w, "and" | "with" | "of" | "on" | "in" | "the" | "each") {
            break;
        }
    }
    if plural {
        Count::Several
    } else {
        Count::Exactly(1)
    }
}

fn negated_before(tokens: &[String], at: usize) -> bool {
    let lo = at.saturating_sub(3);
    tokens[lo..at]
        .iter()
        .any(|w| matches!(w.as_str(), "no" | "without" | "not" | "nor"))
}

/// Reads a prompt.
pub fn read(prompt: &str) -> Reading {
    let tokens = tokenize(prompt);
    let joined = format!(" {} ", tokens.join(" "));

    // Room type: the earliest-mentioned type word wins; longer words first at equal position.
    let mut room_type = "room".to_string();
    let mut best: Option<(usize, usize)> = None;
    for (key, info) in room_types() {
        for word in &info.words {
            let needle = format!(" {word} ");
            if let Some(pos) = joined.find(&needle) {
                let cand = (pos, usize::MAX - word.len());
                if best.is_none_or(|b| cand < b) {
                    best = Some(cand);
                    room_type = key.clone();
                }
            }
        }
    }

    let size_scale = if tokens
        .iter()
        .any(|w| matches!(w.as_str(), "tiny" | "compact" | "small" | "cozy" | "little"))
    {
        0.8
    } else if tokens
        .iter()
        .any(|w| matches!(w.as_str(), "large" | "spacious" | "big" | "huge" | "grand"))
    {
        1.3
    } else {
        1.0
    };

    // Objects: longest phrase match (up to three words) at each position.
    let mut mentions: Vec<Mention> = Vec::new();
    let mut i = 0;
    while i < tokens.len() {
        let mut matched = None;
        for len in (1..=3).rev() {
            if i + len > tokens.len() {
                continue;
            }
            let words = &tokens[i..i + len];
            let last = words[len - 1].as_str();
            let sing = singular(last);
            let mut phrase: Vec<&str> = words[..len - 1].iter().map(String::as_str).collect();
            phrase.push(&sing);
            let phrase = phrase.join(" ");
            if let Some(cat) = procedural::resolve_category(&phrase) {
                matched = Some((len, cat.to_string(), phrase, sing != last));
                break;
            }
        }
        match matched {
            Some((len, category, noun, plural)) => {
                // "room" words are handled above; skip "shelf" inside "shelf unit" etc. by the
                // longest-match rule.
                let count = count_before(&tokens, i, plural);
                let negated = negated_before(&tokens, i);
                mentions.push(Mention {
                    category,
                    noun,
                    count,
                    negated,
                });
                i += len;
            }
            None => i += 1,
        }
    }
    Reading {
        room_type,
        size_scale,
        mentions,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_and_room_type() {
        let r = read("A small kitchen with a table, four chairs and at least 10 mugs.");
        assert_eq!(r.room_type, "kitchen");
        assert_eq!(r.size_scale, 0.8);
        let by_cat: BTreeMap<_, _> = r
            .mentions
            .iter()
            .map(|m| (m.category.as_str(), m.count))
            .collect();
        assert_eq!(by_cat["table"], Count::Exactly(1));
        assert_eq!(by_cat["chair"], Count::Exactly(4));
        assert_eq!(by_cat["mug"], Count::AtLeast(10));
    }

    #[test]
    fn plurals_aliases_and_negation() {
        let r = read("An office with bookshelves, some plates, and no cabinet.");
        assert_eq!(r.room_type, "office");
        let shelf = r
            .mentions
            .iter()
            .find(|m| m.category == "bookshelf")
            .unwrap();
        assert_eq!(shelf.count, Count::Several);
        let cab = r.mentions.iter().find(|m| m.category == "cabinet").unwrap();
        assert!(cab.negated);
        let plate = r.mentions.iter().find(|m| m.category == "plate").unwrap();
        assert_eq!(plate.count, Count::Several);
    }

    #[test]
    fn unknown_room_is_plain_room() {
        let r = read("Something with a chair.");
        assert_eq!(r.room_type, "room");
        assert_eq!(r.mentions.len(), 1);
    }

    #[test]
    fn singulars() {
        assert_eq!(singular("shelves"), "shelf");
        assert_eq!(singular("libraries"), "library");
        assert_eq!(singular("glass"), "glass");
        assert_eq!(singular("chairs"), "chair");
        assert_eq!(singular("bus"), "bus");
        assert_eq!(singular("bookshelves"), "bookshelf");
        assert_eq!(singular("benches"), "bench");
        assert_eq!(singular("potatoes"), "potato");
        assert_eq!(singular("boxes"), "box");
    }
}
