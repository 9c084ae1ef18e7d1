//! Words of a prompt for the brief: tokens with byte offsets, sentences and clauses, room
//! mentions with their counts, ordinals and size words, and the materials and ceiling heights
//! a clause names.

use crate::layout::knowledge::{knowledge, material_word, room_words};
use crate::prompt::singular;

/// A lower-case word with its byte range in the prompt.
#[derive(Debug, Clone)]
pub(super) struct Tok {
    pub(super) w: String,
    pub(super) start: usize,
}

/// Words of `text[from..to]` as [`crate::prompt::tokenize`] splits them, with byte offsets.
pub(super) fn tokens(text: &str, from: usize, to: usize) -> Vec<Tok> {
    let mut out = Vec::new();
    let mut cur: Option<usize> = None;
    let slice = &text[from..to];
    let push = |out: &mut Vec<Tok>, s: usize, e: usize| {
        let raw = &text[s..e];
        let trimmed = raw.trim_matches('-');
        if trimmed.is_empty() {
            return;
        }
        let lead = raw.len() - raw.trim_start_matches('-').len();
        out.push(Tok {
            w: trimmed.to_lowercase(),
            start: s + lead,
        });
    };
    for (i, c) in slice.char_indices() {
        let inside = c.is_alphanumeric() || c == '-' || c == '\'';
        match (inside, cur) {
            (true, None) => cur = Some(from + i),
            (false, Some(s)) => {
                push(&mut out, s, from + i);
                cur = None;
            }
            _ => {}
        }
    }
    if let Some(s) = cur {
        push(&mut out, s, to);
    }
    // Possessive "'s" belongs to the word only in room words ("kid's room"); elsewhere drop it.
    for t in &mut out {
        if let Some(stem) = t.w.strip_suffix("'s")
            && !room_words()
                .iter()
                .any(|(w, _)| w.iter().any(|x| x == &t.w))
        {
            t.w = stem.to_string();
        }
        t.w = t.w.trim_matches('\'').to_string();
    }
    out
}

/// Byte ranges of the sentences of `text` (split at `.`, `!`, `?`, `;` followed by a space).
pub(super) fn sentences(text: &str) -> Vec<(usize, usize)> {
    let mut out = Vec::new();
    let mut start = 0;
    let chars: Vec<(usize, char)> = text.char_indices().collect();
    for (k, &(i, c)) in chars.iter().enumerate() {
        if matches!(c, '.' | '!' | '?' | ';' | '\n') {
            let next = chars.get(k + 1).map(|x| x.1);
            let prev = if k > 0 { Some(chars[k - 1].1) } else { None };
            let decimal = c == '.'
                && prev.is_some_and(|p| p.is_ascii_digit())
                && next.is_some_and(|n| n.is_ascii_digit());
            if !decimal && next.is_none_or(char::is_whitespace) {
                if text[start..i].trim().len() > 1 {
                    out.push((start, i + c.len_utf8()));
                }
                start = i + c.len_utf8();
            }
        }
    }
    if text[start..].trim().len() > 1 {
        out.push((start, text.len()));
    }
    out
}

pub(super) fn number_word(w: &str) -> Option<usize> {
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
        return Some(i);
    }
    match w {
        "a" | "an" | "single" | "another" => Some(1),
        "pair" | "couple" | "both" | "twin" => Some(2),
        _ => w.parse::<usize>().ok().filter(|n| *n <= 40),
    }
}

pub(super) fn ordinal_word(w: &str) -> Option<usize> {
    const WORDS: [&str; 10] = [
        "first", "second", "third", "fourth", "fifth", "sixth", "seventh", "eighth", "ninth",
        "tenth",
    ];
    WORDS
        .iter()
        .position(|x| *x == w)
        .map(|i| i + 1)
        .or(match w {
            "1st" => Some(1),
            "2nd" => Some(2),
            "3rd" => Some(3),
            "4th" => Some(4),
            "5th" => Some(5),
            "last" => Some(usize::MAX),
            _ => None,
        })
}

pub(super) fn size_word(w: &str) -> Option<f64> {
    match w {
        "tiny" | "small" | "compact" | "little" | "cozy" | "cosy" | "narrow" => Some(0.8),
        "large" | "big" | "spacious" | "huge" | "grand" | "generous" | "wide" => Some(1.25),
        _ => None,
    }
}

/// A room word found in the text.
#[derive(Debug, Clone)]
pub(super) struct Mention {
    pub(super) room_type: String,
    /// Token range of the words.
    pub(super) first: usize,
    pub(super) last: usize,
    pub(super) plural: bool,
    pub(super) label: String,
}

/// Room words in `toks`, longest match first, skipping modifiers ("bar counter").
pub(super) fn mentions(toks: &[Tok]) -> Vec<Mention> {
    let k = knowledge();
    let mut out = Vec::new();
    let mut i = 0;
    while i < toks.len() {
        let mut found = None;
        for (words, ty) in room_words() {
            let n = words.len();
            if i + n > toks.len() {
                continue;
            }
            let head_ok = (0..n - 1).all(|j| toks[i + j].w == words[j]);
            let last = &toks[i + n - 1].w;
            let sing = singular(last);
            if !head_ok || (*last != words[n - 1] && sing != words[n - 1]) {
                continue;
            }
            if let Some(next) = toks.get(i + n) {
                let nw = singular(&next.w);
                if k.house()
                    .not_room_after
                    .iter()
                    .any(|x| *x == next.w || *x == nw)
                {
                    continue;
                }
            }
            let label = words.join(" ");
            found = Some(Mention {
                room_type: ty.clone(),
                first: i,
                last: i + n - 1,
                plural: *last != words[n - 1],
                label,
            });
            break;
        }
        match found {
            Some(m) => {
                i = m.last + 1;
                out.push(m);
            }
            None => i += 1,
        }
    }
    out
}

pub(super) const STOP: [&str; 9] = ["and", "with", "of", "the", "its", "their", "or", "in", "to"];

/// Count written before the mention at token `at` ("two exam rooms"); `None` when there is
/// no number word (a bare plural, or "the kitchen").
pub(super) fn count_before(toks: &[Tok], at: usize) -> Option<usize> {
    for i in (at.saturating_sub(3)..at).rev() {
        let w = toks[i].w.as_str();
        if let Some(n) = number_word(w) {
            return Some(n);
        }
        if STOP.contains(&w) {
            return None;
        }
    }
    None
}

pub(super) fn determiner_before(toks: &[Tok], at: usize) -> Option<String> {
    for i in (at.saturating_sub(3)..at).rev() {
        let w = toks[i].w.as_str();
        if matches!(
            w,
            "the" | "its" | "their" | "this" | "that" | "each" | "every"
        ) {
            return Some(w.to_string());
        }
        if number_word(w).is_some() || matches!(w, "and" | "with" | "of" | "in") {
            return None;
        }
    }
    None
}

pub(super) fn ordinal_before(toks: &[Tok], at: usize) -> Option<usize> {
    for i in (at.saturating_sub(3)..at).rev() {
        if let Some(n) = ordinal_word(&toks[i].w) {
            return Some(n);
        }
        if STOP.contains(&toks[i].w.as_str()) && toks[i].w != "the" {
            return None;
        }
    }
    None
}

pub(super) fn size_before(toks: &[Tok], at: usize) -> Option<f64> {
    (at.saturating_sub(3)..at)
        .rev()
        .find_map(|i| size_word(&toks[i].w))
}

pub(super) const VERBS: [&str; 20] = [
    "has", "have", "contains", "contain", "features", "feature", "includes", "include", "holds",
    "hold", "is", "are", "offers", "gets", "comes", "houses", "displays", "provides", "opens",
    "should",
];

/// A clause: its byte range and the token index range inside its sentence's tokens.
#[derive(Debug, Clone)]
pub(super) struct Clause {
    pub(super) start: usize,
    pub(super) end: usize,
    pub(super) toks: Vec<Tok>,
}

/// Splits a sentence into clauses where a new subject room starts ("... and its bathroom has
/// ...", "...; the kitchen has ...").
pub(super) fn clauses(text: &str, start: usize, end: usize) -> Vec<Clause> {
    let toks = tokens(text, start, end);
    let ms = mentions(&toks);
    let mut cuts = vec![start];
    for m in &ms {
        if m.first == 0 {
            continue;
        }
        let verb_after = toks
            .get(m.last + 1)
            .is_some_and(|t| VERBS.contains(&t.w.as_str()));
        // Walk back over an ordinal to the determiner.
        let mut d = m.first - 1;
        if ordinal_word(&toks[d].w).is_some() && d > 0 {
            d -= 1;
        }
        let det = matches!(toks[d].w.as_str(), "the" | "its" | "their");
        let joined = d > 0 && matches!(toks[d - 1].w.as_str(), "and" | "while" | "whereas" | "but");
        if verb_after && det && (joined || d == 0) {
            let cut = if joined {
                toks[d - 1].start
            } else {
                toks[d].start
            };
            if cut > start {
                cuts.push(cut);
            }
        }
    }
    cuts.push(end);
    cuts.dedup();
    cuts.windows(2)
        .filter_map(|w| {
            let (s, e) = (w[0], w[1]);
            let toks = tokens(text, s, e);
            if toks.is_empty() {
                return None;
            }
            Some(Clause {
                start: s,
                end: e,
                toks,
            })
        })
        .collect()
}

/// Words that turn a clause into a statement about the whole house.
pub(super) fn house_wide(toks: &[Tok]) -> bool {
    let w: Vec<&str> = toks.iter().map(|t| t.w.as_str()).collect();
    let has = |x: &str| w.contains(&x);
    has("throughout")
        || w.windows(2).any(|p| {
            matches!(
                (p[0], p[1]),
                ("all", "rooms")
                    | ("every", "room")
                    | ("each", "room")
                    | ("all", "floors")
                    | ("all", "walls")
            )
        })
        || (toks.len() > 1
            && knowledge()
                .house()
                .house_nouns
                .iter()
                .any(|n| *n == w[1] && matches!(w[0], "the" | "this")))
}

/// A material named for floors or walls in a clause: `(floor, wall)`.
pub(super) fn materials_in(toks: &[Tok]) -> (Option<String>, Option<String>) {
    let mut floor = None;
    let mut wall = None;
    for (i, t) in toks.iter().enumerate() {
        let target = match t.w.as_str() {
            "floor" | "floors" | "flooring" | "floorboards" => &mut floor,
            "walls" | "wall" | "paneling" | "panelling" => &mut wall,
            _ => continue,
        };
        // "marble floors", "polished concrete floor"; "floors are hardwood", "walls of brick".
        let before = (i.saturating_sub(3)..i).rev();
        let linked = toks
            .get(i + 1)
            .is_some_and(|t| matches!(t.w.as_str(), "is" | "are" | "of" | "in" | "made"));
        let after = if linked {
            i + 2..(i + 5).min(toks.len())
        } else {
            0..0
        };
        for j in before.chain(after) {
            let two = toks
                .get(j + 1)
                .filter(|_| j + 1 != i)
                .map(|n| format!("{} {}", toks[j].w, n.w))
                .unwrap_or_default();
            if let Some(m) = material_word(&two).or_else(|| material_word(&toks[j].w)) {
                *target = Some(m.to_string());
                break;
            }
        }
    }
    (floor, wall)
}

/// Wall height named in a clause about ceilings, metres.
pub(super) fn wall_height_in(toks: &[Tok]) -> Option<f64> {
    if !toks.iter().any(|t| t.w.starts_with("ceiling")) {
        return None;
    }
    for (i, t) in toks.iter().enumerate() {
        // "3 m", "3-meter", "3.2 metres", "10 ft", "10-foot".
        let (num, unit) = match t.w.split_once('-') {
            Some((n, u)) => (n.to_string(), Some(u.to_string())),
            None => (t.w.clone(), toks.get(i + 1).map(|n| n.w.clone())),
        };
        let Ok(v) = num.parse::<f64>() else { continue };
        let metres = match unit.as_deref() {
            Some("m" | "meter" | "meters" | "metre" | "metres") => v,
            Some("ft" | "foot" | "feet") => v * 0.3048,
            _ => continue,
        };
        return Some(metres.clamp(2.2, 6.0));
    }
    let w: Vec<&str> = toks.iter().map(|t| t.w.as_str()).collect();
    if w.iter()
        .any(|x| matches!(*x, "high" | "tall" | "vaulted" | "double-height" | "lofty"))
    {
        return Some(3.3);
    }
    if w.contains(&"low") {
        return Some(2.4);
    }
    None
}
