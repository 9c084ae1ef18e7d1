//! Noun phrases: determiner, quantifier, number, ordinal, group word ("a stack of", "pairs
//! of"), modifiers and head — an object noun (longest lexicon match, compounds, or the
//! open-vocabulary rule), a room word, a landmark, a part ("the top level"), a pronoun.
//!
//! This module reads one phrase at a time; `chunk` decides where phrases start.

use super::attributes::{Attributes, modifier_at};
use super::lexicon::Lexicon;
use super::mentions::GroupKind;
use super::tokens::Token;
use crate::knowledge::Knowledge;

/// Pronouns the interpreter resolves.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Pronoun {
    /// "it"
    It,
    /// "them", "they"
    Them,
    /// "each other", "one another"
    EachOther,
    /// "one" as a subject ("where one displays ...")
    One,
    /// "the other" as a subject
    Other,
}

/// What a noun phrase names.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Head {
    /// An object noun.
    Object {
        /// Lexicon entry of the whole noun, if known.
        entry: Option<usize>,
        /// The noun as written, singular, lower case.
        noun: String,
        /// Canonical noun (entry noun, or `noun` when unknown).
        canonical: String,
        /// Lexicon entry of the last word when the whole noun is unknown.
        head_entry: Option<usize>,
    },
    /// A room-type word.
    Room {
        /// Knowledge-base key.
        key: String,
        /// Words as written (singular).
        words: String,
    },
    /// Wall, corner, ceiling, window, ... (lexicon landmark class).
    Landmark(String),
    /// Part of a parent: "level", "setting", with "top"/"other" when given.
    Part {
        /// `level` or `setting`.
        kind: String,
        /// "top", "bottom", "other", ...
        which: Option<String>,
    },
    /// "people", "guests" (place settings).
    Setting,
    /// A pronoun.
    Pronoun(Pronoun),
    /// A feature of an object ("patterns", "fittings").
    Feature,
    /// Anything that is not an object ("area", "theme", an adjective alone).
    NonObject,
}

/// A noun phrase.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Np {
    /// Determiner class (`indefinite`, `definite`, `possessive`, `several`, `each`, ...).
    pub det: Option<String>,
    /// Quantifier class (`at_least`, `exactly`, ...).
    pub quant: Option<String>,
    /// Number written.
    pub number: Option<u32>,
    /// "10+".
    pub plus: bool,
    /// "first", "second".
    pub ordinal: Option<u32>,
    /// "a stack of", "pairs of".
    pub group: Option<GroupKind>,
    /// "arrangement", "set-up" after the noun.
    pub group_suffix: bool,
    /// "no TV", "not a single chair".
    pub negated: bool,
    /// "the other", "another".
    pub other: bool,
    /// Modifiers.
    pub attrs: Attributes,
    /// What it names.
    pub head: Head,
    /// Written in the plural.
    pub plural: bool,
    /// The word "one" was the number ("one bin").
    pub one_word: bool,
}

impl Np {
    /// True when the phrase has a determiner, quantifier or number (not a bare noun).
    pub fn has_det(&self) -> bool {
        self.det.is_some() || self.quant.is_some() || self.number.is_some() || self.group.is_some()
    }

    /// True for "the", "its", "this", "these", "each".
    pub fn is_definite(&self) -> bool {
        matches!(
            self.det.as_deref(),
            Some("definite" | "possessive" | "each")
        )
    }
}

pub(crate) fn word(tokens: &[Token], i: usize) -> Option<&str> {
    tokens
        .get(i)
        .filter(|t| t.is_word())
        .map(|t| t.text.as_str())
}

pub(crate) fn pronoun_np(p: Pronoun) -> Np {
    Np {
        det: None,
        quant: None,
        number: None,
        plus: false,
        ordinal: None,
        group: None,
        group_suffix: false,
        negated: false,
        other: false,
        attrs: Attributes::default(),
        head: Head::Pronoun(p),
        plural: matches!(p, Pronoun::Them | Pronoun::EachOther),
        one_word: false,
    }
}

/// "about", "over", "around" are quantifiers only before a number.
pub(crate) fn quantifier_fits(lex: &Lexicon, tokens: &[Token], i: usize) -> bool {
    match lex.quantifier_at(tokens, i) {
        Some((n, "about_number" | "more_than_number")) => {
            tokens.get(i + n).and_then(|t| lex.number(t)).is_some()
        }
        Some(_) => true,
        None => false,
    }
}

/// The longest lexicon noun at `j` that agrees with the phrase's determiner: "A TV stands
/// against the wall" is a TV that stands, not "TV stands" — a singular determiner (or "the"
/// before a preposition) with a plural compound whose last word is also a verb keeps the
/// shorter noun and leaves the verb.
fn agree(
    lex: &Lexicon,
    np: &Np,
    tokens: &[Token],
    j: usize,
    end: usize,
) -> Option<(usize, usize, bool)> {
    let found = lex.noun_at(tokens, j).filter(|(n, ..)| j + n <= end)?;
    let (n, _, plural) = found;
    if !plural || n < 2 {
        return Some(found);
    }
    let last = j + n - 1;
    let Some(w) = word(tokens, last) else {
        return Some(found);
    };
    let singular_det = matches!(np.det.as_deref(), Some("indefinite" | "each" | "another"))
        || np.number == Some(1);
    let verb_like_next = lex.preposition_at(tokens, last + 1).is_some()
        || word(tokens, last + 1).is_some_and(|x| lex.determiner(x).is_some());
    let agrees_as_verb = lex.verb(w).is_some()
        && (singular_det || (np.det.as_deref() == Some("definite") && verb_like_next));
    if agrees_as_verb && let Some(shorter) = lex.noun_at_most(tokens, j, n - 1) {
        return Some(shorter);
    }
    Some(found)
}

/// Parses a noun phrase starting at `i`; returns it and the index after it.
pub(crate) fn parse_np(
    lex: &Lexicon,
    kb: &Knowledge,
    tokens: &[Token],
    i: usize,
    end: usize,
    sentence_start: usize,
    in_list: bool,
) -> Option<(Np, usize)> {
    let mut np = Np {
        det: None,
        quant: None,
        number: None,
        plus: false,
        ordinal: None,
        group: None,
        group_suffix: false,
        negated: false,
        other: false,
        attrs: Attributes::default(),
        head: Head::NonObject,
        plural: false,
        one_word: false,
    };
    let mut j = i;
    let at = |j: usize| if j < end { word(tokens, j) } else { None };
    if matches!(at(j), Some("no" | "not")) {
        np.negated = true;
        j += 1;
    }
    // Quantifier, determiner, quantifier again, number, ordinal — in any sensible order.
    for _ in 0..4 {
        if j >= end {
            break;
        }
        if np.quant.is_none()
            && let Some((n, class)) = lex.quantifier_at(tokens, j)
            && quantifier_fits(lex, tokens, j)
        {
            np.quant = Some(class.to_string());
            j += n;
            continue;
        }
        if let Some(w) = at(j)
            && np.det.is_none()
            && np.number.is_none()
            && let Some(class) = lex.determiner(w)
        {
            // "each" followed by nothing nounish is not a determiner here.
            if class == "other" || class == "another" {
                np.other = true;
            }
            np.det = Some(if class == "other" {
                "definite".to_string()
            } else {
                class.to_string()
            });
            j += 1;
            if w == "the" && at(j) == Some("other") {
                np.other = true;
                j += 1;
            }
            continue;
        }
        if np.number.is_none()
            && let Some(t) = tokens.get(j)
            && let Some(n) = lex.number(t)
        {
            np.one_word = t.text == "one";
            np.number = Some(n);
            j += 1;
            if tokens.get(j).is_some_and(|t| t.is_punct('+')) {
                np.plus = true;
                j += 1;
            }
            continue;
        }
        if let Some(w) = at(j)
            && np.ordinal.is_none()
            && let Some(o) = lex.ordinal(w)
        {
            np.ordinal = Some(o);
            j += 1;
            continue;
        }
        break;
    }
    // "one" as a subject pronoun: "where one displays ..., the other displays ...".
    if let Some(w) = at(j)
        && (np.one_word || (np.other && np.number.is_none()))
        && lex.verb(w).is_some()
        && lex.noun_at(tokens, j).is_none()
    {
        np.head = Head::Pronoun(if np.one_word {
            Pronoun::One
        } else {
            Pronoun::Other
        });
        return Some((np, j));
    }
    // Group words: "a stack of", "pairs of".
    if let Some(w) = at(j)
        && let Some(class) = lex.group(w)
        && at(j + 1) == Some("of")
        && let Some(kind) = GroupKind::from_class(class)
    {
        np.group = Some(kind);
        j += 2;
        if kind == GroupKind::Pair {
            // "5 pairs of shoes": the number counts pairs.
        } else if let Some(t) = tokens.get(j)
            && let Some(n) = lex.number(t)
        {
            np.number = Some(n);
            j += 1;
        } else if let Some((n, class)) = lex.quantifier_at(tokens, j)
            && quantifier_fits(lex, tokens, j)
        {
            np.quant = Some(class.to_string());
            j += n;
            if let Some(t) = tokens.get(j)
                && let Some(num) = lex.number(t)
            {
                np.number = Some(num);
                j += 1;
            }
        } else if np.group != Some(GroupKind::Pair) {
            // "a stack of books": the count is of the books, not of stacks.
            np.number = None;
            if np.det.as_deref() == Some("indefinite") {
                np.det = None;
            }
        }
    }
    // Top/bottom/other before a part noun ("the top level", "the other two levels").
    let mut which: Option<String> = None;
    if let Some(w) = at(j)
        && matches!(
            w,
            "top" | "bottom" | "middle" | "lower" | "upper" | "remaining" | "last"
        )
        && at(j + 1).is_some_and(|n| lex.part(n).is_some())
    {
        which = Some(w.to_string());
        j += 1;
    }
    if np.other && which.is_none() {
        which = Some("other".to_string());
    }
    // Modifiers.
    while j < end {
        match modifier_at(lex, kb, tokens, j, sentence_start) {
            Some(m) if j + m.len <= end => {
                np.attrs.add(&m);
                j += m.len;
            }
            _ => break,
        }
    }
    let evidence =
        np.has_det() || np.ordinal.is_some() || !np.attrs.modifiers.is_empty() || np.negated;
    let w = at(j)?;
    // Head.
    let noun = agree(lex, &np, tokens, j, end);
    let room = kb.room_type_at(tokens, j).filter(|(n, _)| j + n <= end);
    let noun_len = noun.map_or(0, |(n, ..)| n);
    let room_len = room.map_or(0, |(n, _)| n);
    let bare_ambiguous = noun_len == 1 && lex.is_ambiguous_bare(w) && !evidence && !in_list;
    if room_len > 0 && room_len >= noun_len {
        let (n, key) = room.unwrap_or((0, ""));
        let words: Vec<String> = tokens[j..j + n].iter().map(|t| t.text.clone()).collect();
        let mut ws = words.clone();
        if let Some(last) = ws.last_mut() {
            *last = lex.singular(last);
        }
        np.plural = lex.is_plural(&words[n - 1]);
        np.head = Head::Room {
            key: key.to_string(),
            words: ws.join(" "),
        };
        return Some((np, j + n));
    }
    if let Some((n, entry, plural)) = noun
        && !bare_ambiguous
    {
        let mut start = j;
        let (mut n, mut entry, mut plural) = (n, entry, plural);
        // Noun-noun compounds: "glass table" — the first noun modifies the second.
        while !plural
            && start + n < end
            && let Some((n2, e2, p2)) = lex.noun_at(tokens, start + n)
            && start + n + n2 <= end
            && lex.verb(&tokens[start + n].text).is_none()
        {
            let text: Vec<&str> = tokens[start..start + n]
                .iter()
                .map(|t| t.raw.as_str())
                .collect();
            let text = text.join(" ");
            if let Some(mat) = lex.material(&tokens[start].text)
                && n == 1
            {
                np.attrs.materials.push(mat.to_string());
            }
            np.attrs.modifiers.push(text);
            start += n;
            n = n2;
            entry = e2;
            plural = p2;
        }
        // A known noun followed by an unknown noun ends there: "ball pit", "luggage rack".
        if !plural
            && start + n < end
            && let Some(x) = at(start + n)
            && lex.noun_at(tokens, start + n).is_none()
            && lex.preposition_at(tokens, start + n).is_none()
            && lex.verb(x).is_none()
            && kb.room_type_at(tokens, start + n).is_none()
            && !lex.is_function_word(x)
            && lex.landmark(x).is_none()
            && !lex.is_feature_noun(x)
            && !lex.is_non_object(x)
            && !lex.is_adjective(x)
            && lex.number(&tokens[start + n]).is_none()
            && !x.ends_with("ing")
            && !x.ends_with("ed")
            && !x.ends_with("ly")
            && x.chars().all(|ch| ch.is_alphabetic())
            && at(start + n + 1)
                .is_none_or(|y| lex.is_function_word(y) || lex.landmark(y).is_some())
        {
            let mut written: Vec<String> = tokens[start..start + n + 1]
                .iter()
                .map(|t| t.text.clone())
                .collect();
            let plural2 = lex.is_plural(x);
            if let Some(last) = written.last_mut() {
                *last = lex.singular(last);
            }
            let noun = written.join(" ");
            np.plural = plural2;
            np.head = Head::Object {
                entry: None,
                noun: noun.clone(),
                canonical: noun,
                head_entry: lex.entry_index(&lex.singular(x)),
            };
            return Some((np, start + n + 1));
        }
        // A part noun with an ordinal or "top": "the top shelf", "the second shelf".
        let head_word = tokens[start + n - 1].text.as_str();
        if (np.ordinal.is_some() || which.is_some())
            && lex.part(head_word).is_some_and(|p| p == "level_if_parent")
        {
            np.head = Head::Part {
                kind: "level".to_string(),
                which,
            };
            np.plural = plural;
            return Some((np, start + n));
        }
        let mut written: Vec<String> = tokens[start..start + n]
            .iter()
            .map(|t| t.text.clone())
            .collect();
        if let Some(last) = written.last_mut() {
            *last = lex.singular(last);
        }
        let canonical = lex
            .objects
            .get(entry)
            .map_or_else(|| written.join(" "), |e| e.noun.clone());
        np.plural = plural;
        np.head = Head::Object {
            entry: Some(entry),
            noun: written.join(" "),
            canonical,
            head_entry: None,
        };
        let mut k = start + n;
        if let Some(s) = at(k)
            && lex.is_group_suffix(s)
        {
            np.group_suffix = true;
            k += 1;
        }
        return Some((np, k));
    }
    if let Some(class) = lex.landmark(w) {
        // "the front wall", "the back corner": the last landmark word is the head.
        if let Some(next) = at(j + 1)
            && let Some(c2) = lex.landmark(next)
            && matches!(c2, "wall" | "walls" | "corner" | "window" | "door")
        {
            np.plural = lex.is_plural(next);
            np.head = Head::Landmark(c2.to_string());
            return Some((np, j + 2));
        }
        np.plural = lex.is_plural(w);
        np.head = Head::Landmark(class.to_string());
        return Some((np, j + 1));
    }
    if let Some(part) = lex.part(w)
        && part != "level_if_parent"
        && part != "top"
    {
        let kind = if part == "setting" {
            "setting"
        } else {
            "level"
        };
        np.plural = lex.is_plural(w);
        np.head = Head::Part {
            kind: kind.to_string(),
            which,
        };
        // "place settings"
        return Some((np, j + 1));
    }
    if lex.is_setting_noun(w) {
        np.plural = true;
        np.head = Head::Setting;
        return Some((np, j + 1));
    }
    if lex.is_feature_noun(w) {
        np.head = Head::Feature;
        return Some((np, j + 1));
    }
    if lex.is_non_object(w) {
        let mut k = j;
        while at(k).is_some_and(|x| lex.is_non_object(x)) {
            k += 1;
        }
        np.head = Head::NonObject;
        return Some((np, k));
    }
    // Open vocabulary: up to three unknown words, the last is the head.
    if evidence || in_list {
        let mut k = j;
        let mut words: Vec<String> = Vec::new();
        while k < end && words.len() < 3 {
            let Some(x) = at(k) else { break };
            if k > j
                && let Some((n2, e2, p2)) = lex.noun_at(tokens, k)
                && k + n2 <= end
            {
                np.attrs
                    .modifiers
                    .extend(tokens[j..k].iter().map(|t| t.raw.clone()));
                let mut written: Vec<String> =
                    tokens[k..k + n2].iter().map(|t| t.text.clone()).collect();
                if let Some(last) = written.last_mut() {
                    *last = lex.singular(last);
                }
                np.plural = p2;
                np.head = Head::Object {
                    entry: Some(e2),
                    noun: written.join(" "),
                    canonical: lex
                        .objects
                        .get(e2)
                        .map_or_else(|| written.join(" "), |e| e.noun.clone()),
                    head_entry: None,
                };
                return Some((np, k + n2));
            }
            if k > j
                && let Some((n2, key)) = kb.room_type_at(tokens, k)
            {
                np.attrs
                    .modifiers
                    .extend(tokens[j..k].iter().map(|t| t.raw.clone()));
                let mut ws: Vec<String> =
                    tokens[k..k + n2].iter().map(|t| t.text.clone()).collect();
                if let Some(last) = ws.last_mut() {
                    *last = lex.singular(last);
                }
                np.head = Head::Room {
                    key: key.to_string(),
                    words: ws.join(" "),
                };
                return Some((np, k + n2));
            }
            if lex.is_function_word(x)
                || lex.landmark(x).is_some()
                || lex.is_setting_noun(x)
                || lex.is_non_object(x)
                || lex.number(&tokens[k]).is_some()
            {
                break;
            }
            if k > j && lex.is_feature_noun(x) {
                np.head = Head::Feature;
                return Some((np, k + 1));
            }
            words.push(x.to_string());
            k += 1;
        }
        let last_ok = words.last().is_some_and(|l| {
            !l.ends_with("ly") && !l.ends_with("ing") && l.chars().any(char::is_alphabetic)
        });
        if last_ok {
            let last = words.last().cloned().unwrap_or_default();
            np.plural = lex.is_plural(&last);
            let mut sing = words.clone();
            if let Some(l) = sing.last_mut() {
                *l = lex.singular(l);
            }
            let head_entry = sing.last().and_then(|l| lex.entry_index(l));
            let noun = sing.join(" ");
            np.head = Head::Object {
                entry: None,
                noun: noun.clone(),
                canonical: noun,
                head_entry,
            };
            return Some((np, k));
        }
    }
    if j > i && (evidence || !np.attrs.modifiers.is_empty()) {
        // Only modifiers ("leather and metal accents": "leather" alone).
        np.head = Head::NonObject;
        return Some((np, j));
    }
    None
}
