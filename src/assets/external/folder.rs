//! A local folder of meshes (OBJ, glTF, GLB) described by `index.json`, searchable by text
//! and size.
//!
//! ```json
//! {"meshes": [
//!   {"file": "chairs/eames.glb", "name": "lounge chair", "description": "leather lounge chair",
//!    "category": "armchair", "tags": ["mid-century"], "dimensions_m": [0.84, 0.85, 0.83],
//!    "support": "floor", "material": "leather", "up": "+y", "front": "+z", "units": "m",
//!    "hollow": null, "license": "CC-BY-4.0"}
//! ]}
//! ```
//!
//! Only `file` is required. `up` / `front` are axes in the file's own coordinates (defaults:
//! glTF's +Y up and +Z front for `.gltf`/`.glb`; the same for `.obj`), `units` is `m`, `cm`
//! or `mm` (default `m`), `support` defaults to the router's stage, `material` to `plastic`.
//! Paths are relative to the folder and may not leave it.

use std::path::{Path, PathBuf};

use serde::Deserialize;

use super::import::{Axis, ImportOptions, import_parts};
use super::{ExternalError, match_score, search_words};
use crate::assets::procedural::SupportClass;
use crate::assets::{Asset, VisualPart};

/// One mesh of the folder.
#[derive(Debug, Clone, Deserialize)]
pub struct MeshEntry {
    /// Path relative to the folder.
    pub file: String,
    /// Short name.
    #[serde(default)]
    pub name: String,
    /// Free text.
    #[serde(default)]
    pub description: String,
    /// Category noun.
    #[serde(default)]
    pub category: String,
    /// Extra search words.
    #[serde(default)]
    pub tags: Vec<String>,
    /// Real size (x, y, z) in metres after canonicalisation, if known.
    #[serde(default)]
    pub dimensions_m: Option<[f64; 3]>,
    /// Support class.
    #[serde(default)]
    pub support: Option<SupportClass>,
    /// Material name.
    #[serde(default)]
    pub material: Option<String>,
    /// Up axis in file coordinates.
    #[serde(default)]
    pub up: Option<Axis>,
    /// Front axis in file coordinates.
    #[serde(default)]
    pub front: Option<Axis>,
    /// `m`, `cm` or `mm`.
    #[serde(default)]
    pub units: Option<String>,
    /// Wall thickness of a hollow object, metres.
    #[serde(default)]
    pub hollow: Option<f64>,
    /// Licence of the file.
    #[serde(default)]
    pub license: Option<String>,
}

impl MeshEntry {
    fn words(&self) -> Vec<String> {
        search_words(&format!(
            "{} {} {} {}",
            self.name,
            self.description,
            self.category.replace('_', " "),
            self.tags.join(" ")
        ))
    }
}

#[derive(Deserialize)]
#[serde(untagged)]
enum IndexFile {
    Wrapped { meshes: Vec<MeshEntry> },
    Bare(Vec<MeshEntry>),
}

/// An opened mesh folder.
#[derive(Debug, Clone)]
pub struct MeshFolder {
    dir: PathBuf,
    entries: Vec<MeshEntry>,
    index_hash: String,
}

/// Resolves `rel` inside `dir`, refusing absolute paths and `..`.
pub(crate) fn inside(dir: &Path, rel: &str) -> Result<PathBuf, ExternalError> {
    let p = Path::new(rel);
    if p.is_absolute()
        || p.components()
            .any(|c| matches!(c, std::path::Component::ParentDir))
    {
        return Err(ExternalError::Mesh(format!(
            "path {rel:?} leaves the folder"
        )));
    }
    Ok(dir.join(p))
}

/// Reads a mesh file (OBJ, glTF, GLB) into visual parts; glTF is converted to +Z up on the way.
pub(crate) fn read_mesh_file(path: &Path) -> Result<(Vec<VisualPart>, bool), ExternalError> {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .unwrap_or("")
        .to_ascii_lowercase();
    match ext.as_str() {
        "gltf" | "glb" => crate::assets::gltf_read::read_file(path)
            .map(|p| (p, true))
            .map_err(ExternalError::Mesh),
        "obj" => {
            let text = std::fs::read_to_string(path).map_err(|e| ExternalError::Io {
                path: path.to_path_buf(),
                message: e.to_string(),
            })?;
            let mut mesh = crate::geometry::obj::parse_obj(&text)
                .map_err(|e| ExternalError::Mesh(format!("{}: {e}", path.display())))?;
            if mesh.normals.len() != mesh.positions.len() {
                crate::geometry::mesh::recompute_normals(&mut mesh);
            }
            Ok((
                vec![VisualPart {
                    name: "part_0".into(),
                    mesh,
                    color: [0.7, 0.7, 0.7, 1.0],
                    texture: None,
                }],
                false,
            ))
        }
        other => Err(ExternalError::Mesh(format!(
            "{}: unsupported mesh format {other:?} (use OBJ, glTF or GLB)",
            path.display()
        ))),
    }
}

impl MeshFolder {
    /// Opens `dir/index.json`.
    pub fn open(dir: &Path) -> Result<MeshFolder, ExternalError> {
        let path = dir.join("index.json");
        let text = std::fs::read_to_string(&path).map_err(|e| ExternalError::Io {
            path: path.clone(),
            message: e.to_string(),
        })?;
        let index: IndexFile = serde_json::from_str(&text).map_err(|e| ExternalError::Index {
            path: path.clone(),
            message: e.to_string(),
        })?;
        let entries = match index {
            IndexFile::Wrapped { meshes } => meshes,
            IndexFile::Bare(m) => m,
        };
        for e in &entries {
            inside(dir, &e.file).map_err(|err| ExternalError::Index {
                path: path.clone(),
                message: err.to_string(),
            })?;
        }
        Ok(MeshFolder {
            dir: dir.to_path_buf(),
            entries,
            index_hash: blake3::hash(text.as_bytes()).to_hex()[..16].to_string(),
        })
    }

    /// The folder's entries.
    pub fn entries(&self) -> &[MeshEntry] {
        &self.entries
    }

    /// Identifies the folder's content (for cache keys).
    pub fn fingerprint(&self) -> String {
        format!("{}:{}", self.dir.display(), self.index_hash)
    }

    /// Entries ranked by how well they fit `text` (and `category`, and `size`), best first;
    /// entries sharing nothing with the query are left out.
    pub fn search(
        &self,
        text: &str,
        category: Option<&str>,
        size: Option<[f64; 3]>,
    ) -> Vec<(f64, &MeshEntry)> {
        let q = search_words(text);
        let mut out: Vec<(f64, &MeshEntry)> = self
            .entries
            .iter()
            .map(|e| {
                let cat_hit = category.is_some_and(|c| {
                    let c = crate::scene::sanitize_name(c);
                    !e.category.is_empty() && crate::scene::sanitize_name(&e.category) == c
                });
                let sizes = size.zip(e.dimensions_m);
                (match_score(&q, &e.words(), cat_hit, sizes), e)
            })
            .filter(|(s, _)| *s > 0.0)
            .collect();
        out.sort_by(|a, b| b.0.total_cmp(&a.0).then_with(|| a.1.file.cmp(&b.1.file)));
        out
    }

    /// The best entry for a request when it shares the noun (score of at least one half).
    pub fn best_match(&self, text: &str, noun: &str, size: Option<[f64; 3]>) -> Option<&MeshEntry> {
        let query = if text.trim().is_empty() { noun } else { text };
        self.search(query, Some(noun), size)
            .into_iter()
            .find(|(s, _)| *s >= 0.5)
            .map(|(_, e)| e)
    }

    fn options(
        &self,
        entry: &MeshEntry,
        support: SupportClass,
        size: Option<[f64; 3]>,
        gltf: bool,
        hash: String,
    ) -> ImportOptions {
        let up = entry.up.unwrap_or(Axis::PosY);
        let front = entry.front.unwrap_or(Axis::PosZ);
        let (up, front) = if gltf {
            (up.after_gltf_load(), front.after_gltf_load())
        } else {
            (up, front)
        };
        let unit_scale = match entry.units.as_deref() {
            Some("cm") => 0.01,
            Some("mm") => 0.001,
            _ => 1.0,
        };
        ImportOptions {
            up,
            front,
            unit_scale,
            support: entry.support.unwrap_or(support),
            size: size.or(entry.dimensions_m),
            material: entry
                .material
                .clone()
                .filter(|m| crate::assets::material::material(m).is_some())
                .unwrap_or_else(|| "plastic".into()),
            hollow: entry.hollow,
            category: if entry.category.is_empty() {
                entry.name.clone()
            } else {
                entry.category.clone()
            },
            source: serde_json::json!({
                "kind": "mesh_folder",
                "file": entry.file,
                "name": entry.name,
                "description": entry.description,
                "license": entry.license,
            }),
            source_hash: hash,
        }
    }

    /// A content id for importing `entry` at `support` and `size` (without reading the file).
    pub fn asset_id(
        &self,
        entry: &MeshEntry,
        support: SupportClass,
        size: Option<[f64; 3]>,
    ) -> String {
        let key = serde_json::json!({"folder": self.index_hash, "file": entry.file, "support": support.as_str(), "size": size});
        crate::assets::content_id(
            if entry.category.is_empty() {
                &entry.name
            } else {
                &entry.category
            },
            &key,
        )
    }

    /// Imports `entry` as an asset of `support`, scaled to `size` (or the entry's own size).
    pub fn import(
        &self,
        entry: &MeshEntry,
        support: SupportClass,
        size: Option<[f64; 3]>,
    ) -> Result<Asset, ExternalError> {
        let path = inside(&self.dir, &entry.file)?;
        let bytes = std::fs::read(&path).map_err(|e| ExternalError::Io {
            path: path.clone(),
            message: e.to_string(),
        })?;
        let (parts, gltf) = read_mesh_file(&path)?;
        let hash = blake3::hash(&bytes).to_hex()[..16].to_string();
        let opts = self.options(entry, support, size, gltf, hash);
        let (mut asset, notes) = import_parts(parts, &opts)?;
        // The router looks assets up by this id; keep the import's own id in provenance.
        asset.provenance["content_id"] = serde_json::json!(asset.id);
        asset.id = self.asset_id(entry, support, size);
        if !notes.is_empty() {
            asset.provenance["notes"] = serde_json::json!(notes);
        }
        asset.provenance["source"]["path"] = serde_json::json!(path.display().to_string());
        Ok(asset)
    }
}
