//! What a critic returns: a 0-10 score with a reason per category, and concrete issues.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// A scoring category a stage defines for its critic.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CategorySpec {
    /// Identifier (`snake_case`), e.g. `prompt_following`.
    pub id: String,
    /// What a 10 means, for the critic.
    pub description: String,
}

impl CategorySpec {
    /// A category.
    pub fn new(id: &str, description: &str) -> Self {
        CategorySpec {
            id: id.to_string(),
            description: description.to_string(),
        }
    }
}

/// One category's score.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct Score {
    /// Category id.
    pub category: String,
    /// 0 (unusable) to 10 (nothing to improve).
    pub score: u8,
    /// Why, in a sentence or two.
    pub reason: String,
}

/// A concrete problem the designer can fix.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct Issue {
    /// Object ids involved, where there are any.
    #[serde(default)]
    pub objects: Vec<String>,
    /// What is wrong and what would fix it.
    pub description: String,
}

/// A critic's verdict on the current state of a stage.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema, Default)]
pub struct Critique {
    /// One score per category of the stage.
    pub scores: Vec<Score>,
    /// Concrete problems.
    #[serde(default)]
    pub issues: Vec<Issue>,
}

/// Problems with a critique as submitted.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum CritiqueError {
    /// A category of the stage has no score.
    #[error("missing a score for category {0:?}")]
    Missing(String),
    /// A score for a category the stage does not have.
    #[error("unknown category {0:?}; the categories are: {1}")]
    Unknown(String, String),
    /// Scores run 0 to 10.
    #[error("score {score} for {category:?} is outside 0-10")]
    OutOfRange {
        /// Category.
        category: String,
        /// The bad score.
        score: u8,
    },
}

impl Critique {
    /// Sum of all scores.
    pub fn total(&self) -> u32 {
        self.scores.iter().map(|s| u32::from(s.score)).sum()
    }

    /// Score of one category.
    pub fn score(&self, category: &str) -> Option<u8> {
        self.scores
            .iter()
            .find(|s| s.category == category)
            .map(|s| s.score)
    }

    /// Lowest score (10 for an empty critique).
    pub fn min_score(&self) -> u8 {
        self.scores.iter().map(|s| s.score).min().unwrap_or(10)
    }

    /// Checks that every category of `categories` is scored exactly once, within 0-10.
    pub fn validate(&self, categories: &[CategorySpec]) -> Result<(), CritiqueError> {
        let names = categories
            .iter()
            .map(|c| c.id.as_str())
            .collect::<Vec<_>>()
            .join(", ");
        for s in &self.scores {
            if !categories.iter().any(|c| c.id == s.category) {
                return Err(CritiqueError::Unknown(s.category.clone(), names));
            }
            if s.score > 10 {
                return Err(CritiqueError::OutOfRange {
                    category: s.category.clone(),
                    score: s.score,
                });
            }
        }
        for c in categories {
            if self.score(&c.id).is_none() {
                return Err(CritiqueError::Missing(c.id.clone()));
            }
        }
        Ok(())
    }

    /// Whether going from `previous` to `self` is a regression that warrants rolling back:
    /// any category dropping by `category_drop` or more, or the sum dropping by `sum_drop` or
    /// more. Returns the reason.
    pub fn regression_from(
        &self,
        previous: &Critique,
        category_drop: u8,
        sum_drop: u32,
    ) -> Option<String> {
        for s in &previous.scores {
            if let Some(now) = self.score(&s.category)
                && s.score >= now
                && s.score - now >= category_drop
            {
                return Some(format!(
                    "{} dropped from {} to {}",
                    s.category, s.score, now
                ));
            }
        }
        let (before, after) = (previous.total(), self.total());
        if before >= after && before - after >= sum_drop {
            return Some(format!("the total dropped from {before} to {after}"));
        }
        None
    }

    /// Short text for logs and prompts: `cat 7/10 (reason); ...`.
    pub fn summary(&self) -> String {
        self.scores
            .iter()
            .map(|s| format!("{} {}/10 ({})", s.category, s.score, s.reason))
            .collect::<Vec<_>>()
            .join("; ")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn c(scores: &[(&str, u8)]) -> Critique {
        Critique {
            scores: scores
                .iter()
                .map(|(k, v)| Score {
                    category: k.to_string(),
                    score: *v,
                    reason: String::new(),
                })
                .collect(),
            issues: vec![],
        }
    }

    #[test]
    fn regression_rules() {
        let prev = c(&[("a", 7), ("b", 6)]);
        assert!(
            c(&[("a", 5), ("b", 8)])
                .regression_from(&prev, 2, 1)
                .unwrap()
                .contains("a dropped")
        );
        assert!(
            c(&[("a", 7), ("b", 5)])
                .regression_from(&prev, 2, 1)
                .unwrap()
                .contains("total")
        );
        assert!(
            c(&[("a", 8), ("b", 6)])
                .regression_from(&prev, 2, 1)
                .is_none()
        );
        assert!(
            c(&[("a", 6), ("b", 7)])
                .regression_from(&prev, 2, 1)
                .is_none()
        );
    }

    #[test]
    fn validation() {
        let cats = [CategorySpec::new("a", ""), CategorySpec::new("b", "")];
        assert!(c(&[("a", 7), ("b", 6)]).validate(&cats).is_ok());
        assert_eq!(
            c(&[("a", 7)]).validate(&cats),
            Err(CritiqueError::Missing("b".into()))
        );
        assert!(matches!(
            c(&[("a", 7), ("b", 11)]).validate(&cats),
            Err(CritiqueError::OutOfRange { .. })
        ));
        assert!(matches!(
            c(&[("a", 7), ("b", 1), ("z", 3)]).validate(&cats),
            Err(CritiqueError::Unknown(..))
        ));
    }
}
