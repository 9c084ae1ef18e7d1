//! Floor and wall materials from words: "light hardwood" is `oak`, "polished concrete" is
//! `concrete`. Names are entries of the material table (friction, density, colour); the
//! architecture renders them as plain colours.

use schemars::JsonSchema;
use serde::Serialize;

use super::knowledge::material_word;
use crate::assets::material;

/// A material as the agents see it.
#[derive(Debug, Clone, PartialEq, Serialize, JsonSchema)]
pub struct MaterialInfo {
    /// Name in the material table.
    pub material: String,
    /// The words that matched.
    pub matched: String,
    /// Base colour, linear RGB.
    pub color: [f64; 3],
    /// Static friction coefficient.
    pub mu_static: f64,
    /// Dynamic friction coefficient.
    pub mu_dynamic: f64,
}

/// The material a description names, if any (two-word phrases before single words, later
/// words before earlier ones: the head noun comes last).
pub fn lookup(description: &str) -> Option<MaterialInfo> {
    let toks = crate::words::tokenize(description);
    let mut found: Option<(String, &'static str)> = None;
    'outer: for n in [2usize, 1] {
        for i in (0..toks.len().saturating_sub(n - 1)).rev() {
            let phrase = toks[i..i + n].join(" ");
            if let Some(m) = material_word(&phrase) {
                found = Some((phrase, m));
                break 'outer;
            }
        }
    }
    let (matched, name) = found?;
    let m = material::material(name)?;
    Some(MaterialInfo {
        material: name.to_string(),
        matched,
        color: m.color,
        mu_static: m.mu_static,
        mu_dynamic: m.mu_dynamic,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn words_to_materials() {
        assert_eq!(lookup("light hardwood floor").unwrap().material, "oak");
        assert_eq!(lookup("polished concrete").unwrap().material, "concrete");
        assert_eq!(lookup("white marble").unwrap().material, "marble");
        assert_eq!(lookup("Carpet").unwrap().material, "carpet");
        assert!(lookup("sunshine").is_none());
    }
}
