//! Attributes of an object mention: colours, materials, styles and themes, size words, other
//! adjectives, features ("with brass fittings"), and the modifier words as written, which
//! become the asset description ("Star Wars themed desk lamp").
//!
//! This module recognises one modifier at a time; the chunker decides where a noun phrase
//! starts and ends.

use serde::{Deserialize, Serialize};

use crate::knowledge::Knowledge;
use crate::words::lexicon::Lexicon;
use crate::words::tokens::Token;

/// What the prompt says about an object besides its noun and count.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct Attributes {
    /// Colour names ("red", "navy-blue").
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub colors: Vec<String>,
    /// Material-table names ("wood", "brass", "marble").
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub materials: Vec<String>,
    /// Styles and themes as written ("Art Deco", "Star Wars", "steampunk").
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub styles: Vec<String>,
    /// Size class ("small", "large", "long", "tall").
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub size: Option<String>,
    /// Other known adjectives ("open", "antique", "refrigerated").
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub adjectives: Vec<String>,
    /// Features given after "with" ("with brass fittings and exposed gears").
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub features: Vec<String>,
    /// Shelf levels or tiers ("three-level shelf").
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub levels: Option<u32>,
    /// Modifier words before the noun, as written and in order.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub modifiers: Vec<String>,
}

impl Attributes {
    /// True when nothing is known beyond the noun.
    pub fn is_empty(&self) -> bool {
        self.modifiers.is_empty() && self.features.is_empty() && self.styles.is_empty()
    }

    /// Free-text description: modifiers, noun, features ("red ceramic mug",
    /// "Art Deco style sofa with geometric patterns").
    pub fn describe(&self, noun: &str) -> String {
        let mut parts: Vec<&str> = self.modifiers.iter().map(String::as_str).collect();
        parts.push(noun);
        let mut s = parts.join(" ");
        for f in &self.features {
            s.push_str(" with ");
            s.push_str(f);
        }
        s
    }

    /// Adds what `other` says and `self` does not.
    pub fn merge(&mut self, other: &Attributes) {
        fn add(v: &mut Vec<String>, from: &[String]) {
            for x in from {
                if !v.contains(x) {
                    v.push(x.clone());
                }
            }
        }
        add(&mut self.colors, &other.colors);
        add(&mut self.materials, &other.materials);
        add(&mut self.styles, &other.styles);
        add(&mut self.adjectives, &other.adjectives);
        add(&mut self.features, &other.features);
        add(&mut self.modifiers, &other.modifiers);
        if self.size.is_none() {
            self.size.clone_from(&other.size);
        }
        if self.levels.is_none() {
            self.levels = other.levels;
        }
    }

    /// Records one recognised modifier.
    pub(crate) fn add(&mut self, m: &Modifier) {
        match &m.kind {
            ModKind::Style(s) => push_unique(&mut self.styles, s),
            ModKind::Color { color, material } => {
                push_unique(&mut self.colors, color);
                if let Some(mat) = material {
                    push_unique(&mut self.materials, mat);
                }
            }
            ModKind::Material(mat) => push_unique(&mut self.materials, mat),
            ModKind::Size(s) => self.size = Some(s.clone()),
            ModKind::Levels(n) => self.levels = Some(*n),
            ModKind::Adjective(a) => push_unique(&mut self.adjectives, a),
        }
        push_unique(&mut self.modifiers, &m.text);
    }
}

fn push_unique(v: &mut Vec<String>, s: &str) {
    if !v.iter().any(|x| x == s) {
        v.push(s.to_string());
    }
}

/// What kind of modifier a word (or run of words) is.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum ModKind {
    /// Style or theme (display form).
    Style(String),
    /// Colour, possibly also a material ("brass", "golden").
    Color {
        /// Colour name.
        color: String,
        /// Material-table name, when the word is also a material.
        material: Option<String>,
    },
    /// Material-table name.
    Material(String),
    /// Size class.
    Size(String),
    /// "three-level": shelf levels.
    Levels(u32),
    /// Any other adjective.
    Adjective(String),
}

/// One recognised modifier.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Modifier {
    /// Tokens used.
    pub len: usize,
    /// Kind.
    pub kind: ModKind,
    /// Text as written.
    pub text: String,
}

fn raw_join(tokens: &[Token]) -> String {
    tokens
        .iter()
        .map(|t| t.raw.as_str())
        .collect::<Vec<_>>()
        .join(" ")
}

/// A style phrase ending in a style suffix: "Star Wars themed", "Art Deco style",
/// "Minecraft themed". Not when the suffix starts a verb phrase ("inspired by ...").
fn suffixed_style(lex: &Lexicon, tokens: &[Token], at: usize) -> Option<Modifier> {
    for n in (1..=4).rev() {
        let run = tokens.get(at..at + n)?;
        let Some(suffix) = tokens.get(at + n) else {
            continue;
        };
        if !suffix.is_word() || !lex.is_style_suffix(&suffix.text) {
            continue;
        }
        if run
            .iter()
            .any(|t| !t.is_word() || lex.is_function_word(&t.text))
        {
            continue;
        }
        // "this shop feels like ...": a verb before "like" makes no style.
        let verb_before = run.last().is_some_and(|t| {
            !t.capitalized()
                && (lex.verb(&t.text).is_some()
                    || (t.text.ends_with('s')
                        && !crate::words::wordnet::wordnet()
                            .base_forms(&t.text, crate::words::wordnet::Pos::Verb)
                            .is_empty()))
        });
        if verb_before {
            continue;
        }
        // "large Pop Art style": the size word is not part of the style.
        let first = &run[0];
        if n > 1
            && !first.capitalized()
            && lex.style_at(tokens, at).is_none()
            && (lex.size_adjective(&first.text).is_some()
                || lex.is_adjective(&first.text)
                || lex.color_at(tokens, at).is_some()
                || lex.material(&first.text).is_some())
        {
            continue;
        }
        let next = tokens.get(at + n + 1).map(|t| t.text.as_str());
        if matches!(
            next,
            Some("by" | "like" | "after" | "as" | "on" | "in" | "with" | "to")
        ) {
            continue;
        }
        let style = raw_join(run);
        return Some(Modifier {
            len: n + 1,
            kind: ModKind::Style(style),
            text: raw_join(&tokens[at..at + n + 1]),
        });
    }
    None
}

/// "a truing stand": an -ing form of a WordNet verb that WordNet has no noun for, right after a
/// determiner and before a singular noun WordNet reads as a placeable thing, is a modifier
/// whatever the verb table lists.
fn rare_gerund_before_thing(lex: &Lexicon, tokens: &[Token], at: usize) -> bool {
    let wn = crate::words::wordnet::wordnet();
    let (Some(w), Some(next)) = (tokens.get(at), tokens.get(at + 1)) else {
        return false;
    };
    next.is_word()
        && !wn
            .base_forms(&w.text, crate::words::wordnet::Pos::Verb)
            .is_empty()
        && crate::words::ground::noun_info(&w.text).is_none()
        && at > 0
        && lex.determiner(&tokens[at - 1].text).is_some()
        && !lex.is_plural(&next.text)
        && lex.determiner(&next.text).is_none()
        && crate::words::ground::verdict(&next.text) == crate::words::ground::Verdict::Object
}

/// Recognises the modifier starting at `tokens[at]`, or None when the word is not one (a noun,
/// a room word, a function word, punctuation). `sentence_start` is the first token of the
/// sentence (a capital there says nothing).
pub(crate) fn modifier_at(
    lex: &Lexicon,
    kb: &Knowledge,
    tokens: &[Token],
    at: usize,
    sentence_start: usize,
) -> Option<Modifier> {
    let t = tokens.get(at)?;
    if !t.is_word() {
        return None;
    }
    if let Some(m) = suffixed_style(lex, tokens, at) {
        return Some(m);
    }
    let w = t.text.as_str();
    if let Some((head, suffix)) = w.rsplit_once('-')
        && lex.is_style_suffix(suffix)
        && !head.is_empty()
    {
        let raw_head = t.raw.rsplit_once('-').map_or(head, |(h, _)| h);
        return Some(Modifier {
            len: 1,
            kind: ModKind::Style(raw_head.to_string()),
            text: t.raw.clone(),
        });
    }
    if let Some((n, _)) = lex.style_at(tokens, at) {
        // A style word that is also the start of a longer noun ("robot arm") is the noun.
        let noun_len = lex.noun_at(tokens, at).map_or(0, |(l, ..)| l);
        if noun_len <= n {
            // "Jurassic Park": a capitalised style word begins a proper name.
            let mut n = n;
            while tokens[at].capitalized()
                && tokens.get(at + n).is_some_and(|u| {
                    u.is_word()
                        && u.capitalized()
                        && !lex.is_function_word(&u.text)
                        && lex.noun_at(tokens, at + n).is_none()
                })
            {
                n += 1;
            }
            let mut len = n;
            if tokens
                .get(at + n)
                .is_some_and(|s| lex.is_style_suffix(&s.text))
            {
                len += 1;
            }
            return Some(Modifier {
                len,
                kind: ModKind::Style(raw_join(&tokens[at..at + n])),
                text: raw_join(&tokens[at..at + len]),
            });
        }
    }
    if lex.noun_at(tokens, at).is_some() || kb.room_type_at(tokens, at).is_some() {
        return None;
    }
    // "six long reading tables", "a waiting chair": a gerund the verb table lists, after a
    // determiner, a number or a modifier and before a noun, modifies the noun.
    let after_det = at > 0
        && tokens.get(at - 1).is_some_and(|p| {
            lex.determiner(&p.text).is_some()
                || lex.number(p).is_some()
                || (p.is_word() && !lex.is_function_word(&p.text))
        });
    if after_det
        && w.ends_with("ing")
        && (lex.verb(w).is_some() && lex.noun_at(tokens, at + 1).is_some()
            || rare_gerund_before_thing(lex, tokens, at))
    {
        return Some(single(t, ModKind::Adjective(w.to_string())));
    }
    // "a mounted vise", "two stacked crates", "the sleeping loft", "two full bathrooms": a
    // participle or adjective the verb table lists, right after a determiner or a number and
    // before a noun, modifies it. So does an -ed participle after an adjective that follows a
    // determiner ("an enormous illuminated psalter").
    let wn = crate::words::wordnet::wordnet();
    let after_adjective = |k: usize| {
        k > 0
            && tokens.get(k).is_some_and(|p| {
                p.is_word()
                    && crate::words::ground::is_adjective(&p.text)
                    && lex.noun_at(tokens, k).is_none()
                    && lex.verb(&p.text).is_none()
            })
            && tokens
                .get(k - 1)
                .is_some_and(|d| lex.determiner(&d.text).is_some() || lex.number(d).is_some())
    };
    if (w.ends_with("ed") || w.ends_with("ing") || crate::words::ground::is_adjective(w))
        && lex.verb(w).is_some()
        && at > 0
        && tokens.get(at - 1).is_some_and(|p| {
            lex.determiner(&p.text).is_some()
                || lex.number(p).is_some()
                || (w.ends_with("ed") && after_adjective(at - 1))
        })
        && tokens.get(at + 1).is_some_and(|u| {
            u.is_word()
                && !lex.is_function_word(&u.text)
                && (lex.noun_at(tokens, at + 1).is_some()
                    || wn.has_pos(&u.text, crate::words::wordnet::Pos::Noun))
        })
    {
        return Some(single(t, ModKind::Adjective(w.to_string())));
    }
    if lex.is_function_word(w) || lex.landmark(w).is_some() {
        return None;
    }
    if let Some((n, color, _)) = lex.color_at(tokens, at) {
        let material = (n == 1)
            .then(|| lex.material(w))
            .flatten()
            .map(str::to_string);
        return Some(Modifier {
            len: n,
            kind: ModKind::Color { color, material },
            text: raw_join(&tokens[at..at + n]),
        });
    }
    if let Some(mat) = lex.material(w) {
        return Some(single(t, ModKind::Material(mat.to_string())));
    }
    if let Some(size) = lex.size_adjective(w) {
        return Some(single(t, ModKind::Size(size.to_string())));
    }
    if let Some((num, unit)) = w.split_once('-') {
        let n = lex.number(&Token {
            text: num.to_string(),
            raw: num.to_string(),
            start: 0,
            end: 0,
            kind: if num.chars().all(|c| c.is_ascii_digit()) {
                num.parse().map_or(
                    crate::words::tokens::TokenKind::Word,
                    crate::words::tokens::TokenKind::Number,
                )
            } else {
                crate::words::tokens::TokenKind::Word
            },
            possessive: false,
        });
        if let Some(n) = n {
            let kind = if matches!(
                unit,
                "level" | "tier" | "shelf" | "shelved" | "story" | "storey" | "layer"
            ) {
                ModKind::Levels(n)
            } else {
                ModKind::Adjective(w.to_string())
            };
            return Some(single(t, kind));
        }
    }
    if lex.is_adjective(w) || lex.density(w).is_some() || lex.density_room_only(w).is_some() {
        return Some(single(t, ModKind::Adjective(w.to_string())));
    }
    let next_wordish = tokens
        .get(at + 1)
        .is_some_and(|u| u.is_word() && !lex.is_function_word(&u.text));
    // Participles ("scattered", "folded", "hanging"), unless the word is a noun WordNet
    // knows as written ("flowerbed", "seaweed", "building").
    // A gerund that is a noun too modifies a noun after it: "six reading tables".
    let noun_lemma = wn.is_lemma(w, crate::words::wordnet::Pos::Noun)
        && !tokens.get(at + 1).is_some_and(|u| {
            w.ends_with("ing")
                && (lex.noun_at(tokens, at + 1).is_some()
                    || wn.has_pos(&u.text, crate::words::wordnet::Pos::Noun))
        });
    // "wall-mounted", "king-size"; not "fridge-freezer", two nouns of the lexicon.
    let hyphen_noun = w.contains('-') && lex.noun_at_most(tokens, at, 1).is_some();
    if (w.contains('-') && !hyphen_noun)
        || (w.len() > 4 && w.ends_with("ed") && !noun_lemma)
        || (w.len() > 5 && w.ends_with("ing") && next_wordish && !noun_lemma)
    {
        return Some(single(t, ModKind::Adjective(w.to_string())));
    }
    // A proper name inside a sentence ("a Jurassic Park poster"): a theme.
    if t.capitalized() && at > sentence_start && !lex.is_non_object(w) {
        let mut n = 1;
        while tokens.get(at + n).is_some_and(|u| {
            u.is_word()
                && u.capitalized()
                && !lex.is_function_word(&u.text)
                && lex.noun_at(tokens, at + n).is_none()
        }) {
            n += 1;
        }
        // "a Bible lies on the table": a name followed by its verb is the thing itself.
        let followed = tokens.get(at + n).is_some_and(|u| {
            u.is_word()
                && !lex.is_function_word(&u.text)
                && (lex.verb(&u.text).is_none()
                    || lex.noun_at(tokens, at + n).is_some()
                    || kb.room_type_at(tokens, at + n).is_some())
        });
        if followed {
            return Some(Modifier {
                len: n,
                kind: ModKind::Style(raw_join(&tokens[at..at + n])),
                text: raw_join(&tokens[at..at + n]),
            });
        }
    }
    // WordNet's adjectives: "stylish", "somber"; one that is also a noun ("antique",
    // "quiet") modifies when a noun follows.
    if wn.has_pos(w, crate::words::wordnet::Pos::Adj) && !lex.is_non_object(w) {
        let noun_too = wn.has_pos(w, crate::words::wordnet::Pos::Noun);
        let noun_next = next_wordish
            && tokens.get(at + 1).is_some_and(|u| {
                wn.has_pos(&u.text, crate::words::wordnet::Pos::Noun)
                    || lex.noun_at(tokens, at + 1).is_some()
                    || kb.room_type_at(tokens, at + 1).is_some()
            });
        if !noun_too || noun_next {
            return Some(single(t, ModKind::Adjective(w.to_string())));
        }
    }
    None
}

fn single(t: &Token, kind: ModKind) -> Modifier {
    Modifier {
        len: 1,
        kind,
        text: t.raw.clone(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::knowledge::knowledge;
    use crate::words::lexicon::lexicon;
    use crate::words::tokens::lex;

    fn mods(text: &str, at: usize) -> Vec<ModKind> {
        let t = lex(text);
        let mut out = Vec::new();
        let mut i = at;
        while let Some(m) = modifier_at(lexicon(), knowledge(), &t, i, 0) {
            i += m.len;
            out.push(m.kind);
        }
        out
    }

    #[test]
    fn styles_colours_materials_sizes() {
        assert_eq!(
            mods("a Star Wars themed desk lamp", 1),
            [ModKind::Style("Star Wars".into())]
        );
        assert_eq!(
            mods("an Art Deco style floor lamp", 1),
            [ModKind::Style("Art Deco".into())]
        );
        assert_eq!(
            mods("a Picasso-style cubist painting", 1)[0],
            ModKind::Style("Picasso".into())
        );
        assert_eq!(
            mods("a large red wooden bowl", 1),
            [
                ModKind::Size("large".into()),
                ModKind::Color {
                    color: "red".into(),
                    material: None
                },
                ModKind::Material("wood".into())
            ]
        );
        assert_eq!(mods("a single three-level shelf", 2), [ModKind::Levels(3)]);
        assert_eq!(
            mods("a Jurassic Park poster", 1),
            [ModKind::Style("Jurassic Park".into())]
        );
        assert_eq!(
            mods("a steampunk desk", 1),
            [ModKind::Style("steampunk".into())]
        );
        // "Frozen" counts as a theme only with a capital.
        assert_eq!(
            mods("a Frozen poster", 1),
            [ModKind::Style("Frozen".into())]
        );
        assert!(
            mods("a frozen pizza", 1)
                .iter()
                .all(|m| !matches!(m, ModKind::Style(_)))
        );
    }

    #[test]
    fn describe_keeps_words_in_order() {
        let mut a = Attributes::default();
        let t = lex("a red ceramic mug");
        let mut i = 1;
        while let Some(m) = modifier_at(lexicon(), knowledge(), &t, i, 0) {
            a.add(&m);
            i += m.len;
        }
        assert_eq!(a.describe("mug"), "red ceramic mug");
        assert_eq!(a.materials, ["ceramic"]);
    }
}
