//! Finding the master segment of a slave point without an all-pairs loop: a tracked point
//! walks from its last segment to the neighbour its projection points to (`ξ > 1`: next,
//! `ξ < −1`: previous); an untracked point queries a uniform grid of segment bounding boxes
//! built once per increment.

use super::geometry::SegmentGeom;

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

/// Uniform grid over segment bounding boxes inflated by the search radius, stored flat
/// (cell lists in one array with offsets, no hashing). The number of cells is bounded by a
/// small multiple of the number of segments, whatever the radius or the extent.
#[derive(Debug, Clone)]
pub struct SegmentGrid {
    origin: [f64; 2],
    cell: f64,
    dims: [usize; 2],
    /// `items[start[c]..start[c + 1]]` are the segments of cell `c`.
    start: Vec<u32>,
    items: Vec<u32>,
    /// Segments covering too many cells (long rigid planes), checked for every query.
    big: Vec<u32>,
}

impl SegmentGrid {
    pub fn new(boxes: impl Iterator<Item = ([f64; 2], [f64; 2])>, radius: f64) -> Self {
        let boxes: Vec<([f64; 2], [f64; 2])> = boxes
            .map(|(lo, hi)| ([lo[0] - radius, lo[1] - radius], [hi[0] + radius, hi[1] + radius]))
            .collect();
        let n = boxes.len();
        let mut lo = [f64::MAX; 2];
        let mut hi = [f64::MIN; 2];
        for (a, b) in &boxes {
            for d in 0..2 {
                lo[d] = lo[d].min(a[d]);
                hi[d] = hi[d].max(b[d]);
            }
        }
        let extent = [(hi[0] - lo[0]).max(0.0), (hi[1] - lo[1]).max(0.0)];
        let max_cells = (4 * n).max(16) as f64;
        let mut cell = radius.max((extent[0] * extent[1] / max_cells).sqrt());
        cell = cell.max(extent[0].max(extent[1]) / max_cells).max(1e-12);
        let finite = extent[0].is_finite() && extent[1].is_finite() && cell.is_finite();
        let dims = if finite {
            [(extent[0] / cell) as usize + 1, (extent[1] / cell) as usize + 1]
        } else {
            [0, 0]
        };
        let mut grid = SegmentGrid {
            origin: lo,
            cell,
            dims,
            start: vec![0; dims[0] * dims[1] + 1],
            items: Vec::new(),
            big: Vec::new(),
        };
        // two passes: count, then fill (counting sort into the flat array)
        let mut ranges = Vec::with_capacity(n);
        for (k, (a, b)) in boxes.iter().enumerate() {
            match (grid.key(*a), grid.key(*b)) {
                (Some(i0), Some(i1)) if (i1[0] - i0[0] + 1) * (i1[1] - i0[1] + 1) <= 64 => {
                    for i in i0[0]..=i1[0] {
                        for j in i0[1]..=i1[1] {
                            grid.start[i * dims[1] + j + 1] += 1;
                        }
                    }
                    ranges.push(Some((i0, i1)));
                }
                _ => {
                    grid.big.push(k as u32);
                    ranges.push(None);
                }
            }
        }
        for c in 1..grid.start.len() {
            grid.start[c] += grid.start[c - 1];
        }
        let mut fill = grid.start.clone();
        grid.items = vec![0; *grid.start.last().unwrap_or(&0) as usize];
        for (k, r) in ranges.iter().enumerate() {
            let Some((i0, i1)) = r else { continue };
            for i in i0[0]..=i1[0] {
                for j in i0[1]..=i1[1] {
                    let c = i * dims[1] + j;
                    grid.items[fill[c] as usize] = k as u32;
                    fill[c] += 1;
                }
            }
        }
        grid
    }

    /// Cell of `p`, or `None` outside the grid.
    fn key(&self, p: [f64; 2]) -> Option<[usize; 2]> {
        let f = [(p[0] - self.origin[0]) / self.cell, (p[1] - self.origin[1]) / self.cell];
        if !(f[0] >= 0.0 && f[1] >= 0.0) {
            return None;
        }
        let (i, j) = (f[0] as usize, f[1] as usize);
        (i < self.dims[0] && j < self.dims[1]).then_some([i, j])
    }

    /// Candidate segments near `p` (including oversized ones).
    pub fn candidates(&self, p: [f64; 2]) -> impl Iterator<Item = usize> + '_ {
        let here: &[u32] = match self.key(p) {
            Some([i, j]) => {
                let c = i * self.dims[1] + j;
                &self.items[self.start[c] as usize..self.start[c + 1] as usize]
            }
            None => &[],
        };
        here.iter().chain(&self.big).map(|&k| k as usize)
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
            .map(|i| SegmentGeom::linear([i as f64, 0.0], [i as f64 + 1.0, 0.0]))
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
