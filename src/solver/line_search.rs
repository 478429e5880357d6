//! Globalising Newton's corrections: a watchdog over the merit function of the whole
//! system, `φ = ‖R(u, N, T)‖² + Σ C²` (equilibrium with the contact force unknowns and
//! their complementarity residuals: [`crate::assembly::Assembler::merit`]), with a
//! backtracking line search when the watch fails; always on.
//!
//! The watchdog (Chamberlain, Powell, Lemaréchal & Pedersen, Math Prog Study 16 (1982)
//! 1–17; Nocedal & Wright, Numerical Optimization (2006) §15.6): from a saved iterate `x_c`,
//! Newton takes up to [`RELAXED`] full steps without testing them; as soon as one reaches
//! `φ ≤ (1 − 2σ) φ(x_c)` the watch ends there. Full steps keep Newton's quadratic
//! convergence where the merit rises for a while before it falls — a beam rotating under
//! its load, whose first correction stretches it, raises `‖R‖` a millionfold — and a
//! semismooth Newton's active-set changes may raise it for an iteration too. If the watch
//! fails, Newton goes back to `x_c` and backtracks along its correction: a trial is
//! accepted by the Armijo test `φ(s) ≤ (1 − 2σ s) φ(x_c)` with `σ = 10⁻⁴` (the Newton
//! direction of the mixed system descends `φ`: `φ'(0) = −2φ` where the active set holds),
//! a rejected step shrinks to the minimiser of the quadratic through `φ(0)`, `φ'(0)` and
//! `φ(s)`, kept within `[0.1 s, 0.5 s]` (Dennis & Schnabel (1996) §6.3.2). An
//! inadmissible trial — an element inverted or without enhanced-strain equilibrium, a
//! contact point through its master — has `φ = ∞`: the step is halved, in the watch too.
//! Each trial is assembled with its tangent, so an accepted trial is the next iterate's
//! assembly.
//!
//! Once the attempt's active set returns to a pattern it met before — a cycle, which a
//! semismooth Newton method whose full steps converge never makes (Hintermüller, Ito &
//! Kunisch 2003, §4) — the watch ends and every further correction is searched
//! monotonically (Armijo from the current iterate): the merit then decreases at every
//! iterate, and a cycle of full steps cannot repeat.
//!
//! After [`MAX_TRIALS`] trials without a decrease, the last admissible trial is taken and
//! the failure counted ([`super::newton::Converged::line_search_failures`], the run's
//! summary); when no trial was admissible the attempt fails with the reason.

use super::newton::{apply, inadmissible, Iterate, NewtonFailure};
use super::state::TrialState;

/// Full steps the watchdog takes from a saved iterate before it goes back to it.
pub const RELAXED: usize = 3;
/// Trials per correction (the shortest is `0.5^(MAX_TRIALS−1)` of it or less).
pub const MAX_TRIALS: usize = 12;
const SIGMA: f64 = 1e-4;

/// What the watchdog keeps of the iterate it watches from (allocated once per run).
#[derive(Debug, Default)]
pub struct Watchdog {
    /// The saved iterate, its correction and where that correction starts from.
    saved: Option<TrialState>,
    du: Vec<f64>,
    u_before: Vec<f64>,
    alphas_before: Vec<f64>,
    /// The merit of the saved iterate, and the full steps taken since (`None`: no watch).
    merit: f64,
    relaxed: Option<usize>,
    /// The attempt met an active set again (a cycle): every correction is searched
    /// monotonically from then on.
    monotone: bool,
}

impl Watchdog {
    /// No watch under way (at the start of an attempt).
    pub fn reset(&mut self) {
        self.relaxed = None;
        self.monotone = false;
    }

    /// The attempt's active set returned to a pattern met before: no more full steps
    /// without a test (module docs).
    pub fn go_monotone(&mut self) {
        self.monotone = true;
    }
}

impl<S: crate::model::Dim> Iterate<'_, S> {
    /// Take the correction in `ws.du` from the iterate saved in `ws.u_before` (and the
    /// contact system's [`crate::contact::system::ContactSystem::save_iterate`]) under the
    /// watchdog (module docs); on return the state is at the step taken, assembled with its
    /// tangent. Returns the step.
    pub(super) fn globalise(&mut self) -> Result<f64, NewtonFailure> {
        let phi0 = *self.ws.merits.last().expect("the iterate was tested");
        if self.ws.continuation.on() {
            self.ws.watchdog.relaxed = None;
            // a pseudo-time step is taken whole, halved only where inadmissible
            return self.line_search(phi0, f64::INFINITY);
        }
        let monotone = self.ws.watchdog.monotone;
        let relaxed = match self.ws.watchdog.relaxed {
            Some(n) if n >= RELAXED || monotone => return self.back_to_watch(),
            Some(n) => n,
            None if monotone => return self.line_search(phi0, phi0),
            None => {
                self.start_watch(phi0);
                0
            }
        };
        let tangent = !self.expects_convergence();
        self.move_to(1.0);
        match self.assemble(tangent) {
            Ok(()) if !tangent => self.tangent_skipped(),
            Ok(()) => {}
            Err(f) if inadmissible(&f) => {
                self.ws.watchdog.relaxed = None;
                return self.line_search(phi0, phi0);
            }
            Err(f) => return Err(f),
        }
        let phi = self.asm.merit(&self.state.contact);
        let watch = &mut self.ws.watchdog;
        watch.relaxed = match phi <= (1.0 - 2.0 * SIGMA) * watch.merit {
            true => None,
            false => Some(relaxed + 1),
        };
        Ok(1.0)
    }

    /// Save the current iterate and its correction as the watch's start.
    fn start_watch(&mut self, phi0: f64) {
        let ws = &mut *self.ws;
        let w = &mut ws.watchdog;
        match &mut w.saved {
            Some(saved) => saved.copy_iterate_from(self.state),
            None => w.saved = Some(self.state.clone()),
        }
        w.du.clone_from(&ws.du);
        w.u_before.clone_from(&ws.u_before);
        w.alphas_before.clone_from(&ws.alphas_before);
        w.merit = phi0;
        w.relaxed = Some(0);
    }

    /// The watch failed: back to its saved iterate, and backtrack along its correction.
    fn back_to_watch(&mut self) -> Result<f64, NewtonFailure> {
        let ws = &mut *self.ws;
        let w = &mut ws.watchdog;
        let saved = w.saved.as_ref().expect("a watch saved its iterate");
        self.state.copy_iterate_from(saved);
        ws.du.clone_from(&w.du);
        ws.u_before.clone_from(&w.u_before);
        ws.alphas_before.clone_from(&w.alphas_before);
        w.relaxed = None;
        let phi = w.merit;
        self.line_search(phi, phi)
    }

    /// Backtrack along the correction from merit `phi0`, accepting by the Armijo test
    /// against `reference` (module docs).
    fn line_search(&mut self, phi0: f64, reference: f64) -> Result<f64, NewtonFailure> {
        let mut s = 1.0;
        let mut last_failure = None;
        for trial in 0..MAX_TRIALS {
            self.move_to(s);
            let phi = match self.assemble(true) {
                Ok(()) => self.asm.merit(&self.state.contact),
                Err(f) if inadmissible(&f) => {
                    last_failure = Some(f);
                    f64::INFINITY
                }
                Err(f) => return Err(f),
            };
            if phi.is_finite() {
                last_failure = None;
                if phi <= reference - 2.0 * SIGMA * s * phi0 {
                    return Ok(s);
                }
            }
            if trial + 1 == MAX_TRIALS {
                break;
            }
            s = next_step(s, phi0, phi);
        }
        match last_failure {
            // the shortest trial was admissible: taken, and counted
            None => {
                self.ws.line_search_failures += 1;
                Ok(s)
            }
            Some(f) => Err(f),
        }
    }

    /// The state a fraction `s` along the correction: displacements, enhanced-strain
    /// parameters from the start of the correction, contact force unknowns.
    fn move_to(&mut self, s: f64) {
        let ws = &mut *self.ws;
        self.state.u.copy_from_slice(&ws.u_before);
        self.state.alphas.copy_from_slice(&ws.alphas_before);
        apply(&mut self.state.u, &self.asm.dofs.eq, &ws.du, s);
        self.state.contact.to_step(s);
    }
}

/// The next trial step after `s` was rejected with merit `phi` (`phi0` at `s = 0`, slope
/// `−2 phi0`): the minimiser of the interpolating quadratic within `[0.1 s, 0.5 s]`; half
/// the step when `phi` is not finite.
fn next_step(s: f64, phi0: f64, phi: f64) -> f64 {
    if !phi.is_finite() {
        return 0.5 * s;
    }
    // φ(σ) ≈ φ0 − 2 φ0 σ + a σ², a = (φ(s) − φ0 + 2 φ0 s)/s²: minimiser φ0/a
    let a = (phi - phi0 + 2.0 * phi0 * s) / (s * s);
    let s_min = if a > 0.0 { phi0 / a } else { 0.5 * s };
    s_min.clamp(0.1 * s, 0.5 * s)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_next_step_minimises_the_quadratic_within_its_bounds() {
        // φ(s) = (1 − s)² · 4 + tiny: the full step overshoots to φ(1) = 4 + 4 = 8
        // (quadratic through φ0 = 4, slope −8, φ(1) = 8: a = 12, minimiser 1/3)
        assert!((next_step(1.0, 4.0, 8.0) - 1.0 / 3.0).abs() < 1e-12);
        // far overshoot: at least a tenth
        assert_eq!(next_step(1.0, 1.0, 1e12), 0.1);
        // inadmissible: half
        assert_eq!(next_step(0.5, 1.0, f64::INFINITY), 0.25);
        // barely worse: at most half
        assert_eq!(next_step(1.0, 1.0, 0.0), 0.5);
    }
}
