//! Noun phrases: determiner, quantifier, number, ordinal, group word ("a stack of", "pairs
//! of"), modifiers and head — an object noun (longest lexicon match, compounds, or the
//! open-vocabulary rule), a room word, a landmark, a part ("the top level"), a pronoun.
//!
//! This module reads one phrase at a time; `chunk` decides where phrases start.

use super::attributes::{Attributes, modifier_at};
use super::mentions::GroupKind;
use super::report::{NounReport, NounStatus};
use crate::knowledge::Knowledge;
use crate::words::ground::{self, Verdict};
use crate::words::lexicon::Lexicon;
use crate::words::tokens::{Token, TokenKind};

/// Parts of the building that name where a thing goes when they stand before its noun
/// ("floor cushion", "wall mirror", "ceiling hook", "window box", "door wreath", "corner shelf").
const BUILDING_PART_MODIFIERS: [&str; 6] = ["floor", "wall", "ceiling", "window", "door", "corner"];

/// English modal verbs, a closed class: each is followed by a verb in its base form.
const MODALS: &[&str] = &[
    "can", "could", "may", "might", "must", "shall", "should", "will", "would",
];

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
    /// The number of sets written before "sets of" ("two sets of bunk beds").
    pub sets: Option<u32>,
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
    /// How the head noun was grounded when the lexicon did not know it.
    pub report: Option<NounReport>,
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
        head: Head::Pronoun(p),
        plural: matches!(p, Pronoun::Them | Pronoun::EachOther),
        ..blank_np()
    }
}

/// "about", "over", "around" and "up to" are quantifiers only before a number ("leads up
/// to the loft" is no count).
pub(crate) fn quantifier_fits(lex: &Lexicon, tokens: &[Token], i: usize) -> bool {
    match lex.quantifier_at(tokens, i) {
        Some((n, "about_number" | "more_than_number" | "at_most")) => {
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
    let phrase = Phrase {
        lex,
        kb,
        tokens,
        start: i,
        end,
        sentence_start,
        in_list,
    };
    let mut np = blank_np();
    let j = phrase.read_counts(&mut np);
    if let Some(pronoun) = phrase.subject_pronoun(&np, j) {
        np.head = Head::Pronoun(pronoun);
        return Some((np, j));
    }
    let j = phrase.read_group(&mut np, j);
    let (which, j) = phrase.read_part_position(&np, j);
    let mods_from = j;
    let j = phrase.read_modifiers(&mut np, j);
    let evidence =
        np.has_det() || np.ordinal.is_some() || !np.attrs.modifiers.is_empty() || np.negated;
    let before = BeforeHead {
        j,
        mods_from,
        which,
        evidence,
    };
    let next = phrase.read_head(&mut np, &before)?;
    Some((np, next))
}

/// "Stuffed animals — at least a dozen — tumble out", "Flash sheets — dozens of them — cover
/// the walls": a count alone between `start` and `end` (the words inside a pair of dashes),
/// possibly followed by "of them", "in all", "in total" or "or so". Returns the number and
/// the quantifier class read.
pub(crate) fn apposed_count(
    lex: &Lexicon,
    kb: &Knowledge,
    tokens: &[Token],
    start: usize,
    end: usize,
) -> Option<(Option<u32>, Option<String>)> {
    let phrase = Phrase {
        lex,
        kb,
        tokens,
        start,
        end,
        sentence_start: start,
        in_list: false,
    };
    let mut np = blank_np();
    let j = phrase.read_counts(&mut np);
    let rest: Vec<&str> = (j..end).filter_map(|k| word(tokens, k)).collect();
    let tail_ok = (j..end).all(|k| word(tokens, k).is_some())
        && matches!(
            rest.as_slice(),
            [] | ["of", "them"] | ["in", "all"] | ["in", "total"] | ["or", "so"] | ["or", "more"]
        );
    let counted = np.number.is_some() || np.quant.is_some();
    (counted && tail_ok && !np.negated && np.ordinal.is_none()).then(|| {
        let quant = match (np.quant, rest.as_slice()) {
            (None, ["or", "more"]) => Some("at_least".to_string()),
            (q, _) => q,
        };
        (np.number, quant)
    })
}

/// A phrase with no words read yet.
pub(crate) fn blank_np() -> Np {
    Np {
        det: None,
        quant: None,
        number: None,
        plus: false,
        ordinal: None,
        group: None,
        sets: None,
        group_suffix: false,
        negated: false,
        other: false,
        attrs: Attributes::default(),
        head: Head::NonObject,
        plural: false,
        one_word: false,
        report: None,
    }
}

/// The tokens a noun phrase is read from, and where it may start and end.
struct Phrase<'a> {
    lex: &'a Lexicon,
    kb: &'a Knowledge,
    tokens: &'a [Token],
    /// First token of the phrase.
    start: usize,
    /// The phrase ends before this token.
    end: usize,
    sentence_start: usize,
    /// The phrase is an item of a list: it presents a thing even when bare.
    in_list: bool,
}

/// Where the head of a phrase starts, and what came before it.
struct BeforeHead {
    /// First token of the head.
    j: usize,
    /// First modifier (names keep the modifiers written with them).
    mods_from: usize,
    /// "top", "bottom", "other", ... before a part noun.
    which: Option<String>,
    /// A determiner, count, ordinal, modifier or "no" presents the head as a thing.
    evidence: bool,
}

/// A lexicon noun in the tokens: `len` tokens from `start`.
#[derive(Clone, Copy)]
struct NounAt {
    start: usize,
    len: usize,
    entry: usize,
    plural: bool,
}

impl<'a> Phrase<'a> {
    /// The word at `j`, `None` past the phrase's end or at punctuation.
    fn at(&self, j: usize) -> Option<&'a str> {
        if j < self.end {
            word(self.tokens, j)
        } else {
            None
        }
    }

    /// "no"/"not", then quantifier, determiner, quantifier again, number, ordinal — in any
    /// sensible order; returns the index after them.
    fn read_counts(&self, np: &mut Np) -> usize {
        let (lex, tokens) = (self.lex, self.tokens);
        let mut j = self.start;
        if matches!(self.at(j), Some("no" | "not")) {
            np.negated = true;
            j += 1;
            // "no longer a car", "not even a chair".
            if matches!(self.at(j), Some("longer" | "even")) && self.at(j + 1).is_some() {
                j += 1;
            }
        }
        for _ in 0..4 {
            if j >= self.end {
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
            if let Some(w) = self.at(j)
                && np.det.is_none()
                && np.number.is_none()
                && let Some(class) = lex.determiner(w)
            {
                j = self.read_determiner(np, j, w, class);
                continue;
            }
            if np.number.is_none()
                && let Some(t) = tokens.get(j)
                && let Some(n) = lex.number(t)
                && !self.names_a_kind(np, j)
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
            if let Some(w) = self.at(j)
                && np.ordinal.is_none()
                && let Some(o) = lex.ordinal(w)
            {
                np.ordinal = Some(o);
                j += 1;
                continue;
            }
            break;
        }
        j
    }

    /// The determiner `w` of class `class` at `j`; returns the index after it.
    fn read_determiner(&self, np: &mut Np, mut j: usize, w: &str, class: &str) -> usize {
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
        // "each with its own swivel chair": one more of its kind per owner, not a reference.
        if class == "possessive" && self.at(j) == Some("own") && self.at(j + 1).is_some() {
            np.det = Some("indefinite".to_string());
            j += 1;
        }
        if w == "the" && self.at(j) == Some("other") {
            np.other = true;
            j += 1;
        } else if w == "the" && self.at(j) == Some("others") {
            // "the others": the rest of a group just named, no noun.
            np.other = true;
            np.plural = true;
            j += 1;
        }
        j
    }

    /// "one" or "the other" as a subject: "where one displays ..., the other displays ...".
    fn subject_pronoun(&self, np: &Np, j: usize) -> Option<Pronoun> {
        let w = self.at(j)?;
        let subject = (np.one_word || (np.other && np.number.is_none()))
            && self.lex.verb(w).is_some()
            && self.lex.noun_at(self.tokens, j).is_none();
        subject.then_some(if np.one_word {
            Pronoun::One
        } else {
            Pronoun::Other
        })
    }

    /// Group words: "a stack of", "pairs of"; and any word the lexicon does not know as an
    /// object before "of" and a plural noun ("a tangle of cables", "an array of candles"):
    /// the things are the plural noun, the word says how they lie. Returns the index after.
    fn read_group(&self, np: &mut Np, mut j: usize) -> usize {
        let (lex, tokens) = (self.lex, self.tokens);
        let partitive = |w: &str| {
            lex.noun_at(tokens, j).is_none()
                && !lex.is_function_word(w)
                && lex.quantifier_at(tokens, j).is_none()
                && ground::is_noun(w)
                // "a caddy of crayons": a container holds its contents; it is no measure.
                && !ground::is_kind_of_word(w, "container")
                && word(tokens, j + 2).is_some_and(|x| {
                    lex.is_plural(x) && (lex.noun_at(tokens, j + 2).is_some() || ground::is_noun(x))
                })
        };
        let Some(kind) = self
            .at(j)
            .filter(|_| self.at(j + 1) == Some("of"))
            .and_then(|w| {
                lex.group(w)
                    .and_then(GroupKind::from_class)
                    .or_else(|| partitive(w).then_some(GroupKind::Pile))
            })
        else {
            return j;
        };
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
            if kind == GroupKind::Set {
                np.sets = np.number;
            }
            np.number = None;
            if np.det.as_deref() == Some("indefinite") {
                np.det = None;
            }
        }
        j
    }

    /// Whether the number word at `j` after "a" begins the name of a kind with the word after
    /// it ("a single bed", "a twin bed": WordNet nouns), not a count ("a single chair").
    fn names_a_kind(&self, np: &Np, j: usize) -> bool {
        let tokens = self.tokens;
        np.det.as_deref() == Some("indefinite")
            && tokens.get(j).is_some_and(|t| t.kind == TokenKind::Word)
            && j + 1 < self.end
            && tokens.get(j + 1).is_some_and(|next| {
                next.is_word()
                    && ground::is_noun(&format!(
                        "{} {}",
                        tokens[j].text.to_lowercase(),
                        next.text.to_lowercase()
                    ))
            })
    }

    /// Top/bottom/other before a part noun ("the top level", "the other two levels").
    fn read_part_position(&self, np: &Np, mut j: usize) -> (Option<String>, usize) {
        let mut which: Option<String> = None;
        if let Some(w) = self.at(j)
            && matches!(
                w,
                "top" | "bottom" | "middle" | "lower" | "upper" | "remaining" | "last"
            )
            && self.at(j + 1).is_some_and(|n| self.lex.part(n).is_some())
        {
            which = Some(w.to_string());
            j += 1;
        }
        if np.other && which.is_none() {
            which = Some("other".to_string());
        }
        (which, j)
    }

    /// Modifiers, and a room word that modifies the noun after it; returns the index after.
    fn read_modifiers(&self, np: &mut Np, mut j: usize) -> usize {
        let (lex, kb, tokens, end) = (self.lex, self.kb, self.tokens, self.end);
        while j < end {
            // "an operating theatre": a room WordNet knows as a whole is no modifier + room.
            if kb.room_type_at(tokens, j).is_none()
                && let (Some(a), Some(b)) = (self.at(j), self.at(j + 1))
                && j + 2 <= end
                && wordnet_room_words(&format!("{a} {}", lex.singular(b))).is_some()
            {
                break;
            }
            // "a folding ironing board": a modifier that begins a noun WordNet knows whole
            // ("ironing board") is part of the head.
            if self.wordnet_compound_at(j) {
                break;
            }
            match modifier_at(lex, kb, tokens, j, self.sentence_start) {
                Some(m) if j + m.len <= end => {
                    np.attrs.add(&m);
                    j += m.len;
                }
                _ if self.adjective_before_modifier(j) => {
                    let w = tokens[j].text.clone();
                    np.attrs.adjectives.push(w);
                    np.attrs.modifiers.push(tokens[j].raw.clone());
                    j += 1;
                }
                _ if self.noun_modifier_at(j) => {
                    np.attrs.modifiers.push(tokens[j].raw.clone());
                    j += 1;
                }
                _ => break,
            }
        }
        // "a living room sofa", "this boutique day spa": a room word before a noun modifies it.
        if let Some((rn, _)) = kb.room_type_at(tokens, j)
            && j + rn < end
            && lex.noun_at(tokens, j).is_none_or(|(l, ..)| l <= rn)
            && noun_follows(lex, kb, tokens, j + rn)
        {
            np.attrs
                .modifiers
                .extend(tokens[j..j + rn].iter().map(|t| t.raw.clone()));
            j += rn;
        }
        j
    }

    /// "A plush grey sofa", "a compact mid-century cafe": a one-word noun WordNet also reads as
    /// an adjective, followed by a colour, material, size or style word, is an adjective.
    fn adjective_before_modifier(&self, j: usize) -> bool {
        let (lex, tokens) = (self.lex, self.tokens);
        let Some(w) = self.at(j) else { return false };
        let next_describes = self.at(j + 1).is_some_and(|x| {
            lex.color_at(tokens, j + 1).is_some()
                || lex.material(x).is_some()
                || lex.size_adjective(x).is_some()
                || lex.style_at(tokens, j + 1).is_some()
        });
        lex.noun_at(tokens, j).is_some_and(|(n, ..)| n == 1)
            && !lex.is_plural(w)
            && ground::is_adjective(w)
            && next_describes
            && j + 2 < self.end
    }

    /// "Meditation cushions", "art books": a noun in its base form that the lexicon does not
    /// know, right before a lexicon noun, modifies it.
    fn noun_modifier_at(&self, j: usize) -> bool {
        let (lex, tokens) = (self.lex, self.tokens);
        let Some(w) = self.at(j) else { return false };
        j + 1 < self.end
            && lex.noun_at(tokens, j).is_none()
            && self.kb.room_type_at(tokens, j).is_none()
            && !lex.is_function_word(w)
            // "four floor cushions", "a door wreath": a part of the building in its base form
            // right before a lexicon noun says where the thing goes; other landmarks ("the
            // back", "the middle") do not modify.
            && (lex.landmark(w).is_none() || BUILDING_PART_MODIFIERS.contains(&w))
            && crate::words::wordnet::wordnet().is_lemma(w, crate::words::wordnet::Pos::Noun)
            && lex
                .noun_at(tokens, j + 1)
                .is_some_and(|(n, ..)| j + 1 + n <= self.end)
    }

    /// Whether the words at `j` begin a compound noun WordNet knows as written ("ironing
    /// board", "spinning wheel") whose last word the lexicon does not know as a noun.
    fn wordnet_compound_at(&self, j: usize) -> bool {
        let (lex, tokens) = (self.lex, self.tokens);
        if lex.noun_at(tokens, j).is_some() || lex.style_at(tokens, j).is_some() {
            return false;
        }
        (2..=3).any(|n| {
            let last = j + n - 1;
            let words: Option<Vec<&str>> = (j..=last).map(|k| self.at(k)).collect();
            words.is_some_and(|ws| {
                let mut ws: Vec<String> = ws.iter().map(|w| w.to_string()).collect();
                if let Some(l) = ws.last_mut() {
                    *l = lex.singular(l);
                }
                let c = ws.join(" ");
                lex.noun_at(tokens, last).is_none()
                    && ground::noun_lemma(&c).is_some_and(|l| l == c)
            })
        })
    }

    /// The head: a room, a lexicon noun, a landmark, part or feature word, or an open-vocabulary
    /// noun, tried in that order; sets it on `np` and returns the index after the phrase.
    fn read_head(&self, np: &mut Np, before: &BeforeHead) -> Option<usize> {
        let (lex, tokens, j) = (self.lex, self.tokens, before.j);
        let Some(w) = self.at(j) else {
            return self.material_as_head(np, before);
        };
        let noun = agree(lex, np, tokens, j, self.end);
        let room = self
            .kb
            .room_type_at(tokens, j)
            .filter(|(n, _)| j + n <= self.end);
        let noun_len = noun.map_or(0, |(n, ..)| n);
        if let Some(next) = self.room_head(np, before, noun_len, room) {
            return Some(next);
        }
        if let Some((len, entry, plural)) = noun {
            if j > before.mods_from && names_building(lex, tokens, j, len) {
                np.head = Head::NonObject;
                return Some(j + len);
            }
            if np.det.as_deref() == Some("definite") && self.building_at(j + len) {
                np.head = Head::NonObject;
                return Some(j + len + 1);
            }
            if !self.bare_ambiguous(w, j, noun_len, before.evidence) {
                let noun = NounAt {
                    start: j,
                    len,
                    entry,
                    plural,
                };
                return Some(self.object_head(np, before, noun));
            }
        }
        if let Some(next) = self.landmark_part_or_setting_head(np, before, w) {
            return Some(next);
        }
        if let Some(next) = self.space_room_head(np, before, w) {
            return Some(next);
        }
        if let Some(next) = self.feature_or_non_object_head(np, before, w) {
            return Some(next);
        }
        if (before.evidence || self.in_list || self.bare_plural_thing(j))
            && let Some(next) = self.open_vocabulary_head(np, before)
        {
            return Some(next);
        }
        if let Some(next) = self.material_as_head(np, before) {
            return Some(next);
        }
        if j > self.start && (before.evidence || !np.attrs.modifiers.is_empty()) {
            // Only modifiers ("leather and metal accents": "leather" alone).
            np.head = Head::NonObject;
            return Some(j);
        }
        None
    }

    /// "the iron resting on it", "an iron": a material word after a determiner with no noun
    /// after it is the noun itself, grounded like any other (WordNet's iron is also an
    /// appliance); "leather and metal accents" has no determiner and keeps "leather" a material.
    fn material_as_head(&self, np: &mut Np, before: &BeforeHead) -> Option<usize> {
        let j = before.j;
        let last = j.checked_sub(1).filter(|&k| k >= before.mods_from)?;
        let w = self.at(last)?;
        let mat = self.lex.material(w)?;
        let presented = np.det.as_deref().is_some_and(|d| d != "possessive") || np.number.is_some();
        if !presented || np.attrs.materials.last().map(String::as_str) != Some(mat) {
            return None;
        }
        let mut trial = np.clone();
        trial.attrs.materials.pop();
        trial.attrs.modifiers.pop();
        let at = BeforeHead {
            j: last,
            mods_from: before.mods_from,
            which: before.which.clone(),
            evidence: true,
        };
        let next = self.open_vocabulary_head(&mut trial, &at)?;
        if !matches!(trial.head, Head::Object { .. }) {
            return None;
        }
        *np = trial;
        Some(next)
    }

    /// A lone one-word noun that is often something else ("light"), or a predicate, with
    /// nothing that presents it as a thing.
    fn bare_ambiguous(&self, w: &str, j: usize, noun_len: usize, evidence: bool) -> bool {
        let (lex, i) = (self.lex, self.start);
        // "this home is compact": a bare word after a linking verb that WordNet also reads as
        // an adjective is the predicate, not a thing.
        let predicate = j == i
            && i > self.sentence_start
            && word(self.tokens, i - 1).is_some_and(is_linking_verb)
            && !lex.is_plural(w)
            && ground::is_adjective(w);
        noun_len == 1
            && (lex.is_ambiguous_bare(w) || predicate || self.coordinated_adjective(w, j))
            && !evidence
            && !self.in_list
    }

    /// "Tongs of every shape hang from a rack", "Skeins of yarn fill the shelf": a bare plural
    /// that begins its phrase and that WordNet reads as a placeable thing wherever it heads
    /// one is that thing, as a plural subject or object without a determiner usually is.
    fn bare_plural_thing(&self, j: usize) -> bool {
        j == self.start
            && self.at(j).is_some_and(|w| {
                (self.lex.is_plural(w) || plural_only(self.lex, w))
                    && ground::verdict(w) == ground::Verdict::Object
            })
    }

    /// "Compact but efficient, this laundry room ...": a bare word WordNet also reads as an
    /// adjective, joined by a conjunction to a word that is only an adjective, is one.
    fn coordinated_adjective(&self, w: &str, j: usize) -> bool {
        !self.lex.is_plural(w)
            && ground::is_adjective(w)
            && word(self.tokens, j + 1).is_some_and(|c| self.lex.is_conjunction(c))
            && word(self.tokens, j + 2)
                .is_some_and(|x| ground::is_adjective(x) && ground::only_other_pos(x).is_some())
    }

    /// A room head when the words name a room at least as long as the lexicon noun there.
    fn room_head(
        &self,
        np: &mut Np,
        before: &BeforeHead,
        noun_len: usize,
        room: Option<(usize, &str)>,
    ) -> Option<usize> {
        let (lex, tokens, j, end) = (self.lex, self.tokens, before.j, self.end);
        let room_len = room.map_or(0, |(n, _)| n);
        // "a wooden bar", "a marble counter": rooms are not made of a material; a room word
        // that WordNet also knows as a thing is that thing.
        if room_len >= noun_len.max(1)
            && (!np.attrs.materials.is_empty()
                || made_of_thing(lex, tokens, before.mods_from, j, room_len))
        {
            let words: Vec<&str> = tokens[j..j + room_len]
                .iter()
                .map(|t| t.text.as_str())
                .collect();
            if let Ok(head) = ground_words(lex, &words, Evidence::Strong) {
                np.plural = lex.is_plural(words[room_len - 1]);
                let mut noun = words.clone();
                noun[room_len - 1] = &head.singular;
                np.set_grounded(noun.join(" "), &head);
                return Some(j + room_len);
            }
        }
        // "a kiln room", "a boot room": nouns before a room word name the room.
        // Not when the room word is a verb in -s after a singular phrase ("a plan chest
        // stores sheets of paper").
        let singular_det = matches!(np.det.as_deref(), Some("indefinite" | "each" | "another"))
            && np.number.is_none();
        let verb_s = |k: usize| {
            singular_det
                && lex.is_plural(&tokens[k].text)
                && crate::words::wordnet::wordnet()
                    .has_pos(&tokens[k].text, crate::words::wordnet::Pos::Verb)
        };
        if room_len == 0
            && let Some((n, key, words)) = room_compound(lex, self.kb, tokens, j, end)
            && noun_len < n
            && !verb_s(j + n - 1)
        {
            np.plural = lex.is_plural(&tokens[j + n - 1].text);
            let words = singular_last(lex, &words);
            np.head = Head::Room { key, words };
            return Some(j + n);
        }
        // A room or building WordNet knows and the registry does not ("scullery"): the
        // nearest room type along its hypernyms.
        if room_len == 0
            && noun_len == 0
            && let Some((n, key, words)) = wordnet_room(lex, tokens, j, end)
        {
            np.plural = lex.is_plural(&tokens[j + n - 1].text);
            let words = room_name(lex, tokens, before.mods_from, j, singular_last(lex, &words));
            np.head = Head::Room { key, words };
            return Some(j + n);
        }
        let (n, key) = room.filter(|(n, _)| *n > 0 && *n >= noun_len)?;
        Some(self.registry_room_head(np, before, n, key))
    }

    /// A room type of the registry, `n` words at the head, widened by a second room word or a
    /// space word after it.
    fn registry_room_head(
        &self,
        np: &mut Np,
        before: &BeforeHead,
        mut n: usize,
        key: &str,
    ) -> usize {
        let (lex, tokens, j, end) = (self.lex, self.tokens, before.j, self.end);
        // "a florist shop", "the reception hall": a second room word names the same room.
        if let Some((n2, _)) = self
            .kb
            .room_type_at(tokens, j + n)
            .filter(|(n2, _)| j + n + n2 <= end)
            && lex.noun_at(tokens, j + n).is_none_or(|(l, ..)| l <= n2)
            // "the pantry stores sacks": a verb.
            && word(tokens, j + n).is_none_or(|x| lex.verb(x).is_none())
        {
            n += n2;
        }
        // "a salon floor", "the kitchen area": the space of a room type is that room.
        if j + n < end
            && word(tokens, j + n)
                .is_some_and(|x| ground::rules().is_room_space_word(&lex.singular(x)))
            && lex.noun_at(tokens, j + n).is_none_or(|(l, ..)| l == 1)
        {
            n += 1;
        }
        let words: Vec<String> = tokens[j..j + n].iter().map(|t| t.text.clone()).collect();
        let mut ws = words.clone();
        if let Some(last) = ws.last_mut() {
            *last = lex.singular(last);
        }
        np.plural = lex.is_plural(&words[n - 1]);
        np.head = Head::Room {
            key: key.to_string(),
            words: room_name(lex, tokens, before.mods_from, j, ws.join(" ")),
        };
        j + n
    }

    /// A lexicon noun head, with the nouns before it as modifiers, unknown nouns after it, or
    /// read as a part ("the top shelf"); returns the index after the phrase.
    fn object_head(&self, np: &mut Np, before: &BeforeHead, noun: NounAt) -> usize {
        let noun = self.absorb_noun_compounds(np, noun);
        let NounAt {
            start,
            len: n,
            plural,
            ..
        } = noun;
        // A known noun followed by nouns the lexicon does not know ends with them: "ball
        // pit", "filter coffee stand" — when WordNet grounds the last one as a thing.
        if !plural && let Some(next) = self.compound_tail_head(np, start, n) {
            return next;
        }
        // "glass doors", "a brick wall": a material noun before a part of the building is
        // what that part is made of, not a thing of its own.
        let head_word = self.tokens[start + n - 1].text.as_str();
        if n == 1
            && !plural
            && let Some(mat) = self.lex.material(head_word)
            && let Some(next) = self.at(start + 1)
            && self.lex.landmark(next).is_some()
            && self.lex.noun_at(self.tokens, start + 1).is_none()
        {
            np.attrs.materials.push(mat.to_string());
            np.attrs.modifiers.push(self.tokens[start].raw.clone());
            let at = BeforeHead {
                j: start + 1,
                mods_from: before.mods_from,
                which: before.which.clone(),
                evidence: before.evidence,
            };
            if let Some(k) = self.landmark_part_or_setting_head(np, &at, next) {
                return k;
            }
        }
        // A part noun with an ordinal or "top": "the top shelf", "the second shelf".
        if (np.ordinal.is_some() || before.which.is_some())
            && self
                .lex
                .part(head_word)
                .is_some_and(|p| p == "level_if_parent")
        {
            np.head = Head::Part {
                kind: "level".to_string(),
                which: before.which.clone(),
            };
            np.plural = plural;
            return start + n;
        }
        self.lexicon_object(np, before, noun)
    }

    /// Whether the modal verb at `k` ("can", "will") is a noun: a modal is always followed
    /// by a verb ("a chair can seat two"), so one that is not ("an orange can on it", "a tin
    /// can.") is the noun.
    fn modal_as_noun(&self, k: usize) -> bool {
        let wn = crate::words::wordnet::wordnet();
        word(self.tokens, k).is_some_and(|w| MODALS.contains(&w))
            && !word(self.tokens, k + 1)
                .is_some_and(|next| wn.has_pos(next, crate::words::wordnet::Pos::Verb))
    }

    /// Noun-noun compounds: "glass table" — the first noun modifies the second. Returns the
    /// last noun.
    fn absorb_noun_compounds(&self, np: &mut Np, noun: NounAt) -> NounAt {
        let (lex, tokens, end) = (self.lex, self.tokens, self.end);
        let NounAt {
            mut start,
            len: mut n,
            mut entry,
            mut plural,
        } = noun;
        while !plural
            && start + n < end
            && let Some((n2, e2, p2)) = lex.noun_at(tokens, start + n)
            && start + n + n2 <= end
            // "glass display case": a longer noun is no verb ("display"); "an orange can on
            // the shelf": a modal that no verb follows is a noun.
            && (n2 >= 2
                || lex.verb(&tokens[start + n].text).is_none()
                || self.modal_as_noun(start + n))
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
        NounAt {
            start,
            len: n,
            entry,
            plural,
        }
    }

    /// The noun of `n` words at `start` followed by unknown nouns WordNet grounds; returns the
    /// index after them, `None` when no such nouns follow.
    fn compound_tail_head(&self, np: &mut Np, start: usize, n: usize) -> Option<usize> {
        let (lex, tokens) = (self.lex, self.tokens);
        let singular_det = matches!(np.det.as_deref(), Some("indefinite" | "each" | "another"))
            || np.number == Some(1);
        let (len, head) = compound_tail(lex, self.kb, tokens, start + n, self.end, singular_det)?;
        let last = start + n + len - 1;
        if self.verb_of_coordinated_subject(last) {
            return None;
        }
        // "an antique barometer": a one-word noun that is also an adjective modifies.
        let adjective_first = n == 1
            && crate::words::wordnet::wordnet()
                .has_pos(&tokens[start].text, crate::words::wordnet::Pos::Adj);
        if adjective_first {
            np.attrs.adjectives.push(tokens[start].text.clone());
            np.attrs.modifiers.push(tokens[start].raw.clone());
        }
        let from = if adjective_first { start + n } else { start };
        let mut written: Vec<String> = tokens[from..=last].iter().map(|t| t.text.clone()).collect();
        np.plural = lex.is_plural(&tokens[last].text);
        if let Some(w) = written.last_mut() {
            *w = head.singular.clone();
        }
        np.set_grounded(written.join(" "), &head);
        Some(last + 1)
    }

    /// "A broom and a mop stand in the corner": the second of two coordinated subjects, in a
    /// sentence with no verb before it, ends in a verb in its base form (the plural verb of
    /// both), not in a compound noun ("mop stand").
    fn verb_of_coordinated_subject(&self, k: usize) -> bool {
        let (lex, tokens) = (self.lex, self.tokens);
        let Some(w) = word(tokens, k) else {
            return false;
        };
        let base_verb = lex.verb(w).is_some() && !w.ends_with('s') && !w.ends_with("ed");
        let after_and = self.start > self.sentence_start
            && word(tokens, self.start - 1).is_some_and(|c| lex.is_conjunction(c));
        let no_verb_before = (self.sentence_start..self.start)
            .all(|i| word(tokens, i).is_none_or(|x| lex.verb(x).is_none()));
        let then_place = lex.preposition_at(tokens, k + 1).is_some()
            || word(tokens, k + 1).is_some_and(|x| lex.landmark(x).is_some());
        base_verb && after_and && no_verb_before && then_place
    }

    /// The object head of lexicon entry `entry` written as `noun`, and a group suffix after it
    /// ("arrangement"); returns the index after the phrase.
    fn lexicon_object(&self, np: &mut Np, before: &BeforeHead, noun: NounAt) -> usize {
        let (lex, tokens) = (self.lex, self.tokens);
        let (start, n, entry) = (noun.start, noun.len, noun.entry);
        let mut written: Vec<String> = tokens[start..start + n]
            .iter()
            .map(|t| t.text.clone())
            .collect();
        // "chests of drawers": the word before "of" is the one in the plural.
        let counted = match written.iter().position(|w| w == "of") {
            Some(p) if p > 0 => Some(0),
            _ => written.len().checked_sub(1),
        };
        if let Some(w) = counted.and_then(|i| written.get_mut(i)) {
            *w = lex.singular(w);
        }
        let canonical = lex
            .objects
            .get(entry)
            .map_or_else(|| written.join(" "), |e| e.noun.clone());
        np.plural = noun.plural;
        np.head = Head::Object {
            entry: Some(entry),
            noun: name_of(lex, tokens, before.mods_from, start, &written.join(" ")),
            canonical,
            head_entry: None,
        };
        let mut k = start + n;
        if let Some(s) = self.at(k)
            && lex.is_group_suffix(s)
        {
            np.group_suffix = true;
            k += 1;
        }
        k
    }

    /// A landmark ("the front wall"), a part ("levels", "place settings") or a setting noun
    /// ("people") at the head `w`.
    fn landmark_part_or_setting_head(
        &self,
        np: &mut Np,
        before: &BeforeHead,
        w: &str,
    ) -> Option<usize> {
        let (lex, j) = (self.lex, before.j);
        if let Some(class) = lex.landmark(w)
            && !(j + 1 < self.end && landmark_before_thing(lex, self.tokens, j))
        {
            // "the front wall", "the back corner": the last landmark word is the head.
            if let Some(next) = self.at(j + 1)
                && let Some(c2) = lex.landmark(next)
                && matches!(c2, "wall" | "walls" | "corner" | "window" | "door")
            {
                np.plural = lex.is_plural(next);
                np.head = Head::Landmark(c2.to_string());
                return Some(j + 2);
            }
            np.plural = lex.is_plural(w);
            np.head = Head::Landmark(class.to_string());
            return Some(j + 1);
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
                which: before.which.clone(),
            };
            // "place settings"
            return Some(j + 1);
        }
        if lex.is_setting_noun(w) {
            np.plural = true;
            np.head = Head::Setting;
            return Some(j + 1);
        }
        None
    }

    /// "a hot-desking area", "a play zone": an area or zone word after words that say what
    /// it is for names a space, typed by a thing those words name (else a generic room). A
    /// house's list makes it a room of its own; a room's "with" keeps it a zone of the room.
    fn space_room_head(&self, np: &mut Np, before: &BeforeHead, w: &str) -> Option<usize> {
        let (lex, tokens, j) = (self.lex, self.tokens, before.j);
        let space = matches!(lex.singular(w).as_str(), "area" | "zone");
        if !space || j == before.mods_from || self.kb.room_type_at(tokens, j).is_some() {
            return None;
        }
        let kind = word(tokens, j - 1)?;
        let key = type_for_object(lex, &lex.singular(kind));
        let words = room_name(lex, tokens, before.mods_from, j, lex.singular(w));
        if words == lex.singular(w) {
            return None;
        }
        np.plural = lex.is_plural(w);
        np.head = Head::Room { key, words };
        Some(j + 1)
    }

    /// A feature word ("accents") or words that are never objects ("area", "theme") at the
    /// head `w`; `None` when a noun they modify follows.
    fn feature_or_non_object_head(
        &self,
        np: &mut Np,
        before: &BeforeHead,
        w: &str,
    ) -> Option<usize> {
        let (lex, tokens, j) = (self.lex, self.tokens, before.j);
        if lex.is_feature_noun(w) {
            // "a spinning wheel": a part word that makes a thing WordNet knows with the word
            // before it is that thing.
            if j > before.mods_from
                && let Some(prev) = word(tokens, j - 1)
                && let Some(pair) = wordnet_pair(lex, prev, w)
                && let Ok(head) = ground_words(lex, &[prev, w], Evidence::Strong)
            {
                np.plural = head.singular != w;
                np.set_grounded(pair, &head);
                return Some(j + 1);
            }
            np.head = Head::Feature;
            return Some(j + 1);
        }
        if lex.is_non_object(w) {
            let mut k = j;
            while self.at(k).is_some_and(|x| lex.is_non_object(x)) {
                k += 1;
            }
            // "a coffee grinder": a word that is never an object may modify a noun after it.
            let noun_after = k < self.end
                && compound_word(lex, self.kb, tokens, k)
                && (lex.noun_at(tokens, k).is_some() || self.at(k).is_some_and(ground::is_noun));
            if !noun_after {
                np.head = Head::NonObject;
                return Some(k);
            }
        }
        None
    }

    /// Whether the word at `k` names a building the nouns before it say the use of ("the ham
    /// radio shack"): a word the lexicon does not know whose every sense is a building or
    /// shelter. Only after "the": "a toy barn" and "a gingerbread house" are things.
    fn building_at(&self, k: usize) -> bool {
        self.at(k)
            .is_some_and(|w| self.lex.noun_at(self.tokens, k).is_none() && ground::is_building(w))
    }

    /// Open vocabulary: words the lexicon does not know, the last a noun WordNet grounds.
    fn open_vocabulary_head(&self, np: &mut Np, before: &BeforeHead) -> Option<usize> {
        let (lex, tokens, j) = (self.lex, self.tokens, before.j);
        // Counted, listed or introduced with "a": the phrase presents a thing.
        let strong = np.number.is_some()
            || np.quant.is_some()
            || np.group.is_some()
            || np.negated
            || self.in_list
            || matches!(
                np.det.as_deref(),
                Some("indefinite" | "each" | "another" | "several")
            );
        let evidence = if strong {
            Evidence::Strong
        } else {
            Evidence::Weak
        };
        let phrase = (self.start, self.end);
        match open_head(lex, self.kb, tokens, j, phrase, np, evidence, self.in_list) {
            Open::Lexicon { before: at, n2, .. } if names_building(lex, tokens, at, n2) => {
                np.head = Head::NonObject;
                Some(at + n2)
            }
            Open::Lexicon { before: at, n2, .. }
                if np.det.as_deref() == Some("definite") && self.building_at(at + n2) =>
            {
                np.head = Head::NonObject;
                Some(at + n2 + 1)
            }
            Open::Lexicon {
                before: at,
                n2,
                entry,
                plural,
            } => {
                let noun = NounAt {
                    start: at,
                    len: n2,
                    entry,
                    plural,
                };
                Some(self.modified_lexicon_object(np, before, noun))
            }
            Open::Room {
                before: at,
                n2,
                key,
            } => {
                np.attrs
                    .modifiers
                    .extend(tokens[j..at].iter().map(|t| t.raw.clone()));
                let mut ws: Vec<String> =
                    tokens[at..at + n2].iter().map(|t| t.text.clone()).collect();
                if let Some(last) = ws.last_mut() {
                    *last = lex.singular(last);
                }
                np.head = Head::Room {
                    key,
                    words: ws.join(" "),
                };
                Some(at + n2)
            }
            Open::Feature(k) => {
                np.head = Head::Feature;
                Some(k)
            }
            Open::Object {
                adjectives,
                noun,
                head,
                next,
                plural,
            } => {
                np.attrs.modifiers.extend(adjectives);
                np.plural = plural;
                np.set_grounded(noun.clone(), &head);
                // The name as written keeps the words before it ("a deep fryer", "an
                // analytical balance"); the category is the noun alone.
                let start = next.saturating_sub(noun.split(' ').count());
                if let Head::Object { noun: written, .. } = &mut np.head {
                    *written = name_of(lex, tokens, before.mods_from, start, &noun);
                }
                Some(next)
            }
            Open::Dropped { next, report } => {
                np.report = Some(report);
                np.head = Head::NonObject;
                Some(next)
            }
            Open::Nothing => None,
        }
    }

    /// A lexicon noun after words the lexicon does not know ("velvet chaise"): they modify it.
    fn modified_lexicon_object(&self, np: &mut Np, before: &BeforeHead, noun: NounAt) -> usize {
        let (lex, tokens) = (self.lex, self.tokens);
        let (at, n2, entry) = (noun.start, noun.len, noun.entry);
        np.attrs
            .modifiers
            .extend(tokens[before.j..at].iter().map(|t| t.raw.clone()));
        let mut written: Vec<String> = tokens[at..at + n2].iter().map(|t| t.text.clone()).collect();
        if let Some(last) = written.last_mut() {
            *last = lex.singular(last);
        }
        np.plural = noun.plural;
        np.head = Head::Object {
            entry: Some(entry),
            noun: name_of(lex, tokens, before.mods_from, at, &written.join(" ")),
            canonical: lex
                .objects
                .get(entry)
                .map_or_else(|| written.join(" "), |e| e.noun.clone()),
            head_entry: None,
        };
        at + n2
    }
}

/// A head noun the lexicon does not know, grounded in WordNet.
struct Grounded {
    /// Singular of the last word.
    singular: String,
    /// WordNet lemma of the grounded noun (the longest compound WordNet knows).
    lemma: String,
    /// The lexicon noun it is built as (nearest hypernym the lexicon knows).
    family: Option<String>,
    /// Lexicon index of `family`.
    family_entry: Option<usize>,
    /// Hypernym lemmas from the noun to its family.
    via: Vec<String>,
    /// No dictionary knows the word.
    unknown: bool,
}

impl Np {
    /// The head is `noun`, which the lexicon does not know and WordNet grounded as `head`.
    fn set_grounded(&mut self, noun: String, head: &Grounded) {
        self.report = Some(head.report(&noun));
        self.head = Head::Object {
            entry: None,
            noun: noun.clone(),
            canonical: noun,
            head_entry: head.family_entry,
        };
    }
}

impl Grounded {
    fn report(&self, noun: &str) -> NounReport {
        NounReport {
            noun: noun.to_string(),
            lemma: Some(self.lemma.clone()),
            status: if self.unknown {
                NounStatus::Unknown
            } else if self.family.is_some() {
                NounStatus::Routed
            } else {
                NounStatus::StandIn
            },
            family: self.family.clone(),
            reason: if self.unknown {
                Some("no dictionary knows the word; counted or listed, so a stand-in".to_string())
            } else {
                (!self.via.is_empty()).then(|| self.via.join(" > "))
            },
        }
    }
}

/// How a phrase presents its noun as a thing.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
enum Evidence {
    /// Nothing presents it.
    Weak,
    /// The phrase counts it, lists it or introduces it with "a".
    Strong,
    /// As `Strong`, and the sentence places it: a spatial preposition or a verb of placing
    /// or holding next to it ("a ribbon on the table", "shelves hold catalogues").
    Placed,
}

/// Grounds the noun made of `words` (the last is the head): the longest compound ending at
/// the head that WordNet knows decides, with how the phrase presents it.
fn ground_words(lex: &Lexicon, words: &[&str], evidence: Evidence) -> Result<Grounded, String> {
    let strong = evidence >= Evidence::Strong;
    let Some(last) = words.last() else {
        return Err("no noun".to_string());
    };
    let mut found: Option<(String, Verdict)> = None;
    for start in 0..words.len() {
        let compound = words[start..].join(" ");
        if ground::noun_lemma(&compound).is_some() {
            found = Some((compound.clone(), ground::verdict(&compound)));
            break;
        }
    }
    let (compound, verdict) = match found {
        Some(f) => f,
        // A word no dictionary knows ("hoverboards") is a thing only where the phrase counts
        // or lists it; it stands in, and grounds nothing (see `Reading::understood`).
        None if strong
            && !ground::is_word(last)
            && !lex.is_non_object(last)
            && !lex.is_function_word(last) =>
        {
            return Ok(Grounded {
                singular: lex.singular(last),
                lemma: words.join(" "),
                family: None,
                family_entry: None,
                via: Vec::new(),
                unknown: true,
            });
        }
        None => (last.to_string(), ground::verdict(last)),
    };
    match verdict {
        Verdict::Object => {}
        Verdict::NeedsEvidence if strong => {}
        Verdict::NeedsEvidence => {
            return Err("rarely a thing, and the phrase neither counts nor lists it".to_string());
        }
        Verdict::Rarely(_) if evidence == Evidence::Placed => {}
        Verdict::NotObject(why) | Verdict::Rarely(why) => return Err(why),
    }
    Ok(grounded(lex, &compound, last))
}

/// The grounding of `compound` (head `last`), a noun WordNet reads as a thing.
fn grounded(lex: &Lexicon, compound: &str, last: &str) -> Grounded {
    let lemma = ground::noun_lemma(compound).unwrap_or_else(|| compound.to_string());
    let singular = ground::noun_lemma(last).unwrap_or_else(|| lex.singular(last));
    let family = ground::family(compound, &|n: &str| lex.lookup(n).is_some());
    let family_entry = family
        .as_ref()
        .and_then(|f| lex.lookup(&f.noun))
        .and_then(|e| lex.entry_index(&e.noun));
    Grounded {
        singular,
        lemma,
        family: family
            .as_ref()
            .and_then(|f| lex.lookup(&f.noun))
            .map(|e| e.noun.clone()),
        family_entry,
        via: family.map(|f| f.via).unwrap_or_default(),
        unknown: false,
    }
}

/// A noun that a room word before it modifies ("sofa" in "living room sofa"): a noun of the
/// lexicon or WordNet, no room or room-space word, no verb in -s ("The kitchen boasts").
fn noun_follows(lex: &Lexicon, kb: &Knowledge, tokens: &[Token], k: usize) -> bool {
    let Some(x) = word(tokens, k) else {
        return false;
    };
    let verb_s = x.ends_with('s')
        && !crate::words::wordnet::wordnet()
            .base_forms(x, crate::words::wordnet::Pos::Verb)
            .is_empty();
    let wn = crate::words::wordnet::wordnet();
    // "three bedrooms upstairs": a word WordNet also reads as an adverb, and no object of
    // the lexicon, ends the phrase.
    let adverb = lex.noun_at(tokens, k).is_none() && wn.has_pos(x, crate::words::wordnet::Pos::Adv);
    compound_word(lex, kb, tokens, k)
        && !adverb
        && (lex.noun_at(tokens, k).is_some() || ground::is_noun(x))
        && !ground::rules().is_room_space_word(&lex.singular(x))
        && kb.room_type_at(tokens, k).is_none()
        && !verb_s
}

/// A word that may continue an open noun compound: not a function word, a landmark, a
/// preposition, a verb of the lexicon, a number, and a noun or adjective to WordNet.
fn compound_word(lex: &Lexicon, kb: &Knowledge, tokens: &[Token], k: usize) -> bool {
    let Some(x) = word(tokens, k) else {
        return false;
    };
    !lex.is_function_word(x)
        && (lex.landmark(x).is_none() || landmark_before_thing(lex, tokens, k))
        && lex.preposition_at(tokens, k).is_none()
        && lex.verb(x).is_none()
        && lex.number(&tokens[k]).is_none()
        && !lex.is_setting_noun(x)
        && !lex.is_feature_noun(x)
        && kb.room_type_at(tokens, k).is_none()
        && x.chars().all(|c| c.is_alphabetic() || c == '-')
        && !matches!(ground::only_other_pos(x), Some("verb" | "adverb"))
}

/// A noun WordNet has only in the plural ("tongs", "pliers"); not "glass" or "grass", whose
/// lemma ends in -ss.
fn plural_only(lex: &Lexicon, w: &str) -> bool {
    lex.plurale_tantum(w) && !w.ends_with("ss")
}

/// "a floor loom", "a wall tapestry": a singular landmark word at `k` before a noun WordNet
/// reads as a placeable thing, which is no verb there (no determiner or number follows it),
/// says where the thing stands or hangs; the thing is the head.
fn landmark_before_thing(lex: &Lexicon, tokens: &[Token], k: usize) -> bool {
    let (Some(w), Some(next)) = (word(tokens, k), word(tokens, k + 1)) else {
        return false;
    };
    lex.landmark(w).is_some()
        && !lex.is_plural(w)
        && lex.landmark(next).is_none()
        && lex.part(next).is_none()
        && lex.verb(next).is_none()
        && lex.preposition_at(tokens, k + 1).is_none()
        && !determiner_or_number_at(lex, tokens, k + 2)
        && ground::verdict(next) == ground::Verdict::Object
}

/// A plural at `k` after a singular noun, which WordNet reads as a placeable thing once
/// singular and which no determiner or number follows (then it would be a verb taking an
/// object).
fn plural_thing_after_singular(lex: &Lexicon, tokens: &[Token], k: usize) -> bool {
    let (Some(prev), Some(x)) = (word(tokens, k - 1), word(tokens, k)) else {
        return false;
    };
    lex.is_plural(x)
        && !lex.is_plural(prev)
        && ground::is_noun(prev)
        && lex.determiner(x).is_none()
        && lex.preposition_at(tokens, k).is_none()
        && !determiner_or_number_at(lex, tokens, k + 1)
        && ground::verdict(&lex.singular(x)) == ground::Verdict::Object
}

/// A determiner or a number at `k`: a noun phrase starts there, so the word before it is no
/// part of a compound noun (a verb, if WordNet knows it as one).
fn determiner_or_number_at(lex: &Lexicon, tokens: &[Token], k: usize) -> bool {
    word(tokens, k).is_some_and(|x| lex.determiner(x).is_some())
        || tokens.get(k).is_some_and(|t| lex.number(t).is_some())
}

/// Length of a compound noun WordNet knows as written (2 or 3 words, the last possibly plural)
/// that starts at `k` and ends before `end`.
fn wordnet_compound_len(lex: &Lexicon, tokens: &[Token], k: usize, end: usize) -> Option<usize> {
    (2..=3).rev().find(|&n| {
        k + n <= end && (k..k + n).all(|q| word(tokens, q).is_some()) && {
            let mut ws: Vec<String> = tokens[k..k + n].iter().map(|t| t.text.clone()).collect();
            if let Some(l) = ws.last_mut() {
                *l = lex.singular(l);
            }
            let c = ws.join(" ");
            ground::noun_lemma(&c).is_some_and(|l| l == c)
        }
    })
}

/// A word the verb table lists that is also a WordNet noun in its base form ("mount",
/// "stand", "rest"), and no determiner or preposition.
fn base_form_noun(lex: &Lexicon, tokens: &[Token], k: usize) -> bool {
    let Some(x) = word(tokens, k) else {
        return false;
    };
    lex.verb(x).is_some()
        && lex.determiner(x).is_none()
        && lex.preposition_at(tokens, k).is_none()
        && crate::words::wordnet::wordnet().is_lemma(x, crate::words::wordnet::Pos::Noun)
        && !x.ends_with('s')
        && !x.ends_with("ed")
        && !x.ends_with("ing")
        && tokens.get(k.wrapping_sub(1)).is_some_and(|t| {
            // Only after a modifier: "each have", "a display" keep their own readings.
            !lex.is_plural(&t.text)
                && t.is_word()
                && lex.determiner(&t.text).is_none()
                && lex.number(t).is_none()
                && lex.quantifier_at(tokens, k - 1).is_none()
        })
}

/// Tag count under which an -ing noun is rare enough to read as a verb form after a noun
/// ("ticking", "humming"; not "painting", "drawing").
const RARE_ING_NOUN_COUNT: u32 = 5;

/// Whether the -ing word at `k`, after a noun, is a participle: a WordNet verb form whose noun
/// senses name no thing or are rare, followed by a preposition, a determiner, punctuation or
/// the end of the phrase, and not one WordNet noun with the word before it.
fn participle_after_noun(lex: &Lexicon, tokens: &[Token], k: usize, end: usize) -> bool {
    let wn = crate::words::wordnet::wordnet();
    let Some(x) = word(tokens, k) else {
        return false;
    };
    if !x.ends_with("ing")
        || wn
            .base_forms(x, crate::words::wordnet::Pos::Verb)
            .is_empty()
    {
        return false;
    }
    let prev_is_noun = word(tokens, k - 1).is_some_and(ground::is_noun);
    let clause_follows = k + 1 >= end
        || word(tokens, k + 1).is_none_or(|n| {
            lex.preposition_at(tokens, k + 1).is_some() || lex.determiner(n).is_some()
        });
    let rare = ground::noun_info(x).is_none_or(|i| {
        i.share == 0.0
            || wn
                .noun_senses(&i.lemma)
                .iter()
                .map(|s| s.count)
                .sum::<u32>()
                < RARE_ING_NOUN_COUNT
    });
    prev_is_noun
        && clause_follows
        && rare
        && word(tokens, k - 1).is_some_and(|p| wordnet_pair(lex, p, x).is_none())
}

/// After a lexicon noun: one or two nouns the lexicon does not know that end the phrase
/// and that WordNet grounds as a thing ("pit" of "ball pit", "coffee stand" of "filter coffee
/// stand"). Returns (words used, grounding).
fn compound_tail(
    lex: &Lexicon,
    kb: &Knowledge,
    tokens: &[Token],
    at: usize,
    end: usize,
    singular_det: bool,
) -> Option<(usize, Grounded)> {
    let mut len = 0;
    let wn = crate::words::wordnet::wordnet();
    // "cake stand", "music stand": a noun in its base form, even one the verb table lists.
    let tail_word = |k: usize| {
        let x = tokens[k].text.as_str();
        compound_word(lex, kb, tokens, k)
            || (lex.verb(x).is_some()
                && wn.is_lemma(x, crate::words::wordnet::Pos::Noun)
                && !x.ends_with('s')
                && !x.ends_with("ed")
                && !x.ends_with("ing")
                && lex.preposition_at(tokens, k).is_none())
    };
    // "a drill press": the noun before and this word are one WordNet noun.
    let wn_compound = |k: usize| {
        k > 0 && {
            let c = format!("{} {}", tokens[k - 1].text, lex.singular(&tokens[k].text));
            ground::noun_lemma(&c).is_some_and(|l| l == c)
        }
    };
    // "a bench grinder share a cart": a word WordNet knows as a verb, then a new phrase.
    let verb_then_phrase = |k: usize| {
        tokens.get(k).is_some_and(|t| {
            !wn.base_forms(&t.text, crate::words::wordnet::Pos::Verb)
                .is_empty()
        }) && tokens
            .get(k + 1)
            .is_some_and(|u| lex.determiner(&u.text).is_some() || lex.number(u).is_some())
    };
    while len < 2
        && at + len < end
        && !(len > 0 && verb_then_phrase(at + len))
        && !participle_after_noun(lex, tokens, at + len, end)
        && lex.noun_at(tokens, at + len).is_none()
        && tail_word(at + len)
        && ground::is_noun(&tokens[at + len].text)
        // "A sturdy squat rack anchors the centre": a verb in -s after "a ...".
        && (!singular_det
            || !tokens[at + len].text.ends_with('s')
            || wn.base_forms(&tokens[at + len].text, crate::words::wordnet::Pos::Verb).is_empty()
            || wn_compound(at + len))
    {
        len += 1;
        if lex.is_plural(&tokens[at + len - 1].text) {
            break;
        }
    }
    if len == 0 {
        return None;
    }
    let after = tokens.get(at + len);
    // "a bench vice bolted to ...": a participle after it ends the phrase too.
    let participle = |x: &str| {
        x.ends_with("ed")
            && !wn
                .base_forms(x, crate::words::wordnet::Pos::Verb)
                .is_empty()
    };
    let ends = after.is_none_or(|t| {
        !t.is_word()
            || lex.is_function_word(&t.text)
            || lex.landmark(&t.text).is_some()
            || lex.preposition_at(tokens, at + len).is_some()
            || lex.verb(&t.text).is_some()
            || participle(&t.text)
            || verb_then_phrase(at + len)
    });
    if !ends {
        return None;
    }
    // "Shelves above the desk display a meteorite": a word the verb table knows, followed by
    // the start of another noun phrase, is the verb.
    let starts_phrase = after.is_some_and(|t| {
        lex.determiner(&t.text).is_some()
            || lex.number(t).is_some()
            || lex.quantifier_at(tokens, at + len).is_some()
    });
    // "a bread bin and a toaster share a corner": a word WordNet knows as a verb is one here
    // too, unless the noun before and it are one WordNet noun.
    let last_word = tokens[at + len - 1].text.as_str();
    let wordnet_verb =
        wn.has_pos(last_word, crate::words::wordnet::Pos::Verb) && !(len == 1 && wn_compound(at));
    if starts_phrase && (lex.verb(last_word).is_some() || wordnet_verb) {
        return None;
    }
    let words: Vec<&str> = tokens[at..at + len]
        .iter()
        .map(|t| t.text.as_str())
        .collect();
    // The known noun before makes the phrase an object phrase: a rarely physical head
    // ("pit") still names the thing. A compound WordNet knows grounds as a whole.
    if len == 1 && wn_compound(at) {
        let whole = [tokens[at - 1].text.as_str(), words[0]];
        // Without a family it would be a stand-in: the known noun builds it better, under
        // the compound's name ("drill press" built as a drill).
        let known = lex
            .entry_index(&tokens[at - 1].text)
            .or_else(|| lex.entry_index(&lex.singular(&tokens[at - 1].text)));
        return ground_words(lex, &whole, Evidence::Strong)
            .ok()
            .and_then(|mut g| {
                if g.family.is_none() {
                    let entry = known?;
                    g.family = lex.objects.get(entry).map(|e| e.noun.clone());
                    g.family_entry = Some(entry);
                    g.via = vec![g.lemma.clone(), tokens[at - 1].text.clone()];
                }
                Some((len, g))
            });
    }
    // "a bench vice", "a bench grinder": after a known noun, a noun with any physical sense
    // names that thing.
    ground_words(lex, &words, Evidence::Strong)
        .ok()
        .or_else(|| {
            let last = *words.last()?;
            let info = ground::noun_info(last)?;
            // Not a word that is as often a verb ("a table set for four").
            let plain = lex.verb(last).is_none() && !lex.is_ambiguous_bare(last);
            (len == 1 && plain && !info.placeable.is_empty()).then(|| grounded(lex, last, last))
        })
        .map(|g| (len, g))
}

/// What an open-vocabulary phrase turned out to be.
enum Open {
    /// A lexicon noun after unknown modifiers ("velvet chaise" → ... "chaise").
    Lexicon {
        before: usize,
        n2: usize,
        entry: usize,
        plural: bool,
    },
    /// A room word after unknown modifiers.
    Room {
        before: usize,
        n2: usize,
        key: String,
    },
    /// A feature noun ("leather accents").
    Feature(usize),
    /// A noun WordNet grounds as a thing.
    Object {
        adjectives: Vec<String>,
        noun: String,
        head: Grounded,
        next: usize,
        plural: bool,
    },
    /// Words that name no thing (adjectives, feelings, states, unknown words).
    Dropped { next: usize, report: NounReport },
    /// Nothing to read.
    Nothing,
}

/// Reads words the lexicon does not know at `j`: the run of compound words, then WordNet
/// decides whether its last word names a thing. Adjectives before it are modifiers; nouns
/// before it are part of the name ("filter coffee stand").
#[allow(clippy::too_many_arguments)]
fn open_head(
    lex: &Lexicon,
    kb: &Knowledge,
    tokens: &[Token],
    j: usize,
    (phrase_start, end): (usize, usize),
    np: &Np,
    evidence: Evidence,
    in_list: bool,
) -> Open {
    let at = |k: usize| if k < end { word(tokens, k) } else { None };
    let singular_det = matches!(np.det.as_deref(), Some("indefinite" | "each" | "another"))
        || np.number == Some(1);
    let plural_count = np.number.is_some_and(|n| n > 1);
    let mut k = j;
    while k < end && k - j < 4 {
        let Some(x) = at(k) else { break };
        if k > j
            && let Some((n2, entry, plural)) = lex.noun_at(tokens, k)
            && k + n2 <= end
        {
            return Open::Lexicon {
                before: k,
                n2,
                entry,
                plural,
            };
        }
        if k > j
            && let Some((n2, key)) = kb.room_type_at(tokens, k)
            && !made_of_thing(lex, tokens, j, k, n2)
        {
            return Open::Room {
                before: k,
                n2,
                key: key.to_string(),
            };
        }
        if k > j && lex.is_feature_noun(x) {
            if wordnet_pair(lex, &tokens[k - 1].text, x).is_some() {
                k += 1;
                break;
            }
            return Open::Feature(k + 1);
        }
        // "its checkerboard floor", "a chalkboard wall": nouns before a part of the building
        // describe it.
        if k > j
            && lex.is_non_object(x)
            && ground::noun_info(x).is_some_and(|i| i.structure && i.share < 0.5)
        {
            return Open::Feature(k + 1);
        }
        // "a refracting telescope": words WordNet knows together as one noun are read whole,
        // whatever the first of them is on its own (here a verb form).
        if let Some(n) = wordnet_compound_len(lex, tokens, k, end) {
            k += n;
            continue;
        }
        // "a grinding wheel turned by a pedal": after a noun, a past participle that is no
        // noun begins a clause about it.
        if k > j
            && x.ends_with("ed")
            && !ground::is_noun(x)
            && !crate::words::wordnet::wordnet()
                .base_forms(x, crate::words::wordnet::Pos::Verb)
                .is_empty()
        {
            break;
        }
        // "Skeins of yarn fill the shelf": a word WordNet knows as a verb with a determiner or
        // number right after it is that verb; no compound noun runs into a determiner.
        if k > j
            && crate::words::wordnet::wordnet().has_pos(x, crate::words::wordnet::Pos::Verb)
            && determiner_or_number_at(lex, tokens, k + 1)
        {
            break;
        }
        // "a heavy iron mount dominates": after modifiers, a noun in its base form that the
        // verb table also lists ends the phrase as its noun; a singular subject's verb would
        // end in -s.
        if k == j
            && k > phrase_start
            && base_form_noun(lex, tokens, k)
            && !(plural_count && plural_thing_after_singular(lex, tokens, k + 1))
        {
            k += 1;
            break;
        }
        // "Two repair stands clamp bicycles": a count of several before a singular noun wants
        // a plural head, so a plural the verb table also lists ("stands", "rests") that
        // WordNet reads as a thing ends the compound as its head.
        if k > j && plural_count && plural_thing_after_singular(lex, tokens, k) {
            k += 1;
            break;
        }
        if !compound_word(lex, kb, tokens, k) {
            break;
        }
        // "a brass metronome ticking on its lid": after a noun, a verb form in -ing that
        // rarely names a thing, with a preposition, a determiner or nothing after it, begins
        // a clause about the noun.
        if k > j && participle_after_noun(lex, tokens, k, end) {
            break;
        }
        // A word that is never an object on its own ("coffee", "reading") may still modify
        // the noun after it ("coffee stand").
        if lex.is_non_object(x)
            && !(k + 1 < end
                && compound_word(lex, kb, tokens, k + 1)
                && !lex.is_non_object(&tokens[k + 1].text))
        {
            break;
        }
        // "a headboard dominates the space": after a singular noun, a verb in -s is the verb.
        // "the observatory opens to the sky": after "the" too, when the word is rarely a
        // thing ("cups" stays a noun).
        let rarely_thing = || {
            np.det.as_deref() == Some("definite")
                && ground::noun_info(x)
                    .is_none_or(|i| i.share < ground::rules().min_share_with_evidence)
        };
        if k > j
            && (singular_det || rarely_thing())
            && x.ends_with('s')
            && ground::only_other_pos(x).is_none()
            && crate::words::wordnet::wordnet().has_pos(x, crate::words::wordnet::Pos::Verb)
            && at(k - 1).is_some_and(ground::is_noun)
        {
            break;
        }
        k += 1;
        if k > j + 1 && lex.is_plural(x) && ground::is_noun(x) {
            // A plural noun ends a compound ("chairs", not "chairs cushions").
            break;
        }
    }
    if k == j {
        return Open::Nothing;
    }
    let words: Vec<&str> = tokens[j..k].iter().map(|t| t.text.as_str()).collect();
    let raw: Vec<&str> = tokens[j..k].iter().map(|t| t.raw.as_str()).collect();
    let written = raw.join(" ");
    // The head is the last word; adjectives before the first noun of the name are modifiers.
    let name_from = words
        .iter()
        .position(|w| ground::is_noun(w) && ground::only_other_pos(w).is_none())
        .map(|p| {
            // A word WordNet also knows as an adjective stays a modifier unless it ends the run.
            let mut q = p;
            while q + 1 < words.len()
                && crate::words::wordnet::wordnet()
                    .has_pos(words[q], crate::words::wordnet::Pos::Adj)
            {
                q += 1;
            }
            q
        })
        .unwrap_or(words.len() - 1);
    // An adjective that WordNet lists in a compound with the rest, as a thing, is part of the
    // name ("an analytical balance": a scale, where a balance alone is mostly a state).
    let name_from = (0..name_from)
        .find(|&start| {
            let compound = words[start..].join(" ");
            ground::noun_lemma(&compound).is_some() && ground::verdict(&compound) == Verdict::Object
        })
        .unwrap_or(name_from);
    let name = &words[name_from..];
    let last = words[words.len() - 1];
    let bare = np.det.is_none()
        && np.number.is_none()
        && np.quant.is_none()
        && np.group.is_none()
        && !np.negated;
    let singular = ground::noun_lemma(last).is_some_and(|l| l == last) && !plural_only(lex, last);
    // "elegant and formal", "adds greenery": a bare word that is also an adjective, or a
    // bare singular outside a list, names no object.
    let bare_reason = if bare && ground::is_adjective(last) {
        Some("an adjective here (no determiner)")
    } else if bare && singular && !in_list {
        Some("a bare singular outside a list (a mass word here)")
    } else {
        None
    };
    let dropped = |reason: String| Open::Dropped {
        next: k,
        report: NounReport {
            noun: written.clone(),
            lemma: ground::noun_lemma(&name.join(" ")),
            status: NounStatus::Dropped,
            family: None,
            reason: Some(reason),
        },
    };
    if let Some(reason) = bare_reason {
        return dropped(reason.to_string());
    }
    // A rarely physical noun is a thing where the sentence places it and the phrase names
    // several of them or a kind of it, not one it already knows ("shelves hold catalogues",
    // "a microfilm reader in the corner"; not "under a sloping roof", "in the hills").
    // "a lectern holding a great Bible": a capitalised noun inside the phrase names a kind.
    let named = k > phrase_start + 1 && tokens.get(k - 1).is_some_and(|t| t.capitalized());
    let plural_or_kind = name.len() >= 2 || lex.is_plural(last) || named;
    let known = matches!(np.det.as_deref(), Some("definite" | "possessive"));
    // "at a moment's notice": the determiner counts a possessor that is a time, so the noun
    // after it has only its own word to go on ("a day's newspaper" still names a paper, "a
    // tailor's chalk" is a kind of chalk).
    let evidence = if tokens[j..k.saturating_sub(1)].iter().any(|t| {
        t.possessive && ground::noun_info(&t.text).is_some_and(|i| i.lexname == "noun.time")
    }) {
        Evidence::Weak
    } else {
        evidence
    };
    let evidence = if evidence == Evidence::Strong
        && plural_or_kind
        && !known
        && placed(lex, tokens, phrase_start, k)
    {
        Evidence::Placed
    } else {
        evidence
    };
    if ground::is_animal(&name.join(" "))
        && !made_likeness(np)
        && !animal_placed(lex, tokens, phrase_start, k)
    {
        return dropped("an animal the sentence does not place in the room".to_string());
    }
    match ground_words(lex, name, evidence) {
        Ok(head) => {
            let last = words.len() - 1;
            let mut noun: Vec<String> = name.iter().map(|w| w.to_string()).collect();
            if let Some(l) = noun.last_mut() {
                *l = head.singular.clone();
            }
            Open::Object {
                adjectives: raw[..name_from].iter().map(|w| w.to_string()).collect(),
                noun: noun.join(" "),
                plural: head.singular != words[last],
                head,
                next: k,
            }
        }
        Err(reason) => match likeness(lex, np, &words[..name_from], last) {
            Some(head) => Open::Object {
                adjectives: raw[..name_from].iter().map(|w| w.to_string()).collect(),
                noun: head.singular.clone(),
                plural: head.singular != last,
                head,
                next: k,
            },
            None => dropped(reason),
        },
    }
}

/// An animal made as a thing: "a stuffed giraffe" is a stuffed animal, "a ceramic owl" or
/// "two brass elephants" figurines. `before` are the words between the modifiers and the
/// noun `last`.
fn likeness(lex: &Lexicon, np: &Np, before: &[&str], last: &str) -> Option<Grounded> {
    let info = ground::noun_info(last)?;
    if info.lexname != "noun.animal" {
        return None;
    }
    let words: Vec<String> = np
        .attrs
        .modifiers
        .iter()
        .map(|m| m.to_lowercase())
        .chain(before.iter().map(|w| w.to_string()))
        .collect();
    let soft = words.iter().any(|w| {
        matches!(
            w.as_str(),
            "stuffed" | "plush" | "toy" | "cuddly" | "soft" | "knitted" | "inflatable"
        )
    });
    let made = !np.attrs.materials.is_empty()
        || words
            .iter()
            .any(|w| lex.material(w).is_some() || matches!(w.as_str(), "carved" | "model"));
    let family = if soft {
        "stuffed animal"
    } else if made {
        "figurine"
    } else {
        return None;
    };
    let entry = lex.entry_index(family)?;
    Some(Grounded {
        singular: info.lemma.clone(),
        lemma: info.lemma,
        family: Some(family.to_string()),
        family_entry: Some(entry),
        via: vec![family.to_string()],
        unknown: false,
    })
}

/// Whether the sentence places the phrase of tokens `start..next`: a spatial preposition
/// or a verb of placing, holding or showing right before it ("shelves hold catalogues", "on a
/// board"), or one right after it ("a ribbon on the table", "a berth runs along the hull").
fn placed(lex: &Lexicon, tokens: &[Token], start: usize, next: usize) -> bool {
    let spatial_at = |k: usize| {
        lex.preposition_at(tokens, k)
            .filter(|(_, class)| *class != "from")
            .map(|(n, _)| n)
    };
    let placing_verb = |k: usize| {
        word(tokens, k)
            .and_then(|w| lex.verb(w))
            .is_some_and(|class| !matches!(class, "inspired" | "styled" | "made" | "other"))
    };
    // "next to a ...": a preposition of several words that ends right before the phrase.
    let preposition_before =
        (start.saturating_sub(3)..start).any(|k| spatial_at(k).is_some_and(|n| k + n == start));
    let before = preposition_before || start.checked_sub(1).is_some_and(placing_verb);
    let of_next = word(tokens, next) == Some("of");
    !of_next
        && (before
            || (start..next).any(|k| of_group(lex, tokens, k))
            || spatial_at(next).is_some()
            || placing_verb(next)
            || listed_placed(lex, tokens, start))
}

/// Words before an animal's name that make it a made thing ("a stuffed owl", "a toy dog").
const MADE_ANIMAL_WORDS: [&str; 8] = [
    "stuffed",
    "toy",
    "plush",
    "cuddly",
    "carved",
    "model",
    "taxidermy",
    "wind-up",
];

/// Whether the phrase's modifiers make its animal a made thing: a material ("a brass fox") or
/// one of [`MADE_ANIMAL_WORDS`].
fn made_likeness(np: &Np) -> bool {
    !np.attrs.materials.is_empty()
        || np
            .attrs
            .modifiers
            .iter()
            .any(|m| MADE_ANIMAL_WORDS.contains(&m.to_lowercase().as_str()))
}

/// "A fat cat is asleep on the sofa", "a fox rests on a stand": an animal is in the room when
/// the words right after its phrase place it (a spatial preposition, a verb of placing); "a
/// scale for large dogs", "posters showing a cat" place none.
fn animal_placed(lex: &Lexicon, tokens: &[Token], start: usize, next: usize) -> bool {
    let purpose = start
        .checked_sub(1)
        .and_then(|k| word(tokens, k))
        .is_some_and(|w| {
            matches!(w, "for" | "of" | "like" | "about")
                || lex.verb(w).is_some_and(|c| c == "display")
        });
    let spatial = lex
        .preposition_at(tokens, next)
        .is_some_and(|(_, class)| class != "from");
    let placing = word(tokens, next)
        .and_then(|w| lex.verb(w))
        .is_some_and(|class| !matches!(class, "inspired" | "styled" | "made" | "other"));
    !purpose && (spatial || placing)
}

/// "a stack of flyers", "full of logbooks", "a jar of cotton rolls": the phrase at `start`
/// follows "of" after a group word, "full" or a container.
fn of_group(lex: &Lexicon, tokens: &[Token], start: usize) -> bool {
    start >= 2
        && word(tokens, start - 1) == Some("of")
        && word(tokens, start - 2).is_some_and(|g| {
            g == "full"
                || lex.group(g).is_some()
                // "a jar of cotton rolls": what a container holds is in it.
                || lex.entry(&lex.singular(g)).is_some_and(|e| e.container)
        })
}

/// Whether the list the phrase at `start` ends is placed: back over the list's earlier
/// items ("shelves hold books and logbooks", "a stack of flyers and invoices", "full of sea
/// charts and logbooks") to a placing verb, a spatial preposition, or "of" after a group
/// word or "full". Only a phrase after "and", "or" or a comma is a later item.
fn listed_placed(lex: &Lexicon, tokens: &[Token], start: usize) -> bool {
    let joins = |k: usize| {
        tokens
            .get(k)
            .is_some_and(|t| t.text == "," || matches!(t.text.as_str(), "and" | "or"))
    };
    if start == 0 || !joins(start - 1) {
        return false;
    }
    let placing = |w: &str| {
        lex.verb(w)
            .is_some_and(|class| !matches!(class, "inspired" | "styled" | "made" | "other"))
    };
    for k in (start.saturating_sub(14)..start).rev() {
        let Some(w) = word(tokens, k) else {
            if tokens[k].text == "," {
                continue;
            }
            return false;
        };
        if w == "of" {
            return of_group(lex, tokens, k + 1);
        }
        if placing(w)
            || lex
                .preposition_at(tokens, k)
                .is_some_and(|(_, class)| class != "from")
        {
            return true;
        }
        if lex.verb(w).is_some() || lex.is_relative(w) {
            return false;
        }
    }
    false
}

/// "a wooden bar", "a marble counter": a material word among `from..at` before the room word
/// of `n` words at `at`, which WordNet also knows as a thing. Rooms are not made of a
/// material; the thing is meant.
fn made_of_thing(lex: &Lexicon, tokens: &[Token], from: usize, at: usize, n: usize) -> bool {
    (from..at).any(|k| word(tokens, k).is_some_and(|w| lex.material(w).is_some()))
        && word(tokens, at + n - 1).is_some_and(|w| {
            ground::noun_info(&lex.singular(w)).is_some_and(|i| !i.placeable.is_empty())
        })
}

/// A room's name as the prompt gives it: the room words with the kind words before them
/// ("common kitchen", "sleeping loft", "family bakery"): nouns that are no adjective, and
/// gerunds. Describing adjectives ("spacious", "modern") stay out of the name.
fn room_name(lex: &Lexicon, tokens: &[Token], from: usize, at: usize, words: String) -> String {
    let wn = crate::words::wordnet::wordnet();
    let mut name = words;
    let mut k = at;
    while k > from {
        let Some(w) = word(tokens, k - 1) else { break };
        // Kind words stay ("common kitchen", "staff toilet"); size, colour, material, style
        // and density words describe the room and go to its attributes.
        let noun = (wn.has_pos(w, crate::words::wordnet::Pos::Noun) || ground::is_adjective(w))
            && lex.material(w).is_none()
            && lex.color_at(tokens, k - 1).is_none()
            && lex.size_adjective(w).is_none()
            && lex.density(w).is_none()
            && lex.density_room_only(w).is_none()
            && !lex.is_adjective(w)
            && lex.style_at(tokens, k - 1).is_none();
        let gerund = w.ends_with("ing")
            && !wn
                .base_forms(w, crate::words::wordnet::Pos::Verb)
                .is_empty();
        // "hot-desking area", "open-plan kitchen".
        let hyphenated = w.contains('-') && lex.style_at(tokens, k - 1).is_none();
        if !(noun || gerund || hyphenated) {
            break;
        }
        name = format!("{w} {name}");
        k -= 1;
    }
    name
}

/// `first` and the part word `part` as one noun WordNet knows ("spinning wheel"), singular.
fn wordnet_pair(lex: &Lexicon, first: &str, part: &str) -> Option<String> {
    let pair = format!("{first} {}", lex.singular(part));
    ground::noun_lemma(&pair).filter(|l| *l == pair)
}

/// The room type a room named after an object belongs to ("kiln room": where kilns are):
/// the house table of where objects go, else the first type whose furniture lists it, else a
/// generic room.
fn type_for_object(lex: &Lexicon, noun: &str) -> String {
    let reg = crate::knowledge::knowledge();
    let canonical = lex
        .lookup(noun)
        .map_or_else(|| noun.to_string(), |e| e.noun.clone());
    let registry = crate::knowledge::rooms::registry();
    if let Some(t) = registry
        .house()
        .items_to_rooms
        .get(&canonical)
        .and_then(|v| v.first())
    {
        return t.clone();
    }
    let furnished_by = |noun: &str| {
        reg.rooms()
            .iter()
            .find(|(_, r)| r.furniture.iter().any(|i| i.noun == noun))
            .map(|(k, _)| k.clone())
    };
    if let Some(k) = furnished_by(&canonical) {
        return k;
    }
    // "a bunk room": a bunk is a bed, and bedrooms have beds.
    ground::family(noun, &|n: &str| furnished_by(n).is_some())
        .and_then(|f| furnished_by(&f.noun))
        .unwrap_or_else(|| "room".to_string())
}

/// One or two nouns before a room word ("kiln room", "pottery storage room"): (words used,
/// type, words as written). A generic room word ("room", "area") takes its type from the
/// nouns; a typed one keeps its type.
fn room_compound(
    lex: &Lexicon,
    kb: &Knowledge,
    tokens: &[Token],
    j: usize,
    end: usize,
) -> Option<(usize, String, String)> {
    for m in 1..=2usize {
        if j + m >= end {
            return None;
        }
        let w = word(tokens, j + m - 1)?;
        // A word WordNet does not know at all ("cardio room") may name the room too.
        let wn = crate::words::wordnet::wordnet();
        let unknown = w.chars().all(char::is_alphabetic)
            && [
                crate::words::wordnet::Pos::Noun,
                crate::words::wordnet::Pos::Verb,
                crate::words::wordnet::Pos::Adj,
                crate::words::wordnet::Pos::Adv,
            ]
            .iter()
            .all(|&p| !wn.has_pos(w, p));
        let nounish = ground::is_noun(w) || lex.noun_at(tokens, j + m - 1).is_some() || unknown;
        if !nounish
            || lex.is_function_word(w)
            || lex.preposition_at(tokens, j + m - 1).is_some()
            || lex.landmark(w).is_some()
            || lex.verb(w).is_some()
        {
            return None;
        }
        // A room word of the registry, or one WordNet knows as a room ("phone booths").
        let room_after = kb
            .room_type_at(tokens, j + m)
            .map(|(rn, key)| (rn, key.to_string()))
            .or_else(|| {
                // Not a thing of the lexicon that WordNet also reads as a room ("cupboard"),
                // nor ending in a verb ("the engine bay houses ...").
                let (rn, key, _) = wordnet_room(lex, tokens, j + m, end)?;
                let verb = word(tokens, j + m + rn - 1).is_some_and(|x| {
                    x.ends_with('s')
                        && !wn
                            .base_forms(x, crate::words::wordnet::Pos::Verb)
                            .is_empty()
                });
                (lex.noun_at(tokens, j + m).is_none() && !verb).then_some((rn, key))
            });
        if let Some((rn, key)) = room_after
            && j + m + rn <= end
        {
            let mut written: Vec<String> = tokens[j..j + m + rn]
                .iter()
                .map(|t| t.text.clone())
                .collect();
            if let Some(l) = written.last_mut() {
                *l = lex.singular(l);
            }
            let key = if key == "room" {
                type_for_object(lex, &lex.singular(&tokens[j + m - 1].text))
            } else {
                key
            };
            return Some((m + rn, key, written.join(" ")));
        }
        // "a toilet block", "the staff quarters": a room for the things before the word.
        if let Some(part) = word(tokens, j + m)
            && ground::rules().is_room_part_word(&lex.singular(part))
            && (j + m + 1 >= end || lex.noun_at(tokens, j + m + 1).is_none())
        {
            let mut written: Vec<String> =
                tokens[j..=j + m].iter().map(|t| t.text.clone()).collect();
            if let Some(l) = written.last_mut() {
                *l = lex.singular(l);
            }
            // "a foam block" names no room: the thing must be one some room type holds, or
            // the part word must rarely be a thing itself ("an engine bay").
            let key = type_for_object(lex, &lex.singular(&tokens[j + m - 1].text));
            if key == "room" && ground::verdict(&lex.singular(part)) == Verdict::Object {
                return None;
            }
            return Some((m + 1, key, written.join(" ")));
        }
    }
    None
}

/// A single word WordNet knows as a room, building or place of business, and rarely as a
/// thing ("scullery", "bakehouse"): the nearest registry type along its hypernyms, else a
/// generic room.
fn wordnet_room(
    lex: &Lexicon,
    tokens: &[Token],
    j: usize,
    end: usize,
) -> Option<(usize, String, String)> {
    if j >= end {
        return None;
    }
    let w = word(tokens, j)?;
    if lex.is_function_word(w) || lex.is_non_object(w) || lex.landmark(w).is_some() {
        return None;
    }
    // A two-word room WordNet knows ("operating theatre", "living quarters").
    if j + 1 < end
        && let Some(w2) = word(tokens, j + 1)
        && let Some(r) = wordnet_room_words(&format!("{w} {}", lex.singular(w2)))
    {
        return Some((2, r.0, r.1));
    }
    let noun_at = |k: usize| {
        k < end
            && word(tokens, k).is_some_and(|x| {
                ground::is_noun(x) && lex.verb(x).is_none() && !lex.is_function_word(x)
            })
    };
    // "this photographer's darkroom": a noun before a room WordNet knows names that room.
    if noun_at(j)
        && let Some(w2) = word(tokens, j + 1).filter(|_| j + 1 < end)
        && !noun_at(j + 2)
        && let Some((key, lemma)) = wordnet_room_words(&lex.singular(w2))
    {
        return Some((2, key, format!("{w} {lemma}")));
    }
    // "a farmhouse table": a noun after it is the head.
    if noun_at(j + 1) {
        return None;
    }
    wordnet_room_words(w).map(|(key, lemma)| (1, key, lemma))
}

/// "this small rural fire station": the word before the lexicon noun at `at` (`n` words) makes
/// it a WordNet building; it holds the rooms, it is not in one.
fn names_building(lex: &Lexicon, tokens: &[Token], at: usize, n: usize) -> bool {
    let (Some(prev), Some(last)) = (
        at.checked_sub(1).and_then(|p| word(tokens, p)),
        word(tokens, at + n - 1),
    ) else {
        return false;
    };
    let compound = format!("{prev} {}", lex.singular(last));
    ground::noun_lemma(&compound).is_some() && ground::is_building(&compound)
}

/// A verb that links its subject to a description ("is", "seems", "feels").
fn is_linking_verb(w: &str) -> bool {
    matches!(
        w,
        "is" | "are"
            | "was"
            | "were"
            | "be"
            | "seems"
            | "seem"
            | "looks"
            | "feels"
            | "remains"
            | "becomes"
            | "stays"
    )
}

/// (type, lemma) of words WordNet knows as a room and rarely as a thing.
fn wordnet_room_words(w: &str) -> Option<(String, String)> {
    let info = ground::noun_info(w)?;
    let r = ground::rules();
    if !info.roomlike || info.share >= r.min_share || info.room_share < r.min_room_share {
        return None;
    }
    let reg = crate::knowledge::knowledge();
    let family = ground::room_family(w, &|n: &str| reg.room_type_of(n).is_some());
    let key = family
        .and_then(|f| reg.room_type_of(&f.noun).map(str::to_string))
        .unwrap_or_else(|| "room".to_string());
    Some((key, info.lemma))
}

/// The object's name as the prompt gives it: the noun with the modifiers before it, up to
/// the first adverb ("potted plant", "walnut desk", "grand piano"). `from` is where the
/// modifiers start, `at` where the noun starts.
fn name_of(lex: &Lexicon, tokens: &[Token], from: usize, at: usize, noun: &str) -> String {
    let wn = crate::words::wordnet::wordnet();
    let mut name = noun.to_string();
    let mut k = at;
    while k > from {
        let Some(w) = word(tokens, k - 1) else { break };
        let longer = format!("{w} {name}");
        let known_compound = ground::noun_lemma(&longer).is_some_and(|l| l == longer)
            || lex.entry_index(&longer).is_some();
        // Every modifier of the noun stays in its name ("potted plant", "conical flask",
        // "terracotta pot", "mini fridge"), except an adverb: a name read this way still ends
        // with the noun, so it meets a label of the noun alone.
        let describing = !(w.ends_with("ly") && wn.has_pos(w, crate::words::wordnet::Pos::Adv));
        if !(known_compound || describing) {
            break;
        }
        name = longer;
        k -= 1;
    }
    name
}

/// The words with their last one singular ("six stalls": "stall").
pub(crate) fn singular_last(lex: &Lexicon, words: &str) -> String {
    match words.rsplit_once(' ') {
        Some((pre, last)) => format!("{pre} {}", lex.singular(last)),
        None => lex.singular(words),
    }
}
