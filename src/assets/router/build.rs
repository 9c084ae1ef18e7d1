//! Building what a phrase names: a known category through the user's articulated library,
//! the external sources or the procedural generators (with retries on other seeds), an
//! unknown noun through the external sources or a generic stand-in; and the validation every
//! result passes (physics, hull budget, requested size, watertight visuals).

use std::sync::Arc;

use super::{RouteError, RouterContext, Strategy, parse};
use crate::assets::attributes::Attributes;
use crate::assets::procedural::{self, AssetRequest, Kind, SupportClass};
use crate::assets::{Asset, physical};

/// The size to ask a generator for: the request's, else the typical size scaled by size words.
pub(super) fn wanted_size(
    category: &str,
    request_size: Option<[f64; 3]>,
    attrs: &Attributes,
) -> Option<[f64; 3]> {
    if request_size.is_some() {
        return request_size;
    }
    if (attrs.size_scale - 1.0).abs() < 1e-9 {
        return None;
    }
    procedural::prior(category)
        .map(|p| [0, 1, 2].map(|i| (p.typical[i] * attrs.size_scale).clamp(p.min[i], p.max[i])))
}

/// Checks a built asset against the request: physics, hull budget, size, watertightness.
pub(super) fn validate(
    asset: &Asset,
    support: SupportClass,
    size: Option<[f64; 3]>,
) -> Result<(), String> {
    physical::check(asset, support).map_err(|e| e.to_string())?;
    if let Some(want) = size {
        let [lo, hi] = asset.bounds();
        for i in 0..3 {
            let got = hi[i] - lo[i];
            if (got - want[i]).abs() > 0.1 * want[i] + 0.002 {
                let axis = ["width", "depth", "height"][i];
                return Err(format!(
                    "{axis} came out {got:.3} m for a requested {:.3} m",
                    want[i]
                ));
            }
        }
    }
    let summary = physical::summarize(asset, support);
    let reason = asset
        .provenance
        .get("open_visual_reason")
        .and_then(|r| r.as_str());
    if !summary.watertight && reason.is_none() {
        return Err(format!(
            "visual mesh is not closed ({}) and no reason was recorded",
            summary.open_visuals.join(", ")
        ));
    }
    Ok(())
}

pub(super) fn size_feedback(category: &str, size: [f64; 3]) -> Option<String> {
    let p = procedural::prior(category)?;
    let out: Vec<String> = (0..3)
        .filter(|&i| size[i] < p.min[i] * 0.9 || size[i] > p.max[i] * 1.1)
        .map(|i| {
            format!(
                "{} {:.2} m is outside {:.2}-{:.2} m",
                ["width", "depth", "height"][i],
                size[i],
                p.min[i],
                p.max[i]
            )
        })
        .collect();
    (!out.is_empty()).then(|| {
        format!(
            "a {} cannot be that size ({}); ask for a size inside the range, e.g. the typical {:.2} x {:.2} x {:.2} m, or for another object",
            category.replace('_', " "),
            out.join(", "),
            p.typical[0],
            p.typical[1],
            p.typical[2]
        )
    })
}

/// Builds one known category with retries; returns the asset and its strategy.
pub(super) fn build_known(
    category: &'static str,
    phrase: &parse::Phrase,
    size: Option<[f64; 3]>,
    explicit_size: Option<[f64; 3]>,
    seed: u64,
    ctx: &RouterContext,
    notes: &mut Vec<String>,
) -> Result<(Arc<Asset>, Strategy), RouteError> {
    let prior = procedural::prior(category).ok_or_else(|| RouteError::Failed {
        description: phrase.text.clone(),
        category: category.to_string(),
        attempts: vec!["no prior for the category".into()],
    })?;
    let mut attempts = Vec::new();
    if let Some(s) = size
        && let Some(f) = size_feedback(category, s)
    {
        return Err(RouteError::Failed {
            description: phrase.text.clone(),
            category: category.to_string(),
            attempts: vec![f],
        });
    }
    // The user's articulated library first, for articulated categories.
    if prior.kind == Kind::Articulated
        && let Some(lib) = &ctx.library
        && let Some(entry) = lib.best_match(&phrase.text, Some(category), size)
    {
        let target = size.or(Some(prior.typical));
        match ctx
            .cache
            .get_or_build(&lib.asset_id(entry, target, seed), || {
                lib.load(entry, target, seed)
            }) {
            Ok((asset, _)) => match validate(&asset, prior.support, size) {
                Ok(()) => return Ok((asset, Strategy::Articulated)),
                Err(e) => attempts.push(format!("library model {}: {e}", entry.file)),
            },
            Err(e) => attempts.push(format!("library model {}: {e}", entry.file)),
        }
    }
    // External models come at their own size unless the request gave one.
    if ctx.prefer_external
        && let Some(found) = build_external(
            phrase,
            category,
            prior.support,
            explicit_size,
            seed,
            ctx,
            &mut attempts,
        )
    {
        return Ok((found, Strategy::External));
    }
    let style = phrase.attributes.style.as_ref();
    let tries = ctx.max_attempts.max(1);
    for k in 0..tries as u64 {
        let mut r = AssetRequest::new(category, seed.wrapping_add(k));
        r.size = size;
        r.material = phrase.attributes.material.clone();
        r.color = phrase.attributes.color;
        let id = match procedural::asset_id(&r, style) {
            Ok(id) => id,
            Err(e) => {
                attempts.push(e.to_string());
                continue;
            }
        };
        match ctx
            .cache
            .get_or_build(&id, || procedural::build_styled(&r, style))
        {
            Ok((asset, _)) => match validate(&asset, prior.support, size) {
                Ok(()) => {
                    if k > 0 {
                        notes.push(format!(
                            "{category}: built with seed {} after {k} failed attempt(s): {}",
                            r.seed,
                            attempts.join("; ")
                        ));
                    }
                    let strategy = match asset.provenance["strategy"].as_str() {
                        Some("articulated") => Strategy::Articulated,
                        Some("thin_covering") => Strategy::ThinCovering,
                        _ => Strategy::Procedural,
                    };
                    return Ok((asset, strategy));
                }
                Err(e) => attempts.push(format!("seed {}: {e}", r.seed)),
            },
            Err(e) => attempts.push(format!("seed {}: {e}", r.seed)),
        }
    }
    Err(RouteError::Failed {
        description: phrase.text.clone(),
        category: category.to_string(),
        attempts,
    })
}

/// Tries the mesh folder, then the HTTP backend; `None` when neither is configured or both
/// failed (failures go to `attempts`).
pub(super) fn build_external(
    phrase: &parse::Phrase,
    noun: &str,
    support: SupportClass,
    size: Option<[f64; 3]>,
    seed: u64,
    ctx: &RouterContext,
    attempts: &mut Vec<String>,
) -> Option<Arc<Asset>> {
    if let Some(folder) = &ctx.mesh_folder
        && let Some(entry) = folder.best_match(&phrase.text, noun, size)
    {
        let id = folder.asset_id(entry, support, size);
        match ctx
            .cache
            .get_or_build(&id, || folder.import(entry, support, size))
        {
            Ok((a, _)) => match validate(&a, support, size) {
                Ok(()) => return Some(a),
                Err(e) => attempts.push(format!("mesh folder {}: {e}", entry.file)),
            },
            Err(e) => attempts.push(format!("mesh folder {}: {e}", entry.file)),
        }
    }
    if let Some(backend) = &ctx.backend {
        let description = if phrase.text.is_empty() {
            noun.to_string()
        } else {
            phrase.text.clone()
        };
        let id = backend.asset_id(&description, support, size, seed);
        match ctx.cache.get_or_build(&id, || {
            backend.generate_asset(&description, noun, support, size, seed)
        }) {
            Ok((a, _)) => match validate(&a, support, size) {
                Ok(()) => return Some(a),
                Err(e) => attempts.push(format!("text-to-3D backend: {e}")),
            },
            Err(e) => attempts.push(format!("text-to-3D backend: {e}")),
        }
    }
    None
}

/// Builds whatever a phrase names at a support class: a known category, an external asset,
/// or a generic stand-in (with a note).
pub(super) fn build_phrase(
    phrase: &parse::Phrase,
    category: Option<&'static str>,
    support: SupportClass,
    size: Option<[f64; 3]>,
    seed: u64,
    ctx: &RouterContext,
    notes: &mut Vec<String>,
) -> Result<(Arc<Asset>, String, Strategy), RouteError> {
    if let Some(cat) = category {
        let wanted = wanted_size(cat, size, &phrase.attributes);
        let (a, s) = build_known(cat, phrase, wanted, size, seed, ctx, notes)?;
        return Ok((a, cat.to_string(), s));
    }
    let noun = phrase
        .unknown_noun
        .clone()
        .or_else(|| phrase.noun.clone())
        .ok_or(RouteError::Empty)?;
    let mut attempts = Vec::new();
    if let Some(a) = build_external(phrase, &noun, support, size, seed, ctx, &mut attempts) {
        notes.push(format!(
            "\"{noun}\" is not in the procedural library; imported it from an external source ({})",
            a.provenance["source"].as_str().unwrap_or("external")
        ));
        return Ok((a, crate::scene::sanitize_name(&noun), Strategy::External));
    }
    let a = procedural::build_generic(
        &noun,
        support,
        size,
        seed,
        phrase.attributes.material.as_deref(),
        phrase.attributes.color,
    )
    .map_err(|e| RouteError::Failed {
        description: phrase.text.clone(),
        category: noun.clone(),
        attempts: vec![e.to_string()],
    })?;
    let [lo, hi] = a.bounds();
    let mut note = format!(
        "generic: no generator knows \"{noun}\"; built a generic {} shape {:.2} x {:.2} x {:.2} m as a stand-in (provenance marks it generic)",
        support.as_str(),
        hi[0] - lo[0],
        hi[1] - lo[1],
        hi[2] - lo[2]
    );
    if !attempts.is_empty() {
        note.push_str(&format!(
            "; external sources failed: {}",
            attempts.join("; ")
        ));
    }
    notes.push(note);
    let a = Arc::new(a);
    ctx.cache.put(a.clone());
    Ok((a, crate::scene::sanitize_name(&noun), Strategy::Generic))
}
