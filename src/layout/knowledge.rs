//! Layout knowledge compiled in from `src/data/layout_rooms.json`: per room type its role in the
//! circulation graph, size prior, materials and windows; adjacency rules between types; the
//! words that tell room mentions from object nouns; where unassigned objects go; material words.
//!
//! This is data only. Reading a prompt into rooms is [`super::brief`]; turning rooms into
//! sizes and connectivity requirements is [`super::spec`].

use std::collections::BTreeMap;
use std::sync::OnceLock;

use serde::{Deserialize, Serialize};

/// The part a room plays in how people move through a house.
#[derive(
    Debug,
    Clone,
    Copy,
    PartialEq,
    Eq,
    Serialize,
    Deserialize,
    PartialOrd,
    Ord,
    Hash,
    schemars::JsonSchema,
)]
#[serde(rename_all = "snake_case")]
pub enum Role {
    /// Corridor or hallway: every other room may open onto it.
    Hub,
    /// Reception or lobby: where people come in.
    Entry,
    /// A shared room people walk through (living room, kitchen, restaurant).
    Public,
    /// A room people go to, not through (bedroom, office).
    Private,
    /// A bathroom: a leaf, never passed through.
    Wet,
    /// Storage and technical rooms: leaves without windows by default.
    Service,
}

impl Role {
    /// Whether people may walk through a room of this role to reach another room.
    pub fn passable(self) -> bool {
        matches!(self, Role::Hub | Role::Entry | Role::Public)
    }

    /// `hub`, `entry`, ...
    pub fn as_str(self) -> &'static str {
        match self {
            Role::Hub => "hub",
            Role::Entry => "entry",
            Role::Public => "public",
            Role::Private => "private",
            Role::Wet => "wet",
            Role::Service => "service",
        }
    }
}

/// What the layout knows about one room type.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct RoomKind {
    /// Circulation role.
    pub role: Role,
    /// Typical clear interior size `[long, short]`, metres.
    pub size: [f64; 2],
    /// Smallest usable side, metres.
    pub min_side: f64,
    /// Default floor material (a name of the material table).
    pub floor: String,
    /// Default wall material.
    pub wall: String,
    /// Whether the room wants windows.
    pub windows: bool,
    /// Window sill height, metres.
    pub sill: f64,
    /// Words naming the type (lower case, space separated).
    pub words: Vec<String>,
}

/// An adjacency rule: a room of type `a` next to one of the types `b`.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct AdjacencyRule {
    /// The type the rule is about.
    pub a: String,
    /// Types it should be next to (the first present one counts).
    pub b: Vec<String>,
    /// Required (a door between them) or only preferred (shared wall).
    pub required: bool,
}

/// The whole table.
#[derive(Debug, Clone, Deserialize)]
pub struct Knowledge {
    /// Room types by key.
    pub room_types: BTreeMap<String, RoomKind>,
    /// Adjacency rules.
    pub adjacency: Vec<AdjacencyRule>,
    /// Room types people enter a house through when there is no reception or hallway, best
    /// first.
    pub entrance_preference: Vec<String>,
    /// Nouns naming a whole building ("apartment", "hotel").
    pub house_nouns: Vec<String>,
    /// Words after a room word that make it a modifier ("bar counter", "office chair").
    pub not_room_after: Vec<String>,
    /// Object noun -> room types it belongs in, best first.
    pub items_to_rooms: BTreeMap<String, Vec<String>>,
    /// Material words -> material table names.
    pub materials: BTreeMap<String, String>,
    /// Floor materials that suit wet rooms.
    pub wet_floor_materials: Vec<String>,
    /// Style words that apply to a whole house.
    pub style_words: Vec<String>,
}

/// The layout knowledge table.
pub fn knowledge() -> &'static Knowledge {
    static TABLE: OnceLock<Knowledge> = OnceLock::new();
    TABLE.get_or_init(|| {
        // Shipped data, checked by a unit test: a parse error is a bug in the build.
        serde_json::from_str::<Knowledge>(include_str!("../data/layout_rooms.json")).unwrap_or(
            Knowledge {
                room_types: BTreeMap::new(),
                adjacency: Vec::new(),
                entrance_preference: Vec::new(),
                house_nouns: Vec::new(),
                not_room_after: Vec::new(),
                items_to_rooms: BTreeMap::new(),
                materials: BTreeMap::new(),
                wet_floor_materials: Vec::new(),
                style_words: Vec::new(),
            },
        )
    })
}

/// The generic room every unknown type falls back to.
pub fn fallback_kind() -> RoomKind {
    knowledge()
        .room_types
        .get("room")
        .cloned()
        .unwrap_or(RoomKind {
            role: Role::Public,
            size: [4.2, 3.6],
            min_side: 2.6,
            floor: "oak".into(),
            wall: "plaster".into(),
            windows: true,
            sill: 0.9,
            words: vec!["room".into()],
        })
}

/// The knowledge of `room_type`, or the generic room.
pub fn kind(room_type: &str) -> RoomKind {
    knowledge()
        .room_types
        .get(room_type)
        .cloned()
        .unwrap_or_else(fallback_kind)
}

/// Every room word as token lists with its type, longest first.
pub fn room_words() -> &'static [(Vec<String>, String)] {
    static WORDS: OnceLock<Vec<(Vec<String>, String)>> = OnceLock::new();
    WORDS.get_or_init(|| {
        let mut out: Vec<(Vec<String>, String)> = knowledge()
            .room_types
            .iter()
            .flat_map(|(key, k)| {
                k.words
                    .iter()
                    .map(move |w| (crate::prompt::tokenize(w), key.clone()))
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
    use super::*;

    #[test]
    fn table_loads_and_is_consistent() {
        let k = knowledge();
        assert!(
            k.room_types.len() >= 40,
            "{} room types",
            k.room_types.len()
        );
        for (key, r) in &k.room_types {
            assert!(r.size[0] >= r.size[1], "{key}: size is [long, short]");
            assert!(r.min_side <= r.size[1], "{key}: min side above the prior");
            for m in [&r.floor, &r.wall] {
                assert!(
                    crate::assets::material::material(m).is_some(),
                    "{key}: unknown material {m}"
                );
            }
        }
        for rule in &k.adjacency {
            assert!(k.room_types.contains_key(&rule.a), "{}", rule.a);
            for b in &rule.b {
                assert!(k.room_types.contains_key(b), "{b}");
            }
        }
        for t in &k.entrance_preference {
            assert!(k.room_types.contains_key(t), "{t}");
        }
        for (item, types) in &k.items_to_rooms {
            for t in types {
                assert!(k.room_types.contains_key(t), "{item}: {t}");
            }
        }
        for m in k.materials.values().chain(&k.wet_floor_materials) {
            assert!(crate::assets::material::material(m).is_some(), "{m}");
        }
        // No word names two types.
        let mut seen = BTreeMap::new();
        for (w, t) in room_words() {
            if let Some(prev) = seen.insert(w.clone(), t.clone()) {
                panic!("{w:?} names both {prev} and {t}");
            }
        }
        assert_eq!(material_word("Hardwood"), Some("oak"));
        assert_eq!(material_word("marble"), Some("marble"));
        assert_eq!(kind("nonsense").role, Role::Public);
    }
}
