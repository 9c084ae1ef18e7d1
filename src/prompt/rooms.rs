//! Rooms and house structure: is the prompt one room or a house, which rooms with which
//! counts ("two exam rooms", "four guest bedrooms with en-suite bathrooms"), and which room a
//! later phrase is about ("the first exam room", "its bathroom", "the studio").
//!
//! The room list comes from the first sentence ("A dental office with a reception, two exam
//! rooms, ..."). This module does not assign objects to rooms; the interpreter does, using
//! [`resolve`] when a sentence names its room.

use serde::{Deserialize, Serialize};

use super::chunk::{Chunk, Head, Item, Np};
use crate::words::ground;
use crate::words::lexicon::Lexicon;
use crate::words::tokens::Token;

/// One room or a house of several.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Scope {
    /// A single room.
    Room,
    /// Several rooms.
    House,
}

/// How full a room should look.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Density {
    /// "minimalist", "spartan": only what is needed.
    Minimalist,
    /// "sparse", "bare", "empty".
    Sparse,
    /// "pristine", "tidy", "spotless": normal furniture, few loose objects.
    Pristine,
    /// "lived-in", "homey": a few more small objects.
    LivedIn,
    /// "cluttered", "messy": many small objects.
    Cluttered,
    /// "packed", "crowded", "overflowing": as much as fits.
    Packed,
}

impl Density {
    /// From a lexicon density class.
    pub(crate) fn from_class(class: &str) -> Option<Density> {
        Some(match class {
            "minimalist" => Density::Minimalist,
            "sparse" => Density::Sparse,
            "pristine" => Density::Pristine,
            "lived_in" => Density::LivedIn,
            "cluttered" => Density::Cluttered,
            "packed" => Density::Packed,
            _ => return None,
        })
    }
}

/// One room of the reading.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RoomReading {
    /// Room-type key (see [`crate::knowledge`]); `room` when nothing matched.
    pub room_type: String,
    /// Readable name, unique in the reading ("exam room 2", "second bedroom", "bathroom of
    /// guest bedroom 1").
    pub name: String,
    /// The room words as written, singular ("exam room").
    pub words: String,
    /// Position among rooms listed together ("two exam rooms": 1 and 2).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ordinal: Option<u32>,
    /// The room this one belongs to (an en-suite bathroom's bedroom).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub parent: Option<usize>,
    /// Size factor from the room's own words such as "small" (0.8) or "spacious" (1.35);
    /// in a house, the house's factor is [`super::Reading::size_scale`].
    pub size_scale: f64,
    /// Styles and themes of the whole room ("Star Wars", "Art Deco").
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub styles: Vec<String>,
    /// Density words about this room.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub density: Option<Density>,
    /// The prompt text about this room (its sentences and clauses).
    pub text: String,
}

impl RoomReading {
    pub(crate) fn new(room_type: &str, words: &str, name: String) -> RoomReading {
        RoomReading {
            room_type: room_type.to_string(),
            name,
            words: words.to_string(),
            ordinal: None,
            parent: None,
            size_scale: 1.0,
            styles: Vec::new(),
            density: None,
            text: String::new(),
        }
    }
}

/// Size factor of a room phrase from its modifier words.
pub(crate) fn size_of(lex: &Lexicon, np: &Np) -> f64 {
    np.attrs
        .modifiers
        .iter()
        .filter_map(|m| lex.room_size(&m.to_lowercase()))
        .next()
        .unwrap_or(1.0)
}

/// Density named by a room phrase's modifiers ("a cluttered garage", "a tidy office").
pub(crate) fn density_of(lex: &Lexicon, np: &Np) -> Option<Density> {
    np.attrs.modifiers.iter().find_map(|m| {
        let w = m.to_lowercase();
        lex.density(&w)
            .or_else(|| lex.density_room_only(&w))
            .and_then(Density::from_class)
    })
}

/// The house structure read from the first sentence.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Structure {
    /// Room or house.
    pub scope: Scope,
    /// The rooms (one for a single room).
    pub rooms: Vec<RoomReading>,
    /// "dental office", "boutique hotel" (houses only).
    pub house_type: Option<String>,
    /// Size factor of the whole (house) or of the room.
    pub size_scale: f64,
    /// Styles of the whole.
    pub styles: Vec<String>,
    /// Density of the whole.
    pub density: Option<Density>,
    /// The sentence that lists the rooms (its phrases are rooms, not objects).
    pub list_sentence: Option<usize>,
    /// What the reader capped, in words for the user.
    pub notes: Vec<String>,
    /// Phrases of the room list that name rooms though their head is a thing ("a staff
    /// toilet"): (chunk index in the list sentence, the phrase as a room).
    pub coerced: Vec<(usize, Np)>,
    /// Chunks of the list sentence before its list: the building, not objects in it.
    pub head_chunks: usize,
    /// Room words that name the single room under its old use ("the spare room" turned
    /// into a home gym).
    pub aliases: Vec<String>,
}

fn ordinal_word(n: u32) -> &'static str {
    const W: [&str; 16] = [
        "",
        "first",
        "second",
        "third",
        "fourth",
        "fifth",
        "sixth",
        "seventh",
        "eighth",
        "ninth",
        "tenth",
        "eleventh",
        "twelfth",
        "thirteenth",
        "fourteenth",
        "fifteenth",
    ];
    W.get(n as usize).copied().unwrap_or("")
}

/// Where the room list of a sentence starts: after "with", a possession verb ("includes",
/// "features", "has", "consists of"), "there is", "including", or a colon.
fn list_start(tokens: &[Token], chunks: &[Chunk]) -> Option<usize> {
    let word = |i: usize| tokens.get(i).map_or("", |t| t.text.as_str());
    // "divided into", "split into", "made up of": the list starts after the phrase.
    let phrase_end = chunks.iter().flat_map(|c| c.range.clone()).find_map(|i| {
        matches!(
            (word(i), word(i + 1)),
            (
                "divided" | "split" | "organised" | "organized" | "arranged",
                "into"
            ) | ("made", "up")
        )
        .then_some(i + 1)
    });
    // "Upstairs there is a kitchen with ..., a living room with ... and a bedroom": the list
    // starts at "there is".
    let existential = |c: &Chunk| {
        c.range.start > 0
            && word(c.range.start - 1) == "there"
            && matches!(word(c.range.start), "is" | "are")
    };
    chunks.iter().position(|c| match &c.item {
        Item::With | Item::Including => true,
        _ if existential(c) => true,
        // "has been turned into": an auxiliary, no possession.
        Item::Verb(class, _) => class == "possess" && word(c.range.end) != "been",
        Item::Comma => tokens.get(c.range.start).is_some_and(|t| t.is_punct(':')),
        _ => phrase_end.is_some_and(|e| c.range.contains(&e) || c.range.start == e),
    })
}

/// True for "room", "rooms", "space": a room word that names no type. A room the registry
/// has no type for ("scullery", "bunk room") also takes the generic type, but it is named.
fn generic_room(np: &Np) -> bool {
    matches!(&np.head, Head::Room { key, words } if key == "room"
        && crate::knowledge::knowledge().room_type_of(words) == Some("room"))
}

/// "round, snug and richly decorated": a one-word room phrase with no determiner or number
/// whose word WordNet also reads as an adjective describes; it names no room.
fn bare_adjective_room(np: &Np) -> bool {
    matches!(&np.head, Head::Room { words, .. } if !words.contains(' ')
        && crate::words::ground::is_adjective(words))
        && np.det.is_none()
        && np.number.is_none()
        && !np.plural
}

/// A zone inside a room rather than a room: "a seating area", "a reading nook".
fn zone(np: &Np) -> bool {
    matches!(&np.head, Head::Room { words, .. } if ["area", "corner", "nook", "zone", "space"].iter().any(|z| words.ends_with(z)))
}

/// Rooms a sentence introduces: a room phrase that is no preposition's object and either
/// counts or introduces ("a mudroom by the entrance has ...", "Beyond it lie three treatment
/// rooms") or, definite, has its own verb ("The dining room features ...", "..., while the
/// reading room contains ..."). Generic rooms ("the room") and zones are not introduced.
///
/// In a house (`in_house`: the prompt names at least two rooms), every room phrase names a
/// room of it, a preposition's object too ("the hall opens into a large sitting room", "the
/// parents sleep in the master bedroom"), and so does a zone a room type names ("Beyond the
/// lounge lies a dining area"); corners and nooks stay parts of their room.
fn introduced_rooms(chunks: &[Chunk], in_house: bool) -> Vec<&Np> {
    let mut out = Vec::new();
    for (k, c) in chunks.iter().enumerate() {
        let Item::Np(np) = &c.item else { continue };
        let Head::Room { key, words } = &np.head else {
            continue;
        };
        let typed_zone =
            in_house && key != "room" && !["corner", "nook"].iter().any(|z| words.ends_with(z));
        if generic_room(np) || np.negated || (zone(np) && !typed_zone) {
            continue;
        }
        let prep = k > 0 && matches!(chunks[k - 1].item, Item::Prep(_));
        let governed = k > 0
            && matches!(
                chunks[k - 1].item,
                Item::Prep(_) | Item::Of | Item::For | Item::Without | Item::SetFor
            );
        if (governed && !(in_house && prep)) || np.det.as_deref() == Some("possessive") {
            continue;
        }
        // "a bench with five cubbies": what a thing comes with is part of it, not a room.
        let part_of_thing = k > 1
            && chunks[k - 1].item == Item::With
            && matches!(&chunks[k - 2].item, Item::Np(p) if matches!(p.head, Head::Object { .. }));
        if part_of_thing {
            continue;
        }
        if in_house {
            out.push(np.as_ref());
            continue;
        }
        let introduces = np.number.is_some()
            || matches!(np.det.as_deref(), Some("indefinite" | "another"))
            || np.plural && np.det.is_none();
        // Skip what stands between a subject and its verb ("by the entrance").
        let mut j = k + 1;
        while let Some(Chunk {
            item: Item::Prep(_),
            ..
        }) = chunks.get(j)
        {
            j += 1;
            while matches!(chunks.get(j).map(|c| &c.item), Some(Item::Np(_))) {
                j += 1;
            }
        }
        let verb_follows = matches!(
            chunks.get(j).map(|c| &c.item),
            Some(Item::Verb(..) | Item::With)
        );
        if introduces || verb_follows {
            out.push(np.as_ref());
        }
    }
    out
}

/// A prompt that opens with a part of a building or its inside names its room that way: "The
/// command bridge of a research vessel, ..." is a room called "command bridge"; "The inside
/// of a Mongolian ger, ..." a room called "ger". The first sentence's chunks are rewritten:
/// the room phrase becomes a room, the building around it names no object.
pub(crate) fn room_named_by_part(lex: &Lexicon, tokens: &[Token], first: &mut [Chunk]) {
    let last_word = |r: &std::ops::Range<usize>| {
        tokens[r.clone()]
            .iter()
            .rev()
            .find(|t| t.is_word())
            .map(|t| lex.singular(&t.text))
    };
    // "The inside of a ger": "inside of" reads as a preposition after a bare "the".
    if let [a, prep, b, ..] = &mut *first
        && matches!(prep.item, Item::Prep(_))
        && matches!(&a.item, Item::Np(np) if np.det.as_deref() == Some("definite") && a.range.len() == 1)
        && matches!(
            tokens.get(prep.range.start).map(|t| t.text.as_str()),
            Some("inside" | "interior")
        )
        && let Item::Np(whole) = &mut b.item
        && !matches!(whole.head, Head::Room { .. })
    {
        if let Some(words) = phrase_noun(whole).or_else(|| last_word(&b.range)) {
            let key = room_type_of_noun(&words);
            whole.head = Head::Room { key, words };
            // The room is what the "of" phrase names, not a place where something is.
            prep.item = Item::Of;
        }
        return;
    }
    let [a, of, b, ..] = first else { return };
    if of.item != Item::Of {
        return;
    }
    let (Item::Np(part), Item::Np(whole)) = (&mut a.item, &mut b.item) else {
        return;
    };
    if part.det.as_deref() != Some("definite") || part.number.is_some() {
        return;
    }
    let inside = last_word(&a.range).is_some_and(|w| matches!(w.as_str(), "inside" | "interior"));
    if inside {
        if !matches!(whole.head, Head::Room { .. })
            && let Some(words) = phrase_noun(whole).or_else(|| last_word(&b.range))
        {
            let key = room_type_of_noun(&words);
            whole.head = Head::Room { key, words };
        }
        part.head = Head::NonObject;
        return;
    }
    if matches!(part.head, Head::Room { .. }) {
        return;
    }
    if let (Some(words), Some(whole_words)) = (phrase_noun(part), phrase_noun(whole))
        && crate::words::ground::can_be_building(&whole_words)
    {
        let key = room_type_of_noun(&words);
        part.head = Head::Room { key, words };
        whole.head = Head::NonObject;
    }
}

/// "Each cell has ..." after "six monks' cells": a word the chunker could not read as a
/// phrase, after "each", that is the head noun of a room of no known type, names those rooms.
pub(crate) fn each_by_head(lex: &Lexicon, rooms: &[RoomReading], sentence: &mut Vec<Chunk>) {
    let mut k = 0;
    while k + 1 < sentence.len() {
        if let (Item::Each, Item::Other(w)) = (&sentence[k].item, &sentence[k + 1].item) {
            let w = lex.singular(w);
            let room = rooms
                .iter()
                .find(|r| r.room_type == "room" && head_names(&r.words, &w));
            if let Some(r) = room {
                let np = Np {
                    det: Some("each".to_string()),
                    head: Head::Room {
                        key: r.room_type.clone(),
                        words: r.words.clone(),
                    },
                    ..crate::prompt::phrase::blank_np()
                };
                let range = sentence[k].range.start..sentence[k + 1].range.end;
                sentence.splice(
                    k..k + 2,
                    [Chunk {
                        item: Item::Np(Box::new(np)),
                        range,
                    }],
                );
            }
        }
        k += 1;
    }
}

/// Whether `noun` is a room's words or their last word ("cell" of "monks cell").
pub(crate) fn head_names(words: &str, noun: &str) -> bool {
    words == noun
        || words
            .strip_suffix(noun)
            .is_some_and(|rest| rest.ends_with(' '))
}

/// The noun a phrase names, read as a thing or not ("command bridge" is rarely one).
fn phrase_noun(np: &Np) -> Option<String> {
    match &np.head {
        Head::Object { noun, .. } => Some(noun.clone()),
        Head::Room { words, .. } => Some(words.clone()),
        Head::NonObject => np.report.as_ref().map(|r| r.noun.clone()),
        _ => None,
    }
}

/// The room type of a noun the registry may not know: the nearest type along the WordNet
/// hypernyms of its last word, else the generic `room`.
fn room_type_of_noun(words: &str) -> String {
    let reg = crate::knowledge::knowledge();
    let head = words.rsplit(' ').next().unwrap_or(words);
    crate::words::ground::room_family(head, &|n: &str| reg.room_type_of(n).is_some())
        .and_then(|f| reg.room_type_of(&f.noun).map(str::to_string))
        .unwrap_or_else(|| "room".to_string())
}

/// The sentence, among the first few, that lists the rooms: rooms after "with", a
/// possession verb or a colon, at least two of them ("It contains a reception hall, a
/// breakfast room, three guest rooms and two bathrooms.").
fn list_sentence(tokens: &[Token], sentences: &[Vec<Chunk>]) -> usize {
    for (i, chunks) in sentences.iter().enumerate().take(3) {
        let Some(w) = list_start(tokens, chunks) else {
            continue;
        };
        let n: u32 = chunks[w + 1..]
            .iter()
            .filter_map(|c| match &c.item {
                Item::Np(np)
                    if matches!(np.head, Head::Room { .. })
                        && !generic_room(np)
                        && !np.is_definite() =>
                {
                    Some(np.number.unwrap_or(1).max(1))
                }
                _ => None,
            })
            .sum();
        if n >= 2 {
            return i;
        }
    }
    0
}

/// Reads the house structure: the room list of the first sentence ("A dental office with a
/// reception, two exam rooms, ...", "The space includes three rooms: a living room, ..."),
/// then rooms that later sentences introduce as their subjects ("The dining room features
/// ..."). `sentences` are the chunks of every sentence; `tokens` give the house name.
pub(crate) fn structure(lex: &Lexicon, tokens: &[Token], sentences: &[Vec<Chunk>]) -> Structure {
    let list_at = list_sentence(tokens, sentences);
    let first: &[Chunk] = sentences.get(list_at).map_or(&[], Vec::as_slice);
    let with_at = list_start(tokens, first);
    let head_np = first[..with_at.unwrap_or(first.len())]
        .iter()
        .find_map(|c| match &c.item {
            Item::Np(np) => Some((np.as_ref(), c.range.clone())),
            _ => None,
        });
    let head_np = head_np.as_ref().map(|(np, r)| (*np, r.clone()));
    let size_scale = head_np.as_ref().map_or(1.0, |(np, _)| size_of(lex, np));
    let styles = head_np
        .as_ref()
        .map(|(np, _)| np.attrs.styles.clone())
        .unwrap_or_default();
    let density = head_np.as_ref().and_then(|(np, _)| density_of(lex, np));
    // Room phrases after "with"; "X with en-suite Ys" makes Ys children of X.
    let coerced = with_at.map_or_else(Vec::new, |w| coerced_rooms(lex, &first[w + 1..]));
    let mut listed: Vec<(&Np, Option<usize>)> = Vec::new();
    if let Some(w) = with_at {
        let mut last_room: Option<usize> = None;
        let mut after_with = false;
        let mut after_prep = false;
        for (k, c) in first[w + 1..].iter().enumerate() {
            let item = coerced
                .iter()
                .find(|(at, _)| *at == k)
                .map(|(_, np)| np)
                .or(match &c.item {
                    Item::Np(np) => Some(np.as_ref()),
                    _ => None,
                });
            match &c.item {
                Item::Np(_) => {
                    let Some(np) = item else { continue };
                    // "in the middle of the room" is a place, not a listed room; "three
                    // rooms:" counts the rooms that follow.
                    // "..., and the manager's office": a definite list item is a room too,
                    // unless the list named it already.
                    let named_before = |w: &str| {
                        listed
                            .iter()
                            .any(|(p, _)| matches!(&p.head, Head::Room { words, .. } if words == w))
                    };
                    // After a preposition only a new room counts ("connected to an open
                    // kitchen"), not a place ("in the middle of the room").
                    let listed_room = (!after_prep || !np.is_definite())
                        && !generic_room(np)
                        && match &np.head {
                            Head::Room { words, .. } => !np.is_definite() || !named_before(words),
                            _ => false,
                        };
                    after_prep = false;
                    if listed_room {
                        let parent = if after_with { last_room } else { None };
                        listed.push((np, parent));
                        if parent.is_none() {
                            last_room = Some(listed.len() - 1);
                        }
                    }
                    after_with = false;
                }
                Item::With => after_with = true,
                Item::Prep(_) => after_prep = true,
                _ => {}
            }
        }
    }
    // "a 3 bedroom, 2 bathroom home", "a two-bedroom apartment": rooms counted before the list.
    let head_end = with_at.and_then(|w| first.get(w)).map_or_else(
        || first.last().map_or(0, |c| c.range.end),
        |c| c.range.start,
    );
    let head_start = first.first().map_or(0, |c| c.range.start);
    let counted = counted_rooms(lex, &tokens[head_start..head_end.max(head_start)]);
    let head_is_room = head_np
        .as_ref()
        .is_some_and(|(np, _)| matches!(np.head, Head::Room { .. }) && !generic_room(np));
    let listed_count: u32 = listed
        .iter()
        .map(|(np, _)| np.number.unwrap_or(1).max(1))
        .sum();
    // "A pharmacy with a waiting area": one room with a zone; "a bedroom with an en-suite
    // bathroom": two rooms.
    let single_zone = listed.len() == 1 && listed.iter().all(|(np, _)| zone(np));
    let counted_n: u32 = counted.iter().map(|(_, _, n)| n).sum();
    let is_house =
        listed_count + counted_n >= 2 || (listed_count == 1 && head_is_room && !single_zone);
    let mut st = if is_house {
        house_from_list(
            lex,
            tokens,
            first,
            with_at,
            head_np.map(|(np, _)| np),
            &listed,
        )
    } else {
        single_room(lex, tokens, first, sentences)
    };
    st.size_scale = if is_house {
        size_scale
    } else {
        st.rooms
            .first()
            .map_or(size_scale, |r| r.size_scale_or(size_scale))
    };
    if is_house {
        add_counted_rooms(&counted, &mut st);
        let at = with_at.map_or(0, |w| w + 1);
        st.coerced = coerced.into_iter().map(|(k, np)| (at + k, np)).collect();
        st.head_chunks = with_at.unwrap_or(0);
    }
    st.styles = styles;
    st.density = density;
    st.list_sentence = is_house.then_some(list_at);
    add_subject_rooms(lex, sentences, &mut st);
    st
}

/// List items that name a thing with a room sense among rooms ("..., a sluice room and a
/// staff toilet"): in a list of at least two rooms, a phrase outside any room's "with"
/// whose head WordNet also knows as a room is that room. (index in `items`, the phrase as a
/// room).
fn coerced_rooms(lex: &Lexicon, items: &[Chunk]) -> Vec<(usize, Np)> {
    let rooms = items
        .iter()
        .enumerate()
        .filter(|(k, c)| {
            let governed = *k > 0 && matches!(items[k - 1].item, Item::Prep(_));
            let Item::Np(np) = &c.item else { return false };
            matches!(np.head, Head::Room { .. }) && !generic_room(np) && !zone(np) && !governed
        })
        .count();
    if rooms < 2 {
        return Vec::new();
    }
    let mut out = Vec::new();
    let mut in_with = false;
    let mut after_prep = false;
    for (k, c) in items.iter().enumerate() {
        match &c.item {
            Item::Np(np) => {
                match &np.head {
                    Head::Room { .. } => in_with = false,
                    Head::Object { .. } | Head::NonObject if !in_with && !after_prep => {
                        // A word read as no thing ("three nuns' cells": mostly biology) is a
                        // room only by a room sense of its own.
                        let (noun, unknown) = match &np.head {
                            Head::Object { noun, entry, .. } => (noun, entry.is_none()),
                            _ => match &np.report {
                                Some(r) => (&r.noun, false),
                                None => continue,
                            },
                        };
                        // "six stalls": the room words are singular.
                        let noun = super::phrase::singular_last(lex, noun);
                        let head = noun.rsplit(' ').next().unwrap_or(&noun);
                        // Among three rooms or more, a thing the lexicon does not know is
                        // a room too ("..., a gym and four sleeping pods").
                        let roomlike = crate::words::ground::noun_info(head)
                            .is_some_and(|i| i.roomlike)
                            || (unknown && rooms >= 3);
                        if roomlike {
                            let key = room_type_of_noun(head);
                            let mut room = (**np).clone();
                            room.head = Head::Room {
                                key,
                                words: noun.clone(),
                            };
                            out.push((k, room));
                        }
                    }
                    _ => {}
                }
                after_prep = false;
            }
            Item::With => in_with = true,
            Item::Prep(_) => after_prep = true,
            _ => {}
        }
    }
    out
}

/// Rooms counted by a number before a room word ("3 bedroom", "two-bedroom", "2-bath"):
/// (type, words, count).
fn counted_rooms(lex: &Lexicon, tokens: &[Token]) -> Vec<(String, String, u32)> {
    let reg = crate::knowledge::knowledge();
    let house = crate::knowledge::rooms::registry().house();
    let room_of = |w: &str| -> Option<(String, String)> {
        let w = lex.singular(w);
        if let Some(t) = reg.room_type_of(&w).filter(|t| *t != "room") {
            return Some((t.to_string(), w));
        }
        let t = house.count_words.get(&w)?;
        Some((t.clone(), t.replace('_', " ")))
    };
    // "a six-bed hospital ward", "a four-bed dorm room": a house's count word ("bed" for
    // bedrooms) before a room that is no dwelling counts the things in that room, not rooms.
    let room_after = |i: usize| {
        (i + 1..tokens.len()).any(|k| {
            (1..=2).any(|n| {
                k + n <= tokens.len() && {
                    let words: Vec<String> = tokens[k..k + n]
                        .iter()
                        .map(|t| lex.singular(&t.text))
                        .collect();
                    let words = words.join(" ");
                    ground::is_room_word(&words) && !ground::is_dwelling(&words)
                }
            })
        })
    };
    let mut out: Vec<(String, String, u32)> = Vec::new();
    for (i, t) in tokens.iter().enumerate() {
        let by_count_word = |w: &str| {
            reg.room_type_of(&lex.singular(w))
                .is_none_or(|t| t == "room")
        };
        let found = match t.text.split_once('-') {
            Some((_, b)) if by_count_word(b) && room_after(i) => None,
            Some((a, b)) => lex.number_word(a).zip(room_of(b)),
            None if tokens.get(i + 1).is_some_and(|x| by_count_word(&x.text))
                && room_after(i + 1) =>
            {
                None
            }
            None => lex
                .number(t)
                .zip(tokens.get(i + 1).and_then(|x| room_of(&x.text))),
        };
        if let Some((n, (key, words))) = found
            && (1..=MAX_PER_PHRASE).contains(&n)
            && !out.iter().any(|(k, ..)| *k == key)
        {
            out.push((key, words, n));
        }
    }
    out
}

/// Adds the rooms counted before the list that the list does not name, up to their counts.
fn add_counted_rooms(counted: &[(String, String, u32)], st: &mut Structure) {
    let registry = crate::knowledge::knowledge().registry();
    let before = st.rooms.len();
    for (key, words, n) in counted {
        let have = st
            .rooms
            .iter()
            .filter(|r| registry.is_a(&r.room_type, key))
            .count() as u32;
        for k in have..*n {
            if st.rooms.len() >= MAX_ROOMS {
                break;
            }
            let name = if *n > 1 {
                format!("{words} {}", k + 1)
            } else {
                words.clone()
            };
            let mut r = RoomReading::new(key, words, name);
            r.ordinal = (*n > 1).then_some(k + 1);
            st.rooms.push(r);
        }
    }
    if st.rooms.len() > before {
        unique_names(&mut st.rooms);
    }
}

/// One room: the first room phrase that names a type (the head, usually; "The room is dimly
/// lit ... in a cozy living room": the living room), else a generic room.
fn single_room(
    lex: &Lexicon,
    tokens: &[Token],
    first: &[Chunk],
    sentences: &[Vec<Chunk>],
) -> Structure {
    // A room with a registry type over a named room without one ("The spare room has been
    // turned into a home gym": a home gym).
    // A room after a preposition is where the room is, when the sentence names another
    // ("Hidden in a converted basement, this recording studio has ..."): the other first.
    // "The clubroom of the chess society sits behind a café": a room named outside a
    // preposition comes before one placed by it, whether or not the registry knows its type.
    fn typed(chunks: &[Chunk], registry_type: bool, placed_ok: bool) -> Option<&Np> {
        let room_at = |k: usize| match &chunks[k].item {
            Item::Np(np)
                if matches!(&np.head, Head::Room { key, .. } if !registry_type || key != "room")
                    && !generic_room(np)
                    && !bare_adjective_room(np)
                    && !np.negated
                    && (placed_ok || k == 0 || !matches!(chunks[k - 1].item, Item::Prep(_))) =>
            {
                Some(np.as_ref())
            }
            _ => None,
        };
        (0..chunks.len()).find_map(room_at)
    }
    // "The spare room has been turned into a home gym", "a garage used as a workshop": the
    // room after "into" or "as" is what the room is now.
    let role = first
        .iter()
        .enumerate()
        .skip(1)
        .find_map(|(k, c)| match &c.item {
            Item::Np(np)
                if matches!(np.head, Head::Room { .. })
                    && !generic_room(np)
                    && c.range.start > 0
                    && tokens
                        .get(c.range.start - 1)
                        .is_some_and(|t| t.text == "into" || t.text == "as")
                    && first[..k].iter().any(
                        |p| matches!(&p.item, Item::Np(n) if matches!(n.head, Head::Room { .. })),
                    ) =>
            {
                Some(np.as_ref())
            }
            _ => None,
        });
    let aliases: Vec<String> = role
        .map(|_| {
            first
                .iter()
                .filter_map(|c| match &c.item {
                    Item::Np(np) => match &np.head {
                        Head::Room { words, .. } => Some(words.clone()),
                        _ => None,
                    },
                    _ => None,
                })
                .collect()
        })
        .unwrap_or_default();
    let unplaced = role
        .or_else(|| typed(first, true, false))
        .or_else(|| typed(first, false, false));
    // "Out in a converted garden shed, the ham radio shack hums ...": a building the
    // sentence's subject names comes before a room a preposition places.
    let subject = unplaced
        .is_none()
        .then(|| building_subject(lex, tokens, first))
        .flatten();
    let room_np = unplaced
        .or_else(|| {
            subject
                .is_none()
                .then(|| typed(first, true, true))
                .flatten()
        })
        .or_else(|| {
            subject
                .is_none()
                .then(|| typed(first, false, true))
                .flatten()
        })
        .or_else(|| {
            subject.is_none().then_some(())?;
            sentences
                .iter()
                .skip(1)
                .find_map(|s| typed(s, false, false).or_else(|| typed(s, false, true)))
        });
    let room_np = room_np.or_else(|| {
        subject.is_none().then_some(())?;
        first.iter().find_map(|c| match &c.item {
            Item::Np(np) if matches!(np.head, Head::Room { .. }) => Some(np.as_ref()),
            _ => None,
        })
    });
    let mut room = match room_np.map(|np| &np.head) {
        Some(Head::Room { key, words }) => RoomReading::new(key, words, words.clone()),
        _ => match subject.or_else(|| building_subject(lex, tokens, first)) {
            Some(words) => {
                let key = room_type_of_noun(&words);
                RoomReading::new(&key, &words, words.clone())
            }
            None => RoomReading::new("room", "room", "room".into()),
        },
    };
    // The converted room keeps its name ("the garage", furnished as a woodworking shop);
    // its new use gives the type.
    if role.is_some()
        && let Some(old) = aliases.first().filter(|w| **w != room.words)
    {
        room.name = old.clone();
        room.words = old.clone();
    }
    if let Some(np) = room_np {
        room.size_scale = size_of(lex, np);
        room.styles = np.attrs.styles.clone();
        room.density = density_of(lex, np);
    }
    Structure {
        scope: Scope::Room,
        rooms: vec![room],
        house_type: None,
        size_scale: 1.0,
        styles: Vec::new(),
        density: None,
        list_sentence: None,
        notes: Vec::new(),
        coerced: Vec::new(),
        head_chunks: 0,
        aliases,
    }
}

/// "At the top of the tower, the observatory opens to the sky", "The honey house at the edge
/// of the orchard is sticky": with no room word, the subject of the first sentence names the
/// room when WordNet knows its last word (or the last two) as a room or building. A
/// building placed by a preposition is where the room is, not the room.
fn building_subject(lex: &Lexicon, tokens: &[Token], first: &[Chunk]) -> Option<String> {
    first.iter().enumerate().find_map(|(k, c)| {
        let Item::Np(np) = &c.item else { return None };
        let subject = np.head == Head::NonObject
            && np.has_det()
            && !np.negated
            && (k == 0 || matches!(first[k - 1].item, Item::Comma))
            && matches!(
                first.get(k + 1).map(|x| &x.item),
                Some(Item::Verb(..) | Item::Prep(_))
            );
        if !subject {
            return None;
        }
        let words: Vec<String> = tokens[c.range.clone()]
            .iter()
            .filter(|t| t.is_word() && lex.determiner(&t.text).is_none())
            .map(|t| t.text.clone())
            .collect();
        let last = words.last()?;
        let one = lex.singular(last);
        let two = words
            .len()
            .checked_sub(2)
            .map(|i| format!("{} {one}", words[i]));
        let roomish = |w: &str| {
            crate::words::ground::is_room_word(w) || crate::words::ground::can_be_building(w)
        };
        if let Some(two) = two
            .as_ref()
            .filter(|t| crate::words::ground::noun_lemma(t).is_some() && roomish(t))
        {
            return Some(two.clone());
        }
        // "the honey house", "the ham radio shack": a kind of building named by the nouns
        // before it.
        let modifying_noun = |w: &String| {
            crate::words::ground::is_noun(w)
                && !lex.is_adjective(w)
                && np.attrs.size.as_deref() != Some(w.as_str())
                && !np.attrs.styles.iter().any(|x| x == w)
                && lex.material(w).is_none()
        };
        let nouns_before = words[..words.len() - 1]
            .iter()
            .rev()
            .take_while(|w| modifying_noun(w))
            .count();
        if !roomish(&one) {
            return None;
        }
        let first = words.len() - 1 - nouns_before;
        Some(if nouns_before == 0 {
            one
        } else {
            format!("{} {one}", words[first..words.len() - 1].join(" "))
        })
    })
}

/// A house from the room list of the first sentence.
fn house_from_list(
    lex: &Lexicon,
    tokens: &[Token],
    first: &[Chunk],
    with_at: Option<usize>,
    head_np: Option<&Np>,
    listed: &[(&Np, Option<usize>)],
) -> Structure {
    let size_scale = head_np.map_or(1.0, |np| size_of(lex, np));
    let listed_count: u32 = listed
        .iter()
        .map(|(np, _)| np.number.unwrap_or(1).max(1))
        .sum();
    let mut rooms: Vec<RoomReading> = Vec::new();
    let mut notes: Vec<String> = Vec::new();
    if listed_count == 1
        && let Some(np) = head_np
        && let Head::Room { key, words } = &np.head
    {
        let mut r = RoomReading::new(key, words, words.clone());
        r.size_scale = size_of(lex, np);
        r.styles = np.attrs.styles.clone();
        rooms.push(r);
    }
    // listed index -> room indices created for it
    let mut made: Vec<Vec<usize>> = Vec::new();
    for (np, parent) in listed {
        let Head::Room { key, words } = &np.head else {
            made.push(Vec::new());
            continue;
        };
        let n = capped(np.number.unwrap_or(1).max(1), words, &mut notes);
        let mut ids = Vec::new();
        match parent.and_then(|p| made.get(p).cloned()) {
            Some(parents) if !parents.is_empty() => {
                // One child per parent room ("four guest bedrooms with en-suite bathrooms").
                for p in parents {
                    let pname = rooms[p].name.clone();
                    let mut r =
                        RoomReading::new(&child_type(key), words, format!("{words} of {pname}"));
                    r.parent = Some(p);
                    r.size_scale = size_of(lex, np);
                    ids.push(rooms.len());
                    rooms.push(r);
                }
            }
            _ => {
                for k in 0..n {
                    let name = if n > 1 {
                        format!("{words} {}", k + 1)
                    } else if let (Some(o), Some("indefinite")) = (np.ordinal, np.det.as_deref()) {
                        // "a second bedroom" is a name, not a position.
                        format!("{} {words}", ordinal_word(o))
                    } else {
                        words.clone()
                    };
                    let mut r = RoomReading::new(key, words, name);
                    r.ordinal = (n > 1).then_some(k + 1);
                    r.size_scale = size_of(lex, np);
                    r.styles = np.attrs.styles.clone();
                    ids.push(rooms.len());
                    rooms.push(r);
                }
            }
        }
        made.push(ids);
    }
    // "A bedroom with a bathroom": the head room's own bathroom.
    let head_private = rooms.len() == 2
        && listed_count == 1
        && crate::knowledge::knowledge()
            .room(&rooms[0].room_type)
            .is_some_and(|r| r.role == crate::knowledge::rooms::Role::Private);
    if head_private && rooms[1].parent.is_none() && child_type(&rooms[1].room_type) == "en_suite" {
        rooms[1].room_type = "en_suite".to_string();
        rooms[1].parent = Some(0);
    }
    if rooms.len() > MAX_ROOMS {
        notes.push(format!(
            "{} rooms asked for, {MAX_ROOMS} built: a house has at most {MAX_ROOMS} rooms",
            rooms.len()
        ));
        rooms.truncate(MAX_ROOMS);
        for r in &mut rooms {
            r.parent = r.parent.filter(|&p| p < MAX_ROOMS);
        }
    }
    unique_names(&mut rooms);
    // "A small dental office with ...": the words before the list, without determiners and
    // size words.
    let upto = with_at
        .and_then(|w| first.get(w))
        .map_or(0, |c| c.range.start);
    let from = first.first().map_or(0, |c| c.range.start);
    let words: Vec<&str> = tokens[from..upto.max(from)]
        .iter()
        .filter(|t| t.is_word())
        .map(|t| t.text.as_str())
        .filter(|w| {
            lex.determiner(w).is_none()
                && lex.room_size(w).is_none()
                && lex.size_adjective(w).is_none()
                && lex.verb(w).is_none()
        })
        .collect();
    let house_type = (!words.is_empty()).then(|| words.join(" "));
    Structure {
        scope: Scope::House,
        rooms,
        house_type,
        size_scale,
        styles: Vec::new(),
        density: None,
        list_sentence: None,
        notes,
        coerced: Vec::new(),
        head_chunks: 0,
        aliases: Vec::new(),
    }
}

/// Rooms that later sentences introduce as their subjects and that no room of the structure
/// is ("The dining room features ..." after "a living room with ..."). Zones ("the seating
/// area has ...") stay parts of their room.
fn add_subject_rooms(lex: &Lexicon, sentences: &[Vec<Chunk>], st: &mut Structure) {
    let list = st.list_sentence;
    // Sentences before the room list describe the building, not its rooms. A second pass,
    // once the prompt is a house, reads every room phrase as a room of it, before the list
    // too ("The children share a bedroom ... There is also a bathroom ... and a kitchen").
    // There, a building ("This backpacker hostel has ...") is the house itself.
    let rooms_in = |in_house: bool| -> Vec<&Np> {
        sentences
            .iter()
            .enumerate()
            .filter(|(i, _)| list.is_none_or(|l| *i > l || (in_house && *i < l)))
            .flat_map(|(i, chunks)| {
                introduced_rooms(chunks, in_house)
                    .into_iter()
                    .filter(move |np| {
                        // "... no mirrors anywhere in the lodge" after the rooms: the building
                        // named again is the house, no room of it.
                        let before_list = list.is_some_and(|l| i < l);
                        !((before_list || np.is_definite())
                            && matches!(&np.head, Head::Room { key, words }
                                if key == "room" && crate::words::ground::is_building(words)))
                    })
            })
            .collect()
    };
    let mut added = add_rooms(lex, &rooms_in(false), st);
    if st.rooms.len() >= 2 {
        added |= add_rooms(lex, &rooms_in(true), st);
    }
    if added {
        unique_names(&mut st.rooms);
        st.scope = Scope::House;
    }
}

/// Adds the rooms of `nps` that no room of the structure is; true when one was added.
fn add_rooms(lex: &Lexicon, nps: &[&Np], st: &mut Structure) -> bool {
    let mut added = false;
    for &np in nps {
        let Head::Room { key, words } = &np.head else {
            continue;
        };
        // "The office is tidy" after "this open-plan office": the same room.
        // Same words, or the same type under the same head word ("the bedroom" after "a
        // guest bedroom") or under the type's own name ("the studio"); "the loft bedroom"
        // is not "the bunk room".
        let head = |w: &str| w.rsplit(' ').next().unwrap_or("").to_string();
        let type_name = crate::knowledge::knowledge().room_type_of(words) == Some(key.as_str());
        // "a half bath; upstairs there are two full bathrooms": a counted phrase in other
        // words introduces rooms of its own.
        let counted_new = np.number.is_some_and(|n| n >= 2) && !np.is_definite();
        let known = st.rooms.iter().any(|r| {
            (r.room_type == *key
                && key != "room"
                && !counted_new
                && (type_name || head(&r.words) == head(words)))
                || r.words == *words
                || r.words.ends_with(&format!(" {words}"))
        }) || st.aliases.contains(words);
        if known {
            continue;
        }
        let n = capped(np.number.unwrap_or(1).max(1), words, &mut st.notes);
        let name = |k: u32| {
            if n > 1 {
                format!("{words} {}", k + 1)
            } else {
                words.clone()
            }
        };
        let mut first = 0;
        if st.rooms.len() == 1 && st.rooms[0].room_type == "room" {
            // A generic first room is the (first) room this sentence describes; "three
            // treatment rooms" still gives three.
            let scale = st.rooms[0].size_scale;
            let generic =
                std::mem::replace(&mut st.rooms[0], RoomReading::new(key, words, name(0)));
            // The building the prompt began with is no room of its own.
            st.aliases.push(generic.words);
            st.rooms[0].ordinal = (n > 1).then_some(1);
            st.rooms[0].size_scale = scale * size_of(lex, np);
            first = 1;
        }
        for k in first..n {
            if st.rooms.len() >= MAX_ROOMS {
                st.notes.push(format!(
                    "{words}: not built, a house has at most {MAX_ROOMS} rooms"
                ));
                break;
            }
            let mut r = RoomReading::new(key, words, name(k));
            r.ordinal = (n > 1).then_some(k + 1);
            r.size_scale = size_of(lex, np);
            st.rooms.push(r);
        }
        added = true;
    }
    added
}

/// Most rooms one phrase adds ("forty offices" gives 20; the rest is reported).
pub const MAX_PER_PHRASE: u32 = 20;
/// Most rooms of a house; the rest of a longer list is left out (and reported).
pub const MAX_ROOMS: usize = 40;

/// Rooms a phrase asks for, capped, with a note when the cap cut it.
fn capped(n: u32, words: &str, notes: &mut Vec<String>) -> u32 {
    if n > MAX_PER_PHRASE {
        notes.push(format!(
            "{n} {words}s asked for, {MAX_PER_PHRASE} built: one phrase adds at most {MAX_PER_PHRASE} rooms"
        ));
        return MAX_PER_PHRASE;
    }
    n
}

/// The room type of a room listed as another room's own ("four bedrooms with en-suite
/// bathrooms"): a wet room becomes that room's en-suite.
fn child_type(key: &str) -> String {
    let reg = crate::knowledge::knowledge();
    let wet = reg
        .room(key)
        .is_some_and(|r| r.role == crate::knowledge::rooms::Role::Wet);
    if wet && reg.room("en_suite").is_some() {
        "en_suite".to_string()
    } else {
        key.to_string()
    }
}

/// Names stay unique: a second "bathroom" listed separately becomes "bathroom 2".
fn unique_names(rooms: &mut [RoomReading]) {
    for i in 0..rooms.len() {
        let dup = rooms[..i]
            .iter()
            .filter(|r| r.name == rooms[i].name)
            .count();
        if dup > 0 {
            rooms[i].name = format!("{} {}", rooms[i].name, dup + 1);
        }
    }
}

impl RoomReading {
    fn size_scale_or(&self, fallback: f64) -> f64 {
        if self.size_scale != 1.0 {
            self.size_scale
        } else {
            fallback
        }
    }
}

/// The room a room phrase refers to, given the room in focus: by name ("the second
/// bedroom"), by possessive ("its bathroom": the child of the room in focus), by ordinal among
/// rooms of the type ("the first exam room"), else the first room of the type. A type also
/// names the types that extend it when the house has none of its own ("its bathroom" is the
/// en-suite, "the bedroom" the master bedroom).
pub(crate) fn resolve(rooms: &[RoomReading], np: &Np, current: usize) -> Option<usize> {
    let Head::Room { key, words } = &np.head else {
        return None;
    };
    let registry = crate::knowledge::knowledge().registry();
    if key == "room" && words != "room" {
        // A word with no registry type ("the suites" after "two guest suites", "the
        // scullery"): the rooms listed under those words.
        let named: Vec<usize> = (0..rooms.len())
            .filter(|&i| rooms[i].words == *words || rooms[i].words.ends_with(&format!(" {words}")))
            .collect();
        if !named.is_empty() {
            let o = np.ordinal.unwrap_or(1).saturating_sub(1) as usize;
            return named.get(o).copied();
        }
    }
    let key: &String = if rooms.iter().any(|r| r.room_type == *key) {
        key
    } else {
        match rooms.iter().find(|r| registry.is_a(&r.room_type, key)) {
            Some(r) => &r.room_type,
            None => key,
        }
    };
    if words == "room" && np.ordinal.is_none() {
        return Some(current);
    }
    if let Some(o) = np.ordinal {
        let name = format!("{} {words}", ordinal_word(o));
        if let Some(i) = rooms.iter().position(|r| r.name == name) {
            return Some(i);
        }
    }
    if np.det.as_deref() == Some("possessive") {
        // The focus room's own child of that type, or the focus room's parent's child.
        let owner = rooms.get(current).and_then(|r| r.parent).unwrap_or(current);
        if let Some(i) = rooms
            .iter()
            .position(|r| r.parent == Some(owner) && r.room_type == *key)
        {
            return Some(i);
        }
    }
    let same: Vec<usize> = (0..rooms.len())
        .filter(|&i| rooms[i].room_type == *key && rooms[i].parent.is_none())
        .collect();
    let same = if same.is_empty() {
        (0..rooms.len())
            .filter(|&i| rooms[i].room_type == *key)
            .collect()
    } else {
        same
    };
    if let Some(o) = np.ordinal {
        // Prefer rooms listed under the same words ("the first kids bedroom").
        let by_words: Vec<usize> = same
            .iter()
            .copied()
            .filter(|&i| rooms[i].words == *words)
            .collect();
        let pool = if by_words.is_empty() {
            &same
        } else {
            &by_words
        };
        return pool.get(o.saturating_sub(1) as usize).copied();
    }
    let by_words = same.iter().copied().find(|&i| rooms[i].words == *words);
    by_words.or_else(|| same.first().copied())
}
