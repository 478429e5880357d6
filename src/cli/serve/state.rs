//! The service's shared state: where the data lives, the catalogue, the live runs, the
//! backend that solves, the limits, and the signal that wakes idle workers.

use super::catalogue::Catalogue;
use super::live::Live;
use super::model::Recordings;
use std::path::PathBuf;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::{Condvar, Mutex};
use std::time::Duration;

/// Where runs are solved.
#[derive(Debug, Clone, PartialEq)]
pub enum Backend {
    /// Child processes of the service (`contrail run`), `workers` at a time.
    Local,
    /// One `sbatch` job per run on a cluster that shares the data folder.
    Slurm {
        /// Extra `sbatch` arguments (e.g. `--partition=debug`).
        sbatch_args: Vec<String>,
        /// How often the jobs are polled.
        poll: Duration,
    },
}

impl Backend {
    pub fn name(&self) -> &'static str {
        match self {
            Backend::Local => "local",
            Backend::Slurm { .. } => "slurm",
        }
    }
}

/// Size limits of what clients send.
#[derive(Debug, Clone)]
pub struct Limits {
    /// Request bodies (bytes).
    pub body_bytes: usize,
    /// A scene's TOML text (bytes).
    pub scene_bytes: usize,
    /// `--set` overrides of one run.
    pub sets: usize,
    /// Elements of all generated meshes of a scene.
    pub elements: usize,
    /// Runs of one sweep plan.
    pub sweep_runs: usize,
}

impl Default for Limits {
    fn default() -> Limits {
        Limits {
            body_bytes: 1 << 20,
            scene_bytes: 256 << 10,
            sets: 64,
            elements: 200_000,
            sweep_runs: 10_000,
        }
    }
}

pub struct Service {
    /// The data folder (catalogue, `runs/`, `scenes/`); solver processes run in it.
    pub data: PathBuf,
    pub catalogue: Catalogue,
    pub live: Live,
    pub backend: Backend,
    /// This binary: the solver processes are `EXE run ...`.
    pub exe: PathBuf,
    pub workers: usize,
    /// Threads of each run (`contrail run --threads`; Slurm's `--cpus-per-task`).
    pub threads_per_run: usize,
    pub token: Option<String>,
    pub limits: Limits,
    /// Recordings parsed for the model view (a small cache).
    pub recordings: Recordings,
    stopping: AtomicBool,
    work: (Mutex<u64>, Condvar),
}

impl Service {
    pub fn new(data: PathBuf, catalogue: Catalogue, backend: Backend, workers: usize) -> std::io::Result<Service> {
        Ok(Service {
            data,
            catalogue,
            live: Live::new(),
            backend,
            exe: std::env::current_exe()?,
            workers,
            threads_per_run: 1,
            token: None,
            limits: Limits::default(),
            recordings: Recordings::default(),
            stopping: AtomicBool::new(false),
            work: (Mutex::new(0), Condvar::new()),
        })
    }

    /// Wake the idle workers (a run was queued).
    pub fn notify_work(&self) {
        let mut n = self.work.0.lock().unwrap_or_else(|e| e.into_inner());
        *n += 1;
        self.work.1.notify_all();
    }

    /// Sleep until work may be there (or `timeout` passes).
    pub fn wait_for_work(&self, timeout: Duration) {
        let n = self.work.0.lock().unwrap_or_else(|e| e.into_inner());
        let seen = *n;
        let _ = self
            .work
            .1
            .wait_timeout_while(n, timeout, |n| *n == seen && !self.stopping());
    }

    pub fn stopping(&self) -> bool {
        self.stopping.load(Ordering::SeqCst)
    }

    pub fn stop(&self) {
        self.stopping.store(true, Ordering::SeqCst);
        self.notify_work();
    }

    /// The recording of a run.
    pub fn recording(&self, id: &str) -> PathBuf {
        self.data.join("runs").join(format!("{id}.mcap"))
    }
}
