//! What the service knows of running runs beyond the catalogue: the latest progress and the
//! curve so far of each, the process to interrupt, and a broadcast of events (status
//! changes and progress) that the server-sent-event streams and the web page follow.

use contrail::study::ProgressLine;
use serde::Serialize;
use std::collections::HashMap;
use std::sync::Mutex;
use tokio::sync::broadcast;

/// One event of the stream.
#[derive(Debug, Clone, Serialize)]
pub struct Event {
    /// `status` (a run was queued, started or ended) or `progress` (an increment converged).
    pub event: &'static str,
    pub id: String,
    pub data: serde_json::Value,
}

/// A running run's state.
#[derive(Debug, Default, Clone)]
pub struct LiveRun {
    /// Process id of the local solver (None on Slurm or before it started).
    pub pid: Option<u32>,
    pub progress: Option<ProgressLine>,
    /// `[t, displacement, force]` of every converged increment so far.
    pub curve: Vec<[f64; 3]>,
    /// Indices into `curve` of increments with crossings.
    pub crossing_at: Vec<usize>,
    /// When the progress was last written to the catalogue.
    pub saved: Option<std::time::Instant>,
    /// A cancel was asked for (the solver is interrupted as soon as it runs).
    pub cancel: bool,
}

pub struct Live {
    runs: Mutex<HashMap<String, LiveRun>>,
    tx: broadcast::Sender<Event>,
}

impl Live {
    pub fn new() -> Live {
        Live {
            runs: Mutex::new(HashMap::new()),
            tx: broadcast::channel(4096).0,
        }
    }

    fn runs(&self) -> std::sync::MutexGuard<'_, HashMap<String, LiveRun>> {
        self.runs.lock().unwrap_or_else(|e| e.into_inner())
    }

    pub fn subscribe(&self) -> broadcast::Receiver<Event> {
        self.tx.subscribe()
    }

    /// Tell every listener (no listener is fine).
    pub fn send(&self, event: &'static str, id: &str, data: serde_json::Value) {
        let _ = self.tx.send(Event {
            event,
            id: id.to_string(),
            data,
        });
    }

    pub fn start(&self, id: &str, pid: Option<u32>) {
        self.runs().insert(
            id.to_string(),
            LiveRun {
                pid,
                ..LiveRun::default()
            },
        );
    }

    /// Set the process of a run; returns whether a cancel is pending.
    pub fn set_pid(&self, id: &str, pid: u32) -> bool {
        let mut runs = self.runs();
        let run = runs.entry(id.to_string()).or_default();
        run.pid = Some(pid);
        run.cancel
    }

    /// Mark a run for cancelling; returns its process if it has one (None: not live here).
    pub fn request_cancel(&self, id: &str) -> Option<Option<u32>> {
        let mut runs = self.runs();
        let run = runs.get_mut(id)?;
        run.cancel = true;
        Some(run.pid)
    }

    /// Processes of the runs solved here.
    pub fn pids(&self) -> Vec<u32> {
        self.runs().values().filter_map(|r| r.pid).collect()
    }

    pub fn end(&self, id: &str) -> Option<LiveRun> {
        self.runs().remove(id)
    }

    pub fn get(&self, id: &str) -> Option<LiveRun> {
        self.runs().get(id).cloned()
    }

    /// Take an increment line: keep it and its curve point, broadcast it, and say whether it
    /// is time to write the progress to the catalogue (at most twice a second per run).
    pub fn progress(&self, id: &str, line: &ProgressLine) -> bool {
        let save = {
            let mut runs = self.runs();
            let run = runs.entry(id.to_string()).or_default();
            if let ProgressLine::Increment {
                t,
                displacement,
                force,
                new_crossings,
                ..
            } = line
            {
                run.curve
                    .push([*t, displacement.unwrap_or(*t), force.unwrap_or(f64::NAN)]);
                if *new_crossings > 0 {
                    run.crossing_at.push(run.curve.len() - 1);
                }
            }
            run.progress = Some(line.clone());
            let due = run.saved.is_none_or(|s| s.elapsed().as_millis() >= 500);
            if due {
                run.saved = Some(std::time::Instant::now());
            }
            due
        };
        self.send("progress", id, serde_json::to_value(line).unwrap_or_default());
        save
    }
}
