//! The contact force unknowns of the 3D points in Newton's iterate
//! ([`super::decision`]): their weights, their start from the converged forces, their
//! linearised correction and the steps along it, and the forces a converged iterate keeps
//! — the 3D side of `contact::system::unknowns`.

use super::decision::SurfaceForces;
use super::point::{SurfaceLinearization, DOFS};
use super::system::SurfaceSystem;
use crate::contact::law::ContactState;
use crate::model::{Model, SlaveMeasure, Solid, SurfaceMaster, SurfacePair};

/// A closed point's linearised penalty forces and the global DOFs of their gradients (the
/// first `len` entries).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct PointLinearization {
    pub dofs: [usize; DOFS],
    pub len: usize,
    pub lin: SurfaceLinearization,
}

impl PointLinearization {
    /// The penalty forces at the correction `du` (global DOFs):
    /// `N_ε + ∇N_ε · Δu` and `t_ε + ∇t_ε · Δu`.
    fn corrected(&self, du: &dyn Fn(usize) -> f64) -> SurfaceForces {
        let l = &self.lin;
        let mut f = SurfaceForces {
            normal: l.normal,
            tangential: l.tangential,
        };
        for (j, &dof) in self.dofs[..self.len].iter().enumerate() {
            let d = du(dof);
            f.normal += l.d_normal[j] * d;
            for c in 0..3 {
                f.tangential[c] += l.d_tangential[c][j] * d;
            }
        }
        f
    }
}

impl SurfaceSystem {
    /// Decide every point by the penalty rule (`penalty`: the seed's active set,
    /// [`crate::settings::ActiveSet::Penalty`]; weights 1) or by the augmented forces with
    /// each point's weights ([`augmented_weights`]).
    pub fn set_penalty_weights(&mut self, model: &Model<Solid>, penalty: bool) {
        self.weights = (model.surface_contacts.iter())
            .map(|p| match penalty {
                true => vec![(1.0, 1.0); p.slaves.len()],
                false => augmented_weights(model, p),
            })
            .collect();
    }

    /// Start the force unknowns from the forces of the last converged increment.
    pub(super) fn reset_forces(&mut self) {
        for (forces, hist) in self.forces.iter_mut().zip(&self.committed) {
            for (f, h) in forces.iter_mut().zip(hist) {
                *f = if h.closed { h.forces } else { SurfaceForces::default() };
            }
        }
    }

    /// Decide the states by the force unknowns alone at the next evaluations (points
    /// closed at the last converged increment).
    pub fn set_warm_start(&mut self, warm: bool) {
        self.warm = warm;
    }

    /// `Σ C²` of the complementarity residuals at the last evaluation.
    pub fn complementarity2(&self) -> f64 {
        self.complementarity2
    }

    /// `Σ (N² + |t|²)` of the force unknowns.
    pub fn force_norm2(&self) -> f64 {
        let length2 = |v: [f64; 3]| v.iter().map(|c| c * c).sum::<f64>();
        (self.forces.iter().flatten())
            .map(|f| f.normal * f.normal + length2(f.tangential))
            .sum()
    }

    /// The force unknowns at the full correction `du` (global DOFs, zero where prescribed):
    /// the linearised constitutive equations of the decided state; zero at an open point.
    pub fn correct_forces(&mut self, du: &dyn Fn(usize) -> f64) {
        for (steps, now) in self.forces_step.iter_mut().zip(&self.current) {
            for (step, p) in steps.iter_mut().zip(now) {
                *step = p.linearization.map_or(SurfaceForces::default(), |l| l.corrected(du));
            }
        }
    }

    /// Go back to the iterate kept by [`Self::save_iterate`], with the force unknowns a
    /// fraction `s` of the way to the full correction's.
    pub fn to_step(&mut self, s: f64) {
        self.restore_iterate();
        for ((f, b), st) in self.forces.iter_mut().zip(&self.forces_base).zip(&self.forces_step) {
            for ((f, b), st) in f.iter_mut().zip(b).zip(st) {
                f.normal = b.normal + s * (st.normal - b.normal);
                f.tangential = std::array::from_fn(|c| b.tangential[c] + s * (st.tangential[c] - b.tangential[c]));
            }
        }
    }

    /// Make the force unknowns the contact forces of the current (converged) iterate:
    /// records, monitors and the committed history take them from the evaluations.
    pub fn adopt_forces(&mut self) {
        for (now, forces) in self.current.iter_mut().zip(&self.forces) {
            for (p, f) in now.iter_mut().zip(forces) {
                if let Some(e) = p.eval.as_mut().filter(|e| e.state != ContactState::Open) {
                    e.normal_force = f.normal;
                    // a point without a friction history keeps its zero traction (its end
                    // fixes the anchor)
                    if p.frictional {
                        e.traction = e.projection.point.covariant(f.tangential);
                    }
                }
            }
        }
    }
}

/// The weights of a 3D pair's augmented forces, per slave point: `ρ = min(1, c/(ε √A))`
/// ([`crate::contact::decision::weights`] with the stiffness `c/√A`), `c` the smaller
/// plane-strain modulus of the deformable bodies the pair joins and `A` the slave's
/// tributary area. The point's penalty spring is `ε A` and the bodies' stiffness at a node
/// of that spacing about `c √A`: their ratio is dimensionless, so the decisions — and the
/// iterations — are the same in any units. On an edge slave (tributary length `ℓ`) the
/// spring is `ε ℓ` and the stiffness `c ℓ`: `ρ = min(1, c/ε)`.
fn augmented_weights(model: &Model<Solid>, pair: &SurfacePair) -> Vec<(f64, f64)> {
    let master = match pair.master {
        SurfaceMaster::Facets { body, .. } => Some(body),
        SurfaceMaster::Rigid(_) => None,
    };
    let c = model.contact_stiffness(pair.slaves.iter().copied(), master);
    (0..pair.slaves.len())
        .map(|is| {
            let measure = pair.areas.get(is).copied().unwrap_or(1.0);
            // the body's stiffness per unit of the slave's measure: c/√A on a face, c along
            // an edge (spring ε ℓ against c ℓ)
            let stiffness = match pair.measure {
                SlaveMeasure::Area => c / measure.sqrt(),
                SlaveMeasure::Length => c,
            };
            match c.is_finite() && measure > 0.0 {
                true => crate::contact::decision::weights(stiffness, pair.law.eps_n, pair.law.eps_t),
                false => (1.0, 1.0),
            }
        })
        .collect()
}
