//! The gallery: every category of the procedural library built at its typical size, previewed
//! and laid out on contact sheets (one per support class), for people to look at.
//!
//! `scenesmith gallery --out DIR` writes `DIR/gallery_<class>.png` (`floor`, `wall`, `ceiling`,
//! `surface`) and `DIR/gallery.json` (one row per category: sheet, size, mass, hull count,
//! joints). The same seed gives the same bytes.

use std::path::{Path, PathBuf};

use rayon::prelude::*;
use serde::Serialize;

use super::{Image, RenderError, asset_preview, contact_sheet};
use crate::assets::procedural::{self, AssetRequest, SupportClass};
use crate::util::fsx::write_atomic;

/// Options of a gallery.
#[derive(Debug, Clone)]
pub struct GalleryOptions {
    /// Output directory (created when missing).
    pub out: PathBuf,
    /// Seed of every generator.
    pub seed: u64,
    /// Preview size in pixels (width, height).
    pub cell: (u32, u32),
    /// Images per row of a sheet.
    pub columns: usize,
    /// Only categories whose name contains this (all when `None`).
    pub filter: Option<String>,
}

impl GalleryOptions {
    /// Every category, seed 0, 240 x 180 previews, 12 per row.
    pub fn new(out: impl Into<PathBuf>) -> GalleryOptions {
        GalleryOptions {
            out: out.into(),
            seed: 0,
            cell: (240, 180),
            columns: 12,
            filter: None,
        }
    }
}

/// One category in the gallery.
#[derive(Debug, Clone, Serialize)]
pub struct GalleryEntry {
    /// Category noun.
    pub category: String,
    /// Sheet file it is on (`gallery_floor.png`, ...).
    pub sheet: String,
    /// Size (x, y, z) of the built asset, metres.
    pub size_m: [f64; 3],
    /// Mass, kg.
    pub mass_kg: f64,
    /// Convex collision pieces.
    pub collision_pieces: usize,
    /// Joint names (articulated assets).
    pub joints: Vec<String>,
}

/// What a gallery run wrote.
#[derive(Debug, Clone, Serialize)]
pub struct GalleryReport {
    /// Sheets written.
    pub sheets: Vec<PathBuf>,
    /// Every category shown.
    pub entries: Vec<GalleryEntry>,
    /// Categories that failed to build or render, with the reason.
    pub failed: Vec<(String, String)>,
}

/// Why a gallery could not be made.
#[derive(Debug, thiserror::Error)]
pub enum GalleryError {
    /// No category matched the filter.
    #[error("no category matches {0:?}")]
    NothingMatches(String),
    /// Rendering or writing failed.
    #[error(transparent)]
    Render(#[from] RenderError),
    /// The index could not be serialised.
    #[error("gallery.json: {0}")]
    Index(String),
}

fn class_name(s: SupportClass) -> &'static str {
    match s {
        SupportClass::Floor => "floor",
        SupportClass::Wall => "wall",
        SupportClass::Ceiling => "ceiling",
        SupportClass::Surface => "surface",
    }
}

/// A rendered category, or why it failed.
type Rendered = Result<(GalleryEntry, Image), String>;

fn render_category(category: &str, sheet: &str, opts: &GalleryOptions) -> Rendered {
    let asset =
        procedural::build(&AssetRequest::new(category, opts.seed)).map_err(|e| e.to_string())?;
    let image = asset_preview(&asset, opts.cell.0, opts.cell.1).map_err(|e| e.to_string())?;
    let [lo, hi] = asset.bounds();
    let entry = GalleryEntry {
        category: category.to_string(),
        sheet: sheet.to_string(),
        size_m: [hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]],
        mass_kg: asset.links.iter().map(|l| l.mass.mass).sum(),
        collision_pieces: asset.links.iter().map(|l| l.collisions.len()).sum(),
        joints: asset.joints.iter().map(|j| j.name.clone()).collect(),
    };
    Ok((entry, image))
}

/// Builds, previews and lays out every category; writes the sheets and `gallery.json`.
pub fn write_gallery(opts: &GalleryOptions) -> Result<GalleryReport, GalleryError> {
    let mut by_class: Vec<(SupportClass, Vec<&'static str>)> = [
        SupportClass::Floor,
        SupportClass::Wall,
        SupportClass::Ceiling,
        SupportClass::Surface,
    ]
    .into_iter()
    .map(|c| (c, Vec::new()))
    .collect();
    for category in procedural::categories() {
        if let Some(f) = &opts.filter
            && !category.contains(f.as_str())
        {
            continue;
        }
        let Some(prior) = procedural::prior(category) else {
            continue;
        };
        if let Some((_, list)) = by_class.iter_mut().find(|(c, _)| *c == prior.support) {
            list.push(category);
        }
    }
    if by_class.iter().all(|(_, l)| l.is_empty()) {
        return Err(GalleryError::NothingMatches(
            opts.filter.clone().unwrap_or_default(),
        ));
    }
    let mut report = GalleryReport {
        sheets: Vec::new(),
        entries: Vec::new(),
        failed: Vec::new(),
    };
    for (class, categories) in by_class.iter().filter(|(_, l)| !l.is_empty()) {
        let sheet = format!("gallery_{}.png", class_name(*class));
        // Categories render in parallel; the sheet keeps the sorted order.
        let rendered: Vec<(&str, Rendered)> = categories
            .par_iter()
            .map(|c| (*c, render_category(c, &sheet, opts)))
            .collect();
        let mut items = Vec::new();
        for (category, r) in rendered {
            match r {
                Ok((entry, image)) => {
                    items.push((category.to_string(), image));
                    report.entries.push(entry);
                }
                Err(reason) => report.failed.push((category.to_string(), reason)),
            }
        }
        if items.is_empty() {
            continue;
        }
        let png = contact_sheet(&items, opts.columns)?.encode_png()?;
        let path = opts.out.join(&sheet);
        write_file(&path, &png)?;
        report.sheets.push(path);
    }
    let mut index = serde_json::to_string_pretty(&report.entries)
        .map_err(|e| GalleryError::Index(e.to_string()))?;
    index.push('\n');
    write_file(&opts.out.join("gallery.json"), index.as_bytes())?;
    Ok(report)
}

fn write_file(path: &Path, bytes: &[u8]) -> Result<(), RenderError> {
    write_atomic(path, bytes)?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_filtered_gallery_shows_every_matching_category_once() {
        let dir = tempfile::tempdir().unwrap();
        let mut opts = GalleryOptions::new(dir.path());
        opts.filter = Some("table".into());
        opts.cell = (96, 72);
        let report = write_gallery(&opts).unwrap();
        assert!(report.failed.is_empty(), "{:?}", report.failed);
        let want: Vec<&str> = procedural::categories()
            .into_iter()
            .filter(|c| c.contains("table"))
            .collect();
        let mut got: Vec<&str> = report.entries.iter().map(|e| e.category.as_str()).collect();
        got.sort();
        assert_eq!(got, want);
        for sheet in &report.sheets {
            let bytes = std::fs::read(sheet).unwrap();
            assert_eq!(&bytes[1..4], b"PNG");
        }
        let index: serde_json::Value =
            serde_json::from_slice(&std::fs::read(dir.path().join("gallery.json")).unwrap())
                .unwrap();
        assert_eq!(index.as_array().unwrap().len(), want.len());
        // A table is taller than a coffee table, and everything weighs something.
        let size = |c: &str| {
            report
                .entries
                .iter()
                .find(|e| e.category == c)
                .map(|e| e.size_m[2])
        };
        assert!(size("table").unwrap_or(0.0) > size("coffee_table").unwrap_or(1.0));
        assert!(report.entries.iter().all(|e| e.mass_kg > 0.0));

        opts.filter = Some("no such thing".into());
        assert!(matches!(
            write_gallery(&opts),
            Err(GalleryError::NothingMatches(_))
        ));
    }
}
