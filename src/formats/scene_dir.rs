//! The scene directory: `package.xml`, `scene.dmd.yaml`, `scene_furniture_welded.dmd.yaml`,
//! `scene.json`, `assets/<id>/...` and `rooms/<room>/...`.

use std::path::Path;

use super::FormatError;
use super::directives::{Variant, directives_yaml, package_xml};
use super::sdf::asset_files;
use crate::scene::Scene;
use crate::state::SceneState;
use crate::util::fsx::{io_err, write_atomic};

/// Names of the files at the top of a scene directory.
pub mod names {
    /// Drake directives, furniture and manipulands free.
    pub const DIRECTIVES: &str = "scene.dmd.yaml";
    /// Drake directives, furniture welded.
    pub const DIRECTIVES_FURNITURE_WELDED: &str = "scene_furniture_welded.dmd.yaml";
    /// The scene state.
    pub const SCENE_JSON: &str = "scene.json";
    /// The package manifest.
    pub const PACKAGE_XML: &str = "package.xml";
}

fn write_plain(path: &Path, bytes: &[u8]) -> Result<(), FormatError> {
    if let Some(parent) = path.parent() {
        std::fs::create_dir_all(parent).map_err(io_err("create directory", parent))?;
    }
    std::fs::write(path, bytes).map_err(io_err("write", path))?;
    Ok(())
}

/// Writes every file of the scene into `dir` (normally a staging directory).
pub fn write_scene_dir(dir: &Path, state: &SceneState) -> Result<(), FormatError> {
    let scene = &state.scene;
    for (id, asset) in &state.assets {
        if !scene.objects.iter().any(|o| &o.asset == id) {
            continue;
        }
        let asset_dir = dir.join(asset.scene_dir());
        for f in asset_files(asset) {
            write_plain(&asset_dir.join(&f.name), &f.bytes)?;
        }
    }
    write_plain(&dir.join(names::PACKAGE_XML), package_xml(scene).as_bytes())?;
    for (name, variant) in [
        (names::DIRECTIVES, Variant::Default),
        (names::DIRECTIVES_FURNITURE_WELDED, Variant::FurnitureWelded),
    ] {
        let yaml = directives_yaml(scene, variant).map_err(|e| FormatError::Yaml(e.to_string()))?;
        write_plain(&dir.join(name), yaml.as_bytes())?;
    }
    write_scene_json(dir, scene)
}

/// Writes `scene.json` atomically.
pub fn write_scene_json(dir: &Path, scene: &Scene) -> Result<(), FormatError> {
    let mut text = serde_json::to_string_pretty(scene).map_err(|e| FormatError::SceneJson {
        path: dir.join(names::SCENE_JSON),
        reason: e.to_string(),
    })?;
    text.push('\n');
    write_atomic(&dir.join(names::SCENE_JSON), text.as_bytes())?;
    Ok(())
}

/// Loads a whole scene directory: `scene.json` plus every asset read back from its folder.
pub fn load_state(dir: &Path) -> Result<SceneState, FormatError> {
    let scene = read_scene(dir)?;
    let mut state = SceneState::new(scene);
    for (id, record) in &state.scene.assets {
        let asset_dir = record
            .sdf
            .strip_suffix("/model.sdf")
            .map(|d| dir.join(d))
            .filter(|_| !record.sdf.contains(".."))
            .ok_or_else(|| FormatError::AssetRead {
                asset: id.clone(),
                dir: dir.to_path_buf(),
                reason: format!("unexpected model path {:?}", record.sdf),
            })?;
        let asset = super::sdf_read::read_asset(&asset_dir, record).map_err(|reason| {
            FormatError::AssetRead {
                asset: id.clone(),
                dir: asset_dir.clone(),
                reason,
            }
        })?;
        state.assets.insert(id.clone(), asset);
    }
    Ok(state)
}

/// Reads and validates `scene.json` from a scene directory.
pub fn read_scene(dir: &Path) -> Result<Scene, FormatError> {
    let path = dir.join(names::SCENE_JSON);
    let text = std::fs::read_to_string(&path).map_err(|e| FormatError::SceneJson {
        path: path.clone(),
        reason: e.to_string(),
    })?;
    let scene: Scene = serde_json::from_str(&text).map_err(|e| FormatError::SceneJson {
        path: path.clone(),
        reason: e.to_string(),
    })?;
    scene.validate().map_err(|e| FormatError::SceneJson {
        path,
        reason: e.to_string(),
    })?;
    Ok(scene)
}
