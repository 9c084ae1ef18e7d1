//! Object mentions and their counts: "two nightstands", "at least 10 cans", "exactly 5 pairs
//! of shoes", "a stack of 8 books", "each with a chair" (a count per parent), "a table set for
//! 4 people" (place settings).
//!
//! This module holds the types and the count arithmetic; the chunker reads the words and the
//! interpreter decides what a count is relative to.

use serde::{Deserialize, Serialize};

use super::attributes::Attributes;
use super::relations::Relation;
use crate::words::lexicon::Support;

/// How many of something the prompt asks for.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(tag = "kind", content = "n", rename_all = "snake_case")]
pub enum Count {
    /// "exactly five", or a plain number ("two chairs", "a chair"). "up to three" and "about
    /// three" read as three.
    Exactly(u32),
    /// "at least ten", "10+", "more than nine".
    AtLeast(u32),
    /// A plural without a number ("chairs", "some books", "multiple").
    Several,
}

impl Count {
    /// The smallest number that satisfies the count.
    pub fn minimum(self) -> u32 {
        match self {
            Count::Exactly(n) | Count::AtLeast(n) => n,
            Count::Several => 2,
        }
    }

    /// The count multiplied by `k` parents (a per-parent count made total).
    pub fn times(self, k: Count) -> Count {
        match (self, k) {
            (Count::Several, _) | (_, Count::Several) => Count::Several,
            (Count::Exactly(a), Count::Exactly(b)) => Count::Exactly(a.saturating_mul(b)),
            (Count::Exactly(a) | Count::AtLeast(a), Count::Exactly(b) | Count::AtLeast(b)) => {
                Count::AtLeast(a.saturating_mul(b))
            }
        }
    }

    /// True for "at least".
    pub fn is_at_least(self) -> bool {
        matches!(self, Count::AtLeast(_))
    }
}

/// A group the objects form.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum GroupKind {
    /// "a stack of", "stacked".
    Stack,
    /// "a pile of", "piled", "a heap of".
    Pile,
    /// "a mix of apples and oranges".
    Mix,
    /// "a row of".
    Row,
    /// "pairs of shoes" (the count is in single objects).
    Pair,
    /// "a set of".
    Set,
    /// "a mess of dishes".
    Mess,
    /// "a sofa and coffee table arrangement".
    Arrangement,
}

impl GroupKind {
    /// Group kind of a lexicon group class.
    pub(crate) fn from_class(class: &str) -> Option<GroupKind> {
        Some(match class {
            "stack" => GroupKind::Stack,
            "pile" => GroupKind::Pile,
            "mix" => GroupKind::Mix,
            "row" => GroupKind::Row,
            "pair" => GroupKind::Pair,
            "set" => GroupKind::Set,
            "mess" => GroupKind::Mess,
            _ => return None,
        })
    }
}

/// Membership in a group; mentions of one group share the id.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub struct Group {
    /// Kind.
    pub kind: GroupKind,
    /// Group id, unique within the reading.
    pub id: u32,
}

/// What a count is relative to.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum Per {
    /// Per instance of another mention ("six desks, each with a chair").
    Each {
        /// The parent mention.
        parent: usize,
    },
    /// Per place setting of a table ("each setting has a plate").
    Setting {
        /// The table mention.
        table: usize,
    },
}

/// One object the prompt names (or excludes).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Mention {
    /// Canonical noun: singular, lower case ("coffee table", "nightstand", "wine glass"); for
    /// nouns the lexicon does not know, the noun as written in the singular.
    pub category: String,
    /// The noun as written, singular ("bedside table").
    pub noun: String,
    /// How many (per parent when `per` is set).
    pub count: Count,
    /// True for "no TV", "without a rug".
    pub negated: bool,
    /// True when the lexicon knows `category`.
    #[serde(default)]
    pub known: bool,
    /// For an unknown compound ("produce crate"), the lexicon noun of its head ("crate").
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub head: Option<String>,
    /// Where it stands (lexicon default, overridden by the prompt's relations).
    pub support: Support,
    /// Holds things inside.
    #[serde(default)]
    pub container: bool,
    /// Names a class (fruit, supplies) rather than a thing.
    #[serde(default)]
    pub generic: bool,
    /// Colours, materials, styles, features.
    #[serde(default)]
    pub attributes: Attributes,
    /// Spatial relations.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub relations: Vec<Relation>,
    /// What the count is relative to.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub per: Option<Per>,
    /// Group membership.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub group: Option<Group>,
    /// Tables: number of place settings ("set for 4 people"), per table when `per_table`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub place_settings: Option<u32>,
    /// Generic mentions: the specific mentions they count together ("at least 6 fruits"
    /// covering the apples and oranges in the same bowl).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub covers: Vec<usize>,
    /// Room index (into `Reading::rooms`).
    #[serde(default)]
    pub room: usize,
    /// Byte span of the noun phrase in the prompt.
    pub span: [usize; 2],
    /// Introduced with "the" without an earlier mention ("rests on the nightstand").
    #[serde(default)]
    pub definite: bool,
}

impl Mention {
    /// The relation of a kind, if any.
    pub fn relation(&self, kind: super::relations::RelationKind) -> Option<&Relation> {
        self.relations.iter().find(|r| r.kind == kind)
    }

    /// The mention this one stands on or in (first support relation to a mention).
    pub fn parent(&self) -> Option<usize> {
        self.relations
            .iter()
            .find(|r| r.is_support())
            .and_then(|r| r.target.mention())
    }

    /// Free-text description (attributes + noun), for the asset router.
    pub fn description(&self) -> String {
        self.attributes.describe(&self.category)
    }
}

/// Count written in a noun phrase: the quantifier class (from the lexicon), the number, the
/// determiner class, plurality, and a "pairs of" multiplier.
pub(crate) fn phrase_count(
    quant: Option<&str>,
    number: Option<u32>,
    plus: bool,
    det: Option<&str>,
    plural: bool,
) -> Count {
    if let Some(n) = number {
        return match quant {
            Some("at_least") => Count::AtLeast(n),
            Some("more_than" | "more_than_number") => Count::AtLeast(n.saturating_add(1)),
            _ if plus => Count::AtLeast(n),
            _ => Count::Exactly(n),
        };
    }
    match quant {
        Some("dozen") => return Count::Exactly(12),
        Some("half_dozen") => return Count::Exactly(6),
        Some("two") => return Count::Exactly(2),
        Some("dozens") => return Count::AtLeast(24),
        Some("several") => return Count::Several,
        _ => {}
    }
    match det {
        Some("several" | "all") => Count::Several,
        Some("indefinite" | "each" | "another") if !plural => Count::Exactly(1),
        _ if plural => Count::Several,
        _ => Count::Exactly(1),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_from_phrases() {
        assert_eq!(
            phrase_count(Some("at_least"), Some(10), false, None, true),
            Count::AtLeast(10)
        );
        assert_eq!(
            phrase_count(None, Some(10), true, None, true),
            Count::AtLeast(10)
        );
        assert_eq!(
            phrase_count(Some("more_than"), Some(9), false, None, true),
            Count::AtLeast(10)
        );
        assert_eq!(
            phrase_count(None, None, false, Some("indefinite"), false),
            Count::Exactly(1)
        );
        assert_eq!(phrase_count(None, None, false, None, true), Count::Several);
        assert_eq!(
            phrase_count(Some("dozen"), None, false, None, true),
            Count::Exactly(12)
        );
        assert_eq!(
            phrase_count(None, None, false, Some("several"), true),
            Count::Several
        );
    }

    #[test]
    fn per_parent_totals() {
        assert_eq!(
            Count::Exactly(4).times(Count::Exactly(4)),
            Count::Exactly(16)
        );
        assert_eq!(
            Count::AtLeast(3).times(Count::Exactly(2)),
            Count::AtLeast(6)
        );
        assert_eq!(Count::Exactly(1).times(Count::Several), Count::Several);
        assert_eq!(Count::Several.minimum(), 2);
    }
}
