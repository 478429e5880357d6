//! Global sparse matrix in compressed-column form: the pattern is built once (and only grows
//! when contact couples new DOFs), values are refilled each iteration, and the symbolic
//! factorisation (banded LU, faer's `LDLᵀ` or LU) is reused until the pattern changes.

use super::aggregation::MeshNode;
use super::band_plan::BandPlan;
use super::faer_lu::LuPlan;
use super::iterative::{IterativePlan, IterativeStats};
use super::ldlt::{LdltPlan, LdltStats};
use faer::sparse::SymbolicSparseColMat;
use faer::Par;
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

pub use crate::settings::LinearSolver;

/// Square sparse matrix with a fixed pattern.
pub struct SparseMatrix {
    pub n: usize,
    /// Row indices per column, sorted.
    cols: Vec<Vec<usize>>,
    col_ptr: Vec<usize>,
    row_idx: Vec<usize>,
    pub values: Vec<f64>,
    symbolic: Option<SymbolicSparseColMat<usize>>,
    /// faer's LU of the current pattern, once needed.
    lu: Option<LuPlan>,
    /// faer's `LDLᵀ` of the current pattern while its values are symmetric (decided at the
    /// first solve of a pattern, dropped at the first solve it cannot make).
    ldlt: Option<LdltPlan>,
    ldlt_decided: bool,
    ldlt_stats: LdltStats,
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
            lu: None,
            ldlt: None,
            ldlt_decided: false,
            ldlt_stats: LdltStats::default(),
            solver: LinearSolver::Auto,
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
        self.lu = None;
        self.band = None;
        self.band_decided = false;
        self.retire_iterative();
        self.retire_ldlt();
    }

    /// Choose the solver (resets the factorisation).
    pub fn set_solver(&mut self, solver: LinearSolver) {
        self.solver = solver;
        self.band = None;
        self.band_decided = false;
        self.retire_iterative();
        self.retire_ldlt();
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

    /// Counts of the symmetric (`LDLᵀ`) factorisations so far.
    pub fn ldlt_stats(&self) -> LdltStats {
        self.ldlt_stats
    }

    /// Drop the `LDLᵀ` plan of the current pattern (the next pattern decides again).
    fn retire_ldlt(&mut self) {
        self.ldlt = None;
        self.ldlt_decided = false;
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

    /// Solve `A x = b` in place (ordering and symbolic analysis reused while the pattern is
    /// unchanged): a banded LU with partial pivoting after reverse Cuthill–McKee when the band
    /// is narrow (see [`super::band`]); otherwise faer's sparse `LDLᵀ` with AMD ordering while
    /// the matrix is symmetric ([`super::ldlt`]) and faer's sparse LU (COLAMD, partial
    /// pivoting) when it is not; faer's factorisations run sequentially below
    /// [`PARALLEL_FROM`] unknowns (threads cost more than they save on small systems) and
    /// with faer's global parallelism above.
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
        } else if !self.solve_symmetric(started, b) {
            self.solve_sparse(Instant::now(), b)?;
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
        let factored = plan.factorize(&self.values);
        self.factorizations += 1;
        let done = Instant::now();
        self.factor_time += done - started;
        factored?;
        plan.solve(b);
        self.solve_time += done.elapsed();
        Ok(())
    }

    /// The parallelism of faer's factorisations: sequential below [`PARALLEL_FROM`].
    fn par(&self) -> Par {
        if self.n < PARALLEL_FROM {
            Par::Seq
        } else {
            faer::get_global_parallelism()
        }
    }

    /// The pattern in faer's form (built once per pattern).
    fn symbolic(&mut self) -> &SymbolicSparseColMat<usize> {
        self.symbolic.get_or_insert_with(|| {
            SymbolicSparseColMat::new_checked(self.n, self.n, self.col_ptr.clone(), None, self.row_idx.clone())
        })
    }

    /// Factorise and solve with faer's `LDLᵀ` when the solver is `Auto` or `General`, the
    /// pattern is structurally symmetric and the values are symmetric; returns whether it
    /// did (`b` is untouched when not). The first solve it cannot make retires the plan for
    /// the rest of the pattern's life (its time counts as factorisation time).
    fn solve_symmetric(&mut self, started: Instant, b: &mut [f64]) -> bool {
        if !matches!(self.solver, LinearSolver::Auto | LinearSolver::General) {
            return false;
        }
        let par = self.par();
        if !self.ldlt_decided {
            self.ldlt_decided = true;
            self.symbolic();
            self.ldlt = LdltPlan::new(self.n, &self.col_ptr, &self.row_idx, &self.values, par);
            if let Some(plan) = &self.ldlt {
                self.symbolic_factorizations += 1;
                self.ldlt_stats.plans += 1;
                self.ldlt_stats.factor_nnz = plan.factor_nnz();
            }
        }
        let (Some(plan), Some(sym)) = (self.ldlt.as_mut(), self.symbolic.as_ref()) else {
            return false;
        };
        let outcome = plan.factorize_and_solve(sym.as_ref(), &self.values, b, par);
        self.factor_time += started.elapsed();
        match outcome {
            Ok(solve_time) => {
                self.factorizations += 1;
                self.ldlt_stats.solves += 1;
                self.factor_time -= solve_time;
                self.solve_time += solve_time;
                true
            }
            Err(failure) => {
                self.ldlt_stats.fallbacks += 1;
                self.ldlt_stats.last_failure = Some(failure);
                self.ldlt = None;
                false
            }
        }
    }

    /// Factorise and solve with faer's sparse LU (symbolic analysis reused).
    fn solve_sparse(&mut self, started: Instant, b: &mut [f64]) -> Result<(), LinearError> {
        let par = self.par();
        self.symbolic();
        let sym = self.symbolic.as_ref().expect("set above").as_ref();
        if self.lu.is_none() {
            self.lu = Some(LuPlan::new(sym, par)?);
            self.symbolic_factorizations += 1;
        }
        let lu = self.lu.as_mut().expect("set above");
        lu.factorize(sym, &self.values, par)?;
        self.factorizations += 1;
        let factored = Instant::now();
        self.factor_time += factored - started;
        lu.solve(b, par);
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
