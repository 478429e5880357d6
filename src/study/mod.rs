//! A library API for runs: a scene (built-in name or path) with `--set` overrides in, a typed
//! outcome out — completed, failed with a [`FailureKind`], or interrupted — with the figures
//! a sweep keeps (increments, Newton iterations, cut-backs, wall time, load reached) and the
//! small data its metrics need. The caller may ask for an MCAP recording and attach its own
//! observers. The sweep runner uses this, never the command line.

mod classify;
mod collect;
mod progress;

pub use crate::record::FailureKind;
pub use classify::{classify, FailureEvidence};
pub use collect::{Collector, ContactLoss, CrossingJump, RunData};
pub use progress::{ProgressLine, ProgressSink};

use crate::record::mcap::sink::{McapOptions, McapSink};
use crate::record::{Fanout, Observer};
use crate::scene::AnyProblem;
use crate::solver::SolveError;
use serde::{Deserialize, Serialize};
use std::io::BufWriter;
use std::path::{Path, PathBuf};
use std::sync::atomic::AtomicBool;
use std::time::Instant;

/// One run to make: a scene and its overrides.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Study {
    /// Built-in scene name or path to a scene TOML file.
    pub scene: String,
    /// `key.path=value` overrides, applied in order.
    pub sets: Vec<String>,
}

/// What the caller wants besides the outcome.
#[derive(Debug, Clone, Default)]
pub struct RunOptions {
    /// Record the run to this MCAP file (directories are created).
    pub mcap: Option<PathBuf>,
    /// Positions every N-th increment in the recording (0 or 1: every one).
    pub positions_every: usize,
    /// Threads of the run where its scene leaves `solver.threads` at 0 (0: all the cores
    /// this process may use); a sweep running runs side by side gives each its share.
    pub threads: usize,
}

/// How a run ended.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "status", rename_all = "lowercase")]
pub enum Status {
    Completed,
    Failed {
        kind: FailureKind,
        /// Increment that failed (0: before the first one) and its target pseudo-time.
        increment: usize,
        t: f64,
        message: String,
    },
    Interrupted {
        increment: usize,
        t: f64,
    },
}

impl Status {
    /// `completed`, `failed` or `interrupted`.
    pub fn name(&self) -> &'static str {
        match self {
            Status::Completed => "completed",
            Status::Failed { .. } => "failed",
            Status::Interrupted { .. } => "interrupted",
        }
    }
}

/// Summary figures of a run (also of a failed one: up to its last converged increment).
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct Figures {
    pub increments: usize,
    pub newton_iterations: usize,
    pub cutbacks: usize,
    pub crossings: usize,
    pub wall_time_s: f64,
    /// Last converged pseudo-time and the end of the stepping.
    pub t_reached: f64,
    pub t_end: f64,
    /// Degrees of freedom of the model (0 when it could not be built).
    pub dofs: usize,
    /// Transfer scheme of each contact pair.
    pub transfer: Vec<String>,
}

impl Figures {
    /// Fraction of the load path reached, `t_reached / t_end` in [0, 1].
    pub fn load_fraction(&self) -> f64 {
        if self.t_end > 0.0 {
            (self.t_reached / self.t_end).clamp(0.0, 1.0)
        } else {
            0.0
        }
    }
}

/// Everything a run returns.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct StudyOutcome {
    pub status: Status,
    pub figures: Figures,
    pub data: RunData,
}

/// The recording could not be created (the run was not started).
#[derive(Debug, thiserror::Error)]
pub enum StudyError {
    #[error("{path}: cannot create the recording: {message}\n  hint: check that the output folder is writable")]
    Recording { path: String, message: String },
}

fn create(path: &Path, positions_every: usize) -> Result<McapSink<BufWriter<std::fs::File>>, StudyError> {
    let err = |message: String| StudyError::Recording {
        path: path.display().to_string(),
        message,
    };
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).map_err(|e| err(e.to_string()))?;
    }
    let f = std::fs::File::create(path).map_err(|e| err(e.to_string()))?;
    let name = path.display().to_string();
    let opts = McapOptions {
        positions_every: positions_every.max(1),
        ..McapOptions::default()
    };
    McapSink::new(BufWriter::new(f), &name, opts).map_err(|e| err(e.to_string()))
}

impl Study {
    /// A study of `scene` with `sets`.
    pub fn new(scene: impl Into<String>, sets: Vec<String>) -> Study {
        Study {
            scene: scene.into(),
            sets,
        }
    }

    /// Check that the scene loads with its overrides (no run).
    pub fn check(&self) -> Result<(), crate::scene::SceneError> {
        crate::load_any_scene(&self.scene, &self.sets).map(|_| ())
    }

    /// Run the study. A scene that does not load is a [`FailureKind::BadInput`] outcome, a
    /// solver failure a classified one; `stop` interrupts the run (polled between Newton
    /// iterations). `observers` get every record too.
    pub fn run(
        &self,
        opts: &RunOptions,
        observers: &mut [&mut dyn Observer],
        stop: &AtomicBool,
    ) -> Result<StudyOutcome, StudyError> {
        let (src, problem) = match crate::load_any_scene(&self.scene, &self.sets) {
            Ok(x) => x,
            Err(e) => {
                return Ok(StudyOutcome {
                    status: Status::Failed {
                        kind: FailureKind::BadInput,
                        increment: 0,
                        t: 0.0,
                        message: e.to_string(),
                    },
                    figures: Figures::default(),
                    data: RunData::default(),
                })
            }
        };
        match problem {
            AnyProblem::Plane(p) => self.run_problem(&src, p, opts, observers, stop),
            AnyProblem::Solid(p) => self.run_problem(&src, p, opts, observers, stop),
        }
    }

    /// Run a loaded problem of either dimension, recorded as `opts` asks.
    fn run_problem<S: crate::model::Dim>(
        &self,
        src: &crate::scene::SceneSource,
        mut problem: crate::problem::Problem<S>,
        opts: &RunOptions,
        observers: &mut [&mut dyn Observer],
        stop: &AtomicBool,
    ) -> Result<StudyOutcome, StudyError> {
        if problem.settings.newton.threads == 0 {
            problem.settings.newton.threads = opts.threads;
        }
        let info = crate::run_info(src, &self.sets, &problem);
        let mut mcap = match &opts.mcap {
            Some(p) => Some(create(p, opts.positions_every)?),
            None => None,
        };
        let mut sinks: Vec<&mut dyn Observer> = Vec::new();
        if let Some(m) = mcap.as_mut() {
            sinks.push(m);
        }
        for o in observers.iter_mut() {
            sinks.push(&mut **o);
        }
        Ok(run_loaded(&problem, &info, &mut sinks, stop).outcome)
    }
}

/// A finished solve: its typed outcome (what sweeps and the service keep) and the solver's
/// own summary or error (the figures `contrail run` prints).
pub struct Finished {
    pub outcome: StudyOutcome,
    pub result: Result<crate::solver::RunSummary, SolveError>,
}

/// Solve a loaded problem, every record handed to `observers` and to the collector that
/// makes the outcome: the one runner behind [`Study::run`], `contrail run` and so the
/// service's workers (which run `contrail run`).
pub fn run_loaded<S: crate::model::Dim>(
    problem: &crate::problem::Problem<S>,
    info: &crate::record::RunInfo,
    observers: &mut [&mut dyn Observer],
    stop: &AtomicBool,
) -> Finished {
    let started = Instant::now();
    let mut collector = Collector::default();
    let mut sinks: Vec<&mut dyn Observer> = vec![&mut collector];
    for o in observers.iter_mut() {
        sinks.push(&mut **o);
    }
    let mut fan = Fanout { sinks };
    let result = crate::solver::run(problem, info, &mut fan, stop);
    drop(fan);
    let outcome = outcome_of(&result, collector, problem, info, started);
    Finished { outcome, result }
}

/// The typed outcome of a finished solve: its status (a failure classified from the error
/// and the collector's evidence), figures and data.
fn outcome_of<S: crate::model::Dim>(
    result: &Result<crate::solver::RunSummary, SolveError>,
    collector: Collector,
    problem: &crate::problem::Problem<S>,
    info: &crate::record::RunInfo,
    started: Instant,
) -> StudyOutcome {
    let mut figures = Figures {
        increments: collector.increments,
        newton_iterations: collector.newton_iterations,
        cutbacks: collector.cutbacks,
        crossings: collector.data.crossings.len(),
        wall_time_s: 0.0,
        t_reached: collector.last_t,
        t_end: problem.settings.stepping.end,
        dofs: problem.model.dof_count(),
        transfer: info.transfer.clone(),
    };
    let status = match result {
        Ok(s) => {
            figures.t_reached = s.t;
            Status::Completed
        }
        Err(e) => {
            let (increment, t) = match e {
                SolveError::StepFailed {
                    increment, t, cutbacks, ..
                } => {
                    figures.cutbacks += cutbacks;
                    (*increment, *t)
                }
                SolveError::Interrupted { increment, t } => (*increment, *t),
                SolveError::Observer(_) => (collector.increments + 1, collector.last_t),
            };
            match classify(e, &collector.evidence) {
                Some(kind) => Status::Failed {
                    kind,
                    increment,
                    t,
                    message: e.to_string(),
                },
                None => Status::Interrupted { increment, t },
            }
        }
    };
    figures.wall_time_s = started.elapsed().as_secs_f64();
    StudyOutcome {
        status,
        figures,
        data: collector.data,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bad_input_is_an_outcome_not_an_error() {
        let s = Study::new("no-such-scene", vec![]);
        let out = s.run(&RunOptions::default(), &mut [], &AtomicBool::new(false)).unwrap();
        assert!(matches!(
            out.status,
            Status::Failed {
                kind: FailureKind::BadInput,
                ..
            }
        ));
        let s = Study::new("crossing", vec!["contact.nope=1".into()]);
        assert!(s.check().is_err());
    }

    #[test]
    fn crossing_completes_with_its_crossings() {
        let s = Study::new("crossing", vec!["stepping.increments=40".into()]);
        let out = s.run(&RunOptions::default(), &mut [], &AtomicBool::new(false)).unwrap();
        assert_eq!(out.status, Status::Completed);
        assert_eq!(out.figures.increments, 40);
        assert_eq!(out.figures.load_fraction(), 1.0);
        assert_eq!(out.data.crossings.len(), 3);
        assert!(out.data.contact_lost.is_empty());
    }

    #[test]
    fn a_stopped_run_is_interrupted() {
        let s = Study::new("crossing", vec![]);
        let out = s.run(&RunOptions::default(), &mut [], &AtomicBool::new(true)).unwrap();
        assert!(matches!(out.status, Status::Interrupted { .. }));
    }
}
