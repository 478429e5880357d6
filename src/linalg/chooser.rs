//! Which factorisation solves `K Δu = −R`, and what happens when one fails: the one place
//! that decides (the plans themselves are behind [`Factorization`]).
//!
//! Per pattern ([`SparseMatrix::generation`]), with the setting [`LinearSolver`]:
//! - `auto`: the banded LU after reverse Cuthill–McKee when the band is narrow
//!   ([`super::band`]); otherwise faer's `LDLᵀ` while the values are symmetric
//!   ([`super::ldlt`]), and faer's sparse LU when they are not;
//! - `general`: `LDLᵀ`, else the sparse LU (no band); `sparse-lu`: the sparse LU only;
//! - `iterative`: the multigrid Krylov solver ([`super::iterative`]), with the sparse LU
//!   for a solve it cannot make.
//!
//! Fallbacks: an `LDLᵀ` factorisation or solve that fails (unsymmetric values, a zero
//! pivot, a large backward error) retires the plan for the rest of its pattern and the LU
//! solves; a failed iterative solve is repeated by the LU (the next solve tries the
//! iterative solver again). faer's factorisations run sequentially below
//! [`PARALLEL_FROM`] unknowns (measured: every size) and on the run's threads above; an
//! `LDLᵀ` from [`PARALLEL_FROM_FLOPS`] flops on.

use super::aggregation::MeshNodes;
use super::band_plan::BandPlan;
use super::factorization::{Factorization, LinearError};
use super::faer_lu::LuPlan;
use super::inertia::Inertia;
use super::iterative::{IterativePlan, IterativeStats};
use super::lagged::{LaggedSolve, LaggedStats};
use super::ldlt::{mirror_map, symmetric, LdltPlan, LdltStats};
use super::sparse::SparseMatrix;
pub use crate::settings::LinearSolver;
use crate::team::Team;
use faer::Par;
use std::sync::Arc;
use std::time::{Duration, Instant};

/// Systems with at least this many unknowns would be factorised on the run's threads
/// (faer's rayon parallelism) by the LU, the band and the multigrid set-up; smaller ones
/// sequentially. No size was found where that pays: faer's parallel `LDLᵀ` took 1.3–2.4×
/// the sequential time at 4e4, 1e5 and 4e5 unknowns of 2D meshes with 2, 4, 8 and 16
/// threads (16-core machine, 2026-11-26; also with 2 threads on the 2-core one; `cargo run
/// --release --example factor_grain -- 400x50 1000x50 2000x100`), so these are sequential
/// at every size. The `LDLᵀ` decides by its flops instead ([`PARALLEL_FROM_FLOPS`]).
pub const PARALLEL_FROM: usize = usize::MAX;

/// `LDLᵀ` factorisations of at least this many flops (`Σ m_j²`, [`super::ldlt::factor_flops`])
/// run on the run's threads; cheaper ones sequentially. What pays is the size of the dense
/// fronts, not the number of unknowns: nested dissection of a 3D mesh ends in separators of
/// thousands of unknowns, whose dense factorisations parallelise, while the fronts of 2D
/// meshes stay small. Measured 2026-11-29 on the 2-core machine (`SCENE=scenes/hertz-3d.toml
/// cargo run --release --example factor_grain -- 16x16x12 24x24x18 28x28x21 32x32x24`,
/// factorisation and solve, 2 threads against one): 0.72× at 1.9e9 flops (10 540 unknowns),
/// 1.05× at 2.0e10 (34 050), 1.14× at 4.8e10 (53 389), 1.44–1.60× at 1.07e11 (78 936); 2D
/// meshes have small fronts and stay far below (`-- 1000x50 2000x100`: 6.4e8 flops at 1e5
/// unknowns, 5.6e9 at 4e5, 0.66× and 0.58× on 2 threads).
pub const PARALLEL_FROM_FLOPS: f64 = 3e10;

/// What the lagged solves' cost model ([`super::lagged`]) takes a factorisation on the run's
/// threads to gain over one on one thread: 1.44–1.60× measured with 2 threads at 1.07e11
/// flops ([`PARALLEL_FROM_FLOPS`]), less for smaller factorisations, not measured with more
/// threads. It makes the lagged solves' budget, hence which solves are lagged, depend on
/// whether the factorisation is parallel: a run of such a model on one thread and on two
/// may differ at round-off.
pub const PARALLEL_FACTOR_SPEEDUP: f64 = 1.5;

/// Numeric factorisations made, and the time spent in them (symbolic analyses and the
/// multigrid set-up included) and in the substitutions.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct SolveTimes {
    pub factorizations: usize,
    pub factor_time: Duration,
    pub solve_time: Duration,
}

/// The linear solves of one matrix over a run: the plans of its current pattern and the
/// counts of all patterns.
pub struct LinearSolve {
    solver: LinearSolver,
    /// Free equations and reference position of each mesh node (the multigrid's rigid-body
    /// modes), when the owner gave them.
    nodes: Option<MeshNodes>,
    /// The pattern the plans below were made for.
    generation: Option<u64>,
    band: Option<BandPlan>,
    ldlt: Option<LdltPlan>,
    ldlt_decided: bool,
    ldlt_stats: LdltStats,
    /// Solves with the `LDLᵀ` of an earlier tangent as preconditioner (`auto` only).
    lagged: Option<LaggedSolve>,
    lagged_stats: LaggedStats,
    lu: Option<LuPlan>,
    iterative: Option<IterativePlan>,
    /// Counts of the iterative plans of earlier patterns.
    iterative_stats: IterativeStats,
    /// Symbolic analyses made (one per plan).
    pub symbolic_factorizations: usize,
    pub times: SolveTimes,
    /// Threads the factorisations may use (the run's budget), and the size from which they do.
    threads: usize,
    parallel_from: usize,
    /// `LDLᵀ` factorisations of at least these flops use the threads.
    parallel_from_flops: f64,
    /// The run's team (the assembler's), handed to the iterative solver.
    team: Option<Arc<Team>>,
    /// What the latest factorisation said of the tangent's definiteness, until taken
    /// ([`Self::take_inertia`]).
    inertia: Option<Inertia>,
    /// The mirror of each upper entry of the banded pattern (`None` inside: not structurally
    /// symmetric), made at the first negative determinant of the pattern.
    band_mirror: Option<Option<Vec<(usize, usize)>>>,
}

impl Default for LinearSolve {
    fn default() -> Self {
        LinearSolve::new(LinearSolver::Auto)
    }
}

impl LinearSolve {
    pub fn new(solver: LinearSolver) -> Self {
        LinearSolve {
            solver,
            nodes: None,
            generation: None,
            band: None,
            ldlt: None,
            ldlt_decided: false,
            ldlt_stats: LdltStats::default(),
            lagged: None,
            lagged_stats: LaggedStats::default(),
            lu: None,
            iterative: None,
            iterative_stats: IterativeStats::default(),
            symbolic_factorizations: 0,
            times: SolveTimes::default(),
            threads: 1,
            parallel_from: PARALLEL_FROM,
            parallel_from_flops: PARALLEL_FROM_FLOPS,
            team: None,
            inertia: None,
            band_mirror: None,
        }
    }

    /// Let factorisations use `threads` threads (the run's budget) where they pay: from
    /// [`PARALLEL_FROM`] unknowns, an `LDLᵀ` from [`PARALLEL_FROM_FLOPS`] flops.
    pub fn set_threads(&mut self, threads: usize) {
        self.threads = threads.max(1);
    }

    /// Replace the measured thresholds: factorisations of at least `unknowns` unknowns, and
    /// `LDLᵀ` factorisations of at least `flops` flops, use the threads (a probe of what
    /// parallelism gains sets both to zero).
    pub fn set_parallel_thresholds(&mut self, unknowns: usize, flops: f64) {
        self.parallel_from = unknowns;
        self.parallel_from_flops = flops;
    }

    /// Share the iterative solver's products and smoothing with the run's `team`.
    pub fn set_team(&mut self, team: Option<Arc<Team>>) {
        if let Some(p) = self.iterative.as_mut() {
            p.set_team(team.clone());
        }
        self.team = team;
    }

    /// The parallelism of faer's factorisations of an `n`-unknown system (the LU, the band,
    /// the multigrid set-up).
    fn parallelism(&self, n: usize) -> Par {
        if self.threads < 2 || n < self.parallel_from {
            Par::Seq
        } else {
            Par::rayon(self.threads)
        }
    }

    /// The parallelism of an `LDLᵀ` factorisation and its substitutions, by its flops
    /// ([`PARALLEL_FROM_FLOPS`]).
    fn ldlt_parallelism(&self, flops: f64) -> Par {
        if self.threads < 2 || flops < self.parallel_from_flops {
            Par::Seq
        } else {
            Par::rayon(self.threads)
        }
    }

    /// Choose the solver (the plans are made again at the next solve).
    pub fn set_solver(&mut self, solver: LinearSolver) {
        self.solver = solver;
        self.forget_plans();
    }

    /// Give the free equations and reference position of each mesh node: the multigrid
    /// preconditioner of the iterative solver is built on their rigid-body modes.
    pub fn set_nodes(&mut self, nodes: MeshNodes) {
        self.nodes = Some(nodes);
        self.forget_plans();
    }

    /// Whether the banded LU solves the current pattern.
    pub fn banded(&self) -> bool {
        self.band.is_some()
    }

    /// The half-bandwidths `(kl, ku)` of the banded factorisation in use, if one is.
    pub fn band_widths(&self) -> Option<(usize, usize)> {
        self.band.as_ref().map(|b| (b.lu.kl, b.lu.ku))
    }

    /// Counts of the iterative solves so far (all zero when only the direct solvers were used).
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

    /// Counts of the solves with an earlier tangent's factor so far.
    pub fn lagged_stats(&self) -> LaggedStats {
        let mut s = self.lagged_stats;
        if let Some(l) = &self.lagged {
            add_lagged(&mut s, &l.stats);
        }
        s
    }

    /// What the latest factorisation since the last call said of the tangent's definiteness
    /// ([`Inertia`]): `None` when no factorisation was made since, or the last one does not
    /// tell (faer's LU, the Krylov solver, a banded LU of an unsymmetric matrix with a
    /// negative determinant).
    pub fn take_inertia(&mut self) -> Option<Inertia> {
        self.inertia.take()
    }

    /// Counts of the symmetric (`LDLᵀ`) factorisations so far.
    pub fn ldlt_stats(&self) -> LdltStats {
        self.ldlt_stats
    }

    /// Solve `a x = b` in place, with the plans of `a`'s pattern (made at its first solve).
    pub fn solve(&mut self, a: &SparseMatrix, b: &mut [f64]) -> Result<(), LinearError> {
        if self.generation != Some(a.generation()) {
            self.plan(a);
        }
        let par = self.parallelism(a.n);
        if let Some(plan) = self.iterative.as_mut() {
            let started = Instant::now();
            if Factorization::solve(plan, a, b, par).is_ok() {
                let setup = plan.last_setup;
                self.times.factor_time += setup;
                self.times.solve_time += started.elapsed().saturating_sub(setup);
            } else {
                // counted as a failure by the plan; `b` is as it was
                self.times.solve_time += started.elapsed();
                self.solve_lu(a, b, par)?;
            }
        } else if let Some(plan) = self.band.as_mut() {
            factorize_and_solve(plan, a, b, par, &mut self.times)?;
            let inertia = plan.inertia();
            self.inertia = inertia.filter(|i| i.positive() || self.band_symmetric(a));
        } else if !self.solve_symmetric(a, b) {
            self.solve_lu(a, b, par)?;
            self.inertia = None;
        }
        if b.iter().any(|v| !v.is_finite()) {
            return Err(LinearError::NonFinite);
        }
        Ok(())
    }

    /// The plans of a new pattern: the band when the setting allows it and it pays, the
    /// iterative solver when asked for (the symmetric and LU plans are made when first used).
    fn plan(&mut self, a: &SparseMatrix) {
        self.forget_plans();
        self.generation = Some(a.generation());
        if self.solver == LinearSolver::Auto {
            self.band = BandPlan::new(a.n, &a.col_ptr, &a.row_idx);
            self.symbolic_factorizations += usize::from(self.band.is_some());
        }
        // only when asked for: on the large-model benchmark it is slower than the LU at
        // every size measured (docs/large-models.md)
        if let (LinearSolver::Iterative, Some(nodes)) = (self.solver, &self.nodes) {
            let mut plan = IterativePlan::new(a.n, &a.col_ptr, &a.row_idx, nodes);
            plan.set_team(self.team.clone());
            self.iterative = Some(plan);
        }
    }

    /// Drop every plan (the counts of the iterative one are kept).
    fn forget_plans(&mut self) {
        self.generation = None;
        self.band = None;
        self.band_mirror = None;
        self.lu = None;
        self.ldlt = None;
        self.ldlt_decided = false;
        if let Some(l) = self.lagged.take() {
            add_lagged(&mut self.lagged_stats, &l.stats);
        }
        if self.iterative.is_some() {
            self.iterative_stats = self.iterative_stats();
            self.iterative = None;
        }
    }

    /// Whether the banded matrix is symmetric: a banded LU's negative determinant tells of
    /// stability only then (not of a frictional tangent). Checked only for a negative
    /// determinant, over the pattern's mirror map (made once).
    fn band_symmetric(&mut self, a: &SparseMatrix) -> bool {
        let mirror = self
            .band_mirror
            .get_or_insert_with(|| mirror_map(a.n, &a.col_ptr, &a.row_idx));
        mirror.as_ref().is_some_and(|m| symmetric(m, &a.values))
    }

    /// Solve with `LDLᵀ` when the setting allows it and the pattern's first values were
    /// symmetric; returns whether it did (`b` is untouched when not). A failure retires the
    /// plan for the rest of the pattern's life.
    fn solve_symmetric(&mut self, a: &SparseMatrix, b: &mut [f64]) -> bool {
        if !matches!(self.solver, LinearSolver::Auto | LinearSolver::General) {
            return false;
        }
        if !self.ldlt_decided {
            self.ldlt_decided = true;
            let started = Instant::now();
            let threads = self.ldlt_parallelism(f64::INFINITY);
            self.ldlt = LdltPlan::new(a.n, &a.col_ptr, &a.row_idx, &a.values, self.nodes.as_ref(), threads);
            self.times.factor_time += started.elapsed();
            if let Some(plan) = &self.ldlt {
                self.symbolic_factorizations += 1;
                self.ldlt_stats.plans += 1;
                self.ldlt_stats.factor_nnz = plan.factor_nnz();
                self.ldlt_stats.ordering = Some(plan.ordering);
                self.ldlt_stats.flops = plan.flops;
            }
        }
        let Some(flops) = self.ldlt.as_ref().map(|p| p.flops.0) else {
            return false;
        };
        let par = self.ldlt_parallelism(flops);
        let Some(plan) = self.ldlt.as_mut() else {
            return false;
        };
        // only `auto` reuses factors: `general` is the reference that factorises every tangent
        if self.solver == LinearSolver::Auto && self.lagged.is_none() {
            // a factorisation on the threads costs fewer substitutions (which stay on one)
            let speedup = if matches!(par, Par::Seq) {
                1.0
            } else {
                PARALLEL_FACTOR_SPEEDUP
            };
            let flops = plan.flops.0 / speedup;
            self.lagged = Some(LaggedSolve::new(a.n, flops, plan.factor_nnz(), a.nnz()));
        }
        if let Some(lagged) = self.lagged.as_mut().filter(|l| plan.factored() && l.worth_trying()) {
            let started = Instant::now();
            let solved = lagged.solve(plan, a, b, Par::Seq);
            self.times.solve_time += started.elapsed();
            if solved {
                return true;
            }
        }
        match factorize_and_solve(plan, a, b, par, &mut self.times) {
            Ok(()) => {
                self.inertia = Some(plan.inertia());
                if let Some(lagged) = self.lagged.as_mut() {
                    lagged.factorized();
                }
                self.ldlt_stats.solves += 1;
                true
            }
            Err(e) => {
                self.ldlt_stats.fallbacks += 1;
                if let LinearError::Symmetric(why) = e {
                    self.ldlt_stats.last_failure = Some(why);
                }
                self.ldlt = None;
                false
            }
        }
    }

    /// Solve with faer's sparse LU (its symbolic analysis made once per pattern).
    fn solve_lu(&mut self, a: &SparseMatrix, b: &mut [f64], par: Par) -> Result<(), LinearError> {
        if self.lu.is_none() {
            let started = Instant::now();
            self.lu = Some(LuPlan::new(a.symbolic(), par)?);
            self.times.factor_time += started.elapsed();
            self.symbolic_factorizations += 1;
        }
        let lu = self.lu.as_mut().expect("set above");
        factorize_and_solve(lu, a, b, par, &mut self.times)
    }
}

fn add_lagged(sum: &mut LaggedStats, s: &LaggedStats) {
    sum.solves += s.solves;
    sum.iterations += s.iterations;
    sum.max_iterations = sum.max_iterations.max(s.max_iterations);
    sum.abandoned += s.abandoned;
}

/// Factorise and solve with one plan, timing both steps.
fn factorize_and_solve(
    plan: &mut dyn Factorization,
    a: &SparseMatrix,
    b: &mut [f64],
    par: Par,
    times: &mut SolveTimes,
) -> Result<(), LinearError> {
    let started = Instant::now();
    let factored = plan.factorize(a, par);
    let done = Instant::now();
    times.factor_time += done - started;
    factored?;
    times.factorizations += 1;
    let solved = plan.solve(a, b, par);
    times.solve_time += done.elapsed();
    solved
}

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
#[path = "chooser_tests.rs"]
mod tests;
