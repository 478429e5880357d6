//! A problem: what a scene becomes, the model and how to solve it. The model holds no solver
//! settings, so one model can be run with other stepping or Newton settings (a study).

use crate::model::{Dim, Model, Plane};
use crate::settings::SolverSettings;

/// A model (2D by default, or 3D) and the settings it is solved with.
#[derive(Debug, Clone, Default)]
pub struct Problem<S: Dim = Plane> {
    pub model: Model<S>,
    pub settings: SolverSettings,
}
