//! Properties of the reader over generated prompts: templates filled with nouns drawn from
//! WordNet (things, and abstract nouns as distractors), WordNet adjectives, counts and room
//! lists from the room registry. Whatever the words:
//! - no object is named after an abstract noun or an adjective;
//! - every room a list counts is read with its count, and paragraph rooms are kept;
//! - distributive counts multiply ("three X, each with two Y": six Y);
//! - a negated noun is excluded and the others are not.
//!
//! The word pools are drawn once, deterministically, from the compiled-in WordNet extract;
//! `PROPTEST_CASES` raises the number of cases.

use std::sync::OnceLock;

use proptest::prelude::*;
use scenesmith::knowledge::knowledge;
use scenesmith::prompt::{self, Count, Reading, Scope};
use scenesmith::words::ground::{self, Verdict};
use scenesmith::words::wordnet::{Pos, wordnet};
use scenesmith::words::{self, lexicon};

struct Pools {
    things: Vec<String>,
    abstracts: Vec<String>,
    adjectives: Vec<String>,
    rooms: Vec<(String, String)>,
}

/// Words the reader treats as grammar or as a class of its own: never in a pool.
fn special(w: &str) -> bool {
    let lex = lexicon();
    let toks = words::tokenize(w);
    lex.is_function_word(w)
        || lex.landmark(w).is_some()
        || lex.is_non_object(w)
        || lex.is_feature_noun(w)
        || lex.group(w).is_some()
        || lex.part(w).is_some()
        || lex.is_setting_noun(w)
        || lex.material(w).is_some()
        || lex.size_adjective(w).is_some()
        || lex.density(w).is_some()
        || lex.density_room_only(w).is_some()
        || lex.room_size(w).is_some()
        || lex.verb(w).is_some()
        || lex.is_negation(w)
        || lex.is_adjective(w)
        || lex.ordinal(w).is_some()
        || toks.len() != 1
        // Class nouns ("artefact", "fruit") stand for their members by design.
        || lex.lookup(w).is_some_and(|e| e.generic)
        || knowledge().room_type_of(w).is_some()
        || knowledge().room_type_of(&prompt::singular(w)).is_some()
}

/// A plural that WordNet reads back to the word.
fn plural(w: &str) -> Option<String> {
    let p = if w.ends_with('y') && !w.ends_with("ay") && !w.ends_with("ey") && !w.ends_with("oy") {
        format!("{}ies", &w[..w.len() - 1])
    } else if ["s", "x", "z", "ch", "sh"].iter().any(|e| w.ends_with(e)) {
        format!("{w}es")
    } else {
        format!("{w}s")
    };
    let back = wordnet().base_forms(&p, Pos::Noun);
    (back.first().map(String::as_str) == Some(w)
        && !wordnet().is_lemma(&p, Pos::Noun)
        && lexicon().singular(&p) == w)
        .then_some(p)
}

fn pools() -> &'static Pools {
    static POOLS: OnceLock<Pools> = OnceLock::new();
    POOLS.get_or_init(|| {
        let wn = wordnet();
        let simple =
            |w: &str| w.len() >= 4 && w.len() <= 12 && w.chars().all(|c| c.is_ascii_lowercase());
        let mut things = Vec::new();
        let mut abstracts = Vec::new();
        for (i, w) in wn.noun_lemmas().enumerate() {
            if !simple(w) || special(w) {
                continue;
            }
            let other_pos = wn.has_pos(w, Pos::Verb) || wn.has_pos(w, Pos::Adj);
            if other_pos {
                continue;
            }
            let Some(info) = ground::noun_info(w) else {
                continue;
            };
            if info.roomlike {
                continue;
            }
            // Animals are things only where a sentence places them; the templates do not
            // always place theirs.
            if i % 7 == 0 && info.share >= 0.95 && plural(w).is_some() && !ground::is_animal(w) {
                things.push(w.to_string());
            } else if i % 5 == 0
                && info.placeable.is_empty()
                && matches!(ground::verdict(w), Verdict::NotObject(_))
                && plural(w).is_some()
                && [
                    "noun.feeling",
                    "noun.state",
                    "noun.attribute",
                    "noun.cognition",
                    "noun.act",
                ]
                .contains(&info.lexname.as_str())
            {
                abstracts.push(w.to_string());
            }
        }
        // Adjectives that are no nouns and no verbs ("somber", "stylish").
        let mut adjectives = Vec::new();
        for w in [
            "somber",
            "stylish",
            "practical",
            "serene",
            "gloomy",
            "vibrant",
            "elegant",
            "luxurious",
            "tranquil",
            "cheerful",
            "chaotic",
            "spacious",
            "airy",
            "rustic",
            "eclectic",
            "minimalist",
            "whimsical",
            "austere",
            "lavish",
            "cozy",
        ] {
            if wn.has_pos(w, Pos::Adj) && !wn.has_pos(w, Pos::Noun) && !wn.has_pos(w, Pos::Verb) {
                adjectives.push(w.to_string());
            }
        }
        // Room words with one word and a plural the reader reads back.
        let mut rooms: Vec<(String, String)> = Vec::new();
        for (key, r) in knowledge().rooms() {
            if key == "room" || key == "en_suite" || key.contains("store") {
                continue;
            }
            if let Some(w) = r
                .words
                .iter()
                .find(|w| !w.contains(' ') && !w.contains('-') && plural(w).is_some())
                && !rooms.iter().any(|(k, _)| k == key)
            {
                rooms.push((key.clone(), w.clone()));
            }
        }
        Pools {
            things,
            abstracts,
            adjectives,
            rooms,
        }
    })
}

fn pick(v: &[String], i: usize) -> &str {
    &v[i % v.len()]
}

fn mentions_of(r: &Reading, noun: &str) -> Vec<usize> {
    (0..r.mentions.len())
        .filter(|&i| {
            let m = &r.mentions[i];
            m.noun.split(' ').any(|w| w == noun) || m.category.split(' ').any(|w| w == noun)
        })
        .collect()
}

fn number_word(n: u32) -> &'static str {
    [
        "zero", "one", "two", "three", "four", "five", "six", "seven", "eight", "nine",
    ][n as usize]
}

#[test]
fn the_pools_are_large_enough() {
    let p = pools();
    assert!(p.things.len() >= 200, "{} things", p.things.len());
    assert!(
        p.abstracts.len() >= 100,
        "{} abstract nouns",
        p.abstracts.len()
    );
    assert!(
        p.adjectives.len() >= 10,
        "{} adjectives",
        p.adjectives.len()
    );
    assert!(p.rooms.len() >= 15, "{} room words", p.rooms.len());
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(cases()))]

    /// Abstract nouns and adjectives around real things never become objects.
    #[test]
    fn no_object_from_abstract_words(a in 0usize..100_000, b in 0usize..100_000,
        c in 0usize..100_000, d in 0usize..100_000, n in 2u32..7, room in 0usize..1000) {
        let p = pools();
        let thing = pick(&p.things, a);
        let abs1 = pick(&p.abstracts, b);
        let abs2 = pick(&p.abstracts, c);
        let adj = pick(&p.adjectives, d);
        let (_, room_word) = &p.rooms[room % p.rooms.len()];
        let prompt = format!(
            "The {room_word} is {adj}, creating a {adj} {abs1}. It holds {} {}, reflecting \
             the owner's {abs2} despite the {abs1}. It is both {adj} and practical.",
            number_word(n),
            plural(thing).unwrap_or_default()
        );
        let r = prompt::read(&prompt);
        for m in &r.mentions {
            for w in [abs1, abs2, adj, "practical"] {
                prop_assert!(
                    !m.noun.split(' ').any(|x| x == w) && !m.category.split(' ').any(|x| x == w),
                    "{prompt:?}: object {:?} from {w:?}", m.noun
                );
            }
        }
        let got = mentions_of(&r, thing);
        prop_assert!(!got.is_empty(), "{prompt:?}: no {thing}");
        prop_assert_eq!(r.total(got[0]), Count::Exactly(n), "{:?}", prompt);
    }

    /// Every room a list counts is read with its count, in list and paragraph forms.
    #[test]
    fn counted_rooms_are_read_with_their_counts(i in 0usize..1000, j in 0usize..1000,
        k in 0usize..1000, n1 in 1u32..4, n2 in 1u32..4, form in 0usize..3,
        thing in 0usize..100_000) {
        let p = pools();
        let pick_room = |x: usize| &p.rooms[x % p.rooms.len()];
        let (t1, w1) = pick_room(i);
        let (t2, w2) = pick_room(j);
        let (t3, w3) = pick_room(k);
        prop_assume!(t1 != t2 && t2 != t3 && t1 != t3);
        let phrase = |n: u32, w: &str| {
            if n == 1 { format!("a {w}") } else { format!("{} {}", number_word(n), plural(w).unwrap_or_default()) }
        };
        let obj = pick(&p.things, thing);
        let prompt = match form {
            0 => format!(
                "A house with {}, {} and a {w3}. The {w3} has a {obj}.",
                phrase(n1, w1), phrase(n2, w2)
            ),
            1 => format!(
                "This quiet home is full of charm. It contains {}, {} and a {w3}.",
                phrase(n1, w1), phrase(n2, w2)
            ),
            _ => format!(
                "The space includes {} rooms: {}, {} and a {w3}.",
                number_word(n1 + n2 + 1), phrase(n1, w1), phrase(n2, w2)
            ),
        };
        let r = prompt::read(&prompt);
        prop_assert_eq!(r.scope, Scope::House, "{:?}", prompt);
        let count = |t: &str| r.rooms.iter().filter(|x| x.room_type == t).count() as u32;
        prop_assert_eq!(count(t1), n1, "{:?} {:?}", prompt, r.rooms.iter().map(|x| &x.name).collect::<Vec<_>>());
        prop_assert_eq!(count(t2), n2, "{:?}", prompt);
        prop_assert_eq!(count(t3), 1, "{:?}", prompt);
        prop_assert_eq!(r.rooms.len() as u32, n1 + n2 + 1, "{:?}", prompt);
    }

    /// Paragraph houses: every room a sentence describes is kept.
    #[test]
    fn paragraph_rooms_are_kept(i in 0usize..1000, j in 0usize..1000, a in 0usize..100_000,
        b in 0usize..100_000, n in 2u32..6) {
        let p = pools();
        let (t1, w1) = &p.rooms[i % p.rooms.len()];
        let (t2, w2) = &p.rooms[j % p.rooms.len()];
        prop_assume!(t1 != t2);
        let (x, y) = (pick(&p.things, a), pick(&p.things, b));
        prop_assume!(x != y);
        let prompt = format!(
            "This cosy home is full of light. The {w1} has a {x}. The {w2} holds {} {}.",
            number_word(n),
            plural(y).unwrap_or_default()
        );
        let r = prompt::read(&prompt);
        let types: Vec<&str> = r.rooms.iter().map(|x| x.room_type.as_str()).collect();
        prop_assert!(types.contains(&t1.as_str()) && types.contains(&t2.as_str()),
            "{:?}: {:?}", prompt, types);
        let ys = mentions_of(&r, y);
        prop_assert!(!ys.is_empty(), "{:?}: no {}", prompt, y);
        let room2 = r.rooms.iter().position(|x| &x.room_type == t2);
        prop_assert_eq!(Some(r.mentions[ys[0]].room), room2, "{:?}", prompt);
        prop_assert_eq!(r.total(ys[0]), Count::Exactly(n), "{:?}", prompt);
    }

    /// Distributive counts multiply.
    #[test]
    fn distributive_counts_multiply(a in 0usize..100_000, b in 0usize..100_000,
        n in 2u32..6, m in 2u32..5, form in 0usize..3) {
        let p = pools();
        let (x, y) = (pick(&p.things, a), pick(&p.things, b));
        prop_assume!(x != y);
        let (xs, ys) = (plural(x).unwrap_or_default(), plural(y).unwrap_or_default());
        let prompt = match form {
            0 => format!("A room with {} {xs}, each with {} {ys}.", number_word(n), number_word(m)),
            1 => format!("A room with {} {xs} with {} {ys} each.", number_word(n), number_word(m)),
            _ => format!("A room. {} {xs} each hold {} {ys}.", capitalise(number_word(n)), number_word(m)),
        };
        let r = prompt::read(&prompt);
        let got = mentions_of(&r, y);
        prop_assert!(!got.is_empty(), "{:?}: no {}", prompt, y);
        prop_assert_eq!(r.total(got[0]), Count::Exactly(n * m), "{:?}", prompt);
    }

    /// A negated noun is excluded; the noun the prompt keeps is not.
    #[test]
    fn negations_exclude_only_their_noun(a in 0usize..100_000, b in 0usize..100_000,
        room in 0usize..1000, form in 0usize..3) {
        let p = pools();
        let (x, y) = (pick(&p.things, a), pick(&p.things, b));
        prop_assume!(x != y);
        let (_, w) = &p.rooms[room % p.rooms.len()];
        let ys = plural(y).unwrap_or_default();
        let prompt = match form {
            0 => format!("A {w} with a {x} but no {ys}."),
            1 => format!("A {w} with a {x}. There are no {ys}."),
            _ => format!("A {w} with a {x} and without any {ys}."),
        };
        let r = prompt::read(&prompt);
        let xs = mentions_of(&r, x);
        let yy = mentions_of(&r, y);
        prop_assert!(xs.iter().any(|&i| !r.mentions[i].negated), "{:?}", prompt);
        prop_assert!(!yy.is_empty() && yy.iter().all(|&i| r.mentions[i].negated), "{:?}", prompt);
    }
}

/// Cases per property: 256, or `PROPTEST_CASES`.
fn cases() -> u32 {
    std::env::var("PROPTEST_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(256)
}

fn capitalise(s: &str) -> String {
    let mut c = s.chars();
    c.next()
        .map(|f| f.to_uppercase().collect::<String>() + c.as_str())
        .unwrap_or_default()
}
