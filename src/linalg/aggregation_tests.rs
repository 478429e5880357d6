use super::*;

/// Three nodes in a row, each component coupled to the same component of its neighbours by
/// a unit spring, and a spring `k n ⊗ n` on the middle node (`n.len()` components per node).
fn springs_in_a_row(k: f64, n: &[f64]) -> Csr {
    let d = n.len();
    let mut dense = vec![vec![0.0; 3 * d]; 3 * d];
    for (i, j) in [(0, 1), (1, 2)] {
        for c in 0..d {
            let (p, q) = (d * i + c, d * j + c);
            dense[p][p] += 1.0;
            dense[q][q] += 1.0;
            dense[p][q] -= 1.0;
            dense[q][p] -= 1.0;
        }
    }
    for (r, nr) in n.iter().enumerate() {
        for (c, nc) in n.iter().enumerate() {
            dense[d + r][d + c] += k * nr * nc;
        }
    }
    Csr::from_dense_rows(&dense)
}

/// Three nodes in a row (x = 0, 1, 2), neighbours coupled like springs in both
/// directions, and a stiff spring `k n ⊗ n` on the middle node along `n = (0.6, 0.8)`:
/// only that node's modes lose their component along `n`.
#[test]
fn a_penalty_direction_is_taken_out_of_the_modes() {
    let (k, n) = (1e6, [0.6, 0.8]);
    let a = springs_in_a_row(k, &n);
    let nodes: Vec<MeshNode> = (0..3)
        .map(|i| ([Some(2 * i), Some(2 * i + 1)], [i as f64, 0.0]))
        .collect();
    let mut nns = NearNullSpace::rigid_body_2d(6, &nodes);
    let before = nns.modes.clone();
    assert_eq!(nns.constrain_stiff_directions(&a, 2.0), 1);
    let (held, held_before) = ([nns.modes[2], nns.modes[3]], [before[2], before[3]]);
    for (m, (x, y)) in held[0].iter().zip(&held[1]).enumerate() {
        let along = n[0] * x + n[1] * y;
        assert!(
            along.abs() < 1e-12,
            "mode {m} still moves the held node along n: {along}"
        );
        let across = -n[1] * x + n[0] * y;
        let across_before = -n[1] * held_before[0][m] + n[0] * held_before[1][m];
        assert!((across - across_before).abs() < 1e-12, "mode {m} across n changed");
    }
    for d in [0, 1, 4, 5] {
        assert_eq!(nns.modes[d], before[d], "unknown {d} of a free node changed");
    }
}

/// The same in 3D: three nodes in a row, coupled per component, a stiff spring on the
/// middle node along `n = (0.48, 0.6, 0.64)`: that node's six modes lose their component
/// along `n`, the other nodes' are unchanged.
#[test]
#[allow(clippy::needless_range_loop)] // modes and components index several arrays
fn a_penalty_direction_is_taken_out_of_the_six_modes_of_a_3d_node() {
    let (k, n) = (1e6, [0.48, 0.6, 0.64]);
    let a = springs_in_a_row(k, &n);
    let nodes: Vec<SolidNode> = (0..3)
        .map(|i| ([Some(3 * i), Some(3 * i + 1), Some(3 * i + 2)], [i as f64, 0.5, -0.25]))
        .collect();
    let mut nns = NearNullSpace::rigid_body(9, &MeshNodes::Solid(nodes));
    let before = nns.modes.clone();
    assert_eq!(nns.constrain_stiff_directions(&a, 2.0), 1);
    for m in 0..6 {
        let along: f64 = (0..3).map(|c| n[c] * nns.modes[3 + c][m]).sum();
        assert!(
            along.abs() < 1e-12,
            "mode {m} still moves the held node along n: {along}"
        );
        let along_before: f64 = (0..3).map(|c| n[c] * before[3 + c][m]).sum();
        for c in 0..3 {
            let kept = before[3 + c][m] - along_before * n[c];
            assert!((nns.modes[3 + c][m] - kept).abs() < 1e-12, "mode {m}, component {c}");
        }
    }
    for d in [0, 1, 2, 6, 7, 8] {
        assert_eq!(nns.modes[d], before[d], "unknown {d} of a free node changed");
    }
}
