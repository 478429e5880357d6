//! Why a Newton attempt at an increment failed, as one type the stepping driver acts on
//! (a cut-back, a retry from another start) and maps to the recorded failure kind.

use crate::assembly::AssemblyError;
use crate::linalg::factorization::LinearError;
use crate::record::FailureKind;

/// Why an increment failed (the stepping driver cuts the step back on these).
#[derive(Debug, Clone, thiserror::Error)]
pub enum NewtonFailure {
    #[error("no convergence in {iterations} iterations")]
    MaxIterations { iterations: usize },
    #[error("active-set cycle: {points} contact points kept changing state or segment ({iterations} iterations)")]
    ActiveSetCycle { iterations: usize, points: usize },
    #[error("residual diverged (‖R‖ = {residual:.3e})")]
    Diverged { residual: f64 },
    #[error("non-finite residual")]
    NonFinite,
    #[error(
        "{points} contact points passed through their master within one Newton step ({first}): deeper inside it \
         than the search radius, where a point cannot be told from one beyond a thin body's far side; raise the \
         pair's search_radius if penetrations that deep are meant (a soft eps_n), otherwise a smaller step avoids it"
    )]
    Tunnelled { points: usize, first: String },
    #[error(
        "rigid body `{body}` would move {travel:.3e} in this step, farther than the search radius {radius:.3e} of \
         pair `{pair}`: a point out of reach at the step's start could end deeper inside its master than the \
         search can see, unseen and without force"
    )]
    StepBeyondSearch {
        body: String,
        pair: String,
        travel: f64,
        radius: f64,
    },
    #[error(
        "augmented Lagrangian of pair `{pair}` not converged after {updates} multiplier updates: the \
         multipliers still change by {relative:.2e} of the pair's largest normal force (augmented_tol = {tol:.1e}); \
         raise augmented_max, loosen augmented_tol, or raise eps_n / eps_t (each update contracts the error \
         by about k/(k + eps) for a local stiffness k)"
    )]
    Augmentation {
        pair: String,
        updates: usize,
        relative: f64,
        tol: f64,
    },
    #[error(transparent)]
    Element(#[from] AssemblyError),
    #[error(transparent)]
    Linear(#[from] LinearError),
}

impl NewtonFailure {
    /// The failure kind recorded in the outcome.
    pub fn kind(&self) -> FailureKind {
        match self {
            NewtonFailure::MaxIterations { .. } | NewtonFailure::Augmentation { .. } => FailureKind::NoConvergence,
            NewtonFailure::ActiveSetCycle { .. } => FailureKind::ActiveSetCycle,
            NewtonFailure::Diverged { .. } => FailureKind::Diverged,
            NewtonFailure::NonFinite => FailureKind::NonFinite,
            NewtonFailure::Tunnelled { .. } | NewtonFailure::StepBeyondSearch { .. } => FailureKind::LostContact,
            NewtonFailure::Element(_) => FailureKind::InvertedElement,
            NewtonFailure::Linear(_) => FailureKind::LinearSolver,
        }
    }
}
