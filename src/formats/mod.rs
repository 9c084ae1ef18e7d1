//! Writers for every file format the project produces, each from the one scene model, and
//! the scene directory that holds them.

pub mod directives;
pub mod gltf;
pub mod obj;
pub mod scene_dir;
pub mod sdf;
pub mod xml;

/// What can go wrong writing or reading scene files.
#[derive(Debug, thiserror::Error)]
pub enum FormatError {
    /// File-system error.
    #[error(transparent)]
    Fs(#[from] crate::util::fsx::FsError),
    /// YAML serialisation failed.
    #[error("could not write YAML: {0}")]
    Yaml(String),
    /// `scene.json` could not be read.
    #[error("could not read {path}: {reason}")]
    SceneJson {
        /// The file.
        path: std::path::PathBuf,
        /// Parse or validation problem.
        reason: String,
    },
}
