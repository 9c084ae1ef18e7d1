//! The room registry: every room type defined once, in its own file
//! `src/data/rooms/<type>.json` (words naming it, circulation role, size range, materials,
//! windows, adjacency, default contents), and the house-level tables that are about no single
//! type in `src/data/rooms/_house.json`. `src/data/rooms/README.md` says what each field means.
//!
//! This module owns parsing and checking that data. The prompt reader and the stage plans read
//! it through [`crate::knowledge::knowledge`], the layout through its own `layout::knowledge`;
//! neither keeps a table of its own.

use std::collections::{BTreeMap, HashMap};

use serde::{Deserialize, Serialize};

use super::{KbItem, SurfaceRule};

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

/// Clear interior sizes `[long, short]` of a room type, metres.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SizeRange {
    /// Smallest the type is laid out ("a small ..." in a small house).
    pub min: [f64; 2],
    /// The size a room of the type starts from.
    pub typical: [f64; 2],
    /// Largest the size words make it (contents and hub growth may exceed it).
    pub max: [f64; 2],
}

impl SizeRange {
    /// The typical size scaled by `scale` (size words), kept inside the range.
    pub fn scaled(&self, scale: f64) -> [f64; 2] {
        [0, 1].map(|i| (self.typical[i] * scale).clamp(self.min[i], self.max[i]))
    }
}

/// A type's wish to be next to another type.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct AdjacencyRule {
    /// Types it should be next to (the first present one counts).
    pub next_to: Vec<String>,
    /// Required (a door between them) or only preferred (a shared wall is a plus).
    pub required: bool,
}

/// Everything known about one room type: one file of `src/data/rooms/`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RoomType {
    /// Words naming the type (lower case, singular).
    pub words: Vec<String>,
    /// Circulation role.
    pub role: Role,
    /// Clear interior size range `[long, short]`, metres.
    pub size: SizeRange,
    /// Narrowest usable side, metres.
    pub min_side: f64,
    /// Wall height of the type as a single room, metres.
    pub wall_height: f64,
    /// Default floor material (a name of `materials.json`).
    pub floor: String,
    /// Default wall material.
    pub wall: String,
    /// Whether the room wants windows.
    pub windows: bool,
    /// Window sill height, metres.
    pub sill: f64,
    /// Types this one should be next to.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub adjacency: Vec<AdjacencyRule>,
    /// Room type whose lists this one inherits where it gives none.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub extends: Option<String>,
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

/// Tables about a whole house rather than one room type (`_house.json`).
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct HouseTables {
    /// Nouns naming a whole building ("apartment", "hotel").
    pub house_nouns: Vec<String>,
    /// Words after a room word that make it a modifier ("bar counter", "office chair").
    pub not_room_after: Vec<String>,
    /// Room types people enter a house through when there is no entry or hub room, best
    /// first.
    pub entrance_preference: Vec<String>,
    /// Object noun -> room types it belongs in, best first.
    pub items_to_rooms: BTreeMap<String, Vec<String>>,
    /// Material words -> material table names.
    pub materials: BTreeMap<String, String>,
    /// Floor materials that suit wet rooms.
    pub wet_floor_materials: Vec<String>,
    /// Style words that apply to a whole house.
    pub style_words: Vec<String>,
    /// Short words that count rooms of a type after a number ("3-bed, 2-bath"), as
    /// word -> room type.
    #[serde(default)]
    pub count_words: BTreeMap<String, String>,
    /// Storage and display pieces a room of each role gets, in this order, while the pieces
    /// it plans hold too few small objects for its usual clutter (a music room of a piano, a
    /// drum kit and guitar stands; see `plan::STORAGE_FLOOR`). A noun may repeat: one more of
    /// it.
    #[serde(default)]
    pub clutter_storage: BTreeMap<Role, Vec<String>>,
}

/// Errors in the room data.
#[derive(Debug, thiserror::Error)]
pub enum RoomsError {
    /// A data file does not parse (unknown field, bad role, bad place rule, ...).
    #[error("room data file {file} does not parse")]
    Parse {
        /// Which file, relative to `src/data/`.
        file: String,
        /// The JSON error.
        source: serde_json::Error,
    },
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
    /// A field names a room type that has no file.
    #[error("{owner}: {field} names unknown room type {name:?}")]
    UnknownType {
        /// The type (or `_house`) whose field it is.
        owner: String,
        /// The field.
        field: &'static str,
        /// The missing type.
        name: String,
    },
    /// A value is out of its range or empty.
    #[error("{owner}: {detail}")]
    Invalid {
        /// The type (or `_house`) at fault.
        owner: String,
        /// What is wrong.
        detail: String,
    },
}

/// The parsed and checked room registry.
#[derive(Debug, Default)]
pub struct Registry {
    types: BTreeMap<String, RoomType>,
    house: HouseTables,
    words: HashMap<String, String>,
    max_words: usize,
}

/// `(type, file text)` of every type file, the type being the file name. Without a build
/// script the list is explicit; `every_room_file_is_compiled_in` fails when a file of the
/// directory is missing here.
macro_rules! room_files {
    ($($t:literal),* $(,)?) => {
        &[$(($t, include_str!(concat!("../data/rooms/", $t, ".json")))),*]
    };
}

/// Every compiled-in room type file.
pub const ROOM_FILES: &[(&str, &str)] = room_files![
    "art_gallery",
    "artist_studio",
    "attic",
    "bakery",
    "bar",
    "barber_shop",
    "basement",
    "bathroom",
    "bedroom",
    "bookstore",
    "break_room",
    "cafe",
    "classroom",
    "closet",
    "clothing_store",
    "common_room",
    "computer_lab",
    "conference_room",
    "corridor",
    "dance_studio",
    "daycare",
    "dining_room",
    "dorm_room",
    "en_suite",
    "entryway",
    "exam_room",
    "florist",
    "furniture_showroom",
    "gaming_room",
    "garage",
    "grocery_store",
    "guest_bedroom",
    "gym",
    "hallway",
    "home_office",
    "home_theater",
    "hospital_room",
    "hotel_lobby",
    "hotel_room",
    "kids_bedroom",
    "kitchen",
    "laundromat",
    "laundry_room",
    "library",
    "living_kitchen",
    "living_room",
    "locker_room",
    "lounge",
    "master_bedroom",
    "meeting_room",
    "museum_room",
    "music_room",
    "nursery",
    "office",
    "open_office",
    "pantry",
    "pet_grooming_salon",
    "pet_store",
    "pharmacy",
    "playroom",
    "pottery_store",
    "private_office",
    "reception",
    "restaurant",
    "robotics_lab",
    "room",
    "science_lab",
    "server_room",
    "shop",
    "storage_room",
    "studio_apartment",
    "study_room",
    "sunroom",
    "teen_bedroom",
    "toy_store",
    "waiting_room",
    "wine_cellar",
    "workout_area",
    "workshop",
    "xray_room",
    "yoga_room",
];

/// The compiled-in house-level tables.
pub const HOUSE_FILE: &str = include_str!("../data/rooms/_house.json");

fn invalid(owner: &str, detail: String) -> RoomsError {
    RoomsError::Invalid {
        owner: owner.to_string(),
        detail,
    }
}

impl Registry {
    /// Parses and checks type files `(type, JSON)` and the house tables.
    pub fn parse(files: &[(&str, &str)], house: &str) -> Result<Registry, RoomsError> {
        let mut types: BTreeMap<String, RoomType> = BTreeMap::new();
        for (key, text) in files {
            let t: RoomType = serde_json::from_str(text).map_err(|source| RoomsError::Parse {
                file: format!("rooms/{key}.json"),
                source,
            })?;
            let key_ok = !key.is_empty()
                && !key.starts_with('_')
                && key.chars().all(|c| c.is_ascii_lowercase() || c == '_');
            if !key_ok {
                return Err(invalid(key, "a type name is lower-case snake case".into()));
            }
            if types.insert(key.to_string(), t).is_some() {
                return Err(invalid(key, "listed twice".into()));
            }
        }
        inherit(&mut types)?;
        for (key, t) in &types {
            check_type(key, t, &types)?;
        }
        let mut words: HashMap<String, String> = HashMap::new();
        // Words as the tokenizer splits them ("manager's office" and "manager office" read
        // the same): one type each too.
        let mut tokenized: HashMap<String, String> = HashMap::new();
        let mut max_words = 1;
        for (key, t) in &types {
            for w in &t.words {
                let toks = crate::words::tokenize(w).join(" ");
                let clash = words
                    .get(w)
                    .or_else(|| tokenized.get(&toks).filter(|a| *a != key));
                if let Some(a) = clash {
                    return Err(RoomsError::DuplicateWord {
                        word: w.clone(),
                        a: a.clone(),
                        b: key.clone(),
                    });
                }
                max_words = max_words.max(w.split(' ').count());
                words.insert(w.clone(), key.clone());
                tokenized.insert(toks, key.clone());
            }
        }
        let house: HouseTables =
            serde_json::from_str(house).map_err(|source| RoomsError::Parse {
                file: "rooms/_house.json".into(),
                source,
            })?;
        check_house(&house, &types)?;
        Ok(Registry {
            types,
            house,
            words,
            max_words,
        })
    }

    /// Parses the compiled-in data.
    pub fn compiled() -> Result<Registry, RoomsError> {
        Registry::parse(ROOM_FILES, HOUSE_FILE)
    }

    /// Every room type, by key.
    pub fn types(&self) -> &BTreeMap<String, RoomType> {
        &self.types
    }

    /// One room type.
    pub fn get(&self, key: &str) -> Option<&RoomType> {
        self.types.get(key)
    }

    /// The house-level tables.
    pub fn house(&self) -> &HouseTables {
        &self.house
    }

    /// Every adjacency rule with the type it belongs to, in type order.
    pub fn adjacency(&self) -> impl Iterator<Item = (&str, &AdjacencyRule)> {
        self.types
            .iter()
            .flat_map(|(k, t)| t.adjacency.iter().map(move |r| (k.as_str(), r)))
    }

    /// The type a word or phrase names exactly ("exam room").
    pub fn type_of(&self, words: &str) -> Option<&str> {
        self.words.get(words).map(String::as_str)
    }

    /// Whether a room of type `ty` is a `key`: the same type, or one that extends it.
    pub fn is_a(&self, ty: &str, key: &str) -> bool {
        ty == key || self.get(ty).and_then(|t| t.extends.as_deref()) == Some(key)
    }

    /// Most words in one room phrase.
    pub fn max_words(&self) -> usize {
        self.max_words
    }
}

/// Copies the parent's lists into a child that gives none. One level: a parent may not
/// extend another type.
fn inherit(types: &mut BTreeMap<String, RoomType>) -> Result<(), RoomsError> {
    let children: Vec<(String, String)> = types
        .iter()
        .filter_map(|(k, t)| t.extends.clone().map(|p| (k.clone(), p)))
        .collect();
    for (child, parent) in children {
        let p = types
            .get(&parent)
            .cloned()
            .ok_or_else(|| RoomsError::UnknownType {
                owner: child.clone(),
                field: "extends",
                name: parent.clone(),
            })?;
        if p.extends.is_some() {
            return Err(invalid(
                &child,
                format!("extends {parent:?}, which extends another type"),
            ));
        }
        if let Some(c) = types.get_mut(&child) {
            if c.furniture.is_empty() {
                c.furniture = p.furniture;
            }
            if c.wall_items.is_empty() {
                c.wall_items = p.wall_items;
            }
            if c.ceiling.is_empty() {
                c.ceiling = p.ceiling;
            }
            if c.surfaces.is_empty() {
                c.surfaces = p.surfaces;
            }
        }
    }
    Ok(())
}

fn check_type(
    key: &str,
    t: &RoomType,
    types: &BTreeMap<String, RoomType>,
) -> Result<(), RoomsError> {
    let bad = |detail: String| Err(invalid(key, detail));
    if t.words.is_empty() {
        return bad("no words".into());
    }
    for (i, w) in t.words.iter().enumerate() {
        if w.trim() != w || w.is_empty() || w.to_lowercase() != *w {
            return bad(format!("word {w:?} is not trimmed lower case"));
        }
        if t.words[..i].contains(w) {
            return bad(format!("word {w:?} listed twice"));
        }
    }
    let s = &t.size;
    for (name, v) in [("min", s.min), ("typical", s.typical), ("max", s.max)] {
        if !(v[1] > 0.0 && v[0] >= v[1] && v[0].is_finite()) {
            return bad(format!("size {name} {v:?} is not [long, short] > 0"));
        }
    }
    if (0..2).any(|i| !(s.min[i] <= s.typical[i] && s.typical[i] <= s.max[i])) {
        return bad(format!(
            "size needs min <= typical <= max, got {:?} {:?} {:?}",
            s.min, s.typical, s.max
        ));
    }
    if !(t.min_side > 0.0 && t.min_side <= s.min[1]) {
        return bad(format!(
            "min_side {} outside (0, size.min short side {}]",
            t.min_side, s.min[1]
        ));
    }
    if !(2.2..=6.0).contains(&t.wall_height) {
        return bad(format!("wall_height {} outside 2.2..6 m", t.wall_height));
    }
    if !(0.0..t.wall_height).contains(&t.sill) {
        return bad(format!("sill {} outside the wall", t.sill));
    }
    for rule in &t.adjacency {
        if rule.next_to.is_empty() {
            return bad("an adjacency rule names no type".into());
        }
        for b in &rule.next_to {
            if b == key || !types.contains_key(b) {
                return Err(RoomsError::UnknownType {
                    owner: key.into(),
                    field: "adjacency",
                    name: b.clone(),
                });
            }
        }
    }
    for (list, items) in [
        ("furniture", &t.furniture),
        ("wall_items", &t.wall_items),
        ("ceiling", &t.ceiling),
    ] {
        for item in items {
            if item.noun.trim().is_empty() {
                return bad(format!("an item of {list} has an empty noun"));
            }
            if item.count[0] > item.count[1] {
                return bad(format!("{list} {}: count {:?}", item.noun, item.count));
            }
        }
    }
    for rule in &t.surfaces {
        let empty = rule.parent.trim().is_empty()
            || rule.items.is_empty()
            || rule.items.iter().any(|i| i.trim().is_empty());
        if empty || rule.count[0] > rule.count[1] {
            return bad(format!(
                "surface rule of {:?} is empty or its count is reversed",
                rule.parent
            ));
        }
    }
    Ok(())
}

fn check_house(h: &HouseTables, types: &BTreeMap<String, RoomType>) -> Result<(), RoomsError> {
    let known = |field: &'static str, name: &String| {
        if types.contains_key(name) {
            Ok(())
        } else {
            Err(RoomsError::UnknownType {
                owner: "_house".into(),
                field,
                name: name.clone(),
            })
        }
    };
    for t in &h.entrance_preference {
        known("entrance_preference", t)?;
    }
    for t in h
        .items_to_rooms
        .values()
        .flatten()
        .chain(h.count_words.values())
    {
        known("items_to_rooms or count_words", t)?;
    }
    Ok(())
}

/// The compiled-in registry (empty when the data is broken, which
/// `compiled_registry_is_valid` forbids).
pub fn registry() -> &'static Registry {
    super::knowledge().registry()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn compiled_registry_is_valid() {
        let r = Registry::compiled().unwrap();
        assert_eq!(r.types().len(), ROOM_FILES.len());
        assert!(r.get("room").is_some(), "the generic fallback type");
    }

    #[test]
    fn every_room_file_is_compiled_in() {
        let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/src/data/rooms");
        let mut on_disk: Vec<String> = std::fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .filter_map(|n| n.strip_suffix(".json").map(str::to_string))
            .filter(|n| !n.starts_with('_'))
            .collect();
        on_disk.sort();
        let listed: Vec<String> = ROOM_FILES.iter().map(|(k, _)| k.to_string()).collect();
        assert_eq!(on_disk, listed, "ROOM_FILES must list every file, sorted");
    }

    #[test]
    fn broken_data_names_the_file_and_the_fault() {
        let good = ROOM_FILES.iter().find(|(k, _)| *k == "room").unwrap().1;
        let e = Registry::parse(&[("room", "{\"words\": []}")], HOUSE_FILE).unwrap_err();
        assert!(e.to_string().contains("rooms/room.json"), "{e}");
        let twice = [("room", good), ("room_two", good)];
        assert!(matches!(
            Registry::parse(&twice, HOUSE_FILE),
            Err(RoomsError::DuplicateWord { .. })
        ));
        let reversed = good.replace("\"typical\": [4.2, 3.6]", "\"typical\": [9.9, 3.6]");
        assert_ne!(reversed, good, "the test edits the generic room's size");
        let e = Registry::parse(&[("room", &reversed)], HOUSE_FILE).unwrap_err();
        assert!(e.to_string().contains("min <= typical <= max"), "{e}");
        let place = good.replacen("\"center\"", "\"sideways\"", 1);
        let e = Registry::parse(&[("room", &place)], HOUSE_FILE).unwrap_err();
        assert!(matches!(e, RoomsError::Parse { .. }), "{e}");
        let adj = good.replacen(
            "\"sill\": 0.9",
            "\"sill\": 0.9, \"adjacency\": [{\"next_to\": [\"nowhere\"], \"required\": true}]",
            1,
        );
        let e = Registry::parse(&[("room", &adj)], HOUSE_FILE).unwrap_err();
        assert!(matches!(e, RoomsError::UnknownType { .. }), "{e}");
    }

    #[test]
    fn scaled_sizes_stay_in_range() {
        let r = Registry::compiled().unwrap();
        let k = r.get("kitchen").unwrap();
        assert_eq!(k.size.scaled(1.0), k.size.typical);
        let tiny = k.size.scaled(0.1);
        assert_eq!(tiny, k.size.min);
        assert_eq!(k.size.scaled(10.0), k.size.max);
    }
}
