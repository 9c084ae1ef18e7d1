//! Procedural assets: parametric, seeded generators made of exact convex parts.
//!
//! A request names a category and optionally a size, a material and a colour; the category's
//! prior (from `src/data/asset_priors.json`: size range, support class, default and accent
//! materials, generator and variant, aliases) fills in the rest. The same request always yields
//! the same asset with the same content-addressed id.
//!
//! Generators live in one file per family (`tables`, `seating`, `beds`, `storage`, `kitchen`,
//! `bathroom`, `equipment`, `misc`, `lighting`, `wall`, `kitchenware`, `food`, `electronics`,
//! `decor`);
//! thin coverings (rugs, posters, tablecloths) are in [`crate::assets::thin`] and drawers and
//! doors in [`crate::assets::articulated`]. Nouns no generator knows get a generic shape
//! from their support class through [`build_generic`], marked `generic` in provenance.
//!
//! This module does not decide which stage may ask for what, split composites, or cache: that
//! is the router's job ([`crate::assets::router`]).

mod bathroom;
mod beds;
mod decor;
mod electronics;
mod equipment;
mod food;
mod generic;
mod kitchen;
mod kitchenware;
mod lighting;
mod misc;
pub(crate) mod parts;
mod seating;
pub mod shapes;
mod shelving;
mod storage;
mod tables;
mod toys;
mod wall;

use std::collections::BTreeMap;
use std::sync::OnceLock;

use rand::rngs::ChaCha8Rng;
use rand::{RngExt, SeedableRng};
use serde::{Deserialize, Serialize};

use super::attributes::Style;
use super::{Asset, AssetError, Link, Material, content_id, material, physical};
use crate::geometry::ConvexPiece;
use crate::scene::SurfaceRecord;

pub use generic::build_generic;

/// Bumped whenever any generator's output changes, so cached assets are rebuilt.
pub const GENERATOR_VERSION: u32 = 5;

/// A fingerprint of everything that shapes a built asset: the generators, the geometry and
/// physics code and the data tables, hashed from their sources compiled into the binary. The
/// disk cache keys on it, so an asset built by an older binary is never served after a
/// change, without anyone remembering to bump [`GENERATOR_VERSION`].
pub fn generator_fingerprint() -> &'static str {
    static FINGERPRINT: std::sync::OnceLock<String> = std::sync::OnceLock::new();
    FINGERPRINT.get_or_init(|| {
        let sources: &[&[u8]] = &[
            include_bytes!("bathroom.rs").as_slice(),
            include_bytes!("beds.rs").as_slice(),
            include_bytes!("decor.rs").as_slice(),
            include_bytes!("electronics.rs").as_slice(),
            include_bytes!("equipment.rs").as_slice(),
            include_bytes!("food.rs").as_slice(),
            include_bytes!("generic.rs").as_slice(),
            include_bytes!("kitchen.rs").as_slice(),
            include_bytes!("kitchenware.rs").as_slice(),
            include_bytes!("lighting.rs").as_slice(),
            include_bytes!("misc.rs").as_slice(),
            include_bytes!("mod.rs").as_slice(),
            include_bytes!("parts.rs").as_slice(),
            include_bytes!("seating.rs").as_slice(),
            include_bytes!("shapes.rs").as_slice(),
            include_bytes!("shelving.rs").as_slice(),
            include_bytes!("storage.rs").as_slice(),
            include_bytes!("tables.rs").as_slice(),
            include_bytes!("toys.rs").as_slice(),
            include_bytes!("wall.rs").as_slice(),
            include_bytes!("../articulated/library.rs").as_slice(),
            include_bytes!("../articulated/mod.rs").as_slice(),
            include_bytes!("../articulated/parts.rs").as_slice(),
            include_bytes!("../articulated/reader.rs").as_slice(),
            include_bytes!("../textures/art.rs").as_slice(),
            include_bytes!("../textures/mod.rs").as_slice(),
            include_bytes!("../../geometry/convex.rs").as_slice(),
            include_bytes!("../../geometry/mass.rs").as_slice(),
            include_bytes!("../../geometry/mesh.rs").as_slice(),
            include_bytes!("../../geometry/mod.rs").as_slice(),
            include_bytes!("../../geometry/polygon.rs").as_slice(),
            include_bytes!("../builder.rs").as_slice(),
            include_bytes!("../physical.rs").as_slice(),
            include_bytes!("../material.rs").as_slice(),
            include_bytes!("../attributes.rs").as_slice(),
            include_bytes!("../thin.rs").as_slice(),
            include_bytes!("../mod.rs").as_slice(),
            include_bytes!("../../data/asset_priors.json").as_slice(),
            include_bytes!("../../data/asset_attributes.json").as_slice(),
            include_bytes!("../../data/materials.json").as_slice(),
        ];
        let mut h = blake3::Hasher::new();
        for s in sources {
            h.update(&(s.len() as u64).to_le_bytes());
            h.update(s);
        }
        h.finalize().to_hex()[..12].to_string()
    })
}

/// Where an asset of a category is normally supported.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
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

impl SupportClass {
    /// `floor`, `surface`, `wall`, `ceiling`.
    pub fn as_str(self) -> &'static str {
        match self {
            SupportClass::Floor => "floor",
            SupportClass::Surface => "surface",
            SupportClass::Wall => "wall",
            SupportClass::Ceiling => "ceiling",
        }
    }
}

/// How the embedded library makes a category.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Kind {
    /// Rigid parametric model.
    #[default]
    Procedural,
    /// Parametric model with joints (doors, drawers, lids).
    Articulated,
    /// Thin textured geometry (rugs, posters, tablecloths).
    ThinCovering,
}

impl Kind {
    /// `procedural`, `articulated`, `thin_covering`.
    pub fn as_str(self) -> &'static str {
        match self {
            Kind::Procedural => "procedural",
            Kind::Articulated => "articulated",
            Kind::ThinCovering => "thin_covering",
        }
    }
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
    /// Variant of the generator (`coffee` for a coffee table, `king` for a bed, ...).
    #[serde(default)]
    pub variant: String,
    /// Material of legs, frames, handles and trims (the main material when absent).
    #[serde(default)]
    pub accent: Option<String>,
    /// Procedural, articulated or thin covering.
    #[serde(default)]
    pub kind: Kind,
    /// Things are put inside it (bowls, baskets, bins, drawers' carcasses, fridges).
    #[serde(default)]
    pub container: bool,
    /// Default colour (linear RGB) when the request names none; the material's otherwise.
    #[serde(default)]
    pub color: Option<[f64; 3]>,
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

/// Noun (category or alias, lower case, single spaces) -> categories it may mean, the
/// category itself first.
fn noun_index() -> &'static BTreeMap<String, Vec<&'static str>> {
    static INDEX: OnceLock<BTreeMap<String, Vec<&'static str>>> = OnceLock::new();
    INDEX.get_or_init(|| {
        let mut index: BTreeMap<String, Vec<&'static str>> = BTreeMap::new();
        for (k, p) in priors() {
            index
                .entry(k.replace('_', " "))
                .or_default()
                .insert(0, k.as_str());
            for a in &p.aliases {
                let e = index.entry(a.clone()).or_default();
                if !e.contains(&k.as_str()) {
                    e.push(k.as_str());
                }
            }
        }
        index
    })
}

fn normalize_noun(noun: &str) -> String {
    noun.trim()
        .to_ascii_lowercase()
        .replace(['_', '-'], " ")
        .split_whitespace()
        .collect::<Vec<_>>()
        .join(" ")
}

/// The category a noun names (the noun itself or an alias), if any generator knows it.
pub fn resolve_category(noun: &str) -> Option<&'static str> {
    let noun = normalize_noun(noun);
    if let Some((k, _)) = priors().get_key_value(noun.replace(' ', "_").as_str()) {
        return Some(k.as_str());
    }
    noun_index().get(&noun).and_then(|v| v.first().copied())
}

/// Every category a noun may name (a "clock" is a wall clock or a table clock); the first is
/// what [`resolve_category`] returns.
pub fn candidate_categories(noun: &str) -> Vec<&'static str> {
    let noun = normalize_noun(noun);
    let mut out: Vec<&'static str> = Vec::new();
    if let Some((k, _)) = priors().get_key_value(noun.replace(' ', "_").as_str()) {
        out.push(k.as_str());
    }
    for c in noun_index().get(&noun).into_iter().flatten() {
        if !out.contains(c) {
            out.push(c);
        }
    }
    out
}

/// Every noun the library knows (categories with spaces, and aliases), longest first.
pub fn known_nouns() -> Vec<&'static str> {
    let mut v: Vec<&'static str> = noun_index().keys().map(String::as_str).collect();
    v.sort_by(|a, b| b.len().cmp(&a.len()).then(a.cmp(b)));
    v
}

/// The prior of a category.
pub fn prior(category: &str) -> Option<&'static Prior> {
    priors().get(category)
}

/// The category of `category`'s generator that rests on `support` and answers to the same
/// head noun ("storage bin" on a shelf, "toy bin" on the floor: both are a "bin"), when
/// `category` itself rests elsewhere.
pub fn support_sibling(category: &str, support: SupportClass) -> Option<&'static str> {
    let p = prior(category)?;
    if p.support == support {
        return None;
    }
    let head = category.rsplit('_').next()?;
    let named = |c: &str, q: &Prior| {
        q.support == support
            && (c.rsplit('_').next() == Some(head) || q.aliases.iter().any(|a| a == head))
    };
    // The same generator's variant first; else a kind of the same head noun built by
    // another generator (a shelf on the wall: a wall shelf).
    priors()
        .iter()
        .find(|(c, q)| q.generator == p.generator && named(c, q))
        .or_else(|| priors().iter().find(|(c, q)| named(c, q)))
        .map(|(c, _)| c.as_str())
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
    /// Bounding size (x, y, z) the asset must fill, metres.
    pub size: [f64; 3],
    /// Main material.
    pub material: Material,
    /// Main colour, linear RGB.
    pub color: [f64; 3],
    /// Material of legs, frames, handles.
    pub accent: Material,
    /// Colour of legs, frames, handles.
    pub accent_color: [f64; 3],
    /// Generator variant from the prior.
    pub variant: &'static str,
    /// Style from the request, if any.
    pub style: Option<Style>,
    /// The seeded random source.
    pub rng: ChaCha8Rng,
}

impl GenContext {
    /// The style's name, or "".
    pub fn style_name(&self) -> &str {
        self.style.as_ref().map_or("", |s| s.name.as_str())
    }

    /// A palette colour of the style (or a default palette), chosen by index.
    pub fn palette(&self, i: usize) -> [f64; 3] {
        const DEFAULT: [[f64; 3]; 6] = [
            [0.55, 0.05, 0.04],
            [0.05, 0.20, 0.50],
            [0.80, 0.55, 0.08],
            [0.10, 0.35, 0.12],
            [0.85, 0.85, 0.82],
            [0.04, 0.04, 0.05],
        ];
        match &self.style {
            Some(s) if !s.palette.is_empty() => s.palette[i % s.palette.len()],
            _ => DEFAULT[i % DEFAULT.len()],
        }
    }

    /// A uniform random number in `[lo, hi)`.
    pub fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        if hi > lo {
            self.rng.random_range(lo..hi)
        } else {
            lo
        }
    }
}

/// What a generator returns before ids and provenance are attached.
pub(crate) struct Generated {
    pub links: Vec<super::Link>,
    pub joints: Vec<super::Joint>,
    pub surfaces: Vec<SurfaceRecord>,
}

pub(crate) type GeneratorFn =
    fn(&mut GenContext) -> Result<Generated, crate::geometry::GeometryError>;

fn generator(name: &str) -> Option<GeneratorFn> {
    static TABLE: OnceLock<BTreeMap<&'static str, GeneratorFn>> = OnceLock::new();
    TABLE
        .get_or_init(|| {
            let families: [&[(&str, GeneratorFn)]; 18] = [
                tables::GENERATORS,
                seating::GENERATORS,
                beds::GENERATORS,
                storage::GENERATORS,
                shelving::GENERATORS,
                kitchen::GENERATORS,
                bathroom::GENERATORS,
                equipment::GENERATORS,
                misc::GENERATORS,
                lighting::GENERATORS,
                wall::GENERATORS,
                kitchenware::GENERATORS,
                food::GENERATORS,
                electronics::GENERATORS,
                decor::GENERATORS,
                toys::GENERATORS,
                super::thin::GENERATORS,
                generic::GENERATORS,
            ];
            families.iter().flat_map(|f| f.iter().copied()).collect()
        })
        .get(name)
        .copied()
}

/// Rounds to 0.1 mm so ids do not depend on float noise.
fn round_size(size: [f64; 3]) -> [f64; 3] {
    size.map(|v| (v * 1e4).round() / 1e4)
}

/// Whether a material name is one of the woods (styles replace woods, not metals or glass).
fn is_wood(name: &str) -> bool {
    matches!(
        name,
        "wood"
            | "oak"
            | "walnut"
            | "pine"
            | "mdf"
            | "cherry"
            | "maple"
            | "mahogany"
            | "teak"
            | "birch"
            | "laminate"
    )
}

/// The pieces of `link` that reach its lowest level (within 0.1 mm): what it stands on.
fn feet(link: &Link) -> Vec<&ConvexPiece> {
    let lowest = link
        .collisions
        .iter()
        .map(|c| c.bounds().0[2])
        .fold(f64::INFINITY, f64::min);
    link.collisions
        .iter()
        .filter(|c| c.bounds().0[2] <= lowest + 1e-4)
        .collect()
}

/// A bottom face at least this wide gets contact pads ([`ConvexPiece::corner_pads`]), metres.
const PAD_MIN_EXTENT_M: f64 = 0.05;

/// Contact pads under the pieces of a floor-standing `link` that reach its lowest level when
/// fewer than three do (a plinth, a base), at most `room` of them (the asset's piece budget):
/// the link rests on four points or more under point contact, not one or two. Small objects
/// get none: four more compliant pieces on each of a kitchen's 90 objects made its stability
/// check 1.5x slower in Drake's default (hydroelastic) contact, for 1-2 cm of drift of a
/// printer or a keyboard under point contact. Legs and side panels
/// already give a point each and get none: a filing cabinet on two side panels and a back
/// plinth with pads besides slid 3 cm under point contact, without them it stays.
fn add_corner_pads(link: &mut Link, room: usize) {
    let feet = feet(link);
    // Three pieces on the floor (legs, side panels) already give three points.
    if feet.len() >= 3 {
        return;
    }
    let pads: Vec<ConvexPiece> = feet
        .iter()
        .flat_map(|c| c.corner_pads(PAD_MIN_EXTENT_M))
        .take(room)
        .collect();
    link.collisions.extend(pads);
}

/// Builds the asset a request describes.
pub fn build(request: &AssetRequest) -> Result<Asset, AssetError> {
    build_styled(request, None)
}

/// Everything decided about a build before the generator runs.
struct Plan {
    category: &'static str,
    prior: &'static Prior,
    gen_fn: GeneratorFn,
    size: [f64; 3],
    material_name: String,
    material: Material,
    color: [f64; 3],
    accent_name: String,
    accent: Material,
    accent_color: [f64; 3],
    style_name: Option<String>,
    id: String,
    rng: ChaCha8Rng,
}

fn plan(request: &AssetRequest, style: Option<&Style>) -> Result<Plan, AssetError> {
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
            // Typical size with up to +-6 % seeded variation per axis, inside the prior.
            let mut out = prior.typical;
            for (i, v) in out.iter_mut().enumerate() {
                *v = (*v * (1.0 + rng.random_range(-0.06..0.06))).clamp(prior.min[i], prior.max[i]);
            }
            out
        }
    };
    let size = round_size(size);
    let material_name = request
        .material
        .clone()
        .filter(|m| material::material(m).is_some())
        .or_else(|| {
            style
                .filter(|_| is_wood(&prior.material))
                .map(|s| s.main_material.clone())
        })
        .unwrap_or_else(|| prior.material.clone());
    let mat = material::material_or_default(&material_name);
    let color = request.color.or(prior.color).unwrap_or(mat.color);
    let accent_name = style
        .map(|s| s.accent_material.clone())
        .or_else(|| prior.accent.clone())
        .unwrap_or_else(|| material_name.clone());
    let accent = material::material_or_default(&accent_name);
    let accent_color = match (style, &prior.accent) {
        (Some(s), _) => s.accent_color,
        (None, Some(_)) => accent.color,
        (None, None) => parts::shade(color, 0.82),
    };
    let style_name = style.map(|s| s.name.clone());
    let key = serde_json::json!({
        "generator": prior.generator,
        "variant": prior.variant,
        "generator_version": GENERATOR_VERSION,
        "size": size,
        "material": material_name,
        "color": color,
        "style": style_name,
        "seed": request.seed,
    });
    let id = content_id(category, &key);
    Ok(Plan {
        category,
        prior,
        gen_fn,
        size,
        material_name,
        material: mat,
        color,
        accent_name,
        accent,
        accent_color,
        style_name,
        id,
        rng,
    })
}

/// The content id [`build_styled`] would give this request, without building it (for cache
/// look-ups).
pub fn asset_id(request: &AssetRequest, style: Option<&Style>) -> Result<String, AssetError> {
    plan(request, style).map(|p| p.id)
}

/// Builds the asset a request describes in a style (accent material and colour, palette,
/// wood replaced by the style's main material unless the request names a material).
pub fn build_styled(request: &AssetRequest, style: Option<&Style>) -> Result<Asset, AssetError> {
    let p = plan(request, style)?;
    let mut ctx = GenContext {
        size: p.size,
        material: p.material,
        color: p.color,
        accent: p.accent,
        accent_color: p.accent_color,
        variant: p.prior.variant.as_str(),
        style: style.cloned(),
        rng: p.rng,
    };
    let mut generated = (p.gen_fn)(&mut ctx).map_err(|source| AssetError::Geometry {
        asset: p.id.clone(),
        cause: source,
    })?;
    let pieces: usize = generated.links.iter().map(|l| l.collisions.len()).sum();
    let room = physical::hull_cap(p.prior.support).saturating_sub(pieces);
    if p.prior.support == SupportClass::Floor
        && let Some(root) = generated.links.first_mut()
    {
        add_corner_pads(root, room);
    }
    let kind = if generated.joints.is_empty() {
        p.prior.kind
    } else {
        Kind::Articulated
    };
    let mut asset = Asset {
        id: p.id,
        category: p.category.to_string(),
        material: p.material_name,
        links: generated.links,
        joints: generated.joints,
        surfaces: generated.surfaces,
        is_static: false,
        provenance: serde_json::json!({
            "strategy": kind.as_str(),
            "generator": p.prior.generator,
            "variant": p.prior.variant,
            "generator_version": GENERATOR_VERSION,
            "parameters": {"size": p.size, "color": p.color, "accent": p.accent_name, "style": p.style_name},
            "support": p.prior.support.as_str(),
            "seed": request.seed,
            "license": "CC0-1.0 (generated by scenesmith)",
        }),
    };
    physical::check(&asset, p.prior.support)?;
    let summary = physical::summarize(&asset, p.prior.support);
    asset.provenance["physics"] = serde_json::to_value(&summary).unwrap_or_default();
    Ok(asset)
}

#[cfg(test)]
mod tests;
