//! Spatial relations between a mention and what it is placed against: another mention, or a
//! part of the room (wall, corner, ceiling, floor, window, entrance, the room's middle).
//!
//! A relation is the preposition class from the lexicon normalised with its target ("in" +
//! "corner" is in the corner, "on" + "ceiling" hangs from it, "hangs" + "on the wall" is on the
//! wall). This module does not decide which mention a phrase attaches to (the interpreter
//! does).

use serde::{Deserialize, Serialize};

/// What kind of relation.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum RelationKind {
    /// Back against (the wall).
    Against,
    /// Along (one wall, the walls).
    Along,
    /// Inside (the bowl, the corner).
    In,
    /// On top of (the table), on (the wall, the floor).
    On,
    /// Under (the table).
    Under,
    /// Above (the bed), over.
    Above,
    /// Next to, beside.
    NextTo,
    /// Near, by, close to.
    Near,
    /// Behind.
    Behind,
    /// In front of.
    InFrontOf,
    /// Across from, opposite.
    AcrossFrom,
    /// Facing.
    Facing,
    /// Between two things (or between the members of a plural target).
    Between,
    /// Around (chairs around the table; from "surrounded by" too).
    Around,
    /// On each side of, flanking.
    Flanking,
    /// In the middle of the room.
    Center,
    /// At the front of.
    FrontOf,
    /// At the back of.
    BackOf,
    /// At the end or head of.
    EndOf,
    /// Hanging from (the ceiling).
    Hanging,
    /// Goes with ("a desk with a chair"): the designer decides the arrangement.
    With,
}

/// What a relation points at.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(tag = "kind", content = "mention", rename_all = "snake_case")]
pub enum Target {
    /// Another mention (index into `Reading::mentions`).
    Mention(usize),
    /// A wall (or the walls).
    Wall,
    /// A corner.
    Corner,
    /// The ceiling.
    Ceiling,
    /// The floor.
    Floor,
    /// A window.
    Window,
    /// The entrance or a door.
    Entrance,
    /// The room itself (its middle, front, back).
    Room,
    /// The members of the same mention ("facing each other").
    EachOther,
}

impl Target {
    /// The mention index, when the target is a mention.
    pub fn mention(self) -> Option<usize> {
        match self {
            Target::Mention(i) => Some(i),
            _ => None,
        }
    }
}

/// One spatial relation of a mention.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Relation {
    /// Kind.
    pub kind: RelationKind,
    /// Target.
    pub target: Target,
    /// Second target of "between X and Y".
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub second: Option<Target>,
    /// Which member of a plural target ("the other bin" is member 1).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub instance: Option<u32>,
    /// Part of the target ("level 1", "top level", "setting").
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub part: Option<String>,
    /// True when inferred from sentence structure ("a shelf with books" puts the books on the
    /// shelf) rather than said with a preposition; an explicit relation replaces it.
    #[serde(default)]
    pub implied: bool,
}

impl Relation {
    /// An explicit relation.
    pub fn new(kind: RelationKind, target: Target) -> Relation {
        Relation {
            kind,
            target,
            second: None,
            instance: None,
            part: None,
            implied: false,
        }
    }

    /// True when the relation puts the object on or in another object (a support relation).
    pub fn is_support(&self) -> bool {
        matches!(self.kind, RelationKind::On | RelationKind::In)
            && matches!(self.target, Target::Mention(_))
    }
}

/// The target a landmark class names (`wall`, `corner`, ...), or None for object nouns.
pub(crate) fn landmark_target(class: &str) -> Option<Target> {
    Some(match class {
        "wall" | "walls" => Target::Wall,
        "corner" => Target::Corner,
        "ceiling" => Target::Ceiling,
        "floor" => Target::Floor,
        "window" => Target::Window,
        "door" | "entrance" => Target::Entrance,
        "room" | "center" | "front" | "back" | "side" | "end" => Target::Room,
        _ => return None,
    })
}

/// Normalises a preposition class (from the lexicon), the landmark class of its object (if
/// the object is a landmark) and the clause's verb class into a relation kind and target.
/// Returns None for prepositions that carry no placement ("from" without a ceiling, "at" a
/// noun).
pub(crate) fn normalize(
    prep: &str,
    landmark: Option<&str>,
    verb: Option<&str>,
    target: Target,
) -> Option<(RelationKind, Target)> {
    use RelationKind as K;
    let lm = landmark.unwrap_or("");
    // The room's middle, front and back, however they are introduced.
    match (prep, lm) {
        ("center_of", _) | ("in" | "at" | "on" | "to", "center") => {
            return Some((K::Center, Target::Room));
        }
        ("front_of", _) | ("in" | "at" | "to", "front") => return Some((K::FrontOf, Target::Room)),
        ("back_of", _) | ("in" | "at" | "to", "back") => return Some((K::BackOf, Target::Room)),
        ("end_of", "room") | ("at" | "in", "end") => return Some((K::EndOf, Target::Room)),
        _ => {}
    }
    if target == Target::Ceiling && matches!(prep, "from" | "on" | "in" | "to") {
        return Some((K::Hanging, Target::Ceiling));
    }
    let kind = match prep {
        "against" => K::Against,
        "along" => K::Along,
        "in" => K::In,
        "on" => K::On,
        "under" => K::Under,
        "above" => K::Above,
        "next_to" => K::NextTo,
        "near" | "by" => K::Near,
        "behind" => K::Behind,
        "in_front_of" | "in_front" => K::InFrontOf,
        "across_from" => K::AcrossFrom,
        "facing" => K::Facing,
        "between" => K::Between,
        "around" => K::Around,
        "flanking" | "each_side" => K::Flanking,
        "end_of" => K::EndOf,
        "at" => match target {
            Target::Corner => K::In,
            Target::Wall => K::Against,
            Target::Window | Target::Entrance => K::Near,
            Target::Mention(_) => K::Near,
            _ => return None,
        },
        "from" => return None,
        _ => return None,
    };
    // "hangs on the wall", "mounted on the wall" are on the wall; "leans against" is against.
    let kind = match (kind, verb) {
        (K::In, _) if target == Target::Wall => K::On,
        (K::Near | K::NextTo, Some("hang")) if target == Target::Ceiling => K::Hanging,
        (k, _) => k,
    };
    Some((kind, target))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn landmarks_normalise() {
        assert_eq!(
            normalize("in", Some("corner"), None, Target::Corner),
            Some((RelationKind::In, Target::Corner))
        );
        assert_eq!(
            normalize("center_of", Some("room"), None, Target::Room),
            Some((RelationKind::Center, Target::Room))
        );
        assert_eq!(
            normalize("in", Some("center"), None, Target::Room),
            Some((RelationKind::Center, Target::Room))
        );
        assert_eq!(
            normalize("from", Some("ceiling"), Some("hang"), Target::Ceiling),
            Some((RelationKind::Hanging, Target::Ceiling))
        );
        assert_eq!(
            normalize("by", Some("door"), None, Target::Entrance),
            Some((RelationKind::Near, Target::Entrance))
        );
        assert_eq!(
            normalize("back_of", Some("room"), None, Target::Room),
            Some((RelationKind::BackOf, Target::Room))
        );
        assert_eq!(normalize("from", None, None, Target::Mention(2)), None);
    }
}
