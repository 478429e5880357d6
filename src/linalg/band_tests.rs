use super::*;

/// Dense `A x` for a matrix given as `(i, j, v)` entries.
fn mul(n: usize, a: &[(usize, usize, f64)], x: &[f64]) -> Vec<f64> {
    let mut y = vec![0.0; n];
    for &(i, j, v) in a {
        y[i] += v * x[j];
    }
    y
}

fn factor_solve(n: usize, kl: usize, ku: usize, a: &[(usize, usize, f64)], b: &mut [f64]) -> Result<(), ZeroPivot> {
    let mut lu = BandLu::new(n, kl, ku);
    for &(i, j, v) in a {
        let s = lu.slot(i, j);
        lu.add(s, v);
    }
    lu.factorize()?;
    lu.solve(b);
    Ok(())
}

/// CSC pattern of an `nx × ny` grid of nodes numbered row by row (`j·nx + i`), `dofs`
/// unknowns per node (`dofs·node + component`), each quad coupling all unknowns of its
/// four nodes.
fn grid_pattern(nx: usize, ny: usize, dofs: usize) -> (Vec<usize>, Vec<usize>) {
    let id = |i: usize, j: usize| j * nx + i;
    let mut cols: Vec<Vec<usize>> = (0..dofs * nx * ny).map(|v| vec![v]).collect();
    for j in 0..ny - 1 {
        for i in 0..nx - 1 {
            let q = [id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)];
            for &a in &q {
                for &b in &q {
                    for da in 0..dofs {
                        for db in 0..dofs {
                            cols[dofs * a + da].push(dofs * b + db);
                        }
                    }
                }
            }
        }
    }
    let mut col_ptr = vec![0];
    let mut row_idx = Vec::new();
    for c in &mut cols {
        c.sort_unstable();
        c.dedup();
        row_idx.extend_from_slice(c);
        col_ptr.push(row_idx.len());
    }
    (col_ptr, row_idx)
}

#[test]
fn unsymmetric_band_with_zero_diagonal_needs_pivoting_and_is_solved() {
    // tridiagonal-plus, zero (0,0): the first step must swap rows
    let n = 7;
    let mut a = Vec::new();
    for i in 0..n {
        if i > 0 {
            a.push((i, i - 1, 1.0 + 0.1 * i as f64));
        }
        if i + 1 < n {
            a.push((i, i + 1, -2.0 + 0.05 * i as f64));
        }
        if i + 2 < n {
            a.push((i, i + 2, 0.3));
        }
        a.push((i, i, if i == 0 { 0.0 } else { 4.0 + i as f64 }));
    }
    let x: Vec<f64> = (0..n).map(|i| (i as f64 * 0.7).sin() + 0.2).collect();
    let mut b = mul(n, &a, &x);
    factor_solve(n, 1, 2, &a, &mut b).unwrap();
    for (i, (bi, xi)) in b.iter().zip(&x).enumerate() {
        assert!((bi - xi).abs() < 1e-13, "x[{i}] = {bi} vs {xi}");
    }
}

#[test]
fn singular_matrix_is_reported() {
    let a = [(0, 0, 1.0), (0, 1, 2.0), (1, 0, 2.0), (1, 1, 4.0)];
    let mut b = [1.0, 1.0];
    assert_eq!(factor_solve(2, 1, 1, &a, &mut b), Err(ZeroPivot(1)));
}

#[test]
fn rcm_gives_the_narrow_band_of_a_strip_numbered_along_its_length() {
    // a 20×2 grid of nodes numbered row by row (band 20), 4-neighbour + diagonal coupling
    let n = 20 * 2;
    let (col_ptr, row_idx) = grid_pattern(20, 2, 1);
    let perm = reverse_cuthill_mckee(n, &col_ptr, &row_idx, Root::Node);
    let mut inv = vec![usize::MAX; n];
    for (new, &old) in perm.iter().enumerate() {
        inv[old] = new;
    }
    assert!(inv.iter().all(|&v| v < n), "a permutation");
    let w = (0..n)
        .flat_map(|c| row_idx[col_ptr[c]..col_ptr[c + 1]].iter().map(move |&r| (r, c)))
        .map(|(r, c)| inv[r].abs_diff(inv[c]))
        .max()
        .unwrap();
    assert!(w <= 3, "half-bandwidth {w} after RCM (20 before)");
}

#[test]
fn supervariables_halve_the_band_of_a_two_dof_strip() {
    // a 30×5 grid of nodes (30 along, 5 across) with two unknowns per node, quads coupling
    // all unknowns of their four nodes; numbered across the strip first the band would be
    // 2·(5 + 1) + 1 = 13
    let n = 2 * 30 * 5;
    let (col_ptr, row_idx) = grid_pattern(30, 5, 2);
    let plain = reverse_cuthill_mckee(n, &col_ptr, &row_idx, Root::Node);
    let grouped = supervariable_rcm(n, &col_ptr, &row_idx, Root::FarLevel);
    let mut sorted = grouped.clone();
    sorted.sort_unstable();
    assert_eq!(sorted, (0..n).collect::<Vec<_>>(), "a permutation");
    let (kl, ku) = band_widths(n, &col_ptr, &row_idx, &grouped);
    let (pl, pu) = band_widths(n, &col_ptr, &row_idx, &plain);
    assert!(kl.max(ku) <= 13, "supervariable RCM: ({kl}, {ku})");
    assert!(kl.max(ku) < pl.max(pu), "plain RCM ({pl}, {pu}) is wider");
}

/// The AVX2 compilation of the factorisation and the solve gives the baseline's figures to
/// the last bit (`crate::cpu`): a pivoting band of each width the update unrolls and one
/// wider.
#[test]
fn the_avx2_factorisation_and_solve_are_the_baselines_to_the_last_bit() {
    if !crate::cpu::wide_vectors() {
        return; // nothing to compare on this processor
    }
    for (n, kl) in [(30, 1), (60, 5), (200, 13), (300, 40), (300, 43)] {
        let mut lu = BandLu::new(n, kl, kl);
        let mut x = 0x9e37_79b9_7f4a_7c15u64;
        for i in 0..n {
            for j in i.saturating_sub(kl)..(i + kl + 1).min(n) {
                x = x.wrapping_mul(6_364_136_223_846_793_005).wrapping_add(1);
                // small diagonals: the pivots move
                let v = (x >> 11) as f64 / (1u64 << 52) as f64 - 1.0 + if i == j { 0.01 } else { 0.0 };
                let s = lu.slot(i, j);
                lu.add(s, v);
            }
        }
        let mut base = lu.clone();
        base.factorize_in_place().unwrap();
        // SAFETY: the processor has AVX2 (checked above)
        unsafe { lu.factorize_avx2() }.unwrap();
        assert_eq!(lu.ipiv, base.ipiv, "n {n}, kl {kl}");
        assert!(
            lu.ipiv.iter().enumerate().any(|(j, p)| *p != j),
            "n {n}, kl {kl}: no pivoting"
        );
        assert!(
            lu.ab.iter().zip(&base.ab).all(|(a, b)| a.to_bits() == b.to_bits()),
            "n {n}, kl {kl}"
        );
        let rhs: Vec<f64> = (0..n).map(|i| (i as f64).sin()).collect();
        let (mut a, mut b) = (rhs.clone(), rhs);
        base.solve_in_place(&mut b);
        // SAFETY: as above
        unsafe { lu.solve_avx2(&mut a) };
        assert!(
            a.iter().zip(&b).all(|(x, y)| x.to_bits() == y.to_bits()),
            "n {n}, kl {kl}"
        );
    }
}
