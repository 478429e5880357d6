//! The near-null space of a level and its aggregation for the smoothed-aggregation
//! multigrid ([`super::amg`]): the rigid-body modes of 2D nodes (with the directions that a
//! stiff penalty holds taken out), the aggregation of the node graph on its strong couplings,
//! and the tentative prolongator that reproduces the near-null space on each aggregate.

use super::csr::Csr;

/// A 2D mesh node as the linear solver sees it: its free equations `(x, y)` (`None` where
/// prescribed) and its reference position.
pub type MeshNode = ([Option<usize>; 2], [f64; 2]);

/// A 3D mesh node as the linear solver sees it: its free equations `(x, y, z)` and its
/// reference position.
pub type SolidNode = ([Option<usize>; 3], [f64; 3]);

/// The mesh nodes of a model, in its dimension.
#[derive(Debug, Clone)]
pub enum MeshNodes {
    Plane(Vec<MeshNode>),
    Solid(Vec<SolidNode>),
}

/// Most modes of a near-null space: the six rigid-body modes of a 3D solid.
pub const MAX_MODES: usize = 6;

/// The near-null space of one level: its node groups and, per unknown, the values of the
/// modes.
pub struct NearNullSpace {
    /// Unknowns of each node (every unknown in exactly one node).
    pub nodes: Vec<Vec<usize>>,
    /// Per unknown, the value of each mode (the first [`Self::count`] are used).
    pub modes: Vec<[f64; MAX_MODES]>,
    /// The modes per node: 3 for a 2D solid, 6 for a 3D one.
    pub count: usize,
}

impl NearNullSpace {
    /// The rigid-body modes of the nodes of a model: in 2D the translations `(1, 0)`,
    /// `(0, 1)` and the rotation `(−y, x)`; in 3D the translations along x, y, z and the
    /// rotations `e_k × X` about the three axes, at each node's reference position `X`.
    pub fn rigid_body(n: usize, nodes: &MeshNodes) -> Self {
        match nodes {
            MeshNodes::Plane(nodes) => Self::rigid_body_2d(n, nodes),
            MeshNodes::Solid(nodes) => Self::from_nodes(n, 6, nodes.iter().map(|(eqs, x)| (&eqs[..], rigid_3d(*x)))),
        }
    }

    /// The rigid-body modes of 2D nodes: for each node its free unknowns
    /// `(x-equation, y-equation)` and reference position.
    pub fn rigid_body_2d(n: usize, nodes: &[MeshNode]) -> Self {
        let rows = |x: [f64; 2]| {
            let mut r = [[0.0; MAX_MODES]; 3];
            r[0][..3].copy_from_slice(&[1.0, 0.0, -x[1]]);
            r[1][..3].copy_from_slice(&[0.0, 1.0, x[0]]);
            r
        };
        Self::from_nodes(n, 3, nodes.iter().map(|(eqs, x)| (&eqs[..], rows(*x))))
    }

    /// The near-null space of nodes given as (free equations per component, the modes' values
    /// per component), `count` modes each.
    fn from_nodes<'a>(
        n: usize,
        count: usize,
        nodes: impl Iterator<Item = (&'a [Option<usize>], [[f64; MAX_MODES]; 3])>,
    ) -> Self {
        let mut modes = vec![[0.0; MAX_MODES]; n];
        let mut groups = Vec::new();
        let mut covered = vec![false; n];
        for (eqs, rows) in nodes {
            let mut g = Vec::new();
            for (c, eq) in eqs.iter().enumerate() {
                if let Some(e) = *eq {
                    modes[e] = rows[c];
                    covered[e] = true;
                    g.push(e);
                }
            }
            if !g.is_empty() {
                groups.push(g);
            }
        }
        // an unknown of no node (none in this code, but keep the partition complete)
        for (e, c) in covered.iter().enumerate() {
            if !c {
                modes[e] = [0.0; MAX_MODES];
                modes[e][0] = 1.0;
                groups.push(vec![e]);
            }
        }
        NearNullSpace {
            nodes: groups,
            modes,
            count,
        }
    }
}

/// The six rigid-body modes of a 3D node at `x`, per component: translations, then the
/// rotations `e_x × X = (0, −z, y)`, `e_y × X = (z, 0, −x)`, `e_z × X = (−y, x, 0)`.
fn rigid_3d(x: [f64; 3]) -> [[f64; MAX_MODES]; 3] {
    [
        [1.0, 0.0, 0.0, 0.0, x[2], -x[1]],
        [0.0, 1.0, 0.0, -x[2], 0.0, x[0]],
        [0.0, 0.0, 1.0, x[1], -x[0], 0.0],
    ]
}

impl NearNullSpace {
    /// Take out of the modes the direction of a node that a stiff spring holds (a contact
    /// penalty `ε_N n ⊗ n`, seed eq. 5, far stiffer than the solid): where the largest
    /// eigenvalue `λ` (eigenvector `v`) of the node's diagonal block `A_II` exceeds
    /// `factor · Σ_J ‖A_IJ‖` — for a node of the solid alone `A_II t = −Σ_J A_IJ t` for any
    /// translation `t`, so `λ ≤ Σ_J ‖A_IJ‖` — the modes become `(I − v vᵀ) B_I` there, as if
    /// that direction were prescribed. A coarse space that moves such a node along `v`
    /// carries the penalty's energy, and the Krylov solver then needs hundreds of
    /// iterations (measured: no convergence in 400 on `punch-large` with `ε_N = 10³ E`).
    pub fn constrain_stiff_directions(&mut self, a: &Csr, factor: f64) -> usize {
        let mut node_of = vec![usize::MAX; a.nrows];
        for (i, g) in self.nodes.iter().enumerate() {
            for &d in g {
                node_of[d] = i;
            }
        }
        let mut count = 0;
        for g in &self.nodes {
            if !(2..=3).contains(&g.len()) {
                continue;
            }
            let (blk, coupling) = node_block(a, g, &node_of);
            let (lambda, v) = match g.len() {
                2 => largest_eigenpair_2(&blk),
                _ => largest_eigenpair_3(&blk),
            };
            if lambda <= factor * coupling {
                continue;
            }
            for k in 0..self.count {
                let along: f64 = g.iter().zip(&v).map(|(&e, vc)| vc * self.modes[e][k]).sum();
                for (&e, vc) in g.iter().zip(&v) {
                    self.modes[e][k] -= along * vc;
                }
            }
            count += 1;
        }
        count
    }
}

/// A node's diagonal block `A_II` (its unknowns `g`, up to 3) and its coupling to the other
/// nodes, `Σ_J ‖A_IJ‖` (Frobenius norms).
fn node_block(a: &Csr, g: &[usize], node_of: &[usize]) -> ([[f64; 3]; 3], f64) {
    let mut blk = [[0.0; 3]; 3];
    let mut off: Vec<(usize, f64)> = Vec::new();
    for (r, &d) in g.iter().enumerate() {
        for k in a.ptr[d]..a.ptr[d + 1] {
            let c = a.idx[k];
            if let Some(col) = g.iter().position(|&e| e == c) {
                blk[r][col] += a.val[k];
            } else {
                match off.iter_mut().find(|(j, _)| *j == node_of[c]) {
                    Some(e) => e.1 += a.val[k] * a.val[k],
                    None => off.push((node_of[c], a.val[k] * a.val[k])),
                }
            }
        }
    }
    (blk, off.iter().map(|(_, s)| s.sqrt()).sum())
}

/// The largest eigenvalue of the symmetric part of a 2×2 block and its unit eigenvector (in
/// closed form).
fn largest_eigenpair_2(blk: &[[f64; 3]; 3]) -> (f64, [f64; 3]) {
    let (p, q, r) = (blk[0][0], 0.5 * (blk[0][1] + blk[1][0]), blk[1][1]);
    let mean = 0.5 * (p + r);
    let rad = (0.25 * (p - r) * (p - r) + q * q).sqrt();
    let lambda = mean + rad;
    let v = if q.abs() > 1e-300 || (p - r).abs() > 0.0 {
        let (x, y) = if p >= r { (lambda - r, q) } else { (q, lambda - p) };
        let l = x.hypot(y);
        [x / l, y / l, 0.0]
    } else {
        [1.0, 0.0, 0.0]
    };
    (lambda, v)
}

/// The largest eigenvalue of the symmetric part of a 3×3 block and its unit eigenvector.
fn largest_eigenpair_3(blk: &[[f64; 3]; 3]) -> (f64, [f64; 3]) {
    let m = nalgebra::Matrix3::from_fn(|r, c| 0.5 * (blk[r][c] + blk[c][r]));
    let eig = m.symmetric_eigen();
    let k = eig.eigenvalues.imax();
    let v = eig.eigenvectors.column(k);
    (eig.eigenvalues[k], [v[0], v[1], v[2]])
}

const FREE: usize = usize::MAX;

/// Aggregate of each node (standard aggregation on the graph of the strong couplings of
/// `a`'s nodes), and, for `theta > 0`, the filtered matrix for the prolongator smoothing.
pub(super) fn aggregate(a: &Csr, nodes: &[Vec<usize>], theta: f64) -> (Vec<usize>, Option<Csr>) {
    let mut node_of = vec![FREE; a.nrows];
    let mut slot_of = vec![0usize; a.nrows];
    for (i, g) in nodes.iter().enumerate() {
        for (s, &d) in g.iter().enumerate() {
            node_of[d] = i;
            slot_of[d] = s;
        }
    }
    let strong = strong_couplings(a, nodes, &node_of, &slot_of, theta);
    let filtered = (theta > 0.0).then(|| filtered_matrix(a, nodes, &node_of, &strong));
    (greedy_aggregates(&strong), filtered)
}

/// The graph of strong couplings between nodes, as `(ptr, adjacent)` (CSR, without the node
/// itself).
type Graph = (Vec<usize>, Vec<usize>);

/// Node adjacency, strong couplings only: `s_IJ ≥ θ √(d_I d_J)` with `s_IJ² = Σ_c
/// min(a_{Ic,Jc}, 0)²` over the like components (x with x, y with y) and `d_I² = Σ_c
/// a_{Ic,Ic}²`. The unlike couplings (`(λ + μ)/4` whatever the element's shape) and the
/// positive ones (a stretched bilinear element couples the two nodes of a long edge
/// positively, in proportion to its aspect ratio) would hide the direction in which the
/// element is stiff.
fn strong_couplings(a: &Csr, nodes: &[Vec<usize>], node_of: &[usize], slot_of: &[usize], theta: f64) -> Graph {
    let nn = nodes.len();
    let mut marker = vec![FREE; nn];
    let mut block = vec![0.0f64; nn];
    let mut touched = Vec::new();
    let own: Vec<f64> = nodes
        .iter()
        .map(|g| {
            let sum: f64 = (g.iter())
                .flat_map(|&d| (a.ptr[d]..a.ptr[d + 1]).filter(move |&k| a.idx[k] == d))
                .map(|k| a.val[k] * a.val[k])
                .sum();
            sum.sqrt()
        })
        .collect();
    let mut adj_ptr = vec![0usize];
    let mut adj = Vec::new();
    for (i, g) in nodes.iter().enumerate() {
        marker[i] = i;
        touched.clear();
        for &d in g {
            for k in a.ptr[d]..a.ptr[d + 1] {
                let j = node_of[a.idx[k]];
                if j == FREE || j == i {
                    continue;
                }
                if marker[j] != i {
                    marker[j] = i;
                    block[j] = 0.0;
                    touched.push(j);
                }
                if slot_of[a.idx[k]] == slot_of[d] && a.val[k] < 0.0 {
                    block[j] += a.val[k] * a.val[k];
                }
            }
        }
        for &j in &touched {
            if block[j].sqrt() >= theta * (own[i] * own[j]).sqrt() {
                adj.push(j);
            }
        }
        adj_ptr.push(adj.len());
    }
    (adj_ptr, adj)
}

/// `a` with its weak couplings lumped onto the diagonal (for the smoothing of the
/// prolongator, so that it does not spread across weak directions).
fn filtered_matrix(a: &Csr, nodes: &[Vec<usize>], node_of: &[usize], (adj_ptr, adj): &Graph) -> Csr {
    let mut f = a.clone();
    for (i, g) in nodes.iter().enumerate() {
        let strong = &adj[adj_ptr[i]..adj_ptr[i + 1]];
        for &d in g {
            let mut lumped = 0.0;
            let mut diag_k = None;
            for k in f.ptr[d]..f.ptr[d + 1] {
                let j = node_of[f.idx[k]];
                if f.idx[k] == d {
                    diag_k = Some(k);
                } else if j != i && !strong.contains(&j) {
                    lumped += f.val[k];
                    f.val[k] = 0.0;
                }
            }
            if let Some(k) = diag_k {
                f.val[k] += lumped;
            }
        }
    }
    f
}

/// Standard aggregation in three passes over the graph of strong couplings.
fn greedy_aggregates((adj_ptr, adj): &Graph) -> Vec<usize> {
    let nn = adj_ptr.len() - 1;
    let nbrs = |i: usize| &adj[adj_ptr[i]..adj_ptr[i + 1]];
    let mut agg = vec![FREE; nn];
    let mut count = 0;
    // pass 1: a free node whose neighbours are all free, with its neighbours
    for i in 0..nn {
        if agg[i] == FREE && nbrs(i).iter().all(|&j| agg[j] == FREE) {
            agg[i] = count;
            for &j in nbrs(i) {
                agg[j] = count;
            }
            count += 1;
        }
    }
    // pass 2: join a neighbouring aggregate of pass 1
    let first = agg.clone();
    for (i, a) in agg.iter_mut().enumerate() {
        if *a == FREE {
            if let Some(&j) = nbrs(i).iter().find(|&&j| first[j] != FREE) {
                *a = first[j];
            }
        }
    }
    // pass 3: what is left, with its free neighbours
    for i in 0..nn {
        if agg[i] == FREE {
            agg[i] = count;
            for &j in nbrs(i) {
                if agg[j] == FREE {
                    agg[j] = count;
                }
            }
            count += 1;
        }
    }
    agg
}

/// The tentative prolongator (one orthonormal block per aggregate) and the coarse level's
/// near-null space (one node per aggregate).
pub(super) fn tentative(n: usize, nns: &NearNullSpace, agg_of_node: &[usize]) -> (Csr, NearNullSpace) {
    let n_agg = agg_of_node.iter().max().map_or(0, |m| m + 1);
    let mut dofs_of: Vec<Vec<usize>> = vec![Vec::new(); n_agg];
    for (node, &g) in agg_of_node.iter().enumerate() {
        dofs_of[g].extend_from_slice(&nns.nodes[node]);
    }
    // per fine unknown: its (coarse column, value) entries
    let mut rows: Vec<[(usize, f64); MAX_MODES]> = vec![[(0, 0.0); MAX_MODES]; n];
    let mut row_len = vec![0usize; n];
    let mut coarse_nodes = Vec::with_capacity(n_agg);
    let count = nns.count;
    let mut coarse_modes = Vec::with_capacity(count * n_agg);
    let mut q: Vec<[f64; MAX_MODES]> = Vec::new();
    for dofs in &dofs_of {
        q.clear();
        q.extend(dofs.iter().map(|&d| nns.modes[d]));
        // modified Gram–Schmidt on the columns; a column that is (numerically) in the span of
        // the previous ones is dropped
        let mut kept: Vec<usize> = Vec::with_capacity(count);
        for k in 0..count {
            let norm0 = q.iter().map(|r| r[k] * r[k]).sum::<f64>().sqrt();
            for &j in &kept {
                let d: f64 = q.iter().map(|r| r[j] * r[k]).sum();
                q.iter_mut().for_each(|r| r[k] -= d * r[j]);
            }
            let norm = q.iter().map(|r| r[k] * r[k]).sum::<f64>().sqrt();
            if norm > 1e-8 * norm0 && norm > 0.0 {
                q.iter_mut().for_each(|r| r[k] /= norm);
                kept.push(k);
            }
        }
        let first = coarse_modes.len();
        for &j in &kept {
            // coarse mode values: R_jk = q_j · B_k
            let mut rj = [0.0; MAX_MODES];
            for (k, v) in rj.iter_mut().enumerate().take(count) {
                *v = dofs.iter().zip(&q).map(|(&d, qr)| qr[j] * nns.modes[d][k]).sum();
            }
            coarse_modes.push(rj);
        }
        for (&d, qr) in dofs.iter().zip(&q) {
            for (c, &j) in kept.iter().enumerate() {
                rows[d][row_len[d]] = (first + c, qr[j]);
                row_len[d] += 1;
            }
        }
        coarse_nodes.push((first..coarse_modes.len()).collect());
    }
    let mut p0 = Csr {
        nrows: n,
        ncols: coarse_modes.len(),
        ptr: Vec::with_capacity(n + 1),
        ..Default::default()
    };
    p0.ptr.push(0);
    for (r, len) in rows.iter().zip(&row_len) {
        for &(c, v) in &r[..*len] {
            p0.idx.push(c);
            p0.val.push(v);
        }
        p0.ptr.push(p0.idx.len());
    }
    (
        p0,
        NearNullSpace {
            nodes: coarse_nodes,
            modes: coarse_modes,
            count,
        },
    )
}

#[cfg(test)]
#[path = "aggregation_tests.rs"]
mod tests;
