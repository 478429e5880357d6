//! Direct solvers of the sparse matrix: the banded and the general LU agree, the pattern
//! grows.

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
    for solver in [LinearSolver::Auto, LinearSolver::Sparse] {
        let mut a = SparseMatrix::new(n, &mut groups.clone().into_iter());
        a.set_solver(solver);
        fill(&mut a);
        let mut b = vec![0.0; n];
        a.mul(&x, &mut b);
        a.solve(&mut b).unwrap();
        assert_eq!(a.band_widths().is_some(), solver == LinearSolver::Auto);
        if let Some((kl, ku)) = a.band_widths() {
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
