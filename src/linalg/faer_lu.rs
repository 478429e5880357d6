//! faer's general sparse LU (COLAMD column ordering, partial pivoting) of one pattern: the
//! symbolic analysis, numeric storage and workspace are kept across
//! factorisations, so that refactorising allocates nothing once the pattern is fixed.

use super::factorization::LinearError;
use faer::dyn_stack::{MemBuffer, MemStack};
use faer::sparse::linalg::lu::{factorize_symbolic_lu, LuRef, NumericLu, SymbolicLu};
use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};
use faer::{Conj, MatMut, Par};

/// The LU of one pattern.
pub struct LuPlan {
    symbolic: SymbolicLu<usize>,
    numeric: NumericLu<usize, f64>,
    scratch: MemBuffer,
}

impl LuPlan {
    /// Symbolic analysis of the pattern `sym` and workspace for `par`.
    pub fn new(sym: SymbolicSparseColMatRef<'_, usize>, par: Par) -> Result<Self, LinearError> {
        let symbolic =
            factorize_symbolic_lu(sym, Default::default()).map_err(|e| LinearError::Factorization(format!("{e:?}")))?;
        let req = symbolic
            .factorize_numeric_lu_scratch::<f64>(par, Default::default())
            .or(symbolic.solve_in_place_scratch::<f64>(1, par));
        let scratch = MemBuffer::try_new(req).map_err(|e| LinearError::Factorization(format!("{e:?}")))?;
        Ok(LuPlan {
            symbolic,
            numeric: NumericLu::new(),
            scratch,
        })
    }

    /// Numeric factorisation of `A` (pattern `sym`, values `values`).
    pub fn factorize(
        &mut self,
        sym: SymbolicSparseColMatRef<'_, usize>,
        values: &[f64],
        par: Par,
    ) -> Result<(), LinearError> {
        let mat = SparseColMatRef::new(sym, values);
        self.symbolic
            .factorize_numeric_lu(
                &mut self.numeric,
                mat,
                par,
                MemStack::new(&mut self.scratch),
                Default::default(),
            )
            .map_err(|e| LinearError::Factorization(format!("{e:?}")))?;
        Ok(())
    }

    /// Solve `A x = b` in place with the last factorisation.
    pub fn solve(&mut self, b: &mut [f64], par: Par) {
        let n = b.len();
        LuRef::new_unchecked(&self.symbolic, &self.numeric).solve_in_place_with_conj(
            Conj::No,
            MatMut::from_column_major_slice_mut(b, n, 1),
            par,
            MemStack::new(&mut self.scratch),
        );
    }
}
