//! Finding the master segment of a slave point without an all-pairs loop: a tracked point
//! walks from its last segment to the neighbour its projection points to (`ξ > 1`: next,
//! `ξ < −1`: previous); an untracked point queries a uniform grid of segment bounding boxes
//! (cell size = search radius) built once per evaluation.

use super::geometry::SegmentGeom;
use std::collections::HashMap;

/// Tolerance on `|ξ| ≤ 1` when deciding that a projection belongs to a segment.
pub const XI_TOL: f64 = 1e-10;

/// Outcome of a search for one slave point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Located {
    pub segment: usize,
    pub xi: f64,
    pub gap: f64,
}

/// Walk from `start` along the chain; returns the segment whose projection has
/// `|ξ| ≤ 1`, or the last segment of the walk when the point lies past a free end or in the
/// gap at a convex vertex (then `|ξ| > 1` and the caller treats it as outside).
pub fn walk(
    start: usize,
    rs: [f64; 2],
    geom: &dyn Fn(usize) -> SegmentGeom<f64>,
    neighbours: &dyn Fn(usize) -> (Option<usize>, Option<usize>),
    max_steps: usize,
) -> Located {
    let mut seg = start;
    let mut p = geom(seg).project(rs);
    let mut came_from: Option<usize> = None;
    for _ in 0..max_steps {
        let (prev, next) = neighbours(seg);
        let to = if p.xi > 1.0 + XI_TOL {
            next
        } else if p.xi < -1.0 - XI_TOL {
            prev
        } else {
            None
        };
        let Some(to) = to else { break };
        if Some(to) == came_from {
            break; // convex vertex gap: stay where we are
        }
        let q = geom(to).project(rs);
        came_from = Some(seg);
        seg = to;
        p = q;
    }
    Located {
        segment: seg,
        xi: p.xi,
        gap: p.gap,
    }
}

/// Uniform grid over segment bounding boxes inflated by the search radius.
pub struct SegmentGrid {
    cell: f64,
    cells: HashMap<(i64, i64), Vec<usize>>,
}

impl SegmentGrid {
    pub fn new(boxes: impl Iterator<Item = ([f64; 2], [f64; 2])>, radius: f64) -> Self {
        let cell = radius.max(1e-12);
        let mut cells: HashMap<(i64, i64), Vec<usize>> = HashMap::new();
        for (k, (lo, hi)) in boxes.enumerate() {
            let (i0, j0) = Self::key(cell, [lo[0] - radius, lo[1] - radius]);
            let (i1, j1) = Self::key(cell, [hi[0] + radius, hi[1] + radius]);
            // very long pieces (rigid planes) are capped to keep the grid small; the caller
            // falls back to a direct check for them
            if (i1 - i0 + 1) * (j1 - j0 + 1) > 4096 {
                cells.entry((i64::MIN, i64::MIN)).or_default().push(k);
                continue;
            }
            for i in i0..=i1 {
                for j in j0..=j1 {
                    cells.entry((i, j)).or_default().push(k);
                }
            }
        }
        SegmentGrid { cell, cells }
    }

    fn key(cell: f64, p: [f64; 2]) -> (i64, i64) {
        ((p[0] / cell).floor() as i64, (p[1] / cell).floor() as i64)
    }

    /// Candidate segments near `p` (including oversized ones).
    pub fn candidates(&self, p: [f64; 2]) -> impl Iterator<Item = usize> + '_ {
        let here = self.cells.get(&Self::key(self.cell, p)).into_iter().flatten();
        let big = self.cells.get(&(i64::MIN, i64::MIN)).into_iter().flatten();
        here.chain(big).copied()
    }
}

/// Closest segment among `candidates` with `|ξ| ≤ 1` and `|ζ| ≤ radius`.
pub fn closest(
    rs: [f64; 2],
    candidates: impl Iterator<Item = usize>,
    geom: &dyn Fn(usize) -> SegmentGeom<f64>,
    radius: f64,
) -> Option<Located> {
    let mut best: Option<Located> = None;
    for k in candidates {
        let p = geom(k).project(rs);
        if p.xi.abs() <= 1.0 + XI_TOL && p.gap.abs() <= radius && best.is_none_or(|b| p.gap.abs() < b.gap.abs()) {
            best = Some(Located {
                segment: k,
                xi: p.xi,
                gap: p.gap,
            });
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;

    fn chain() -> Vec<SegmentGeom<f64>> {
        (0..10)
            .map(|i| SegmentGeom::Linear {
                x1: [i as f64, 0.0],
                x2: [i as f64 + 1.0, 0.0],
            })
            .collect()
    }

    #[test]
    fn walk_follows_the_projection_and_stops_at_free_ends() {
        let c = chain();
        let g = |k: usize| c[k];
        let nb = |k: usize| (k.checked_sub(1), if k + 1 < 10 { Some(k + 1) } else { None });
        let l = walk(2, [6.5, 0.1], &g, &nb, 20);
        assert_eq!(l.segment, 6);
        assert!(l.xi.abs() < 1e-12);
        let l = walk(8, [12.0, 0.1], &g, &nb, 20);
        assert_eq!(l.segment, 9);
        assert!(l.xi > 1.0);
    }

    #[test]
    fn grid_finds_the_same_segment_as_brute_force() {
        let c = chain();
        let g = |k: usize| c[k];
        let grid = SegmentGrid::new((0..10).map(|k| ([k as f64, 0.0], [k as f64 + 1.0, 0.0])), 0.5);
        for x in [0.1, 3.3, 7.9, 9.99] {
            let a = closest([x, -0.2], grid.candidates([x, -0.2]), &g, 0.5).unwrap();
            let b = closest([x, -0.2], 0..10, &g, 0.5).unwrap();
            assert_eq!(a.segment, b.segment);
        }
        assert!(closest([4.0, 3.0], grid.candidates([4.0, 3.0]), &g, 0.5).is_none());
    }
}
