//! Scene files for the Drake bridge while a scene is still in memory: a temporary directory
//! with the scene's `package.xml` and asset folders, plus one directives file per *subset*
//! (some objects free, some welded, the rest absent) that a settle request loads.
//!
//! Directives files are named by the hash of their text, so the same subset is the same file
//! and the bridge's plant cache recognises it. The directory is deleted when the workspace is
//! dropped. This module writes files only; it does not talk to the bridge.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

use super::PhysicsError;
use crate::formats::FormatError;
use crate::formats::directives::{Variant, directives_yaml, package_xml};
use crate::formats::sdf::asset_files;
use crate::state::SceneState;

/// How an object takes part in a subset scene.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum Role {
    /// Free body (gravity acts on it).
    Free,
    /// Welded to the world where it stands.
    Welded,
}

/// A temporary directory holding a scene's assets and subset directives.
pub struct Workspace {
    dir: tempfile::TempDir,
    written: BTreeSet<String>,
}

fn io(path: &Path) -> impl FnOnce(std::io::Error) -> PhysicsError + '_ {
    move |source| PhysicsError::Io {
        path: path.to_path_buf(),
        cause: source,
    }
}

impl Workspace {
    /// A new workspace with the package manifest and every asset of `state`.
    pub fn new(state: &SceneState) -> Result<Workspace, PhysicsError> {
        let dir = tempfile::Builder::new()
            .prefix("scenesmith-physics-")
            .tempdir()
            .map_err(io(&std::env::temp_dir()))?;
        let mut ws = Workspace {
            dir,
            written: BTreeSet::new(),
        };
        let pkg = ws.package_xml();
        std::fs::write(&pkg, package_xml(&state.scene)).map_err(io(&pkg))?;
        ws.sync_assets(state)?;
        Ok(ws)
    }

    /// The directory.
    pub fn path(&self) -> &Path {
        self.dir.path()
    }

    /// The package manifest every directives file resolves `package://` against.
    pub fn package_xml(&self) -> PathBuf {
        self.dir.path().join("package.xml")
    }

    /// Writes the assets of `state` not written yet (asset ids are content-addressed, so a
    /// written id never changes).
    pub fn sync_assets(&mut self, state: &SceneState) -> Result<(), PhysicsError> {
        for (id, asset) in &state.assets {
            if self.written.contains(id) {
                continue;
            }
            let asset_dir = self.dir.path().join(asset.scene_dir());
            std::fs::create_dir_all(&asset_dir).map_err(io(&asset_dir))?;
            for f in asset_files(asset) {
                let path = asset_dir.join(&f.name);
                std::fs::write(&path, &f.bytes).map_err(io(&path))?;
            }
            self.written.insert(id.clone());
        }
        Ok(())
    }

    /// Writes the directives of a subset: the listed objects with their roles (architecture is
    /// always static), in scene order; returns the file's path.
    pub fn write_subset(
        &mut self,
        state: &SceneState,
        members: &BTreeMap<String, Role>,
    ) -> Result<PathBuf, PhysicsError> {
        for id in members.keys() {
            if state.scene.object(id).is_none() {
                return Err(PhysicsError::UnknownObject(id.clone()));
            }
        }
        self.sync_assets(state)?;
        let mut sub = state.scene.clone();
        sub.objects.retain(|o| members.contains_key(&o.id));
        for o in &mut sub.objects {
            o.welded = members.get(&o.id) == Some(&Role::Welded);
        }
        let yaml = directives_yaml(&sub, Variant::Default)
            .map_err(|e| FormatError::Yaml(e.to_string()))?;
        let hash = blake3::hash(yaml.as_bytes()).to_hex();
        let path = self
            .dir
            .path()
            .join(format!("subset_{}.dmd.yaml", &hash.as_str()[..16]));
        if !path.exists() {
            std::fs::write(&path, yaml).map_err(io(&path))?;
        }
        Ok(path)
    }
}
