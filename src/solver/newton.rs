//! Newton–Raphson for one load increment, with residual and energy-norm criteria and an
//! optional backtracking line search.

use super::active_set::{hold_first_correction, touching_points, ActiveSetWatch};
use super::state::TrialState;
use crate::assembly::{Assembler, AssemblyError};
use crate::linalg::sparse::LinearError;
use crate::model::Model;
use crate::record::{FailureKind, IterationRecord};
use crate::settings::{LineSearch, NewtonSettings};

/// Why an increment failed (the stepping driver cuts the step back on these).
#[derive(Debug, Clone, thiserror::Error)]
pub enum NewtonFailure {
    #[error("no convergence in {iterations} iterations")]
    MaxIterations { iterations: usize },
    #[error("active-set cycle: {points} contact points kept changing state or segment ({iterations} iterations)")]
    ActiveSetCycle { iterations: usize, points: usize },
    #[error("frozen contact points did not verify: ‖R‖ = {residual:.3e} with them released")]
    FrozenNotVerified { residual: f64 },
    #[error("residual diverged (‖R‖ = {residual:.3e})")]
    Diverged { residual: f64 },
    #[error("non-finite residual")]
    NonFinite,
    #[error(
        "augmented Lagrangian of pair `{pair}` not converged after {updates} multiplier updates: the \
         multipliers still change by {relative:.2e} of the pair's largest normal force (augmented_tol = {tol:.1e}); \
         raise augmented_max, loosen augmented_tol, or raise eps_n / eps_t (each update contracts the error \
         by about k/(k + eps) for a local stiffness k)"
    )]
    Augmentation {
        pair: String,
        updates: usize,
        relative: f64,
        tol: f64,
    },
    #[error(transparent)]
    Element(#[from] AssemblyError),
    #[error(transparent)]
    Linear(#[from] LinearError),
}

impl NewtonFailure {
    /// The failure kind recorded in the outcome.
    pub fn kind(&self) -> FailureKind {
        match self {
            NewtonFailure::MaxIterations { .. } | NewtonFailure::Augmentation { .. } => FailureKind::NoConvergence,
            NewtonFailure::ActiveSetCycle { .. } | NewtonFailure::FrozenNotVerified { .. } => {
                FailureKind::ActiveSetCycle
            }
            NewtonFailure::Diverged { .. } => FailureKind::Diverged,
            NewtonFailure::NonFinite => FailureKind::NonFinite,
            NewtonFailure::Element(_) => FailureKind::InvertedElement,
            NewtonFailure::Linear(_) => FailureKind::LinearSolver,
        }
    }
}

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

/// Norm of the reactions (internal forces at prescribed DOFs) and of the applied loads.
fn reference_force(model: &Model, asm: &Assembler, t: f64) -> f64 {
    let reac: f64 = asm.dofs.prescribed.iter().map(|&d| asm.r_full[d].powi(2)).sum();
    let load: f64 = model.loads.iter().map(|l| l.ramp.at(t).powi(2)).sum();
    (reac + load).sqrt()
}

/// Buffers and diagnostics of one attempt, reused across increments.
#[derive(Debug, Default)]
pub struct Workspace {
    r: Vec<f64>,
    du: Vec<f64>,
    frozen: Vec<bool>,
    /// Points held (closed, or in stick) for the first correction of an attempt.
    held: Vec<usize>,
    /// `‖R‖` at each iterate of the last attempt.
    pub residuals: Vec<f64>,
    /// The active-set history of the last attempt.
    pub watch: ActiveSetWatch,
}

/// Iterate to equilibrium at time `t` starting from `state` (prescribed DOFs are set here).
/// `on_iteration` receives one record per correction; failures leave `state` dirty (the
/// caller restores the last converged one). `predicted`: `state` is an extrapolated start;
/// points it finds open that were closed at the last converged increment are held closed
/// for the first correction ([`hold_first_correction`]; the first residual recorded is
/// then that of the held state).
///
/// Converged when `‖R‖ ≤ max(tol · F_ref, residual_abs, ε_round)` and the energy norm of the
/// last correction fell below `energy_tol` times that of the first, where `F_ref` is the
/// norm of reactions and loads (never below the largest converged one of the run) and
/// `ε_round = 1e-13 ‖Σ|r_e|‖` is the round-off level of the assembled residual (the norm
/// of the summed absolute element and contact contributions): refining the mesh or the
/// step never asks for a residual below what the arithmetic can resolve.
#[allow(clippy::too_many_arguments)]
pub fn solve_increment(
    model: &Model,
    settings: &NewtonSettings,
    asm: &mut Assembler,
    state: &mut TrialState,
    t: f64,
    reference_floor: f64,
    record: &mut dyn FnMut(IterationRecord) -> bool,
    (increment, attempt): (usize, usize),
    predicted: bool,
    ws: &mut Workspace,
) -> Result<Converged, NewtonFailure> {
    ws.residuals.clear();
    ws.held.clear();
    for p in &model.prescribed {
        state.u[p.dof] = p.ramp.at(t);
    }
    let n = asm.dofs.n_free;
    ws.r.resize(n, 0.0);
    ws.du.resize(n, 0.0);
    let mut e0 = 0.0f64;
    let mut e_last = f64::INFINITY;
    let mut r0 = 0.0f64;
    let mut freezing = settings.freeze_after > 0;
    let mut verified_once = false;
    let mut started = false;
    // the line search's full-step trial assembles the residual and, unless the step is
    // expected to converge, the tangent: when it accepts s = 1, the next iteration starts
    // from that assembly instead of repeating it (and adds the tangent only if it must go on)
    let mut assembled = Assembled::Nothing;
    for k in 0..=settings.max_iterations {
        if assembled == Assembled::Nothing {
            asm.assemble(model, &state.u, t, &mut state.alphas, &mut state.contact, true)?;
            assembled = Assembled::Full;
        }
        if !started {
            let retry = attempt > 0 && !predicted;
            let pushed_in = touching_pushed_in(model, asm, state, t, ws)?;
            if hold_first_correction(&mut state.contact, model, (predicted, retry), &pushed_in, &mut ws.held) > 0 {
                asm.assemble(model, &state.u, t, &mut state.alphas, &mut state.contact, true)?;
            }
            ws.watch.start(&state.contact);
            ws.frozen.clear();
            ws.frozen.resize(state.contact.signature_len(), false);
            started = true;
        }
        asm.free_residual(&mut ws.r);
        let rn = norm(&ws.r);
        if !rn.is_finite() {
            return Err(NewtonFailure::NonFinite);
        }
        ws.residuals.push(rn);
        let fref = reference_force(model, asm, t).max(reference_floor);
        if k == 0 {
            r0 = rn;
        }
        let tol = (settings.residual_tol * fref)
            .max(settings.residual_abs)
            .max(asm.roundoff());
        let res_ok = rn <= tol;
        let energy_ok = k > 0 && e_last <= settings.energy_tol * e0.max(f64::MIN_POSITIVE);
        if res_ok && (energy_ok || k == 0 || rn <= settings.residual_abs.max(asm.roundoff())) {
            let frozen = state.contact.frozen_count();
            if frozen == 0 {
                return Ok(Converged {
                    iterations: k,
                    residuals: ws.residuals.clone(),
                    reference: fref,
                    frozen: ws.frozen.iter().filter(|f| **f).count(),
                    augmentations: 0,
                });
            }
            // release the frozen states (keeping admissible segments) and check them; points
            // held for the first correction of a predicted start (only ever at k = 0) are
            // checked alike but are not reported as frozen (they were not chattering)
            let chattering = frozen - ws.held.len();
            state.contact.verify_frozen();
            asm.assemble(model, &state.u, t, &mut state.alphas, &mut state.contact, true)?;
            assembled = Assembled::Full;
            asm.free_residual(&mut ws.r);
            let rv = norm(&ws.r);
            if rv <= tol {
                ws.residuals.push(rv);
                return Ok(Converged {
                    iterations: k,
                    residuals: ws.residuals.clone(),
                    reference: fref,
                    frozen: chattering,
                    augmentations: 0,
                });
            }
            if verified_once {
                return Err(NewtonFailure::FrozenNotVerified { residual: rv });
            }
            // go on from here with every point free to choose (no more freezing)
            state.contact.unfreeze();
            verified_once = true;
            freezing = false;
            e0 = 0.0;
        }
        if rn > settings.divergence_factor * r0.max(fref) {
            return Err(NewtonFailure::Diverged { residual: rn });
        }
        if k == settings.max_iterations {
            break;
        }
        if assembled == Assembled::Residual {
            // the residual-only trial did not converge after all: its tangent now
            asm.assemble(model, &state.u, t, &mut state.alphas, &mut state.contact, true)?;
        }
        for (d, ri) in ws.du.iter_mut().zip(&ws.r) {
            *d = -ri;
        }
        asm.matrix.solve(&mut ws.du)?;
        let energy = ws.du.iter().zip(&ws.r).map(|(a, b)| a * b).sum::<f64>().abs();
        if e0 == 0.0 {
            e0 = energy;
        }
        e_last = energy;
        apply(&mut state.u, &asm.dofs.eq, &ws.du, 1.0);
        // the held points are free again once the first correction is computed: the line
        // search's trials (and so the next iterate) are assembled with their own state;
        // a correction made with stick held is the elastic predictor, taken in full (the
        // return mapping at its end finds the slipping points; backtracking on ‖R‖ from it
        // would undo the motion the stick tangent predicted)
        let elastic_predictor = state.contact.stick_held_count() > 0;
        for flat in ws.held.drain(..) {
            state.contact.release(flat);
        }
        // Will the full step converge? Then its trial needs no tangent (one fewer per
        // increment): the energy test is already met by this correction and the residual,
        // reduced at the rate of the last iteration (an overestimate where convergence is
        // quadratic), falls below the tolerance. A wrong guess costs one more assembly.
        let r_prev = ws.residuals.len().checked_sub(2).map(|i| ws.residuals[i]);
        let likely_converged = k > 0
            && e_last <= settings.energy_tol * e0.max(f64::MIN_POSITIVE)
            && r_prev.is_some_and(|rp| rp > 0.0 && rn * (rn / rp) <= tol);
        let want_tangent = !likely_converged;
        let (step, reuse) = if !settings.line_search || elastic_predictor {
            (1.0, None)
        } else {
            // g(0) = Δu·R(u) < 0 along a descent direction (a symmetric positive tangent)
            let g0 = ws.du.iter().zip(&ws.r).map(|(a, b)| a * b).sum::<f64>();
            // the slope is that of an energy only for a conservative iterate (no frictional
            // slip): elsewhere the residual norm is the merit
            let slope_ok =
                settings.line_search_rule == LineSearch::Slope && g0 < 0.0 && state.contact.conservative(model);
            if slope_ok {
                slope_search(model, asm, state, t, ws, g0, want_tangent)?
            } else {
                residual_backtracking(model, asm, state, t, ws, rn, want_tangent)?
            }
        };
        let changes = ws.watch.observe(&state.contact, k + 1);
        // frozen decisions change what the next assembly computes
        let froze = freezing
            && ws
                .watch
                .freeze_chattering(&mut state.contact, settings.freeze_after, &mut ws.frozen)
                > 0;
        assembled = match (reuse, froze) {
            (Some(true), false) => Assembled::Full,
            (Some(false), false) => Assembled::Residual,
            _ => Assembled::Nothing,
        };
        let keep_going = record(IterationRecord {
            increment,
            attempt,
            t,
            iteration: k + 1,
            residual: rn,
            energy,
            reference: fref,
            line_search: step,
            active_set_changes: changes,
        });
        if !keep_going {
            break;
        }
    }
    let iterations = ws.residuals.len() - 1;
    if ws.watch.cycling(3) {
        let points = ws.watch.report(&state.contact, model, usize::MAX).len();
        return Err(NewtonFailure::ActiveSetCycle { iterations, points });
    }
    Err(NewtonFailure::MaxIterations { iterations })
}

/// The touching points (see [`touching_points`]) that a first correction with them open
/// pushes into their master: one linear solve and one residual assembly at the trial, then
/// the first iterate is assembled again (nothing is done when no point touches).
fn touching_pushed_in(
    model: &Model,
    asm: &mut Assembler,
    state: &mut TrialState,
    t: f64,
    ws: &mut Workspace,
) -> Result<Vec<usize>, NewtonFailure> {
    let touching = touching_points(&state.contact);
    if touching.is_empty() {
        return Ok(touching);
    }
    asm.free_residual(&mut ws.r);
    for (d, ri) in ws.du.iter_mut().zip(&ws.r) {
        *d = -ri;
    }
    asm.matrix.solve(&mut ws.du)?;
    apply(&mut state.u, &asm.dofs.eq, &ws.du, 1.0);
    asm.assemble(model, &state.u, t, &mut state.alphas, &mut state.contact, false)?;
    let closed = |flat: &usize| {
        let (ip, is) = state.contact.point_index(*flat);
        state.contact.current[ip][is]
            .eval
            .is_some_and(|e| e.state != crate::contact::law::ContactState::Open)
    };
    let pushed: Vec<usize> = touching.into_iter().filter(closed).collect();
    apply(&mut state.u, &asm.dofs.eq, &ws.du, -1.0);
    asm.assemble(model, &state.u, t, &mut state.alphas, &mut state.contact, true)?;
    Ok(pushed)
}

/// Backtracking on `‖R‖` (`state.u` is at `u + Δu` on entry and at `u + sΔu` on return).
/// The full-step trial assembles the tangent as well when `want_tangent`, the shorter ones
/// the residual only; returns `(s, reuse)`, `reuse = Some(with tangent)` when the full step
/// was accepted (the assembler holds that trial's assembly), `None` otherwise.
fn residual_backtracking(
    model: &Model,
    asm: &mut Assembler,
    state: &mut TrialState,
    t: f64,
    ws: &mut Workspace,
    rn: f64,
    want_tangent: bool,
) -> Result<(f64, Option<bool>), NewtonFailure> {
    let mut step = 1.0;
    for _ in 0..8 {
        let full = step == 1.0 && want_tangent;
        asm.assemble(model, &state.u, t, &mut state.alphas, &mut state.contact, full)?;
        asm.free_residual(&mut ws.r);
        let rt = norm(&ws.r);
        if rt.is_finite() && rt <= (1.0 - 1e-4 * step) * rn {
            return Ok((step, (step == 1.0).then_some(full)));
        }
        // take back half of the current step (no copy of u on the hot path)
        apply(&mut state.u, &asm.dofs.eq, &ws.du, -0.5 * step);
        step *= 0.5;
    }
    Ok((step, None))
}

/// Regula falsi (Illinois) on the slope `g(s) = Δu·R(u + sΔu)` until
/// `|g(s)| ≤ 0.8 |g(0)|` (see [`LineSearch::Slope`]); `s = 1` when the full step already
/// meets it or still descends. At most 8 assemblies (the full-step one with the tangent when
/// `want_tangent`, to be reused when `s = 1` is accepted: the second value returned, as in
/// [`residual_backtracking`]); a non-finite residual
/// halves the step.
fn slope_search(
    model: &Model,
    asm: &mut Assembler,
    state: &mut TrialState,
    t: f64,
    ws: &mut Workspace,
    g0: f64,
    want_tangent: bool,
) -> Result<(f64, Option<bool>), NewtonFailure> {
    const ETA: f64 = 0.8;
    let (mut s_lo, mut g_lo) = (0.0, g0);
    let mut s_hi = 1.0;
    let mut g_hi = f64::NAN;
    let mut s = 1.0;
    let mut side = 0i8;
    for _ in 0..8 {
        let full = s == 1.0 && want_tangent;
        asm.assemble(model, &state.u, t, &mut state.alphas, &mut state.contact, full)?;
        asm.free_residual(&mut ws.r);
        let g = ws.du.iter().zip(&ws.r).map(|(a, b)| a * b).sum::<f64>();
        let next = if !g.is_finite() {
            0.5 * s
        } else {
            if g.abs() <= ETA * g0.abs() || (s == 1.0 && g < 0.0) {
                return Ok((s, (s == 1.0).then_some(full)));
            }
            // keep the root of g bracketed in [s_lo, s_hi]
            if g < 0.0 {
                (s_lo, g_lo) = (s, g);
                if side == -1 {
                    g_hi *= 0.5;
                }
                side = -1;
            } else {
                (s_hi, g_hi) = (s, g);
                if side == 1 {
                    g_lo *= 0.5;
                }
                side = 1;
            }
            if g_hi.is_finite() {
                s_hi - g_hi * (s_hi - s_lo) / (g_hi - g_lo)
            } else {
                0.5 * (s_lo + s_hi)
            }
        };
        let next = next.clamp(1e-3, 1.0);
        apply(&mut state.u, &asm.dofs.eq, &ws.du, next - s);
        s = next;
    }
    Ok((s, None))
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

fn apply(u: &mut [f64], eq: &[Option<usize>], du: &[f64], s: f64) {
    for (d, e) in eq.iter().enumerate() {
        if let Some(e) = e {
            u[d] += s * du[*e];
        }
    }
}

fn norm(v: &[f64]) -> f64 {
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
