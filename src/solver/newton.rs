//! Newton's method for one load increment: a semismooth Newton method on the displacements
//! and the contact force unknowns (condensed point by point, see
//! [`crate::contact::decision`]), globalised by a line search on the merit function of the
//! whole system ([`super::line_search`]), with a convergence test that depends neither on
//! the iterate nor on where the model sits or in what units it is written.
//!
//! One iteration: assemble → test → solve → search along the correction.

use super::state::TrialState;
use crate::assembly::Assembler;
use crate::contact::decision::Kink;
use crate::model::{Dim, Model};
use crate::record::IterationRecord;
use crate::settings::NewtonSettings;

pub use super::newton_failure::NewtonFailure;
pub use super::newton_types::{Acceptance, Converged, IncrementTarget, Workspace};

/// Assemble residual (and tangent if `with_tangent`) at `state`, refusing a state in which
/// contact points passed through their master ([`crate::contact::system::ContactSystem::tunnelled`]).
pub(super) fn assemble_at<S: Dim>(
    model: &Model<S>,
    asm: &mut Assembler<S>,
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

/// The force scale of a state: the norm of the reactions (internal forces at prescribed
/// DOFs), of the applied loads and of the contact forces.
pub fn force_scale<S: Dim>(
    model: &Model<S>,
    asm: &Assembler<S>,
    contact: &crate::contact::system::ContactSystem,
    t: f64,
) -> f64 {
    let reac: f64 = asm.dofs.prescribed.iter().map(|&d| asm.r_full[d].powi(2)).sum();
    let load: f64 = model.loads.iter().map(|l| l.ramp.at(t).powi(2)).sum();
    (reac + load + contact.force_norm().powi(2)).sqrt()
}

/// The norms an attempt is judged by.
#[derive(Debug, Clone, Copy, Default)]
struct Norms {
    /// `‖R‖` of the first iterate and of the current one; the reference force and the
    /// residual tolerance (fixed at the first iterate: an iterate cannot loosen its own test).
    r0: f64,
    rn: f64,
    fref: f64,
    tol: f64,
    /// Energy norms `|Δu·R|` of the first and the last correction.
    e0: f64,
    e_last: f64,
}

/// Iterate to equilibrium at `target.t` starting from `state` (prescribed DOFs are set here).
/// `on_iteration` receives one record per correction; failures leave `state` dirty (the
/// caller restores the last converged one).
///
/// The residual judged is that of the mixed system, `‖R‖ = √φ` with `φ` the merit
/// function ([`Assembler::merit`]): equilibrium with the contact force unknowns, and their
/// complementarity residuals — the penalty law to within `tol · F_ref / c` in the gap, `c`
/// the bodies' stiffness, whatever `ε`. Converged when `‖R‖ ≤ max(tol · F_ref,
/// residual_abs)` and the energy norm of the last correction fell below `energy_tol` times
/// that of the first, or when `‖R‖` is at the round-off floor `ε_round` of the assembled
/// residual ([`Assembler::roundoff`]); which test accepted is recorded ([`Acceptance`]).
/// `F_ref` is fixed for the attempt: the largest force scale ([`force_scale`]) of the run's
/// converged increments, or, before there is one, of the attempt's first iterate.
pub fn solve_increment<S: Dim>(
    model: &Model<S>,
    settings: &NewtonSettings,
    asm: &mut Assembler<S>,
    state: &mut TrialState,
    target: IncrementTarget,
    record: &mut dyn FnMut(IterationRecord) -> bool,
    ws: &mut Workspace,
) -> Result<Converged, NewtonFailure> {
    let mut it = Iterate::start(model, settings, asm, state, target, ws)?;
    for k in 0.. {
        if let Some(converged) = it.test_convergence(k)? {
            return Ok(converged);
        }
        if k >= settings.max_iterations + it.ws.front_iterations {
            break;
        }
        let (energy, step) = it.correct()?;
        let changes = it.ws.watch.observe(&it.state.contact, k + 1);
        it.count_front(changes);
        let keep_going = record(IterationRecord {
            increment: target.increment,
            attempt: target.attempt,
            t: target.t,
            iteration: k + 1,
            residual: it.norms.rn,
            energy,
            reference: it.norms.fref,
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
pub(super) struct Iterate<'a, S: Dim> {
    pub(super) model: &'a Model<S>,
    settings: &'a NewtonSettings,
    pub(super) asm: &'a mut Assembler<S>,
    pub(super) state: &'a mut TrialState,
    pub(super) ws: &'a mut Workspace,
    pub(super) t: f64,
    norms: Norms,
    /// The iterate's assembly was made without the tangent (it was expected to converge):
    /// how to repeat it with the tangent — the warm start and the kink it was made with.
    missing_tangent: Option<(bool, Kink)>,
}

impl<'a, S: Dim> Iterate<'a, S> {
    /// Prescribe the DOFs, size the buffers, assemble the first iterate and fix the
    /// reference force.
    fn start(
        model: &'a Model<S>,
        settings: &'a NewtonSettings,
        asm: &'a mut Assembler<S>,
        state: &'a mut TrialState,
        target: IncrementTarget,
        ws: &'a mut Workspace,
    ) -> Result<Self, NewtonFailure> {
        ws.residuals.clear();
        ws.merits.clear();
        ws.line_search_failures = 0;
        ws.front_iterations = 0;
        ws.inertia = None;
        asm.linear.take_inertia();
        ws.watchdog.reset();
        ws.continuation.reset();
        for p in &model.prescribed {
            state.u[p.dof] = p.at(target.t);
        }
        let n = asm.dofs.n_free;
        ws.r.resize(n, 0.0);
        ws.du.resize(n, 0.0);
        // the first correction of an attempt starts from the converged active set: the
        // points decide by their force unknowns alone (see `contact::decision`)
        state.contact.set_warm_start(true);
        // an increment like the last one, which its start already satisfied, is expected to
        // be accepted at its start too: no tangent unless it must iterate
        let skip = settings.skip_converging_tangents && target.attempt == 0 && ws.last_start_accepted;
        assemble_at(model, asm, state, target.t, !skip)?;
        state.contact.set_warm_start(false);
        let missing_tangent = skip.then_some((true, state.contact.kink()));
        asm.timings.tangents_skipped += usize::from(skip);
        ws.watch.start(&state.contact);
        let fref = match target.reference_floor {
            f if f > 0.0 => f,
            _ => force_scale(model, asm, &state.contact, target.t).max(asm.merit(&state.contact).sqrt()),
        };
        let norms = Norms {
            fref,
            tol: (settings.residual_tol * fref).max(settings.residual_abs),
            ..Norms::default()
        };
        Ok(Iterate {
            model,
            settings,
            asm,
            state,
            ws,
            t: target.t,
            norms,
            missing_tangent,
        })
    }

    pub(super) fn assemble(&mut self, with_tangent: bool) -> Result<(), NewtonFailure> {
        assemble_at(self.model, self.asm, self.state, self.t, with_tangent)
    }

    /// The residual and energy tests at iterate `k`, then the divergence test. On
    /// convergence the contact points take their force unknowns as their forces
    /// ([`crate::contact::system::ContactSystem::adopt_forces`]).
    fn test_convergence(&mut self, k: usize) -> Result<Option<Converged>, NewtonFailure> {
        self.asm.free_residual(&mut self.ws.r);
        let merit = self.asm.merit(&self.state.contact);
        let rn = merit.sqrt();
        if !rn.is_finite() {
            return Err(NewtonFailure::NonFinite);
        }
        self.norms.rn = rn;
        self.ws.residuals.push(rn);
        self.ws.merits.push(merit);
        if k == 0 {
            self.norms.r0 = rn;
        }
        let floor = self.asm.roundoff();
        let energy_ok = k > 0 && self.norms.e_last <= self.settings.energy_tol * self.norms.e0.max(f64::MIN_POSITIVE);
        let accepted = match (rn <= floor, rn <= self.norms.tol.max(floor)) {
            (true, _) => Some(Acceptance::RoundOff),
            (false, true) if k == 0 => Some(Acceptance::Start),
            (false, true) if energy_ok => Some(Acceptance::Residual),
            _ => None,
        };
        if let Some(by) = accepted {
            self.ws.last_start_accepted = k == 0;
            if let [r0, r1, ..] = self.ws.residuals[..] {
                self.ws.last_first_rate = Some(r1 / r0);
            }
            self.state.contact.adopt_forces();
            return Ok(Some(self.converged(k, by)));
        }
        if rn > self.settings.divergence_factor * self.norms.r0.max(self.norms.fref) {
            return Err(NewtonFailure::Diverged { residual: rn });
        }
        Ok(None)
    }

    fn converged(&self, k: usize, accepted_by: Acceptance) -> Converged {
        Converged {
            iterations: k,
            residuals: self.ws.residuals.clone(),
            reference: force_scale(self.model, self.asm, &self.state.contact, self.t),
            augmentations: 0,
            accepted_by,
            line_search_failures: self.ws.line_search_failures,
            front_iterations: self.ws.front_iterations,
            stabilised: self.ws.continuation.corrections,
            stabilisation_work: self.ws.continuation.work,
            inertia: self.ws.inertia,
        }
    }

    /// Count an iteration that changed the active set to one not met before in the attempt
    /// (at most one per contact point). A semismooth Newton method on a contact problem
    /// terminates once its active set stops changing, and its sets do not repeat while it
    /// converges (Hintermüller, Ito & Kunisch, SIAM J Optim 13 (2003) 865–888, Thm 3.1 and
    /// §4; Hüeber & Wohlmuth, CMAME 194 (2005) 3147–3166, §5): a lift-off or slip front
    /// crossing many points moves a few points per iteration — the tension region of a
    /// body held by stiff contact springs is a few springs long — and each new set is
    /// progress, not failure. Only the iterations that repeat a set (a cycle) or leave it
    /// unchanged count against `max_iterations`; the extension is recorded per increment
    /// (`front_iterations`).
    fn count_front(&mut self, changes: usize) {
        let points = self.state.contact.signature_len();
        let new = self.ws.watch.new_pattern();
        if changes > 0 && new && self.ws.front_iterations < points {
            self.ws.front_iterations += 1;
        }
        if changes > 0 && !new {
            self.ws.watchdog.go_monotone();
        }
    }

    /// Solve for the correction `Δu = −K⁻¹R`, linearise the force unknowns along it, and
    /// search along it. Returns the correction's energy norm `|Δu·R|` and the step taken.
    fn correct(&mut self) -> Result<(f64, f64), NewtonFailure> {
        self.add_missing_tangent()?;
        self.solve_correction()?;
        self.start_correction();
        let ws = &mut *self.ws;
        let energy = ws.du.iter().zip(&ws.r).map(|(a, b)| a * b).sum::<f64>().abs();
        if self.norms.e0 == 0.0 {
            self.norms.e0 = energy;
        }
        self.norms.e_last = energy;
        let failures = self.ws.line_search_failures;
        let step = self.globalise()?;
        if self.ws.continuation.on() {
            let growth = self.asm.merit(&self.state.contact).sqrt() / self.norms.rn;
            self.ws.continuation.took(&self.ws.du, step, growth);
        }
        if self.ws.line_search_failures > failures {
            self.ws.continuation.engage();
        }
        self.state.contact.set_kink(Kink::Open);
        Ok((energy, step))
    }

    /// Whether the iterate a full step along the correction just solved reaches is expected
    /// to pass the convergence test, so that its assembly needs no tangent. The residual is
    /// predicted at the rate of the last correction, `‖R_{k+1}‖ ≈ (‖R_k‖/‖R_{k−1}‖) ‖R_k‖`
    /// (an overestimate while convergence is quadratic; for the first correction, the rate
    /// of the last converged attempt's first), and judged as [`Self::test_convergence`]
    /// will judge it. The answer is the same either way: a wrong guess costs one assembly
    /// without the tangent before the tangent is assembled.
    pub(super) fn expects_convergence(&self) -> bool {
        if !self.settings.skip_converging_tangents {
            return false;
        }
        let r = &self.ws.residuals;
        let rate = match r[..] {
            [] => return false,
            [_] => match self.ws.last_first_rate {
                Some(rate) => rate,
                None => return false,
            },
            [.., a, b] => b / a,
        };
        let Some(&rn) = r.last() else { return false };
        let predicted = rate * rn;
        if !(rate < 1.0 && predicted.is_finite()) {
            return false;
        }
        let floor = self.asm.roundoff();
        let energy_ok = self.norms.e_last <= self.settings.energy_tol * self.norms.e0.max(f64::MIN_POSITIVE);
        predicted <= floor || (energy_ok && predicted <= self.norms.tol.max(floor))
    }

    /// Note that the assembly just made at the iterate lacks the tangent.
    pub(super) fn tangent_skipped(&mut self) {
        self.missing_tangent = Some((false, self.state.contact.kink()));
        self.asm.timings.tangents_skipped += 1;
    }

    /// The iterate was expected to converge and did not: assemble it again, with the
    /// tangent, as it was assembled (same warm start and kink).
    fn add_missing_tangent(&mut self) -> Result<(), NewtonFailure> {
        let Some((warm, kink)) = self.missing_tangent.take() else {
            return Ok(());
        };
        self.asm.timings.tangents_missed += 1;
        let now = self.state.contact.kink();
        self.state.contact.set_kink(kink);
        self.state.contact.set_warm_start(warm);
        let assembled = self.assemble(true);
        self.state.contact.set_warm_start(false);
        self.state.contact.set_kink(now);
        assembled?;
        self.asm.free_residual(&mut self.ws.r);
        let merit = self.asm.merit(&self.state.contact);
        *self.ws.merits.last_mut().expect("the iterate was tested") = merit;
        Ok(())
    }

    /// Keep the iterate the correction in `ws.du` starts from, and the force unknowns at its
    /// full step.
    fn start_correction(&mut self) {
        let ws = &mut *self.ws;
        ws.u_before.clone_from(&self.state.u);
        ws.alphas_before.clone_from(&self.state.alphas);
        self.state.contact.save_iterate();
        let (eq, du) = (&self.asm.dofs.eq, &ws.du);
        self.state.contact.correct_forces(&|d| eq[d].map_or(0.0, |e| du[e]));
    }

    /// `Δu = −K⁻¹R` into `ws.du`. Where the tangent with the points touching without force
    /// taken open is singular (a zero pivot, or a correction longer than the model: a body
    /// held by nothing but the supports it rests on), the other element of the generalised
    /// Jacobian is taken for this correction: they rest ([`Kink::Resting`]).
    fn solve_correction(&mut self) -> Result<(), NewtonFailure> {
        let size = self.model.size();
        let solved = self.solve_direction();
        let sane = |du: &[f64]| du.iter().all(|d| d.abs() <= size);
        let open = self.state.contact.kink() == Kink::Open;
        if !open || self.state.contact.resting_points() == 0 {
            return solved;
        }
        if solved.is_ok() && sane(&self.ws.du) {
            return self.choose_kink_side();
        }
        self.solve_resting()
    }

    /// The open correction in `ws.du` is consistent unless it drives points resting at the
    /// kink into their master with a force above the residual tolerance (the element of the
    /// generalised Jacobian it was made with says they carry no force, the correction that
    /// they would). Then the other element is tried for those points — they rest (and
    /// stick, at the tangential kink), the other points at the kink stay open — and its
    /// correction is taken if it is consistent in turn: every resting point pressed onto
    /// its master along it, within its friction cone ([`ContactSystem::resting_forces`]). Forces within the residual tolerance are
    /// zero to this test, as to the convergence test: a point that carries no force either
    /// way (where strict complementarity fails) is no reason to leave the open side.
    /// Otherwise the open correction stays, and the next iterate decides by its gaps, as
    /// the primal–dual active-set method does (Hintermüller, Ito & Kunisch 2003). The
    /// choice between the two elements of the B-subdifferential by the sign conditions of
    /// the step is Qi & Sun's (Math Program 58 (1993) 353–367) and the contact form of it
    /// Hüeber & Wohlmuth's (CMAME 194 (2005) 3147–3166, §3).
    ///
    /// [`ContactSystem::resting_forces`]: crate::contact::system::ContactSystem::resting_forces
    fn choose_kink_side(&mut self) -> Result<(), NewtonFailure> {
        let tol = self.norms.tol;
        let (eq, du) = (&self.asm.dofs.eq, &self.ws.du);
        let driven_in =
            (self.state.contact).rest_driven_in(S::plane(self.model), tol, &|d| eq[d].map_or(0.0, |e| du[e]));
        if driven_in == 0 {
            return Ok(());
        }
        self.asm.timings.kink_trials += 1;
        self.ws.du_open.clone_from(&self.ws.du);
        let warm = self.ws.residuals.len() == 1;
        self.assemble_iterate(Kink::Resting, warm, true)?;
        let solved = self.solve_direction().is_ok();
        let (eq, du) = (&self.asm.dofs.eq, &self.ws.du);
        let resting = self
            .state
            .contact
            .resting_forces(S::plane(self.model), false, &|d| eq[d].map_or(0.0, |e| du[e]));
        if solved && resting.is_some_and(|f| f.normal_min > tol && f.cone_excess <= tol) {
            self.asm.timings.resting_corrections += 1;
            return Ok(());
        }
        self.state.contact.rest_all();
        self.assemble_iterate(Kink::Open, warm, false)?;
        self.ws.du.clone_from(&self.ws.du_open);
        Ok(())
    }

    /// Assemble the iterate again with the points at the normal kink on `kink`'s side (and
    /// its first decision by the force unknowns where `warm`; the tangent if `tangent`),
    /// as the iterate's merit and residual.
    fn assemble_iterate(&mut self, kink: Kink, warm: bool, tangent: bool) -> Result<(), NewtonFailure> {
        self.state.contact.set_kink(kink);
        self.state.contact.set_warm_start(warm);
        let assembled = self.assemble(tangent);
        self.state.contact.set_warm_start(false);
        assembled?;
        let merit = self.asm.merit(&self.state.contact);
        *self.ws.merits.last_mut().expect("the iterate was tested") = merit;
        self.asm.free_residual(&mut self.ws.r);
        Ok(())
    }

    /// Assemble the iterate with the points at the normal kink resting ([`Kink::Resting`])
    /// and solve for the correction.
    fn solve_resting(&mut self) -> Result<(), NewtonFailure> {
        self.state.contact.rest_all();
        self.state.contact.set_kink(Kink::Resting);
        self.assemble(true)?;
        let merit = self.asm.merit(&self.state.contact);
        *self.ws.merits.last_mut().expect("the iterate was tested") = merit;
        self.asm.free_residual(&mut self.ws.r);
        self.solve_direction()
    }

    fn solve_direction(&mut self) -> Result<(), NewtonFailure> {
        let ws = &mut *self.ws;
        for (d, ri) in ws.du.iter_mut().zip(&ws.r) {
            *d = -ri;
        }
        let shifted = ws.continuation.on();
        ws.continuation.solve(self.asm, &mut ws.du)?;
        // the definiteness of the tangent itself, not of one shifted by the continuation
        if let Some(inertia) = self.asm.linear.take_inertia().filter(|_| !shifted) {
            ws.inertia = Some(inertia);
        }
        Ok(())
    }

    /// Why the iteration stopped without converging: an active-set cycle, or too many
    /// iterations.
    fn failure(&self) -> NewtonFailure {
        let iterations = self.ws.residuals.len() - 1;
        if self.ws.watch.cycling(3) {
            let points = self.ws.watch.changed_points();
            return NewtonFailure::ActiveSetCycle { iterations, points };
        }
        NewtonFailure::MaxIterations { iterations }
    }
}

pub(super) fn apply(u: &mut [f64], eq: &[Option<usize>], du: &[f64], s: f64) {
    for (d, e) in eq.iter().enumerate() {
        if let Some(e) = e {
            u[d] += s * du[*e];
        }
    }
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
