//! The finest level's work of the multigrid Krylov solver ([`super::iterative`],
//! [`super::amg`]) shared among the run's team of threads ([`crate::team::Team`], whose idle
//! workers sleep): the product `A x`, the residual `b − A x`, and a Gauss–Seidel sweep by
//! blocks of rows.
//!
//! The product and the residual are summed row by row in the same order on any number of
//! threads: the same bits as on one. Gauss–Seidel itself is sequential (row `i` needs the
//! rows before it), so a large system is swept by [`SMOOTHING_BLOCKS`] blocks of consecutive
//! rows, each sweeping its own rows with the values of the other blocks from before the sweep
//! (hybrid Gauss–Seidel), on the diagonal raised by the row's couplings to the other blocks,
//! `d_i + Σ_{j ∉ block(i)} |a_ij|` (ℓ1 Gauss–Seidel: Baker, Falgout, Kolev & Yang, SIAM J.
//! Sci. Comput. 33 (2011), which converges for any symmetric positive definite `A`, where
//! plain hybrid Gauss–Seidel may not). The forward sweep's adjoint is the backward sweep on
//! the same blocks, so the V-cycle stays symmetric for conjugate gradients. The blocks are
//! fixed by the system's size, never by the thread count: every thread count gives the same
//! bits.

use super::csr::Csr;
use crate::team::Team;
use std::sync::Mutex;

/// Systems with at least this many unknowns are smoothed by blocks, smaller ones by the
/// sequential sweep. A project choice, not a measured crossover: it keeps every system
/// below it (all the verification scenes' iterative runs) on the smoother they were checked
/// with; at 79 000 unknowns the blocks cost 7 % more Krylov iterations and save 30 % of an
/// iteration's time on 2 threads (docs/large-models.md).
pub const BLOCK_SMOOTHING_FROM: usize = 50_000;

/// Blocks of a block sweep: a project choice, as many as the threads of a 4-core machine
/// (more blocks weaken the smoother: Baker et al. 2011 bound its convergence for any count,
/// but each block boundary adds ℓ1 terms).
pub const SMOOTHING_BLOCKS: usize = 4;

/// Rows per piece of a product or a residual.
const ROWS_PER_PIECE: usize = 8192;

/// `y` cut into consecutive pieces of `rows` rows, each with its first row.
fn pieces(y: &mut [f64], rows: usize) -> Vec<Mutex<(usize, &mut [f64])>> {
    y.chunks_mut(rows.max(1))
        .enumerate()
        .map(|(k, c)| Mutex::new((k * rows.max(1), c)))
        .collect()
}

/// Run `job` on each piece, on the team or on the calling thread.
fn each<'a>(team: Option<&Team>, parts: &[Mutex<(usize, &'a mut [f64])>], job: &(dyn Fn(usize, &mut [f64]) + Sync)) {
    let one = |k: usize| {
        let mut part = parts[k].lock().unwrap_or_else(|e| e.into_inner());
        let (first, rows) = &mut *part;
        job(*first, rows);
    };
    match team {
        Some(t) if parts.len() > 1 => t.run(parts.len(), &one),
        _ => (0..parts.len()).for_each(one),
    }
}

/// `y = A x`, shared among `team`.
pub fn mul(a: &Csr, x: &[f64], y: &mut [f64], team: Option<&Team>) {
    let parts = pieces(&mut y[..a.nrows], ROWS_PER_PIECE);
    each(team, &parts, &|first, ys| {
        for (k, yr) in ys.iter_mut().enumerate() {
            let r = first + k;
            let mut s = 0.0;
            for e in a.ptr[r]..a.ptr[r + 1] {
                s += a.val[e] * x[a.idx[e]];
            }
            *yr = s;
        }
    });
}

/// `r = b − A x`, shared among `team`.
pub fn residual(a: &Csr, x: &[f64], b: &[f64], r: &mut [f64], team: Option<&Team>) {
    let parts = pieces(&mut r[..a.nrows], ROWS_PER_PIECE);
    each(team, &parts, &|first, rs| {
        for (k, ri) in rs.iter_mut().enumerate() {
            let i = first + k;
            let mut s = b[i];
            for e in a.ptr[i]..a.ptr[i + 1] {
                s -= a.val[e] * x[a.idx[e]];
            }
            *ri = s;
        }
    });
}

/// Rows per block of a block sweep of `n` rows.
fn block_rows(n: usize) -> usize {
    n.div_ceil(SMOOTHING_BLOCKS).max(1)
}

/// What a block sweep divides by: the ℓ1 diagonal `d_i + Σ_{j ∉ block(i)} |a_ij|` (`d` the
/// diagonal the sequential sweep divides by), and whether row `i` couples to another block at
/// all (the others read their own block's values only).
#[derive(Debug, Clone)]
pub struct BlockDiagonal {
    pub l1: Vec<f64>,
    pub crosses: Vec<bool>,
}

/// The [`BlockDiagonal`] of `a` on its blocks.
pub fn l1_diagonal(a: &Csr, diag: &[f64]) -> BlockDiagonal {
    let rows = block_rows(a.nrows);
    let (mut l1, mut crosses) = (Vec::with_capacity(a.nrows), Vec::with_capacity(a.nrows));
    for (i, d) in diag.iter().enumerate().take(a.nrows) {
        let block = i / rows;
        let off = (a.ptr[i]..a.ptr[i + 1]).filter(|&e| a.idx[e] / rows != block);
        crosses.push(off.clone().next().is_some());
        l1.push(d + off.map(|e| a.val[e].abs()).sum::<f64>());
    }
    BlockDiagonal { l1, crosses }
}

/// One block Gauss–Seidel sweep on `A x = b`, forward or backward, `blocks` the
/// [`BlockDiagonal`] of `A`; the blocks shared among `team`, `before` a scratch vector.
pub fn block_gauss_seidel(
    a: &Csr,
    blocks: &BlockDiagonal,
    b: &[f64],
    x: &mut [f64],
    backward: bool,
    (before, team): (&mut Vec<f64>, Option<&Team>),
) {
    // the other blocks' values from before the sweep (a scratch the caller keeps)
    before.clear();
    before.extend_from_slice(x);
    let before = &before[..];
    let rows = block_rows(a.nrows);
    let parts = pieces(&mut x[..a.nrows], rows);
    each(team, &parts, &|first, xs| {
        let last = first + xs.len();
        let mut row = |i: usize| {
            let mut s = b[i];
            let entries = a.ptr[i]..a.ptr[i + 1];
            if blocks.crosses[i] {
                for e in entries {
                    let j = a.idx[e];
                    let xj = if (first..last).contains(&j) {
                        xs[j - first]
                    } else {
                        before[j]
                    };
                    s -= a.val[e] * xj;
                }
            } else {
                for e in entries {
                    s -= a.val[e] * xs[a.idx[e] - first];
                }
            }
            // x_i += (b − A x)_i / ℓ1_i: Gauss–Seidel's update where ℓ1_i = a_ii (the sum
            // above took the row's own term with the current x_i)
            xs[i - first] += s / blocks.l1[i];
        };
        if backward {
            (first..last).rev().for_each(&mut row);
        } else {
            (first..last).for_each(&mut row);
        }
    });
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 1D Laplacian of `n` unknowns with a shifted diagonal (symmetric positive definite).
    fn laplacian(n: usize) -> Csr {
        let (mut ptr, mut idx, mut val) = (vec![0], Vec::new(), Vec::new());
        for i in 0..n {
            for (j, v) in [(i.wrapping_sub(1), -1.0), (i, 2.1), (i + 1, -1.0)] {
                if j < n {
                    idx.push(j);
                    val.push(v);
                }
            }
            ptr.push(idx.len());
        }
        Csr {
            nrows: n,
            ncols: n,
            ptr,
            idx,
            val,
        }
    }

    #[test]
    fn products_and_residuals_on_a_team_are_the_sequential_bits() {
        let a = laplacian(20_000);
        let x: Vec<f64> = (0..a.nrows).map(|i| (i as f64 * 0.37).sin()).collect();
        let b: Vec<f64> = (0..a.nrows).map(|i| (i as f64 * 0.11).cos()).collect();
        let (mut y1, mut y2) = (vec![0.0; a.nrows], vec![0.0; a.nrows]);
        a.mul(&x, &mut y1);
        let team = Team::new(2);
        mul(&a, &x, &mut y2, Some(&team));
        assert_eq!(y1, y2);
        a.residual(&x, &b, &mut y1);
        residual(&a, &x, &b, &mut y2, Some(&team));
        assert_eq!(y1, y2);
    }

    #[test]
    fn a_block_sweep_is_the_same_on_any_team_and_reduces_the_error() {
        let a = laplacian(4_000);
        let diag = a.diagonal();
        let l1 = l1_diagonal(&a, &diag);
        // only the rows next to a block boundary have a raised diagonal
        let raised = diag.iter().zip(&l1.l1).filter(|(d, l)| d != l).count();
        assert_eq!(raised, 2 * (SMOOTHING_BLOCKS - 1));
        assert_eq!(l1.crosses.iter().filter(|c| **c).count(), raised);
        let b = vec![1.0; a.nrows];
        let sweep = |team: Option<&Team>| {
            let mut x = vec![0.0; a.nrows];
            for k in 0..40 {
                block_gauss_seidel(&a, &l1, &b, &mut x, k % 2 == 1, (&mut Vec::new(), team));
            }
            x
        };
        let alone = sweep(None);
        let team = Team::new(3);
        assert_eq!(alone, sweep(Some(&team)));
        let mut r = vec![0.0; a.nrows];
        a.residual(&alone, &b, &mut r);
        let norm = |v: &[f64]| v.iter().map(|x| x * x).sum::<f64>().sqrt();
        assert!(norm(&r) < 0.05 * norm(&b), "{}", norm(&r) / norm(&b));
    }
}
