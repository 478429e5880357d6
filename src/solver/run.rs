//! Load stepping over the pseudo-time: increments, cut-backs on failure, growth back toward
//! the nominal step, and the reports to the observer.

use super::augmented::solve_augmented;
use super::newton::Workspace;
use super::state::TrialState;
use crate::assembly::{Assembler, Timings};
use crate::contact::system::Config;
use crate::model::Model;
use crate::problem::Problem;
use crate::record::{
    ChangingPoint, ContactPointRecord, CrossingRecord, FailureKind, IncrementRecord, LogLevel, LogRecord,
    MonitorRecord, Observer, ObserverError, Outcome, RunInfo, StepView,
};
use crate::settings::{Predictor, SolverSettings, TangentCheckWhen};
use std::sync::atomic::{AtomicBool, Ordering};
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
    let names: Vec<String> = points
        .iter()
        .take(4)
        .map(|p| {
            let segs: Vec<String> = p
                .history
                .iter()
                .map(|d| format!("{:?}@{}", d.state, d.segment.map_or("-".into(), |s| s.to_string())))
                .collect();
            format!(
                "{} `{}` ({} changes from iteration {}, ξ = {:.3}: {})",
                p.slave_label,
                p.pair_name,
                p.changes,
                p.first_change,
                p.xi,
                segs.join(" → ")
            )
        })
        .collect();
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
    /// Elements that lost stability at some converged increment (see
    /// [`super::element_check`]): the first such increment, the most at one increment and
    /// the worst element seen.
    pub unstable_elements: Option<UnstableSummary>,
}

/// Where and how many elements lost stability in a run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct UnstableSummary {
    pub first_increment: usize,
    pub most: usize,
    pub worst_element: usize,
    pub worst_ratio: f64,
}

/// Check the elements at a converged increment; log a warning when the unstable set changes
/// in size (the first time too), and keep the run's account.
fn check_elements(
    model: &Model,
    asm: &Assembler,
    state: &TrialState,
    (increment, t): (usize, f64),
    last_count: &mut usize,
    summary: &mut RunSummary,
    obs: &mut dyn Observer,
) -> Result<(), ObserverError> {
    let Ok(unstable) = super::element_check::unstable_elements(model, asm, &state.u, &state.alphas) else {
        return Ok(());
    };
    if unstable.len() != *last_count && !unstable.is_empty() {
        let names: Vec<String> = unstable.iter().take(5).map(|e| e.element.to_string()).collect();
        log(
            obs,
            LogLevel::Warning,
            increment,
            t,
            format!(
                "{} elements have lost stability (their tangent is not positive definite in a deformation mode: an hourglass pattern; the answer may be wrong): elements {}{}; the element kind `q4-eas-safe` (the default) does not hourglass",
                unstable.len(),
                names.join(", "),
                if unstable.len() > 5 { ", …" } else { "" }
            ),
        )?;
    }
    *last_count = unstable.len();
    if let Some(worst) = unstable.first() {
        let s = summary.unstable_elements.get_or_insert(UnstableSummary {
            first_increment: increment,
            most: 0,
            worst_element: worst.element,
            worst_ratio: worst.ratio,
        });
        s.most = s.most.max(unstable.len());
        if worst.ratio < s.worst_ratio {
            (s.worst_element, s.worst_ratio) = (worst.element, worst.ratio);
        }
    }
    Ok(())
}

fn log(
    obs: &mut dyn Observer,
    level: LogLevel,
    increment: usize,
    t: f64,
    message: String,
) -> Result<(), ObserverError> {
    obs.log(&LogRecord {
        level,
        increment,
        t,
        message,
    })
}

/// Run the problem's load stepping to `stepping.end`, reporting to `obs`. `stop` is polled
/// between Newton iterations (Ctrl-C).
pub fn run(
    problem: &Problem,
    info: &RunInfo,
    obs: &mut dyn Observer,
    stop: &AtomicBool,
) -> Result<RunSummary, SolveError> {
    let started = Instant::now();
    let model = &problem.model;
    obs.start(model, info)?;
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

/// The finite-difference check of the tangent at a failing iterate, as one log line.
fn diagnose_tangent(
    model: &Model,
    asm: &mut Assembler,
    trial: &TrialState,
    t: f64,
    points: &[ChangingPoint],
) -> String {
    let nodes = super::tangent_check::nodes_of_points(model, &trial.contact, points);
    match super::tangent_check::check_tangent(model, asm, trial, t, &nodes) {
        Ok(c) => format!("at the last iterate: {}", c.summary()),
        Err(e) => format!("at the last iterate: tangent check not possible ({e})"),
    }
}

fn drive(
    model: &Model,
    settings: &SolverSettings,
    obs: &mut dyn Observer,
    stop: &AtomicBool,
    started: Instant,
) -> Result<RunSummary, SolveError> {
    let st = &settings.stepping;
    let nominal = st.end / st.increments.max(1) as f64;
    let mut asm = Assembler::new(model);
    asm.matrix.set_solver(settings.newton.linear_solver);
    let mut ws = Workspace::default();
    let mut committed = TrialState::new(model);
    let labels = crate::record::ContactLabels::new(model);
    let mut summary = RunSummary::default();
    let mut t = 0.0;
    let mut dt = nominal;
    let mut streak = 0;
    let mut fref = 0.0f64;
    let mut increment = 0;
    // the last converged increment `(uₙ − uₙ₋₁, Δtₙ)`, for the secant predictor
    let mut last_du = vec![0.0; model.dof_count()];
    let mut last_dt: Option<f64> = None;
    let mut recording = std::time::Duration::ZERO;
    let mut unstable_count = 0;
    while t < st.end * (1.0 - 1e-12) {
        increment += 1;
        let t_inc = Instant::now();
        let mut attempt = 0;
        let mut cuts = 0;
        let mut predict = st.predictor == Predictor::Secant && last_dt.is_some();
        // entries contact added to the tangent while a point crossed segments go again
        // when no longer written (they widen a banded factorisation)
        asm.shrink_unused_contact_pattern(model);
        let (state, conv, t_new) = loop {
            let mut t_new = (t + dt).min(st.end);
            if st.end - t_new < 1e-6 * dt {
                t_new = st.end;
            }
            let mut trial = committed.clone();
            trial.contact.reset_current();
            if let (true, Some(dt_last)) = (predict, last_dt) {
                let ratio = (t_new - t) / dt_last;
                for (d, e) in asm.dofs.eq.iter().enumerate() {
                    if e.is_some() {
                        trial.u[d] += ratio * last_du[d];
                    }
                }
            }
            let mut obs_err = None;
            let mut interrupted = false;
            let res = solve_augmented(
                model,
                &settings.newton,
                &mut asm,
                &mut trial,
                t_new,
                fref,
                &mut |rec| {
                    let handed = Instant::now();
                    if let Err(e) = obs.iteration(&rec) {
                        obs_err = Some(e);
                    }
                    recording += handed.elapsed();
                    interrupted = stop.load(Ordering::Relaxed);
                    obs_err.is_none() && !interrupted
                },
                (increment, attempt),
                predict,
                &mut ws,
            );
            if let Some(e) = obs_err {
                return Err(e.into());
            }
            if interrupted || stop.load(Ordering::Relaxed) {
                return Err(SolveError::Interrupted { increment, t });
            }
            match res {
                Ok(c) => break (trial, c, t_new),
                Err(f) if predict => {
                    // a predicted start that fails is retried from the converged state first
                    log(
                        obs,
                        LogLevel::Info,
                        increment,
                        t_new,
                        format!(
                            "increment {increment} at t = {t_new:.6}: {f} from the predicted start; \
                             retrying from the last converged state"
                        ),
                    )?;
                    predict = false;
                    attempt += 1;
                }
                Err(f) => {
                    // the step may not fall below nominal / 2^max_cutbacks, however it got there
                    let last = cuts >= st.max_cutbacks || dt * 0.5 < nominal * 0.5f64.powi(st.max_cutbacks as i32);
                    let check = match settings.newton.check_tangent {
                        TangentCheckWhen::Off => false,
                        TangentCheckWhen::OnFailure => last,
                        TangentCheckWhen::EveryFailedAttempt => true,
                    };
                    if check {
                        let points = ws.watch.report(&trial.contact, model, 8);
                        let message = diagnose_tangent(model, &mut asm, &trial, t_new, &points);
                        log(obs, LogLevel::Warning, increment, t_new, message)?;
                    }
                    if last {
                        return Err(SolveError::StepFailed {
                            increment,
                            t: t_new,
                            dt,
                            cutbacks: cuts,
                            reason: f.to_string(),
                            residuals: ws.residuals.clone(),
                            kind: f.kind(),
                            points: ws.watch.report(&trial.contact, model, 8),
                        });
                    }
                    log(
                        obs,
                        LogLevel::Warning,
                        increment,
                        t_new,
                        format!("increment {increment} at t = {t_new:.6}: {f}; cutting the step {dt:.3e} in half"),
                    )?;
                    dt *= 0.5;
                    attempt += 1;
                    cuts += 1;
                    summary.cutbacks += 1;
                    streak = 0;
                }
            }
        };
        for ((d, a), b) in last_du.iter_mut().zip(&state.u).zip(&committed.u) {
            *d = a - b;
        }
        last_dt = Some(t_new - t);
        committed = state;
        let t_prev = t;
        t = t_new;
        fref = fref.max(conv.reference);
        summary.newton_iterations += conv.iterations;
        summary.augmentations += conv.augmentations;
        let cfg = Config {
            model,
            u: &committed.u,
            t,
        };
        // records first: they compare the converged iterate with the previous increment
        let handed = Instant::now();
        let snapshots = committed.contact.snapshots(&cfg);
        let points: Vec<ContactPointRecord> = (snapshots.iter())
            .map(|p| ContactPointRecord::from_snapshot(&labels, p))
            .collect();
        let monitors = super::monitor::records(model, &asm, &committed.u, t, &snapshots);
        // committing the history is physics, not recording: kept out of the recording time
        let committing = Instant::now();
        let events = committed.contact.commit(&cfg);
        let commit_time = committing.elapsed();
        let crossings: Vec<CrossingRecord> = events.iter().map(CrossingRecord::from).collect();
        summary.crossings += crossings.len();
        let mut reaction_total = [0.0; 2];
        for &d in &asm.dofs.prescribed {
            reaction_total[d % 2] += asm.r_full[d];
        }
        let rec = IncrementRecord {
            increment,
            t,
            dt: t_new - t_prev,
            iterations: conv.iterations,
            cutbacks: cuts,
            converged: true,
            wall_time_s: t_inc.elapsed().as_secs_f64(),
            residuals: conv.residuals,
            monitor: monitors.first().cloned(),
            monitors,
            reaction_total,
        };
        summary.monitor = rec.monitor.clone();
        summary.monitors = rec.monitors.clone();
        obs.increment(
            &rec,
            &StepView {
                model,
                u: &committed.u,
                contact: &points,
                crossings: &crossings,
            },
        )?;
        recording += handed.elapsed().saturating_sub(commit_time);
        check_elements(
            model,
            &asm,
            &committed,
            (increment, t),
            &mut unstable_count,
            &mut summary,
            obs,
        )?;
        asm.update_hourglass_holds(model, &committed.u);
        summary.increments = increment;
        streak += 1;
        if streak >= st.grow_after && dt < nominal {
            dt = (dt * st.growth).min(nominal);
            streak = 0;
        }
    }
    summary.t = t;
    summary.wall_time_s = started.elapsed().as_secs_f64();
    summary.symbolic_factorizations = asm.matrix.symbolic_factorizations;
    summary.timings = asm.timings();
    summary.iterative = asm.matrix.iterative_stats();
    summary.ldlt = asm.matrix.ldlt_stats();
    summary.recording_s = recording.as_secs_f64();
    Ok(summary)
}
