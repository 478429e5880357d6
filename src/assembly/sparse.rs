//! Global sparse matrix in compressed-column form: the pattern is built once (and only grows
//! when contact couples new DOFs), values are refilled each iteration, and the symbolic LU
//! factorisation (faer) is reused until the pattern changes.

use super::aggregation::MeshNode;
use super::band::{band_widths, reverse_cuthill_mckee, supervariable_rcm, BandLu, Root};
use super::iterative::{IterativePlan, IterativeStats};
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
    #[error(transparent)]
    Band(#[from] super::band::ZeroPivot),
}

/// Which direct solver factorises the matrix.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LinearSolver {
    /// Banded LU after reverse Cuthill–McKee when the band is narrow, faer's sparse LU
    /// otherwise (default).
    Auto,
    /// Always faer's sparse LU (`CONTRAIL_LINEAR_SOLVER=sparse`, for comparisons).
    Sparse,
    /// The multigrid-preconditioned Krylov solver ([`super::iterative`]) when the matrix
    /// knows its nodes (`CONTRAIL_LINEAR_SOLVER=iterative`), whatever the size; a solve it
    /// cannot converge falls back to faer's LU.
    Iterative,
}

impl LinearSolver {
    /// The choice from the environment variable `CONTRAIL_LINEAR_SOLVER` (`sparse`,
    /// `iterative` or `auto`; anything else means `auto`): a diagnostic switch for
    /// benchmarks, not a setting of a study (the solvers give the same solution to round-off,
    /// the iterative one to its tolerance, [`super::iterative::RELATIVE_TOLERANCE`]).
    pub fn from_env() -> Self {
        match std::env::var("CONTRAIL_LINEAR_SOLVER").as_deref() {
            Ok("sparse") => LinearSolver::Sparse,
            Ok("iterative") => LinearSolver::Iterative,
            _ => LinearSolver::Auto,
        }
    }
}

/// The banded factorisation of a pattern: RCM permutation and the band slot of each stored
/// entry.
struct BandPlan {
    lu: BandLu,
    /// `perm[new] = old`
    perm: Vec<usize>,
    /// band slot of `values[k]`
    slots: Vec<usize>,
    rhs: Vec<f64>,
}

impl BandPlan {
    /// A plan if the RCM-ordered pattern has a narrow band (see [`BandLu::worth_it`]).
    fn new(n: usize, col_ptr: &[usize], row_idx: &[usize]) -> Option<Self> {
        // RCM on the supervariables (nodes) from a far level or a node, and on the unknowns:
        // the narrowest band wins
        let candidates = [
            supervariable_rcm(n, col_ptr, row_idx, Root::FarLevel),
            supervariable_rcm(n, col_ptr, row_idx, Root::Node),
            reverse_cuthill_mckee(n, col_ptr, row_idx, Root::Node),
        ];
        let (perm, (kl, ku)) = candidates
            .into_iter()
            .map(|p| {
                let w = band_widths(n, col_ptr, row_idx, &p);
                (p, w)
            })
            .min_by_key(|(_, (kl, ku))| kl * ku)
            .expect("three candidates");
        let mut inv = vec![0; n];
        for (new, &old) in perm.iter().enumerate() {
            inv[old] = new;
        }
        let entries = || (0..n).flat_map(|c| row_idx[col_ptr[c]..col_ptr[c + 1]].iter().map(move |&r| (r, c)));
        if !BandLu::worth_it(n, kl.max(ku)) {
            return None;
        }
        let lu = BandLu::new(n, kl, ku);
        let slots = entries().map(|(r, c)| lu.slot(inv[r], inv[c])).collect();
        Some(BandPlan {
            lu,
            perm,
            slots,
            rhs: vec![0.0; n],
        })
    }
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
    solver: LinearSolver,
    /// The pattern given at construction (the elements'), which [`Self::extend`] grows.
    base: Vec<Vec<usize>>,
    /// Per stored entry: not in `base` (added by [`Self::extend`]).
    extension: Vec<bool>,
    /// The pattern holds entries beyond `base`.
    extended: bool,
    /// An extension entry was written by [`Self::add_to`] since the last
    /// [`Self::shrink_unused_extension`].
    extension_used: bool,
    /// Banded factorisation of the current pattern, when it pays (decided once per pattern).
    band: Option<BandPlan>,
    band_decided: bool,
    /// Free equations and reference position of each mesh node (for the multigrid's
    /// rigid-body modes), when the owner gave them.
    nodes: Option<Vec<MeshNode>>,
    /// The iterative solver of the current pattern, when chosen.
    iterative: Option<IterativePlan>,
    /// Counts of the iterative solves of all patterns so far.
    iterative_stats: IterativeStats,
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
            base: Vec::new(),
            extension: Vec::new(),
            extended: false,
            extension_used: false,
            cols,
            col_ptr: Vec::new(),
            row_idx: Vec::new(),
            values: Vec::new(),
            symbolic: None,
            lu_symbolic: None,
            numeric: NumericLu::new(),
            scratch: MemBuffer::new(faer::dyn_stack::StackReq::EMPTY),
            rhs: Mat::zeros(0, 1),
            solver: LinearSolver::from_env(),
            band: None,
            band_decided: false,
            nodes: None,
            iterative: None,
            iterative_stats: IterativeStats::default(),
            symbolic_factorizations: 0,
            factorizations: 0,
            factor_time: Duration::ZERO,
            solve_time: Duration::ZERO,
        };
        m.compress();
        m.base = m.cols.clone();
        m.extension = vec![false; m.row_idx.len()];
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
        self.band = None;
        self.band_decided = false;
        self.retire_iterative();
    }

    /// Choose the solver (resets the factorisation).
    pub fn set_solver(&mut self, solver: LinearSolver) {
        self.solver = solver;
        self.band = None;
        self.band_decided = false;
        self.retire_iterative();
    }

    /// Give the free equations `(x, y)` and reference position of each mesh node: the
    /// multigrid preconditioner of the iterative solver is built on their rigid-body modes.
    pub fn set_nodes(&mut self, nodes: Vec<MeshNode>) {
        self.nodes = Some(nodes);
        self.band_decided = false;
        self.retire_iterative();
    }

    /// Counts of the iterative solves so far (all zero when only the LU was used).
    pub fn iterative_stats(&self) -> IterativeStats {
        let mut s = self.iterative_stats;
        if let Some(p) = &self.iterative {
            let c = p.stats;
            s.solves += c.solves;
            s.cg_solves += c.cg_solves;
            s.krylov_iterations += c.krylov_iterations;
            s.max_krylov_iterations = s.max_krylov_iterations.max(c.max_krylov_iterations);
            s.builds += c.builds;
            s.failures += c.failures;
            if c.builds > 0 {
                s.levels = c.levels;
                s.complexity = c.complexity;
                s.constrained_nodes = c.constrained_nodes;
            }
        }
        s
    }

    /// Fold the current iterative plan's counts into the run's and drop it.
    fn retire_iterative(&mut self) {
        if self.iterative.is_some() {
            self.iterative_stats = self.iterative_stats();
            self.iterative = None;
        }
    }

    /// The half-bandwidths `(kl, ku)` of the banded factorisation in use, if one is.
    pub fn band_widths(&self) -> Option<(usize, usize)> {
        self.band.as_ref().map(|b| (b.lu.kl, b.lu.ku))
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
            self.extension = (0..self.n)
                .flat_map(|c| {
                    self.row_idx[self.col_ptr[c]..self.col_ptr[c + 1]]
                        .iter()
                        .map(move |&r| (r, c))
                })
                .map(|(r, c)| self.base[c].binary_search(&r).is_err())
                .collect();
            self.extended = true;
            self.extension_used = true;
        }
        changed
    }

    /// `values[slot] += v`, noting whether the entry is one of [`Self::extend`]'s.
    #[inline]
    pub fn add_to(&mut self, slot: usize, v: f64) {
        self.values[slot] += v;
        self.extension_used |= self.extension[slot];
    }

    /// Drop the entries [`Self::extend`] added when none was written by [`Self::add_to`]
    /// since the last call, if the banded factorisation is in use (its band is set by the
    /// widest entry). Contact couples the nodes of a point's last segment with those of its
    /// current one only in the increments where it crosses from one to the other (seed eqs.
    /// 2–4): kept, those entries would widen the band of a 120×4 strip from 13 to 23 for
    /// the rest of the run. Returns whether the pattern changed (the values are reset then,
    /// and the caller must recompute its slots). The general sparse LU keeps its pattern (a
    /// new symbolic analysis of a large model costs more than the fill it saves).
    pub fn shrink_unused_extension(&mut self) -> bool {
        let unused = !std::mem::take(&mut self.extension_used);
        if !unused || self.band.is_none() || !self.extended {
            return false;
        }
        self.cols.clone_from(&self.base);
        self.compress();
        self.extension = vec![false; self.row_idx.len()];
        self.extended = false;
        true
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

    /// Solve `A x = b` in place (LU with partial pivoting, ordering and symbolic analysis
    /// reused while the pattern is unchanged): a banded LU after reverse Cuthill–McKee when
    /// the band is narrow (see [`super::band`]), otherwise faer's sparse LU, sequential below
    /// [`PARALLEL_FROM`] unknowns (threads cost more than they save on small systems) and with
    /// faer's global parallelism above.
    pub fn solve(&mut self, b: &mut [f64]) -> Result<(), LinearError> {
        let started = Instant::now();
        if !self.band_decided {
            self.band_decided = true;
            if self.solver == LinearSolver::Auto {
                self.band = BandPlan::new(self.n, &self.col_ptr, &self.row_idx);
                if self.band.is_some() {
                    self.symbolic_factorizations += 1;
                }
            }
            // the iterative solver only when asked for: on the large-model benchmark it is
            // slower than the LU at every size measured (docs/large-models.md)
            if let (LinearSolver::Iterative, Some(nodes)) = (self.solver, &self.nodes) {
                self.iterative = Some(IterativePlan::new(self.n, &self.col_ptr, &self.row_idx, nodes));
            }
        }
        if let Some(plan) = self.iterative.as_mut() {
            match plan.solve(&self.values, b) {
                Ok(setup) => {
                    self.factor_time += setup;
                    self.solve_time += started.elapsed() - setup;
                }
                Err(_) => {
                    // this one with the direct LU (counted as a failure; `b` is as it was);
                    // the next solve tries the iterative solver again
                    self.solve_time += started.elapsed();
                    self.solve_sparse(Instant::now(), b)?;
                }
            }
        } else if self.band.is_some() {
            self.solve_band(started, b)?;
        } else {
            self.solve_sparse(started, b)?;
        }
        if b.iter().any(|v| !v.is_finite()) {
            return Err(LinearError::NonFinite);
        }
        Ok(())
    }

    /// Factorise and solve with the banded LU of the RCM-ordered matrix.
    fn solve_band(&mut self, started: Instant, b: &mut [f64]) -> Result<(), LinearError> {
        let Some(plan) = self.band.as_mut() else {
            return Err(LinearError::Factorization("no banded factorisation planned".into()));
        };
        plan.lu.clear();
        for (&s, &v) in plan.slots.iter().zip(&self.values) {
            plan.lu.add(s, v);
        }
        let factored = plan.lu.factorize();
        self.factorizations += 1;
        let done = Instant::now();
        self.factor_time += done - started;
        factored?;
        for (r, &old) in plan.rhs.iter_mut().zip(&plan.perm) {
            *r = b[old];
        }
        plan.lu.solve(&mut plan.rhs);
        for (r, &old) in plan.rhs.iter().zip(&plan.perm) {
            b[old] = *r;
        }
        self.solve_time += done.elapsed();
        Ok(())
    }

    /// Factorise and solve with faer's sparse LU (symbolic analysis reused).
    fn solve_sparse(&mut self, started: Instant, b: &mut [f64]) -> Result<(), LinearError> {
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
        Ok(())
    }
}

/// Systems with at least this many unknowns are factorised with faer's global parallelism.
pub const PARALLEL_FROM: usize = 20_000;

/// The unknowns of each cell of an `nx × ny` grid of 4-node cells, nodes numbered row by row
/// and two unknowns per node (for tests).
#[cfg(test)]
pub(crate) fn quad_grid_groups(nx: usize, ny: usize) -> Vec<Vec<usize>> {
    let node = |i: usize, j: usize| j * (nx + 1) + i;
    let mut groups = Vec::new();
    for j in 0..ny {
        for i in 0..nx {
            let q = [node(i, j), node(i + 1, j), node(i + 1, j + 1), node(i, j + 1)];
            groups.push(q.iter().flat_map(|&n| [2 * n, 2 * n + 1]).collect::<Vec<_>>());
        }
    }
    groups
}

#[cfg(test)]
#[path = "sparse_tests.rs"]
mod tests;
