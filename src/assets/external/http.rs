//! Client of an HTTP text-to-3D backend.
//!
//! Protocol (version 1), one request per asset:
//!
//! ```text
//! POST <url>            Content-Type: application/json
//! {"protocol": 1, "description": "a steampunk desk lamp with copper pipes",
//!  "dimensions_m": [0.2, 0.35, 0.45] | null, "support": "surface", "seed": 7, "format": "glb"}
//!
//! 200 OK                Content-Type: model/gltf-binary        body: the GLB file
//! 4xx/5xx               Content-Type: application/json         {"error": "what went wrong"}
//! ```
//!
//! The model is read as glTF (+Y up, +Z front, metres); the importer canonicalises it (Z up,
//! +Y front), scales it to `dimensions_m`, decomposes it and weighs it. Anything that is not
//! a GLB file is rejected with its first bytes in the message; a backend that does not answer
//! within the timeout is abandoned. Backends should be deterministic in `seed`.

use std::time::Duration;

use super::ExternalError;
use super::import::{Axis, ImportOptions, import_parts};
use crate::assets::Asset;
use crate::assets::procedural::SupportClass;
use crate::util::http_body::read_limited;

/// Protocol version sent with every request.
pub const PROTOCOL: u32 = 1;

/// Largest model accepted from a backend by default, bytes (a detailed GLB with textures is
/// a few tens of MB).
pub const MAX_MODEL_BYTES: usize = 256 << 20;

/// A text-to-3D backend endpoint.
#[derive(Debug, Clone)]
pub struct HttpBackend {
    url: String,
    timeout: Duration,
    max_bytes: usize,
}

impl HttpBackend {
    /// A backend at `url` (the full endpoint, e.g. `http://127.0.0.1:8000/generate`).
    pub fn new(url: &str, timeout: Duration) -> HttpBackend {
        HttpBackend {
            url: url.to_string(),
            timeout,
            max_bytes: MAX_MODEL_BYTES,
        }
    }

    /// The same backend with another limit on the size of a model, bytes.
    pub fn with_max_bytes(mut self, max_bytes: usize) -> HttpBackend {
        self.max_bytes = max_bytes;
        self
    }

    /// The endpoint.
    pub fn url(&self) -> &str {
        &self.url
    }

    /// Asks the backend for a model; returns the GLB bytes.
    pub fn generate(
        &self,
        description: &str,
        support: SupportClass,
        size: Option<[f64; 3]>,
        seed: u64,
    ) -> Result<Vec<u8>, ExternalError> {
        let body = serde_json::json!({
            "protocol": PROTOCOL,
            "description": description,
            "dimensions_m": size,
            "support": support.as_str(),
            "seed": seed,
            "format": "glb",
        });
        let url = self.url.clone();
        let timeout = self.timeout;
        let max_bytes = self.max_bytes;
        // A private single-threaded runtime on its own thread: callable from sync code and
        // from inside another runtime alike.
        let worker =
            std::thread::spawn(move || -> Result<(u16, String, Vec<u8>), ExternalError> {
                let rt = tokio::runtime::Builder::new_current_thread()
                    .enable_all()
                    .build()
                    .map_err(|e| ExternalError::Backend {
                        url: url.clone(),
                        message: format!("no async runtime: {e}"),
                    })?;
                rt.block_on(async {
                    let _ = rustls::crypto::ring::default_provider().install_default();
                    let client = reqwest::Client::builder()
                        .timeout(timeout)
                        .build()
                        .map_err(|e| ExternalError::Backend {
                            url: url.clone(),
                            message: e.to_string(),
                        })?;
                    let timed_out = |e: &reqwest::Error| e.is_timeout();
                    let resp = client.post(&url).json(&body).send().await.map_err(|e| {
                        if timed_out(&e) {
                            ExternalError::Timeout {
                                url: url.clone(),
                                seconds: timeout.as_secs_f64(),
                            }
                        } else {
                            ExternalError::Backend {
                                url: url.clone(),
                                message: e.to_string(),
                            }
                        }
                    })?;
                    let status = resp.status().as_u16();
                    let ctype = resp
                        .headers()
                        .get(reqwest::header::CONTENT_TYPE)
                        .and_then(|v| v.to_str().ok())
                        .unwrap_or("")
                        .to_string();
                    let bytes = read_limited(resp, max_bytes).await.map_err(|e| {
                        if e.is_timeout() {
                            ExternalError::Timeout {
                                url: url.clone(),
                                seconds: timeout.as_secs_f64(),
                            }
                        } else {
                            ExternalError::Backend {
                                url: url.clone(),
                                message: e.to_string(),
                            }
                        }
                    })?;
                    Ok((status, ctype, bytes))
                })
            });
        let (status, ctype, bytes) = worker.join().map_err(|_| ExternalError::Backend {
            url: self.url.clone(),
            message: "the request thread panicked".into(),
        })??;
        if !(200..300).contains(&status) {
            let message = serde_json::from_slice::<serde_json::Value>(&bytes)
                .ok()
                .and_then(|v| v.get("error").and_then(|e| e.as_str()).map(str::to_string))
                .unwrap_or_else(|| {
                    String::from_utf8_lossy(&bytes[..bytes.len().min(200)]).into_owned()
                });
            return Err(ExternalError::Backend {
                url: self.url.clone(),
                message: format!("HTTP {status}: {message}"),
            });
        }
        if !bytes.starts_with(b"glTF") {
            let head = String::from_utf8_lossy(&bytes[..bytes.len().min(40)]).into_owned();
            return Err(ExternalError::Garbage {
                url: self.url.clone(),
                message: format!("{} bytes of {ctype:?} starting {head:?}", bytes.len()),
            });
        }
        Ok(bytes)
    }

    /// The content id of what [`Self::generate_asset`] would return.
    pub fn asset_id(
        &self,
        description: &str,
        support: SupportClass,
        size: Option<[f64; 3]>,
        seed: u64,
    ) -> String {
        let key = serde_json::json!({"url": self.url, "description": description, "support": support.as_str(), "size": size, "seed": seed, "protocol": PROTOCOL});
        crate::assets::content_id(
            description.split_whitespace().last().unwrap_or("external"),
            &key,
        )
    }

    /// Generates and imports a model: canonical frame, scaled to `size`, decomposed, weighed.
    pub fn generate_asset(
        &self,
        description: &str,
        noun: &str,
        support: SupportClass,
        size: Option<[f64; 3]>,
        seed: u64,
    ) -> Result<Asset, ExternalError> {
        let glb = self.generate(description, support, size, seed)?;
        let parts =
            crate::assets::gltf_read::parse(&glb, None).map_err(|e| ExternalError::Garbage {
                url: self.url.clone(),
                message: e,
            })?;
        let opts = ImportOptions {
            up: Axis::PosY.after_gltf_load(),
            front: Axis::PosZ.after_gltf_load(),
            unit_scale: 1.0,
            support,
            size,
            material: "plastic".into(),
            hollow: None,
            category: noun.to_string(),
            source: serde_json::json!({"kind": "text_to_3d", "url": self.url, "description": description, "seed": seed}),
            source_hash: blake3::hash(&glb).to_hex()[..16].to_string(),
        };
        let (mut asset, notes) = import_parts(parts, &opts)?;
        asset.provenance["content_id"] = serde_json::json!(asset.id);
        asset.id = self.asset_id(description, support, size, seed);
        if !notes.is_empty() {
            asset.provenance["notes"] = serde_json::json!(notes);
        }
        Ok(asset)
    }
}
