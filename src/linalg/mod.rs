//! Linear algebra below the assembly: the sparse matrix (pattern built once, values refilled)
//! and the solvers of `K Δu = −R` it chooses among — a banded LU for narrow bands, faer's
//! supernodal `LDLᵀ` for symmetric tangents, faer's sparse LU for the rest, and an opt-in
//! smoothed-aggregation multigrid Krylov solver — with the fallbacks between them. Which is
//! used is the solver setting `linear_solver` ([`crate::settings::LinearSolver`]).

pub mod aggregation;
pub mod amg;
pub mod band;
pub mod band_plan;
pub mod csr;
pub mod faer_lu;
pub mod iterative;
pub mod ldlt;
pub mod sparse;
