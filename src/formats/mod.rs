//! Writers for every file format the project produces, each from the one scene model, the
//! scene directory that holds them and the directory of one asset (`asset_dir`).

pub mod asset_dir;
pub mod directives;
pub mod gltf;
pub mod scene_dir;
pub mod sdf;
pub mod sdf_read;

/// What can go wrong writing or reading scene files.
#[derive(Debug, thiserror::Error)]
pub enum FormatError {
    /// File-system error.
    #[error(transparent)]
    Fs(#[from] crate::util::fsx::FsError),
    /// YAML serialisation failed.
    #[error("could not write YAML: {0}")]
    Yaml(String),
    /// An asset folder of a scene could not be read back.
    #[error("could not read asset {asset} from {dir}: {reason}")]
    AssetRead {
        /// Asset id.
        asset: String,
        /// Its folder.
        dir: std::path::PathBuf,
        /// What is wrong.
        reason: String,
    },
    /// `scene.json` could not be read.
    #[error("could not read {path}: {reason}")]
    SceneJson {
        /// The file.
        path: std::path::PathBuf,
        /// Parse or validation problem.
        reason: String,
    },
}
