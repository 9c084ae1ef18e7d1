//! The prompt reader and the room planner never panic and stay consistent on word salad and
//! arbitrary text; they end in the plan, so they live with it rather than with the reader.

use proptest::prelude::*;

use crate::plan::plan_rooms;
use crate::prompt::read;

const WORDS: &[&str] = &[
    "a",
    "the",
    "its",
    "each",
    "one",
    "other",
    "another",
    "two",
    "5",
    "at",
    "least",
    "exactly",
    "pairs",
    "of",
    "stack",
    "pile",
    "with",
    "without",
    "no",
    "and",
    "or",
    ",",
    ".",
    "on",
    "in",
    "the",
    "corner",
    "wall",
    "middle",
    "room",
    "next",
    "to",
    "window",
    "facing",
    "it",
    "them",
    "each other",
    "surrounded",
    "by",
    "set",
    "for",
    "people",
    "setting",
    "level",
    "first",
    "top",
    "table",
    "chairs",
    "bed",
    "nightstand",
    "shelf",
    "books",
    "bowl",
    "apples",
    "fruits",
    "kitchen",
    "bathroom",
    "bedrooms",
    "house",
    "has",
    "contains",
    "holds",
    "stacked",
    "hanging",
    "ceiling",
    "above",
    "between",
    "Star",
    "Wars",
    "themed",
    "Frozen",
    "blue",
    "wooden",
    "tiny",
    "cluttered",
    "flux",
    "capacitor",
    "in total",
    "its",
    "en-suite",
    "which",
    "where",
    "is",
    "are",
    "styled",
    "like",
    "inspired",
    "covers",
    "flank",
    "entrance",
    "10+",
    "(",
    ")",
    "'s",
    "-",
    "x-ray",
    "room.",
    "with,",
    "each.",
    "of.",
];

proptest! {
    #![proptest_config(ProptestConfig::with_cases(400))]
    #[test]
    fn any_word_salad_reads_and_plans_without_panicking(idx in proptest::collection::vec(0..WORDS.len(), 0..40)) {
        let text: Vec<&str> = idx.iter().map(|&i| WORDS[i]).collect();
        let text = text.join(" ");
        let r = read(&text);
        prop_assert!(!r.rooms.is_empty());
        for m in &r.mentions {
            prop_assert!(m.room < r.rooms.len());
            for rel in &m.relations {
                if let crate::prompt::Target::Mention(t) = rel.target {
                    prop_assert!(t < r.mentions.len());
                }
            }
        }
        let plans = plan_rooms(&r);
        prop_assert_eq!(plans.len(), r.rooms.len());
    }

    #[test]
    fn arbitrary_text_reads_without_panicking(text in "\\PC{0,200}") {
        let r = read(&text);
        prop_assert!(!r.rooms.is_empty());
        let _ = plan_rooms(&r);
    }
}
