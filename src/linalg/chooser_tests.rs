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

/// A symmetric matrix on the pattern of `groups` (each group a cell coupling its unknowns):
/// each cell adds `w (I − 11ᵀ/m)` (positive semi-definite), the diagonal gets `1 − shift(i)`,
/// so that a few large shifts make it indefinite.
fn symmetric_cells(n: usize, groups: &[Vec<usize>], shift: impl Fn(usize) -> f64) -> SparseMatrix {
    let mut a = SparseMatrix::new(n, &mut groups.iter().cloned());
    for (e, g) in groups.iter().enumerate() {
        let w = 1.0 + (e % 5) as f64 * 0.3;
        let m = g.len() as f64;
        for &r in g {
            for &c in g {
                let v = w * (f64::from(u8::from(r == c)) - 1.0 / m);
                a.add_to(a.index(r, c).unwrap(), v);
            }
        }
    }
    for i in 0..n {
        a.add_to(a.index(i, i).unwrap(), 1.0 - shift(i));
    }
    a
}

/// The negative eigenvalues of `a`, from a dense symmetric eigen-decomposition.
fn dense_negative_eigenvalues(a: &SparseMatrix) -> usize {
    let mut d = nalgebra::DMatrix::<f64>::zeros(a.n, a.n);
    for c in 0..a.n {
        for k in a.col_ptr[c]..a.col_ptr[c + 1] {
            d[(a.row_idx[k], c)] = a.values[k];
        }
    }
    nalgebra::SymmetricEigen::new(d)
        .eigenvalues
        .iter()
        .filter(|&&l| l < 0.0)
        .count()
}

/// The 7-point Laplacian of an `m³` grid of unknowns (Dirichlet outside), shifted by `−σ`,
/// on the pattern of the grid's hexahedral cells; its eigenvalues are
/// `Σ_d (2 − 2 cos(π k_d/(m + 1)))`, `k_d = 1..=m`, so its negative ones are counted exactly.
fn shifted_laplacian(m: usize, sigma: f64) -> (SparseMatrix, usize) {
    let node = |i: usize, j: usize, k: usize| (k * m + j) * m + i;
    let cells = m - 1;
    let mut groups = (0..cells.pow(3)).map(|c| {
        let (i, j, k) = (c % cells, (c / cells) % cells, c / (cells * cells));
        (0..8)
            .map(|v| node(i + (v & 1), j + ((v >> 1) & 1), k + (v >> 2)))
            .collect::<Vec<_>>()
    });
    let n = m.pow(3);
    let mut a = SparseMatrix::new(n, &mut groups);
    for k in 0..m {
        for j in 0..m {
            for i in 0..m {
                let p = node(i, j, k);
                a.add_to(a.index(p, p).unwrap(), 6.0 - sigma);
                let neighbours = [
                    (i + 1 < m, node(i + 1, j, k)),
                    (j + 1 < m, node(i, j + 1, k)),
                    (k + 1 < m, node(i, j, k + 1)),
                ];
                for (_, q) in neighbours.into_iter().filter(|&(inside, _)| inside) {
                    a.add_to(a.index(p, q).unwrap(), -1.0);
                    a.add_to(a.index(q, p).unwrap(), -1.0);
                }
            }
        }
    }
    let mode = |k: usize| 2.0 - 2.0 * (std::f64::consts::PI * k as f64 / (m + 1) as f64).cos();
    let negative = (1..=m)
        .flat_map(|a| (1..=m).flat_map(move |b| (1..=m).map(move |c| (a, b, c))))
        .filter(|&(a, b, c)| mode(a) + mode(b) + mode(c) < sigma)
        .count();
    (a, negative)
}

/// Sylvester's law of inertia through the chooser: the `LDLᵀ`'s negative pivots are the
/// matrix's negative eigenvalues (a strip: a simplicial factor; a 3D grid: supernodal);
/// the banded LU gives their parity.
#[test]
fn factorisations_tell_the_negative_eigenvalues() {
    let strip = quad_grid_groups(30, 3);
    let n_strip = 2 * 31 * 4;
    for shifts in [0usize, 1, 2, 5] {
        let a = symmetric_cells(
            n_strip,
            &strip,
            |i| if i % 37 == 5 && i / 37 < shifts { 9.0 } else { 0.0 },
        );
        let expected = dense_negative_eigenvalues(&a);
        let mut b = vec![1.0; n_strip];
        let mut ldlt = LinearSolve::new(LinearSolver::General);
        ldlt.solve(&a, &mut b).unwrap();
        assert_eq!(
            ldlt.take_inertia(),
            Some(Inertia {
                negative: expected,
                exact: true
            }),
            "shifts {shifts}"
        );
        assert_eq!(ldlt.take_inertia(), None, "taken once");
        assert!(!ldlt.ldlt.as_ref().expect("an LDLᵀ plan").is_supernodal());
        let mut auto = LinearSolve::new(LinearSolver::Auto);
        b.fill(1.0);
        auto.solve(&a, &mut b).unwrap();
        assert!(auto.banded());
        assert_eq!(
            auto.take_inertia(),
            Some(Inertia {
                negative: expected % 2,
                exact: false
            })
        );
    }
    for sigma in [0.5, 1.3, 2.9] {
        let (a, expected) = shifted_laplacian(14, sigma);
        let mut b = vec![1.0; a.n];
        let mut ldlt = LinearSolve::new(LinearSolver::General);
        ldlt.solve(&a, &mut b).unwrap();
        assert!(ldlt.ldlt.as_ref().expect("an LDLᵀ plan").is_supernodal());
        assert_eq!(
            ldlt.take_inertia(),
            Some(Inertia {
                negative: expected,
                exact: true
            }),
            "σ = {sigma}"
        );
    }
}
