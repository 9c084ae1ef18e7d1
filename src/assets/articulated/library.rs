//! A user folder of articulated models (SDFormat or URDF) described by `index.json`,
//! searchable by text and size, loaded into assets.
//!
//! ```json
//! {"models": [
//!   {"file": "kitchen/cabinet_2door.urdf", "name": "two-door kitchen cabinet",
//!    "description": "white base cabinet with two hinged doors", "category": "cabinet",
//!    "tags": ["kitchen"], "dimensions_m": [0.8, 0.6, 0.9], "up": "+z", "front": "+y",
//!    "license": "CC-BY-4.0"}
//! ]}
//! ```
//!
//! What is read is described in [`super::reader`]. Models are rotated so `up` is +Z and `front` +Y (defaults: already so), put
//! on the floor (bottom at z = 0, centred) and scaled uniformly to the requested size.
//! Nested models, `relative_to` other than the model, and ball/planar joints are refused with
//! a message naming the file.

use std::path::{Path, PathBuf};

use nalgebra::{Matrix3, Rotation3, Vector3};
use serde::Deserialize;

use super::reader::{merge_fixed, read_sdf, read_urdf};
use crate::assets::external::import::Axis;
use crate::assets::external::{match_score, search_words};
use crate::assets::{Asset, AssetError, JointKind, content_id, physical};
use crate::geometry::MassProps;
use crate::scene::{Pose, SurfaceRecord};
use crate::util::xml;

/// What can go wrong with the library.
#[derive(Debug, thiserror::Error)]
pub enum LibraryError {
    /// The index or a model file could not be read.
    #[error("{path}: {message}")]
    Io {
        /// The file.
        path: PathBuf,
        /// The problem.
        message: String,
    },
    /// A model uses something this reader does not support or is malformed.
    #[error("{file}: {message}")]
    Model {
        /// The model file.
        file: String,
        /// The problem.
        message: String,
    },
    /// The loaded asset failed its checks.
    #[error(transparent)]
    Asset(#[from] AssetError),
}

/// One model of the library.
#[derive(Debug, Clone, Deserialize)]
pub struct LibraryEntry {
    /// Path of the `.sdf` or `.urdf` file relative to the library folder.
    pub file: String,
    /// Short name.
    #[serde(default)]
    pub name: String,
    /// Free text.
    #[serde(default)]
    pub description: String,
    /// Category noun (a procedural category name lets the router use it for that category).
    #[serde(default)]
    pub category: String,
    /// Extra search words.
    #[serde(default)]
    pub tags: Vec<String>,
    /// Size (x, y, z) in metres, canonical frame.
    #[serde(default)]
    pub dimensions_m: Option<[f64; 3]>,
    /// Up axis of the model.
    #[serde(default)]
    pub up: Option<Axis>,
    /// Front axis of the model.
    #[serde(default)]
    pub front: Option<Axis>,
    /// Licence.
    #[serde(default)]
    pub license: Option<String>,
}

#[derive(Deserialize)]
#[serde(untagged)]
enum IndexFile {
    Wrapped { models: Vec<LibraryEntry> },
    Bare(Vec<LibraryEntry>),
}

/// An opened library folder.
#[derive(Debug, Clone)]
pub struct ArticulatedLibrary {
    dir: PathBuf,
    entries: Vec<LibraryEntry>,
    index_hash: String,
}

impl ArticulatedLibrary {
    /// Opens `dir/index.json`.
    pub fn open(dir: &Path) -> Result<ArticulatedLibrary, LibraryError> {
        let path = dir.join("index.json");
        let text = std::fs::read_to_string(&path).map_err(|e| LibraryError::Io {
            path: path.clone(),
            message: e.to_string(),
        })?;
        let index: IndexFile = serde_json::from_str(&text).map_err(|e| LibraryError::Io {
            path: path.clone(),
            message: e.to_string(),
        })?;
        let entries = match index {
            IndexFile::Wrapped { models } => models,
            IndexFile::Bare(m) => m,
        };
        for e in &entries {
            crate::assets::external::folder::inside(dir, &e.file).map_err(|err| {
                LibraryError::Io {
                    path: path.clone(),
                    message: err.to_string(),
                }
            })?;
        }
        Ok(ArticulatedLibrary {
            dir: dir.to_path_buf(),
            entries,
            index_hash: blake3::hash(text.as_bytes()).to_hex()[..16].to_string(),
        })
    }

    /// The library's entries.
    pub fn entries(&self) -> &[LibraryEntry] {
        &self.entries
    }

    /// Identifies the library's content (for cache keys).
    pub fn fingerprint(&self) -> String {
        format!("{}:{}", self.dir.display(), self.index_hash)
    }

    /// Entries ranked by fit to `text`, `category` and `size`, best first.
    pub fn search(
        &self,
        text: &str,
        category: Option<&str>,
        size: Option<[f64; 3]>,
    ) -> Vec<(f64, &LibraryEntry)> {
        let q = search_words(text);
        let mut out: Vec<(f64, &LibraryEntry)> = self
            .entries
            .iter()
            .map(|e| {
                let words = search_words(&format!(
                    "{} {} {} {}",
                    e.name,
                    e.description,
                    e.category.replace('_', " "),
                    e.tags.join(" ")
                ));
                let cat_hit = category.is_some_and(|c| {
                    !e.category.is_empty()
                        && crate::scene::sanitize_name(&e.category)
                            == crate::scene::sanitize_name(c)
                });
                (
                    match_score(&q, &words, cat_hit, size.zip(e.dimensions_m)),
                    e,
                )
            })
            .filter(|(s, _)| *s > 0.0)
            .collect();
        out.sort_by(|a, b| b.0.total_cmp(&a.0).then_with(|| a.1.file.cmp(&b.1.file)));
        out
    }

    /// The best entry of `category` for a request, if one fits (same category, or shares
    /// the words with a score of at least one half).
    pub fn best_match(
        &self,
        text: &str,
        category: Option<&str>,
        size: Option<[f64; 3]>,
    ) -> Option<&LibraryEntry> {
        self.search(text, category, size)
            .into_iter()
            .find(|(s, _)| *s >= 0.5)
            .map(|(_, e)| e)
    }

    /// The content id of `entry` loaded at `size`.
    pub fn asset_id(&self, entry: &LibraryEntry, size: Option<[f64; 3]>, seed: u64) -> String {
        let key = serde_json::json!({"library": self.index_hash, "file": entry.file, "size": size, "seed": seed, "reader": 1});
        let cat = if entry.category.is_empty() {
            &entry.name
        } else {
            &entry.category
        };
        content_id(cat, &key)
    }

    /// Loads `entry`, canonicalised and scaled uniformly to fit `size` (or as it is).
    pub fn load(
        &self,
        entry: &LibraryEntry,
        size: Option<[f64; 3]>,
        seed: u64,
    ) -> Result<Asset, LibraryError> {
        let path =
            crate::assets::external::folder::inside(&self.dir, &entry.file).map_err(|e| {
                LibraryError::Model {
                    file: entry.file.clone(),
                    message: e.to_string(),
                }
            })?;
        let text = std::fs::read_to_string(&path).map_err(|e| LibraryError::Io {
            path: path.clone(),
            message: e.to_string(),
        })?;
        let model_dir = path.parent().unwrap_or(&self.dir).to_path_buf();
        let err = |message: String| LibraryError::Model {
            file: entry.file.clone(),
            message,
        };
        let root = xml::parse(&text).map_err(err)?;
        let mut model = match root.name() {
            "robot" => read_urdf(&root, &model_dir, &self.dir).map_err(err)?,
            "sdf" => read_sdf(&root, &model_dir, &self.dir).map_err(err)?,
            other => {
                return Err(err(format!(
                    "root element <{other}> is neither <robot> (URDF) nor <sdf>"
                )));
            }
        };
        merge_fixed(&mut model).map_err(err)?;
        let up = entry.up.unwrap_or(Axis::PosZ);
        let front = entry.front.unwrap_or(Axis::PosY);
        let rot = crate::assets::external::import::canonical_rotation(up, front)
            .map_err(|e| err(e.to_string()))?;
        let category = if entry.category.is_empty() {
            entry.name.clone()
        } else {
            entry.category.clone()
        };
        let mut asset = model
            .into_asset(self.asset_id(entry, size, seed), &category)
            .map_err(err)?;
        canonicalise(&mut asset, rot, size);
        let [lo, hi] = asset.bounds();
        asset.surfaces.push(SurfaceRecord {
            id: "top".into(),
            link: asset.links[0].name.clone(),
            center: [(lo[0] + hi[0]) / 2.0, (lo[1] + hi[1]) / 2.0, hi[2]],
            size: [(hi[0] - lo[0]) * 0.8, (hi[1] - lo[1]) * 0.8],
            clearance: 0.5,
        });
        asset.provenance = serde_json::json!({
            "strategy": "articulated",
            "source": {"kind": "articulated_library", "file": entry.file, "name": entry.name, "license": entry.license},
            "seed": seed,
        });
        physical::check(&asset, crate::assets::procedural::SupportClass::Floor)?;
        asset.provenance["physics"] = serde_json::to_value(physical::summarize(
            &asset,
            crate::assets::procedural::SupportClass::Floor,
        ))
        .unwrap_or_default();
        Ok(asset)
    }
}

/// Rotates the model frame by `rot`, scales uniformly to fit `size`, and puts the bottom at
/// z = 0 centred in x and y.
fn canonicalise(asset: &mut Asset, rot: Matrix3<f64>, size: Option<[f64; 3]>) {
    let q = nalgebra::UnitQuaternion::from_rotation_matrix(&Rotation3::from_matrix_unchecked(rot));
    let turn = Pose(nalgebra::Isometry3::from_parts(
        nalgebra::Translation3::identity(),
        q,
    ));
    for l in asset.links.iter_mut() {
        l.model_from_link = turn.compose(&l.model_from_link);
    }
    let [lo, hi] = asset.bounds();
    let ext = [0, 1, 2].map(|i| (hi[i] - lo[i]).max(1e-9));
    let s = size.map_or(1.0, |w| {
        ((w[0] / ext[0]) * (w[1] / ext[1]) * (w[2] / ext[2])).cbrt()
    });
    if (s - 1.0).abs() > 1e-12 {
        for l in asset.links.iter_mut() {
            let t = l.model_from_link.translation() * s;
            l.model_from_link = l.model_from_link.with_translation(t);
            for v in l.visuals.iter_mut() {
                v.mesh = v.mesh.scaled([s; 3]);
            }
            for p in l.collisions.iter_mut() {
                for v in p.vertices.iter_mut() {
                    *v = v.map(|c| c * s);
                }
            }
            l.mass = MassProps {
                mass: l.mass.mass * s.powi(3),
                com: l.mass.com.map(|c| c * s),
                inertia: l.mass.inertia.map(|r| r.map(|c| c * s.powi(5))),
            };
        }
        for j in asset.joints.iter_mut() {
            if j.kind == JointKind::Prismatic {
                j.lower *= s;
                j.upper *= s;
            }
        }
    }
    let [lo, hi] = asset.bounds();
    let shift = Vector3::new(-(lo[0] + hi[0]) / 2.0, -(lo[1] + hi[1]) / 2.0, -lo[2]);
    for l in asset.links.iter_mut() {
        let t = l.model_from_link.translation() + shift;
        l.model_from_link = l.model_from_link.with_translation(t);
    }
}
