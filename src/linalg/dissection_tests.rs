//! Nested dissection: a permutation that keeps each node's unknowns together, puts the
//! unknowns of no node last, cuts a grid along a grid plane, and fills less than minimum
//! degree on a 3D mesh.

use super::super::aggregation::{MeshNodes, SolidNode};
use super::super::ldlt::{LdltPlan, Ordering};
use super::super::sparse::SparseMatrix;
use super::*;
use faer::Par;

/// A grid of `nx × ny × nz` hexahedra, three unknowns per node (the nodes of the face
/// `x = 0` fixed when `fix`), plus `loose` unknowns coupled to the first node's: the
/// matrix (symmetric, diagonally dominant) and the mesh nodes.
pub(crate) fn hex_grid(nx: usize, ny: usize, nz: usize, fix: bool, loose: usize) -> (SparseMatrix, MeshNodes) {
    let node = |i: usize, j: usize, k: usize| (k * (ny + 1) + j) * (nx + 1) + i;
    let count = (nx + 1) * (ny + 1) * (nz + 1);
    let mut eq = vec![None; count];
    let mut n = 0;
    let mut nodes: Vec<SolidNode> = Vec::new();
    for k in 0..=nz {
        for j in 0..=ny {
            for i in 0..=nx {
                let free = !(fix && i == 0);
                if free {
                    eq[node(i, j, k)] = Some(n);
                    n += 3;
                }
                let e = eq[node(i, j, k)]
                    .map(|e| [Some(e), Some(e + 1), Some(e + 2)])
                    .unwrap_or([None; 3]);
                nodes.push((e, [i as f64, j as f64 * 1.5, k as f64 * 0.5]));
            }
        }
    }
    let mut groups = Vec::new();
    for k in 0..nz {
        for j in 0..ny {
            for i in 0..nx {
                let mut g = Vec::new();
                for (di, dj, dk) in (0..8).map(|c| (c & 1, (c >> 1) & 1, c >> 2)) {
                    if let Some(e) = eq[node(i + di, j + dj, k + dk)] {
                        g.extend([e, e + 1, e + 2]);
                    }
                }
                groups.push(g);
            }
        }
    }
    let first = eq.iter().flatten().next().copied().unwrap_or(0);
    for l in 0..loose {
        groups.push(vec![first, n + l]);
    }
    let total = n + loose;
    let mut a = SparseMatrix::new(total, &mut groups.into_iter());
    for c in 0..total {
        for k in a.col_ptr[c]..a.col_ptr[c + 1] {
            let r = a.row_idx[k];
            a.values[k] = if r == c {
                30.0
            } else {
                -0.1 - 0.01 * ((r + c) % 5) as f64
            };
        }
    }
    (a, MeshNodes::Solid(nodes))
}

#[test]
fn the_order_is_a_permutation_with_each_node_together_and_loose_unknowns_last() {
    let (a, nodes) = hex_grid(5, 4, 3, true, 2);
    let order = nested_dissection(a.n, &a.col_ptr, &a.row_idx, &nodes);
    let mut seen = order.clone();
    seen.sort_unstable();
    assert_eq!(seen, (0..a.n).collect::<Vec<_>>());
    assert_eq!(&order[a.n - 2..], &[a.n - 2, a.n - 1]);
    for chunk in order[..a.n - 2].chunks(3) {
        assert_eq!(chunk[0] % 3, 0);
        assert_eq!(chunk[1], chunk[0] + 1);
        assert_eq!(chunk[2], chunk[0] + 2);
    }
}

#[test]
fn the_first_cut_of_a_grid_is_one_grid_plane_across_its_longest_node_count() {
    // 17 × 5 × 5 nodes: the smallest separator is a plane of 5 × 5 nodes at one x
    let (a, nodes) = hex_grid(16, 4, 4, false, 0);
    let order = nested_dissection(a.n, &a.col_ptr, &a.row_idx, &nodes);
    let MeshNodes::Solid(list) = &nodes else { unreachable!() };
    let x_of = |eq: usize| list[eq / 3].1[0];
    let last: Vec<f64> = order[a.n - 75..].iter().map(|&e| x_of(e)).collect();
    assert!(last.iter().all(|&x| x == last[0]), "{last:?}");
    assert!(x_of(order[a.n - 76]) != last[0]);
}

#[test]
fn nested_dissection_costs_fewer_flops_than_minimum_degree_on_a_3d_mesh() {
    let (a, nodes) = hex_grid(12, 12, 12, true, 0);
    let plan = LdltPlan::new(a.n, &a.col_ptr, &a.row_idx, &a.values, Some(&nodes), Par::Seq).unwrap();
    let (kept, other) = plan.flops;
    assert_eq!(plan.ordering, Ordering::NestedDissection);
    assert!(kept < 0.7 * other.unwrap(), "{kept:.3e} against {:.3e}", other.unwrap());
    // without the nodes only minimum degree is analysed
    let amd = LdltPlan::new(a.n, &a.col_ptr, &a.row_idx, &a.values, None, Par::Seq).unwrap();
    assert_eq!((amd.ordering, amd.flops.1), (Ordering::MinimumDegree, None));
    assert_eq!(amd.flops.0, other.unwrap());
}

#[test]
fn both_orderings_solve_to_round_off() {
    let (a, nodes) = hex_grid(6, 5, 4, true, 1);
    let x: Vec<f64> = (0..a.n).map(|i| ((i * 7) % 13) as f64 - 6.0).collect();
    let mut b0 = vec![0.0; a.n];
    a.mul(&x, &mut b0);
    for nodes in [Some(&nodes), None] {
        let mut plan = LdltPlan::new(a.n, &a.col_ptr, &a.row_idx, &a.values, nodes, Par::Seq).unwrap();
        plan.factorize(a.symbolic(), &a.values, Par::Seq).unwrap();
        let mut b = b0.clone();
        plan.solve(a.symbolic(), &a.values, &mut b, Par::Seq).unwrap();
        let err = b.iter().zip(&x).fold(0.0f64, |m, (u, v)| m.max((u - v).abs()));
        assert!(err < 1e-12, "{:?}: {err:e}", plan.ordering);
    }
}
