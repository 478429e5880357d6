//! Smoothed-aggregation algebraic multigrid (Vaněk, Mandel & Brezina, Computing 56, 1996)
//! for the tangent of 2D and 3D solids, used as the preconditioner of a Krylov solver on models too
//! large for a direct factorisation to scale (see [`super::iterative`]).
//!
//! Setup, per level `A_l` (the fine level is the tangent):
//! 1. **Aggregation** of the level's nodes (the DOF groups that share one near-null-space
//!    block: a mesh node on the fine level, an aggregate on the coarser ones) on the graph of
//!    `A_l`'s strong couplings (all of them by default, as pyamg does for SA): pass 1 makes
//!    an aggregate of every node whose neighbours are all still free, together with them;
//!    pass 2 adds each remaining node to the aggregate of a neighbour made in pass 1; pass 3
//!    groups what is left with its free neighbours.
//! 2. **Tentative prolongator** `P₀`: on each aggregate the rows of the near-null space `B`
//!    (on the fine level the rigid-body modes of a solid: in 2D the translations `(1, 0)`,
//!    `(0, 1)` and the rotation `(−y, x)`, in 3D three translations and three rotations, at
//!    each node's reference position) are
//!    orthonormalised (modified Gram–Schmidt, `B_agg = Q R`); `Q` is the aggregate's block of
//!    `P₀` and `R` its rows of the coarse near-null space, so `P₀ B_c = B` exactly.
//! 3. **Smoothed prolongator** `P = (I − ω D⁻¹ A) P₀`, `ω = 4 / (3 ρ(D⁻¹ A))`, `ρ` estimated by
//!    a power iteration; **Galerkin** coarse operator `A_{l+1} = Pᵀ A_l P`.
//!
//! Coarsening stops at [`COARSEST`] unknowns (or when a level no longer shrinks), where a
//! dense LU solves exactly. The V-cycle smooths with one forward Gauss–Seidel sweep before
//! and one backward sweep after the coarse correction, so for a symmetric positive definite
//! `A` it is a symmetric positive definite preconditioner (for conjugate gradients). The
//! finest level of a system of at least [`par_csr::BLOCK_SMOOTHING_FROM`] unknowns is swept by
//! ℓ1 Gauss–Seidel on blocks of rows, its sweeps and residuals shared among the run's team
//! ([`par_csr`]; the same bits on any number of threads).

pub use super::aggregation::NearNullSpace;
use super::aggregation::{aggregate, tentative};
use super::csr::Csr;
use super::par_csr;
use crate::team::Team;
use faer::linalg::solvers::{PartialPivLu, Solve};
use faer::{Mat, MatMut};
use std::sync::Arc;

/// Levels with at most this many unknowns are solved by a dense LU.
pub const COARSEST: usize = 400;

/// Strength threshold θ of the finest level's aggregation. Measured on `punch-large`
/// (bilinear elements up to 33:1 near the symmetry axis) at 1e4 unknowns: θ = 0 needs 132
/// CG iterations for a relative residual of 1e-9 at operator complexity 1.50; θ = 0.15, 96
/// at 2.06; θ = 0.25, 98 at 3.22; θ = 0.05–0.1, 148–175 — none faster overall, so all
/// couplings count as strong (as pyamg's default for smoothed aggregation).
pub const STRENGTH_THRESHOLD: f64 = 0.0;

/// Most levels of a hierarchy.
const MAX_LEVELS: usize = 12;

/// One level of the hierarchy.
#[derive(Debug)]
struct Level {
    a: Csr,
    diag: Vec<f64>,
    /// The ℓ1 diagonal of a level smoothed by blocks ([`par_csr`]; the finest of a large
    /// system), none where the sweep is sequential.
    l1: Option<par_csr::BlockDiagonal>,
    /// Prolongator from the next coarser level, and its transpose.
    p: Csr,
    r: Csr,
}

/// Vectors of one level used by the V-cycle.
#[derive(Debug, Default)]
struct Work {
    x: Vec<f64>,
    b: Vec<f64>,
    res: Vec<f64>,
    /// The block smoother's copy of `x` from before a sweep (empty where the sweep is
    /// sequential).
    before: Vec<f64>,
}

/// A multigrid hierarchy and the coarsest level's factorisation.
#[derive(Debug)]
pub struct Hierarchy {
    levels: Vec<Level>,
    /// The run's team, which shares the finest level's work (none: the calling thread).
    team: Option<Arc<Team>>,
    coarse: PartialPivLu<f64>,
    coarse_n: usize,
    work: Vec<Work>,
}

impl Hierarchy {
    /// Build the hierarchy of the fine operator `a` with near-null space `nns`, all
    /// couplings strong ([`STRENGTH_THRESHOLD`]).
    pub fn new(a: Csr, nns: NearNullSpace) -> Hierarchy {
        Self::with_strength(a, nns, STRENGTH_THRESHOLD)
    }

    /// Build the hierarchy with strength threshold `theta` on the finest level (all couplings
    /// strong on the coarser ones, whose aggregates are no longer stretched).
    pub fn with_strength(a: Csr, mut nns: NearNullSpace, theta: f64) -> Hierarchy {
        let mut levels = Vec::new();
        let mut a = a;
        while a.nrows > COARSEST && levels.len() + 1 < MAX_LEVELS {
            let (aggregates, filtered) = aggregate(&a, &nns.nodes, if levels.is_empty() { theta } else { 0.0 });
            let (p0, coarse_nns) = tentative(a.nrows, &nns, &aggregates);
            if p0.ncols * 10 > a.nrows * 9 {
                break; // no longer coarsening
            }
            let diag = smoothing_diagonal(&a);
            let af = filtered.as_ref().unwrap_or(&a);
            let fdiag = smoothing_diagonal(af);
            let omega = 4.0 / (3.0 * spectral_radius_dinv_a(af, &fdiag));
            let p = af.matmul_then(&p0, |r, c, v| p0.get(r, c) - omega / fdiag[r] * v);
            let r = p.transpose();
            let coarse = r.matmul(&a.matmul(&p));
            let l1 = (levels.is_empty() && a.nrows >= par_csr::BLOCK_SMOOTHING_FROM)
                .then(|| par_csr::l1_diagonal(&a, &diag));
            levels.push(Level { a, diag, l1, p, r });
            a = coarse;
            nns = coarse_nns;
        }
        let coarse_n = a.nrows;
        let dense = Mat::from_fn(coarse_n, coarse_n, |i, j| a.get(i, j));
        let coarse = PartialPivLu::new(dense.as_ref());
        let mut work: Vec<Work> = levels
            .iter()
            .map(|l| Work {
                x: vec![0.0; l.a.nrows],
                b: vec![0.0; l.a.nrows],
                res: vec![0.0; l.a.nrows],
                before: Vec::new(),
            })
            .collect();
        work.push(Work {
            x: vec![0.0; coarse_n],
            b: vec![0.0; coarse_n],
            res: Vec::new(),
            before: Vec::new(),
        });
        Hierarchy {
            levels,
            team: None,
            coarse,
            coarse_n,
            work,
        }
    }

    /// Unknowns per level, finest first.
    pub fn sizes(&self) -> Vec<usize> {
        let mut s: Vec<usize> = self.levels.iter().map(|l| l.a.nrows).collect();
        s.push(self.coarse_n);
        s
    }

    /// Stored entries of all operators over those of the finest (operator complexity).
    pub fn operator_complexity(&self) -> f64 {
        let fine = self.levels.first().map_or(1, |l| l.a.val.len().max(1));
        let all: usize = self.levels.iter().map(|l| l.a.val.len()).sum::<usize>() + self.coarse_n * self.coarse_n;
        all as f64 / fine as f64
    }

    /// Replace the values of the finest operator (same pattern) — the coarse levels are kept
    /// (a preconditioner may lag behind the tangent).
    pub fn set_fine_values(&mut self, val: impl Iterator<Item = f64>) {
        if let Some(l) = self.levels.first_mut() {
            for (dst, v) in l.a.val.iter_mut().zip(val) {
                *dst = v;
            }
            l.diag = smoothing_diagonal(&l.a);
            if l.l1.is_some() {
                l.l1 = Some(par_csr::l1_diagonal(&l.a, &l.diag));
            }
        }
    }

    /// Share the finest level's work with `team` (the same bits on any team).
    pub fn set_team(&mut self, team: Option<Arc<Team>>) {
        self.team = team;
    }

    /// One V-cycle: `x ≈ A⁻¹ b` (x is overwritten).
    pub fn apply(&mut self, b: &[f64], x: &mut [f64]) {
        if self.levels.is_empty() {
            x.copy_from_slice(b);
            let mut m = MatMut::from_column_major_slice_mut(x, self.coarse_n, 1);
            self.coarse.solve_in_place(m.as_mut());
            return;
        }
        self.work[0].b.copy_from_slice(b);
        self.cycle(0);
        x.copy_from_slice(&self.work[0].x);
    }

    fn cycle(&mut self, l: usize) {
        if l == self.levels.len() {
            let w = &mut self.work[l];
            w.x.copy_from_slice(&w.b);
            let m = MatMut::from_column_major_slice_mut(&mut w.x, self.coarse_n, 1);
            self.coarse.solve_in_place(m);
            return;
        }
        let lev = &self.levels[l];
        let team = self.team.as_deref();
        {
            let w = &mut self.work[l];
            w.x.fill(0.0);
            smooth(lev, w, false, team);
            par_csr::residual(&lev.a, &w.x, &w.b, &mut w.res, team);
        }
        let (fine, coarse) = self.work.split_at_mut(l + 1);
        lev.r.mul(&fine[l].res, &mut coarse[0].b);
        self.cycle(l + 1);
        let lev = &self.levels[l];
        let (fine, coarse) = self.work.split_at_mut(l + 1);
        let w = &mut fine[l];
        lev.p.mul_add(&coarse[0].x, &mut w.x);
        smooth(lev, w, true, self.team.as_deref());
    }
}

/// One smoothing sweep of a level: by blocks where it has an ℓ1 diagonal, else sequential.
fn smooth(lev: &Level, w: &mut Work, backward: bool, team: Option<&Team>) {
    match &lev.l1 {
        Some(l1) => par_csr::block_gauss_seidel(&lev.a, l1, &w.b, &mut w.x, backward, (&mut w.before, team)),
        None => gauss_seidel(&lev.a, &lev.diag, &w.b, &mut w.x, backward),
    }
}

/// The diagonal for Gauss–Seidel and the prolongator smoothing, 1 where it is zero (a row
/// the pattern keeps but nothing fills).
fn smoothing_diagonal(a: &Csr) -> Vec<f64> {
    a.diagonal()
        .into_iter()
        .map(|d| if d != 0.0 { d } else { 1.0 })
        .collect()
}

/// One Gauss–Seidel sweep on `A x = b`, forward or backward.
fn gauss_seidel(a: &Csr, diag: &[f64], b: &[f64], x: &mut [f64], backward: bool) {
    let mut row = |i: usize| {
        let mut s = b[i];
        for k in a.ptr[i]..a.ptr[i + 1] {
            let j = a.idx[k];
            if j != i {
                s -= a.val[k] * x[j];
            }
        }
        x[i] = s / diag[i];
    };
    if backward {
        (0..a.nrows).rev().for_each(&mut row);
    } else {
        (0..a.nrows).for_each(&mut row);
    }
}

/// `ρ(D⁻¹ A)` by 15 steps of the power iteration (an estimate from below, raised by 5 %).
fn spectral_radius_dinv_a(a: &Csr, diag: &[f64]) -> f64 {
    let n = a.nrows;
    let mut x: Vec<f64> = (0..n).map(|i| 1.0 + 0.5 * ((i as f64) * 0.754_877_666).sin()).collect();
    let mut y = vec![0.0; n];
    let mut rho = 1.0;
    for _ in 0..15 {
        let nx = x.iter().map(|v| v * v).sum::<f64>().sqrt();
        if nx == 0.0 {
            break;
        }
        x.iter_mut().for_each(|v| *v /= nx);
        a.mul(&x, &mut y);
        y.iter_mut().zip(diag).for_each(|(v, d)| *v /= d);
        rho = y.iter().map(|v| v * v).sum::<f64>().sqrt();
        std::mem::swap(&mut x, &mut y);
    }
    if rho.is_finite() && rho > 0.0 {
        1.05 * rho
    } else {
        1.0
    }
}

#[cfg(test)]
mod tests {
    use super::super::aggregation::MeshNode;
    use super::*;

    /// A stand-in for a Q4 tangent: a grid of nodes with 2 unknowns each, coupled as two
    /// independent 9-point Laplacians (every node with its 8 neighbours) plus a small shift.
    fn grid(nx: usize, ny: usize) -> (Csr, Vec<MeshNode>) {
        stretched_grid(nx, ny, 1.0)
    }

    /// The same with the bilinear elements' stencil for cells `r` times taller than wide:
    /// centre `4/3 (r + 1/r)`, left/right `−2r/3 + 1/(3r)`, up/down `r/3 − 2/(3r)` (positive
    /// for `r > √2`), diagonal `−(r + 1/r)/6`.
    fn stretched_grid(nx: usize, ny: usize, r: f64) -> (Csr, Vec<MeshNode>) {
        let id = |i: usize, j: usize| j * nx + i;
        let n = 2 * nx * ny;
        let mut a = Csr {
            nrows: n,
            ncols: n,
            ptr: vec![0],
            ..Default::default()
        };
        let mut nodes = Vec::new();
        for j in 0..ny {
            for i in 0..nx {
                nodes.push(([Some(2 * id(i, j)), Some(2 * id(i, j) + 1)], [i as f64, j as f64]));
            }
        }
        for row in 0..n {
            let (node, c) = (row / 2, row % 2);
            let (i, j) = (node % nx, node / nx);
            let (side, updown, diagonal) = if r == 1.0 {
                (-1.0, -1.0, -1.0)
            } else {
                (
                    -2.0 * r / 3.0 + 1.0 / (3.0 * r),
                    r / 3.0 - 2.0 / (3.0 * r),
                    -(r + 1.0 / r) / 6.0,
                )
            };
            let centre = if r == 1.0 { 8.0 } else { 4.0 / 3.0 * (r + 1.0 / r) };
            a.idx.push(row);
            a.val.push(centre + 1e-3);
            for jj in j.saturating_sub(1)..(j + 2).min(ny) {
                for ii in i.saturating_sub(1)..(i + 2).min(nx) {
                    if (ii, jj) != (i, j) {
                        a.idx.push(2 * id(ii, jj) + c);
                        a.val.push(match (ii == i, jj == j) {
                            (false, true) => side,
                            (true, false) => updown,
                            _ => diagonal,
                        });
                    }
                }
            }
            a.ptr.push(a.idx.len());
        }
        (a, nodes)
    }

    #[test]
    fn v_cycles_reduce_the_error_of_a_grid_problem_fast() {
        let (a, nodes) = grid(60, 60);
        let n = a.nrows;
        let nns = NearNullSpace::rigid_body_2d(n, &nodes);
        let mut h = Hierarchy::new(a.clone(), nns);
        assert!(h.sizes().len() >= 3, "levels {:?}", h.sizes());
        assert!(h.operator_complexity() < 2.5, "complexity {}", h.operator_complexity());
        // stationary iteration x ← x + M⁻¹ (b − A x)
        let b: Vec<f64> = (0..n).map(|i| ((i * 7) % 13) as f64 - 6.0).collect();
        let mut x = vec![0.0; n];
        let (mut r, mut dx) = (vec![0.0; n], vec![0.0; n]);
        let norm = |v: &[f64]| v.iter().map(|x| x * x).sum::<f64>().sqrt();
        let r0 = norm(&b);
        for _ in 0..10 {
            a.residual(&x, &b, &mut r);
            h.apply(&r, &mut dx);
            x.iter_mut().zip(&dx).for_each(|(x, d)| *x += d);
        }
        a.residual(&x, &b, &mut r);
        let factor = (norm(&r) / r0).powf(0.1);
        eprintln!(
            "levels {:?}, complexity {:.2}, factor {factor:.3}",
            h.sizes(),
            h.operator_complexity()
        );
        assert!(factor < 0.3, "mean residual reduction per V-cycle {factor}");
    }

    /// Mean residual reduction per V-cycle of the stationary iteration `x ← x + M⁻¹ (b − A x)`.
    fn v_cycle_factor(a: &Csr, h: &mut Hierarchy, cycles: usize) -> f64 {
        let n = a.nrows;
        let b: Vec<f64> = (0..n).map(|i| ((i * 7) % 13) as f64 - 6.0).collect();
        let mut x = vec![0.0; n];
        let (mut r, mut dx) = (vec![0.0; n], vec![0.0; n]);
        let norm = |v: &[f64]| v.iter().map(|x| x * x).sum::<f64>().sqrt();
        for _ in 0..cycles {
            a.residual(&x, &b, &mut r);
            h.apply(&r, &mut dx);
            x.iter_mut().zip(&dx).for_each(|(x, d)| *x += d);
        }
        a.residual(&x, &b, &mut r);
        (norm(&r) / norm(&b)).powf(1.0 / cycles as f64)
    }

    /// On cells 16 times taller than wide a strength threshold makes the aggregates follow
    /// the stiff direction (semi-coarsening) and the cycle converge faster than aggregating
    /// every neighbour.
    #[test]
    fn strength_threshold_follows_the_anisotropy_of_stretched_cells() {
        let (a, nodes) = stretched_grid(120, 12, 16.0);
        let nns = || NearNullSpace::rigid_body_2d(a.nrows, &nodes);
        let mut all = Hierarchy::with_strength(a.clone(), nns(), 0.0);
        let mut strong = Hierarchy::with_strength(a.clone(), nns(), 0.25);
        let (f_all, f_strong) = (v_cycle_factor(&a, &mut all, 10), v_cycle_factor(&a, &mut strong, 10));
        eprintln!(
            "θ = 0: levels {:?}, factor {f_all:.3}; θ = 0.25: levels {:?}, factor {f_strong:.3}",
            all.sizes(),
            strong.sizes()
        );
        assert!(f_strong < f_all, "θ = 0.25: {f_strong}, θ = 0: {f_all}");
    }

    #[test]
    fn tentative_prolongator_reproduces_the_near_null_space() {
        let (a, nodes) = grid(9, 7);
        let nns = NearNullSpace::rigid_body_2d(a.nrows, &nodes);
        let (agg, _) = aggregate(&a, &nns.nodes, 0.0);
        let (p0, coarse) = tentative(a.nrows, &nns, &agg);
        for k in 0..3 {
            let bc: Vec<f64> = coarse.modes.iter().map(|m| m[k]).collect();
            let mut b = vec![0.0; a.nrows];
            p0.mul(&bc, &mut b);
            for (d, v) in b.iter().enumerate() {
                assert!((v - nns.modes[d][k]).abs() < 1e-12, "mode {k} at {d}");
            }
        }
        assert!(p0.ncols < a.nrows / 3, "{} of {}", p0.ncols, a.nrows);
    }

    /// A 3D grid of `n³` nodes at integer positions, each component coupled to the same
    /// component of its six neighbours (a Laplacian per component; the pattern is what the
    /// aggregation sees).
    fn grid_3d(n: usize) -> (Csr, Vec<super::super::aggregation::SolidNode>) {
        let id = |i: usize, j: usize, k: usize| (k * n + j) * n + i;
        let mut a = Csr {
            nrows: 3 * n * n * n,
            ncols: 3 * n * n * n,
            ptr: vec![0],
            ..Default::default()
        };
        let mut nodes = Vec::new();
        for k in 0..n {
            for j in 0..n {
                for i in 0..n {
                    let me = id(i, j, k);
                    nodes.push((
                        [Some(3 * me), Some(3 * me + 1), Some(3 * me + 2)],
                        [i as f64, j as f64, k as f64],
                    ));
                    for c in 0..3 {
                        let mut row: Vec<(usize, f64)> = vec![(3 * me + c, 6.0)];
                        let mut near = |ii: usize, jj: usize, kk: usize| row.push((3 * id(ii, jj, kk) + c, -1.0));
                        if i > 0 {
                            near(i - 1, j, k)
                        }
                        if i + 1 < n {
                            near(i + 1, j, k)
                        }
                        if j > 0 {
                            near(i, j - 1, k)
                        }
                        if j + 1 < n {
                            near(i, j + 1, k)
                        }
                        if k > 0 {
                            near(i, j, k - 1)
                        }
                        if k + 1 < n {
                            near(i, j, k + 1)
                        }
                        row.sort_by_key(|e| e.0);
                        for (col, v) in row {
                            a.idx.push(col);
                            a.val.push(v);
                        }
                        a.ptr.push(a.idx.len());
                    }
                }
            }
        }
        (a, nodes)
    }

    #[test]
    fn tentative_prolongator_reproduces_the_six_rigid_body_modes_in_3d() {
        use super::super::aggregation::MeshNodes;
        let (a, nodes) = grid_3d(6);
        let nns = NearNullSpace::rigid_body(a.nrows, &MeshNodes::Solid(nodes));
        assert_eq!(nns.count, 6);
        let (agg, _) = aggregate(&a, &nns.nodes, 0.0);
        let (p0, coarse) = tentative(a.nrows, &nns, &agg);
        for k in 0..6 {
            let bc: Vec<f64> = coarse.modes.iter().map(|m| m[k]).collect();
            let mut b = vec![0.0; a.nrows];
            p0.mul(&bc, &mut b);
            for (d, v) in b.iter().enumerate() {
                assert!((v - nns.modes[d][k]).abs() < 1e-12, "mode {k} at {d}");
            }
        }
        // an aggregate of a 3D grid spans all six modes: six coarse unknowns each
        let aggregates = agg.iter().max().unwrap() + 1;
        assert_eq!(
            p0.ncols,
            6 * aggregates,
            "{} columns for {aggregates} aggregates",
            p0.ncols
        );
        assert!(p0.ncols < a.nrows / 3, "{} of {}", p0.ncols, a.nrows);
    }
}
