//! Iterative solution of the Newton system for large models: conjugate gradients (a
//! symmetric tangent) or BiCGStab (an unsymmetric one, e.g. with friction), both faer's,
//! preconditioned by smoothed-aggregation multigrid ([`super::amg`]) built on the rigid-body
//! modes of the mesh nodes.
//!
//! A direct factorisation of a 2D mesh costs at least `O(n^1.5)` operations (Hoffman, Martin
//! & Rose 1973); a multigrid-preconditioned Krylov solve costs `O(n)` per iteration with an
//! iteration count that grows slowly with `n`. The hierarchy is not rebuilt for every
//! tangent: the finest level (and so the smoother and the Krylov operator) always holds the
//! current tangent, the coarse levels are kept while the extra Krylov iterations they cost,
//! summed since the last build, take less time than a build did. A solve that does not
//! converge with a kept hierarchy is retried with a new one; one that fails with a fresh
//! hierarchy is reported, and the caller ([`super::chooser::LinearSolve::solve`]) falls back to
//! the direct LU.

use super::aggregation::MeshNodes;
use super::amg::{Hierarchy, NearNullSpace};
use super::csr::Csr;
use crate::team::Team;
use faer::dyn_stack::{MemBuffer, MemStack, StackReq};
use faer::matrix_free::bicgstab::{bicgstab, bicgstab_scratch, BicgParams};
use faer::matrix_free::conjugate_gradient::{conjugate_gradient, conjugate_gradient_scratch, CgParams};
use faer::matrix_free::{IdentityPrecond, InitialGuessStatus, LinOp, Precond};
use faer::{Mat, MatMut, MatRef, Par};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

/// Relative residual `‖b − A x‖ / ‖b‖` at which the Krylov solve stops: far below what a
/// Newton iteration needs (an inexact Newton step with forcing term η converges as
/// `‖R_{k+1}‖ ≲ η ‖R_k‖ + C ‖R_k‖²`), so the iteration counts match the direct solver's.
pub const RELATIVE_TOLERANCE: f64 = 1e-9;

/// A node direction stiffer than this many times the node's couplings is treated as held
/// (see [`NearNullSpace::constrain_stiff_directions`]).
pub const STIFF_NODE_FACTOR: f64 = 2.0;

/// Most Krylov iterations per solve.
pub const MAX_ITERATIONS: usize = 400;

/// Counts of the iterative solves of a run.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct IterativeStats {
    pub solves: usize,
    /// Of which with conjugate gradients (the others with BiCGStab).
    pub cg_solves: usize,
    pub krylov_iterations: usize,
    pub max_krylov_iterations: usize,
    /// Multigrid hierarchies built.
    pub builds: usize,
    /// Solves that failed (the caller then used the direct LU).
    pub failures: usize,
    /// Unknowns per level of the last hierarchy (finest first), and its operator complexity.
    pub levels: [usize; 8],
    pub complexity: f64,
    /// Nodes whose stiff direction was taken out of the near-null space at the last build.
    pub constrained_nodes: usize,
}

/// Why an iterative solve gave up.
#[derive(Debug, Clone, thiserror::Error)]
#[error("{method} did not converge: relative residual {residual:.2e} after {iterations} iterations")]
pub struct IterativeFailure {
    pub method: &'static str,
    pub residual: f64,
    pub iterations: usize,
}

/// The iterative solver of one sparsity pattern.
pub struct IterativePlan {
    /// The tangent by rows; `fine.val[k] = values[from_csc[k]]`.
    fine: Csr,
    from_csc: Vec<usize>,
    /// For each stored entry (compressed-column order), the slot of its transposed entry, or
    /// `usize::MAX` when that is not stored; and the slots of the diagonal.
    mirror: Vec<usize>,
    diag_slot: Vec<usize>,
    /// Every entry has its transposed one stored and every diagonal entry is stored (the
    /// symmetry test and the multigrid need both).
    structurally_symmetric: bool,
    nodes: MeshNodes,
    /// The run's team: it shares the products and the finest level's smoothing.
    team: Option<Arc<Team>>,
    hierarchy: Option<Mutex<Hierarchy>>,
    build_time: Duration,
    iterations_after_build: usize,
    /// Time lost to the kept hierarchy: extra iterations since the build × time per iteration.
    lag_cost: Duration,
    scratch: MemBuffer,
    x: Mat<f64>,
    b: Mat<f64>,
    pub stats: IterativeStats,
    /// Time spent setting up the multigrid hierarchy in the last solve.
    pub last_setup: Duration,
}

/// The tangent as a faer operator (its product shared among the team, if any).
#[derive(Debug)]
struct Operator<'a>(&'a Csr, Option<&'a Team>);

/// A V-cycle as a faer preconditioner.
#[derive(Debug)]
struct VCycle<'a> {
    hierarchy: &'a Mutex<Hierarchy>,
    n: usize,
}

fn column(m: MatRef<'_, f64>) -> &[f64] {
    m.col(0).try_as_col_major().expect("contiguous column").as_slice()
}

fn column_mut(m: MatMut<'_, f64>) -> &mut [f64] {
    m.col_mut(0)
        .try_as_col_major_mut()
        .expect("contiguous column")
        .as_slice_mut()
}

impl LinOp<f64> for Operator<'_> {
    fn apply_scratch(&self, _: usize, _: Par) -> StackReq {
        StackReq::EMPTY
    }
    fn nrows(&self) -> usize {
        self.0.nrows
    }
    fn ncols(&self) -> usize {
        self.0.ncols
    }
    fn apply(&self, out: MatMut<'_, f64>, rhs: MatRef<'_, f64>, _: Par, _: &mut MemStack) {
        super::par_csr::mul(self.0, column(rhs), column_mut(out), self.1);
    }
    fn conj_apply(&self, out: MatMut<'_, f64>, rhs: MatRef<'_, f64>, par: Par, stack: &mut MemStack) {
        self.apply(out, rhs, par, stack);
    }
}

impl LinOp<f64> for VCycle<'_> {
    fn apply_scratch(&self, _: usize, _: Par) -> StackReq {
        StackReq::EMPTY
    }
    fn nrows(&self) -> usize {
        self.n
    }
    fn ncols(&self) -> usize {
        self.nrows()
    }
    fn apply(&self, out: MatMut<'_, f64>, rhs: MatRef<'_, f64>, _: Par, _: &mut MemStack) {
        let mut h = self.hierarchy.lock().unwrap_or_else(|e| e.into_inner());
        h.apply(column(rhs), column_mut(out));
    }
    fn conj_apply(&self, out: MatMut<'_, f64>, rhs: MatRef<'_, f64>, par: Par, stack: &mut MemStack) {
        self.apply(out, rhs, par, stack);
    }
}

impl Precond<f64> for VCycle<'_> {}

impl IterativePlan {
    /// The plan for the pattern `(col_ptr, row_idx)` of an `n × n` tangent whose unknowns
    /// belong to the given mesh nodes (free equations and reference position of each).
    pub fn new(n: usize, col_ptr: &[usize], row_idx: &[usize], nodes: &MeshNodes) -> Self {
        let index = |r: usize, c: usize| {
            let s = &row_idx[col_ptr[c]..col_ptr[c + 1]];
            s.binary_search(&r).ok().map(|k| col_ptr[c] + k)
        };
        let mut mirror = vec![usize::MAX; row_idx.len()];
        let mut diag_slot = vec![usize::MAX; n];
        let mut count = vec![0usize; n + 1];
        for c in 0..n {
            for k in col_ptr[c]..col_ptr[c + 1] {
                let r = row_idx[k];
                count[r + 1] += 1;
                mirror[k] = index(c, r).unwrap_or(usize::MAX);
                if r == c {
                    diag_slot[c] = k;
                }
            }
        }
        for r in 0..n {
            count[r + 1] += count[r];
        }
        let ptr = count.clone();
        let mut next = count;
        let mut idx = vec![0; row_idx.len()];
        let mut from_csc = vec![0; row_idx.len()];
        for c in 0..n {
            for (k, &r) in row_idx.iter().enumerate().take(col_ptr[c + 1]).skip(col_ptr[c]) {
                idx[next[r]] = c;
                from_csc[next[r]] = k;
                next[r] += 1;
            }
        }
        let fine = Csr {
            nrows: n,
            ncols: n,
            ptr,
            idx,
            val: vec![0.0; row_idx.len()],
        };
        // the scratch of both methods depends on n only (the operators ask for none)
        let (id, op) = (IdentityPrecond { dim: n }, Operator(&fine, None));
        let req = conjugate_gradient_scratch(id, &op, 1, Par::Seq).or(bicgstab_scratch(id, id, &op, 1, Par::Seq));
        IterativePlan {
            fine,
            from_csc,
            structurally_symmetric: !diag_slot.contains(&usize::MAX) && !mirror.contains(&usize::MAX),
            mirror,
            diag_slot,
            nodes: nodes.clone(),
            team: None,
            hierarchy: None,
            build_time: Duration::ZERO,
            iterations_after_build: 0,
            lag_cost: Duration::ZERO,
            scratch: MemBuffer::new(req),
            x: Mat::zeros(n, 1),
            b: Mat::zeros(n, 1),
            stats: IterativeStats::default(),
            last_setup: Duration::ZERO,
        }
    }

    /// Share the products and the finest level's smoothing with `team`.
    pub fn set_team(&mut self, team: Option<Arc<Team>>) {
        if let Some(h) = &self.hierarchy {
            h.lock().unwrap_or_else(|e| e.into_inner()).set_team(team.clone());
        }
        self.team = team;
    }

    /// Whether the values are symmetric: `|a_rc − a_cr| ≤ 1e-10 √(|a_rr a_cc|)` everywhere.
    fn symmetric(&self, values: &[f64]) -> bool {
        let d = |i: usize| values[self.diag_slot[i]].abs();
        (0..self.fine.nrows).all(|r| {
            (self.fine.ptr[r]..self.fine.ptr[r + 1]).all(|k| {
                let (c, slot) = (self.fine.idx[k], self.from_csc[k]);
                (values[slot] - values[self.mirror[slot]]).abs() <= 1e-10 * (d(r) * d(c)).sqrt()
            })
        })
    }

    /// Solve `A x = b` in place (`values` in compressed-column order); returns the time spent
    /// building the preconditioner.
    pub fn solve(&mut self, values: &[f64], b: &mut [f64]) -> Result<Duration, IterativeFailure> {
        if !self.structurally_symmetric {
            self.stats.failures += 1;
            return Err(IterativeFailure {
                method: "the iterative solver (pattern not structurally symmetric)",
                residual: f64::NAN,
                iterations: 0,
            });
        }
        for (v, &k) in self.fine.val.iter_mut().zip(&self.from_csc) {
            *v = values[k];
        }
        let symmetric = self.symmetric(values);
        let mut setup = Duration::ZERO;
        let mut fresh = self.hierarchy.is_none() || self.lag_cost > self.build_time;
        if fresh {
            setup += self.build();
        } else if let Some(h) = &self.hierarchy {
            h.lock()
                .unwrap_or_else(|e| e.into_inner())
                .set_fine_values(self.fine.val.iter().copied());
        }
        let mut started = Instant::now();
        let mut outcome = self.krylov(symmetric, b);
        if outcome.is_err() && !fresh {
            // the kept coarse levels may be what failed: once more with a new hierarchy
            setup += self.build();
            fresh = true;
            started = Instant::now();
            outcome = self.krylov(symmetric, b);
        }
        let elapsed = started.elapsed();
        match outcome {
            Ok((iterations, cg)) => {
                self.stats.solves += 1;
                self.stats.cg_solves += usize::from(cg);
                self.stats.krylov_iterations += iterations;
                self.stats.max_krylov_iterations = self.stats.max_krylov_iterations.max(iterations);
                if fresh {
                    self.iterations_after_build = iterations;
                } else if iterations > self.iterations_after_build {
                    let per = elapsed / iterations.max(1) as u32;
                    self.lag_cost += per * (iterations - self.iterations_after_build) as u32;
                }
                b.copy_from_slice(column(self.x.as_ref()));
                Ok(setup)
            }
            Err(e) => {
                self.stats.failures += 1;
                Err(e)
            }
        }
    }

    /// Build a new hierarchy from the current values; returns the time it took.
    fn build(&mut self) -> Duration {
        let started = Instant::now();
        let mut nns = NearNullSpace::rigid_body(self.fine.nrows, &self.nodes);
        self.stats.constrained_nodes = nns.constrain_stiff_directions(&self.fine, STIFF_NODE_FACTOR);
        let mut h = Hierarchy::new(self.fine.clone(), nns);
        h.set_team(self.team.clone());
        let sizes = h.sizes();
        self.stats.levels = [0; 8];
        for (l, s) in self.stats.levels.iter_mut().zip(&sizes) {
            *l = *s;
        }
        self.stats.complexity = h.operator_complexity();
        self.hierarchy = Some(Mutex::new(h));
        self.stats.builds += 1;
        self.build_time = started.elapsed();
        self.lag_cost = Duration::ZERO;
        self.build_time
    }

    /// One preconditioned Krylov solve of `A x = b` into `self.x`: conjugate gradients when
    /// `symmetric`, BiCGStab otherwise and when CG fails (a symmetric tangent may be
    /// indefinite, e.g. a penalty point deep inside a convex master in the first iterate of
    /// an increment; on the `hertz` scene unpreconditioned CG meets negative curvature too).
    /// Returns the iterations of the method that succeeded and whether it was CG.
    fn krylov(&mut self, symmetric: bool, b: &[f64]) -> Result<(usize, bool), IterativeFailure> {
        let Some(h) = &self.hierarchy else {
            return Err(IterativeFailure {
                method: "the iterative solver (no preconditioner)",
                residual: f64::NAN,
                iterations: 0,
            });
        };
        column_mut(self.b.as_mut()).copy_from_slice(b);
        self.x.fill(0.0);
        let par = Par::Seq;
        let stack = MemStack::new(&mut self.scratch);
        let m = VCycle {
            hierarchy: h,
            n: self.fine.nrows,
        };
        let a = Operator(&self.fine, self.team.as_deref());
        if symmetric {
            // x = 0, but not `InitialGuessStatus::Zero`: faer 0.24's CG then leaves its first
            // residual uninitialised (and so does its BiCGStab)
            let params = CgParams {
                initial_guess: InitialGuessStatus::MaybeNonZero,
                rel_tolerance: RELATIVE_TOLERANCE,
                max_iters: MAX_ITERATIONS,
                ..Default::default()
            };
            match conjugate_gradient(self.x.as_mut(), &m, &a, self.b.as_ref(), params, |_| {}, par, stack) {
                Ok(info) => return Ok((info.iter_count, true)),
                // not positive definite (or too slow): BiCGStab for this solve (making that
                // sticky was measured slower: on `punch-large` CG fails only in the first
                // iterate of an increment, and BiCGStab costs two V-cycles per iteration)
                Err(_) => self.x.fill(0.0),
            }
        }
        let params = BicgParams {
            initial_guess: InitialGuessStatus::MaybeNonZero,
            rel_tolerance: RELATIVE_TOLERANCE,
            max_iters: MAX_ITERATIONS,
            ..Default::default()
        };
        let stack = MemStack::new(&mut self.scratch);
        let id = IdentityPrecond { dim: self.fine.nrows };
        bicgstab(self.x.as_mut(), id, &m, &a, self.b.as_ref(), params, |_| {}, par, stack)
            .map(|info| (info.iter_count, false))
            .map_err(|e| {
                let (residual, iterations) = match e {
                    faer::matrix_free::bicgstab::BicgError::NoConvergence { rel_residual, .. } => {
                        (rel_residual, MAX_ITERATIONS)
                    }
                };
                IterativeFailure {
                    method: "multigrid-preconditioned BiCGStab",
                    residual,
                    iterations,
                }
            })
    }
}

#[cfg(test)]
mod tests {
    use super::super::chooser::{quad_grid_groups, LinearSolve, LinearSolver};
    use super::super::sparse::SparseMatrix;

    /// An `nx × ny` grid of 4-node cells with 2 unknowns per node and symmetric positive
    /// definite values (each cell adds `k (e eᵀ) + I/8`-like couplings), solved by the
    /// iterative and the direct solver.
    fn grid_system(nx: usize, ny: usize, unsymmetric: f64) -> (SparseMatrix, LinearSolve, Vec<f64>) {
        let groups = quad_grid_groups(nx, ny);
        // the left edge fixed: its unknowns are not equations (renumber the others)
        let nn = (nx + 1) * (ny + 1);
        let mut eq = vec![None; 2 * nn];
        let mut k = 0;
        for n in 0..nn {
            if n % (nx + 1) != 0 {
                eq[2 * n] = Some(k);
                eq[2 * n + 1] = Some(k + 1);
                k += 2;
            }
        }
        let groups: Vec<Vec<usize>> = groups
            .iter()
            .map(|g| g.iter().filter_map(|&d| eq[d]).collect())
            .collect();
        let mut a = SparseMatrix::new(k, &mut groups.clone().into_iter());
        for g in &groups {
            for &r in g {
                for &c in g {
                    let v = if r == c {
                        2.0
                    } else {
                        -2.0 / 7.0 + if r < c { unsymmetric } else { 0.0 }
                    };
                    let s = a.index(r, c).unwrap();
                    a.values[s] += v;
                }
            }
        }
        let nodes = (0..nn)
            .map(|n| {
                (
                    [eq[2 * n], eq[2 * n + 1]],
                    [(n % (nx + 1)) as f64, (n / (nx + 1)) as f64],
                )
            })
            .collect();
        let mut solve = LinearSolve::default();
        solve.set_nodes(super::super::aggregation::MeshNodes::Plane(nodes));
        (a, solve, (0..k).map(|i| (0.37 * i as f64).sin()).collect())
    }

    #[test]
    fn iterative_and_direct_solutions_agree() {
        for unsymmetric in [0.0, 0.02] {
            let (a, mut solve, b) = grid_system(40, 30, unsymmetric);
            let mut x_it = b.clone();
            solve.set_solver(LinearSolver::Iterative);
            solve.solve(&a, &mut x_it).unwrap();
            let stats = solve.iterative_stats();
            assert_eq!((stats.solves, stats.failures), (1, 0), "{stats:?}");
            assert_eq!(stats.cg_solves, usize::from(unsymmetric == 0.0));
            assert!(stats.krylov_iterations < 60, "{stats:?}");
            let mut x_lu = b.clone();
            solve.set_solver(LinearSolver::SparseLu);
            solve.solve(&a, &mut x_lu).unwrap();
            let scale = x_lu.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            for (i, (p, q)) in x_it.iter().zip(&x_lu).enumerate() {
                assert!((p - q).abs() < 1e-6 * scale, "x[{i}]: {p} vs {q}");
            }
        }
    }
}
