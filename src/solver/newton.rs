//! Newton–Raphson for one load increment, with residual and energy-norm criteria and an
//! optional backtracking line search.

use super::active_set::{hold_first_correction, touching_pushed_in, ActiveSetWatch};
use super::line_search::{residual_backtracking, slope_search};
use super::state::TrialState;
use crate::assembly::Assembler;
use crate::model::Model;
use crate::record::IterationRecord;
use crate::settings::{LineSearch, NewtonSettings};

pub use super::newton_failure::NewtonFailure;

#[path = "newton_guards.rs"]
mod guards;

/// Outcome of a converged increment (`residuals`: `‖R‖` at each iterate).
#[derive(Debug, Clone)]
pub struct Converged {
    pub iterations: usize,
    pub residuals: Vec<f64>,
    pub reference: f64,
    /// Points frozen during the increment and verified at its end.
    pub frozen: usize,
    /// Multiplier updates of augmented-Lagrangian pairs (each one more solve).
    pub augmentations: usize,
}

/// Assemble residual (and tangent if `with_tangent`) at `state`, refusing a state in which
/// contact points passed through their master ([`crate::contact::system::ContactSystem::tunnelled`]).
pub(super) fn assemble_at(
    model: &Model,
    asm: &mut Assembler,
    state: &mut TrialState,
    t: f64,
    with_tangent: bool,
) -> Result<(), NewtonFailure> {
    asm.assemble(model, &state.u, t, &mut state.alphas, &mut state.contact, with_tangent)?;
    match state.contact.tunnelled() {
        [] => Ok(()),
        through @ [(ip, is), ..] => {
            let pair = &model.contacts[*ip];
            Err(NewtonFailure::Tunnelled {
                points: through.len(),
                first: format!("{} of `{}`", model.slave_label(pair.slaves[*is]), pair.name),
            })
        }
    }
}

/// Whether a failure says the iterate just reached is inadmissible (an element inverted or
/// without enhanced-strain equilibrium, or contact points through their master): a shorter
/// step along the same correction may not be.
pub(super) fn inadmissible(f: &NewtonFailure) -> bool {
    matches!(f, NewtonFailure::Element(_) | NewtonFailure::Tunnelled { .. })
}

/// Norm of the reactions (internal forces at prescribed DOFs) and of the applied loads.
fn reference_force(model: &Model, asm: &Assembler, t: f64) -> f64 {
    let reac: f64 = asm.dofs.prescribed.iter().map(|&d| asm.r_full[d].powi(2)).sum();
    let load: f64 = model.loads.iter().map(|l| l.ramp.at(t).powi(2)).sum();
    (reac + load).sqrt()
}

/// Buffers and diagnostics of one attempt, reused across increments.
#[derive(Debug, Default)]
pub struct Workspace {
    pub(super) r: Vec<f64>,
    pub(super) du: Vec<f64>,
    frozen: Vec<bool>,
    /// Points held (closed, or in stick) for the first correction of an attempt.
    held: Vec<usize>,
    /// `‖R‖` at each iterate of the last attempt.
    pub residuals: Vec<f64>,
    /// The active-set history of the last attempt.
    pub watch: ActiveSetWatch,
    /// The iterate before the last correction (displacements and enhanced-strain
    /// parameters), to shorten a correction that inverts an element.
    u_before: Vec<f64>,
    alphas_before: Vec<[f64; 4]>,
    /// Per point, the direction of its slip at the last iterate (0: not slipping).
    slip_sign: Vec<i8>,
}

/// How many times a Newton correction is halved when its end inverts an element (or an
/// element's enhanced strains find no equilibrium there) before the attempt fails.
pub const MAX_INADMISSIBLE_HALVINGS: usize = 12;

/// Which increment is solved, to what time, and from what start.
#[derive(Debug, Clone, Copy)]
pub struct IncrementTarget {
    /// The pseudo-time the increment ends at.
    pub t: f64,
    /// The largest reference force of the run so far (`F_ref` never falls below it).
    pub reference_floor: f64,
    pub increment: usize,
    pub attempt: usize,
    /// The start is extrapolated from the last converged increments (secant predictor).
    pub predicted: bool,
    /// From a predicted start, shorten inadmissible corrections like any other start
    /// instead of giving the prediction up at the first one (see `Iterate::shorten`).
    pub shorten_predicted: bool,
}

/// Iterate to equilibrium at `target.t` starting from `state` (prescribed DOFs are set here).
/// `on_iteration` receives one record per correction; failures leave `state` dirty (the
/// caller restores the last converged one). `target.predicted`: `state` is an extrapolated
/// start; points it finds open that were closed at the last converged increment are held
/// closed for the first correction ([`hold_first_correction`]; the first residual recorded
/// is then that of the held state).
///
/// Converged when `‖R‖ ≤ max(tol · F_ref, residual_abs, ε_round)` and the energy norm of the
/// last correction fell below `energy_tol` times that of the first, where `F_ref` is the
/// norm of reactions and loads (never below the largest converged one of the run) and
/// `ε_round = 1e-13 ‖Σ|r_e|‖` is the round-off level of the assembled residual (the norm
/// of the summed absolute element and contact contributions): refining the mesh or the
/// step never asks for a residual below what the arithmetic can resolve.
///
/// Each iteration is the textbook sequence of named steps: assemble, test convergence
/// (verifying frozen points), correct, search along the correction, watch the active set.
pub fn solve_increment(
    model: &Model,
    settings: &NewtonSettings,
    asm: &mut Assembler,
    state: &mut TrialState,
    target: IncrementTarget,
    record: &mut dyn FnMut(IterationRecord) -> bool,
    ws: &mut Workspace,
) -> Result<Converged, NewtonFailure> {
    let mut it = Iterate::start(model, settings, asm, state, target, ws)?;
    for k in 0.. {
        it.assemble_if_needed()?;
        it.hold_reversing_slip()?;
        if let Some(converged) = it.test_convergence(k)? {
            return Ok(converged);
        }
        if k >= it.budget() {
            break;
        }
        let (energy, step, reuse) = it.correct(k)?;
        let changes = it.watch_active_set(k, reuse);
        it.count_settling(changes);
        let keep_going = record(IterationRecord {
            increment: target.increment,
            attempt: target.attempt,
            t: target.t,
            iteration: k + 1,
            residual: it.rn,
            energy,
            reference: it.fref,
            line_search: step,
            active_set_changes: changes,
        });
        if !keep_going {
            break;
        }
    }
    Err(it.failure())
}

/// The state of Newton's iteration within one attempt at an increment.
struct Iterate<'a> {
    model: &'a Model,
    settings: &'a NewtonSettings,
    asm: &'a mut Assembler,
    state: &'a mut TrialState,
    ws: &'a mut Workspace,
    t: f64,
    reference_floor: f64,
    /// Energy norm of the first correction (0 until made, and again after a verification).
    e0: f64,
    /// Energy norm of the last correction.
    e_last: f64,
    /// `‖R‖` of the first iterate, of the current one, its reference force and tolerance.
    r0: f64,
    rn: f64,
    fref: f64,
    tol: f64,
    /// Points that keep chattering are frozen (until a verification fails once).
    freezing: bool,
    verified_once: bool,
    /// What the assembler holds at the current iterate.
    assembled: Assembled,
    /// Iterations that left the active set in a pattern not met before in the attempt while
    /// the residual still reached new lows (see [`NewtonSettings::max_settling_iterations`]).
    settling: usize,
    /// The halving of the last correction when its end turned out inadmissible.
    shortened: f64,
    /// A predicted start is given up at its first inadmissible correction.
    abandon_bad_prediction: bool,
    /// First residual of the current run of free iterations (after a failed verification).
    settling_from: usize,
    /// The attempt starts from an extrapolated state: it gets no settling iterations (when
    /// it does not converge within `max_iterations` the increment is retried from the
    /// converged state, which settles from where it truly is).
    predicted: bool,
}

impl<'a> Iterate<'a> {
    /// Prescribe the DOFs, size the buffers, assemble the first iterate and hold the points
    /// that the first correction should see closed or sticking.
    fn start(
        model: &'a Model,
        settings: &'a NewtonSettings,
        asm: &'a mut Assembler,
        state: &'a mut TrialState,
        target: IncrementTarget,
        ws: &'a mut Workspace,
    ) -> Result<Self, NewtonFailure> {
        ws.residuals.clear();
        ws.held.clear();
        ws.u_before.clear();
        ws.slip_sign.clear();
        for p in &model.prescribed {
            state.u[p.dof] = p.ramp.at(target.t);
        }
        let n = asm.dofs.n_free;
        ws.r.resize(n, 0.0);
        ws.du.resize(n, 0.0);
        let t = target.t;
        assemble_at(model, asm, state, t, true)?;
        let retry = target.attempt > 0 && !target.predicted;
        let pushed_in = touching_pushed_in(model, asm, state, t, ws)?;
        let held = hold_first_correction(
            &mut state.contact,
            model,
            (target.predicted, retry),
            &pushed_in,
            &mut ws.held,
        );
        if held > 0 {
            assemble_at(model, asm, state, t, true)?;
        }
        ws.watch.start(&state.contact);
        ws.frozen.clear();
        ws.frozen.resize(state.contact.signature_len(), false);
        Ok(Iterate {
            model,
            settings,
            asm,
            state,
            ws,
            t,
            reference_floor: target.reference_floor,
            e0: 0.0,
            e_last: f64::INFINITY,
            r0: 0.0,
            rn: 0.0,
            fref: 0.0,
            tol: 0.0,
            freezing: settings.freeze_after > 0,
            verified_once: false,
            assembled: Assembled::Full,
            settling: 0,
            shortened: 1.0,
            abandon_bad_prediction: target.predicted && !target.shorten_predicted,
            settling_from: 0,
            predicted: target.predicted,
        })
    }

    fn assemble(&mut self, with_tangent: bool) -> Result<(), NewtonFailure> {
        assemble_at(self.model, self.asm, self.state, self.t, with_tangent)
    }

    /// Residual and tangent at the iterate, unless a line search's full-step trial left them.
    /// An iterate just reached by a correction that inverts an element is pulled back
    /// along the correction (see [`Self::shorten`]).
    fn assemble_if_needed(&mut self) -> Result<(), NewtonFailure> {
        if self.assembled == Assembled::Nothing {
            loop {
                match self.assemble(true) {
                    Ok(()) => break,
                    // (no correction to shorten when the iterate was not reached by one)
                    Err(f) if inadmissible(&f) && self.ws.u_before.len() == self.state.u.len() => self.shorten(f)?,
                    Err(e) => return Err(e),
                }
            }
            self.assembled = Assembled::Full;
        }
        Ok(())
    }

    /// The residual and energy tests at iterate `k` (a converged iterate with frozen points
    /// is verified with them released), then the divergence test.
    fn test_convergence(&mut self, k: usize) -> Result<Option<Converged>, NewtonFailure> {
        self.asm.free_residual(&mut self.ws.r);
        self.rn = norm(&self.ws.r);
        if !self.rn.is_finite() {
            return Err(NewtonFailure::NonFinite);
        }
        self.ws.residuals.push(self.rn);
        self.fref = reference_force(self.model, self.asm, self.t).max(self.reference_floor);
        if k == 0 {
            self.r0 = self.rn;
        }
        let floor = self.settings.residual_abs.max(self.asm.roundoff());
        self.tol = (self.settings.residual_tol * self.fref).max(floor);
        let res_ok = self.rn <= self.tol;
        let energy_ok = k > 0 && self.e_last <= self.settings.energy_tol * self.e0.max(f64::MIN_POSITIVE);
        if res_ok && (energy_ok || k == 0 || self.rn <= floor) {
            if let Some(converged) = self.verify_frozen(k)? {
                return Ok(Some(converged));
            }
        }
        if self.rn > self.settings.divergence_factor * self.r0.max(self.fref) {
            return Err(NewtonFailure::Diverged { residual: self.rn });
        }
        Ok(None)
    }

    /// A converged iterate: done when no point is frozen; otherwise release the frozen
    /// states (keeping admissible segments) and check them. Points held for the first
    /// correction of a predicted start (only ever at k = 0) are checked alike but are not
    /// reported as frozen (they were not chattering). A failed check goes on with every
    /// point free to choose (no more freezing); a second one fails the attempt.
    fn verify_frozen(&mut self, k: usize) -> Result<Option<Converged>, NewtonFailure> {
        let frozen = self.state.contact.frozen_count();
        let converged = |ws: &Workspace, frozen: usize, fref: f64| Converged {
            iterations: k,
            residuals: ws.residuals.clone(),
            reference: fref,
            frozen,
            augmentations: 0,
        };
        if frozen == 0 {
            let chattered = self.ws.frozen.iter().filter(|f| **f).count();
            return Ok(Some(converged(self.ws, chattered, self.fref)));
        }
        let chattering = frozen - self.ws.held.len();
        self.state.contact.verify_frozen();
        self.assemble(true)?;
        self.assembled = Assembled::Full;
        self.asm.free_residual(&mut self.ws.r);
        let rv = norm(&self.ws.r);
        if rv <= self.tol {
            self.ws.residuals.push(rv);
            return Ok(Some(converged(self.ws, chattering, self.fref)));
        }
        if self.verified_once {
            return Err(NewtonFailure::FrozenNotVerified { residual: rv });
        }
        self.state.contact.unfreeze();
        self.settling_from = self.ws.residuals.len();
        self.verified_once = true;
        self.freezing = false;
        self.e0 = 0.0;
        Ok(None)
    }

    /// Solve for the correction `Δu = −K⁻¹R`, take it, free the held points, and search
    /// along it. Returns the correction's energy norm `|Δu·R|`, the step taken and whether
    /// the assembler holds the accepted trial's assembly (see [`residual_backtracking`]).
    fn correct(&mut self, k: usize) -> Result<(f64, f64, Option<bool>), NewtonFailure> {
        if self.assembled == Assembled::Residual {
            // the residual-only trial did not converge after all: its tangent now
            self.assemble(true)?;
        }
        let ws = &mut *self.ws;
        for (d, ri) in ws.du.iter_mut().zip(&ws.r) {
            *d = -ri;
        }
        self.asm.solve(&mut ws.du)?;
        let energy = ws.du.iter().zip(&ws.r).map(|(a, b)| a * b).sum::<f64>().abs();
        if self.e0 == 0.0 {
            self.e0 = energy;
        }
        self.e_last = energy;
        ws.u_before.clone_from(&self.state.u);
        ws.alphas_before.clone_from(&self.state.alphas);
        self.shortened = 1.0;
        apply(&mut self.state.u, &self.asm.dofs.eq, &ws.du, 1.0);
        // the held points are free again once the first correction is computed: the line
        // search's trials (and so the next iterate) are assembled with their own state;
        // a correction made with stick held is the elastic predictor, taken in full (the
        // return mapping at its end finds the slipping points; backtracking on ‖R‖ from it
        // would undo the motion the stick tangent predicted)
        let elastic_predictor = self.state.contact.stick_held_count() > 0;
        for flat in ws.held.drain(..) {
            self.state.contact.release(flat);
        }
        if !self.settings.line_search || elastic_predictor {
            // the iterate is assembled (and shortened if inadmissible) at the next iteration
            return Ok((energy, 1.0, None));
        }
        loop {
            match self.line_search(k) {
                Ok((step, reuse)) => return Ok((energy, step * self.shortened, reuse)),
                Err(f) if inadmissible(&f) => self.shorten(f)?,
                Err(e) => return Err(e),
            }
        }
    }

    /// Will the full step converge? Then its trial needs no tangent (one fewer per
    /// increment): the energy test is already met by this correction and the residual,
    /// reduced at the rate of the last iteration (an overestimate where convergence is
    /// quadratic), falls below the tolerance. A wrong guess costs one more assembly.
    fn likely_converged(&self, k: usize) -> bool {
        let r = &self.ws.residuals;
        let r_prev = r.len().checked_sub(2).map(|i| r[i]);
        k > 0
            && self.e_last <= self.settings.energy_tol * self.e0.max(f64::MIN_POSITIVE)
            && r_prev.is_some_and(|rp| rp > 0.0 && self.rn * (self.rn / rp) <= self.tol)
    }

    /// The slope search where the iterate has an energy (no frictional slip) and the
    /// correction descends (`g(0) = Δu·R(u) < 0`); backtracking on `‖R‖` elsewhere.
    fn line_search(&mut self, k: usize) -> Result<(f64, Option<bool>), NewtonFailure> {
        let want_tangent = !self.likely_converged(k);
        let g0 = self.ws.du.iter().zip(&self.ws.r).map(|(a, b)| a * b).sum::<f64>();
        let slope_ok = self.settings.line_search_rule == LineSearch::Slope
            && g0 < 0.0
            && self.state.contact.conservative(self.model);
        let (model, t) = (self.model, self.t);
        if slope_ok {
            slope_search(model, self.asm, self.state, t, self.ws, g0, want_tangent)
        } else {
            residual_backtracking(model, self.asm, self.state, t, self.ws, self.rn, want_tangent)
        }
    }

    /// Count the active-set changes of the new iterate, freeze points that keep
    /// chattering, and note what the assembler now holds. Returns the changes.
    fn watch_active_set(&mut self, k: usize, reuse: Option<bool>) -> usize {
        let ws = &mut *self.ws;
        let changes = ws.watch.observe(&self.state.contact, k + 1);
        // frozen decisions change what the next assembly computes
        let after = self.settings.freeze_after;
        let froze = self.freezing
            && ws
                .watch
                .freeze_chattering(&mut self.state.contact, after, &mut ws.frozen)
                > 0;
        self.assembled = match (reuse, froze) {
            (Some(true), false) => Assembled::Full,
            (Some(false), false) => Assembled::Residual,
            _ => Assembled::Nothing,
        };
        changes
    }

    /// Why the iteration stopped without converging: an active-set cycle, or too many
    /// iterations.
    fn failure(&self) -> NewtonFailure {
        let iterations = self.ws.residuals.len() - 1;
        if self.ws.watch.cycling(3) {
            let points = self.ws.watch.report(&self.state.contact, self.model, usize::MAX).len();
            return NewtonFailure::ActiveSetCycle { iterations, points };
        }
        NewtonFailure::MaxIterations { iterations }
    }
}

/// What the assembler holds at the current iterate.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Assembled {
    Nothing,
    /// The residual (a full-step trial expected to converge).
    Residual,
    /// Residual and tangent.
    Full,
}

pub(super) fn apply(u: &mut [f64], eq: &[Option<usize>], du: &[f64], s: f64) {
    for (d, e) in eq.iter().enumerate() {
        if let Some(e) = e {
            u[d] += s * du[*e];
        }
    }
}

pub(super) fn norm(v: &[f64]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

/// Observed convergence orders `p_k = ln(r_{k+1}/r_k) / ln(r_k/r_{k−1})` of a residual
/// sequence (only where the residuals are still well above round-off).
pub fn observed_orders(residuals: &[f64], floor: f64) -> Vec<f64> {
    residuals
        .windows(3)
        .filter(|w| w[2] > floor && w[1] < w[0] && w[2] < w[1])
        .map(|w| (w[2] / w[1]).ln() / (w[1] / w[0]).ln())
        .collect()
}
