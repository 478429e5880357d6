//! The one interface of every way this crate solves `K Δu = −R`: a plan made for one
//! sparsity pattern (its analysis: an ordering, a symbolic factorisation, a multigrid
//! set-up), then, for each set of values, a numeric factorisation and a solve. The
//! plans are the banded LU ([`super::band_plan`]), faer's supernodal `LDLᵀ`
//! ([`super::ldlt`]) and sparse LU ([`super::faer_lu`]), and the multigrid-preconditioned
//! Krylov solver ([`super::iterative`]); which one solves, and what happens when one fails,
//! is decided in one place, [`super::chooser::LinearSolve`].

use super::band_plan::BandPlan;
use super::faer_lu::LuPlan;
use super::inertia::Inertia;
use super::iterative::{IterativeFailure, IterativePlan};
use super::ldlt::{LdltFailure, LdltPlan};
use super::sparse::SparseMatrix;
use faer::Par;

/// Failure of a factorisation or a solve.
#[derive(Debug, Clone, thiserror::Error)]
pub enum LinearError {
    #[error("sparse LU failed: {0}")]
    Factorization(String),
    #[error("linear solve produced non-finite values")]
    NonFinite,
    #[error(transparent)]
    Band(#[from] super::band::ZeroPivot),
    #[error("symmetric factorisation not made: {0:?}")]
    Symmetric(LdltFailure),
    #[error(transparent)]
    Iterative(#[from] IterativeFailure),
}

/// A factorisation of one pattern, analysed when the plan was made.
pub trait Factorization {
    /// Numeric factorisation of `a`'s values (`a` has the pattern the plan was made for).
    fn factorize(&mut self, a: &SparseMatrix, par: Par) -> Result<(), LinearError>;
    /// Solve `A x = b` in place with the last factorisation; `b` is as it was on failure.
    fn solve(&mut self, a: &SparseMatrix, b: &mut [f64], par: Par) -> Result<(), LinearError>;
    /// What the last factorisation says of the matrix's definiteness ([`Inertia`]): the
    /// count of negative eigenvalues (`LDLᵀ`) or the determinant's sign (the banded LU, of
    /// any matrix: the caller knows whether it was symmetric); `None` where the
    /// factorisation does not tell (faer's LU, the Krylov solver).
    fn inertia(&self) -> Option<Inertia> {
        None
    }
}

/// Banded LU with partial pivoting in reverse Cuthill–McKee order (sequential).
impl Factorization for BandPlan {
    fn factorize(&mut self, a: &SparseMatrix, _: Par) -> Result<(), LinearError> {
        Ok(BandPlan::factorize(self, &a.values)?)
    }

    fn solve(&mut self, _: &SparseMatrix, b: &mut [f64], _: Par) -> Result<(), LinearError> {
        BandPlan::solve(self, b);
        Ok(())
    }

    fn inertia(&self) -> Option<Inertia> {
        self.lu.inertia()
    }
}

/// faer's sparse LU (COLAMD, partial pivoting).
impl Factorization for LuPlan {
    fn factorize(&mut self, a: &SparseMatrix, par: Par) -> Result<(), LinearError> {
        LuPlan::factorize(self, a.symbolic(), &a.values, par)
    }

    fn solve(&mut self, _: &SparseMatrix, b: &mut [f64], par: Par) -> Result<(), LinearError> {
        LuPlan::solve(self, b, par);
        Ok(())
    }
}

/// faer's supernodal `LDLᵀ`: refuses values that are not symmetric, and a solve whose
/// backward error is too large (it pivots on the diagonal only). The substitutions run on
/// one thread whatever `par` says: they stream the factor from memory, and two threads took
/// longer than one (hertz-3d plate 56 × 56 × 10, 2026-11-29: 0.144 against 0.132 s per
/// preconditioned iteration).
impl Factorization for LdltPlan {
    fn factorize(&mut self, a: &SparseMatrix, par: Par) -> Result<(), LinearError> {
        LdltPlan::factorize(self, a.symbolic(), &a.values, par).map_err(LinearError::Symmetric)
    }

    fn solve(&mut self, a: &SparseMatrix, b: &mut [f64], _: Par) -> Result<(), LinearError> {
        LdltPlan::solve(self, a.symbolic(), &a.values, b, Par::Seq).map_err(LinearError::Symmetric)
    }

    fn inertia(&self) -> Option<Inertia> {
        Some(LdltPlan::inertia(self))
    }
}

/// Conjugate gradients or BiCGStab preconditioned by smoothed-aggregation multigrid. Its
/// "factorisation" is the set-up of the multigrid hierarchy, which is decided within the
/// solve (a Krylov solve that fails on a kept hierarchy rebuilds it and tries once more);
/// the set-up time of the last solve is [`IterativePlan::last_setup`].
impl Factorization for IterativePlan {
    fn factorize(&mut self, _: &SparseMatrix, _: Par) -> Result<(), LinearError> {
        Ok(())
    }

    fn solve(&mut self, a: &SparseMatrix, b: &mut [f64], _: Par) -> Result<(), LinearError> {
        self.last_setup = IterativePlan::solve(self, &a.values, b)?;
        Ok(())
    }
}
