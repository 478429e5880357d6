//! Line searches along a Newton correction `Δu`: backtracking on `‖R‖`, or regula falsi on
//! the slope `Δu·R(u + sΔu)` where the iterate has an energy.

use super::newton::{apply, assemble_at, norm, NewtonFailure, Workspace};
use super::state::TrialState;
use crate::assembly::Assembler;
use crate::model::Model;

/// Backtracking on `‖R‖` (`state.u` is at `u + Δu` on entry and at `u + sΔu` on return).
/// The full-step trial assembles the tangent as well when `want_tangent`, the shorter ones
/// the residual only; returns `(s, reuse)`, `reuse = Some(with tangent)` when the full step
/// was accepted (the assembler holds that trial's assembly), `None` otherwise.
pub(super) fn residual_backtracking(
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
        assemble_at(model, asm, state, t, full)?;
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
/// `|g(s)| ≤ 0.8 |g(0)|` (see [`crate::settings::LineSearch::Slope`]); `s = 1` when the full
/// step already meets it or still descends. At most 8 assemblies (the full-step one with the
/// tangent when `want_tangent`, to be reused when `s = 1` is accepted: the second value
/// returned, as in [`residual_backtracking`]); a non-finite residual halves the step.
pub(super) fn slope_search(
    model: &Model,
    asm: &mut Assembler,
    state: &mut TrialState,
    t: f64,
    ws: &mut Workspace,
    g0: f64,
    want_tangent: bool,
) -> Result<(f64, Option<bool>), NewtonFailure> {
    const ETA: f64 = 0.8;
    let mut bracket = Bracket::new(g0);
    let mut s = 1.0;
    for _ in 0..8 {
        let full = s == 1.0 && want_tangent;
        assemble_at(model, asm, state, t, full)?;
        asm.free_residual(&mut ws.r);
        let g = ws.du.iter().zip(&ws.r).map(|(a, b)| a * b).sum::<f64>();
        let next = if !g.is_finite() {
            0.5 * s
        } else {
            if g.abs() <= ETA * g0.abs() || (s == 1.0 && g < 0.0) {
                return Ok((s, (s == 1.0).then_some(full)));
            }
            bracket.next(s, g)
        };
        let next = next.clamp(1e-3, 1.0);
        apply(&mut state.u, &asm.dofs.eq, &ws.du, next - s);
        s = next;
    }
    Ok((s, None))
}

/// The root of the slope kept bracketed in `[s_lo, s_hi]` (Illinois variant of regula falsi:
/// the value at an end kept twice in a row is halved).
struct Bracket {
    s_lo: f64,
    g_lo: f64,
    s_hi: f64,
    g_hi: f64,
    side: i8,
}

impl Bracket {
    fn new(g0: f64) -> Self {
        Bracket {
            s_lo: 0.0,
            g_lo: g0,
            s_hi: 1.0,
            g_hi: f64::NAN,
            side: 0,
        }
    }

    /// The next trial step after the slope `g` at `s`.
    fn next(&mut self, s: f64, g: f64) -> f64 {
        if g < 0.0 {
            (self.s_lo, self.g_lo) = (s, g);
            if self.side == -1 {
                self.g_hi *= 0.5;
            }
            self.side = -1;
        } else {
            (self.s_hi, self.g_hi) = (s, g);
            if self.side == 1 {
                self.g_lo *= 0.5;
            }
            self.side = 1;
        }
        if self.g_hi.is_finite() {
            self.s_hi - self.g_hi * (self.s_hi - self.s_lo) / (self.g_hi - self.g_lo)
        } else {
            0.5 * (self.s_lo + self.s_hi)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::Bracket;

    #[test]
    fn regula_falsi_finds_the_root_of_a_linear_slope() {
        // g(s) = 2 (s − 0.3) − full step overshoots, the secant lands on the root
        let g = |s: f64| 2.0 * (s - 0.3);
        let mut b = Bracket::new(g(0.0));
        let s = b.next(1.0, g(1.0));
        assert!((s - 0.3).abs() < 1e-12, "{s}");
    }

    #[test]
    fn illinois_halves_a_stale_end() {
        // a convex slope: the secant stays on one side, the stale end is halved
        let g = |s: f64| s * s - 0.04;
        let mut b = Bracket::new(g(0.0));
        let mut s = b.next(1.0, g(1.0));
        for _ in 0..20 {
            s = b.next(s, g(s));
        }
        assert!((s - 0.2).abs() < 1e-8, "{s}");
    }
}
