//! Which category a description names and whether an object is what a noun asks for: the
//! router's reading of nouns, shared by the stages that place objects, the post-processing
//! that keeps them and the metrics that count them.

use crate::assets::{procedural, router};
use crate::scene::SceneObject;

/// The category a free-text description names: the longest phrase (up to three words)
/// that resolves, preferring later words (the head noun comes last in English).
pub fn category_of(description: &str) -> Option<&'static str> {
    router::parse::main_categories(description).first().copied()
}

/// True when an object of `category` is what `noun` asks for: a category the router can
/// build for it (at any stage), or the generic stand-in named after an unknown noun.
pub fn names(noun: &str, category: &str) -> bool {
    let sanitized = crate::scene::sanitize_name(noun);
    if category == noun || category == sanitized {
        return true;
    }
    // A prompt's name keeps the noun's modifiers and ends with the noun
    // ("spattered_radio" for a "paint-spattered radio" the plan calls a radio).
    if procedural::prior(category).is_none()
        && !sanitized.is_empty()
        && category
            .strip_suffix(sanitized.as_str())
            .is_some_and(|rest| rest.ends_with('_'))
    {
        return true;
    }
    let main = router::parse::main_categories(noun);
    // Objects carry the prompt's name ("manicure_table"): what the router builds for the
    // name is what it is.
    let built_as = router::parse::main_categories(&category.replace('_', " "));
    main.contains(&category)
        || built_as.first().is_some_and(|b| main.contains(b))
        || procedural::prior(category).is_some_and(|p| {
            main.iter()
                .any(|c| procedural::support_sibling(c, p.support) == Some(category))
        })
        || router::parse::phrase(noun)
            .unknown_noun
            .is_some_and(|u| crate::scene::sanitize_name(&u) == category)
}

/// True when an object of `category` is a narrower kind of what `noun` names: its name ends
/// with the noun's category and both are built by the same generator ("king_bed" for "bed",
/// "coffee_table" for "table"), so a "hand_mirror", built as a picture frame, is no kind of
/// "mirror". For a plan that names a piece more broadly than the prompt's words built it.
pub fn kind_of(noun: &str, category: &str) -> bool {
    let Some(base) = category_of(noun) else {
        return false;
    };
    let generator = |c: &str| procedural::prior(c).map(|p| p.generator.as_str());
    category
        .strip_suffix(base)
        .is_some_and(|rest| rest.ends_with('_'))
        && generator(base).is_some()
        && generator(base) == generator(category)
}

/// True when `o` in `scene` is what `noun` asks for: placed for the plan's `noun`, or by its
/// name (the prompt's, "manicure_table") or by the library category its asset is built as (`table`, or a narrower
/// kind of it: a `round_rug` is a rug).
pub fn object_is(scene: &crate::scene::Scene, noun: &str, o: &SceneObject) -> bool {
    let built = scene.built_as(o);
    o.planned.as_deref() == Some(noun)
        || names(noun, &o.category)
        || names(noun, built)
        || kind_of(noun, built)
}

/// Footprint of an object whose size nobody knows, m².
const UNKNOWN_FOOTPRINT: f64 = 0.02;

/// Typical footprint of a thing, m² (upright, as it is placed first).
pub fn footprint(noun: &str) -> f64 {
    category_of(noun)
        .and_then(procedural::prior)
        .map_or(UNKNOWN_FOOTPRINT, |p| {
            (p.typical[0] * p.typical[1]).max(1e-4)
        })
}

#[cfg(test)]
mod tests {
    use super::kind_of;

    #[test]
    fn narrower_kinds_of_the_same_generator() {
        assert!(kind_of("bed", "king_bed"));
        assert!(!kind_of("bed", "bed"), "the same category is `names`' case");
        // Built as a picture frame: no kind of wall mirror.
        assert!(!kind_of("mirror", "hand_mirror"));
        assert!(!kind_of("bed", "bedside_table"));
    }
}
