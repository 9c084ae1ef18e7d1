//! What `scenesmith asset` does, as a library call: route one description, write the asset
//! (and its composite parts) as asset directories, report what was made.

use std::path::{Path, PathBuf};

use serde::Serialize;

use crate::assets::router::{self, RouteError, RouteRequest, Routed, RouterContext, Stage};
use crate::assets::{Asset, procedural};
use crate::formats::asset_dir::{AssetWriteError, write_asset_dir};

/// Options of one `scenesmith asset` run.
#[derive(Debug, Clone)]
pub struct AssetOptions {
    /// The description.
    pub description: String,
    /// Output directory.
    pub out: PathBuf,
    /// Stage to route for (guessed from the noun when `None`).
    pub stage: Option<Stage>,
    /// Target size (x, y, z), metres.
    pub size: Option<[f64; 3]>,
    /// Seed.
    pub seed: u64,
}

/// What could go wrong.
#[derive(Debug, thiserror::Error)]
pub enum AssetCommandError {
    /// The router refused or failed.
    #[error(transparent)]
    Route(#[from] RouteError),
    /// Writing failed.
    #[error(transparent)]
    Write(#[from] AssetWriteError),
}

/// One written asset.
#[derive(Debug, Clone, Serialize)]
pub struct WrittenAsset {
    /// Directory.
    pub dir: PathBuf,
    /// Asset id.
    pub id: String,
    /// Category.
    pub category: String,
    /// How it was made.
    pub strategy: router::Strategy,
    /// How many the request wants.
    pub count: u32,
    /// Its relation to the main object.
    pub role: router::Role,
    /// Size (x, y, z), metres.
    pub size_m: [f64; 3],
    /// Mass, kg.
    pub mass_kg: f64,
    /// Convex collision pieces.
    pub collision_pieces: usize,
    /// Joint names.
    pub joints: Vec<String>,
}

/// The report of a run.
#[derive(Debug, Clone, Serialize)]
pub struct AssetReport {
    /// The stage routed for.
    pub stage: Stage,
    /// The main asset and parts.
    pub assets: Vec<WrittenAsset>,
    /// Parts for later stages.
    pub deferred: Vec<router::DeferredRequest>,
    /// Notes from the router.
    pub notes: Vec<String>,
    /// Whether the result came from the cache.
    pub cached: bool,
}

/// The stage a description most likely belongs to: the support class of the first category
/// its noun names, furniture when unknown.
pub fn guess_stage(description: &str) -> Stage {
    let parsed = router::parse::parse(description);
    let cat = parsed
        .compound
        .as_ref()
        .map(|(_, c)| c.container.clone())
        .or_else(|| parsed.main.categories.first().map(|c| c.to_string()));
    cat.and_then(|c| procedural::prior(&c).map(|p| Stage::for_support(p.support)))
        .unwrap_or(Stage::Furniture)
}

fn summary(asset: &Asset, routed: &Routed) -> serde_json::Value {
    serde_json::json!({
        "physics": asset.provenance.get("physics"),
        "notes": routed.notes,
        "deferred": routed.deferred,
        "attributes": routed.attributes,
    })
}

/// Renders a PNG preview of an asset, `None` when it cannot.
pub type PreviewFn<'a> = &'a dyn Fn(&Asset) -> Option<Vec<u8>>;

/// Routes and writes: the main asset into `out`, each part into `out/parts/<category>`.
/// `preview` renders a PNG of an asset (the CLI passes the renderer; `None` skips previews).
pub fn make_asset(
    opts: &AssetOptions,
    ctx: &RouterContext,
    preview: Option<PreviewFn<'_>>,
) -> Result<AssetReport, AssetCommandError> {
    let stage = opts.stage.unwrap_or_else(|| guess_stage(&opts.description));
    let mut req = RouteRequest::new(&opts.description, stage, opts.seed);
    req.size = opts.size;
    let routed = router::route(&req, ctx)?;
    let mut assets = Vec::new();
    let all = std::iter::once(&routed.primary).chain(&routed.parts);
    for (k, part) in all.enumerate() {
        let dir = if k == 0 {
            opts.out.clone()
        } else {
            opts.out
                .join("parts")
                .join(format!("{}_{k}", part.category))
        };
        let png = preview.and_then(|f| f(&part.asset));
        write_asset_dir(
            &dir,
            &part.asset,
            summary(&part.asset, &routed),
            png.as_deref(),
        )?;
        let [lo, hi] = part.asset.bounds();
        assets.push(WrittenAsset {
            dir,
            id: part.asset.id.clone(),
            category: part.category.clone(),
            strategy: part.strategy,
            count: part.count,
            role: part.role,
            size_m: [hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]],
            mass_kg: part.asset.mass(),
            collision_pieces: part.asset.collision_pieces(),
            joints: part.asset.joints.iter().map(|j| j.name.clone()).collect(),
        });
    }
    Ok(AssetReport {
        stage,
        assets,
        deferred: routed.deferred,
        notes: routed.notes,
        cached: routed.cached,
    })
}

/// Whether `dir` holds an asset directory written by [`make_asset`].
pub fn is_asset_dir(dir: &Path) -> bool {
    dir.join(crate::formats::asset_dir::ASSET_JSON).is_file()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stage_guesses() {
        assert_eq!(guess_stage("a red mug"), Stage::Manipuland);
        assert_eq!(guess_stage("a chandelier"), Stage::Ceiling);
        assert_eq!(guess_stage("a wall mirror"), Stage::Wall);
        assert_eq!(guess_stage("fruit bowl"), Stage::Manipuland);
        assert_eq!(guess_stage("a flux capacitor"), Stage::Furniture);
        // A noun the library lacks takes the stage of its WordNet family (a desk).
        assert_eq!(guess_stage("an escritoire"), Stage::Furniture);
        assert_eq!(guess_stage("a samovar"), Stage::Manipuland);
    }

    #[test]
    fn writes_the_main_asset_and_its_parts() {
        let root = tempfile::tempdir().unwrap();
        let opts = AssetOptions {
            description: "a bowl with 4 apples".into(),
            out: root.path().join("bowl"),
            stage: None,
            size: None,
            seed: 1,
        };
        let r = make_asset(&opts, &RouterContext::new(), None).unwrap();
        assert_eq!(r.stage, Stage::Manipuland);
        assert_eq!(r.assets.len(), 2);
        assert!(is_asset_dir(&opts.out));
        assert!(r.assets[1].dir.join("model.sdf").is_file());
        assert_eq!(r.assets[1].count, 4);
    }
}
