//! Pseudo-transient continuation (Ψtc) for the corrections Newton's method cannot take: the
//! correction solves `(K + D/δ) Δu = −R` instead of `K Δu = −R`, `D` the absolute diagonal
//! of the tangent (a drag of every unknown against its last iterate, in the tangent's own
//! units, so the rule is the same in any units and at any placement) and `1/δ` a pseudo-time
//! step's inverse relative to it (Kelley & Keyes, SIAM J Numer Anal 35 (1998) 508–523;
//! Coffey, Kelley & Keyes, SIAM J Sci Comput 25 (2003) 553–569). The steps are taken whole
//! (halved only where inadmissible: an inverted element, a tunnelled point), as Ψtc takes
//! them: along a direction the tangent does not hold, no merit function decreases until
//! contact closes, so a line search cannot drive that motion and the pseudo-time does.
//!
//! When it starts (in an attempt, for the rest of it): after a line search that found no
//! decrease along Newton's correction — the tangent singular along the residual (a body held
//! by nothing but contact that has not closed: a belt laid on a drum it does not yet touch)
//! or a kink of the contact law that the correction does not see. Starting it already where
//! the correction is longer than the model was tried and not kept: the spatial strip on
//! 24×1, whose long corrections the line search takes to convergence, then needed 4–5
//! cut-backs.
//!
//! How it ramps out: after each step `1/δ ← (1/δ) · (‖R_{k+1}‖/‖R_k‖) / ν` — the switched
//! evolution relaxation of Mulder & van Leer (J Comput Phys 59 (1985) 232–246), which grows
//! the pseudo-time step as the residual falls, accelerated by Marquardt's factor ν = 10
//! (J SIAM 11 (1963) 431–441) so that a stalled residual (a body still moving towards its
//! support) lengthens the step too — and the drag is dropped once `1/δ` < [`OFF_BELOW`]:
//! the last corrections are Newton's, with its rate.
//!
//! What it leaves: the residual every convergence test judges is the unshifted one, so an
//! accepted increment is in equilibrium without any drag (unlike a stabilisation with a
//! fixed damping, no artificial force remains in the answer; the equilibrium check of each
//! converged increment says so). The drag's work along the steps taken, `Σ s² Δuᵀ(D/δ)Δu`,
//! and the number of shifted corrections are recorded per increment (`/increment`
//! `stabilised_corrections`, `stabilisation_work`) and summed in the run's summary, as a
//! code reports the energy its contact stabilisation dissipated.

use crate::assembly::Assembler;
use crate::linalg::factorization::LinearError;
use crate::model::Dim;

/// `1/δ` at the first shifted correction (Marquardt's starting λ, 1963).
pub const START: f64 = 1e-2;
/// The factor by which `1/δ` falls after each shifted step that leaves the residual as it
/// was (Marquardt's ν).
pub const NU: f64 = 10.0;
/// `1/δ` below which the drag is dropped: a shift of 1e-10 of the diagonal changes the
/// correction by about that fraction, below the default residual tolerance (1e-9 of the
/// force scale), so the correction is Newton's to the digits the test sees.
pub const OFF_BELOW: f64 = 1e-10;
/// The largest `1/δ`: a drag 1e8 times the diagonal leaves steps of about 1e-8 of an
/// unshifted one, near the residual tolerance; more would only freeze the iterate.
pub const MOST: f64 = 1e8;

/// The continuation's state within one attempt.
#[derive(Debug, Default)]
pub struct Continuation {
    /// `1/δ`, relative to the tangent's diagonal; `None`: corrections are Newton's.
    factor: Option<f64>,
    /// The shifted corrections of the attempt.
    pub corrections: usize,
    /// The drag's work along the steps taken.
    pub work: f64,
    /// The shift of the last shifted correction, per free unknown (for its work).
    shift: Vec<f64>,
    slots: Vec<usize>,
    saved: Vec<f64>,
}

impl Continuation {
    /// Corrections are Newton's again (at the start of an attempt).
    pub fn reset(&mut self) {
        self.factor = None;
        self.corrections = 0;
        self.work = 0.0;
    }

    /// Shift the corrections from now on (a line search found no decrease).
    pub fn engage(&mut self) {
        if self.factor.is_none() {
            self.factor = Some(START);
        }
    }

    /// Whether the next correction is shifted (dropping the shift once it ramped out).
    fn current(&self) -> Option<f64> {
        self.factor
    }

    /// Whether corrections are shifted.
    pub fn on(&self) -> bool {
        self.factor.is_some()
    }

    /// Solve for the correction into `b` (holding `−R`): shifted while the continuation is
    /// on, Newton's otherwise. `rn` is the iterate's residual norm.
    pub fn solve<S: Dim>(&mut self, asm: &mut Assembler<S>, b: &mut [f64]) -> Result<(), LinearError> {
        let Some(factor) = self.current() else {
            return asm.solve(b);
        };
        self.corrections += 1;
        self.shift_diagonal(asm, factor);
        let solved = asm.solve(b);
        for (&slot, &v) in self.slots.iter().zip(&self.saved) {
            asm.matrix.values[slot] = v;
        }
        solved
    }

    /// `K_ii += factor · |K_ii|` over the free unknowns (the mean `|K_ii|` where a diagonal
    /// is zero), the values overwritten kept to be restored.
    fn shift_diagonal<S: Dim>(&mut self, asm: &mut Assembler<S>, factor: f64) {
        let n = asm.dofs.n_free;
        let m = &mut asm.matrix;
        self.slots.clear();
        self.slots
            .extend((0..n).map(|i| m.index(i, i).expect("the pattern keeps every diagonal")));
        self.saved.clear();
        self.saved.extend(self.slots.iter().map(|&s| m.values[s]));
        let mean = self.saved.iter().map(|v| v.abs()).sum::<f64>() / n.max(1) as f64;
        self.shift.clear();
        self.shift.extend(
            self.saved
                .iter()
                .map(|v| factor * if *v != 0.0 { v.abs() } else { mean }),
        );
        for (&slot, &s) in self.slots.iter().zip(&self.shift) {
            m.values[slot] += s;
        }
    }

    /// Step `s` of the correction `du` was taken and changed the residual by the factor
    /// `growth`: count the drag's work along it and update `1/δ` (module docs), dropping the
    /// shift once it is below [`OFF_BELOW`].
    pub fn took(&mut self, du: &[f64], s: f64, growth: f64) {
        let Some(f) = self.factor else { return };
        if self.shift.len() == du.len() {
            self.work += s * s * du.iter().zip(&self.shift).map(|(d, k)| k * d * d).sum::<f64>();
        }
        let next = match growth.is_finite() {
            true => (f * growth / NU).min(MOST),
            false => (f * NU).min(MOST),
        };
        self.factor = (next >= OFF_BELOW).then_some(next);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_drag_ramps_out_as_the_residual_falls_or_stalls_and_rises_with_it() {
        let mut c = Continuation::default();
        assert!(!c.on());
        c.engage();
        assert_eq!(c.current(), Some(START));
        // a stalled residual: 1/δ falls by ν
        c.took(&[], 1.0, 1.0);
        assert!((c.current().unwrap() - START / NU).abs() < 1e-18);
        // a residual that rose 1000×: 1/δ rises by 100
        c.took(&[], 1.0, 1e3);
        assert!((c.current().unwrap() - START * 10.0).abs() < 1e-12);
        // never above MOST
        c.took(&[], 1.0, 1e30);
        assert_eq!(c.current(), Some(MOST));
        // a non-finite growth counts as a rise by ν
        c.factor = Some(1.0);
        c.took(&[], 1.0, f64::NAN);
        assert_eq!(c.current(), Some(NU));
        // falling fast: dropped once below OFF_BELOW, and engaging again starts over
        c.factor = Some(10.0 * OFF_BELOW);
        c.took(&[], 1.0, 0.5);
        assert!(!c.on());
        c.engage();
        assert_eq!(c.current(), Some(START));
        c.reset();
        assert!(!c.on());
        assert_eq!((c.corrections, c.work), (0, 0.0));
    }

    #[test]
    fn the_work_is_the_drag_times_the_step_squared() {
        let mut c = Continuation::default();
        c.engage();
        c.shift = vec![2.0, 0.5];
        c.took(&[1.0, -2.0], 0.5, 1.0);
        // s² Σ k_i du_i² = 0.25 (2·1 + 0.5·4)
        assert!((c.work - 1.0).abs() < 1e-15);
        // a Newton correction adds nothing
        c.factor = None;
        c.took(&[1.0, -2.0], 1.0, 1.0);
        assert!((c.work - 1.0).abs() < 1e-15);
    }
}
