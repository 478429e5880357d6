//! The solution state carried between increments.

use crate::contact::system::ContactSystem;
use crate::model::Model;

/// Displacements, element-internal EAS parameters and contact history.
#[derive(Debug, Clone)]
pub struct TrialState {
    /// Full displacement vector (2 per node).
    pub u: Vec<f64>,
    /// Enhanced-strain parameters per element.
    pub alphas: Vec<[f64; 4]>,
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

    pub fn new(model: &Model) -> Self {
        TrialState {
            u: vec![0.0; model.dof_count()],
            alphas: vec![[0.0; 4]; model.elements.len()],
            contact: ContactSystem::new(model),
        }
    }
}
