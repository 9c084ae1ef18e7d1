//! The layout's view of the room registry ([`crate::knowledge::rooms`]): per room type its role
//! in the circulation graph, size range, materials and windows (all on [`RoomType`]); the
//! adjacency rules and house-level tables; the room words as token lists for the brief; where
//! material words point.
//!
//! This is data only, and none of it is defined here. Reading a prompt into rooms is
//! [`super::brief`]; turning rooms into sizes and connectivity requirements is [`super::spec`].

use std::sync::OnceLock;

pub use crate::knowledge::rooms::{Registry, Role, RoomType, SizeRange};

/// The room registry.
pub fn knowledge() -> &'static Registry {
    crate::knowledge::rooms::registry()
}

/// The generic room every unknown type falls back to.
pub fn fallback_kind() -> &'static RoomType {
    static BROKEN: OnceLock<RoomType> = OnceLock::new();
    knowledge().get("room").unwrap_or_else(|| {
        // Only when the compiled-in data does not load (a unit test forbids that): a bare
        // room, so the layout still runs.
        BROKEN.get_or_init(|| RoomType {
            words: vec!["room".into()],
            role: Role::Public,
            size: SizeRange {
                min: [2.0, 2.0],
                typical: [4.2, 3.6],
                max: [8.0, 8.0],
            },
            min_side: 2.0,
            wall_height: 2.7,
            floor: "oak".into(),
            wall: "plaster".into(),
            windows: true,
            sill: 0.9,
            adjacency: Vec::new(),
            extends: None,
            furniture: Vec::new(),
            wall_items: Vec::new(),
            ceiling: Vec::new(),
            surfaces: Vec::new(),
        })
    })
}

/// The room type `room_type`, or the generic room.
pub fn kind(room_type: &str) -> &'static RoomType {
    knowledge().get(room_type).unwrap_or_else(fallback_kind)
}

/// Every room word as token lists with its type, longest first.
pub fn room_words() -> &'static [(Vec<String>, String)] {
    static WORDS: OnceLock<Vec<(Vec<String>, String)>> = OnceLock::new();
    WORDS.get_or_init(|| {
        let mut out: Vec<(Vec<String>, String)> = knowledge()
            .types()
            .iter()
            .flat_map(|(key, k)| {
                k.words
                    .iter()
                    .map(move |w| (crate::words::tokenize(w), key.clone()))
            })
            .filter(|(t, _)| !t.is_empty())
            .collect();
        out.sort_by(|a, b| b.0.len().cmp(&a.0.len()).then(a.0.cmp(&b.0)));
        // Spellings that read the same ("children's bedroom", "child bedroom") once.
        out.dedup();
        out
    })
}

/// The material table name a word means ("hardwood" -> `oak`), if any.
pub fn material_word(word: &str) -> Option<&'static str> {
    let w = word.trim().to_lowercase();
    knowledge()
        .house()
        .materials
        .get(&w)
        .map(String::as_str)
        .or_else(|| {
            crate::assets::material::names()
                .into_iter()
                .find(|n| *n == w)
        })
}

#[cfg(test)]
mod tests {
    use std::collections::BTreeMap;

    use super::*;

    #[test]
    fn room_words_name_one_type_each() {
        assert!(knowledge().types().len() >= 40);
        // No word names two types once tokenized (the registry checks the raw words).
        let mut seen = BTreeMap::new();
        for (w, t) in room_words() {
            if let Some(prev) = seen.insert(w.clone(), t.clone()) {
                panic!("{w:?} names both {prev} and {t}");
            }
        }
        assert_eq!(material_word("Hardwood"), Some("oak"));
        assert_eq!(material_word("marble"), Some("marble"));
        assert_eq!(kind("nonsense").role, Role::Public);
        assert_eq!(kind("kitchen").size.typical, [4.4, 3.6]);
    }
}
