//! Stage checkpoints on disk, so a run that fails halfway (a crashed bridge, an unreachable
//! model, a full disk) resumes after the last stage that finished.
//!
//! A checkpoint directory sits next to the output (`.<name>.checkpoints/`): the scene after
//! each finished stage (`stages/NNN.json`), the asset folders (content-addressed, written
//! once), the run log so far, and a fingerprint of the inputs (prompt, seed, backend) so a
//! checkpoint is never resumed for a different request.

use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use crate::agents::RunLog;
use crate::formats::sdf::asset_files;
use crate::scene::Scene;
use crate::state::SceneState;
use crate::util::fsx::write_atomic;

/// Where finished stages are saved and found again.
pub trait CheckpointStore {
    /// The scene saved after the stage `key`, if that stage already finished in an earlier run.
    fn load(&mut self, key: &str) -> Option<(SceneState, RunLog)>;
    /// Saves the scene after the stage `key` finished.
    fn save(&mut self, key: &str, scene: &SceneState, log: &RunLog);
}

/// No checkpoints (tests, in-memory builds).
#[derive(Debug, Default)]
pub struct NoCheckpoints;

impl CheckpointStore for NoCheckpoints {
    fn load(&mut self, _key: &str) -> Option<(SceneState, RunLog)> {
        None
    }
    fn save(&mut self, _key: &str, _scene: &SceneState, _log: &RunLog) {}
}

#[derive(Debug, Default, Serialize, Deserialize)]
struct Progress {
    fingerprint: String,
    /// Finished stage keys in order; entry `i` is saved as `stages/{i:03}.json`.
    finished: Vec<String>,
}

/// Checkpoints in a directory.
#[derive(Debug)]
pub struct DirCheckpoints {
    dir: PathBuf,
    progress: Progress,
    /// Keys loaded so far in this run (a resumed run replays the finished prefix).
    resumed: usize,
    /// Log events already saved (each stage file holds only the events its stage added).
    logged: usize,
    /// Room architecture written by this run (rooms change only in the layout stage).
    architecture_written: std::collections::BTreeSet<String>,
}

impl DirCheckpoints {
    /// The checkpoint directory for an output directory.
    pub fn dir_for(out: &Path) -> PathBuf {
        let name = out
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_else(|| "scene".into());
        out.with_file_name(format!(".{name}.checkpoints"))
    }

    /// Opens the checkpoints of `out` for a run with `fingerprint`. With `resume`, earlier
    /// progress with the same fingerprint is kept; otherwise it is discarded.
    pub fn open(out: &Path, fingerprint: &str, resume: bool) -> DirCheckpoints {
        let dir = Self::dir_for(out);
        let progress = std::fs::read_to_string(dir.join("progress.json"))
            .ok()
            .and_then(|t| serde_json::from_str::<Progress>(&t).ok())
            .filter(|p| resume && p.fingerprint == fingerprint);
        let progress = match progress {
            Some(p) => p,
            None => {
                let _ = std::fs::remove_dir_all(&dir);
                Progress {
                    fingerprint: fingerprint.to_string(),
                    finished: Vec::new(),
                }
            }
        };
        DirCheckpoints {
            dir,
            progress,
            resumed: 0,
            logged: 0,
            architecture_written: Default::default(),
        }
    }

    /// Stages finished in earlier runs.
    pub fn finished(&self) -> &[String] {
        &self.progress.finished
    }

    /// Removes the checkpoints (after a successful run).
    pub fn clear(self) {
        let _ = std::fs::remove_dir_all(&self.dir);
    }

    fn stage_file(&self, i: usize) -> PathBuf {
        self.dir.join(format!("stages/{i:03}.json"))
    }
}

#[derive(Serialize, Deserialize)]
struct Saved {
    scene: Scene,
    /// The log events this stage added (the log so far is every earlier stage's in order).
    log: RunLog,
}

impl CheckpointStore for DirCheckpoints {
    fn load(&mut self, key: &str) -> Option<(SceneState, RunLog)> {
        // Only the next finished stage in order can be resumed; anything else means the run
        // took another path and the rest of the checkpoints are stale.
        if self.progress.finished.get(self.resumed).map(String::as_str) != Some(key) {
            self.progress.finished.truncate(self.resumed);
            return None;
        }
        let read = |i: usize| -> Option<Saved> {
            let text = std::fs::read_to_string(self.stage_file(i)).ok()?;
            serde_json::from_str(&text).ok()
        };
        let saved = read(self.resumed)?;
        let mut log = RunLog::default();
        for i in 0..self.resumed {
            log.events.extend(read(i)?.log.events);
        }
        log.events.extend(saved.log.events);
        let mut state = SceneState::new(saved.scene);
        for (id, record) in &state.scene.assets.clone() {
            let asset_dir = self.dir.join(record.sdf.strip_suffix("/model.sdf")?);
            let asset = crate::formats::sdf_read::read_asset(&asset_dir, record).ok()?;
            state.assets.insert(id.clone(), asset);
        }
        self.resumed += 1;
        self.logged = log.events.len();
        tracing::info!("resumed stage {key} from {}", self.dir.display());
        Some((state, log))
    }

    fn save(&mut self, key: &str, scene: &SceneState, log: &RunLog) {
        let result = (|| -> Result<(), String> {
            for asset in scene.assets.values() {
                let rel = asset.scene_dir();
                let dir = self.dir.join(&rel);
                // Procedural assets are content-addressed: written once. Room architecture is
                // written by the layout stage (a room's walls can change while its id stays
                // there) and once more by a resumed run, never again after every stage.
                let architecture = !rel.starts_with("assets/");
                let written = if architecture {
                    key != "layout" && self.architecture_written.contains(&asset.id)
                } else {
                    dir.join("model.sdf").is_file()
                };
                if written {
                    continue;
                }
                if architecture {
                    self.architecture_written.insert(asset.id.clone());
                }
                for f in asset_files(asset) {
                    write_atomic(&dir.join(&f.name), &f.bytes).map_err(|e| e.to_string())?;
                }
            }
            let i = self.progress.finished.len();
            let saved = Saved {
                scene: scene.scene.clone(),
                log: RunLog {
                    events: log.events.get(self.logged..).unwrap_or_default().to_vec(),
                },
            };
            let text = serde_json::to_string(&saved).map_err(|e| e.to_string())?;
            write_atomic(&self.stage_file(i), text.as_bytes()).map_err(|e| e.to_string())?;
            self.progress.finished.push(key.to_string());
            self.resumed = self.progress.finished.len();
            self.logged = log.events.len();
            let p = serde_json::to_string_pretty(&self.progress).map_err(|e| e.to_string())?;
            write_atomic(&self.dir.join("progress.json"), p.as_bytes()).map_err(|e| e.to_string())
        })();
        if let Err(e) = result {
            // A checkpoint that cannot be written only costs the ability to resume.
            tracing::warn!("could not save checkpoint {key}: {e}");
        }
    }
}
