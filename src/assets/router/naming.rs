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

/// True when `o` in `scene` is what `noun` asks for, by its name (the prompt's,
/// "manicure_table") or by the library category its asset is built as (`table`).
pub fn object_is(scene: &crate::scene::Scene, noun: &str, o: &SceneObject) -> bool {
    names(noun, &o.category) || names(noun, scene.built_as(o))
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
