//! Generic shapes for nouns no generator knows: a plinthed block on the floor, a rounded
//! box on a surface, a framed panel on a wall, a dome under the ceiling. Sizes come from the
//! support class's prior (`generic` in `src/data/asset_priors.json`) unless the caller gives
//! one. The asset is marked `generic` in its provenance with the noun it stands for, so the
//! caller can report it; it is never a silent substitute.

use std::collections::BTreeMap;
use std::sync::OnceLock;

use rand::SeedableRng;
use rand::rngs::ChaCha8Rng;
use serde::Deserialize;

use super::parts::{body, shade, single};
use super::{GENERATOR_VERSION, GenContext, Generated, GeneratorFn, Prior, SupportClass};
use crate::assets::{Asset, AssetError, content_id, material, physical};
use crate::geometry::GeometryError;

pub(super) const GENERATORS: &[(&str, GeneratorFn)] = &[("generic", generic)];

#[derive(Deserialize)]
struct GenericTable {
    generic: BTreeMap<String, Prior>,
}

/// The generic prior of a support class.
pub fn generic_prior(support: SupportClass) -> Option<&'static Prior> {
    static TABLE: OnceLock<BTreeMap<String, Prior>> = OnceLock::new();
    TABLE
        .get_or_init(|| {
            serde_json::from_str::<GenericTable>(include_str!("../../data/asset_priors.json"))
                .map(|t| t.generic)
                .unwrap_or_default()
        })
        .get(support.as_str())
}

/// The generic shape of the support class in `ctx.variant`.
fn generic(ctx: &mut GenContext) -> Result<Generated, GeometryError> {
    let [w, d, h] = ctx.size;
    let mut b = body(ctx);
    let c = ctx.color;
    match ctx.variant {
        "wall" => {
            let f = (w.min(h) * 0.08).max(0.015);
            b.add_box([0.0, d / 2.0, h / 2.0], [w, d, h], shade(c, 0.7))?;
            b.add_detail(
                [0.0, d + 0.0005, h / 2.0],
                [w - 2.0 * f, 0.001, h - 2.0 * f],
                c,
            );
        }
        "ceiling" => {
            let r = w.min(d) / 2.0;
            b.add_frustum([0.0, 0.0, -0.02], [0.0, 0.0, 0.0], r, r, shade(c, 0.7))?;
            b.add_solid_lathe(&[(r * 0.9, -h), (r * 0.95, -0.02)], c)?;
        }
        "floor" => {
            let plinth = (h * 0.06).clamp(0.02, 0.08);
            b.add_box(
                [0.0, 0.0, plinth / 2.0],
                [w * 0.92, d * 0.92, plinth],
                shade(c, 0.6),
            )?;
            b.add_rounded_box(
                [0.0, 0.0, (plinth + h) / 2.0],
                [w, d, h - plinth],
                (w.min(d) * 0.08).min(0.05),
                c,
            )?;
        }
        _ => {
            b.add_rounded_box([0.0, 0.0, h / 2.0], [w, d, h], w.min(d).min(h) * 0.2, c)?;
        }
    }
    single(b.finish()?, vec![])
}

/// Builds the generic stand-in for `noun`: the support class's generic shape at `size` (or
/// the class's typical size), in `material` / `color` when given. The asset's category is the
/// noun, its provenance says `"generic": true`.
pub fn build_generic(
    noun: &str,
    support: SupportClass,
    size: Option<[f64; 3]>,
    seed: u64,
    material_name: Option<&str>,
    color: Option<[f64; 3]>,
) -> Result<Asset, AssetError> {
    let prior =
        generic_prior(support).ok_or_else(|| AssetError::UnknownCategory(noun.to_string()))?;
    let size = size
        .unwrap_or(prior.typical)
        .map(|v| (v * 1e4).round() / 1e4);
    if size.iter().any(|v| !(v.is_finite() && *v > 0.0)) {
        return Err(AssetError::Malformed {
            asset: noun.to_string(),
            reason: format!("size {size:?} is not positive"),
        });
    }
    let material_name = material_name
        .filter(|m| material::material(m).is_some())
        .unwrap_or(prior.material.as_str())
        .to_string();
    let mat = material::material_or_default(&material_name);
    let color = color.or(prior.color).unwrap_or(mat.color);
    let category = crate::scene::sanitize_name(noun);
    let key = serde_json::json!({
        "generator": "generic",
        "support": support.as_str(),
        "generator_version": GENERATOR_VERSION,
        "noun": category,
        "size": size,
        "material": material_name,
        "color": color,
        "seed": seed,
    });
    let id = content_id(&category, &key);
    let mut ctx = GenContext {
        size,
        material: mat,
        color,
        accent: mat,
        accent_color: shade(color, 0.7),
        variant: support.as_str(),
        style: None,
        rng: ChaCha8Rng::seed_from_u64(seed),
    };
    let generated = generic(&mut ctx).map_err(|source| AssetError::Geometry {
        asset: id.clone(),
        cause: source,
    })?;
    let mut asset = Asset {
        id,
        category: category.clone(),
        material: material_name,
        links: generated.links,
        joints: vec![],
        surfaces: generated.surfaces,
        is_static: false,
        provenance: serde_json::json!({
            "strategy": "procedural",
            "generator": "generic",
            "generic": true,
            "noun": noun,
            "support": support.as_str(),
            "generator_version": GENERATOR_VERSION,
            "parameters": {"size": size, "color": color},
            "seed": seed,
            "license": "CC0-1.0 (generated by scenesmith)",
        }),
    };
    physical::check(&asset, support)?;
    asset.provenance["physics"] =
        serde_json::to_value(physical::summarize(&asset, support)).unwrap_or_default();
    Ok(asset)
}
