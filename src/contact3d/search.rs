//! Which facets a slave point may be paired with: a uniform grid of the facets' bounding
//! boxes (built once per increment, inflated by the pair's search radius), so that a point
//! is tested against the facets of its own cell only — the cost of a search grows with the
//! number of slaves, not with slaves × facets.

use std::collections::HashMap;

/// Facets binned by the cells their inflated bounding boxes overlap.
#[derive(Debug, Clone, Default)]
pub struct FacetGrid {
    cell: f64,
    bins: HashMap<[i64; 3], Vec<usize>>,
}

impl FacetGrid {
    /// The grid of facets `boxes` (`[min, max]` corners each), every box inflated by
    /// `radius` on each side; the cell size is the larger of `radius` and the mean box
    /// diagonal.
    pub fn new(boxes: &[[[f64; 3]; 2]], radius: f64) -> Self {
        let mean_diagonal = boxes
            .iter()
            .map(|[lo, hi]| (0..3).map(|c| (hi[c] - lo[c]).powi(2)).sum::<f64>().sqrt())
            .sum::<f64>()
            / boxes.len().max(1) as f64;
        let cell = radius.max(mean_diagonal).max(f64::MIN_POSITIVE);
        let mut grid = FacetGrid {
            cell,
            bins: HashMap::new(),
        };
        for (f, [lo, hi]) in boxes.iter().enumerate() {
            let lo = grid.key(lo.map(|v| v - radius));
            let hi = grid.key(hi.map(|v| v + radius));
            for i in lo[0]..=hi[0] {
                for j in lo[1]..=hi[1] {
                    for k in lo[2]..=hi[2] {
                        grid.bins.entry([i, j, k]).or_default().push(f);
                    }
                }
            }
        }
        grid
    }

    fn key(&self, p: [f64; 3]) -> [i64; 3] {
        p.map(|v| (v / self.cell).floor() as i64)
    }

    /// The facets whose inflated boxes overlap the cell of `p` (a superset of those within
    /// the search radius of `p`).
    pub fn candidates(&self, p: [f64; 3]) -> &[usize] {
        self.bins.get(&self.key(p)).map_or(&[], Vec::as_slice)
    }
}

/// The bounding box `[min, max]` of points.
pub fn bounding_box(points: impl IntoIterator<Item = [f64; 3]>) -> [[f64; 3]; 2] {
    let mut b = [[f64::INFINITY; 3], [f64::NEG_INFINITY; 3]];
    for p in points {
        for c in 0..3 {
            b[0][c] = b[0][c].min(p[c]);
            b[1][c] = b[1][c].max(p[c]);
        }
    }
    b
}

/// How far past a free border (in `ξ`: 0.05 % of the facet's width) a point closed on the
/// face at the last converged increment, and still penetrating, stays paired with it (the
/// 2D rule of `contact::pairing::FREE_END_HOLD`): two faces meshed edge to edge keep their
/// border nodes at `ξ = ±1` only to the strain's mismatch.
pub const FREE_BORDER_HOLD: f64 = 1e-3;

/// How far past a free border (in `ξ`) any point is still on the face: the 2D rule's
/// tolerance on `|ξ| ≤ 1` ([`crate::contact::search::XI_TOL`], 1e-10), one rule in both
/// dimensions. A node of a body as wide as its master lies on the border to within the
/// round-off of its coordinates and the displacement noise of converged iterates (4.7e-14 of
/// a 0.05-wide face, i.e. 1.9e-12 in `ξ`, after 900 increments of the refined plate over an
/// edge), which the projection's own `1e-12` took for "beyond".
pub const FREE_BORDER_ROUNDOFF: f64 = crate::contact::search::XI_TOL;

/// Per facet of a face, which of its edges are the face's free border (no other facet of the
/// face has both its nodes): edge `e` runs from node `e` to node `e + 1 (mod 4)`, i.e. edges
/// 0–3 lie at `ξ² = −1`, `ξ¹ = 1`, `ξ² = 1`, `ξ¹ = −1` ([`super::surface::NODE_XI`]).
pub fn free_borders(facets: &[[usize; 4]]) -> Vec<[bool; 4]> {
    let edge = |f: &[usize; 4], e: usize| {
        let (a, b) = (f[e], f[(e + 1) % 4]);
        (a.min(b), a.max(b))
    };
    let mut count: HashMap<(usize, usize), usize> = HashMap::new();
    for f in facets {
        for e in 0..4 {
            *count.entry(edge(f, e)).or_default() += 1;
        }
    }
    (facets.iter())
        .map(|f| std::array::from_fn(|e| count[&edge(f, e)] == 1))
        .collect()
}

/// How far `ξ` lies past the free border of a facet with free edges `free` (0 when it is
/// within `[−1, 1]` across each of them): a point there is beyond the master face, on its
/// facets' extension only, and is not paired (2D: a point past a master's free end).
pub fn past_free_border(xi: [f64; 2], free: [bool; 4]) -> f64 {
    let across = [
        (free[3], -1.0 - xi[0]),
        (free[1], xi[0] - 1.0),
        (free[0], -1.0 - xi[1]),
        (free[2], xi[1] - 1.0),
    ];
    (across.iter()).filter(|(f, _)| *f).map(|&(_, d)| d).fold(0.0, f64::max)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_point_finds_every_facet_within_the_radius_and_not_the_far_ones() {
        // a 10 × 10 tiling of unit squares in z = 0
        let boxes: Vec<[[f64; 3]; 2]> = (0..100)
            .map(|f| {
                let (i, j) = ((f % 10) as f64, (f / 10) as f64);
                [[i, j, 0.0], [i + 1.0, j + 1.0, 0.0]]
            })
            .collect();
        let grid = FacetGrid::new(&boxes, 0.3);
        let p = [4.5, 4.5, 0.2];
        let c = grid.candidates(p);
        assert!(c.contains(&44), "the facet under the point");
        for (f, [lo, hi]) in boxes.iter().enumerate() {
            let d2: f64 = (0..3).map(|k| (p[k] - p[k].clamp(lo[k], hi[k])).powi(2)).sum();
            if d2 <= 0.3f64.powi(2) {
                assert!(c.contains(&f), "facet {f} within reach");
            }
        }
        assert!(c.len() < 30, "{} candidates of 100", c.len());
        assert!(grid.candidates([50.0, 50.0, 0.0]).is_empty());
    }
}
