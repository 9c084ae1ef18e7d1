//! Words of a prompt for the brief: sentences, size words, the clauses about the whole house,
//! and the materials and ceiling heights a clause names. Rooms and what belongs to them are the
//! prompt reader's ([`crate::prompt::read`]); this module only reads the architectural words the
//! reader does not model.

use crate::layout::knowledge::{knowledge, material_word, room_words};

/// A lower-case word of the prompt.
#[derive(Debug, Clone)]
pub(super) struct Tok {
    pub(super) w: String,
}

/// Words of `text[from..to]` as [`crate::words::tokenize`] splits them, with byte offsets.
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
        out.push(Tok {
            w: trimmed.to_lowercase(),
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

pub(super) fn size_word(w: &str) -> Option<f64> {
    match w {
        "tiny" | "small" | "compact" | "little" | "cozy" | "cosy" | "narrow" => Some(0.8),
        "large" | "big" | "spacious" | "huge" | "grand" | "generous" | "wide" => Some(1.25),
        _ => None,
    }
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
