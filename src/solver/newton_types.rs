//! The types Newton's method for one increment hands in and out ([`super::newton`]): what
//! it is asked to solve, what it returns, which test accepted, and the buffers it reuses.

use super::active_set::ActiveSetWatch;

/// Which test accepted an increment (recorded with it).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Acceptance {
    /// `‖R‖ ≤ tol · F_ref` and the energy norm of the last correction below `energy_tol`
    /// times the first's.
    Residual,
    /// `‖R‖` at the round-off floor of the assembled residual.
    RoundOff,
    /// The first iterate already met the residual test (no correction made).
    Start,
}

impl Acceptance {
    pub fn as_str(self) -> &'static str {
        match self {
            Acceptance::Residual => "residual",
            Acceptance::RoundOff => "round-off",
            Acceptance::Start => "start",
        }
    }
}

/// Outcome of a converged increment (`residuals`: `‖R‖` at each iterate).
#[derive(Debug, Clone)]
pub struct Converged {
    pub iterations: usize,
    pub residuals: Vec<f64>,
    /// The force scale of the converged state ([`super::newton::force_scale`]).
    pub reference: f64,
    /// Multiplier updates of augmented-Lagrangian pairs (each one more solve).
    pub augmentations: usize,
    pub accepted_by: Acceptance,
    /// Corrections whose line search found no step that decreased the merit function (the
    /// shortest step tried was taken).
    pub line_search_failures: usize,
    /// Iterations that reached a new active set and so extended the iteration limit
    /// ([`super::newton::Iterate::count_front`]).
    pub front_iterations: usize,
    /// Corrections shifted by the pseudo-transient continuation, and the work of its drag
    /// ([`super::continuation`]).
    pub stabilised: usize,
    pub stabilisation_work: f64,
    /// What the attempt's last factorised tangent (unshifted, symmetric) said of its
    /// definiteness; `None` when the attempt factorised none that tells
    /// ([`crate::linalg::inertia`]).
    pub inertia: Option<crate::linalg::inertia::Inertia>,
}

/// Buffers and diagnostics of one attempt, reused across increments.
#[derive(Debug, Default)]
pub struct Workspace {
    pub(super) r: Vec<f64>,
    pub(super) du: Vec<f64>,
    /// The correction with the points at the normal kink open, while the other element is
    /// tried ([`super::newton::Iterate::choose_kink_side`]).
    pub(super) du_open: Vec<f64>,
    /// `‖R‖` at each iterate of the last attempt.
    pub residuals: Vec<f64>,
    /// The merit function at each iterate of the last attempt.
    pub(super) merits: Vec<f64>,
    /// The active-set history of the last attempt.
    pub watch: ActiveSetWatch,
    /// The iterate a correction starts from (displacements and enhanced-strain parameters).
    pub(super) u_before: Vec<f64>,
    pub(super) alphas_before: Vec<f64>,
    /// Line searches of the attempt that found no decrease.
    pub(super) line_search_failures: usize,
    /// Iterations of the attempt that reached an active set not met before in it (a moving
    /// contact front: [`super::newton::Iterate::count_front`]); each extends the iteration limit by one.
    pub(super) front_iterations: usize,
    /// The globalisation's saved iterate ([`super::line_search`]).
    pub(super) watchdog: super::line_search::Watchdog,
    /// What the last converged attempt showed of the rate of convergence: whether it was
    /// accepted at its start, and `‖R₁‖/‖R₀‖` of its first correction
    /// ([`super::newton::Iterate::expects_convergence`]).
    pub(super) last_start_accepted: bool,
    pub(super) last_first_rate: Option<f64>,
    /// Shifted corrections after a failed line search ([`super::continuation`]).
    pub(super) continuation: super::continuation::Continuation,
    /// The definiteness of the attempt's last factorised tangent ([`Converged::inertia`]).
    pub(super) inertia: Option<crate::linalg::inertia::Inertia>,
}

/// Which increment is solved, to what time, and from what start.
#[derive(Debug, Clone, Copy)]
pub struct IncrementTarget {
    /// The pseudo-time the increment ends at.
    pub t: f64,
    /// The largest force scale of the converged increments so far ([`super::newton::force_scale`]):
    /// `F_ref` never falls below it.
    pub reference_floor: f64,
    pub increment: usize,
    pub attempt: usize,
    /// The start is extrapolated from the last converged increments (secant predictor).
    pub predicted: bool,
}
