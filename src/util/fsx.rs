//! Files that are either wholly written or not there at all.
//!
//! Single files are written to a temporary sibling and renamed into place. A whole scene
//! directory is built in a hidden staging directory next to the target and swapped in by
//! [`StagingDir::commit`]; if the run fails first, the staging directory is removed and whatever
//! was at the target before is untouched.
//!
//! A scene directory lists the files the tool wrote in it ([`MANIFEST`]). Replacing a scene
//! deletes the old one only when it holds nothing else; a directory with files the tool did not
//! write (a user's notes, a hand-edited model) is kept beside the new scene as `<name>.previous`.

use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

/// File-system errors with the path that caused them.
#[derive(Debug, thiserror::Error)]
pub enum FsError {
    /// An I/O operation failed.
    #[error("{action} {path}: {cause}")]
    Io {
        /// What was being done ("write", "create directory", ...).
        action: &'static str,
        /// The path involved.
        path: PathBuf,
        /// The OS error.
        cause: std::io::Error,
    },
    /// The target exists and is not something we may replace.
    #[error(
        "{0} exists and is not a scene directory written by scenesmith (no scene.json with its \
         schema_version and provenance); refusing to replace it"
    )]
    NotASceneDir(PathBuf),
    /// A folder the tool replaces whole holds files the tool did not write.
    #[error(
        "{folder} holds {file}, which scenesmith did not write; move it away (the folder is \
         replaced whole)"
    )]
    ForeignFile {
        /// The folder to be replaced.
        folder: PathBuf,
        /// One of the files the tool did not write.
        file: PathBuf,
    },
}

/// The file in a scene directory that lists, one relative path per line, every file the tool
/// wrote there.
pub const MANIFEST: &str = ".scenesmith_files";

/// Every regular file under `dir`, as paths relative to `dir`, sorted; the manifest itself
/// left out. A missing `dir` has none.
pub fn files_under(dir: &Path) -> Result<Vec<PathBuf>, FsError> {
    let mut out = Vec::new();
    let mut stack = vec![PathBuf::new()];
    while let Some(rel) = stack.pop() {
        let abs = dir.join(&rel);
        let entries = match std::fs::read_dir(&abs) {
            Ok(e) => e,
            Err(e) if e.kind() == std::io::ErrorKind::NotFound && rel.as_os_str().is_empty() => {
                return Ok(out);
            }
            Err(e) => return Err(io_err("read directory", &abs)(e)),
        };
        for entry in entries {
            let entry = entry.map_err(io_err("read directory", &abs))?;
            let kind = entry
                .file_type()
                .map_err(io_err("inspect", &entry.path()))?;
            let name = rel.join(entry.file_name());
            if kind.is_dir() {
                stack.push(name);
            } else if name.as_os_str() != MANIFEST {
                out.push(name);
            }
        }
    }
    out.sort();
    Ok(out)
}

fn read_manifest(dir: &Path) -> Result<Option<Vec<PathBuf>>, FsError> {
    let path = dir.join(MANIFEST);
    match std::fs::read_to_string(&path) {
        Ok(text) => Ok(Some(
            text.lines()
                .filter(|l| !l.is_empty())
                .map(PathBuf::from)
                .collect(),
        )),
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => Ok(None),
        Err(e) => Err(io_err("read", &path)(e)),
    }
}

fn write_manifest(dir: &Path, files: &[PathBuf]) -> Result<(), FsError> {
    let mut text = String::new();
    for f in files {
        text.push_str(&f.to_string_lossy());
        text.push('\n');
    }
    write_atomic(&dir.join(MANIFEST), text.as_bytes())
}

/// Records in the manifest of the scene directory `dir` that the tool wrote `files` (relative
/// to `dir`) and, under `prefix`, nothing else (entries under `prefix` that are not in `files`
/// are dropped). A directory without a manifest is left without one.
pub fn record_files(dir: &Path, prefix: &Path, files: &[PathBuf]) -> Result<(), FsError> {
    let Some(mut listed) = read_manifest(dir)? else {
        return Ok(());
    };
    listed.retain(|f| !f.starts_with(prefix));
    listed.extend(files.iter().cloned());
    listed.sort();
    listed.dedup();
    write_manifest(dir, &listed)
}

/// Writes `bytes` atomically to `dir/name` and records the file in the manifest of the scene
/// directory `dir`.
pub fn write_scene_file(dir: &Path, name: &str, bytes: &[u8]) -> Result<(), FsError> {
    write_atomic(&dir.join(name), bytes)?;
    let rel = PathBuf::from(name);
    record_files(dir, &rel, std::slice::from_ref(&rel))
}

/// Files under `dir` (relative) that its manifest does not list: all of them when it has none.
pub fn unlisted_files(dir: &Path) -> Result<Vec<PathBuf>, FsError> {
    let listed = read_manifest(dir)?.unwrap_or_default();
    Ok(files_under(dir)?
        .into_iter()
        .filter(|f| !listed.contains(f))
        .collect())
}

/// Replaces `folder` with exactly `files` (`(path relative to folder, bytes)`), whatever it
/// held: assembled in a hidden sibling, then swapped in, so a failure leaves the previous
/// folder whole. Callers check first that the old folder holds nothing of the user's.
pub fn swap_folder(folder: &Path, files: &[(PathBuf, Vec<u8>)]) -> Result<(), FsError> {
    let parent = folder.parent().unwrap_or(Path::new("."));
    std::fs::create_dir_all(parent).map_err(io_err("create directory", parent))?;
    let name = folder
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| "folder".into());
    let staging = parent.join(format!(".{name}.partial-{}", unique_suffix()));
    let old = parent.join(format!(".{name}.old-{}", unique_suffix()));
    let result = (|| -> Result<(), FsError> {
        std::fs::create_dir_all(&staging).map_err(io_err("create directory", &staging))?;
        for (path, bytes) in files {
            let path = staging.join(path);
            if let Some(dir) = path.parent() {
                std::fs::create_dir_all(dir).map_err(io_err("create directory", dir))?;
            }
            std::fs::write(&path, bytes).map_err(io_err("write", &path))?;
        }
        if folder.exists() {
            std::fs::rename(folder, &old).map_err(io_err("move aside", folder))?;
        }
        if let Err(e) = std::fs::rename(&staging, folder) {
            let _ = std::fs::rename(&old, folder);
            return Err(io_err("rename into", folder)(e));
        }
        Ok(())
    })();
    if result.is_err() {
        let _ = std::fs::remove_dir_all(&staging);
    }
    let _ = std::fs::remove_dir_all(&old);
    result
}

/// Replaces `folder` (inside the scene directory `scene_dir`) with exactly `files`
/// (`(path relative to folder, bytes)`): assembled in a hidden sibling, then swapped in, so a
/// failure leaves the previous folder whole. Refuses when the old folder holds a file the tool
/// did not write (a scene directory without a manifest is from an earlier version: its folders
/// are taken as the tool's); records the new files in the scene's manifest.
pub fn replace_folder(
    scene_dir: &Path,
    folder: &Path,
    files: &[(PathBuf, Vec<u8>)],
) -> Result<(), FsError> {
    let rel = folder
        .strip_prefix(scene_dir)
        .unwrap_or(folder)
        .to_path_buf();
    // A scene from a version before manifests: its export and render folders are the tool's.
    if let Some(listed) = read_manifest(scene_dir)?
        && let Some(f) = files_under(folder)?
            .into_iter()
            .find(|f| !listed.contains(&rel.join(f)))
    {
        return Err(FsError::ForeignFile {
            folder: folder.to_path_buf(),
            file: f,
        });
    }
    swap_folder(folder, files)?;
    let written: Vec<PathBuf> = files.iter().map(|(p, _)| rel.join(p)).collect();
    record_files(scene_dir, &rel, &written)
}

/// Wraps an `io::Error` with the action and path.
pub fn io_err<'a>(
    action: &'static str,
    path: &'a Path,
) -> impl FnOnce(std::io::Error) -> FsError + 'a {
    move |source| FsError::Io {
        action,
        path: path.to_path_buf(),
        cause: source,
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
    keep_on_failure: Vec<&'static str>,
}

/// What [`StagingDir::commit`] did.
#[derive(Debug, Clone, PartialEq)]
pub struct Committed {
    /// The scene directory.
    pub path: PathBuf,
    /// Where the replaced directory was kept because it held files the tool did not write.
    pub kept_previous: Option<PathBuf>,
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
            keep_on_failure: Vec::new(),
        })
    }

    /// When the run fails, the staged file `name` is kept as `<target>.<name>` (see
    /// [`StagingDir::kept_path`]) instead of going with the staging directory.
    pub fn keep_on_failure(&mut self, name: &'static str) {
        self.keep_on_failure.push(name);
    }

    /// Where the staged file `name` is kept after a failed run.
    pub fn kept_path(target: &Path, name: &str) -> PathBuf {
        let stem = target
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_else(|| "scene".into());
        target.with_file_name(format!("{stem}.{name}"))
    }

    /// Where files go while staging.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// The final location.
    pub fn target(&self) -> &Path {
        &self.target
    }

    /// Moves the staged directory to the target, writing its manifest. A previous scene there
    /// is deleted when it holds only files the tool wrote; otherwise it is kept as
    /// `<target>.previous` (`.previous-2`, ... when that exists).
    pub fn commit(mut self) -> Result<Committed, FsError> {
        check_replaceable(&self.target)?;
        write_manifest(&self.path, &files_under(&self.path)?)?;
        let mut kept_previous = None;
        if self.target.exists() {
            let foreign = !unlisted_files(&self.target)?.is_empty();
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
            if foreign {
                let keep = free_previous_path(&self.target);
                std::fs::rename(&old, &keep)
                    .map_err(io_err("keep the previous scene as", &keep))?;
                kept_previous = Some(keep);
            } else {
                let _ = std::fs::remove_dir_all(&old);
            }
        } else {
            std::fs::rename(&self.path, &self.target)
                .map_err(io_err("rename into", &self.target))?;
        }
        self.committed = true;
        Ok(Committed {
            path: self.target.clone(),
            kept_previous,
        })
    }
}

/// `<target>.previous`, or the first of `<target>.previous-2`, `-3`, ... that does not exist.
fn free_previous_path(target: &Path) -> PathBuf {
    let first = StagingDir::kept_path(target, "previous");
    if !first.exists() {
        return first;
    }
    (2..)
        .map(|n| StagingDir::kept_path(target, &format!("previous-{n}")))
        .find(|p| !p.exists())
        .unwrap_or(first)
}

impl Drop for StagingDir {
    fn drop(&mut self) {
        if !self.committed {
            for name in &self.keep_on_failure {
                let staged = self.path.join(name);
                if staged.is_file() {
                    let _ = std::fs::rename(&staged, StagingDir::kept_path(&self.target, name));
                }
            }
            let _ = std::fs::remove_dir_all(&self.path);
        }
    }
}

/// Whether `dir/scene.json` is a scene this tool wrote: a JSON object with a numeric
/// `schema_version` and a `provenance` that names the tool's version.
pub fn is_scene_dir(dir: &Path) -> bool {
    let Ok(text) = std::fs::read_to_string(dir.join("scene.json")) else {
        return false;
    };
    let Ok(v) = serde_json::from_str::<serde_json::Value>(&text) else {
        return false;
    };
    v["schema_version"].is_u64() && v["provenance"]["tool_version"].is_string()
}

/// A target may be replaced when it does not exist, is an empty directory, or holds a scene
/// this tool wrote.
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
    if empty || is_scene_dir(target) {
        Ok(())
    } else {
        Err(FsError::NotASceneDir(target.to_path_buf()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const OLD_SCENE: &str = r#"{"schema_version": 1, "provenance": {"tool_version": "0.1.0"}}"#;

    /// A scene directory the tool wrote: its scene.json, listed in its manifest.
    fn write_old_scene(target: &Path) {
        std::fs::create_dir_all(target).unwrap();
        std::fs::write(target.join("scene.json"), OLD_SCENE).unwrap();
        write_manifest(target, &[PathBuf::from("scene.json")]).unwrap();
    }

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
        write_old_scene(&target);
        {
            let staging = StagingDir::new(&target).unwrap();
            std::fs::write(staging.path().join("scene.json"), "new").unwrap();
        }
        assert_eq!(
            std::fs::read_to_string(target.join("scene.json")).unwrap(),
            OLD_SCENE
        );
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
    }

    #[test]
    fn commit_replaces_previous_scene() {
        let dir = tempfile::tempdir().unwrap();
        let target = dir.path().join("scene");
        std::fs::create_dir(&target).unwrap();
        write_old_scene(&target);
        let staging = StagingDir::new(&target).unwrap();
        std::fs::write(staging.path().join("scene.json"), "new").unwrap();
        let done = staging.commit().unwrap();
        assert_eq!(done.kept_previous, None);
        assert_eq!(
            std::fs::read_to_string(target.join("scene.json")).unwrap(),
            "new"
        );
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
        assert_eq!(
            std::fs::read_to_string(target.join(MANIFEST)).unwrap(),
            "scene.json\n"
        );
    }

    #[test]
    fn a_previous_scene_with_a_users_file_is_kept_beside_the_new_one() {
        let dir = tempfile::tempdir().unwrap();
        let target = dir.path().join("scene");
        write_old_scene(&target);
        std::fs::write(target.join("notes.txt"), "mine").unwrap();
        for round in 0..2 {
            let staging = StagingDir::new(&target).unwrap();
            std::fs::write(staging.path().join("scene.json"), OLD_SCENE).unwrap();
            let done = staging.commit().unwrap();
            let kept = done.kept_previous.expect("kept");
            let name = ["scene.previous", "scene.previous-2"][round];
            assert_eq!(kept, dir.path().join(name));
            assert_eq!(
                std::fs::read_to_string(kept.join("notes.txt")).unwrap(),
                "mine"
            );
            // The new scene carries a manifest: the user's file goes into it for the next round.
            std::fs::write(target.join("notes.txt"), "mine").unwrap();
        }
    }

    #[test]
    fn a_directory_whose_scene_json_is_not_ours_is_refused() {
        let dir = tempfile::tempdir().unwrap();
        let target = dir.path().join("work");
        std::fs::create_dir(&target).unwrap();
        std::fs::write(target.join("scene.json"), r#"{"camera": [0, 1, 2]}"#).unwrap();
        std::fs::write(target.join("data.csv"), "1,2").unwrap();
        assert!(matches!(
            StagingDir::new(&target),
            Err(FsError::NotASceneDir(_))
        ));
        assert!(target.join("data.csv").is_file());
    }

    #[test]
    fn a_failed_run_keeps_the_files_it_was_told_to_keep() {
        let dir = tempfile::tempdir().unwrap();
        let target = dir.path().join("scene");
        {
            let mut staging = StagingDir::new(&target).unwrap();
            staging.keep_on_failure("llm_log.jsonl");
            std::fs::write(staging.path().join("llm_log.jsonl"), "{}\n").unwrap();
            std::fs::write(staging.path().join("scene.json"), "half").unwrap();
        }
        let kept = StagingDir::kept_path(&target, "llm_log.jsonl");
        assert_eq!(kept, dir.path().join("scene.llm_log.jsonl"));
        assert_eq!(std::fs::read_to_string(&kept).unwrap(), "{}\n");
        assert!(!target.exists());
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
    }

    #[test]
    fn a_replaced_folder_holds_exactly_the_new_files() {
        let dir = tempfile::tempdir().unwrap();
        let scene = dir.path().join("scene");
        std::fs::create_dir(&scene).unwrap();
        write_manifest(&scene, &[]).unwrap();
        let folder = scene.join("renders");
        let files = |names: &[&str]| -> Vec<(PathBuf, Vec<u8>)> {
            names
                .iter()
                .map(|n| (PathBuf::from(n), b"png".to_vec()))
                .collect()
        };
        replace_folder(&scene, &folder, &files(&["top.png", "kitchen_view_0.png"])).unwrap();
        replace_folder(&scene, &folder, &files(&["top.png"])).unwrap();
        assert_eq!(
            files_under(&folder).unwrap(),
            vec![PathBuf::from("top.png")]
        );
        assert!(unlisted_files(&scene).unwrap().is_empty());
        // A file the tool did not write stops the replacement and stays.
        std::fs::write(folder.join("sketch.png"), "mine").unwrap();
        let err = replace_folder(&scene, &folder, &files(&["top.png"])).unwrap_err();
        assert!(matches!(err, FsError::ForeignFile { .. }), "{err}");
        assert!(folder.join("sketch.png").is_file());
        assert_eq!(std::fs::read_dir(&scene).unwrap().count(), 2);
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
