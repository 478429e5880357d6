//! Global sparse matrix in compressed-column form: the pattern is built once (and only grows
//! when contact couples new DOFs), values are refilled each iteration, and the symbolic LU
//! factorisation (faer) is reused until the pattern changes.

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::sparse::linalg::lu::{factorize_symbolic_lu, LuRef, NumericLu, SymbolicLu};
use faer::sparse::{SparseColMatRef, SymbolicSparseColMat};
use faer::{Conj, Mat, Par};
use std::time::{Duration, Instant};

/// Failure of the linear solve.
#[derive(Debug, Clone, thiserror::Error)]
pub enum LinearError {
    #[error("sparse LU failed: {0}")]
    Factorization(String),
    #[error("linear solve produced non-finite values")]
    NonFinite,
}

/// Square sparse matrix with a fixed pattern.
pub struct SparseMatrix {
    pub n: usize,
    /// Row indices per column, sorted.
    cols: Vec<Vec<usize>>,
    col_ptr: Vec<usize>,
    row_idx: Vec<usize>,
    pub values: Vec<f64>,
    symbolic: Option<SymbolicSparseColMat<usize>>,
    lu_symbolic: Option<SymbolicLu<usize>>,
    /// Numeric factors, workspace and right-hand side, kept across iterations so that a
    /// factorisation allocates nothing once the pattern is fixed.
    numeric: NumericLu<usize, f64>,
    scratch: MemBuffer,
    rhs: Mat<f64>,
    /// Number of symbolic factorisations performed (pattern changes + 1).
    pub symbolic_factorizations: usize,
    /// Numeric factorisations performed, and the time spent in them (symbolic analyses
    /// included) and in the substitutions.
    pub factorizations: usize,
    pub factor_time: Duration,
    pub solve_time: Duration,
}

impl SparseMatrix {
    /// Pattern from a list of coupled index groups (each group couples all its members).
    pub fn new(n: usize, groups: &mut dyn Iterator<Item = Vec<usize>>) -> Self {
        let mut cols: Vec<Vec<usize>> = vec![Vec::new(); n];
        for (i, c) in cols.iter_mut().enumerate() {
            c.push(i); // keep the diagonal even for DOFs nothing touches
        }
        for g in groups {
            for &c in &g {
                for &r in &g {
                    cols[c].push(r);
                }
            }
        }
        let mut m = SparseMatrix {
            n,
            cols,
            col_ptr: Vec::new(),
            row_idx: Vec::new(),
            values: Vec::new(),
            symbolic: None,
            lu_symbolic: None,
            numeric: NumericLu::new(),
            scratch: MemBuffer::new(faer::dyn_stack::StackReq::EMPTY),
            rhs: Mat::zeros(0, 1),
            symbolic_factorizations: 0,
            factorizations: 0,
            factor_time: Duration::ZERO,
            solve_time: Duration::ZERO,
        };
        m.compress();
        m
    }

    fn compress(&mut self) {
        self.col_ptr.clear();
        self.row_idx.clear();
        self.col_ptr.push(0);
        for c in &mut self.cols {
            c.sort_unstable();
            c.dedup();
            self.row_idx.extend_from_slice(c);
            self.col_ptr.push(self.row_idx.len());
        }
        self.values = vec![0.0; self.row_idx.len()];
        self.symbolic = None;
        self.lu_symbolic = None;
    }

    pub fn nnz(&self) -> usize {
        self.row_idx.len()
    }

    /// Position of entry `(r, c)` in `values`, if it is in the pattern.
    #[inline]
    pub fn index(&self, r: usize, c: usize) -> Option<usize> {
        let s = &self.row_idx[self.col_ptr[c]..self.col_ptr[c + 1]];
        s.binary_search(&r).ok().map(|k| self.col_ptr[c] + k)
    }

    /// Add entries to the pattern; returns whether it changed (values are reset then).
    pub fn extend(&mut self, entries: &[(usize, usize)]) -> bool {
        let mut changed = false;
        for &(r, c) in entries {
            if self.index(r, c).is_none() {
                self.cols[c].push(r);
                changed = true;
            }
        }
        if changed {
            self.compress();
        }
        changed
    }

    pub fn clear_values(&mut self) {
        self.values.fill(0.0);
    }

    /// `y = A x`.
    pub fn mul(&self, x: &[f64], y: &mut [f64]) {
        y.fill(0.0);
        for (c, xc) in x.iter().enumerate().take(self.n) {
            for k in self.col_ptr[c]..self.col_ptr[c + 1] {
                y[self.row_idx[k]] += self.values[k] * xc;
            }
        }
    }

    /// Solve `A x = b` in place (LU with partial pivoting, symbolic analysis reused).
    /// Sequential below [`PARALLEL_FROM`] unknowns (threads cost more than they save on
    /// small systems), faer's global parallelism above.
    pub fn solve(&mut self, b: &mut [f64]) -> Result<(), LinearError> {
        let started = Instant::now();
        let par = if self.n < PARALLEL_FROM {
            Par::Seq
        } else {
            faer::get_global_parallelism()
        };
        if self.symbolic.is_none() {
            self.symbolic = Some(SymbolicSparseColMat::new_checked(
                self.n,
                self.n,
                self.col_ptr.clone(),
                None,
                self.row_idx.clone(),
            ));
        }
        let sym = self.symbolic.as_ref().expect("set above");
        if self.lu_symbolic.is_none() {
            let lu = factorize_symbolic_lu(sym.as_ref(), Default::default())
                .map_err(|e| LinearError::Factorization(format!("{e:?}")))?;
            let req = lu
                .factorize_numeric_lu_scratch::<f64>(par, Default::default())
                .or(lu.solve_in_place_scratch::<f64>(1, par));
            self.scratch = MemBuffer::try_new(req).map_err(|e| LinearError::Factorization(format!("{e:?}")))?;
            self.lu_symbolic = Some(lu);
            self.numeric = NumericLu::new();
            self.symbolic_factorizations += 1;
        }
        let lu_sym = self.lu_symbolic.as_ref().expect("set above");
        let mat = SparseColMatRef::new(sym.as_ref(), &self.values);
        lu_sym
            .factorize_numeric_lu(
                &mut self.numeric,
                mat,
                par,
                MemStack::new(&mut self.scratch),
                Default::default(),
            )
            .map_err(|e| LinearError::Factorization(format!("{e:?}")))?;
        self.factorizations += 1;
        let factored = Instant::now();
        self.factor_time += factored - started;
        if self.rhs.nrows() != self.n {
            self.rhs = Mat::zeros(self.n, 1);
        }
        for (i, bi) in b.iter().enumerate() {
            self.rhs[(i, 0)] = *bi;
        }
        LuRef::new_unchecked(lu_sym, &self.numeric).solve_in_place_with_conj(
            Conj::No,
            self.rhs.as_mut(),
            par,
            MemStack::new(&mut self.scratch),
        );
        for (i, bi) in b.iter_mut().enumerate() {
            *bi = self.rhs[(i, 0)];
        }
        self.solve_time += factored.elapsed();
        if b.iter().any(|v| !v.is_finite()) {
            return Err(LinearError::NonFinite);
        }
        Ok(())
    }
}

/// Systems with at least this many unknowns are factorised with faer's global parallelism.
pub const PARALLEL_FROM: usize = 20_000;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn unsymmetric_solve_and_pattern_growth() {
        let mut groups = vec![vec![0, 1], vec![1, 2]].into_iter();
        let mut a = SparseMatrix::new(3, &mut groups);
        assert_eq!(a.nnz(), 7);
        assert!(a.index(0, 2).is_none());
        assert!(a.extend(&[(0, 2)]));
        assert!(!a.extend(&[(0, 2)]));
        // A = [[4,1,2],[0,3,1],[0,1,5]] (unsymmetric)
        for (r, c, v) in [
            (0, 0, 4.0),
            (0, 1, 1.0),
            (0, 2, 2.0),
            (1, 1, 3.0),
            (1, 2, 1.0),
            (2, 1, 1.0),
            (2, 2, 5.0),
        ] {
            let k = a.index(r, c).unwrap();
            a.values[k] = v;
        }
        let x = [1.0, -2.0, 0.5];
        let mut b = [0.0; 3];
        a.mul(&x, &mut b);
        a.solve(&mut b).unwrap();
        for i in 0..3 {
            assert!((b[i] - x[i]).abs() < 1e-14);
        }
        // refill values, same symbolic factorisation
        a.values.iter_mut().for_each(|v| *v *= 2.0);
        a.mul(&x, &mut b);
        a.solve(&mut b).unwrap();
        assert_eq!(a.symbolic_factorizations, 1);
        assert!((b[1] + 2.0).abs() < 1e-14);
    }
}
