//! The load stepping over the pseudo-time, step by step: converge an increment (attempts
//! from a predicted or converged start, cut-backs on failure), commit it and hand its
//! records to the observer, grow the step back toward the nominal one.

use super::augmented::solve_augmented;
use super::equilibrium::{Imbalance, EQUILIBRIUM_TOLERANCE};
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

/// The warning for elements that lost stability: how many, the first five, and the remedy.
fn unstable_warning<S: Dim>(model: &Model<S>, unstable: &[super::element_check::UnstableElement]) -> String {
    let names: Vec<String> = unstable.iter().take(5).map(|e| e.element.to_string()).collect();
    let safe = unstable
        .iter()
        .all(|e| S::holds_hourglass(&model.bodies[model.elements[e.element].body].kind));
    let remedy = if safe {
        "the elements are already `q4-eas-safe`: they are deformed beyond what one element resolves (refine the mesh where they are)"
    } else {
        "the element kind `q4-eas-safe` (the default) does not hourglass in compression"
    };
    format!(
        "{} elements have lost stability (their tangent is not positive definite in a deformation mode: an hourglass pattern; the answer may be wrong): elements {}{}; {remedy}",
        unstable.len(),
        names.join(", "),
        if unstable.len() > 5 { ", …" } else { "" }
    )
}

/// Check the elements at a converged increment; log a warning when the unstable set changes
/// in size (the first time too), and keep the run's account.
fn check_elements<S: Dim>(
    model: &Model<S>,
    asm: &Assembler<S>,
    state: &TrialState,
    (increment, t): (usize, f64),
    last_count: &mut usize,
    summary: &mut RunSummary,
    obs: &mut dyn Observer,
) -> Result<(), ObserverError> {
    let unstable = match super::element_check::unstable_elements(model, asm, &state.u, &state.alphas) {
        Ok(unstable) => unstable,
        Err(e) => {
            // the state converged, but an element's tangent could not be evaluated for the
            // check: said once, counted in the summary
            summary.element_check_errors += 1;
            if summary.element_check_errors == 1 {
                let message =
                    format!("the elements' stability could not be checked at this converged increment: {e}; not checked where this recurs");
                log(obs, LogLevel::Warning, increment, t, message)?;
            }
            return Ok(());
        }
    };
    if unstable.len() != *last_count && !unstable.is_empty() {
        log(obs, LogLevel::Warning, increment, t, unstable_warning(model, &unstable))?;
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
    let nodes = super::tangent_check::nodes_of_points(model.plane(), &trial.contact, points);
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
/// What committing the contact history of a converged increment gives the records.
struct ContactCommit {
    points: Vec<ContactPointRecord>,
    monitors: Vec<MonitorRecord>,
    crossings: Vec<CrossingRecord>,
    imbalance: Option<Imbalance>,
    /// The time the commit itself took (physics, not recording).
    commit_time: std::time::Duration,
    /// The 3D contact points, and how many crossed to another facet.
    surface_points: Vec<SurfacePointRecord>,
    surface_crossings: usize,
}

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
        asm.linear.set_threads(threads, crate::linalg::chooser::PARALLEL_FROM);
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
            node_sizes: super::penetration::node_sizes(model.plane()),
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
            match self.attempt(&mut trial, target, obs, stop)? {
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
            let points = self.ws.watch.report(&trial.contact, model.plane(), 8);
            let message = diagnose_tangent(model, &mut self.asm, trial, t_new, &points);
            log(obs, LogLevel::Warning, increment, t_new, message)?;
        }
        if last {
            return Err(SolveError::StepFailed {
                increment,
                t: t_new,
                dt,
                cutbacks,
                reason: self.failure_reason(&f),
                residuals: self.ws.residuals.clone(),
                kind: f.kind(),
                points: self.ws.watch.report(&trial.contact, model.plane(), 8),
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
    /// solution at all because a body is at its friction limit, that diagnosis
    /// ([`friction_limit`]).
    fn failure_reason(&self, f: &NewtonFailure) -> String {
        let may_lack_a_solution = matches!(
            f.kind(),
            FailureKind::NoConvergence
                | FailureKind::ActiveSetCycle
                | FailureKind::Diverged
                | FailureKind::LinearSolver
                | FailureKind::NonFinite
        );
        match may_lack_a_solution.then(|| friction_limit(self.model.plane(), &self.committed.contact, self.t)) {
            Some(Some(hint)) => format!("{f}; {hint}"),
            _ => f.to_string(),
        }
    }

    /// Make the converged increment the committed state: records of the converged iterate
    /// (compared with the previous increment), the contact history committed, the records
    /// handed to `obs`, the elements checked.
    fn commit(&mut self, done: ConvergedIncrement, t_inc: Instant, obs: &mut dyn Observer) -> Result<(), SolveError> {
        for ((d, a), b) in self.last_du.iter_mut().zip(&done.state.u).zip(&self.committed.u) {
            *d = a - b;
        }
        self.last_dt = Some(done.t_new - self.t);
        self.committed = done.state;
        let t_prev = self.t;
        self.t = done.t_new;
        self.fref = self.fref.max(done.conv.reference);
        self.summary.newton_iterations += done.conv.iterations;
        self.summary.augmentations += done.conv.augmentations;
        let handed = Instant::now();
        let ContactCommit {
            points,
            monitors,
            crossings,
            imbalance,
            commit_time,
            surface_points,
            surface_crossings,
        } = self.commit_contact();
        self.check_equilibrium(imbalance)?;
        self.check_penetration(&points, obs)?;
        self.summary.crossings += crossings.len() + surface_crossings;
        self.report_history_jumps(&crossings, obs)?;
        self.report_lost_histories(&surface_points, obs)?;
        self.summary.on_extension += usize::from(done.on_extension > 0);
        self.summary.line_search_failures += done.conv.line_search_failures;
        self.summary.front_iterations += done.conv.front_iterations;
        let equilibrium = imbalance.map_or(0.0, |i| i.relative);
        let (conv, cutbacks, on_extension) = (done.conv, done.cutbacks, done.on_extension);
        let rec = self.increment_record((conv, cutbacks, on_extension), t_prev, t_inc, monitors, equilibrium);
        self.summary.monitor = rec.monitor.clone();
        self.summary.monitors = rec.monitors.clone();
        let view = StepView {
            model: self.model.view(),
            u: &self.committed.u,
            contact: &points,
            crossings: &crossings,
            surface: &surface_points,
        };
        obs.increment(&rec, &view)?;
        self.recording += handed.elapsed().saturating_sub(commit_time);
        let at = (self.increment, self.t);
        check_elements(
            self.model,
            &self.asm,
            &self.committed,
            at,
            &mut self.unstable_count,
            &mut self.summary,
            obs,
        )?;
        self.asm.update_hourglass_holds(self.model, &self.committed.u);
        self.summary.increments = self.increment;
        Ok(())
    }

    /// The record of the increment just committed (at `self.t`, from `t_prev`): its Newton
    /// outcome, cut-backs and points on a segment's extension.
    fn increment_record(
        &self,
        (conv, cutbacks, on_extension): (Converged, usize, usize),
        t_prev: f64,
        t_inc: Instant,
        monitors: Vec<MonitorRecord>,
        equilibrium: f64,
    ) -> IncrementRecord {
        let (reaction_total, reaction_z) = self.reaction_total();
        IncrementRecord {
            increment: self.increment,
            t: self.t,
            dt: self.t - t_prev,
            iterations: conv.iterations,
            cutbacks,
            converged: true,
            wall_time_s: t_inc.elapsed().as_secs_f64(),
            residuals: conv.residuals,
            monitor: monitors.first().cloned(),
            monitors,
            reaction_total,
            reaction_z,
            accepted_by: conv.accepted_by.as_str().into(),
            line_search_failures: conv.line_search_failures,
            on_extension,
            front_iterations: conv.front_iterations,
            equilibrium,
        }
    }

    /// The contact records, monitors and equilibrium check of the converged iterate (they
    /// compare it with the previous increment, so they come first), then the contact
    /// history committed and its crossings.
    fn commit_contact(&mut self) -> ContactCommit {
        let cfg = Config {
            model: self.model.plane(),
            u: &self.committed.u,
            t: self.t,
        };
        let snapshots = self.committed.contact.snapshots(&cfg);
        let points: Vec<ContactPointRecord> = (snapshots.iter())
            .map(|p| ContactPointRecord::from_snapshot(&self.labels, p))
            .collect();
        let solid = S::solid(self.model).map(|model| SurfaceConfig {
            model,
            u: &self.committed.u,
            t: self.t,
        });
        let (surface, surface_points) = match &solid {
            Some(c) => {
                let snapshots = self.committed.contact.surface.snapshots(c);
                let records = (snapshots.iter())
                    .map(|p| SurfacePointRecord::of(c.model, &self.committed.u, p))
                    .collect();
                (snapshots, records)
            }
            None => (Vec::new(), Vec::new()),
        };
        let monitors = super::monitor::records(self.model, &self.asm, &self.committed.u, self.t, &snapshots);
        let imbalance =
            super::equilibrium::worst_imbalance(self.model, &self.asm, self.t, &snapshots, &surface, self.fref);
        let committing = Instant::now();
        let events = self.committed.contact.commit(&cfg);
        let surface_crossings = self.committed.contact.surface.commit();
        let commit_time = committing.elapsed();
        let crossings: Vec<CrossingRecord> = events.iter().map(CrossingRecord::from).collect();
        ContactCommit {
            points,
            monitors,
            crossings,
            imbalance,
            commit_time,
            surface_points,
            surface_crossings,
        }
    }

    /// Count the crossings at which the friction history jumped (see
    /// [`RunSummary::history_jumps`]) and warn at the first one: the run goes on, but its
    /// force history is then not the method's.
    fn report_history_jumps(&mut self, crossings: &[CrossingRecord], obs: &mut dyn Observer) -> Result<(), SolveError> {
        for c in crossings {
            let (before, after) = (c.trial_before, c.trial_after);
            // a point that carried no traction into the crossing has no history to lose
            let carried = before.abs() > 1e-9 * after.abs();
            if !carried || (after - before).abs() <= super::run::HISTORY_JUMP * before.abs().max(after.abs()) {
                continue;
            }
            self.summary.history_jumps += 1;
            if self.summary.history_jumps == 1 {
                let pair = &self.model.contacts[c.pair];
                let message = format!(
                    "crossing of {} of `{}` from segment {} to {}: the trial traction jumped from {before:.4e} to {after:.4e} — \
                     the `{}` transfer does not carry the friction history across segments, and the force history is wrong from \
                     here on (use transfer = \"continuous\"; seed Fig. 4)",
                    self.model.slave_label(pair.slaves[c.slave]),
                    pair.name,
                    c.from_segment,
                    c.to_segment,
                    pair.transfer.name()
                );
                log(obs, LogLevel::Warning, self.increment, self.t, message)?;
            }
        }
        Ok(())
    }

    /// Warn the first time a converged increment penetrates deeper than
    /// [`super::penetration::DEEP_PENETRATION`] of the local element size, and keep the
    /// deepest for the run's summary.
    /// Count the 3D points whose friction history could not be carried onto their new facet
    /// (counted with [`RunSummary::history_jumps`]) and warn at the first: the run goes on,
    /// those points starting their friction afresh.
    fn report_lost_histories(
        &mut self,
        points: &[SurfacePointRecord],
        obs: &mut dyn Observer,
    ) -> Result<(), SolveError> {
        for p in points.iter().filter(|p| p.history_lost) {
            self.summary.history_jumps += 1;
            if self.summary.history_jumps == 1 {
                let message = format!(
                    "node {} of `{}` moved from facet {:?} to {:?}: its friction history could not be carried onto the new \
                     facet (the facets fold onto each other, or the old contact point has no projection on it) and starts \
                     afresh — the force history is not the method's from here on",
                    p.node, p.pair_name, p.previous_facet, p.facet
                );
                log(obs, LogLevel::Warning, self.increment, self.t, message)?;
            }
        }
        Ok(())
    }

    fn check_penetration(&mut self, points: &[ContactPointRecord], obs: &mut dyn Observer) -> Result<(), SolveError> {
        use super::penetration::{deepest, warning, DEEP_PENETRATION};
        let Some(p) = deepest(self.model.plane(), &self.node_sizes, points) else {
            return Ok(());
        };
        if p.ratio <= DEEP_PENETRATION {
            return Ok(());
        }
        let first = self.summary.deep_penetration.is_none();
        if first {
            log(obs, LogLevel::Warning, self.increment, self.t, warning(&p))?;
        }
        if self.summary.deep_penetration.as_ref().is_none_or(|w| p.ratio > w.ratio) {
            self.summary.deep_penetration = Some(p);
        }
        Ok(())
    }

    /// Keep the worst equilibrium imbalance of the run ([`super::equilibrium`]) and stop the
    /// run, saying which body and by how much, when a converged increment is out of
    /// equilibrium: a force was lost between the assembly and the records, and every figure
    /// from here on would be wrong.
    fn check_equilibrium(&mut self, imbalance: Option<Imbalance>) -> Result<(), SolveError> {
        let Some(i) = imbalance else {
            return Ok(());
        };
        if self.summary.equilibrium.is_none_or(|w| i.relative > w) {
            self.summary.equilibrium = Some(i.relative);
        }
        if i.relative <= EQUILIBRIUM_TOLERANCE {
            return Ok(());
        }
        let message = format!(
            "body `{}` is out of equilibrium at the converged increment {}: its loads, reactions and contact forces sum to \
             ({:.4e}, {:.4e}), {:.2e} of the force scale (tolerance {EQUILIBRIUM_TOLERANCE:.0e}) — a force was lost between \
             the assembly and the records; the run stops rather than record a wrong answer (please report it with this recording)",
            self.model.bodies[i.body].name, self.increment, i.resultant[0], i.resultant[1], i.relative
        );
        Err(SolveError::StepFailed {
            increment: self.increment,
            t: self.t,
            dt: self.last_dt.unwrap_or(self.dt),
            cutbacks: 0,
            reason: message,
            residuals: Vec::new(),
            kind: FailureKind::WrongAnswer,
            points: Vec::new(),
        })
    }

    /// Sum of the reactions at the prescribed DOFs, per direction (x, y; z in 3D).
    fn reaction_total(&self) -> ([f64; 2], Option<f64>) {
        let mut total = [0.0; 3];
        for &d in &self.asm.dofs.prescribed {
            total[d % S::D] += self.asm.r_full[d];
        }
        ([total[0], total[1]], (S::D == 3).then_some(total[2]))
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
        summary.recording_s = self.recording.as_secs_f64();
        summary
    }
}
