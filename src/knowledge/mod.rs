//! What the built-in designer knows about rooms: per room type a size prior, default
//! materials, typical furniture with counts and a place rule each, wall and ceiling items,
//! and which surfaces carry which small objects how densely; plus room-independent defaults
//! (where a noun goes when the room type does not say, which seat goes with which table, what
//! goes on a parent).
//!
//! The data lives in `src/data/knowledge/*.json`, compiled in. This module loads and checks it
//! and answers lookups; it does not read prompts (see [`crate::prompt`]) or plan rooms (see
//! [`crate::stages::plan`]).

use std::collections::{BTreeMap, HashMap};
use std::fmt;
use std::sync::OnceLock;

use serde::{Deserialize, Serialize};

use crate::prompt::tokens::Token;

/// Where a piece goes (the `place` rule of a knowledge-base item).
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
#[serde(try_from = "String", into = "String")]
pub enum Place {
    /// Back against a free wall.
    AgainstWall,
    /// In a corner.
    Corner,
    /// In the open middle of the room.
    Center,
    /// Around a table-like parent, facing it (seats).
    Around(String),
    /// Facing another piece.
    Facing(String),
    /// In front of another piece (coffee table before the sofa).
    InFront(String),
    /// Behind another piece (shelves behind the bar counter).
    Behind(String),
    /// Next to another piece.
    Beside(String),
    /// One on each side of another piece (nightstands by the bed).
    Flanking(String),
    /// Under another piece (rug under the table).
    Under(String),
    /// Close to the window.
    NearWindow,
    /// Close to the entrance.
    NearEntrance,
    /// Across the room from something (`entrance`: the far wall).
    AcrossFrom(String),
    /// At the front of the room (teacher's desk, board).
    FrontOfRoom,
    /// Several in a row along one wall.
    RowAlongWall,
    /// Several in a grid filling the floor (desks of a classroom).
    Grid,
    /// Above another piece (wall and ceiling items).
    Above(String),
    /// Spread evenly (wall pictures, ceiling lights).
    Spread,
}

impl TryFrom<String> for Place {
    type Error = String;
    fn try_from(s: String) -> Result<Place, String> {
        let (kind, arg) = match s.split_once(':') {
            Some((k, a)) if !a.trim().is_empty() => (k.trim(), Some(a.trim().to_string())),
            Some((k, _)) => return Err(format!("place rule {k:?} needs a noun after ':'")),
            None => (s.trim(), None),
        };
        let need =
            |arg: Option<String>| arg.ok_or_else(|| format!("place rule {kind:?} needs ':<noun>'"));
        Ok(match kind {
            "against_wall" => Place::AgainstWall,
            "corner" => Place::Corner,
            "center" => Place::Center,
            "near_window" => Place::NearWindow,
            "near_entrance" => Place::NearEntrance,
            "front_of_room" => Place::FrontOfRoom,
            "row_along_wall" => Place::RowAlongWall,
            "grid" => Place::Grid,
            "spread" => Place::Spread,
            "around" => Place::Around(need(arg)?),
            "facing" => Place::Facing(need(arg)?),
            "in_front" => Place::InFront(need(arg)?),
            "behind" => Place::Behind(need(arg)?),
            "beside" => Place::Beside(need(arg)?),
            "flanking" => Place::Flanking(need(arg)?),
            "under" => Place::Under(need(arg)?),
            "across_from" => Place::AcrossFrom(need(arg)?),
            "above" => Place::Above(need(arg)?),
            other => return Err(format!("unknown place rule {other:?}")),
        })
    }
}

impl From<Place> for String {
    fn from(p: Place) -> String {
        p.to_string()
    }
}

impl fmt::Display for Place {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Place::AgainstWall => write!(f, "against_wall"),
            Place::Corner => write!(f, "corner"),
            Place::Center => write!(f, "center"),
            Place::NearWindow => write!(f, "near_window"),
            Place::NearEntrance => write!(f, "near_entrance"),
            Place::FrontOfRoom => write!(f, "front_of_room"),
            Place::RowAlongWall => write!(f, "row_along_wall"),
            Place::Grid => write!(f, "grid"),
            Place::Spread => write!(f, "spread"),
            Place::Around(n) => write!(f, "around:{n}"),
            Place::Facing(n) => write!(f, "facing:{n}"),
            Place::InFront(n) => write!(f, "in_front:{n}"),
            Place::Behind(n) => write!(f, "behind:{n}"),
            Place::Beside(n) => write!(f, "beside:{n}"),
            Place::Flanking(n) => write!(f, "flanking:{n}"),
            Place::Under(n) => write!(f, "under:{n}"),
            Place::AcrossFrom(n) => write!(f, "across_from:{n}"),
            Place::Above(n) => write!(f, "above:{n}"),
        }
    }
}

impl Place {
    /// The other object the rule refers to, if any (`entrance` is not an object).
    pub fn target(&self) -> Option<&str> {
        match self {
            Place::Around(n)
            | Place::Facing(n)
            | Place::InFront(n)
            | Place::Behind(n)
            | Place::Beside(n)
            | Place::Flanking(n)
            | Place::Under(n)
            | Place::Above(n) => Some(n),
            Place::AcrossFrom(n) if n != "entrance" => Some(n),
            _ => None,
        }
    }
}

/// One typical item of a room type.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct KbItem {
    /// Canonical noun (a lexicon noun).
    pub noun: String,
    /// How many: [min, max]; min 0 means optional.
    pub count: [u32; 2],
    /// Where it goes.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub place: Option<Place>,
    /// Mounting height of wall items (bottom edge... centre), metres.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub height: Option<f64>,
}

/// Which small objects go on (or in) one kind of parent, and how densely.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SurfaceRule {
    /// Parent noun ("bookshelf", "dining table").
    pub parent: String,
    /// Objects per parent: [min, max] (per seat when `place_settings`).
    pub count: [u32; 2],
    /// Candidate objects, most typical first.
    pub items: Vec<String>,
    /// Shelves: fraction of the shelf length to fill, [min, max].
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub fill: Option<[f64; 2]>,
    /// Lay the items out as one setting per seat (`count` is then the number of seats).
    #[serde(default)]
    pub place_settings: bool,
}

/// Everything known about one room type.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RoomType {
    /// Words naming the type.
    pub words: Vec<String>,
    /// Room type whose lists this one inherits where it gives none.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub extends: Option<String>,
    /// Clear floor size (x, y), metres.
    pub size: [f64; 2],
    /// Wall height, metres.
    pub wall_height: f64,
    /// Default floor material.
    pub floor: String,
    /// Default wall material.
    pub wall: String,
    /// Typical floor furniture.
    #[serde(default)]
    pub furniture: Vec<KbItem>,
    /// Typical wall-mounted items.
    #[serde(default)]
    pub wall_items: Vec<KbItem>,
    /// Typical ceiling items.
    #[serde(default)]
    pub ceiling: Vec<KbItem>,
    /// Small objects per parent.
    #[serde(default)]
    pub surfaces: Vec<SurfaceRule>,
}

impl RoomType {
    /// The room type's surface rule for a parent noun.
    pub fn surface_rule(&self, parent: &str) -> Option<&SurfaceRule> {
        self.surfaces.iter().find(|s| s.parent == parent)
    }

    /// The room type's item for a noun (any of furniture, wall, ceiling).
    pub fn item(&self, noun: &str) -> Option<&KbItem> {
        self.furniture
            .iter()
            .chain(&self.wall_items)
            .chain(&self.ceiling)
            .find(|i| i.noun == noun)
    }
}

#[derive(Debug, Deserialize)]
struct RoomFile {
    room_types: BTreeMap<String, RoomType>,
}

#[derive(Debug, Deserialize)]
struct ObjectFile {
    placement: BTreeMap<String, Place>,
    seats: BTreeMap<String, (String, u32)>,
    surfaces: Vec<SurfaceRule>,
}

/// Errors in the compiled-in knowledge base.
#[derive(Debug, thiserror::Error)]
pub enum KnowledgeError {
    /// A data file does not parse.
    #[error("knowledge file {file} does not parse: {source}")]
    Parse {
        /// Which file.
        file: &'static str,
        /// The JSON error.
        source: serde_json::Error,
    },
    /// A room type is defined twice.
    #[error("room type {0:?} is defined twice")]
    DuplicateType(String),
    /// A word names two room types.
    #[error("the word {word:?} names both {a:?} and {b:?}")]
    DuplicateWord {
        /// The word.
        word: String,
        /// First type.
        a: String,
        /// Second type.
        b: String,
    },
    /// `extends` names a missing type.
    #[error("room type {child:?} extends unknown type {parent:?}")]
    UnknownParent {
        /// The extending type.
        child: String,
        /// The missing parent.
        parent: String,
    },
}

/// The knowledge base.
#[derive(Debug, Default)]
pub struct Knowledge {
    rooms: BTreeMap<String, RoomType>,
    words: HashMap<String, String>,
    max_words: usize,
    placement: BTreeMap<String, Place>,
    seats: BTreeMap<String, (String, u32)>,
    surfaces: Vec<SurfaceRule>,
}

const ROOM_FILES: [(&str, &str); 3] = [
    (
        "knowledge/rooms_home.json",
        include_str!("../data/knowledge/rooms_home.json"),
    ),
    (
        "knowledge/rooms_work.json",
        include_str!("../data/knowledge/rooms_work.json"),
    ),
    (
        "knowledge/rooms_public.json",
        include_str!("../data/knowledge/rooms_public.json"),
    ),
];

impl Knowledge {
    /// Builds the knowledge base from room files (name, JSON) and the object file.
    pub fn parse(
        room_files: &[(&'static str, &str)],
        objects: &str,
    ) -> Result<Knowledge, KnowledgeError> {
        let mut rooms: BTreeMap<String, RoomType> = BTreeMap::new();
        for (file, text) in room_files {
            let f: RoomFile = serde_json::from_str(text)
                .map_err(|source| KnowledgeError::Parse { file, source })?;
            for (k, v) in f.room_types {
                if rooms.insert(k.clone(), v).is_some() {
                    return Err(KnowledgeError::DuplicateType(k));
                }
            }
        }
        // Inherit lists from the parent where the child gives none.
        let keys: Vec<String> = rooms.keys().cloned().collect();
        for k in &keys {
            let Some(parent) = rooms.get(k).and_then(|r| r.extends.clone()) else {
                continue;
            };
            let p = rooms
                .get(&parent)
                .cloned()
                .ok_or_else(|| KnowledgeError::UnknownParent {
                    child: k.clone(),
                    parent: parent.clone(),
                })?;
            if let Some(r) = rooms.get_mut(k) {
                if r.furniture.is_empty() {
                    r.furniture = p.furniture;
                }
                if r.wall_items.is_empty() {
                    r.wall_items = p.wall_items;
                }
                if r.ceiling.is_empty() {
                    r.ceiling = p.ceiling;
                }
                if r.surfaces.is_empty() {
                    r.surfaces = p.surfaces;
                }
            }
        }
        let mut words: HashMap<String, String> = HashMap::new();
        let mut max_words = 1;
        for (k, r) in &rooms {
            for w in &r.words {
                if let Some(a) = words.get(w) {
                    return Err(KnowledgeError::DuplicateWord {
                        word: w.clone(),
                        a: a.clone(),
                        b: k.clone(),
                    });
                }
                max_words = max_words.max(w.split(' ').count());
                words.insert(w.clone(), k.clone());
            }
        }
        let o: ObjectFile =
            serde_json::from_str(objects).map_err(|source| KnowledgeError::Parse {
                file: "knowledge/objects.json",
                source,
            })?;
        Ok(Knowledge {
            rooms,
            words,
            max_words,
            placement: o.placement,
            seats: o.seats,
            surfaces: o.surfaces,
        })
    }

    /// Every room type, by key.
    pub fn rooms(&self) -> &BTreeMap<String, RoomType> {
        &self.rooms
    }

    /// One room type.
    pub fn room(&self, key: &str) -> Option<&RoomType> {
        self.rooms.get(key)
    }

    /// The room type a word or phrase names ("exam room", "kitchenette").
    pub fn room_type_of(&self, words: &str) -> Option<&str> {
        self.words.get(words).map(String::as_str)
    }

    /// The longest room-type phrase starting at `tokens[at]`: (words used, type key). Plurals
    /// are read in the singular ("exam rooms").
    pub fn room_type_at(&self, tokens: &[Token], at: usize) -> Option<(usize, &str)> {
        let lex = crate::prompt::lexicon::lexicon();
        for len in (1..=self.max_words).rev() {
            let Some(words) = crate::prompt::lexicon::words_at(tokens, at, len) else {
                continue;
            };
            let raw = words.join(" ");
            if let Some(k) = self.words.get(&raw) {
                return Some((len, k));
            }
            let mut sing: Vec<String> = words.iter().map(|w| w.to_string()).collect();
            sing[len - 1] = lex.singular(words[len - 1]);
            if let Some(k) = self.words.get(&sing.join(" ")) {
                return Some((len, k));
            }
        }
        None
    }

    /// Default place of a noun when the room type does not list it.
    pub fn placement(&self, noun: &str) -> Option<&Place> {
        self.placement.get(noun)
    }

    /// The seat that goes with a table-like parent and how many per parent.
    pub fn seat_for(&self, parent: &str) -> Option<(&str, u32)> {
        self.seats.get(parent).map(|(s, n)| (s.as_str(), *n))
    }

    /// Room-independent surface rule of a parent noun.
    pub fn surface_rule(&self, parent: &str) -> Option<&SurfaceRule> {
        self.surfaces.iter().find(|s| s.parent == parent)
    }

    /// Every room-independent surface rule.
    pub fn surface_rules(&self) -> &[SurfaceRule] {
        &self.surfaces
    }

    /// Every default placement.
    pub fn placements(&self) -> &BTreeMap<String, Place> {
        &self.placement
    }

    /// Every seat rule.
    pub fn seats(&self) -> &BTreeMap<String, (String, u32)> {
        &self.seats
    }
}

/// The compiled-in knowledge base. A broken data file yields an empty base here; the test
/// `compiled_knowledge_parses` catches that before it ships.
pub fn knowledge() -> &'static Knowledge {
    static KB: OnceLock<Knowledge> = OnceLock::new();
    KB.get_or_init(|| {
        Knowledge::parse(&ROOM_FILES, include_str!("../data/knowledge/objects.json"))
            .unwrap_or_default()
    })
}

/// Parses the compiled-in data again, returning the error (for tests and `check` tools).
pub fn check_compiled() -> Result<Knowledge, KnowledgeError> {
    Knowledge::parse(&ROOM_FILES, include_str!("../data/knowledge/objects.json"))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::prompt::tokens::lex;

    #[test]
    fn compiled_knowledge_parses() {
        let kb = check_compiled().unwrap();
        assert!(kb.rooms().len() >= 60, "{} room types", kb.rooms().len());
    }

    #[test]
    fn place_rules_round_trip() {
        for s in [
            "against_wall",
            "around:dining table",
            "above:bed",
            "across_from:entrance",
            "grid",
        ] {
            let p = Place::try_from(s.to_string()).unwrap();
            assert_eq!(p.to_string(), s);
        }
        assert!(Place::try_from("around".to_string()).is_err());
        assert!(Place::try_from("sideways".to_string()).is_err());
        assert_eq!(Place::Around("table".into()).target(), Some("table"));
        assert_eq!(Place::AcrossFrom("entrance".into()).target(), None);
    }

    #[test]
    fn room_words_and_inheritance() {
        let kb = knowledge();
        let t = lex("two exam rooms and a kitchenette");
        assert_eq!(kb.room_type_at(&t, 1), Some((2, "exam_room")));
        assert_eq!(kb.room_type_at(&t, 5), Some((1, "kitchen")));
        // master_bedroom gives its own furniture but inherits surfaces from bedroom.
        let m = kb.room("master_bedroom").unwrap();
        assert!(m.surface_rule("nightstand").is_some());
        assert_eq!(kb.seat_for("dining table"), Some(("dining chair", 4)));
    }
}
