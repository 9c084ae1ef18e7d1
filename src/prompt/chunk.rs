//! Shallow parsing: one sentence's tokens become a list of chunks — noun phrases (with
//! determiner, quantifier, number, ordinal, group word, modifiers and head), prepositions,
//! verbs, "with", "each", separators. The interpreter turns chunks into mentions.
//!
//! Which words start a phrase is decided here; the phrase itself is read by `phrase`.

use std::ops::Range;

pub(crate) use super::phrase::{Head, Np, Pronoun};
use super::phrase::{apposed_count, parse_np, pronoun_np, quantifier_fits, word};
use crate::knowledge::Knowledge;
use crate::words::ground;
use crate::words::lexicon::Lexicon;
use crate::words::tokens::{Token, TokenKind};

/// One chunk of a sentence.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum Item {
    /// A noun phrase.
    Np(Box<Np>),
    /// A preposition (lexicon class).
    Prep(String),
    /// A verb (lexicon class) and the word.
    Verb(String, String),
    /// "with"
    With,
    /// "without", "nor"
    Without,
    /// "each" standing alone (", each with", "two stools each")
    Each,
    /// ","
    Comma,
    /// "and", "or", "as well as"
    And,
    /// "which", "that", "where"
    Relative,
    /// "in total"
    InTotal,
    /// "set for" (place settings)
    SetFor,
    /// "for" (purpose)
    For,
    /// "including", "such as"
    Including,
    /// "of" after a noun ("a vase of flowers")
    Of,
    /// Anything else.
    Other(String),
}

/// A chunk with its token range.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Chunk {
    /// The chunk.
    pub item: Item,
    /// Tokens it covers.
    pub range: Range<usize>,
}

/// Chunks the tokens of one sentence.
pub(crate) fn chunk_sentence(
    lex: &Lexicon,
    kb: &Knowledge,
    tokens: &[Token],
    range: Range<usize>,
) -> Vec<Chunk> {
    let mut out: Vec<Chunk> = Vec::new();
    let sentence_start = range.start;
    let end = range.end;
    let mut i = range.start;
    while i < end {
        let t = &tokens[i];
        let push = |out: &mut Vec<Chunk>, item: Item, n: usize| {
            out.push(Chunk {
                item,
                range: i..i + n,
            })
        };
        match t.kind {
            TokenKind::Punct(',' | ':') => {
                push(&mut out, Item::Comma, 1);
                i += 1;
                continue;
            }
            TokenKind::Punct('&' | '/') => {
                push(&mut out, Item::And, 1);
                i += 1;
                continue;
            }
            TokenKind::Punct('\u{2014}') => {
                i = apposed_count_after(lex, kb, tokens, i, end, &mut out);
                continue;
            }
            TokenKind::Punct(_) => {
                i += 1;
                continue;
            }
            _ => {}
        }
        let w = t.text.as_str();
        let next = word(tokens, i + 1);
        let in_list = (matches!(out.last().map(|c| &c.item), Some(Item::Comma | Item::And))
            && out
                .iter()
                .rev()
                .skip(1)
                .find(|c| !matches!(c.item, Item::Comma | Item::And))
                .is_some_and(|c| matches!(c.item, Item::Np(_))))
            // After "with", "of", "including", a preposition or "has": an object slot.
            || matches!(
                out.last().map(|c| &c.item),
                Some(Item::With | Item::Including | Item::Prep(_))
            )
            // "a vase of flowers" lists contents; "a love of greenery", "the place smells of
            // woodsmoke" and "reminiscent of a ship" do not.
            || (matches!(out.last().map(|c| &c.item), Some(Item::Of))
                && !matches!(
                    out.iter().rev().nth(1).map(|c| &c.item),
                    Some(Item::Np(np)) if matches!(np.head, Head::NonObject)
                )
                && !matches!(
                    out.iter().rev().nth(1).map(|c| &c.item),
                    Some(Item::Verb(class, _)) if class == "other"
                )
                && !matches!(
                    out.iter().rev().nth(1).map(|c| &c.item),
                    Some(Item::Other(w)) if ground::is_adjective(w) || lex.verb(w).is_some()
                ))
            || matches!(out.last().map(|c| &c.item), Some(Item::Verb(class, _)) if matches!(class.as_str(), "possess" | "display" | "fill_with"));
        // Fixed phrases first.
        // "as if its owner spends every night chasing comets", "though the owner wishes there
        // were": a clause about what is imagined or wished names nothing in the room; it runs
        // to the next comma or semicolon.
        let imagined = (w == "as" && matches!(next, Some("if" | "though")))
            || (matches!(
                w,
                "wishes" | "wish" | "wished" | "imagine" | "imagines" | "dreams"
            ) && matches!(next, Some("there" | "that" | "for" | "of" | "it" | "they")));
        // "The owners have decided against televisions": what the verb rejects is not there.
        if let Some(n) = lex.negating_verb_at(tokens, i) {
            push(&mut out, Item::Without, n);
            i += n;
            continue;
        }
        if imagined {
            let mut k = i + 1;
            while k < end && !matches!(tokens[k].kind, TokenKind::Punct(',' | ';' | ':')) {
                k += 1;
            }
            push(&mut out, Item::Other(w.to_string()), k - i);
            i = k;
            continue;
        }
        if w == "in" && next == Some("total") {
            push(&mut out, Item::InTotal, 2);
            i += 2;
            continue;
        }
        if w == "set" && next == Some("for") {
            push(&mut out, Item::SetFor, 2);
            i += 2;
            continue;
        }
        if (w == "each" && next == Some("other")) || (w == "one" && next == Some("another")) {
            let np = pronoun_np(Pronoun::EachOther);
            push(&mut out, Item::Np(Box::new(np)), 2);
            i += 2;
            continue;
        }
        if matches!((w, next), ("as", Some("well"))) && word(tokens, i + 2) == Some("as") {
            push(&mut out, Item::And, 3);
            i += 3;
            continue;
        }
        if matches!((w, next), ("along" | "together", Some("with"))) {
            push(&mut out, Item::And, 2);
            i += 2;
            continue;
        }
        if w == "such" && next == Some("as") {
            push(&mut out, Item::Including, 2);
            i += 2;
            continue;
        }
        match w {
            "with" => {
                push(&mut out, Item::With, 1);
                i += 1;
                continue;
            }
            "without" | "nor" | "lacking" | "excluding" => {
                push(&mut out, Item::Without, 1);
                i += 1;
                continue;
            }
            // "nothing on the walls except a clock": after a negation, "except" and "but"
            // end it.
            "except" | "but" if out.iter().any(|c| c.item == Item::Without) => {
                push(&mut out, Item::Other("except".to_string()), 1);
                i += 1;
                continue;
            }
            // "You will not find a cash register here": "not" before a verb in its base form
            // negates the clause.
            "not"
                if next.is_some_and(|n| {
                    crate::words::wordnet::wordnet().is_lemma(n, crate::words::wordnet::Pos::Verb)
                        && lex.determiner(n).is_none()
                }) =>
            {
                push(&mut out, Item::Without, 1);
                i += 1;
                continue;
            }
            // "there is no longer a car in here".
            "no" if tokens.get(i + 1).is_some_and(|t| t.text == "longer") => {
                push(&mut out, Item::Without, 2);
                i += 2;
                continue;
            }
            "including" => {
                push(&mut out, Item::Including, 1);
                i += 1;
                continue;
            }
            "for" => {
                push(&mut out, Item::For, 1);
                i += 1;
                continue;
            }
            "of" => {
                push(&mut out, Item::Of, 1);
                i += 1;
                continue;
            }
            "it" | "them" | "they" => {
                let p = if w == "it" {
                    Pronoun::It
                } else {
                    Pronoun::Them
                };
                push(&mut out, Item::Np(Box::new(pronoun_np(p))), 1);
                i += 1;
                continue;
            }
            _ => {}
        }
        if w == "each" {
            // "each table" is a phrase; ", each with" and "two stools each" are not.
            if let Some((np, j)) = parse_np(lex, kb, tokens, i, end, sentence_start, in_list)
                && !matches!(np.head, Head::NonObject)
            {
                out.push(Chunk {
                    item: Item::Np(Box::new(np)),
                    range: i..j,
                });
                i = j;
                continue;
            }
            push(&mut out, Item::Each, 1);
            i += 1;
            continue;
        }
        // A multi-word noun beats a verb or preposition reading of its first word
        // ("display case", "set").
        let noun_len = lex.noun_at(tokens, i).map_or(0, |(n, ..)| n);
        let room_len = kb.room_type_at(tokens, i).map_or(0, |(n, _)| n);
        let starts_np = noun_len >= 2
            || room_len >= 2
            || lex.determiner(w).is_some()
            || lex.number(t).is_some()
            || (lex.quantifier_at(tokens, i).is_some() && quantifier_fits(lex, tokens, i))
            || matches!(w, "no" | "not");
        if !starts_np {
            // "This trattoria seats a handful of guests", "a table that seats eight": after a
            // singular phrase (or its "that"), a word in -s that WordNet knows as a verb and
            // that a determiner or number follows is the verb, not a plural noun.
            if let Some(class) = verb_after_singular(lex, tokens, i, &out) {
                push(&mut out, Item::Verb(class.to_string(), w.to_string()), 1);
                i += 1;
                continue;
            }
            if let Some((n, class)) = lex.preposition_at(tokens, i) {
                push(&mut out, Item::Prep(class.to_string()), n);
                i += n;
                continue;
            }
            if let Some(class) = lex.verb(w)
                && !(noun_len == 1
                    && !matches!(out.last().map(|c| &c.item), Some(Item::Np(_)))
                    && class != "locate")
            {
                push(&mut out, Item::Verb(class.to_string(), w.to_string()), 1);
                i += 1;
                continue;
            }
            if lex.is_relative(w) {
                push(&mut out, Item::Relative, 1);
                i += 1;
                continue;
            }
            if lex.is_conjunction(w) {
                push(&mut out, Item::And, 1);
                i += 1;
                continue;
            }
        }
        match parse_np(lex, kb, tokens, i, end, sentence_start, in_list) {
            Some((mut np, j)) if j > i => {
                if sensed_mass(&out, &np) || predicate_adjective(tokens, j, &out, &np) {
                    np.head = Head::NonObject;
                }
                out.push(Chunk {
                    item: Item::Np(Box::new(np)),
                    range: i..j,
                });
                i = j;
            }
            _ => {
                if let Some(class) = lex.verb(w) {
                    push(&mut out, Item::Verb(class.to_string(), w.to_string()), 1);
                } else if let Some(class) = wordnet_verb(lex, tokens, i, &out) {
                    push(&mut out, Item::Verb(class.to_string(), w.to_string()), 1);
                } else if lex.is_negation(w) {
                    push(&mut out, Item::Without, 1);
                } else {
                    push(&mut out, Item::Other(w.to_string()), 1);
                }
                i += 1;
            }
        }
    }
    measures_of_variety(tokens, &mut out);
    out
}

/// "the smell of food", "a hint of lavender": a bare singular after "of" that follows a noun
/// naming no thing is what is sensed or meant, not a thing in the room ("the sound of a clock"
/// still places a clock).
fn sensed_mass(out: &[Chunk], np: &Np) -> bool {
    let [.., before, of] = out else {
        return false;
    };
    matches!(of.item, Item::Of)
        && matches!(&before.item, Item::Np(b) if matches!(b.head, Head::NonObject))
        && !np.has_det()
        && np.group.is_none()
        && !np.plural
        && matches!(np.head, Head::Object { .. })
}

/// "A coal forge glows orange", "the shutters are painted cream": a lone bare word right after
/// a verb that takes no object as its thing, which WordNet also reads as an adjective and no
/// list continues, is how the subject looks, not a thing ("the shelf holds cream" still has
/// cream: a verb of having takes things).
fn predicate_adjective(tokens: &[Token], end: usize, out: &[Chunk], np: &Np) -> bool {
    let Some(Chunk {
        item: Item::Verb(class, _),
        ..
    }) = out.last()
    else {
        return false;
    };
    let Head::Object { noun, .. } = &np.head else {
        return false;
    };
    let listed = matches!(word(tokens, end), Some("and" | "or"))
        || matches!(
            tokens.get(end).map(|t| &t.kind),
            Some(TokenKind::Punct(','))
        );
    !matches!(class.as_str(), "possess" | "display" | "fill_with")
        && !np.has_det()
        && !np.plural
        && !noun.contains(' ')
        && np.attrs.modifiers.is_empty()
        && ground::is_adjective(noun)
        && !listed
}

/// Words that say the things before "of" differ in what follows ("hammers of different
/// weights", "jars of various sizes").
const VARIETY: [&str; 6] = [
    "different",
    "various",
    "varying",
    "differing",
    "assorted",
    "mixed",
];

/// "of different weights": after "of" and a word of [`VARIETY`], a noun outside the object
/// lexicon whose senses are mostly no thing (a weight, a shade) says how the things before
/// differ; it is no thing of its own. "jars of different spices" still names spices.
fn measures_of_variety(tokens: &[Token], out: &mut [Chunk]) {
    for k in 1..out.len() {
        if out[k - 1].item != Item::Of {
            continue;
        }
        let first = word(tokens, out[k].range.start);
        let Item::Np(np) = &mut out[k].item else {
            continue;
        };
        let Head::Object {
            noun, entry: None, ..
        } = &np.head
        else {
            continue;
        };
        let head = noun.rsplit(' ').next().unwrap_or(noun);
        let measure = crate::words::ground::noun_info(head).is_some_and(|i| i.share < 0.5);
        if first.is_some_and(|w| VARIETY.contains(&w)) && measure {
            np.head = Head::NonObject;
        }
    }
}

/// A dash at `i`: when a count alone follows up to a second dash and the phrase before the
/// first dash is a thing named in the plural without a count, the count is that phrase's
/// ("Stuffed animals — at least a dozen — tumble out"). Returns where chunking goes on.
fn apposed_count_after(
    lex: &Lexicon,
    kb: &Knowledge,
    tokens: &[Token],
    i: usize,
    end: usize,
    out: &mut [Chunk],
) -> usize {
    let close = (i + 1..end.min(i + 8)).find(|&k| tokens[k].is_punct('\u{2014}'));
    let Some(close) = close else {
        return i + 1;
    };
    let Some(Chunk {
        item: Item::Np(np), ..
    }) = out.last_mut()
    else {
        return i + 1;
    };
    let bare_plural = np.plural
        && np.number.is_none()
        && np.quant.is_none()
        && np.group.is_none()
        && matches!(np.head, Head::Object { .. });
    match apposed_count(lex, kb, tokens, i + 1, close) {
        Some((number, quant)) if bare_plural => {
            np.number = number;
            np.quant = quant;
            close + 1
        }
        _ => i + 1,
    }
}

/// The class of a verb at `i` with a determiner, number or quantifier after it: one in -s
/// right after a singular noun phrase or its relative pronoun, or one in its base form right
/// after a plural object phrase (see `chunk_sentence`).
fn verb_after_singular(
    lex: &Lexicon,
    tokens: &[Token],
    i: usize,
    out: &[Chunk],
) -> Option<&'static str> {
    let w = tokens.get(i)?.text.as_str();
    // A verb of the lexicon's table keeps its own class ("covers", "holds").
    if lex.verb(w).is_some() {
        return None;
    }
    let np = match out {
        [
            ..,
            Chunk {
                item: Item::Np(np), ..
            },
        ]
        | [
            ..,
            Chunk {
                item: Item::Np(np), ..
            },
            Chunk {
                item: Item::Relative,
                ..
            },
        ] => np,
        _ => return None,
    };
    let singular = !np.plural
        && np.number.is_none_or(|n| n == 1)
        && matches!(np.head, Head::Object { .. } | Head::Room { .. });
    let next = tokens.get(i + 1)?;
    let np_next = word(tokens, i + 1).is_some_and(|n| lex.determiner(n).is_some())
        || lex.number(next).is_some()
        || lex.quantifier_at(tokens, i + 1).is_some();
    let wn = crate::words::wordnet::wordnet();
    let verb = w.ends_with('s')
        && lex.is_plural(w)
        && !wn
            .base_forms(w, crate::words::wordnet::Pos::Verb)
            .is_empty();
    if singular && np_next && verb {
        return Some("possess");
    }
    // "Eight beds line the walls": after a plural phrase, a verb in its base form with a
    // phrase after it; placing when that phrase is a part of the room, else of no class
    // ("bookshelves flank the fireplace").
    let plural =
        (np.plural || np.number.is_some_and(|n| n > 1)) && matches!(np.head, Head::Object { .. });
    let base_verb = !w.ends_with('s')
        && wn.is_lemma(w, crate::words::wordnet::Pos::Verb)
        && lex.preposition_at(tokens, i).is_none()
        && !lex.is_function_word(w);
    // "Two repair stands clamp bicycles": a bare plural noun after it is its object too.
    let bare_plural_next = word(tokens, i + 1).is_some_and(|n| {
        lex.is_plural(n) && crate::words::ground::is_noun(n) && lex.verb(n).is_none()
    });
    if plural && (np_next || bare_plural_next) && base_verb {
        let landmark_next =
            (i + 2..i + 4).any(|k| word(tokens, k).is_some_and(|x| lex.landmark(x).is_some()));
        return Some(if landmark_next { "locate" } else { "other" });
    }
    None
}

/// A verb the lexicon's table does not list, after a noun phrase ("The kitchen boasts a
/// range", "the bunk room sleeps ..."): WordNet knows the word as an inflected verb. Its class
/// is `possess` when a noun phrase follows (what the subject has), else `locate`.
fn wordnet_verb(lex: &Lexicon, tokens: &[Token], i: usize, out: &[Chunk]) -> Option<&'static str> {
    let w = tokens.get(i)?.text.as_str();
    let after_np = matches!(out.last().map(|c| &c.item), Some(Item::Np(_)));
    let inflected = w.ends_with('s') || w.ends_with("ed");
    // "Three plinths each support a sculpture": after "each" of a plural subject the verb
    // is in its base form.
    let after_each = out.len() >= 2
        && matches!(out[out.len() - 1].item, Item::Each)
        && matches!(out[out.len() - 2].item, Item::Np(_));
    if !(after_each || (after_np && inflected)) {
        return None;
    }
    let wn = crate::words::wordnet::wordnet();
    if wn
        .base_forms(w, crate::words::wordnet::Pos::Verb)
        .is_empty()
    {
        return None;
    }
    let next_np = word(tokens, i + 1).is_some_and(|n| {
        lex.determiner(n).is_some()
            || tokens.get(i + 1).is_some_and(|t| lex.number(t).is_some())
            || lex.quantifier_at(tokens, i + 1).is_some()
    });
    Some(if next_np { "possess" } else { "locate" })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::knowledge::knowledge;
    use crate::prompt::mentions::GroupKind;
    use crate::words::lexicon::lexicon;
    use crate::words::tokens::{lex, sentences};

    fn chunks(text: &str) -> Vec<Item> {
        let t = lex(text);
        let s = sentences(&t);
        chunk_sentence(lexicon(), knowledge(), &t, s[0].clone())
            .into_iter()
            .map(|c| c.item)
            .collect()
    }

    fn nps(text: &str) -> Vec<Np> {
        chunks(text)
            .into_iter()
            .filter_map(|i| match i {
                Item::Np(np) => Some(*np),
                _ => None,
            })
            .collect()
    }

    fn canon(np: &Np) -> &str {
        match &np.head {
            Head::Object { canonical, .. } => canonical,
            Head::Room { key, .. } => key,
            _ => "",
        }
    }

    #[test]
    fn commas_scope_numbers() {
        let n = nps("A kitchen with four chairs, plates and mugs.");
        assert_eq!(canon(&n[0]), "kitchen");
        assert_eq!((canon(&n[1]), n[1].number), ("chair", Some(4)));
        assert_eq!(
            (canon(&n[2]), n[2].number, n[2].plural),
            ("plate", None, true)
        );
        assert_eq!((canon(&n[3]), n[3].number), ("mug", None));
    }

    #[test]
    fn groups_pairs_and_quantifiers() {
        let n = nps("exactly 5 pairs of shoes and a stack of 8 books and at least 10 cans");
        assert_eq!(n[0].group, Some(GroupKind::Pair));
        assert_eq!(
            (n[0].number, n[0].quant.as_deref()),
            (Some(5), Some("exactly"))
        );
        assert_eq!(
            (canon(&n[1]), n[1].number, n[1].group),
            ("book", Some(8), Some(GroupKind::Stack))
        );
        assert_eq!(
            (n[2].number, n[2].quant.as_deref()),
            (Some(10), Some("at_least"))
        );
    }

    #[test]
    fn open_vocabulary_and_rooms() {
        let n = nps("a golden velociraptor skeleton near two exam rooms");
        assert_eq!(canon(&n[0]), "velociraptor skeleton");
        assert_eq!(n[0].attrs.colors, ["golden"]);
        assert_eq!((canon(&n[1]), n[1].number), ("exam_room", Some(2)));
    }

    #[test]
    fn verbs_prepositions_and_pronouns() {
        let c = chunks("A dining table with four chairs surrounding it.");
        assert!(c.contains(&Item::With));
        assert!(c.contains(&Item::Prep("around".into())));
        assert!(matches!(c.last(), Some(Item::Np(np)) if np.head == Head::Pronoun(Pronoun::It)));
        let c = chunks("where one displays pet food bags and the other displays pet toys");
        assert!(
            c.iter()
                .any(|i| matches!(i, Item::Np(np) if np.head == Head::Pronoun(Pronoun::One)))
        );
        assert!(
            c.iter()
                .any(|i| matches!(i, Item::Np(np) if np.head == Head::Pronoun(Pronoun::Other)))
        );
    }
}
