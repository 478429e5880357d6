//! Load stepping over the pseudo-time: increments, cut-backs on failure, growth back toward
//! the nominal step, and the reports to the observer.

use super::stepping::{drive, log};
use crate::assembly::Timings;
use crate::problem::Problem;
use crate::record::{ChangingPoint, FailureKind, LogLevel, MonitorRecord, Observer, ObserverError, Outcome, RunInfo};
use std::sync::atomic::AtomicBool;
use std::time::Instant;

/// A run that could not finish. The observer has already been told (`finish` was called).
#[derive(Debug, thiserror::Error)]
pub enum SolveError {
    #[error(
        "increment {increment} failed at t = {t:.6} (step {dt:.3e}) after {cutbacks} cut-backs: {reason}; \
         residuals {}{}",
        compact(residuals),
        changing(points)
    )]
    StepFailed {
        increment: usize,
        t: f64,
        dt: f64,
        cutbacks: usize,
        reason: String,
        residuals: Vec<f64>,
        kind: FailureKind,
        /// Contact points that changed state or segment in the last attempt.
        points: Vec<ChangingPoint>,
    },
    #[error("interrupted during increment {increment} (last converged t = {t:.6})")]
    Interrupted { increment: usize, t: f64 },
    #[error("recording failed: {0}")]
    Observer(#[from] ObserverError),
}

/// The last residuals of an attempt, 3 significant digits, at most 8 of them.
fn compact(residuals: &[f64]) -> String {
    let skip = residuals.len().saturating_sub(8);
    let tail: Vec<String> = residuals[skip..].iter().map(|r| format!("{r:.2e}")).collect();
    format!("{}[{}]", if skip > 0 { "… " } else { "" }, tail.join(", "))
}

/// The contact points that kept changing, one short phrase each.
fn changing(points: &[ChangingPoint]) -> String {
    if points.is_empty() {
        return String::new();
    }
    let names: Vec<String> = points.iter().take(4).map(ChangingPoint::describe).collect();
    format!("; changing contact points: {}", names.join("; "))
}

/// Figures of a completed run.
#[derive(Debug, Clone, Default)]
pub struct RunSummary {
    pub increments: usize,
    pub newton_iterations: usize,
    pub cutbacks: usize,
    pub crossings: usize,
    /// Multiplier updates of augmented-Lagrangian pairs over the run (each one more solve of
    /// its increment).
    pub augmentations: usize,
    pub wall_time_s: f64,
    pub t: f64,
    /// The first monitor at the last converged increment.
    pub monitor: Option<MonitorRecord>,
    /// All monitors at the last converged increment, in scene order.
    pub monitors: Vec<MonitorRecord>,
    pub symbolic_factorizations: usize,
    /// Where the time of the Newton iterations went.
    pub timings: Timings,
    /// Time spent handing records to the observer (serialising, writing, viewing).
    pub recording_s: f64,
    /// Counts of the iterative linear solves (all zero when only direct LUs were used).
    pub iterative: crate::linalg::iterative::IterativeStats,
    /// Counts of the symmetric (`LDLᵀ`) factorisations (all zero when none was made).
    pub ldlt: crate::linalg::ldlt::LdltStats,
    /// Counts of the solves preconditioned by an earlier tangent's `LDLᵀ`.
    pub lagged: crate::linalg::lagged::LaggedStats,
    /// Elements that lost stability at some converged increment (see
    /// [`super::element_check`]): the first such increment, the most at one increment and
    /// the worst element seen.
    pub unstable_elements: Option<UnstableSummary>,
    /// Where the tangent first lost positive definiteness (a limit or bifurcation point
    /// passed: [`super::stability`]).
    pub instability: Option<super::stability::Instability>,
    /// The deepest penetration of the run relative to the local element size, when some
    /// converged increment exceeded [`super::penetration::DEEP_PENETRATION`].
    pub deep_penetration: Option<super::penetration::Penetration>,
    /// Crossings at which the transfer scheme changed the friction history (the trial
    /// traction after the crossing differs from the one carried on the old segment's
    /// extension by more than [`HISTORY_JUMP`] of the larger): the force history then carries
    /// the scheme's error (the straightforward transfer's, seed Fig. 4). In 3D: crossings at
    /// which the history could not be carried onto the new facet and was lost.
    pub history_jumps: usize,
    /// Converged increments with contact points left on an extension of their segment.
    pub on_extension: usize,
    /// Line searches that found no decrease of the merit function (their shortest step was
    /// taken), over the run's converged increments.
    pub line_search_failures: usize,
    /// Corrections shifted by the pseudo-transient continuation after a failed line search,
    /// and the work of its drag, over the run's converged increments
    /// ([`super::newton::Converged::stabilised`]).
    pub stabilised_corrections: usize,
    pub stabilisation_work: f64,
    /// Iterations that reached a new active set and so extended the iteration limit
    /// (a moving contact front), over the run's converged increments.
    pub front_iterations: usize,
    /// The worst equilibrium imbalance of a converged increment, `max_b |F_b| / F_ref`
    /// ([`super::equilibrium`]); `None` before the first increment.
    pub equilibrium: Option<f64>,
    /// Converged increments at which the elements' stability check could not be evaluated
    /// (an element's tangent failed: logged at the first).
    pub element_check_errors: usize,
}

/// The relative change of the trial traction at a crossing above which the crossing is
/// counted as a jump of the friction history ([`RunSummary::history_jumps`]). Continuous,
/// path-length and spatial transfer keep it below 1e-6 on the crossing benchmark
/// (`tests/crossing.rs`); straightforward transfer changes it by the order of itself.
pub const HISTORY_JUMP: f64 = 0.05;

/// Where and how many elements lost stability in a run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct UnstableSummary {
    pub first_increment: usize,
    pub most: usize,
    pub worst_element: usize,
    pub worst_ratio: f64,
}

/// Run the problem's load stepping to `stepping.end`, reporting to `obs`. `stop` is polled
/// between Newton iterations (Ctrl-C).
pub fn run<S: crate::model::Dim>(
    problem: &Problem<S>,
    info: &RunInfo,
    obs: &mut dyn Observer,
    stop: &AtomicBool,
) -> Result<RunSummary, SolveError> {
    let started = Instant::now();
    let model = &problem.model;
    obs.start(model.view(), info)?;
    for note in &model.notes {
        log(obs, LogLevel::Warning, 0, 0.0, note.clone())?;
    }
    let result = drive(model, &problem.settings, obs, stop, started);
    let outcome = match &result {
        Ok(s) => Outcome::Completed {
            increments: s.increments,
            t: s.t,
        },
        Err(SolveError::StepFailed {
            increment,
            t,
            reason,
            residuals,
            kind,
            points,
            ..
        }) => Outcome::Failed {
            increment: *increment,
            t: *t,
            reason: reason.clone(),
            residuals: residuals.clone(),
            kind: *kind,
            points: points.clone(),
        },
        Err(SolveError::Interrupted { increment, t }) => Outcome::Interrupted {
            increment: *increment,
            t: *t,
        },
        Err(SolveError::Observer(e)) => Outcome::Failed {
            increment: 0,
            t: 0.0,
            reason: format!("recording failed: {e}"),
            residuals: vec![],
            kind: FailureKind::Recording,
            points: vec![],
        },
    };
    if let Err(e) = &result {
        let (increment, t) = match &outcome {
            Outcome::Failed { increment, t, .. } | Outcome::Interrupted { increment, t } => (*increment, *t),
            Outcome::Completed { increments, t } => (*increments, *t),
        };
        let _ = log(obs, LogLevel::Error, increment, t, e.to_string());
    }
    let fin = obs.finish(&outcome);
    let summary = result?;
    fin?;
    Ok(summary)
}
