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

use crate::state::SceneState;
use crate::util::fsx::{FsError, io_err};

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

    /// Its folder inside `export/` ("" for the single-file glTF).
    fn folder(self) -> &'static str {
        match self {
            ExportFormat::Mjcf => "mujoco",
            ExportFormat::Usd => "usd",
            ExportFormat::Glb => "",
        }
    }

    /// Whether the file `rel` (relative to `export/`) belongs to this format's export.
    fn owns(self, rel: &Path) -> bool {
        match self {
            ExportFormat::Glb => rel == Path::new("scene.glb"),
            _ => rel.starts_with(self.folder()),
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

/// Writes the selected exports into `scene_dir/export/`. All of them are rendered first, then
/// `export/` is replaced whole (the formats not selected carried over from the previous export),
/// so a failure leaves the previous exports in place, never a mix of old and new.
pub fn write_exports(
    scene_dir: &Path,
    state: &SceneState,
    set: &ExportSet,
) -> Result<Vec<WrittenExport>, ExportError> {
    let mut rendered = Vec::new();
    for &format in set.formats() {
        rendered.push((format, render(state, format)?));
    }
    let written = rendered
        .iter()
        .map(|(format, files)| WrittenExport {
            format: *format,
            main_file: format.main_file().to_string(),
            files: files.len(),
            bytes: files.iter().map(|f| f.bytes.len()).sum(),
        })
        .collect();
    replace_exports(scene_dir, rendered)?;
    Ok(written)
}

/// Replaces `scene_dir/export/` with the `rendered` formats plus the files of the formats not
/// rendered, carried over from the previous export.
fn replace_exports(
    scene_dir: &Path,
    rendered: Vec<(ExportFormat, Vec<ExportFile>)>,
) -> Result<(), ExportError> {
    if rendered.is_empty() {
        return Ok(());
    }
    let export_dir = scene_dir.join(paths::EXPORT_DIR);
    let mut staged: Vec<(PathBuf, Vec<u8>)> = Vec::new();
    for rel in crate::util::fsx::files_under(&export_dir)? {
        if !rendered.iter().any(|(f, _)| f.owns(&rel)) {
            let path = export_dir.join(&rel);
            let bytes = std::fs::read(&path).map_err(io_err("read", &path))?;
            staged.push((rel, bytes));
        }
    }
    for (format, files) in rendered {
        let folder = format.folder();
        for f in files {
            // Refuses paths that would leave the folder.
            safe_join(&export_dir.join(folder), &f.path)?;
            staged.push((Path::new(folder).join(&f.path), f.bytes));
        }
    }
    crate::util::fsx::replace_folder(scene_dir, &export_dir, &staged)?;
    Ok(())
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
    fn exports_are_replaced_whole_and_other_formats_carried_over() {
        let dir = tempfile::tempdir().unwrap();
        let scene = dir.path();
        let mjcf = |name: &str| (ExportFormat::Mjcf, vec![ExportFile::text(name, "m".into())]);
        let glb = (
            ExportFormat::Glb,
            vec![ExportFile::text("scene.glb", "g".into())],
        );
        replace_exports(scene, vec![mjcf("a/old.xml"), glb]).unwrap();
        replace_exports(scene, vec![mjcf("b/new.xml")]).unwrap();
        let export = scene.join(paths::EXPORT_DIR);
        assert!(!export.join("mujoco/a/old.xml").exists());
        assert!(export.join("mujoco/b/new.xml").is_file());
        assert_eq!(
            std::fs::read_to_string(export.join("scene.glb")).unwrap(),
            "g"
        );
        // A bad path fails before the old exports are touched.
        let err = replace_exports(scene, vec![mjcf("../evil")]);
        assert!(matches!(err, Err(ExportError::UnsafePath(_))));
        assert!(export.join("mujoco/b/new.xml").is_file());
        assert!(!export.join("evil").exists());
        let hidden: Vec<_> = std::fs::read_dir(scene)
            .unwrap()
            .filter_map(|e| e.ok())
            .filter(|e| e.file_name().to_string_lossy().starts_with('.'))
            .collect();
        assert!(hidden.is_empty());
    }
}
