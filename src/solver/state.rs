//! The solution state carried between increments.

use crate::contact::system::ContactSystem;
use crate::model::{Dim, Model};

/// Displacements, element-internal EAS parameters and contact history.
#[derive(Debug, Clone)]
pub struct TrialState {
    /// Full displacement vector (`D` per node).
    pub u: Vec<f64>,
    /// Enhanced-strain parameters, [`Dim::ALPHAS`] per element (flat).
    pub alphas: Vec<f64>,
    pub contact: ContactSystem,
}

impl TrialState {
    /// Make this state's iterate `other`'s (same model, same increment), without allocating
    /// (see [`ContactSystem::copy_iterate_from`]).
    pub fn copy_iterate_from(&mut self, other: &TrialState) {
        self.u.copy_from_slice(&other.u);
        self.alphas.copy_from_slice(&other.alphas);
        self.contact.copy_iterate_from(&other.contact);
    }

    pub fn new<S: Dim>(model: &Model<S>) -> Self {
        TrialState {
            u: vec![0.0; model.dof_count()],
            alphas: vec![0.0; S::ALPHAS * model.elements.len()],
            contact: ContactSystem::of(model),
        }
    }
}
