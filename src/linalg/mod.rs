//! Linear algebra below the assembly: the sparse matrix (pattern built once, values refilled)
//! and the solvers of `K Δu = −R` it chooses among — a banded LU for narrow bands, faer's
//! supernodal `LDLᵀ` for symmetric tangents, faer's sparse LU for the rest, and an opt-in
//! smoothed-aggregation multigrid Krylov solver — each behind one interface
//! ([`factorization::Factorization`]: analyse once per pattern, factorise, solve), chosen,
//! with the fallbacks between them, in one place ([`chooser::LinearSolve`]). Which is used is
//! the solver setting `linear_solver` ([`crate::settings::LinearSolver`]), recorded with the
//! run's settings.

pub mod aggregation;
pub mod amg;
pub mod band;
pub mod band_plan;
pub mod chooser;
pub mod csr;
pub mod dissection;
pub mod factorization;
pub mod faer_lu;
pub mod inertia;
pub mod iterative;
pub mod lagged;
pub mod ldlt;
pub mod par_csr;
pub mod sparse;
