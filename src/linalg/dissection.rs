//! Nested-dissection ordering of a finite-element tangent's unknowns, from the node graph
//! and the nodes' reference positions (geometric nested dissection: George 1973, "Nested
//! dissection of a regular finite element mesh", SIAM J. Numer. Anal. 10; the separators
//! found as in recursive coordinate bisection).
//!
//! A set of nodes is cut at the median of one coordinate; the separator is the nodes of one
//! half that are coupled to the other half, so that the two halves without it are
//! uncoupled. Of the three axes (two in 2D) and the two sides, the cut with the smallest
//! separator is taken. Each half is ordered the same way, and the separator after both
//! (Liu's post-order), down to sets of at most [`LEAF_NODES`] nodes kept in their given
//! order. A node's unknowns stay together; unknowns of no node are ordered last.
//!
//! On a 3D mesh of `N³` nodes the factor of this ordering holds `O(N⁴)` values and costs
//! `O(N⁶)` flops, against the `O(N⁵)`-fill minimum-degree orderings reach in practice; the
//! symmetric solver ([`super::ldlt`]) analyses both orderings and keeps the one whose
//! factorisation costs fewer flops.

use super::aggregation::MeshNodes;
use super::sparse::sort_dedup_tail;

/// Node sets of at most this many nodes are not cut further: on such a set a separator is
/// a large part of the set, and the dissection stops at small subgraphs (George & Liu,
/// *Computer Solution of Large Sparse Positive Definite Systems*, 1981, §8.2, where the
/// recursion ends at a few grid lines). Any small value serves: faer's supernodal analysis
/// merges the leaves' columns into the supernodes of their parents.
pub const LEAF_NODES: usize = 16;

/// The node graph of a pattern: for each node with free unknowns, its unknowns, position and
/// neighbours.
struct NodeGraph {
    eqs: Vec<Vec<usize>>,
    position: Vec<[f64; 3]>,
    /// Neighbours of node `i`: `adjacency[offsets[i]..offsets[i + 1]]`.
    offsets: Vec<usize>,
    adjacency: Vec<u32>,
    /// Unknowns of no node.
    loose: Vec<usize>,
}

/// The nested-dissection order of the `n` unknowns of the pattern `(col_ptr, row_idx)`
/// (compressed columns, both triangles or either) of the mesh `nodes`: entry `k` is the
/// unknown eliminated `k`-th (faer's forward permutation).
pub fn nested_dissection(n: usize, col_ptr: &[usize], row_idx: &[usize], nodes: &MeshNodes) -> Vec<usize> {
    let graph = NodeGraph::new(n, col_ptr, row_idx, nodes);
    let mut cut = Cutter {
        graph: &graph,
        side: vec![0; graph.eqs.len()],
        order: Vec::with_capacity(graph.eqs.len()),
    };
    let all = (0..graph.eqs.len() as u32).collect::<Vec<_>>();
    cut.dissect(all);
    let mut order = Vec::with_capacity(n);
    for &v in &cut.order {
        order.extend_from_slice(&graph.eqs[v as usize]);
    }
    order.extend_from_slice(&graph.loose);
    debug_assert_eq!(order.len(), n);
    order
}

impl NodeGraph {
    fn new(n: usize, col_ptr: &[usize], row_idx: &[usize], nodes: &MeshNodes) -> Self {
        let mut eqs = Vec::new();
        let mut position = Vec::new();
        let mut push = |e: Vec<usize>, x: [f64; 3]| {
            if !e.is_empty() {
                eqs.push(e);
                position.push(x);
            }
        };
        match nodes {
            MeshNodes::Plane(list) => {
                for (e, x) in list {
                    push(e.iter().flatten().copied().collect(), [x[0], x[1], 0.0]);
                }
            }
            MeshNodes::Solid(list) => {
                for (e, x) in list {
                    push(e.iter().flatten().copied().collect(), *x);
                }
            }
        }
        let mut node_of = vec![u32::MAX; n];
        for (v, e) in eqs.iter().enumerate() {
            for &k in e {
                node_of[k] = v as u32;
            }
        }
        let loose = (0..n).filter(|&k| node_of[k] == u32::MAX).collect();
        let (offsets, adjacency) = node_adjacency(&eqs, &node_of, col_ptr, row_idx);
        NodeGraph {
            eqs,
            position,
            offsets,
            adjacency,
            loose,
        }
    }

    fn neighbours(&self, v: u32) -> &[u32] {
        &self.adjacency[self.offsets[v as usize]..self.offsets[v as usize + 1]]
    }
}

/// The neighbours of each node: the nodes of the rows of its unknowns' columns (sorted, no
/// repeats, itself and unknowns of no node left out), as offsets and a flat list.
fn node_adjacency(eqs: &[Vec<usize>], node_of: &[u32], col_ptr: &[usize], row_idx: &[usize]) -> (Vec<usize>, Vec<u32>) {
    let mut offsets = Vec::with_capacity(eqs.len() + 1);
    let mut adjacency = Vec::new();
    offsets.push(0);
    for (v, e) in eqs.iter().enumerate() {
        let start = adjacency.len();
        for &c in e {
            for &r in &row_idx[col_ptr[c]..col_ptr[c + 1]] {
                let w = node_of[r];
                if w != u32::MAX && w != v as u32 {
                    adjacency.push(w);
                }
            }
        }
        sort_dedup_tail(&mut adjacency, start);
        offsets.push(adjacency.len());
    }
    (offsets, adjacency)
}

/// The recursive bisection: `side` marks the nodes of the set being cut (1: lower half, 2:
/// upper half, 0: elsewhere); `order` receives the nodes in elimination order.
struct Cutter<'a> {
    graph: &'a NodeGraph,
    side: Vec<u8>,
    order: Vec<u32>,
}

impl Cutter<'_> {
    /// Order the nodes of `set`: both halves, then their separator.
    fn dissect(&mut self, set: Vec<u32>) {
        if set.len() <= LEAF_NODES {
            self.order.extend_from_slice(&set);
            return;
        }
        let (lower, upper, separator) = self.best_cut(set);
        if lower.is_empty() || upper.is_empty() {
            // every node of one half is coupled to the other (a clique): nothing to cut
            self.order.extend(lower.iter().chain(&upper).chain(&separator));
            return;
        }
        self.dissect(lower);
        self.dissect(upper);
        self.order.extend_from_slice(&separator);
    }

    /// The cut of `set` with the smallest separator over the axes and the two sides, as
    /// (lower half, upper half, separator), the separator taken out of its half.
    fn best_cut(&mut self, mut set: Vec<u32>) -> (Vec<u32>, Vec<u32>, Vec<u32>) {
        let mut best: Option<(usize, usize, bool)> = None; // (size, axis, from the lower half)
        for axis in 0..3 {
            if self.extent(&set, axis) == 0.0 {
                continue;
            }
            let mid = self.split_at_median(&mut set, axis);
            let (from_lower, from_upper) = self.coupled_counts(&set, mid);
            for (size, lower_side) in [(from_lower, true), (from_upper, false)] {
                if best.is_none_or(|b| size < b.0) {
                    best = Some((size, axis, lower_side));
                }
            }
        }
        let (_, axis, lower_side) = best.unwrap_or((0, 0, true));
        let mid = self.split_at_median(&mut set, axis);
        let upper = set.split_off(mid);
        let lower = set;
        self.mark(&lower, 1);
        self.mark(&upper, 2);
        let (lower, upper, separator) = if lower_side {
            let (separator, rest) = self.separate(&lower, 2);
            (rest, upper, separator)
        } else {
            let (separator, rest) = self.separate(&upper, 1);
            (lower, rest, separator)
        };
        self.mark(&lower, 0);
        self.mark(&upper, 0);
        self.mark(&separator, 0);
        (lower, upper, separator)
    }

    /// The nodes of `half` coupled to nodes marked `other`, and the rest of `half`.
    fn separate(&self, half: &[u32], other: u8) -> (Vec<u32>, Vec<u32>) {
        half.iter().partition(|&&v| self.touches(v, other))
    }

    fn extent(&self, set: &[u32], axis: usize) -> f64 {
        let (lo, hi) = set.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &v| {
            let x = self.graph.position[v as usize][axis];
            (lo.min(x), hi.max(x))
        });
        hi - lo
    }

    /// Reorder `set` so that its first `k` nodes lie below the others along `axis`, cut at
    /// the median coordinate with the nodes at the median in the upper part (a layer of
    /// nodes at one coordinate is not split), or in the lower one when none would lie below;
    /// returns `k`.
    fn split_at_median(&self, set: &mut [u32], axis: usize) -> usize {
        let pos = &self.graph.position;
        let x = |v: u32| pos[v as usize][axis];
        let mid = set.len() / 2;
        set.select_nth_unstable_by(mid, |&a, &b| x(a).total_cmp(&x(b)));
        let median = x(set[mid]);
        let below = partition_in_place(set, |v| x(v) < median);
        if below > 0 {
            return below;
        }
        partition_in_place(set, |v| x(v) <= median)
    }

    /// How many nodes of the lower part (`set[..mid]`) touch the upper part, and the reverse.
    fn coupled_counts(&mut self, set: &[u32], mid: usize) -> (usize, usize) {
        self.mark(&set[..mid], 1);
        self.mark(&set[mid..], 2);
        let from_lower = set[..mid].iter().filter(|&&v| self.touches(v, 2)).count();
        let from_upper = set[mid..].iter().filter(|&&v| self.touches(v, 1)).count();
        self.mark(set, 0);
        (from_lower, from_upper)
    }

    fn touches(&self, v: u32, mark: u8) -> bool {
        self.graph.neighbours(v).iter().any(|&w| self.side[w as usize] == mark)
    }

    fn mark(&mut self, set: &[u32], mark: u8) {
        for &v in set {
            self.side[v as usize] = mark;
        }
    }
}

/// Move the entries satisfying `below` to the front of `set`; returns how many there are.
fn partition_in_place(set: &mut [u32], below: impl Fn(u32) -> bool) -> usize {
    let mut k = 0;
    for i in 0..set.len() {
        if below(set[i]) {
            set.swap(i, k);
            k += 1;
        }
    }
    k
}

#[cfg(test)]
#[path = "dissection_tests.rs"]
pub(crate) mod tests;
