//! What the reader did with each noun of a prompt: grounded in the object lexicon, routed
//! through WordNet to the nearest family the library builds, left to a stand-in, or dropped
//! (with the reason: an adjective, a feeling, a word the dictionary does not know).
//!
//! `generate` and `read` print this report so a user sees how the prompt was understood.

use serde::{Deserialize, Serialize};

/// What happened to a noun.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum NounStatus {
    /// A noun of the object lexicon.
    Lexicon,
    /// A noun WordNet grounds as a thing, built as its nearest family.
    Routed,
    /// A noun WordNet grounds as a thing with no family on its hypernyms: a stand-in shape.
    StandIn,
    /// A word no dictionary knows, counted or listed like an object: a stand-in shape. It
    /// does not count as understood.
    Unknown,
    /// A room or building word.
    Room,
    /// Not built: no physical thing, not a noun, or unknown.
    Dropped,
}

impl NounStatus {
    /// `lexicon`, `routed`, ...
    pub fn as_str(self) -> &'static str {
        match self {
            NounStatus::Lexicon => "lexicon",
            NounStatus::Routed => "routed",
            NounStatus::StandIn => "stand-in",
            NounStatus::Unknown => "unknown",
            NounStatus::Room => "room",
            NounStatus::Dropped => "dropped",
        }
    }
}

/// One noun of the prompt and what the reader did with it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct NounReport {
    /// The words as read (singular head).
    pub noun: String,
    /// WordNet lemma, when WordNet knows the noun.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub lemma: Option<String>,
    /// What happened.
    pub status: NounStatus,
    /// The lexicon noun it is built as (routed nouns) or its canonical noun (lexicon nouns).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub family: Option<String>,
    /// Why it was dropped, or the hypernym path to its family.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub reason: Option<String>,
}

impl NounReport {
    /// One line: `noun -> family (status: reason)`.
    pub fn line(&self) -> String {
        let mut out = self.noun.clone();
        if let Some(f) = self.family.as_ref().filter(|f| **f != self.noun) {
            out.push_str(&format!(" -> {f}"));
        }
        out.push_str(&format!(" ({}", self.status.as_str()));
        if let Some(r) = &self.reason {
            out.push_str(&format!(": {r}"));
        }
        out.push(')');
        out
    }
}

/// The report in a few lines for a terminal: how many nouns were read, and every noun that
/// was routed, stood in or was dropped, with why.
pub fn summary_lines(nouns: &[NounReport]) -> Vec<String> {
    let count = |s: NounStatus| nouns.iter().filter(|n| n.status == s).count();
    let mut out = vec![format!(
        "nouns read: {} ({} rooms, {} in the lexicon, {} routed, {} stand-ins, {} unknown, {} \
         dropped)",
        nouns.len(),
        count(NounStatus::Room),
        count(NounStatus::Lexicon),
        count(NounStatus::Routed),
        count(NounStatus::StandIn),
        count(NounStatus::Unknown),
        count(NounStatus::Dropped)
    )];
    for status in [
        NounStatus::Routed,
        NounStatus::StandIn,
        NounStatus::Unknown,
        NounStatus::Dropped,
    ] {
        let items: Vec<String> = nouns
            .iter()
            .filter(|n| n.status == status)
            .map(NounReport::line)
            .collect();
        if !items.is_empty() {
            out.push(format!("  {}: {}", status.as_str(), items.join("; ")));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lines_name_what_was_routed_and_dropped() {
        let r = crate::prompt::read(
            "A living room with a samovar on a table, despite the unease of the stylish guests.",
        );
        let lines = summary_lines(&r.nouns);
        assert!(lines[0].starts_with("nouns read:"), "{lines:?}");
        let all = lines.join("\n");
        assert!(all.contains("unease") && all.contains("dropped"), "{all}");
        assert!(all.contains("samovar ->"), "{all}");
    }
}
