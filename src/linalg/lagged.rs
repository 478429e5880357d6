//! Newton systems solved by conjugate gradients preconditioned with the factorisation of an
//! earlier tangent of the same pattern, while that is cheaper than a new factorisation.
//!
//! Between two Newton iterations, or two increments, a tangent changes by the material's
//! response to the last correction and by the contact points that opened or closed: the
//! preconditioned operator `K_old⁻¹ K` is the identity plus a perturbation whose
//! eigenvalues cluster near zero, apart from a few (one per contact point that changed
//! state), so conjugate gradients converge in a few iterations, each one product with `K`
//! and one forward and backward substitution with the kept factor (Saad, *Iterative Methods
//! for Sparse Linear Systems*, 2nd ed., §9.2, Algorithm 9.1; the lagged preconditioner of
//! PETSc's `-snes_lag_preconditioner`). On a 3D mesh a factorisation costs tens of
//! substitutions (docs/large-models.md).
//!
//! When to refactorise follows a cost model, not the clock, so that a run's results do not
//! depend on how fast the machine was at the time: `budget` = the factorisation's flops
//! (`Σ m_j²`, [`super::ldlt::factor_flops`]) / ([`SUBSTITUTION_COST`] × the values read by
//! one iteration: twice the factor's, once the tangent's). A lagged solve is tried only
//! when the budget allows at least [`MIN_BUDGET_ITERATIONS`] and the last lagged solve
//! since the factorisation took fewer iterations than the budget; it stops at the budget,
//! and then the tangent is factorised as usual (so a solve costs at most about twice a
//! factorisation, and the next one is direct again). A solve stops at the relative residual
//! [`super::iterative::RELATIVE_TOLERANCE`], as the multigrid solver's do; a breakdown (the
//! old factor indefinite where the tangent is not) also hands the solve to a new
//! factorisation.

use super::iterative::RELATIVE_TOLERANCE;
use super::ldlt::LdltPlan;
use super::sparse::SparseMatrix;
use faer::Par;

/// Time of one value read in a substitution, in multiply-adds of the factorisation: the
/// factorisation works on dense blocks in cache, a substitution streams the factor from
/// memory. Measured 2026-11-29 on this project's 2-core machine (`contrail run hertz-3d`
/// on 32×32×24 and on a 56×56×10 plate, one factorisation ≈ 5 s for 1.07·10¹¹ and
/// 8.6·10¹⁰ `Σ m_j²`, one iteration ≈ 0.1 s for 1.6·10⁸ values): 12 both times.
pub const SUBSTITUTION_COST: f64 = 12.0;

/// A lagged solve is tried only when a factorisation costs at least this many iterations:
/// from a lagged factor, conjugate gradients need a few iterations to gain nine digits,
/// so a smaller budget would mostly end in a factorisation after all.
pub const MIN_BUDGET_ITERATIONS: usize = 8;

/// Counts of the lagged solves of a run.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct LaggedStats {
    /// Solves made with an earlier tangent's factor.
    pub solves: usize,
    pub iterations: usize,
    pub max_iterations: usize,
    /// Lagged solves given up (budget spent or a breakdown); a factorisation followed.
    pub abandoned: usize,
}

/// The state of the lagged solves of one pattern: work vectors and the measured costs.
pub struct LaggedSolve {
    x: Vec<f64>,
    r: Vec<f64>,
    z: Vec<f64>,
    p: Vec<f64>,
    q: Vec<f64>,
    /// Iterations that cost about one factorisation.
    budget: usize,
    /// Iterations of the last lagged solve since the last factorisation (the estimate of
    /// the next one's).
    last_iterations: usize,
    pub stats: LaggedStats,
}

impl LaggedSolve {
    /// The lagged solves of an `n`-unknown pattern whose factorisation costs `factor_flops`
    /// (`Σ m_j²`), with `factor_values` values in the factor and `matrix_values` in the tangent.
    pub fn new(n: usize, factor_flops: f64, factor_values: usize, matrix_values: usize) -> Self {
        let per_iteration = SUBSTITUTION_COST * (2 * factor_values + matrix_values) as f64;
        LaggedSolve {
            x: vec![0.0; n],
            r: vec![0.0; n],
            z: vec![0.0; n],
            p: vec![0.0; n],
            q: vec![0.0; n],
            budget: (factor_flops / per_iteration.max(1.0)) as usize,
            last_iterations: 0,
            stats: LaggedStats::default(),
        }
    }

    /// Note a new factorisation: the next solve may use it.
    pub fn factorized(&mut self) {
        self.last_iterations = 0;
    }

    /// Iterations that cost about as much as one factorisation.
    pub fn budget(&self) -> usize {
        self.budget
    }

    /// Whether the next solve should try the kept factor.
    pub fn worth_trying(&self) -> bool {
        self.budget >= MIN_BUDGET_ITERATIONS && self.last_iterations < self.budget
    }

    /// Solve `a x = b` in place by conjugate gradients preconditioned with `factor` (an
    /// earlier tangent's); returns whether it converged within the budget (`b` untouched
    /// when not).
    pub fn solve(&mut self, factor: &mut LdltPlan, a: &SparseMatrix, b: &mut [f64], par: Par) -> bool {
        let (converged, k) = self.conjugate_gradients(factor, a, b, self.budget, par);
        match converged {
            true => {
                self.last_iterations = k;
                self.stats.solves += 1;
                self.stats.iterations += k;
                self.stats.max_iterations = self.stats.max_iterations.max(k);
                b.copy_from_slice(&self.x);
                true
            }
            false => {
                self.stats.abandoned += 1;
                false
            }
        }
    }

    /// Preconditioned conjugate gradients from `x = 0` (Saad, Algorithm 9.1) into `self.x`:
    /// whether the tolerance was reached (not past `max_iterations`, no breakdown), and the
    /// iterations made.
    fn conjugate_gradients(
        &mut self,
        factor: &mut LdltPlan,
        a: &SparseMatrix,
        b: &[f64],
        max_iterations: usize,
        par: Par,
    ) -> (bool, usize) {
        let target = RELATIVE_TOLERANCE * norm(b);
        self.x.fill(0.0);
        if target == 0.0 {
            return (true, 0);
        }
        self.r.copy_from_slice(b);
        self.z.copy_from_slice(b);
        factor.precondition(&mut self.z, par);
        self.p.copy_from_slice(&self.z);
        let mut rz = dot(&self.r, &self.z);
        for k in 1..=max_iterations {
            product(a, &self.p, &mut self.q);
            let pq = dot(&self.p, &self.q);
            if !(rz > 0.0 && pq > 0.0) {
                return (false, k);
            }
            let alpha = rz / pq;
            axpy(alpha, &self.p, &mut self.x);
            axpy(-alpha, &self.q, &mut self.r);
            if norm(&self.r) <= target {
                return (true, k);
            }
            self.z.copy_from_slice(&self.r);
            factor.precondition(&mut self.z, par);
            let rz_next = dot(&self.r, &self.z);
            let beta = rz_next / rz;
            rz = rz_next;
            for (p, z) in self.p.iter_mut().zip(&self.z) {
                *p = z + beta * *p;
            }
        }
        (false, max_iterations)
    }
}

/// `y = A x` for `A` stored whole (both triangles) by compressed columns.
fn product(a: &SparseMatrix, x: &[f64], y: &mut [f64]) {
    y.fill(0.0);
    for (c, xc) in x.iter().enumerate() {
        for k in a.col_ptr[c]..a.col_ptr[c + 1] {
            y[a.row_idx[k]] += a.values[k] * xc;
        }
    }
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

fn norm(a: &[f64]) -> f64 {
    dot(a, a).sqrt()
}

fn axpy(alpha: f64, x: &[f64], y: &mut [f64]) {
    for (y, x) in y.iter_mut().zip(x) {
        *y += alpha * x;
    }
}

#[cfg(test)]
mod tests {
    use super::super::dissection::tests::hex_grid;
    use super::super::ldlt::LdltPlan;
    use super::*;

    /// A factor of `K₀` preconditions a solve with `K₁ = K₀` + stiff springs on a few
    /// unknowns (contact points that closed): the solution is the direct one's to the
    /// tolerance, in about one iteration per spring.
    #[test]
    fn an_earlier_factor_solves_a_changed_tangent() {
        let (mut a, nodes) = hex_grid(6, 6, 4, true, 0);
        let mut plan = LdltPlan::new(a.n, &a.col_ptr, &a.row_idx, &a.values, Some(&nodes), Par::Seq).unwrap();
        plan.factorize(a.symbolic(), &a.values, Par::Seq).unwrap();
        let springs = [5, 40, 77, 200, 311];
        for &i in &springs {
            let k = a.index(i, i).unwrap();
            a.values[k] *= 1e4;
        }
        for v in a.values.iter_mut() {
            *v *= 1.0 + 1e-3;
        }
        let x: Vec<f64> = (0..a.n).map(|i| ((i * 5) % 11) as f64 - 5.0).collect();
        let mut b = vec![0.0; a.n];
        a.mul(&x, &mut b);
        let mut lagged = LaggedSolve::new(a.n, 1e12, 1, 1);
        assert!(lagged.worth_trying());
        assert!(lagged.solve(&mut plan, &a, &mut b, Par::Seq));
        let err = b.iter().zip(&x).fold(0.0f64, |m, (u, v)| m.max((u - v).abs()));
        assert!(err < 1e-7, "{err:e}");
        let k = lagged.stats.iterations;
        assert!((1..=springs.len() + 6).contains(&k), "{k} iterations");
    }

    /// No budget (a factorisation as cheap as a few iterations): not tried; a budget spent
    /// without convergence: given up, `b` untouched.
    #[test]
    fn a_small_budget_is_not_tried_and_a_spent_one_gives_up() {
        let (mut a, nodes) = hex_grid(4, 4, 4, true, 0);
        let mut plan = LdltPlan::new(a.n, &a.col_ptr, &a.row_idx, &a.values, Some(&nodes), Par::Seq).unwrap();
        plan.factorize(a.symbolic(), &a.values, Par::Seq).unwrap();
        let values = a.nnz() + 2 * plan.factor_nnz();
        let lagged = LaggedSolve::new(a.n, SUBSTITUTION_COST * values as f64 * 7.5, plan.factor_nnz(), a.nnz());
        assert_eq!(lagged.budget(), 7);
        assert!(!lagged.worth_trying());
        // every diagonal changed by a different factor: far from the factored matrix
        for c in 0..a.n {
            let k = a.index(c, c).unwrap();
            a.values[k] *= 1.0 + 40.0 * ((c * 37) % 17) as f64;
        }
        let mut lagged = LaggedSolve::new(a.n, SUBSTITUTION_COST * values as f64 * 8.0, plan.factor_nnz(), a.nnz());
        assert!(lagged.worth_trying());
        let mut b = vec![1.0; a.n];
        assert!(!lagged.solve(&mut plan, &a, &mut b, Par::Seq));
        assert!(b.iter().all(|&v| v == 1.0));
        assert_eq!(lagged.stats.abandoned, 1);
    }
}
