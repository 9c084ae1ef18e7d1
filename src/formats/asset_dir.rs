//! Writing one asset as a directory of its own (what `scenesmith asset` produces): the
//! SDFormat model with its glTF visuals and convex OBJ collisions, `asset.json` (the scene's
//! asset record plus whatever the caller adds: routing notes, physics summary), and an
//! optional preview image.
//!
//! The directory is assembled next to the target and renamed into place, so a failed write
//! leaves the previous contents intact. A target that exists must be empty or a previous
//! asset directory (it holds `asset.json`); anything else is refused.

use std::path::{Path, PathBuf};

use super::sdf::asset_files;
use crate::assets::Asset;
use crate::util::fsx::io_err;

/// Name of the summary file in an asset directory.
pub const ASSET_JSON: &str = "asset.json";

/// What can go wrong writing an asset directory.
#[derive(Debug, thiserror::Error)]
pub enum AssetWriteError {
    /// File-system error.
    #[error(transparent)]
    Fs(#[from] crate::util::fsx::FsError),
    /// The target holds something that is not an asset directory.
    #[error("{0} exists and is not an asset directory (no asset.json); choose another --out")]
    NotAnAssetDir(PathBuf),
}

fn replaceable(target: &Path) -> Result<(), AssetWriteError> {
    if !target.exists() {
        return Ok(());
    }
    let empty = target.is_dir()
        && std::fs::read_dir(target)
            .map_err(io_err("read directory", target))?
            .next()
            .is_none();
    if empty || target.join(ASSET_JSON).is_file() {
        Ok(())
    } else {
        Err(AssetWriteError::NotAnAssetDir(target.to_path_buf()))
    }
}

/// Writes `asset` into `target` (replacing a previous asset directory there): its model
/// files, `asset.json` = `{"record": <asset record>, ...summary}`, and `preview.png` when
/// given. Returns the file names written.
pub fn write_asset_dir(
    target: &Path,
    asset: &Asset,
    summary: serde_json::Value,
    preview_png: Option<&[u8]>,
) -> Result<Vec<String>, AssetWriteError> {
    replaceable(target)?;
    let parent = target
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    std::fs::create_dir_all(parent).map_err(io_err("create directory", parent))?;
    let name = target
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| "asset".into());
    let stage = parent.join(format!(".{name}.partial-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&stage);
    std::fs::create_dir_all(&stage).map_err(io_err("create directory", &stage))?;
    let result = (|| -> Result<Vec<String>, AssetWriteError> {
        let mut written = Vec::new();
        for f in asset_files(asset) {
            let p = stage.join(&f.name);
            std::fs::write(&p, &f.bytes).map_err(io_err("write", &p))?;
            written.push(f.name);
        }
        if let Some(png) = preview_png {
            let p = stage.join("preview.png");
            std::fs::write(&p, png).map_err(io_err("write", &p))?;
            written.push("preview.png".into());
        }
        let mut doc = serde_json::json!({"record": asset.record()});
        if let serde_json::Value::Object(extra) = summary {
            for (k, v) in extra {
                doc[k] = v;
            }
        }
        let mut text = serde_json::to_string_pretty(&doc).unwrap_or_default();
        text.push('\n');
        let p = stage.join(ASSET_JSON);
        std::fs::write(&p, text).map_err(io_err("write", &p))?;
        written.push(ASSET_JSON.into());
        if target.exists() {
            let old = parent.join(format!(".{name}.old-{}", std::process::id()));
            std::fs::rename(target, &old).map_err(io_err("move aside", target))?;
            if let Err(e) = std::fs::rename(&stage, target) {
                let _ = std::fs::rename(&old, target);
                return Err(io_err("rename into", target)(e).into());
            }
            let _ = std::fs::remove_dir_all(&old);
        } else {
            std::fs::rename(&stage, target).map_err(io_err("rename into", target))?;
        }
        Ok(written)
    })();
    if result.is_err() {
        let _ = std::fs::remove_dir_all(&stage);
    }
    result
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::assets::procedural::{AssetRequest, build};

    #[test]
    fn writes_replaces_and_refuses_foreign_directories() {
        let root = tempfile::tempdir().unwrap();
        let out = root.path().join("lamp");
        let a = build(&AssetRequest::new("floor_lamp", 1)).unwrap();
        let files =
            write_asset_dir(&out, &a, serde_json::json!({"notes": ["x"]}), Some(b"png")).unwrap();
        assert!(
            files.contains(&"model.sdf".to_string()) && files.contains(&"preview.png".to_string())
        );
        let doc: serde_json::Value =
            serde_json::from_slice(&std::fs::read(out.join(ASSET_JSON)).unwrap()).unwrap();
        assert_eq!(doc["record"]["id"], a.id.as_str());
        assert_eq!(doc["notes"][0], "x");
        // A second write replaces the first.
        let b = build(&AssetRequest::new("stool", 1)).unwrap();
        write_asset_dir(&out, &b, serde_json::json!({}), None).unwrap();
        assert!(!out.join("preview.png").exists());
        // Something else is never replaced.
        let foreign = root.path().join("mine");
        std::fs::create_dir_all(&foreign).unwrap();
        std::fs::write(foreign.join("thesis.tex"), "keep me").unwrap();
        assert!(matches!(
            write_asset_dir(&foreign, &b, serde_json::json!({}), None),
            Err(AssetWriteError::NotAnAssetDir(_))
        ));
        assert_eq!(
            std::fs::read_to_string(foreign.join("thesis.tex")).unwrap(),
            "keep me"
        );
        let leftovers: Vec<_> = std::fs::read_dir(root.path())
            .unwrap()
            .filter_map(|e| e.ok())
            .filter(|e| e.file_name().to_string_lossy().starts_with('.'))
            .collect();
        assert!(leftovers.is_empty());
    }
}
