//! Rooms and house structure: is the prompt one room or a house, which rooms with which
//! counts ("two exam rooms", "four guest bedrooms with en-suite bathrooms"), and which room a
//! later phrase is about ("the first exam room", "its bathroom", "the studio").
//!
//! The room list comes from the first sentence ("A dental office with a reception, two exam
//! rooms, ..."). This module does not assign objects to rooms; the interpreter does, using
//! [`resolve`] when a sentence names its room.

use serde::{Deserialize, Serialize};

use super::chunk::{Chunk, Head, Item, Np};
use super::lexicon::Lexicon;
use super::tokens::Token;

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
/// "features", "has", "consists of"), "including", or a colon.
fn list_start(tokens: &[Token], chunks: &[Chunk]) -> Option<usize> {
    chunks.iter().position(|c| match &c.item {
        Item::With | Item::Including => true,
        Item::Verb(class, _) => class == "possess",
        Item::Comma => tokens.get(c.range.start).is_some_and(|t| t.is_punct(':')),
        _ => false,
    })
}

/// True for "room", "rooms", "space": a room word that names no type.
fn generic_room(np: &Np) -> bool {
    matches!(&np.head, Head::Room { key, .. } if key == "room")
}

/// A zone inside a room rather than a room: "a seating area", "a reading nook".
fn zone(np: &Np) -> bool {
    matches!(&np.head, Head::Room { words, .. } if ["area", "corner", "nook", "zone", "space"].iter().any(|z| words.ends_with(z)))
}

/// Rooms a sentence introduces: a room phrase that is no preposition's object and either
/// counts or introduces ("a mudroom by the entrance has ...", "Beyond it lie three treatment
/// rooms") or, definite, has its own verb ("The dining room features ...", "..., while the
/// reading room contains ..."). Generic rooms ("the room") and zones are not introduced.
fn introduced_rooms(chunks: &[Chunk]) -> Vec<&Np> {
    let mut out = Vec::new();
    for (k, c) in chunks.iter().enumerate() {
        let Item::Np(np) = &c.item else { continue };
        if !matches!(np.head, Head::Room { .. }) || generic_room(np) || np.negated || zone(np) {
            continue;
        }
        let governed = k > 0
            && matches!(
                chunks[k - 1].item,
                Item::Prep(_) | Item::Of | Item::For | Item::Without | Item::SetFor
            );
        if governed || np.det.as_deref() == Some("possessive") {
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
    let mut listed: Vec<(&Np, Option<usize>)> = Vec::new();
    if let Some(w) = with_at {
        let mut last_room: Option<usize> = None;
        let mut after_with = false;
        let mut after_prep = false;
        for c in &first[w + 1..] {
            match &c.item {
                Item::Np(np) => {
                    // "in the middle of the room" is a place, not a listed room; "three
                    // rooms:" counts the rooms that follow.
                    let listed_room = !after_prep && !np.is_definite() && !generic_room(np);
                    after_prep = false;
                    if listed_room && let Head::Room { .. } = np.head {
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
    let is_house = listed_count >= 2 || (listed_count == 1 && head_is_room && !single_zone);
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
        single_room(lex, first, sentences)
    };
    st.size_scale = if is_house {
        size_scale
    } else {
        st.rooms
            .first()
            .map_or(size_scale, |r| r.size_scale_or(size_scale))
    };
    st.styles = styles;
    st.density = density;
    st.list_sentence = is_house.then_some(list_at);
    add_subject_rooms(lex, sentences, &mut st);
    st
}

/// One room: the first room phrase that names a type (the head, usually; "The room is dimly
/// lit ... in a cozy living room": the living room), else a generic room.
fn single_room(lex: &Lexicon, first: &[Chunk], sentences: &[Vec<Chunk>]) -> Structure {
    fn typed(chunks: &[Chunk]) -> Option<&Np> {
        chunks.iter().find_map(|c| match &c.item {
            Item::Np(np)
                if matches!(np.head, Head::Room { .. }) && !generic_room(np) && !np.negated =>
            {
                Some(np.as_ref())
            }
            _ => None,
        })
    }
    let room_np = typed(first).or_else(|| sentences.iter().skip(1).find_map(|s| typed(s)));
    let room_np = room_np.or_else(|| {
        first.iter().find_map(|c| match &c.item {
            Item::Np(np) if matches!(np.head, Head::Room { .. }) => Some(np.as_ref()),
            _ => None,
        })
    });
    let mut room = match room_np.map(|np| &np.head) {
        Some(Head::Room { key, words }) => RoomReading::new(key, words, words.clone()),
        _ => RoomReading::new("room", "room", "room".into()),
    };
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
    }
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
    }
}

/// Rooms that later sentences introduce as their subjects and that no room of the structure
/// is ("The dining room features ..." after "a living room with ..."). Zones ("the seating
/// area has ...") stay parts of their room.
fn add_subject_rooms(lex: &Lexicon, sentences: &[Vec<Chunk>], st: &mut Structure) {
    let mut added = false;
    let list = st.list_sentence;
    // Sentences before the room list describe the building, not its rooms.
    let nps = sentences
        .iter()
        .enumerate()
        .filter(|(i, _)| list.is_none_or(|l| *i > l))
        .flat_map(|(_, chunks)| introduced_rooms(chunks));
    for np in nps {
        let Head::Room { key, words } = &np.head else {
            continue;
        };
        // "The office is tidy" after "this open-plan office": the same room.
        let known = st.rooms.iter().any(|r| {
            r.room_type == *key || r.words == *words || r.words.ends_with(&format!(" {words}"))
        });
        if known {
            continue;
        }
        if st.rooms.len() == 1 && st.rooms[0].room_type == "room" {
            // A generic first room is the room this sentence describes.
            let scale = st.rooms[0].size_scale;
            st.rooms[0] = RoomReading::new(key, words, words.clone());
            st.rooms[0].size_scale = scale * size_of(lex, np);
            continue;
        }
        let n = capped(np.number.unwrap_or(1).max(1), words, &mut st.notes);
        for k in 0..n {
            if st.rooms.len() >= MAX_ROOMS {
                st.notes.push(format!(
                    "{words}: not built, a house has at most {MAX_ROOMS} rooms"
                ));
                break;
            }
            let name = if n > 1 {
                format!("{words} {}", k + 1)
            } else {
                words.clone()
            };
            let mut r = RoomReading::new(key, words, name);
            r.ordinal = (n > 1).then_some(k + 1);
            r.size_scale = size_of(lex, np);
            st.rooms.push(r);
        }
        added = true;
    }
    if added {
        unique_names(&mut st.rooms);
        st.scope = Scope::House;
    }
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
