//! Exports: the scene for other simulators and viewers, each format written by its own writer
//! from the one scene model ([`SceneState`]), never by rewriting another format's text.
//!
//! | file (inside the scene directory) | for | writer |
//! |---|---|---|
//! | `export/mujoco/scene.xml` + `meshes/`, `textures/` | MuJoCo (MJCF) | [`mjcf`] |
//! | `export/usd/scene.usda` + `assets/*.usda`, `assets/textures/` | Isaac Sim / any USD tool (UsdPhysics) | [`usd`] |
//! | `export/scene.glb` | Blender, web viewers | [`glb`] |
//!
//! [`conformance`] is the gate that loads what was written in MuJoCo, usd-core and Drake (through
//! the bridge) and compares it with the scene. This module does not simulate anything itself.
//!
//! Every path written is built from sanitised names and checked by [`safe_join`], so no name in a
//! prompt or an asset can place a file outside the export directory.

pub mod conformance;
pub mod glb;
pub mod mjcf;
pub mod usd;
mod usda;
pub mod view;

use std::path::{Component, Path, PathBuf};

use crate::stages::SceneState;
use crate::util::fsx::{FsError, io_err, write_atomic};

pub use view::SceneView;

/// Where each export lives, relative to the scene directory.
pub mod paths {
    /// Folder of all exports.
    pub const EXPORT_DIR: &str = "export";
    /// MuJoCo folder.
    pub const MJCF_DIR: &str = "export/mujoco";
    /// The MJCF file.
    pub const MJCF_FILE: &str = "export/mujoco/scene.xml";
    /// USD folder.
    pub const USD_DIR: &str = "export/usd";
    /// The USD stage.
    pub const USD_FILE: &str = "export/usd/scene.usda";
    /// The binary glTF of the whole scene.
    pub const GLB_FILE: &str = "export/scene.glb";
}

/// What can go wrong exporting.
#[derive(Debug, thiserror::Error)]
pub enum ExportError {
    /// File-system error.
    #[error(transparent)]
    Fs(#[from] FsError),
    /// An object names an asset the state does not hold.
    #[error("object {object:?} uses asset {asset:?}, which is not loaded")]
    MissingAsset {
        /// Object id.
        object: String,
        /// Asset id.
        asset: String,
    },
    /// A writer produced a path that would leave the export folder (a bug, caught before
    /// anything is written).
    #[error("refusing to write {0:?}: the path leaves the export folder")]
    UnsafePath(String),
    /// A texture could not be encoded.
    #[error("texture {name:?} of asset {asset:?}: {reason}")]
    Texture {
        /// Asset id.
        asset: String,
        /// Texture name.
        name: String,
        /// What is wrong.
        reason: String,
    },
    /// The `--export` list names something unknown.
    #[error(
        "unknown export format {0:?}: use a comma-separated list of mjcf, usd, glb, or all / none"
    )]
    UnknownFormat(String),
}

/// One export format.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum ExportFormat {
    /// MuJoCo MJCF.
    Mjcf,
    /// USD with UsdPhysics.
    Usd,
    /// Binary glTF.
    Glb,
}

impl ExportFormat {
    /// Every format, in the order they are written.
    pub const ALL: [ExportFormat; 3] = [ExportFormat::Mjcf, ExportFormat::Usd, ExportFormat::Glb];

    /// `mjcf`, `usd` or `glb`.
    pub fn as_str(self) -> &'static str {
        match self {
            ExportFormat::Mjcf => "mjcf",
            ExportFormat::Usd => "usd",
            ExportFormat::Glb => "glb",
        }
    }

    /// The main file of the format, relative to the scene directory.
    pub fn main_file(self) -> &'static str {
        match self {
            ExportFormat::Mjcf => paths::MJCF_FILE,
            ExportFormat::Usd => paths::USD_FILE,
            ExportFormat::Glb => paths::GLB_FILE,
        }
    }
}

/// Which formats to write; the default is every format (what `generate` writes).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ExportSet(Vec<ExportFormat>);

impl Default for ExportSet {
    fn default() -> Self {
        Self::all()
    }
}

impl ExportSet {
    /// Every format.
    pub fn all() -> Self {
        ExportSet(ExportFormat::ALL.to_vec())
    }

    /// No format.
    pub fn none() -> Self {
        ExportSet(Vec::new())
    }

    /// Parses `mjcf,usd,glb`, `all` or `none` (case-insensitive, spaces ignored).
    pub fn parse(text: &str) -> Result<Self, ExportError> {
        let mut set = Vec::new();
        for part in text.split(',').map(|p| p.trim().to_ascii_lowercase()) {
            match part.as_str() {
                "" => {}
                "all" => set.extend(ExportFormat::ALL),
                "none" => {}
                "mjcf" | "mujoco" => set.push(ExportFormat::Mjcf),
                "usd" | "usda" => set.push(ExportFormat::Usd),
                "glb" | "gltf" => set.push(ExportFormat::Glb),
                _ => return Err(ExportError::UnknownFormat(part)),
            }
        }
        set.sort();
        set.dedup();
        Ok(ExportSet(set))
    }

    /// True when `format` is selected.
    pub fn contains(&self, format: ExportFormat) -> bool {
        self.0.contains(&format)
    }

    /// The selected formats, in writing order.
    pub fn formats(&self) -> &[ExportFormat] {
        &self.0
    }

    /// True when nothing is selected.
    pub fn is_empty(&self) -> bool {
        self.0.is_empty()
    }
}

/// A file of an export: path relative to the format's folder, and its bytes.
#[derive(Debug, Clone, PartialEq)]
pub struct ExportFile {
    /// Relative path with `/` separators, e.g. `meshes/table_x/c000.obj`.
    pub path: String,
    /// Content.
    pub bytes: Vec<u8>,
}

impl ExportFile {
    /// A file from text.
    pub fn text(path: impl Into<String>, text: String) -> Self {
        ExportFile {
            path: path.into(),
            bytes: text.into_bytes(),
        }
    }
}

/// `root` joined with a relative path whose every component is a plain name: no `..`, no root,
/// no drive, no empty or hidden-dot-only parts.
pub fn safe_join(root: &Path, rel: &str) -> Result<PathBuf, ExportError> {
    let p = Path::new(rel);
    let mut out = root.to_path_buf();
    let mut any = false;
    for c in p.components() {
        match c {
            Component::Normal(name) if !name.is_empty() => {
                out.push(name);
                any = true;
            }
            _ => return Err(ExportError::UnsafePath(rel.to_string())),
        }
    }
    if !any || rel.contains('\\') {
        return Err(ExportError::UnsafePath(rel.to_string()));
    }
    Ok(out)
}

/// A number for export text: shortest round-trip form, with round-off below 1e-12 (and -0)
/// written as `0`.
pub(crate) fn num(v: f64) -> String {
    if v.abs() < 1e-12 {
        "0".to_string()
    } else {
        format!("{v}")
    }
}

/// Space-separated [`num`]s.
pub(crate) fn nums(values: &[f64]) -> String {
    values.iter().map(|v| num(*v)).collect::<Vec<_>>().join(" ")
}

/// What one format wrote.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct WrittenExport {
    /// The format.
    pub format: ExportFormat,
    /// Main file, relative to the scene directory.
    pub main_file: String,
    /// Number of files written.
    pub files: usize,
    /// Total bytes written.
    pub bytes: usize,
}

/// Renders one format into memory.
pub fn render(state: &SceneState, format: ExportFormat) -> Result<Vec<ExportFile>, ExportError> {
    let view = SceneView::new(state)?;
    match format {
        ExportFormat::Mjcf => mjcf::files(&view),
        ExportFormat::Usd => usd::files(&view),
        ExportFormat::Glb => Ok(vec![ExportFile {
            path: "scene.glb".into(),
            bytes: glb::scene_glb(&view),
        }]),
    }
}

/// Writes the selected exports into `scene_dir/export/`. Each folder format is assembled in a
/// hidden sibling and swapped in whole, so a failure leaves the previous export in place.
pub fn write_exports(
    scene_dir: &Path,
    state: &SceneState,
    set: &ExportSet,
) -> Result<Vec<WrittenExport>, ExportError> {
    let mut written = Vec::new();
    for &format in set.formats() {
        let files = render(state, format)?;
        let bytes = files.iter().map(|f| f.bytes.len()).sum();
        match format {
            ExportFormat::Glb => {
                let path = safe_join(&scene_dir.join(paths::EXPORT_DIR), "scene.glb")?;
                let glb = files.first().map(|f| f.bytes.as_slice()).unwrap_or(&[]);
                write_atomic(&path, glb)?;
            }
            ExportFormat::Mjcf => write_folder(&scene_dir.join(paths::MJCF_DIR), &files)?,
            ExportFormat::Usd => write_folder(&scene_dir.join(paths::USD_DIR), &files)?,
        }
        written.push(WrittenExport {
            format,
            main_file: format.main_file().to_string(),
            files: files.len(),
            bytes,
        });
    }
    Ok(written)
}

/// Writes `files` into a fresh hidden sibling of `folder`, then replaces `folder` with it.
fn write_folder(folder: &Path, files: &[ExportFile]) -> Result<(), ExportError> {
    let parent = folder.parent().unwrap_or(Path::new("."));
    std::fs::create_dir_all(parent).map_err(io_err("create directory", parent))?;
    let name = folder
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| "export".into());
    let pid = std::process::id();
    let staging = parent.join(format!(".{name}.partial-{pid}"));
    let old = parent.join(format!(".{name}.old-{pid}"));
    for stale in [&staging, &old] {
        if stale.exists() {
            std::fs::remove_dir_all(stale).map_err(io_err("remove", stale))?;
        }
    }
    let result = (|| -> Result<(), ExportError> {
        for f in files {
            let path = safe_join(&staging, &f.path)?;
            if let Some(dir) = path.parent() {
                std::fs::create_dir_all(dir).map_err(io_err("create directory", dir))?;
            }
            std::fs::write(&path, &f.bytes).map_err(io_err("write", &path))?;
        }
        if folder.exists() {
            std::fs::rename(folder, &old).map_err(io_err("move aside", folder))?;
        }
        if let Err(e) = std::fs::rename(&staging, folder) {
            let _ = std::fs::rename(&old, folder);
            return Err(io_err("rename into", folder)(e).into());
        }
        Ok(())
    })();
    if result.is_err() {
        let _ = std::fs::remove_dir_all(&staging);
    }
    let _ = std::fs::remove_dir_all(&old);
    result
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn export_set_parses_lists() {
        assert_eq!(ExportSet::parse("all").unwrap(), ExportSet::all());
        assert_eq!(ExportSet::default(), ExportSet::all());
        assert!(ExportSet::parse("none").unwrap().is_empty());
        let s = ExportSet::parse(" USD , mjcf,usd").unwrap();
        assert_eq!(s.formats(), &[ExportFormat::Mjcf, ExportFormat::Usd]);
        assert!(ExportSet::parse("mjcf,fbx").is_err());
    }

    #[test]
    fn safe_join_rejects_escapes() {
        let root = Path::new("/tmp/x");
        assert!(safe_join(root, "meshes/a/c000.obj").is_ok());
        for bad in ["../a", "a/../../b", "/etc/passwd", "", ".", "a\\..\\b"] {
            assert!(safe_join(root, bad).is_err(), "{bad:?}");
        }
    }

    #[test]
    fn folder_swap_replaces_whole_folder() {
        let dir = tempfile::tempdir().unwrap();
        let folder = dir.path().join("export/mujoco");
        write_folder(&folder, &[ExportFile::text("a/old.txt", "old".into())]).unwrap();
        write_folder(&folder, &[ExportFile::text("b/new.txt", "new".into())]).unwrap();
        assert!(!folder.join("a/old.txt").exists());
        assert_eq!(
            std::fs::read_to_string(folder.join("b/new.txt")).unwrap(),
            "new"
        );
        // A bad path fails before the old folder is touched.
        let err = write_folder(&folder, &[ExportFile::text("../evil", "x".into())]);
        assert!(matches!(err, Err(ExportError::UnsafePath(_))));
        assert!(folder.join("b/new.txt").exists());
        assert!(!dir.path().join("export/evil").exists());
        let hidden: Vec<_> = std::fs::read_dir(dir.path().join("export"))
            .unwrap()
            .filter_map(|e| e.ok())
            .filter(|e| e.file_name().to_string_lossy().starts_with('.'))
            .collect();
        assert!(hidden.is_empty());
    }
}
