//! The contact force unknowns of Newton's iterate (`contact::decision`): their start
//! from the converged forces, their linearised correction and the steps along it, and the
//! copies Newton's globalisation makes of an iterate.

use super::{augmented_weights, ContactSystem, PointNow};
use crate::contact::decision::{Forces, Kink};
use crate::contact::law::ContactState;
use crate::model::Model;

impl ContactSystem {
    /// Decide every point by the penalty rule from now on (`true`: the seed's active set,
    /// [`crate::settings::ActiveSet::Penalty`]), or by the augmented forces (`false`).
    pub fn set_penalty_weights(&mut self, model: &Model, penalty: bool) {
        self.weights = model
            .contacts
            .iter()
            .map(|p| {
                if penalty {
                    (1.0, 1.0)
                } else {
                    augmented_weights(model, p)
                }
            })
            .collect();
    }

    /// Forget the current iterate (at the start of an attempt at an increment): the search
    /// grids are rebuilt once for the new increment, and the force unknowns start from the
    /// forces of the last converged increment.
    pub fn reset_current(&mut self) {
        for pair in &mut self.current {
            pair.iter_mut().for_each(|p| *p = PointNow::default());
        }
        self.grids.iter_mut().for_each(|g| *g = None);
        self.left.iter_mut().flatten().for_each(|l| *l = None);
        self.penalty_rule = false;
        self.kink = Kink::Open;
        for (forces, hist) in self.forces.iter_mut().zip(&self.committed) {
            for (f, h) in forces.iter_mut().zip(hist) {
                *f = match h.closed {
                    true => Forces {
                        normal: h.normal,
                        tangential: h.t1 / h.a11.sqrt(),
                    },
                    false => Forces::default(),
                };
            }
        }
    }

    /// Decide every point by the penalty rule (`true`) or by the augmented forces (`false`)
    /// at the next evaluations.
    pub fn use_penalty_rule(&mut self, penalty: bool) {
        self.penalty_rule = penalty;
    }

    /// Take the points at the normal kink (touching without force) on `kink`'s side at the
    /// next evaluations ([`Kink`]).
    pub fn set_kink(&mut self, kink: Kink) {
        self.kink = kink;
    }

    /// Decide the states by the force unknowns alone at the next evaluations (see
    /// [`super::point::PointProblem::warm`]).
    pub fn set_warm_start(&mut self, warm: bool) {
        self.warm = warm;
    }

    pub fn kink(&self) -> Kink {
        self.kink
    }

    /// Points open at the last evaluation that rest on their master within the geometry's
    /// precision without a force unknown: the points [`Kink::Resting`] would take closed.
    pub fn resting_points(&self) -> usize {
        let points = self.current.iter().flatten().zip(self.forces.iter().flatten());
        points.filter(|(p, f)| at_kink(p, f)).count()
    }

    /// `Σ C²` of the complementarity residuals at the last evaluation (see
    /// [`super::decision::complementarity`]).
    pub fn complementarity2(&self) -> f64 {
        self.complementarity2
    }

    /// Make the force unknowns the contact forces of the current iterate (a converged one:
    /// they are in equilibrium with the bodies, and within the tolerance of the penalty
    /// law; the penalty forces of the displacements carry the penalty's amplification of
    /// the gap's last digits, `ε δζ`). Records, monitors and the committed history take
    /// them from the points' evaluations.
    pub fn adopt_forces(&mut self) {
        for (now, forces) in self.current.iter_mut().zip(&self.forces) {
            for (p, f) in now.iter_mut().zip(forces) {
                if let Some(e) = p.eval.as_mut().filter(|e| e.state != ContactState::Open) {
                    e.normal_force = f.normal;
                    e.t1 = f.tangential * e.proj.a11.sqrt();
                }
            }
        }
    }

    /// The norm of the contact force unknowns, `√Σ (N² + t²)` (a part of the reference
    /// force of the convergence test).
    pub fn force_norm(&self) -> f64 {
        let sum: f64 = self
            .forces
            .iter()
            .flatten()
            .map(|f| f.normal * f.normal + f.tangential * f.tangential)
            .sum();
        sum.sqrt()
    }

    /// Make this system's iterate that of `other` (a system of the same model at the same
    /// increment: the history and search grids are the increment's and are not copied),
    /// without allocating — Newton's watchdog goes back to a saved iterate this way.
    pub fn copy_iterate_from(&mut self, other: &ContactSystem) {
        fn copy<T: Copy>(to: &mut [Vec<T>], from: &[Vec<T>]) {
            for (t, f) in to.iter_mut().zip(from) {
                t.copy_from_slice(f);
            }
        }
        copy(&mut self.current, &other.current);
        copy(&mut self.current_base, &other.current_base);
        copy(&mut self.pairings, &other.pairings);
        copy(&mut self.forces, &other.forces);
        copy(&mut self.forces_base, &other.forces_base);
        copy(&mut self.forces_step, &other.forces_step);
        copy(&mut self.lin, &other.lin);
        copy(&mut self.left, &other.left);
        copy(&mut self.multipliers, &other.multipliers);
        self.penalty_rule = other.penalty_rule;
        self.kink = other.kink;
        self.warm = other.warm;
        self.complementarity2 = other.complementarity2;
        self.tunnelled.clear();
        self.tunnelled.extend_from_slice(&other.tunnelled);
    }

    /// Keep the evaluation of the iterate and its force unknowns: the start of a
    /// correction (its line search's trials are paired against this iterate).
    pub fn save_iterate(&mut self) {
        for (b, c) in self.current_base.iter_mut().zip(&self.current) {
            b.copy_from_slice(c);
        }
        for (b, f) in self.forces_base.iter_mut().zip(&self.forces) {
            b.copy_from_slice(f);
        }
    }

    /// The force unknowns at the full correction `du` (global DOFs, zero where prescribed):
    /// `N + ΔN = N_ε + ∇N_ε · Δu`, `T_1 + ΔT_1 = T_1,ε + ∇T_1,ε · Δu` of the decided state
    /// (the linearised constitutive equations; zero at an open point).
    pub fn correct_forces(&mut self, du: &dyn Fn(usize) -> f64) {
        for (steps, lins) in self.forces_step.iter_mut().zip(&self.lin) {
            for (step, lin) in steps.iter_mut().zip(lins) {
                *step = match lin {
                    None => Forces::default(),
                    Some((slots, l)) => {
                        let mut n = l.normal;
                        let mut t1 = l.t1;
                        for (i, &node) in slots.nodes().iter().enumerate() {
                            for c in 0..2 {
                                let d = du(2 * node + c);
                                n += l.d_normal[2 * i + c] * d;
                                t1 += l.d_t1[2 * i + c] * d;
                            }
                        }
                        Forces {
                            normal: n,
                            tangential: t1 / l.a11.sqrt(),
                        }
                    }
                };
            }
        }
    }

    /// Go back to the iterate kept by [`Self::save_iterate`], with the force unknowns a
    /// fraction `s` of the way to the full correction's.
    pub fn to_step(&mut self, s: f64) {
        for (c, b) in self.current.iter_mut().zip(&self.current_base) {
            c.copy_from_slice(b);
        }
        for ((f, b), st) in self.forces.iter_mut().zip(&self.forces_base).zip(&self.forces_step) {
            for ((f, b), st) in f.iter_mut().zip(b).zip(st) {
                *f = Forces {
                    normal: b.normal + s * (st.normal - b.normal),
                    tangential: b.tangential + s * (st.tangential - b.tangential),
                };
            }
        }
    }
}

/// Whether a point is at the normal kink: open, resting on its master within the geometry's
/// precision, without a normal force unknown.
fn at_kink(p: &PointNow, f: &Forces) -> bool {
    p.eval.is_some_and(|e| {
        e.state == ContactState::Open && crate::contact::point::touching(e.proj.gap, e.proj.a11) && f.normal <= 0.0
    })
}
