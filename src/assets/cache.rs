//! The content-addressed asset cache: built assets by content id (their id already hashes the
//! generator, its version, the parameters and the seed), and routing results by a hash of the
//! request, so the same asset is never built twice, in one run (memory) or across runs
//! (a directory on disk, `SCENESMITH_ASSET_CACHE` or `~/.cache/scenesmith/assets`).
//!
//! Disk layout: `<dir>/v<version>/assets/<asset id>.json` (the whole asset: links, meshes,
//! convex pieces, mass properties, joints, surfaces, provenance; textures as embedded PNG) and
//! `<dir>/v<version>/routes/<key>.json` (what a request routed to). Files are written
//! atomically; an unreadable or stale file is ignored and rebuilt, never trusted.

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Arc, Mutex};

use serde::{Deserialize, Serialize};

use super::{Asset, Contact, Joint, JointKind, Link, Texture, VisualPart};
use crate::geometry::{ConvexPiece, MassProps, TriMesh};
use crate::scene::{Pose, SurfaceRecord};

/// Version of the on-disk format (bump with the generator version or this file's DTOs).
pub const CACHE_FORMAT: u32 = 1;

/// Hit and miss counters.
#[derive(Debug, Default)]
pub struct CacheStats {
    /// Assets served from memory.
    pub memory_hits: AtomicU64,
    /// Assets served from disk.
    pub disk_hits: AtomicU64,
    /// Assets built.
    pub misses: AtomicU64,
}

/// Built assets and routing results, in memory and optionally on disk.
#[derive(Debug, Default)]
pub struct AssetCache {
    dir: Option<PathBuf>,
    assets: Mutex<HashMap<String, Arc<Asset>>>,
    routes: Mutex<HashMap<String, serde_json::Value>>,
    /// Counters.
    pub stats: CacheStats,
}

impl AssetCache {
    /// A memory-only cache.
    pub fn in_memory() -> AssetCache {
        AssetCache::default()
    }

    /// A cache that also persists to `dir`.
    pub fn on_disk(dir: &Path) -> AssetCache {
        AssetCache {
            dir: Some(dir.join(format!(
                "v{CACHE_FORMAT}_{}_{}",
                super::procedural::GENERATOR_VERSION,
                super::procedural::generator_fingerprint()
            ))),
            ..AssetCache::default()
        }
    }

    /// The default cache directory: `SCENESMITH_ASSET_CACHE`, else `$XDG_CACHE_HOME` or
    /// `~/.cache`, then `scenesmith/assets`.
    pub fn default_dir() -> Option<PathBuf> {
        if let Some(d) = std::env::var_os("SCENESMITH_ASSET_CACHE") {
            return Some(PathBuf::from(d));
        }
        let base = std::env::var_os("XDG_CACHE_HOME")
            .map(PathBuf::from)
            .or_else(|| std::env::var_os("HOME").map(|h| PathBuf::from(h).join(".cache")))?;
        Some(base.join("scenesmith").join("assets"))
    }

    /// The directory assets persist to, if any.
    pub fn dir(&self) -> Option<&Path> {
        self.dir.as_deref()
    }

    fn asset_path(&self, id: &str) -> Option<PathBuf> {
        let safe = crate::scene::sanitize_name(id);
        self.dir
            .as_ref()
            .map(|d| d.join("assets").join(format!("{safe}.json")))
    }

    fn route_path(&self, key: &str) -> Option<PathBuf> {
        let safe = crate::scene::sanitize_name(key);
        self.dir
            .as_ref()
            .map(|d| d.join("routes").join(format!("{safe}.json")))
    }

    /// The cached asset with this content id, from memory or disk.
    pub fn get(&self, id: &str) -> Option<Arc<Asset>> {
        if let Some(a) = self.lock_assets().get(id).cloned() {
            self.stats.memory_hits.fetch_add(1, Ordering::Relaxed);
            return Some(a);
        }
        let path = self.asset_path(id)?;
        let text = std::fs::read(&path).ok()?;
        let dto: AssetDto = serde_json::from_slice(&text).ok()?;
        let asset = Arc::new(dto.into_asset().ok()?);
        if asset.id != id || asset.validate().is_err() {
            return None;
        }
        self.stats.disk_hits.fetch_add(1, Ordering::Relaxed);
        self.lock_assets().insert(id.to_string(), asset.clone());
        Some(asset)
    }

    /// Stores an asset (memory, and disk when configured; a disk failure only loses the
    /// persistence, never the asset).
    pub fn put(&self, asset: Arc<Asset>) {
        if let Some(path) = self.asset_path(&asset.id)
            && !path.exists()
            && let Ok(bytes) = serde_json::to_vec(&AssetDto::from_asset(&asset))
            && let Err(e) = crate::util::fsx::write_atomic(&path, &bytes)
        {
            tracing::warn!("asset cache: could not write {}: {e}", path.display());
        }
        self.lock_assets().insert(asset.id.clone(), asset);
    }

    /// Builds through the cache: returns the cached asset for `id`, or builds it with `make`,
    /// stores and returns it. `make` runs only on a miss.
    pub fn get_or_build<E>(
        &self,
        id: &str,
        make: impl FnOnce() -> Result<Asset, E>,
    ) -> Result<(Arc<Asset>, bool), E> {
        if let Some(a) = self.get(id) {
            return Ok((a, true));
        }
        self.stats.misses.fetch_add(1, Ordering::Relaxed);
        let asset = Arc::new(make()?);
        self.put(asset.clone());
        Ok((asset, false))
    }

    /// A stored routing result (as JSON, the router's own format).
    pub fn get_route(&self, key: &str) -> Option<serde_json::Value> {
        if let Some(v) = self.lock_routes().get(key).cloned() {
            return Some(v);
        }
        let path = self.route_path(key)?;
        let v: serde_json::Value = serde_json::from_slice(&std::fs::read(path).ok()?).ok()?;
        self.lock_routes().insert(key.to_string(), v.clone());
        Some(v)
    }

    /// Stores a routing result.
    pub fn put_route(&self, key: &str, value: serde_json::Value) {
        if let Some(path) = self.route_path(key)
            && let Ok(bytes) = serde_json::to_vec(&value)
            && let Err(e) = crate::util::fsx::write_atomic(&path, &bytes)
        {
            tracing::warn!("asset cache: could not write {}: {e}", path.display());
        }
        self.lock_routes().insert(key.to_string(), value);
    }

    /// Number of assets held in memory.
    pub fn len(&self) -> usize {
        self.lock_assets().len()
    }

    /// True when nothing is held in memory.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    fn lock_assets(&self) -> std::sync::MutexGuard<'_, HashMap<String, Arc<Asset>>> {
        // A panic while holding the lock cannot leave the map inconsistent (single inserts).
        self.assets.lock().unwrap_or_else(|p| p.into_inner())
    }

    fn lock_routes(&self) -> std::sync::MutexGuard<'_, HashMap<String, serde_json::Value>> {
        self.routes.lock().unwrap_or_else(|p| p.into_inner())
    }
}

/// Standard base64 with padding.
pub fn base64_encode(bytes: &[u8]) -> String {
    const T: &[u8; 64] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    let mut out = String::with_capacity(bytes.len().div_ceil(3) * 4);
    for chunk in bytes.chunks(3) {
        let b = [
            chunk[0],
            *chunk.get(1).unwrap_or(&0),
            *chunk.get(2).unwrap_or(&0),
        ];
        let n = (u32::from(b[0]) << 16) | (u32::from(b[1]) << 8) | u32::from(b[2]);
        for k in 0..4 {
            if k <= chunk.len() {
                out.push(T[((n >> (18 - 6 * k)) & 63) as usize] as char);
            } else {
                out.push('=');
            }
        }
    }
    out
}

#[derive(Serialize, Deserialize)]
struct MeshDto {
    p: Vec<[f64; 3]>,
    n: Vec<[f64; 3]>,
    t: Vec<[u32; 3]>,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    uv: Vec<[f64; 2]>,
}

#[derive(Serialize, Deserialize)]
struct TextureDto {
    name: String,
    png_base64: String,
}

#[derive(Serialize, Deserialize)]
struct VisualDto {
    name: String,
    mesh: MeshDto,
    color: [f64; 4],
    #[serde(default, skip_serializing_if = "Option::is_none")]
    texture: Option<TextureDto>,
}

#[derive(Serialize, Deserialize)]
struct PieceDto {
    v: Vec<[f64; 3]>,
    t: Vec<[u32; 3]>,
}

#[derive(Serialize, Deserialize)]
struct LinkDto {
    name: String,
    model_from_link: Pose,
    visuals: Vec<VisualDto>,
    collisions: Vec<PieceDto>,
    mass: MassProps,
    contact: Contact,
}

#[derive(Serialize, Deserialize)]
struct JointDto {
    name: String,
    kind: JointKind,
    parent: String,
    child: String,
    axis: [f64; 3],
    lower: f64,
    upper: f64,
    damping: f64,
    effort: f64,
}

#[derive(Serialize, Deserialize)]
struct AssetDto {
    id: String,
    category: String,
    material: String,
    links: Vec<LinkDto>,
    joints: Vec<JointDto>,
    surfaces: Vec<SurfaceRecord>,
    is_static: bool,
    provenance: serde_json::Value,
}

impl AssetDto {
    fn from_asset(a: &Asset) -> AssetDto {
        let mesh = |m: &TriMesh| MeshDto {
            p: m.positions.clone(),
            n: m.normals.clone(),
            t: m.triangles.clone(),
            uv: m.uvs.clone(),
        };
        AssetDto {
            id: a.id.clone(),
            category: a.category.clone(),
            material: a.material.clone(),
            links: a
                .links
                .iter()
                .map(|l| LinkDto {
                    name: l.name.clone(),
                    model_from_link: l.model_from_link,
                    visuals: l
                        .visuals
                        .iter()
                        .map(|v| VisualDto {
                            name: v.name.clone(),
                            mesh: mesh(&v.mesh),
                            color: v.color,
                            texture: v.texture.as_ref().and_then(|t| {
                                crate::util::png::encode_rgba(t.width, t.height, &t.rgba)
                                    .ok()
                                    .map(|png| TextureDto {
                                        name: t.name.clone(),
                                        png_base64: base64_encode(&png),
                                    })
                            }),
                        })
                        .collect(),
                    collisions: l
                        .collisions
                        .iter()
                        .map(|c| PieceDto {
                            v: c.vertices.clone(),
                            t: c.triangles.clone(),
                        })
                        .collect(),
                    mass: l.mass,
                    contact: l.contact,
                })
                .collect(),
            joints: a
                .joints
                .iter()
                .map(|j| JointDto {
                    name: j.name.clone(),
                    kind: j.kind,
                    parent: j.parent.clone(),
                    child: j.child.clone(),
                    axis: j.axis,
                    lower: j.lower,
                    upper: j.upper,
                    damping: j.damping,
                    effort: j.effort,
                })
                .collect(),
            surfaces: a.surfaces.clone(),
            is_static: a.is_static,
            provenance: a.provenance.clone(),
        }
    }

    fn into_asset(self) -> Result<Asset, String> {
        let mesh = |m: MeshDto| -> Result<TriMesh, String> {
            let n = m.p.len() as u32;
            if m.n.len() != m.p.len() || m.t.iter().flatten().any(|&i| i >= n) {
                return Err("inconsistent mesh".into());
            }
            Ok(TriMesh {
                positions: m.p,
                normals: m.n,
                triangles: m.t,
                uvs: m.uv,
            })
        };
        let mut links = Vec::new();
        for l in self.links {
            let mut visuals = Vec::new();
            for v in l.visuals {
                let texture = match v.texture {
                    Some(t) => {
                        let png = crate::util::base64::decode(&t.png_base64)?;
                        let (width, height, rgba) = crate::util::png::decode_rgba(&png)?;
                        Some(Texture {
                            name: t.name,
                            width,
                            height,
                            rgba: Arc::new(rgba),
                        })
                    }
                    None => None,
                };
                visuals.push(VisualPart {
                    name: v.name,
                    mesh: mesh(v.mesh)?,
                    color: v.color,
                    texture,
                });
            }
            let collisions = l
                .collisions
                .into_iter()
                .map(|c| {
                    let n = c.v.len() as u32;
                    if c.t.iter().flatten().any(|&i| i >= n) {
                        return Err("inconsistent convex piece".to_string());
                    }
                    Ok(ConvexPiece {
                        vertices: c.v,
                        triangles: c.t,
                    })
                })
                .collect::<Result<Vec<_>, _>>()?;
            links.push(Link {
                name: l.name,
                model_from_link: l.model_from_link,
                visuals,
                collisions,
                mass: l.mass,
                contact: l.contact,
            });
        }
        Ok(Asset {
            id: self.id,
            category: self.category,
            material: self.material,
            links,
            joints: self
                .joints
                .into_iter()
                .map(|j| Joint {
                    name: j.name,
                    kind: j.kind,
                    parent: j.parent,
                    child: j.child,
                    axis: j.axis,
                    lower: j.lower,
                    upper: j.upper,
                    damping: j.damping,
                    effort: j.effort,
                })
                .collect(),
            surfaces: self.surfaces,
            is_static: self.is_static,
            provenance: self.provenance,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::assets::procedural::{AssetRequest, build};

    #[test]
    fn assets_round_trip_through_disk_exactly() {
        let dir = tempfile::tempdir().unwrap();
        let cache = AssetCache::on_disk(dir.path());
        for cat in ["dresser", "rug", "painting", "mug"] {
            let a = Arc::new(build(&AssetRequest::new(cat, 7)).unwrap());
            cache.put(a.clone());
            let fresh = AssetCache::on_disk(dir.path());
            let b = fresh.get(&a.id).expect("read back from disk");
            assert_eq!(*a, *b, "{cat}");
            assert_eq!(fresh.stats.disk_hits.load(Ordering::Relaxed), 1);
        }
    }

    #[test]
    fn builds_once_and_ignores_corrupt_files() {
        let dir = tempfile::tempdir().unwrap();
        let cache = AssetCache::on_disk(dir.path());
        let mut builds = 0;
        let r = AssetRequest::new("chair", 3);
        let id = build(&r).unwrap().id;
        for _ in 0..3 {
            let (_, hit) = cache
                .get_or_build(&id, || {
                    builds += 1;
                    build(&r)
                })
                .unwrap();
            let _ = hit;
        }
        assert_eq!(builds, 1);
        // A truncated file on disk is not trusted: a fresh cache rebuilds.
        let path = cache.asset_path(&id).unwrap();
        std::fs::write(&path, b"{\"id\": ").unwrap();
        let fresh = AssetCache::on_disk(dir.path());
        assert!(fresh.get(&id).is_none());
    }

    #[test]
    fn base64_matches_the_reference_vectors() {
        assert_eq!(base64_encode(b""), "");
        assert_eq!(base64_encode(b"f"), "Zg==");
        assert_eq!(base64_encode(b"fo"), "Zm8=");
        assert_eq!(base64_encode(b"foobar"), "Zm9vYmFy");
        let bytes: Vec<u8> = (0..=255).collect();
        assert_eq!(
            crate::util::base64::decode(&base64_encode(&bytes)).unwrap(),
            bytes
        );
    }
}
