//! Files that are either wholly written or not there at all.
//!
//! Single files are written to a temporary sibling and renamed into place. A whole scene
//! directory is built in a hidden staging directory next to the target and swapped in by
//! [`StagingDir::commit`]; if the run fails first, the staging directory is removed and whatever
//! was at the target before is untouched.

use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

/// File-system errors with the path that caused them.
#[derive(Debug, thiserror::Error)]
pub enum FsError {
    /// An I/O operation failed.
    #[error("{action} {path}: {source}")]
    Io {
        /// What was being done ("write", "create directory", ...).
        action: &'static str,
        /// The path involved.
        path: PathBuf,
        /// The OS error.
        #[source]
        source: std::io::Error,
    },
    /// The target exists and is not something we may replace.
    #[error(
        "{0} exists and is not a scenesmith scene directory (no scene.json); refusing to replace it"
    )]
    NotASceneDir(PathBuf),
}

/// Wraps an `io::Error` with the action and path.
pub fn io_err<'a>(
    action: &'static str,
    path: &'a Path,
) -> impl FnOnce(std::io::Error) -> FsError + 'a {
    move |source| FsError::Io {
        action,
        path: path.to_path_buf(),
        source,
    }
}

static COUNTER: AtomicU64 = AtomicU64::new(0);

fn unique_suffix() -> String {
    format!(
        "{}-{}",
        std::process::id(),
        COUNTER.fetch_add(1, Ordering::Relaxed)
    )
}

/// Writes `bytes` to `path` atomically (temporary sibling, fsync, rename). Creates parent
/// directories.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<(), FsError> {
    let parent = path.parent().unwrap_or(Path::new("."));
    std::fs::create_dir_all(parent).map_err(io_err("create directory", parent))?;
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| "file".into());
    let tmp = parent.join(format!(".{name}.tmp-{}", unique_suffix()));
    let result = (|| {
        let mut f = std::fs::File::create(&tmp).map_err(io_err("create", &tmp))?;
        f.write_all(bytes).map_err(io_err("write", &tmp))?;
        f.sync_all().map_err(io_err("sync", &tmp))?;
        std::fs::rename(&tmp, path).map_err(io_err("rename into", path))
    })();
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    result
}

/// A hidden directory next to `target` where a whole output is assembled.
#[derive(Debug)]
pub struct StagingDir {
    path: PathBuf,
    target: PathBuf,
    committed: bool,
}

impl StagingDir {
    /// Creates `.<target name>.partial-<pid>-<n>` next to `target` (creating the parent).
    ///
    /// Fails early when `target` exists but is not a scene directory, or the parent is not
    /// writable, so nothing is computed for an output that could never be written.
    pub fn new(target: &Path) -> Result<StagingDir, FsError> {
        let target = if target.is_absolute() {
            target.to_path_buf()
        } else {
            std::env::current_dir()
                .map_err(io_err("resolve", target))?
                .join(target)
        };
        check_replaceable(&target)?;
        let parent = target.parent().unwrap_or(Path::new("/")).to_path_buf();
        std::fs::create_dir_all(&parent).map_err(io_err("create directory", &parent))?;
        let name = target
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_else(|| "scene".into());
        let path = parent.join(format!(".{name}.partial-{}", unique_suffix()));
        std::fs::create_dir(&path).map_err(io_err("create directory", &path))?;
        Ok(StagingDir {
            path,
            target,
            committed: false,
        })
    }

    /// Where files go while staging.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// The final location.
    pub fn target(&self) -> &Path {
        &self.target
    }

    /// Moves the staged directory to the target, replacing a previous scene there.
    pub fn commit(mut self) -> Result<PathBuf, FsError> {
        check_replaceable(&self.target)?;
        if self.target.exists() {
            let old = self.target.with_file_name(format!(
                ".{}.old-{}",
                self.target
                    .file_name()
                    .map(|n| n.to_string_lossy().into_owned())
                    .unwrap_or_default(),
                unique_suffix()
            ));
            std::fs::rename(&self.target, &old).map_err(io_err("move aside", &self.target))?;
            if let Err(e) = std::fs::rename(&self.path, &self.target) {
                // Put the previous scene back; the staged one stays for inspection.
                let _ = std::fs::rename(&old, &self.target);
                return Err(io_err("rename into", &self.target)(e));
            }
            let _ = std::fs::remove_dir_all(&old);
        } else {
            std::fs::rename(&self.path, &self.target)
                .map_err(io_err("rename into", &self.target))?;
        }
        self.committed = true;
        Ok(self.target.clone())
    }
}

impl Drop for StagingDir {
    fn drop(&mut self) {
        if !self.committed {
            let _ = std::fs::remove_dir_all(&self.path);
        }
    }
}

/// A target may be replaced when it does not exist, is an empty directory, or holds a scene.
fn check_replaceable(target: &Path) -> Result<(), FsError> {
    if !target.exists() {
        return Ok(());
    }
    if !target.is_dir() {
        return Err(FsError::NotASceneDir(target.to_path_buf()));
    }
    let empty = std::fs::read_dir(target)
        .map_err(io_err("read directory", target))?
        .next()
        .is_none();
    if empty || target.join("scene.json").is_file() {
        Ok(())
    } else {
        Err(FsError::NotASceneDir(target.to_path_buf()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn atomic_write_replaces_content() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("a/b.txt");
        write_atomic(&p, b"one").unwrap();
        write_atomic(&p, b"two").unwrap();
        assert_eq!(std::fs::read(&p).unwrap(), b"two");
        let leftovers: Vec<_> = std::fs::read_dir(p.parent().unwrap())
            .unwrap()
            .filter_map(|e| e.ok())
            .filter(|e| e.file_name().to_string_lossy().contains(".tmp-"))
            .collect();
        assert!(leftovers.is_empty());
    }

    #[test]
    fn dropped_staging_leaves_target_untouched() {
        let dir = tempfile::tempdir().unwrap();
        let target = dir.path().join("scene");
        std::fs::create_dir(&target).unwrap();
        std::fs::write(target.join("scene.json"), "old").unwrap();
        {
            let staging = StagingDir::new(&target).unwrap();
            std::fs::write(staging.path().join("scene.json"), "new").unwrap();
        }
        assert_eq!(
            std::fs::read_to_string(target.join("scene.json")).unwrap(),
            "old"
        );
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
    }

    #[test]
    fn commit_replaces_previous_scene() {
        let dir = tempfile::tempdir().unwrap();
        let target = dir.path().join("scene");
        std::fs::create_dir(&target).unwrap();
        std::fs::write(target.join("scene.json"), "old").unwrap();
        let staging = StagingDir::new(&target).unwrap();
        std::fs::write(staging.path().join("scene.json"), "new").unwrap();
        staging.commit().unwrap();
        assert_eq!(
            std::fs::read_to_string(target.join("scene.json")).unwrap(),
            "new"
        );
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
    }

    #[test]
    fn refuses_to_replace_unrelated_directory() {
        let dir = tempfile::tempdir().unwrap();
        let target = dir.path().join("home");
        std::fs::create_dir(&target).unwrap();
        std::fs::write(target.join("thesis.tex"), "precious").unwrap();
        assert!(matches!(
            StagingDir::new(&target),
            Err(FsError::NotASceneDir(_))
        ));
    }
}
