//! The rules that keep Newton's iteration within what the method can answer: the budget
//! that grows while the active set settles, stick held where slip reverses, and a correction
//! shortened (or a prediction given up) where its end is inadmissible.

use super::{apply, Assembled, Iterate, NewtonFailure, MAX_INADMISSIBLE_HALVINGS};
use crate::contact::law::ContactState;

impl Iterate<'_> {
    /// How many corrections the attempt may make: `max_iterations`, plus one for each
    /// iteration in which the active set was still settling (at most
    /// `max_settling_iterations` more; none from a predicted start).
    pub(super) fn budget(&self) -> usize {
        let settling = if self.predicted { 0 } else { self.settling };
        self.settings.max_iterations + settling.min(self.settings.max_settling_iterations)
    }

    /// Count the iteration just made as settling when it changed the active set into a
    /// pattern not met before in the attempt and the residual is still falling: the lowest
    /// of the last `max_iterations` iterates is below the lowest of the `max_iterations`
    /// before them (a front moving along the contact zone, not a cycle and not a drift
    /// without progress).
    pub(super) fn count_settling(&mut self, changes: usize) {
        // a failed verification of frozen points starts the comparison afresh (the frozen
        // state's residual was not one of the free problem)
        let r = &self.ws.residuals[self.settling_from..];
        let window = self.settings.max_iterations.max(1);
        let falling = r.len() <= window || {
            let (before, recent) = r.split_at(r.len() - window);
            let before = &before[before.len().saturating_sub(window)..];
            let low = |v: &[f64]| v.iter().copied().fold(f64::INFINITY, f64::min);
            low(recent) < low(before)
        };
        if changes > 0 && self.ws.watch.new_pattern() && falling {
            self.settling += 1;
        }
    }

    /// Points whose slip reversed since the last iterate are held in stick for the next
    /// correction (then assembled again): the elastic predictor of the attempt's start,
    /// applied where it is needed again. A point whose anchor lies between two iterates —
    /// at rest under a small normal force, or where the motion reverses — is taken in slip
    /// with no tangential stiffness, the body's response carries it past the anchor, the
    /// trial reverses, and Newton alternates between the two slip directions for ever (the
    /// decisions, slip and slip, never change, so no cycle is seen). With stick held the
    /// correction brings it to its stick equilibrium, and the return mapping decides again
    /// from there (the held points are released after the correction and verified at
    /// convergence like frozen ones).
    pub(super) fn hold_reversing_slip(&mut self) -> Result<(), NewtonFailure> {
        let ws = &mut *self.ws;
        let n = self.state.contact.signature_len();
        ws.slip_sign.resize(n, 0);
        let mut reversed = Vec::new();
        let signs = self
            .state
            .contact
            .current
            .iter()
            .zip(&self.model.contacts)
            .flat_map(|(pts, pair)| {
                pts.iter().map(move |p| match p.eval {
                    Some(e) if pair.law.mu > 0.0 && e.state == ContactState::Slip && e.t1 != 0.0 => e.t1.signum() as i8,
                    _ => 0,
                })
            });
        for (flat, (now, before)) in signs.zip(ws.slip_sign.iter_mut()).enumerate() {
            if now != 0 && *before == -now {
                reversed.push(flat);
            }
            *before = now;
        }
        if reversed.is_empty() {
            return Ok(());
        }
        for &flat in &reversed {
            self.state.contact.hold_stick(flat);
        }
        self.ws.held.extend(reversed);
        self.assemble(true)?;
        self.assembled = Assembled::Full;
        Ok(())
    }

    /// The end of the last correction is inadmissible (an element inverted, or its enhanced
    /// strains found no equilibrium, or contact points went through their master): go back to the iterate before it and take half the
    /// correction. A Newton step is a prediction from the tangent at its start, and a
    /// prediction far beyond where that tangent holds — a soft body under a stiff penalty
    /// pushed through by one node's contact force — says nothing about the solution; the
    /// solution itself is admissible, so a shorter step toward it is too. Fails with the
    /// element's error after [`MAX_INADMISSIBLE_HALVINGS`] halvings — and at once from a
    /// predicted start (unless `target.shorten_predicted`): the extrapolation put the
    /// iterate where the tangent does not hold, and the converged state is the better start
    /// (shortened steps from a bad prediction creep along the edge of the admissible set: on
    /// the 120×4 strip with μ = 0.2 they cost 87 attempts of 30 iterations, 2.6× the run's
    /// time). The caller retries from the converged state, and if that fails too, from the
    /// prediction again with shortening, before it cuts the step back.
    pub(super) fn shorten(&mut self, failure: NewtonFailure) -> Result<(), NewtonFailure> {
        if self.abandon_bad_prediction || self.shortened < 0.5f64.powi(MAX_INADMISSIBLE_HALVINGS as i32 - 1) {
            return Err(failure);
        }
        let ws = &mut *self.ws;
        self.state.u.copy_from_slice(&ws.u_before);
        self.state.alphas.copy_from_slice(&ws.alphas_before);
        ws.du.iter_mut().for_each(|d| *d *= 0.5);
        self.shortened *= 0.5;
        apply(&mut self.state.u, &self.asm.dofs.eq, &ws.du, 1.0);
        Ok(())
    }
}
