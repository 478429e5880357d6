//! The solvers the chooser picks: the banded and the general LU agree, the pattern grows,
//! `LDLᵀ` solves symmetric matrices and falls back to the LU.

use super::*;
use crate::linalg::sparse::SparseMatrix;

#[test]
fn unsymmetric_solve_and_pattern_growth() {
    let mut groups = vec![vec![0, 1], vec![1, 2]].into_iter();
    let mut a = SparseMatrix::new(3, &mut groups);
    let mut solve = LinearSolve::default();
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
    solve.solve(&a, &mut b).unwrap();
    for i in 0..3 {
        assert!((b[i] - x[i]).abs() < 1e-14);
    }
    // refill values, same symbolic factorisation
    a.values.iter_mut().for_each(|v| *v *= 2.0);
    a.mul(&x, &mut b);
    solve.solve(&a, &mut b).unwrap();
    assert_eq!(solve.symbolic_factorizations, 1);
    assert!((b[1] + 2.0).abs() < 1e-14);
}

/// A strip of quads numbered along its length (wide band before reordering), with
/// unsymmetric values: the banded and the sparse LU give the same solution.
#[test]
fn banded_and_sparse_lu_agree_on_a_strip() {
    let (nx, ny) = (30, 3);
    let groups = quad_grid_groups(nx, ny);
    let n = 2 * (nx + 1) * (ny + 1);
    let fill = |a: &mut SparseMatrix| {
        for c in 0..n {
            for k in a.col_ptr[c]..a.col_ptr[c + 1] {
                let r = a.row_idx[k];
                a.values[k] = if r == c {
                    8.0
                } else {
                    ((3 * r + 7 * c) % 11) as f64 / 11.0 - 0.5
                };
            }
        }
    };
    let x: Vec<f64> = (0..n).map(|i| (0.3 * i as f64).cos()).collect();
    let mut solutions = Vec::new();
    for solver in [LinearSolver::Auto, LinearSolver::SparseLu] {
        let mut a = SparseMatrix::new(n, &mut groups.clone().into_iter());
        let mut s = LinearSolve::new(solver);
        fill(&mut a);
        let mut b = vec![0.0; n];
        a.mul(&x, &mut b);
        s.solve(&a, &mut b).unwrap();
        assert_eq!(s.band_widths().is_some(), solver == LinearSolver::Auto);
        if let Some((kl, ku)) = s.band_widths() {
            assert!(
                kl <= 20 && ku <= 20,
                "band ({kl}, {ku}) after RCM (column-wise numbering: 11)"
            );
        }
        solutions.push(b);
    }
    for (i, xi) in x.iter().enumerate() {
        assert!((solutions[0][i] - xi).abs() < 1e-12, "band x[{i}]");
        assert!((solutions[1][i] - xi).abs() < 1e-12, "sparse x[{i}]");
    }
}

/// Fill a grid pattern with symmetric, diagonally dominant values (`sym_part = 1`) plus an
/// antisymmetric part of size `skew`.
fn fill_grid(a: &mut SparseMatrix, diagonal: f64, skew: f64) {
    for c in 0..a.n {
        for k in a.col_ptr[c]..a.col_ptr[c + 1] {
            let r = a.row_idx[k];
            let (lo, hi) = (r.min(c), r.max(c));
            let sym = ((3 * lo + 7 * hi) % 11) as f64 / 11.0 - 0.5;
            let sign = if r < c { 1.0 } else { -1.0 };
            a.values[k] = if r == c { diagonal } else { sym + sign * skew };
        }
    }
}

/// `LDLᵀ` on a symmetric matrix: same solution as the LU, one plan, no fallback; the factor
/// stores less than the LU would (only one triangle).
#[test]
fn symmetric_matrix_is_solved_by_ldlt() {
    let (nx, ny) = (20, 20);
    let n = 2 * (nx + 1) * (ny + 1);
    let x: Vec<f64> = (0..n).map(|i| (0.3 * i as f64).cos()).collect();
    let mut solutions = Vec::new();
    for solver in [LinearSolver::General, LinearSolver::SparseLu] {
        let mut a = SparseMatrix::new(n, &mut quad_grid_groups(nx, ny).into_iter());
        let mut chooser = LinearSolve::new(solver);
        fill_grid(&mut a, 12.0, 0.0);
        let mut b = vec![0.0; n];
        a.mul(&x, &mut b);
        chooser.solve(&a, &mut b).unwrap();
        let s = chooser.ldlt_stats();
        if solver == LinearSolver::General {
            assert_eq!((s.plans, s.solves, s.fallbacks), (1, 1, 0), "{s:?}");
            assert!(s.factor_nnz > a.nnz() / 2);
        } else {
            assert_eq!(s, Default::default());
        }
        solutions.push(b);
    }
    for (i, xi) in x.iter().enumerate() {
        assert!((solutions[0][i] - xi).abs() < 1e-12, "LDLT x[{i}]");
        assert!((solutions[1][i] - xi).abs() < 1e-12, "LU x[{i}]");
    }
}

/// An unsymmetric matrix never gets a plan; one that becomes unsymmetric retires its plan
/// and is solved by the LU, correctly.
#[test]
fn unsymmetric_values_fall_back_to_the_lu() {
    let (nx, ny) = (6, 6);
    let n = 2 * (nx + 1) * (ny + 1);
    let x: Vec<f64> = (0..n).map(|i| 1.0 + (0.7 * i as f64).sin()).collect();
    let solve = |a: &SparseMatrix, s: &mut LinearSolve| {
        let mut b = vec![0.0; n];
        a.mul(&x, &mut b);
        s.solve(a, &mut b).unwrap();
        let err = b.iter().zip(&x).fold(0.0f64, |m, (u, v)| m.max((u - v).abs()));
        assert!(err < 1e-12, "{err}");
    };
    let mut a = SparseMatrix::new(n, &mut quad_grid_groups(nx, ny).into_iter());
    let mut chooser = LinearSolve::new(LinearSolver::General);
    fill_grid(&mut a, 12.0, 0.1);
    solve(&a, &mut chooser);
    assert_eq!(chooser.ldlt_stats().plans, 0);

    let mut a = SparseMatrix::new(n, &mut quad_grid_groups(nx, ny).into_iter());
    let mut chooser = LinearSolve::new(LinearSolver::General);
    fill_grid(&mut a, 12.0, 0.0);
    solve(&a, &mut chooser);
    fill_grid(&mut a, 12.0, 1e-6); // a slip tangent appears
    solve(&a, &mut chooser);
    solve(&a, &mut chooser);
    let s = chooser.ldlt_stats();
    assert_eq!((s.plans, s.solves, s.fallbacks), (1, 1, 1), "{s:?}");
    assert_eq!(s.last_failure, Some(super::super::ldlt::LdltFailure::Unsymmetric));
    assert_eq!(chooser.times.factorizations, 3);
}

/// A symmetric indefinite matrix with zero diagonal (no `LDLᵀ` without pivoting exists) is
/// solved by the LU after the symmetric attempt fails.
#[test]
fn indefinite_matrix_without_diagonal_pivots_falls_back() {
    let mut groups = vec![vec![0, 1], vec![2, 3]].into_iter();
    let mut a = SparseMatrix::new(4, &mut groups);
    let mut chooser = LinearSolve::new(LinearSolver::General);
    // A = [[0,1],[1,0]] ⊕ [[0,2],[2,0]]
    for (r, c, v) in [(0, 1, 1.0), (1, 0, 1.0), (2, 3, 2.0), (3, 2, 2.0)] {
        let k = a.index(r, c).unwrap();
        a.values[k] = v;
    }
    let x = [1.0, -2.0, 0.5, 3.0];
    let mut b = [0.0; 4];
    a.mul(&x, &mut b);
    chooser.solve(&a, &mut b).unwrap();
    for i in 0..4 {
        assert!((b[i] - x[i]).abs() < 1e-14, "x[{i}] = {}", b[i]);
    }
    let s = chooser.ldlt_stats();
    assert_eq!((s.plans, s.solves, s.fallbacks), (1, 0, 1), "{s:?}");
}
