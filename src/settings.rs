//! How a model is solved: load-stepping and Newton settings (the `[stepping]` and `[solver]`
//! tables of a scene). Plain data, kept out of the model: a run = model + these settings.

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// Load stepping over the pseudo-time `t ∈ [0, end]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct Stepping {
    /// Final pseudo-time.
    pub end: f64,
    /// Number of nominal increments (nominal step `end / increments`).
    pub increments: usize,
    /// How many times one increment may be halved before the run fails; the step never falls
    /// below `end / increments / 2^max_cutbacks`.
    pub max_cutbacks: usize,
    /// Step growth factor after `grow_after` consecutive converged increments (back toward the
    /// nominal step, never beyond it).
    pub growth: f64,
    pub grow_after: usize,
    /// Starting iterate of each increment (see [`Predictor`]).
    pub predictor: Predictor,
}

/// Where Newton starts an increment from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "kebab-case")]
pub enum Predictor {
    /// The free DOFs extrapolated along the last converged increment,
    /// `u₀ = uₙ + (Δt/Δtₙ)(uₙ − uₙ₋₁)` (a secant predictor): on a smooth path the first
    /// residual is of order Δt² instead of Δt, which saves about one Newton iteration per
    /// increment. If the predicted attempt fails, the increment is retried once from the
    /// last converged state at the same step before any cut-back.
    #[default]
    Secant,
    /// The last converged state (only the prescribed DOFs move).
    Last,
}

impl Default for Stepping {
    fn default() -> Self {
        Stepping {
            end: 1.0,
            increments: 10,
            max_cutbacks: 10,
            growth: 2.0,
            grow_after: 2,
            predictor: Predictor::Secant,
        }
    }
}

/// How the contact points' states are decided at a Newton iterate
/// ([`crate::contact::decision`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "kebab-case")]
pub enum ActiveSet {
    /// From the augmented contact forces of the Alart–Curnier functions, weighted by the
    /// bodies' stiffness against the penalty: the same solution, decided in the model's own
    /// scale whatever the penalty.
    #[default]
    Augmented,
    /// From the penalty forces of the displacements alone (the seed's rule; the augmented
    /// rule with unit weights), for comparisons.
    Penalty,
}

/// Newton–Raphson settings.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct NewtonSettings {
    /// Corrections per attempt at an increment before it is cut back.
    pub max_iterations: usize,
    /// Converged when `‖R‖ ≤ residual_tol · F_ref` (`F_ref`: the norm of the reactions and
    /// loads at the attempt's first iterate, never below the run's largest converged one) …
    pub residual_tol: f64,
    /// … or `‖R‖ ≤ residual_abs` (a force: 0, the default, leaves only the relative test and
    /// the round-off floor, both in the model's own scale), …
    pub residual_abs: f64,
    /// … and the energy norm `|Δu·R|` of the last correction is `≤ energy_tol` times that of
    /// the first iteration of the increment.
    pub energy_tol: f64,
    /// The iteration is declared divergent when `‖R‖` exceeds this multiple of
    /// `max(‖R₀‖, F_ref)`.
    pub divergence_factor: f64,
    /// How the contact states are decided at each iterate (see [`ActiveSet`]).
    pub active_set: ActiveSet,
    /// When to check the assembled tangent by finite differences (see [`TangentCheckWhen`]).
    pub check_tangent: TangentCheckWhen,
    /// Which linear solver factorises the tangent (see [`LinearSolver`]).
    pub linear_solver: LinearSolver,
    /// Threads this run may use, the solver's own included (0: the cores this process may
    /// use, see [`crate::threads::available_cores`]). The element kernels use them where
    /// they are measured to pay, and so do `LDLᵀ` factorisations of at least 3·10¹⁰ flops
    /// (3D meshes of ~5·10⁴ unknowns and more); the results do not depend on it, except on
    /// such models, which may differ at round-off. `contrail run --threads` sets it;
    /// `contrail sweep --jobs` and `contrail serve --workers` divide the machine among
    /// their runs.
    pub threads: usize,
    /// Assemble an iterate expected to converge without the tangent (a wrong guess assembles
    /// it again with it; `solver::newton`, `expects_convergence`). The iterations and the
    /// answer do not depend on it; `false` for comparisons.
    pub skip_converging_tangents: bool,
}

/// Which linear solver factorises the tangent (`crate::linalg`). They give the same
/// solution to round-off (the iterative one to its tolerance); the choice is about speed and
/// memory, and is recorded with the run's parameters.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "kebab-case")]
pub enum LinearSolver {
    /// Banded LU after reverse Cuthill–McKee when the band is narrow; otherwise faer's sparse
    /// `LDLᵀ` (minimum degree or nested dissection, whichever costs fewer flops) while the
    /// matrix is symmetric — with the factor of an earlier tangent preconditioning conjugate
    /// gradients while that costs less than a new factorisation — and faer's sparse LU when
    /// it is not.
    #[default]
    Auto,
    /// Always faer's sparse LU (for comparisons).
    SparseLu,
    /// faer's `LDLᵀ` or LU, never the banded LU, every tangent factorised (for comparisons).
    General,
    /// The smoothed-aggregation multigrid preconditioned Krylov solver, whatever the size;
    /// a solve it cannot converge falls back to faer's LU. Slower than the direct solvers
    /// on stretched meshes (docs/large-models.md).
    Iterative,
}

/// When the solver checks its assembled tangent by finite differences at a failing iterate
/// (`solver/tangent_check.rs`) and writes the result to the run's log.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "kebab-case")]
pub enum TangentCheckWhen {
    /// Never.
    Off,
    /// At the last iterate of the attempt that makes the run fail.
    #[default]
    OnFailure,
    /// At the last iterate of every attempt that fails (also those cut back).
    EveryFailedAttempt,
}

impl Default for NewtonSettings {
    fn default() -> Self {
        NewtonSettings {
            max_iterations: 25,
            residual_tol: 1e-9,
            residual_abs: 0.0,
            energy_tol: 1e-16,
            divergence_factor: 1e8,
            active_set: ActiveSet::Augmented,
            check_tangent: TangentCheckWhen::OnFailure,
            linear_solver: LinearSolver::Auto,
            threads: 0,
            skip_converging_tangents: true,
        }
    }
}

/// Everything the solver needs besides the model.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields, default)]
pub struct SolverSettings {
    pub stepping: Stepping,
    pub newton: NewtonSettings,
}
