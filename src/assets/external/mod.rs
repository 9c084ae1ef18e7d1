//! External asset sources: an HTTP text-to-3D backend ([`http`]) and a local folder of meshes
//! with a JSON index ([`folder`]). Both deliver foreign meshes that [`import`] brings into the
//! canonical frame, scales, decomposes ([`vhacd`]) and weighs.
//!
//! Nothing here is used unless the router's context configures it (see
//! [`crate::assets::router::RouterContext::from_env`]).

pub mod folder;
pub mod http;
pub mod import;
pub mod vhacd;

pub use folder::MeshFolder;
pub use http::HttpBackend;

/// What can go wrong with an external source.
#[derive(Debug, thiserror::Error)]
pub enum ExternalError {
    /// A file could not be read.
    #[error("{path}: {message}")]
    Io {
        /// The file.
        path: std::path::PathBuf,
        /// The OS error.
        message: String,
    },
    /// The folder's index is malformed.
    #[error("index {path}: {message}")]
    Index {
        /// The index file.
        path: std::path::PathBuf,
        /// What is wrong.
        message: String,
    },
    /// The backend did not answer in time.
    #[error("the text-to-3D backend at {url} did not answer within {seconds:.0} s")]
    Timeout {
        /// Endpoint.
        url: String,
        /// Timeout used.
        seconds: f64,
    },
    /// The backend could not be reached or answered with an error status.
    #[error("the text-to-3D backend at {url} failed: {message}")]
    Backend {
        /// Endpoint.
        url: String,
        /// Status and message.
        message: String,
    },
    /// The backend answered with something that is not a GLB model.
    #[error(
        "the text-to-3D backend at {url} returned something that is not a GLB model: {message}"
    )]
    Garbage {
        /// Endpoint.
        url: String,
        /// What arrived.
        message: String,
    },
    /// The mesh cannot be used.
    #[error("unusable mesh: {0}")]
    Mesh(String),
    /// The imported asset failed its checks.
    #[error(transparent)]
    Asset(#[from] crate::assets::AssetError),
}

/// Words of a text, lower case, singular, without stop words: what index search compares.
pub fn search_words(text: &str) -> Vec<String> {
    const STOP: [&str; 14] = [
        "a", "an", "the", "of", "with", "and", "for", "in", "on", "to", "some", "style", "at",
        "least",
    ];
    crate::assets::attributes::normalize(text)
        .split_whitespace()
        .filter(|w| !STOP.contains(w))
        .map(crate::prompt::singular)
        .collect()
}

/// How well an index entry's words and size fit a query: shared words (category matches count
/// double), minus a penalty for size mismatch. 0 means nothing in common.
pub fn match_score(
    query: &[String],
    entry_words: &[String],
    category_hit: bool,
    sizes: Option<([f64; 3], [f64; 3])>,
) -> f64 {
    if query.is_empty() {
        return 0.0;
    }
    let shared = query.iter().filter(|w| entry_words.contains(w)).count() as f64;
    let mut score = shared / query.len() as f64 + if category_hit { 1.0 } else { 0.0 };
    if score <= 0.0 {
        return 0.0;
    }
    if let Some((want, have)) = sizes {
        let misfit: f64 = (0..3)
            .map(|i| (want[i].max(1e-6) / have[i].max(1e-6)).ln().abs())
            .sum::<f64>()
            / 3.0;
        score -= 0.5 * misfit;
    }
    score.max(0.0)
}
