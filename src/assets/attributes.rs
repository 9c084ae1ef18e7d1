//! Colour, material, style and size words in a request ("red oak", "glass", "steampunk",
//! "small"), read against the lexicon in `src/data/asset_attributes.json`.
//!
//! The router removes the object's own noun phrase first ("wine glass" is a category, not a
//! material), then reads the remaining words here. Multi-word entries ("navy blue",
//! "art deco", "stainless steel") win over their single words.

use std::collections::BTreeMap;
use std::sync::OnceLock;

use serde::{Deserialize, Serialize};

/// A decorative style: default materials, an accent, a colour palette and a texture motif.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Style {
    /// Style key, e.g. `steampunk`.
    #[serde(default)]
    pub name: String,
    /// Words that name the style.
    #[serde(default)]
    pub words: Vec<String>,
    /// Main material when the request names none.
    pub main_material: String,
    /// Material of trims, legs, handles and frames.
    pub accent_material: String,
    /// Accent colour, linear RGB.
    pub accent_color: [f64; 3],
    /// Colours for patterns and artwork, linear RGB.
    pub palette: Vec<[f64; 3]>,
    /// Texture motif for thin coverings (`gears`, `stars`, `pixels`, ...).
    pub motif: String,
}

#[derive(Deserialize)]
struct Lexicon {
    colors: BTreeMap<String, [f64; 3]>,
    material_words: BTreeMap<String, String>,
    styles: BTreeMap<String, Style>,
    size_words: BTreeMap<String, f64>,
}

fn lexicon() -> &'static Lexicon {
    static LEX: OnceLock<Lexicon> = OnceLock::new();
    LEX.get_or_init(|| {
        // Shipped data, checked by a unit test.
        serde_json::from_str::<Lexicon>(include_str!("../data/asset_attributes.json"))
            .map(|mut l| {
                for (k, s) in l.styles.iter_mut() {
                    s.name = k.clone();
                }
                l
            })
            .unwrap_or(Lexicon {
                colors: BTreeMap::new(),
                material_words: BTreeMap::new(),
                styles: BTreeMap::new(),
                size_words: BTreeMap::new(),
            })
    })
}

/// What a request's words say about the object's look.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct Attributes {
    /// Main colour (the first colour word), linear RGB.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub color: Option<[f64; 3]>,
    /// The colour word.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub color_name: Option<String>,
    /// Further colour words, in order ("red and white" -> white).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub other_colors: Vec<(String, [f64; 3])>,
    /// Material named by the words (a key of the material table).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub material: Option<String>,
    /// Style named by the words.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub style: Option<Style>,
    /// Size factor from words such as "small" or "large" (1 when none).
    #[serde(default = "one")]
    pub size_scale: f64,
}

fn one() -> f64 {
    1.0
}

/// Lower-case words of `text`, punctuation removed (hyphens and apostrophes inside words kept
/// as spaces), as a space-padded string for phrase search.
pub fn normalize(text: &str) -> String {
    let mut out = String::from(" ");
    for c in text.chars() {
        if c.is_alphanumeric() {
            out.extend(c.to_lowercase());
        } else if !out.ends_with(' ') {
            out.push(' ');
        }
    }
    if !out.ends_with(' ') {
        out.push(' ');
    }
    out
}

/// Finds the longest phrases of `table` in `text` (space-padded); returns them in text order
/// with their positions, each word used once.
fn find_phrases<'a, V>(text: &str, table: &'a BTreeMap<String, V>) -> Vec<(usize, &'a str, &'a V)> {
    let mut keys: Vec<(&String, &V)> = table.iter().collect();
    keys.sort_by_key(|(k, _)| std::cmp::Reverse(k.len()));
    let mut taken = vec![false; text.len()];
    let mut found = Vec::new();
    for (k, v) in keys {
        let needle = format!(" {} ", normalize(k).trim());
        let mut start = 0;
        while let Some(pos) = text[start..].find(&needle) {
            let at = start + pos;
            let span = at + 1..at + needle.len() - 1;
            if !taken[span.clone()].iter().any(|t| *t) {
                for t in &mut taken[span] {
                    *t = true;
                }
                found.push((at, k.as_str(), v));
            }
            start = at + 1;
        }
    }
    found.sort_by_key(|f| f.0);
    found
}

/// Reads colour, material, style and size words from `text`.
pub fn parse(text: &str) -> Attributes {
    let lex = lexicon();
    let norm = normalize(text);
    let mut attrs = Attributes {
        size_scale: 1.0,
        ..Default::default()
    };
    for (_, name, rgb) in find_phrases(&norm, &lex.colors) {
        if attrs.color.is_none() {
            attrs.color = Some(*rgb);
            attrs.color_name = Some(name.to_string());
        } else {
            attrs.other_colors.push((name.to_string(), *rgb));
        }
    }
    if let Some((_, _, m)) = find_phrases(&norm, &lex.material_words).first() {
        attrs.material = Some((*m).clone());
    }
    let style_words: BTreeMap<String, &Style> = lex
        .styles
        .values()
        .flat_map(|s| s.words.iter().map(move |w| (w.clone(), s)))
        .collect();
    if let Some((_, _, s)) = find_phrases(&norm, &style_words).first() {
        attrs.style = Some((**s).clone());
    }
    for (_, _, f) in find_phrases(&norm, &lex.size_words) {
        attrs.size_scale *= *f;
    }
    attrs
}

/// A style by key (`steampunk`, `art_deco`, ...).
pub fn style(name: &str) -> Option<Style> {
    lexicon().styles.get(name).cloned()
}

/// Every style key.
pub fn style_names() -> Vec<&'static str> {
    lexicon().styles.keys().map(String::as_str).collect()
}

/// A colour by name, linear RGB.
pub fn color(name: &str) -> Option<[f64; 3]> {
    lexicon().colors.get(name).copied()
}

/// Every word the lexicon knows (colours, materials, styles, sizes), so a noun finder can
/// skip them.
pub fn is_attribute_word(word: &str) -> bool {
    let lex = lexicon();
    lex.colors.contains_key(word)
        || lex.material_words.contains_key(word)
        || lex.size_words.contains_key(word)
        || lex
            .styles
            .values()
            .any(|s| s.words.iter().any(|w| w == word))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::assets::material;

    #[test]
    fn lexicon_loads_and_points_at_real_materials() {
        let lex = lexicon();
        assert!(lex.colors.len() > 40);
        for (w, m) in &lex.material_words {
            assert!(
                material::material(m).is_some(),
                "{w} -> unknown material {m}"
            );
        }
        for s in lex.styles.values() {
            assert!(material::material(&s.main_material).is_some(), "{}", s.name);
            assert!(
                material::material(&s.accent_material).is_some(),
                "{}",
                s.name
            );
            assert!(!s.palette.is_empty());
        }
        for c in lex.colors.values() {
            assert!(c.iter().all(|v| (0.0..=1.0).contains(v)));
        }
    }

    #[test]
    fn reads_colours_materials_styles_and_sizes() {
        let a = parse("a small navy blue velvet armchair");
        assert_eq!(a.color_name.as_deref(), Some("navy blue"));
        assert_eq!(a.material.as_deref(), Some("velvet"));
        assert!(a.size_scale < 1.0);
        let b = parse("Steampunk desk with brass fittings");
        assert_eq!(b.style.as_ref().map(|s| s.name.as_str()), Some("steampunk"));
        assert_eq!(b.material.as_deref(), Some("brass"));
        let c = parse("An Art Deco style coffee table, black and gold");
        assert_eq!(c.style.unwrap().name, "art_deco");
        assert_eq!(c.color_name.as_deref(), Some("black"));
        assert_eq!(c.other_colors[0].0, "gold");
        let d = parse("red oak dining table");
        assert_eq!(d.material.as_deref(), Some("oak"));
        assert_eq!(d.color_name.as_deref(), Some("red"));
        assert_eq!(parse("table").color, None);
        assert_eq!(parse("table").size_scale, 1.0);
    }
}
