//! What the built-in designer knows about rooms: per room type a size range, default
//! materials, typical furniture with counts and a place rule each, wall and ceiling items,
//! and which surfaces carry which small objects how densely; plus room-independent defaults
//! (where a noun goes when the room type does not say, which seat goes with which table, what
//! goes on a parent).
//!
//! Room types live in the room registry ([`rooms`], one file per type under
//! `src/data/rooms/`), the room-independent defaults in `src/data/knowledge/objects.json`; both
//! are compiled in. This module loads and checks them and answers lookups; it does not read
//! prompts (`prompt` does) or plan rooms (the room plans do, `plan`).

pub mod rooms;

use std::collections::BTreeMap;
use std::fmt;
use std::sync::OnceLock;

use serde::{Deserialize, Serialize};

use crate::words::tokens::Token;

pub use rooms::{Registry, Role, RoomType, RoomsError, SizeRange};

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
    /// Objects put away inside the parent (in its drawers, behind its doors), most typical
    /// first; how many follows from the room the drawers and shelves have.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub inside: Vec<String>,
    /// Lay the items out as one setting per seat (`count` is then the number of seats).
    #[serde(default)]
    pub place_settings: bool,
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
    /// The room registry is broken.
    #[error(transparent)]
    Rooms(#[from] RoomsError),
    /// The object file does not parse.
    #[error("knowledge file knowledge/objects.json does not parse")]
    Objects(#[source] serde_json::Error),
}

/// The knowledge base.
#[derive(Debug, Default)]
pub struct Knowledge {
    rooms: Registry,
    placement: BTreeMap<String, Place>,
    seats: BTreeMap<String, (String, u32)>,
    surfaces: Vec<SurfaceRule>,
}

const OBJECTS: &str = include_str!("../data/knowledge/objects.json");

impl Knowledge {
    /// Builds the knowledge base from the room registry and the object file.
    pub fn parse(rooms: Registry, objects: &str) -> Result<Knowledge, KnowledgeError> {
        let o: ObjectFile = serde_json::from_str(objects).map_err(KnowledgeError::Objects)?;
        Ok(Knowledge {
            rooms,
            placement: o.placement,
            seats: o.seats,
            surfaces: o.surfaces,
        })
    }

    /// The room registry.
    pub fn registry(&self) -> &Registry {
        &self.rooms
    }

    /// Every room type, by key.
    pub fn rooms(&self) -> &BTreeMap<String, RoomType> {
        self.rooms.types()
    }

    /// One room type.
    pub fn room(&self, key: &str) -> Option<&RoomType> {
        self.rooms.get(key)
    }

    /// The room type a word or phrase names ("exam room", "kitchenette").
    pub fn room_type_of(&self, words: &str) -> Option<&str> {
        self.rooms.type_of(words)
    }

    /// The longest room-type phrase starting at `tokens[at]`: (words used, type key). Plurals
    /// are read in the singular ("exam rooms").
    pub fn room_type_at(&self, tokens: &[Token], at: usize) -> Option<(usize, &str)> {
        let lex = crate::words::lexicon::lexicon();
        for len in (1..=self.rooms.max_words()).rev() {
            let Some(words) = crate::words::lexicon::words_at(tokens, at, len) else {
                continue;
            };
            let raw = words.join(" ");
            if let Some(k) = self.rooms.type_of(&raw) {
                return Some((len, k));
            }
            let mut sing: Vec<String> = words.iter().map(|w| w.to_string()).collect();
            sing[len - 1] = lex.singular(words[len - 1]);
            if let Some(k) = self.rooms.type_of(&sing.join(" ")) {
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

/// The compiled-in knowledge base. Broken data yields an empty base here (logged); the test
/// `compiled_knowledge_parses` catches that before it ships.
pub fn knowledge() -> &'static Knowledge {
    static KB: OnceLock<Knowledge> = OnceLock::new();
    KB.get_or_init(|| {
        check_compiled().unwrap_or_else(|e| {
            let mut msg = e.to_string();
            let mut cause = std::error::Error::source(&e);
            while let Some(c) = cause {
                msg.push_str(&format!(": {c}"));
                cause = c.source();
            }
            tracing::error!("the compiled-in knowledge base does not load: {msg}");
            Knowledge::default()
        })
    })
}

/// Parses the compiled-in data again, returning the error (for tests and `check` tools).
pub fn check_compiled() -> Result<Knowledge, KnowledgeError> {
    Knowledge::parse(Registry::compiled()?, OBJECTS)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::words::tokens::lex;

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
