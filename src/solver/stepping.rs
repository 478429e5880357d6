//! The load stepping over the pseudo-time, step by step: converge an increment (attempts
//! from a predicted or converged start, cut-backs on failure), commit it and hand its
//! records to the observer, grow the step back toward the nominal one.

use super::augmented::solve_augmented;
use super::equilibrium::{Imbalance, EQUILIBRIUM_TOLERANCE};
use super::faceted_node::faceted_node;
use super::friction_limit::friction_limit;
use super::newton::{Converged, IncrementTarget, NewtonFailure, Workspace};
use super::run::{RunSummary, SolveError, UnstableSummary};
use super::state::TrialState;
use crate::assembly::Assembler;
use crate::contact::system::Config;
use crate::contact3d::system::SurfaceConfig;
use crate::model::{Dim, Model};
use crate::record::surface_contact::SurfacePointRecord;
use crate::record::{
    ChangingPoint, ContactPointRecord, CrossingRecord, FailureKind, IncrementRecord, LogLevel, LogRecord,
    MonitorRecord, Observer, ObserverError, StepView,
};
use crate::settings::{Predictor, SolverSettings, TangentCheckWhen};
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Instant;

#[path = "stepping_commit.rs"]
mod commit;

/// Hand one log line to the observer.
pub(super) fn log(
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

/// The finite-difference check of the tangent at a failing iterate, as one log line.
fn diagnose_tangent<S: Dim>(
    model: &Model<S>,
    asm: &mut Assembler<S>,
    trial: &TrialState,
    t: f64,
    points: &[ChangingPoint],
) -> String {
    let nodes = super::tangent_check::nodes_of_points(model.plane(), S::solid(model), &trial.contact, points);
    match super::tangent_check::check_tangent(model, asm, trial, t, &nodes) {
        Ok(c) => format!("at the last iterate: {}", c.summary()),
        Err(e) => format!("at the last iterate: tangent check not possible ({e})"),
    }
}

/// Drive the load stepping: each increment is converged (cut back on failure), committed
/// and reported, and the step grows back toward the nominal one.
pub(super) fn drive<S: Dim>(
    model: &Model<S>,
    settings: &SolverSettings,
    obs: &mut dyn Observer,
    stop: &AtomicBool,
    started: Instant,
) -> Result<RunSummary, SolveError> {
    let mut s = Stepping::new(model, settings);
    let end = settings.stepping.end;
    while s.t < end * (1.0 - 1e-12) {
        s.increment += 1;
        let t_inc = Instant::now();
        // entries contact added to the tangent while a point crossed segments go again
        // when no longer written (they widen a banded factorisation)
        s.asm.shrink_unused_contact_pattern(model);
        let done = s.converge_increment(obs, stop)?;
        s.commit(done, t_inc, obs)?;
        s.grow_step();
    }
    Ok(s.finish(started))
}

/// An increment Newton converged, before it is committed.
struct ConvergedIncrement {
    state: TrialState,
    conv: Converged,
    t_new: f64,
    cutbacks: usize,
    /// Closed points converged on an extension of their segment.
    on_extension: usize,
}

/// What the load stepping carries from one increment to the next.
struct Stepping<'a, S: Dim> {
    model: &'a Model<S>,
    settings: &'a SolverSettings,
    asm: Assembler<S>,
    ws: Workspace,
    /// The last converged state.
    committed: TrialState,
    labels: crate::record::ContactLabels,
    summary: RunSummary,
    increment: usize,
    t: f64,
    dt: f64,
    nominal: f64,
    /// Increments converged since the last cut-back or growth.
    streak: usize,
    /// The largest reference force of the run so far.
    fref: f64,
    /// The last converged increment `(uₙ − uₙ₋₁, Δtₙ)`, for the secant predictor.
    last_du: Vec<f64>,
    last_dt: Option<f64>,
    /// Time spent handing records to the observer.
    recording: std::time::Duration,
    /// Unstable elements at the last converged increment.
    unstable_count: usize,
    /// The tangent's definiteness over the converged increments.
    tangent: super::stability::TangentWatch,
    /// The smallest element edge at each node (the scale of a penetration).
    node_sizes: Vec<f64>,
}

impl<'a, S: Dim> Stepping<'a, S> {
    fn new(model: &'a Model<S>, settings: &'a SolverSettings) -> Self {
        let st = &settings.stepping;
        let nominal = st.end / st.increments.max(1) as f64;
        let mut asm = Assembler::new(model);
        asm.linear.set_solver(settings.newton.linear_solver);
        let threads = crate::threads::resolve(settings.newton.threads);
        asm.set_threads(threads, model.elements.len());
        asm.linear.set_threads(threads);
        let mut committed = TrialState::new(model);
        let penalty = settings.newton.active_set == crate::settings::ActiveSet::Penalty;
        committed.contact.set_penalty_weights(model.plane(), penalty);
        let start = Config {
            model: model.plane(),
            u: &committed.u,
            t: 0.0,
        };
        committed.contact.start_from_initial_configuration(&start);
        if let Some(solid) = S::solid(model) {
            let start = SurfaceConfig {
                model: solid,
                u: &committed.u,
                t: 0.0,
            };
            committed.contact.surface.set_penalty_weights(solid, penalty);
            committed.contact.surface.start_from_initial_configuration(&start);
        }
        Stepping {
            model,
            settings,
            asm,
            ws: Workspace::default(),
            committed,
            labels: crate::record::ContactLabels::new(model.plane()),
            summary: RunSummary::default(),
            increment: 0,
            t: 0.0,
            dt: nominal,
            nominal,
            streak: 0,
            fref: 0.0,
            last_du: vec![0.0; model.dof_count()],
            last_dt: None,
            recording: std::time::Duration::ZERO,
            unstable_count: 0,
            tangent: Default::default(),
            node_sizes: match S::solid(model) {
                Some(solid) => super::penetration::solid_node_sizes(solid),
                None => super::penetration::node_sizes(model.plane()),
            },
        }
    }

    /// The end time of the next attempt (the end itself when it is within 1e-6 Δt).
    fn next_time(&self) -> f64 {
        let end = self.settings.stepping.end;
        let t_new = (self.t + self.dt).min(end);
        if end - t_new < 1e-6 * self.dt {
            end
        } else {
            t_new
        }
    }

    /// The start of an attempt: the converged state, extrapolated along the last increment
    /// when `predict` (secant predictor).
    fn trial_start(&self, t_new: f64, predict: bool) -> TrialState {
        let mut trial = self.committed.clone();
        trial.contact.reset_current();
        if let (true, Some(dt_last)) = (predict, self.last_dt) {
            let ratio = (t_new - self.t) / dt_last;
            for (d, e) in self.asm.dofs.eq.iter().enumerate() {
                if e.is_some() {
                    trial.u[d] += ratio * self.last_du[d];
                }
            }
        }
        trial
    }

    /// Attempts at the increment until one converges: a failed predicted start is retried
    /// from the converged state at the same step, any other failure cuts the step in half
    /// (or ends the run).
    fn converge_increment(
        &mut self,
        obs: &mut dyn Observer,
        stop: &AtomicBool,
    ) -> Result<ConvergedIncrement, SolveError> {
        let st = &self.settings.stepping;
        let mut predict = st.predictor == Predictor::Secant && self.last_dt.is_some();
        let (mut attempt, mut cutbacks) = (0, 0);
        loop {
            let t_new = self.next_time();
            let mut trial = self.trial_start(t_new, predict);
            let target = IncrementTarget {
                t: t_new,
                reference_floor: self.fref,
                increment: self.increment,
                attempt,
                predicted: predict,
            };
            if let Some(f) = super::search_reach::rigid_step_beyond_search(self.model.plane(), self.t, t_new) {
                self.cut_back(f, &trial, t_new, cutbacks, obs)?;
                cutbacks += 1;
                attempt += 1;
                continue;
            }
            let outcome = self.attempt(&mut trial, target, obs, stop)?;
            if outcome.is_err() {
                self.tangent.failed_attempt(self.ws.inertia);
            }
            match outcome {
                Ok(conv) => {
                    return Ok(ConvergedIncrement {
                        on_extension: trial.contact.on_extensions(),
                        state: trial,
                        conv,
                        t_new,
                        cutbacks,
                    })
                }
                Err(f) if predict => {
                    let message = format!(
                        "increment {} at t = {t_new:.6}: {f} from the predicted start; retrying from the last converged state",
                        self.increment
                    );
                    log(obs, LogLevel::Info, self.increment, t_new, message)?;
                    predict = false;
                }
                Err(f) => {
                    self.cut_back(f, &trial, t_new, cutbacks, obs)?;
                    cutbacks += 1;
                }
            }
            attempt += 1;
        }
    }

    /// One attempt (Newton, with the multiplier updates of augmented pairs), its iterations
    /// handed to `obs`; a recording failure or an interrupt ends the run.
    fn attempt(
        &mut self,
        trial: &mut TrialState,
        target: IncrementTarget,
        obs: &mut dyn Observer,
        stop: &AtomicBool,
    ) -> Result<Result<Converged, NewtonFailure>, SolveError> {
        let mut obs_err = None;
        let mut interrupted = false;
        let recording = &mut self.recording;
        let mut hand_over = |rec| {
            let handed = Instant::now();
            if let Err(e) = obs.iteration(&rec) {
                obs_err = Some(e);
            }
            *recording += handed.elapsed();
            interrupted = stop.load(Ordering::Relaxed);
            obs_err.is_none() && !interrupted
        };
        let newton = &self.settings.newton;
        let res = solve_augmented(
            self.model,
            newton,
            &mut self.asm,
            trial,
            target,
            &mut hand_over,
            &mut self.ws,
        );
        if let Some(e) = obs_err {
            return Err(e.into());
        }
        if interrupted || stop.load(Ordering::Relaxed) {
            return Err(SolveError::Interrupted {
                increment: self.increment,
                t: self.t,
            });
        }
        Ok(res)
    }

    /// A failed attempt: diagnose the tangent when asked to, then halve the step — or fail
    /// the run when the step may not be cut further (never below nominal / 2^max_cutbacks,
    /// however it got there).
    fn cut_back(
        &mut self,
        f: NewtonFailure,
        trial: &TrialState,
        t_new: f64,
        cutbacks: usize,
        obs: &mut dyn Observer,
    ) -> Result<(), SolveError> {
        let st = &self.settings.stepping;
        let (model, increment, dt) = (self.model, self.increment, self.dt);
        let last = cutbacks >= st.max_cutbacks || dt * 0.5 < self.nominal * 0.5f64.powi(st.max_cutbacks as i32);
        let check = match self.settings.newton.check_tangent {
            TangentCheckWhen::Off => false,
            TangentCheckWhen::OnFailure => last,
            TangentCheckWhen::EveryFailedAttempt => true,
        };
        if check {
            let points = self.ws.watch.report(&trial.contact, model.plane(), S::solid(model), 8);
            let message = diagnose_tangent(model, &mut self.asm, trial, t_new, &points);
            log(obs, LogLevel::Warning, increment, t_new, message)?;
        }
        if last {
            let points = self.ws.watch.report(&trial.contact, model.plane(), S::solid(model), 8);
            return Err(SolveError::StepFailed {
                increment,
                t: t_new,
                dt,
                cutbacks,
                reason: self.failure_reason(&f, &points),
                residuals: self.ws.residuals.clone(),
                kind: f.kind(),
                points,
            });
        }
        let message = format!("increment {increment} at t = {t_new:.6}: {f}; cutting the step {dt:.3e} in half");
        log(obs, LogLevel::Warning, increment, t_new, message)?;
        self.dt *= 0.5;
        self.summary.cutbacks += 1;
        self.streak = 0;
        Ok(())
    }

    /// What the run's failure says: the Newton failure, and when the increment may have no
    /// solution at all because a body is at its friction limit ([`friction_limit`]) or a
    /// changing point sits at a node of a faceted master ([`faceted_node`]), that diagnosis.
    fn failure_reason(&self, f: &NewtonFailure, points: &[ChangingPoint]) -> String {
        let may_lack_a_solution = matches!(
            f.kind(),
            FailureKind::NoConvergence
                | FailureKind::ActiveSetCycle
                | FailureKind::Diverged
                | FailureKind::LinearSolver
                | FailureKind::NonFinite
        );
        if !may_lack_a_solution {
            return f.to_string();
        }
        let plane = self.model.plane();
        let hints: Vec<String> = [
            friction_limit(plane, &self.committed.contact, self.t),
            faceted_node(plane, points),
            self.tangent.failure_hint(),
        ]
        .into_iter()
        .flatten()
        .collect();
        std::iter::once(f.to_string())
            .chain(hints)
            .collect::<Vec<_>>()
            .join("; ")
    }

    /// After `grow_after` converged increments in a row, the step grows toward the nominal.
    fn grow_step(&mut self) {
        let st = &self.settings.stepping;
        self.streak += 1;
        if self.streak >= st.grow_after && self.dt < self.nominal {
            self.dt = (self.dt * st.growth).min(self.nominal);
            self.streak = 0;
        }
    }

    /// The run's figures.
    fn finish(self, started: Instant) -> RunSummary {
        let mut summary = self.summary;
        let linear = &self.asm.linear;
        summary.t = self.t;
        summary.wall_time_s = started.elapsed().as_secs_f64();
        summary.symbolic_factorizations = linear.symbolic_factorizations;
        summary.timings = self.asm.timings();
        summary.iterative = linear.iterative_stats();
        summary.ldlt = linear.ldlt_stats();
        summary.lagged = linear.lagged_stats();
        summary.recording_s = self.recording.as_secs_f64();
        summary
    }
}
