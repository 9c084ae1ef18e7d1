//! A pool of long-lived Drake bridge processes, so independent physics requests (settling one
//! supporting entity, simulating one room) run in parallel.
//!
//! Workers start lazily, on first use, each in its own thread. Requests that name a
//! `directives` file are routed back to the worker that last served that file's content (its
//! plant cache then skips re-parsing). A worker that dies mid-request is restarted and the
//! request retried once, by [`Bridge::request`]; the pool only adds the parallelism.
//! The pool does not decide what to ask: `settle`, `projection` and `eval` build the requests.

use std::collections::{BTreeMap, VecDeque};
use std::path::Path;
use std::sync::Mutex;
use std::sync::atomic::{AtomicU32, Ordering};

use serde_json::Value;

use super::bridge::{Bridge, BridgeConfig, BridgeError, decode_reply, encode_args};
use super::protocol::Op;

/// One request for [`BridgePool::run_all`]: operation name and arguments.
#[derive(Debug, Clone)]
pub struct Job {
    /// Bridge operation, e.g. `settle`.
    pub op: String,
    /// Its arguments.
    pub args: Value,
}

impl Job {
    /// A job for operation `O` with its arguments.
    pub fn of<O: Op>(args: &O::Args) -> Result<Job, BridgeError> {
        Ok(Job {
            op: O::NAME.to_string(),
            args: encode_args::<O>(args)?,
        })
    }
}

/// N bridge workers (default: one per core).
pub struct BridgePool {
    config: BridgeConfig,
    workers: Vec<Mutex<Option<Bridge>>>,
    /// Last known process id per worker (0 = none), readable while the worker is busy.
    pids: Vec<AtomicU32>,
    /// Content hash of a directives file -> worker that last loaded it.
    affinity: Mutex<BTreeMap<[u8; 32], usize>>,
}

/// Number of workers when nothing says otherwise: `SCENESMITH_BRIDGE_WORKERS`, else the cores.
pub fn default_workers() -> usize {
    std::env::var("SCENESMITH_BRIDGE_WORKERS")
        .ok()
        .and_then(|v| v.parse::<usize>().ok())
        .filter(|n| *n > 0)
        .unwrap_or_else(|| {
            std::thread::available_parallelism()
                .map(|n| n.get())
                .unwrap_or(2)
        })
        .min(16)
}

/// Keeps numeric libraries single-threaded inside each worker: the pool is the parallelism,
/// and BLAS threads on top of it oversubscribe the cores (and make `fork` in the projection's
/// wall-clock guard unsafe).
fn single_threaded(mut config: BridgeConfig) -> BridgeConfig {
    for key in ["OMP_NUM_THREADS", "OPENBLAS_NUM_THREADS", "MKL_NUM_THREADS"] {
        if !config.env.iter().any(|(k, _)| k == key) {
            config.env.push((key.to_string(), "1".to_string()));
        }
    }
    config
}

fn directives_key(args: &Value) -> Option<[u8; 32]> {
    let path = args.get("directives")?.as_str()?;
    let bytes = std::fs::read(Path::new(path)).ok()?;
    let mut h = blake3::Hasher::new();
    h.update(path.as_bytes());
    h.update(&bytes);
    Some(*h.finalize().as_bytes())
}

impl BridgePool {
    /// A pool of `size` workers (at least one) started from `config` when first needed.
    pub fn new(config: BridgeConfig, size: usize) -> BridgePool {
        BridgePool {
            config: single_threaded(config),
            workers: (0..size.max(1)).map(|_| Mutex::new(None)).collect(),
            pids: (0..size.max(1)).map(|_| AtomicU32::new(0)).collect(),
            affinity: Mutex::new(BTreeMap::new()),
        }
    }

    /// A pool configured from the environment with [`default_workers`] workers.
    pub fn from_env() -> BridgePool {
        Self::new(BridgeConfig::from_env(), default_workers())
    }

    /// Number of workers.
    pub fn size(&self) -> usize {
        self.workers.len()
    }

    /// Starts every worker now (in parallel) instead of on first use; fails with the first
    /// start-up error (Python or pydrake missing).
    pub fn start_all(&self) -> Result<(), BridgeError> {
        let results: Vec<Result<(), BridgeError>> = std::thread::scope(|s| {
            let handles: Vec<_> = (0..self.size())
                .map(|i| s.spawn(move || self.with_worker(i, |_| Ok(()))))
                .collect();
            handles
                .into_iter()
                .map(|h| {
                    h.join()
                        .unwrap_or_else(|_| Err(BridgeError::Protocol("worker panicked".into())))
                })
                .collect()
        });
        results.into_iter().collect()
    }

    /// Runs `f` on worker `i`, starting it if needed.
    fn with_worker<T>(
        &self,
        i: usize,
        f: impl FnOnce(&mut Bridge) -> Result<T, BridgeError>,
    ) -> Result<T, BridgeError> {
        let Some(slot) = self.workers.get(i) else {
            return Err(BridgeError::Protocol(format!("no worker {i}")));
        };
        let mut guard = slot
            .lock()
            .map_err(|_| BridgeError::Protocol("a bridge worker lock was poisoned".into()))?;
        if guard.is_none() {
            *guard = Some(self.start_worker(i)?);
        }
        match guard.as_mut() {
            Some(bridge) => {
                let out = f(bridge);
                self.note_pid(i, bridge);
                out
            }
            None => Err(BridgeError::Protocol("bridge worker missing".into())),
        }
    }

    fn start_worker(&self, i: usize) -> Result<Bridge, BridgeError> {
        let bridge = Bridge::start(self.config.clone())?;
        self.note_pid(i, &bridge);
        Ok(bridge)
    }

    fn note_pid(&self, i: usize, bridge: &Bridge) {
        if let Some(slot) = self.pids.get(i) {
            slot.store(bridge.pid().unwrap_or(0), Ordering::SeqCst);
        }
    }

    fn preferred_worker(&self, key: Option<&[u8; 32]>) -> Option<usize> {
        let key = key?;
        self.affinity.lock().ok()?.get(key).copied()
    }

    fn remember(&self, key: Option<[u8; 32]>, worker: usize) {
        if let (Some(k), Ok(mut map)) = (key, self.affinity.lock()) {
            map.insert(k, worker);
        }
    }

    /// Runs operation `O` on a worker (see [`BridgePool::request`] for which one).
    pub fn call<O: Op>(&self, args: &O::Args) -> Result<O::Reply, BridgeError> {
        let result = self.request(O::NAME, encode_args::<O>(args)?)?;
        decode_reply::<O>(result)
    }

    /// Runs operation `O` once per argument set, in parallel over the workers; replies come
    /// back in order.
    pub fn call_all<O: Op>(&self, args: &[O::Args]) -> Vec<Result<O::Reply, BridgeError>> {
        let jobs: Result<Vec<Job>, BridgeError> = args.iter().map(Job::of::<O>).collect();
        match jobs {
            Ok(jobs) => self
                .run_all(jobs)
                .into_iter()
                .map(|r| r.and_then(decode_reply::<O>))
                .collect(),
            Err(e) => {
                let msg = e.to_string();
                args.iter()
                    .map(|_| Err(BridgeError::Protocol(msg.clone())))
                    .collect()
            }
        }
    }

    /// Sends one JSON request to a worker (the one that last saw the same directives if it is
    /// free, else the first free one, else waits for the preferred one).
    pub fn request(&self, op: &str, args: Value) -> Result<Value, BridgeError> {
        let key = directives_key(&args);
        let preferred = self.preferred_worker(key.as_ref()).unwrap_or(0);
        let order: Vec<usize> = std::iter::once(preferred)
            .chain((0..self.size()).filter(|i| *i != preferred))
            .collect();
        for &i in &order {
            if let Ok(mut guard) = self.workers[i].try_lock() {
                if guard.is_none() {
                    *guard = Some(self.start_worker(i)?);
                }
                if let Some(bridge) = guard.as_mut() {
                    let out = bridge.request(op, args);
                    self.note_pid(i, bridge);
                    self.remember(key, i);
                    return out;
                }
            }
        }
        let out = self.with_worker(preferred, |b| b.request(op, args));
        self.remember(key, preferred);
        out
    }

    /// Runs every job, in parallel over the workers; results come back in job order. Jobs that
    /// name the same directives content go to the same worker when possible.
    pub fn run_all(&self, jobs: Vec<Job>) -> Vec<Result<Value, BridgeError>> {
        let n = jobs.len();
        if n == 0 {
            return Vec::new();
        }
        let keys: Vec<Option<[u8; 32]>> = jobs.iter().map(|j| directives_key(&j.args)).collect();
        let queue: Mutex<VecDeque<(usize, Job)>> =
            Mutex::new(jobs.into_iter().enumerate().collect());
        let results: Mutex<Vec<Option<Result<Value, BridgeError>>>> =
            Mutex::new((0..n).map(|_| None).collect());
        let threads = self.size().min(n);
        std::thread::scope(|s| {
            for w in 0..threads {
                let (queue, results, keys) = (&queue, &results, &keys);
                s.spawn(move || {
                    loop {
                        let next = {
                            let Ok(mut q) = queue.lock() else { return };
                            // Prefer a job this worker has the plant for; else the oldest job
                            // no other worker has seen.
                            let pick = q
                                .iter()
                                .position(|(i, _)| {
                                    self.preferred_worker(keys[*i].as_ref()) == Some(w)
                                })
                                .or_else(|| {
                                    q.iter().position(|(i, _)| {
                                        self.preferred_worker(keys[*i].as_ref()).is_none()
                                    })
                                })
                                .or(if q.is_empty() { None } else { Some(0) });
                            pick.and_then(|p| q.remove(p))
                        };
                        let Some((i, job)) = next else { return };
                        let out = self.with_worker(w, |b| b.request(&job.op, job.args));
                        self.remember(keys[i], w);
                        if let Ok(mut r) = results.lock() {
                            r[i] = Some(out);
                        }
                    }
                });
            }
        });
        results
            .into_inner()
            .unwrap_or_default()
            .into_iter()
            .map(|r| {
                r.unwrap_or_else(|| Err(BridgeError::Protocol("a pool job was not run".into())))
            })
            .collect()
    }

    /// Total restarts of crashed workers so far.
    pub fn restarts(&self) -> u32 {
        self.workers
            .iter()
            .filter_map(|w| w.lock().ok().and_then(|g| g.as_ref().map(Bridge::restarts)))
            .sum()
    }

    /// Last known OS process id of each worker (`None` before it started); readable while
    /// the worker is busy (for tests and diagnostics).
    pub fn pids(&self) -> Vec<Option<u32>> {
        self.pids
            .iter()
            .map(|p| Some(p.load(Ordering::SeqCst)).filter(|v| *v != 0))
            .collect()
    }

    /// The Drake version the workers run, once one has started.
    pub fn drake_version(&self) -> Result<String, BridgeError> {
        self.with_worker(0, |b| Ok(b.hello().drake.clone()))
    }
}
