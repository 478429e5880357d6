//! Augmented Lagrangian enforcement by Uzawa updates at converged increments (Wriggers,
//! Computational Contact Mechanics (2006), §6.4; for friction Laursen & Simo, CMAME 108
//! (1993) 133–146, and Simo & Laursen, Comput Struct 42 (1992) 97–116).
//!
//! Each point of an augmented pair carries multipliers ([`Multiplier`]) that are held fixed
//! while Newton solves the increment. At the converged iterate `k` they are updated as the
//! forces the penalty produced there:
//!
//! - normal: `λ_N^{k+1} = ⟨λ_N^k − ε_N ζ^k⟩ = N^k`;
//! - tangential: `λ_T^{k+1} = P_{μN}(λ_T^k − ε_T s^k) = t^k`, the returned traction, where
//!   `λ_T = t^(n) + Λ` is the traction carried from the last converged increment plus this
//!   increment's correction `Λ`, and `s` the slip of this increment (the transfer scheme's
//!   increment). So `Λ^{k+1} = Λ^k + (T_1 − T_1^carried)/√a11`: in stick by `−ε_T s`, in
//!   slip by the change of the cone's traction.
//!
//! The increment is solved again until the largest change of a pair's multipliers,
//! relative to the pair's largest normal force, is at most its `augmented_tol`. With the
//! constraints then met to that tolerance, the result no longer depends on `ε_N`, `ε_T`
//! beyond it: a stuck point does not creep by `T/ε_T`, a pressed one does not sink by
//! `N/ε_N`. The penalties only set how fast the updates converge (a contraction of about
//! `k/(k + ε)` per update for a local stiffness `k`): small penalties need many updates.
//! At a new increment `λ_N` starts from the converged normal force and `Λ` from zero.

use super::law::ContactState;
use super::point::Multiplier;
use super::system::ContactSystem;
use crate::model::{Enforcement, Model};

/// The multiplier change of one augmented pair at a converged iterate.
#[derive(Debug, Clone, PartialEq)]
pub struct PairChange {
    pub pair: usize,
    /// Largest change of a normal or tangential multiplier …
    pub change: f64,
    /// … and the pair's largest normal force (or old normal multiplier) it is measured
    /// against.
    pub scale: f64,
    pub tol: f64,
    /// The pair's cap on updates per increment.
    pub max: usize,
}

impl PairChange {
    /// `change / scale` (zero when nothing changed).
    pub fn relative(&self) -> f64 {
        if self.change == 0.0 {
            0.0
        } else {
            self.change / self.scale.max(f64::MIN_POSITIVE)
        }
    }

    pub fn converged(&self) -> bool {
        self.relative() <= self.tol
    }
}

/// The new multipliers of one point from its evaluation at a converged iterate, and how
/// much they changed (normal, tangential).
fn update(old: Multiplier, eval: Option<&super::point::PointEval<f64>>, mu: f64) -> (Multiplier, f64, f64) {
    match eval.filter(|e| e.state != ContactState::Open) {
        Some(e) => {
            let normal = e.normal_force.max(0.0);
            let tangential = if mu > 0.0 {
                old.tangential + (e.t1 - e.t1_carried) / e.proj.a11.sqrt()
            } else {
                0.0
            };
            let new = Multiplier { normal, tangential };
            (new, (normal - old.normal).abs(), (tangential - old.tangential).abs())
        }
        None => (Multiplier::default(), old.normal, old.tangential.abs()),
    }
}

impl ContactSystem {
    /// Measure, at a converged iterate, how much the Uzawa update would change the
    /// multipliers of every augmented pair; with `apply`, make the update. Empty when no
    /// pair is augmented.
    pub fn augment(&mut self, model: &Model, apply: bool) -> Vec<PairChange> {
        let mut out = Vec::new();
        for (ip, pair) in model.contacts.iter().enumerate() {
            let Enforcement::Augmented { tol, max } = pair.enforcement else {
                continue;
            };
            let mut change = 0.0f64;
            let mut scale = 0.0f64;
            for is in 0..pair.slaves.len() {
                let old = self.multipliers[ip][is];
                let eval = self.current[ip][is].eval;
                let (new, dn, dt) = update(old, eval.as_ref(), pair.law.mu);
                change = change.max(dn).max(dt);
                scale = scale.max(new.normal).max(old.normal);
                if apply {
                    self.multipliers[ip][is] = new;
                }
            }
            out.push(PairChange {
                pair: ip,
                change,
                scale,
                tol,
                max,
            });
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::geometry::Projection;
    use crate::contact::point::PointEval;

    fn eval(state: ContactState, n: f64, t1: f64, carried: f64) -> PointEval<f64> {
        PointEval {
            proj: Projection {
                xi: 0.0,
                gap: -1e-3,
                rho: [0.0; 2],
                rho1: [2.0, 0.0],
                a11: 4.0,
            },
            normal_force: n,
            t1_trial: t1,
            t1,
            state,
            t1_carried: carried,
            complementarity: [0.0; 2],
        }
    }

    #[test]
    fn uzawa_update_takes_the_returned_forces_as_multipliers() {
        let old = Multiplier {
            normal: 3.0,
            tangential: 0.5,
        };
        // stick: T_1 = 2.0 (t = 1.0), carried 1.6 (t = 0.8, of which Λ = 0.5): Λ += 0.2
        let (new, dn, dt) = update(old, Some(&eval(ContactState::Stick, 3.5, 2.0, 1.6)), 0.3);
        assert_eq!(new.normal, 3.5);
        assert!((new.tangential - 0.7).abs() < 1e-15 && (dn - 0.5).abs() < 1e-15 && (dt - 0.2).abs() < 1e-15);
        // frictionless: no tangential multiplier
        let (new, _, _) = update(old, Some(&eval(ContactState::Slip, 3.5, 0.0, 0.0)), 0.0);
        assert_eq!(new.tangential, 0.0);
        // opened: both released, the change is the old multiplier
        let (new, dn, dt) = update(old, Some(&eval(ContactState::Open, 0.0, 0.0, 0.0)), 0.3);
        assert_eq!((new, dn, dt), (Multiplier::default(), 3.0, 0.5));
        let c = PairChange {
            pair: 0,
            change: 0.5,
            scale: 3.5,
            tol: 0.1,
            max: 5,
        };
        assert!(!c.converged() && (c.relative() - 0.5 / 3.5).abs() < 1e-15);
    }
}
