//! Newton–Raphson for one load increment, with residual and energy-norm criteria and an
//! optional backtracking line search.

use super::settings::NewtonSettings;
use super::state::TrialState;
use crate::assembly::sparse::LinearError;
use crate::assembly::{Assembler, AssemblyError};
use crate::model::Model;
use crate::record::IterationRecord;

/// Why an increment failed (the stepping driver cuts the step back on these).
#[derive(Debug, Clone, thiserror::Error)]
pub enum NewtonFailure {
    #[error("no convergence in {iterations} iterations")]
    MaxIterations { iterations: usize },
    #[error("residual diverged (‖R‖ = {residual:.3e})")]
    Diverged { residual: f64 },
    #[error("non-finite residual")]
    NonFinite,
    #[error(transparent)]
    Element(#[from] AssemblyError),
    #[error(transparent)]
    Linear(#[from] LinearError),
}

/// Outcome of a converged increment (`residuals`: `‖R‖` at each iterate).
#[derive(Debug, Clone)]
pub struct Converged {
    pub iterations: usize,
    pub residuals: Vec<f64>,
    pub reference: f64,
}

/// Norm of the reactions (internal forces at prescribed DOFs) and of the applied loads.
fn reference_force(model: &Model, asm: &Assembler, t: f64) -> f64 {
    let reac: f64 = asm.dofs.prescribed.iter().map(|&d| asm.r_full[d].powi(2)).sum();
    let load: f64 = model.loads.iter().map(|l| l.ramp.at(t).powi(2)).sum();
    (reac + load).sqrt()
}

/// Iterate to equilibrium at time `t` starting from `state` (prescribed DOFs are set here).
/// `on_iteration` receives one record per correction; failures leave `state` dirty (the
/// caller restores the last converged one).
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
    residuals: &mut Vec<f64>,
) -> Result<Converged, NewtonFailure> {
    residuals.clear();
    for p in &model.prescribed {
        state.u[p.dof] = p.ramp.at(t);
    }
    let n = asm.dofs.n_free;
    let mut r = vec![0.0; n];
    let mut du = vec![0.0; n];
    let mut e0 = 0.0f64;
    let mut e_last = f64::INFINITY;
    let mut r0 = 0.0f64;
    let mut signature = state.contact.signature();
    for k in 0..=settings.max_iterations {
        asm.assemble(model, &state.u, t, &mut state.alphas, &mut state.contact, true)?;
        asm.free_residual(&mut r);
        let rn = norm(&r);
        if !rn.is_finite() {
            return Err(NewtonFailure::NonFinite);
        }
        residuals.push(rn);
        let fref = reference_force(model, asm, t).max(reference_floor);
        if k == 0 {
            r0 = rn;
        }
        let res_ok = rn <= (settings.residual_tol * fref).max(settings.residual_abs);
        let energy_ok = k > 0 && e_last <= settings.energy_tol * e0.max(f64::MIN_POSITIVE);
        if res_ok && (energy_ok || k == 0 || rn <= settings.residual_abs) {
            return Ok(Converged {
                iterations: k,
                residuals: residuals.clone(),
                reference: fref,
            });
        }
        if rn > settings.divergence_factor * r0.max(fref) {
            return Err(NewtonFailure::Diverged { residual: rn });
        }
        if k == settings.max_iterations {
            break;
        }
        for (d, ri) in du.iter_mut().zip(&r) {
            *d = -ri;
        }
        asm.matrix.solve(&mut du)?;
        let energy = du.iter().zip(&r).map(|(a, b)| a * b).sum::<f64>().abs();
        if k == 0 {
            e0 = energy;
        }
        e_last = energy;
        let mut step = 1.0;
        apply(&mut state.u, &asm.dofs.eq, &du, step);
        if settings.line_search {
            // backtrack on ‖R‖ (residual-only assemblies)
            for _ in 0..8 {
                asm.assemble(model, &state.u, t, &mut state.alphas, &mut state.contact, false)?;
                asm.free_residual(&mut r);
                let rt = norm(&r);
                if rt.is_finite() && rt <= (1.0 - 1e-4 * step) * rn {
                    break;
                }
                // take back half of the current step (no copy of u on the hot path)
                apply(&mut state.u, &asm.dofs.eq, &du, -0.5 * step);
                step *= 0.5;
            }
        }
        let sig = state.contact.signature();
        let changes = sig.iter().zip(&signature).filter(|(a, b)| a != b).count();
        signature = sig;
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
    Err(NewtonFailure::MaxIterations {
        iterations: residuals.len() - 1,
    })
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
