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
        self.surface.reset_current();
        self.left.iter_mut().flatten().for_each(|l| *l = None);
        self.penalty_rule = false;
        self.kink = Kink::Open;
        self.resting_some = false;
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
    /// next evaluations ([`Kink`]): all of them, or, after [`Self::rest_driven_in`], those
    /// it marked.
    pub fn set_kink(&mut self, kink: Kink) {
        self.kink = kink;
    }

    /// Mark, of the points at the normal kink that the last evaluation took open, those
    /// that the correction `du` drives into their master with a normal force above `tol`
    /// ([`Self::resting_forces`]), as the only points [`Kink::Resting`] rests from now on
    /// (until [`Self::rest_all`]). Returns how many were marked.
    pub fn rest_driven_in(&mut self, model: &Model, tol: f64, du: &dyn Fn(usize) -> f64) -> usize {
        let mut marked = 0;
        for ip in 0..model.contacts.len() {
            for is in 0..self.resting[ip].len() {
                let one = self.point_resting_forces(model, ip, is, true, du);
                let driven_in = one.is_some_and(|f| f.normal_max > tol);
                self.resting[ip][is] = driven_in;
                marked += usize::from(driven_in);
            }
        }
        self.resting_some = true;
        marked
    }

    /// [`Kink::Resting`] rests every point at the normal kink again.
    pub fn rest_all(&mut self) {
        self.resting_some = false;
    }

    /// Decide the states by the force unknowns alone at the next evaluations (see
    /// [`super::point::PointProblem::warm`]).
    pub fn set_warm_start(&mut self, warm: bool) {
        self.warm = warm;
        self.surface.set_warm_start(warm);
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

    /// `Σ C²` of the complementarity residuals at the last evaluation, 2D and 3D points
    /// (see [`super::decision::complementarity`], [`crate::contact3d::decision`]).
    pub fn complementarity2(&self) -> f64 {
        self.complementarity2 + self.surface.complementarity2()
    }

    /// Make the force unknowns the contact forces of the current iterate (a converged one:
    /// they are in equilibrium with the bodies, and within the tolerance of the penalty
    /// law; the penalty forces of the displacements carry the penalty's amplification of
    /// the gap's last digits, `ε δζ`). Records, monitors and the committed history take
    /// them from the points' evaluations.
    pub fn adopt_forces(&mut self) {
        self.surface.adopt_forces();
        for (now, forces) in self.current.iter_mut().zip(&self.forces) {
            for (p, f) in now.iter_mut().zip(forces) {
                if let Some(e) = p.eval.as_mut().filter(|e| e.state != ContactState::Open) {
                    e.normal_force = f.normal;
                    e.t1 = f.tangential * e.proj.a11.sqrt();
                }
            }
        }
    }

    /// The norm of the contact force unknowns, `√Σ (N² + t²)` over 2D and 3D points (a part
    /// of the reference force of the convergence test).
    pub fn force_norm(&self) -> f64 {
        let sum: f64 = self
            .forces
            .iter()
            .flatten()
            .map(|f| f.normal * f.normal + f.tangential * f.tangential)
            .sum();
        (sum + self.surface.force_norm2()).sqrt()
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
        self.resting_some = other.resting_some;
        copy(&mut self.resting, &other.resting);
        self.warm = other.warm;
        self.complementarity2 = other.complementarity2;
        self.tunnelled.clear();
        self.tunnelled.extend_from_slice(&other.tunnelled);
        self.surface.copy_iterate_from(&other.surface);
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
        self.surface.save_iterate();
    }

    /// The force unknowns at the full correction `du` (global DOFs, zero where prescribed):
    /// `N + ΔN = N_ε + ∇N_ε · Δu`, `T_1 + ΔT_1 = T_1,ε + ∇T_1,ε · Δu` of the decided state
    /// (the linearised constitutive equations; zero at an open point).
    pub fn correct_forces(&mut self, du: &dyn Fn(usize) -> f64) {
        self.surface.correct_forces(du);
        for ((steps, lins), now) in self.forces_step.iter_mut().zip(&self.lin).zip(&self.current) {
            for ((step, lin), p) in steps.iter_mut().zip(lins).zip(now) {
                let closed = p.eval.is_some_and(|e| e.state != ContactState::Open);
                *step = match lin.filter(|_| closed) {
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

    /// The contact forces, linearised along the correction `du` (global DOFs, zero where
    /// prescribed), of the points at the normal kink (touching, without a normal force
    /// unknown) that the last evaluation took open (`open`: the normal force they would
    /// have closed) or closed ([`Kink::Resting`]); `None` when there is none. Along the
    /// correction made with every such point open, a positive normal force says the
    /// correction drives a point into its master; along the correction made with them
    /// resting, a negative one says a point would have to pull, and a tangential force
    /// outside Coulomb's cone that it would have to slip.
    pub fn resting_forces(&self, model: &Model, open: bool, du: &dyn Fn(usize) -> f64) -> Option<RestingForces> {
        let mut out: Option<RestingForces> = None;
        for ip in 0..model.contacts.len() {
            for is in 0..self.current[ip].len() {
                let Some(f) = self.point_resting_forces(model, ip, is, open, du) else {
                    continue;
                };
                let r = out.get_or_insert(f);
                r.normal_min = r.normal_min.min(f.normal_min);
                r.normal_max = r.normal_max.max(f.normal_max);
                r.cone_excess = r.cone_excess.max(f.cone_excess);
            }
        }
        out
    }

    /// [`Self::resting_forces`] of point `is` of pair `ip` alone (`None` unless it is at the
    /// kink on the side `open` says; with [`Self::rest_driven_in`]'s marks, only a marked
    /// point counts as resting).
    fn point_resting_forces(
        &self,
        model: &Model,
        ip: usize,
        is: usize,
        open: bool,
        du: &dyn Fn(usize) -> f64,
    ) -> Option<RestingForces> {
        let (Some(e), Some((slots, l))) = (self.current[ip][is].eval, self.lin[ip][is]) else {
            return None;
        };
        let marked = open || !self.resting_some || self.resting[ip][is];
        let at_kink = (e.state == ContactState::Open) == open
            && crate::contact::point::touching(e.proj.gap, e.proj.a11)
            && self.forces[ip][is].normal <= 0.0;
        if !(marked && at_kink) {
            return None;
        }
        let (mut n, mut t1) = (l.normal, l.t1);
        for (i, &node) in slots.nodes().iter().enumerate() {
            for c in 0..2 {
                n += l.d_normal[2 * i + c] * du(2 * node + c);
                t1 += l.d_t1[2 * i + c] * du(2 * node + c);
            }
        }
        let mu = model.contacts[ip].law.mu;
        Some(RestingForces {
            normal_min: n,
            normal_max: n,
            cone_excess: t1.abs() / l.a11.sqrt() - mu * n.max(0.0),
        })
    }

    /// Go back to the iterate kept by [`Self::save_iterate`], with the force unknowns a
    /// fraction `s` of the way to the full correction's.
    pub fn to_step(&mut self, s: f64) {
        for (c, b) in self.current.iter_mut().zip(&self.current_base) {
            c.copy_from_slice(b);
        }
        self.surface.to_step(s);
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

/// The linearised contact forces of the resting points along a correction
/// ([`ContactSystem::resting_forces`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RestingForces {
    /// The smallest and the largest normal force.
    pub normal_min: f64,
    pub normal_max: f64,
    /// The largest excess of a tangential force over Coulomb's bound, `|t| − μ⟨N⟩`
    /// (negative: every point inside its cone).
    pub cone_excess: f64,
}

/// Whether a point is at the normal kink: open, resting on its master within the geometry's
/// precision, without a normal force unknown.
fn at_kink(p: &PointNow, f: &Forces) -> bool {
    p.eval.is_some_and(|e| {
        e.state == ContactState::Open && crate::contact::point::touching(e.proj.gap, e.proj.a11) && f.normal <= 0.0
    })
}
