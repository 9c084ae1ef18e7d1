//! Procedural assets: parametric, seeded generators made of convex parts.
//!
//! A request names a category and optionally a size, a material and a colour; the category's
//! prior (from `src/data/asset_priors.json`) fills in the rest. The same request always yields
//! the same asset with the same content-addressed id.

mod furniture;
mod small;

use std::collections::BTreeMap;
use std::sync::OnceLock;

use rand::rngs::ChaCha8Rng;
use rand::{RngExt, SeedableRng};
use serde::{Deserialize, Serialize};

use super::{Asset, AssetError, Material, content_id, material};
use crate::scene::SurfaceRecord;

/// Bumped whenever any generator's output changes, so cached assets are rebuilt.
pub const GENERATOR_VERSION: u32 = 1;

/// Where an asset of a category is normally supported.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum SupportClass {
    /// Stands on the floor.
    Floor,
    /// Rests on a furniture surface.
    Surface,
    /// Mounted on a wall.
    Wall,
    /// Hangs from the ceiling.
    Ceiling,
}

/// Size prior and defaults of one category.
#[derive(Debug, Clone, Serialize, Deserialize)]
pub struct Prior {
    /// Generator function name.
    pub generator: String,
    /// Support class.
    pub support: SupportClass,
    /// Default material.
    pub material: String,
    /// Smallest plausible size (x, y, z), metres.
    pub min: [f64; 3],
    /// Typical size, metres.
    pub typical: [f64; 3],
    /// Largest plausible size, metres.
    pub max: [f64; 3],
    /// Other nouns meaning this category.
    #[serde(default)]
    pub aliases: Vec<String>,
}

#[derive(Deserialize)]
struct PriorTable {
    categories: BTreeMap<String, Prior>,
}

fn priors() -> &'static BTreeMap<String, Prior> {
    static TABLE: OnceLock<BTreeMap<String, Prior>> = OnceLock::new();
    TABLE.get_or_init(|| {
        serde_json::from_str::<PriorTable>(include_str!("../../data/asset_priors.json"))
            .map(|t| t.categories)
            .unwrap_or_default()
    })
}

/// The category a noun names (the noun itself or an alias), if any generator knows it.
pub fn resolve_category(noun: &str) -> Option<&'static str> {
    let noun = noun.trim().to_ascii_lowercase();
    let table = priors();
    if let Some((k, _)) = table.get_key_value(noun.as_str()) {
        return Some(k.as_str());
    }
    table
        .iter()
        .find(|(_, p)| p.aliases.iter().any(|a| a == &noun))
        .map(|(k, _)| k.as_str())
}

/// The prior of a category.
pub fn prior(category: &str) -> Option<&'static Prior> {
    priors().get(category)
}

/// Every category with a generator, sorted.
pub fn categories() -> Vec<&'static str> {
    priors().keys().map(String::as_str).collect()
}

/// What to build.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct AssetRequest {
    /// Category noun (or an alias of one).
    pub category: String,
    /// Wanted size (x, y, z) in metres; clamped to the prior's range.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub size: Option<[f64; 3]>,
    /// Material name from the material table.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub material: Option<String>,
    /// Base colour, linear RGB.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub color: Option<[f64; 3]>,
    /// Seed for every random choice of the generator.
    pub seed: u64,
}

impl AssetRequest {
    /// A request for `category` with defaults for everything else.
    pub fn new(category: &str, seed: u64) -> Self {
        AssetRequest {
            category: category.to_string(),
            size: None,
            material: None,
            color: None,
            seed,
        }
    }
}

/// Everything a generator function gets.
pub(crate) struct GenContext {
    pub size: [f64; 3],
    pub material: Material,
    pub color: [f64; 3],
    pub rng: ChaCha8Rng,
}

/// What a generator returns before ids and provenance are attached.
pub(crate) struct Generated {
    pub links: Vec<super::Link>,
    pub joints: Vec<super::Joint>,
    pub surfaces: Vec<SurfaceRecord>,
}

type GeneratorFn = fn(&mut GenContext) -> Result<Generated, crate::geometry::GeometryError>;

fn generator(name: &str) -> Option<GeneratorFn> {
    Some(match name {
        "table" => furniture::table,
        "chair" => furniture::chair,
        "cabinet" => furniture::cabinet,
        "shelf" => furniture::shelf,
        "mug" => small::mug,
        "plate" => small::plate,
        "book" => small::book,
        _ => return None,
    })
}

/// Rounds to 0.1 mm so ids do not depend on float noise.
fn round_size(size: [f64; 3]) -> [f64; 3] {
    size.map(|v| (v * 1e4).round() / 1e4)
}

/// Builds the asset a request describes.
pub fn build(request: &AssetRequest) -> Result<Asset, AssetError> {
    let category = resolve_category(&request.category)
        .ok_or_else(|| AssetError::UnknownCategory(request.category.clone()))?;
    let prior = prior(category).ok_or_else(|| AssetError::UnknownCategory(category.into()))?;
    let gen_fn = generator(&prior.generator)
        .ok_or_else(|| AssetError::UnknownCategory(prior.generator.clone()))?;

    let mut rng = ChaCha8Rng::seed_from_u64(request.seed);
    let size = match request.size {
        Some(s) => {
            let mut out = [0.0; 3];
            for i in 0..3 {
                out[i] = if s[i].is_finite() && s[i] > 0.0 {
                    s[i].clamp(prior.min[i], prior.max[i])
                } else {
                    prior.typical[i]
                };
            }
            out
        }
        None => {
            // Typical size with up to +-6 % seeded variation per axis.
            let mut out = prior.typical;
            for v in out.iter_mut() {
                *v *= 1.0 + rng.random_range(-0.06..0.06);
            }
            out
        }
    };
    let size = round_size(size);
    let material_name = request
        .material
        .clone()
        .filter(|m| material::material(m).is_some())
        .unwrap_or_else(|| prior.material.clone());
    let mat = material::material_or_default(&material_name);
    let color = request.color.unwrap_or(mat.color);

    let key = serde_json::json!({
        "generator": prior.generator,
        "generator_version": GENERATOR_VERSION,
        "size": size,
        "material": material_name,
        "color": color,
        "seed": request.seed,
    });
    let id = content_id(category, &key);
    let mut ctx = GenContext {
        size,
        material: mat,
        color,
        rng,
    };
    let generated = gen_fn(&mut ctx).map_err(|source| AssetError::Geometry {
        asset: id.clone(),
        source,
    })?;
    let asset = Asset {
        id,
        category: category.to_string(),
        material: material_name,
        links: generated.links,
        joints: generated.joints,
        surfaces: generated.surfaces,
        is_static: false,
        provenance: serde_json::json!({
            "strategy": "procedural",
            "generator": prior.generator,
            "generator_version": GENERATOR_VERSION,
            "parameters": {"size": size, "color": color},
            "seed": request.seed,
            "license": "CC0-1.0 (generated by scenesmith)",
        }),
    };
    asset.validate()?;
    Ok(asset)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_category_builds_a_valid_asset_within_its_prior() {
        for cat in categories() {
            let asset = build(&AssetRequest::new(cat, 11)).unwrap();
            asset.validate().unwrap();
            let p = prior(cat).unwrap();
            let [lo, hi] = asset.bounds();
            for i in 0..3 {
                let extent = hi[i] - lo[i];
                assert!(
                    extent >= p.min[i] * 0.9 && extent <= p.max[i] * 1.1,
                    "{cat}: axis {i} extent {extent} outside prior [{}, {}]",
                    p.min[i],
                    p.max[i]
                );
            }
            // Canonical frame: bottom at z = 0, centred in x.
            assert!(lo[2].abs() < 1e-9, "{cat}: bottom at {}", lo[2]);
            assert!((lo[0] + hi[0]).abs() < 0.05, "{cat}: not centred in x");
            assert!(asset.collision_pieces() >= 1);
        }
    }

    #[test]
    fn same_request_same_asset() {
        let r = AssetRequest::new("chair", 5);
        let a = build(&r).unwrap();
        let b = build(&r).unwrap();
        assert_eq!(a, b);
        let c = build(&AssetRequest::new("chair", 6)).unwrap();
        assert_ne!(a.id, c.id);
    }

    #[test]
    fn aliases_and_unknown_nouns() {
        assert_eq!(resolve_category("Bookshelf"), Some("shelf"));
        assert_eq!(resolve_category("coffee mug"), Some("mug"));
        assert!(matches!(
            build(&AssetRequest::new("spaceship", 1)),
            Err(AssetError::UnknownCategory(_))
        ));
    }

    #[test]
    fn requested_size_is_clamped_to_prior() {
        let mut r = AssetRequest::new("table", 1);
        r.size = Some([50.0, 0.9, 0.75]);
        let a = build(&r).unwrap();
        let [lo, hi] = a.bounds();
        assert!(hi[0] - lo[0] <= 3.2 + 1e-9);
    }

    #[test]
    fn cabinet_door_is_articulated() {
        let a = build(&AssetRequest::new("cabinet", 2)).unwrap();
        assert_eq!(a.links.len(), 2);
        assert_eq!(a.joints.len(), 1);
        let j = &a.joints[0];
        assert!(j.lower == 0.0 && j.upper > 1.5);
    }

    #[test]
    fn mug_is_hollow() {
        let a = build(&AssetRequest::new("mug", 3)).unwrap();
        let link = &a.links[0];
        let solid_volume: f64 = link.collisions.iter().map(|c| c.volume()).sum();
        let [lo, hi] = a.bounds();
        let r = (hi[1] - lo[1]) / 2.0;
        let cylinder = std::f64::consts::PI * r * r * (hi[2] - lo[2]);
        assert!(
            solid_volume < 0.4 * cylinder,
            "{solid_volume} vs {cylinder}"
        );
    }
}
