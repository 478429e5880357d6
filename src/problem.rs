//! A problem: what a scene becomes, the model and how to solve it. The model holds no solver
//! settings, so one model can be run with other stepping or Newton settings (a study).

use crate::model::Model;
use crate::settings::SolverSettings;

/// A model and the settings it is solved with.
#[derive(Debug, Clone, Default)]
pub struct Problem {
    pub model: Model,
    pub settings: SolverSettings,
}
