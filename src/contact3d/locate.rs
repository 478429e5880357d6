//! Which facet of a deformable master face a slave point is paired with: the nearest one
//! (see [`locate`]), among the candidates of the face's search grid.

use super::nagata::FacetBends;
use super::projection::{project, INSIDE_TOLERANCE};
use super::search::FacetGrid;
use super::surface::Facet;
use super::system::SurfaceConfig;
use super::vec3::{norm, sub};

/// The facet slave `x` (current position) is paired with: of the facets within reach, the
/// nearest to `x` — the distance to its point at the projection's `ξ` clamped to
/// `[−1, 1]²`, which is `|ζ|` where `x` projects inside it — so the closest point of the
/// face as a whole (Konyukhov & Schweizerhof, CMAME 197 (2008): the projection onto a C0
/// surface). Of facets as near (to round-off: the two sides of a convex edge, or an edge
/// the point projects onto), `start` (the facet of the last iterate), else one it projects
/// inside, else the one whose projection lies least outside it, its extension then
/// carrying the point (past the face's free border the caller leaves it unpaired, see
/// [`super::evaluate`]). `None`: no facet within the search radius. Neither how far `ξ`
/// lies outside nor being inside may outrank the distance: a point a hair past the free
/// border of a narrow facet it rests on may project inside, or less far outside in `ξ`, a
/// long facet meeting that one at an edge, whose plane is far away. The projections are
/// computed about the slave's reference position `origin` (as the kernels are), so that a
/// model far from the origin pairs as it does near it. With `bends`, the facets are the
/// face's Nagata patches ([`super::nagata`]).
pub fn locate(
    cfg: &SurfaceConfig,
    (facets, bends): (&[[usize; 4]], Option<&FacetBends>),
    grid: &FacetGrid,
    (node, origin): (usize, [f64; 3]),
    start: Option<usize>,
    radius: f64,
) -> Option<usize> {
    let x = cfg.node_about(node, origin);
    let try_facet = |f: usize| -> Option<FacetScore> {
        let corners = cfg.facet_about(&facets[f], origin);
        let facet = Facet {
            x: corners,
            bend: bends.map(|b| b.of(f)),
        };
        let p = project(&facet, x).ok()?;
        let excess = p.point.xi.iter().map(|v| v.abs() - 1.0).fold(0.0, f64::max);
        let nearest = facet.position(p.point.xi.map(|v| v.clamp(-1.0, 1.0)));
        (p.gap.abs() <= radius).then_some(FacetScore {
            excess,
            gap: p.gap.abs(),
            distance: norm(sub(x, nearest)),
            size: norm(sub(facet.x[2], facet.x[0])),
        })
    };
    // the facet of the last iterate first: of facets as near, it stays
    let mut best: Option<(usize, FacetScore)> = start.and_then(|s| try_facet(s).map(|score| (s, score)));
    for &f in grid.candidates(cfg.node(node)).iter().filter(|&&f| Some(f) != start) {
        let Some(score) = try_facet(f) else { continue };
        let replaces = match best {
            None => true,
            // the last iterate's facet keeps a point as near to another: below a vertex
            // pressed into a dimple, each facet around it is as near (the vertex itself)
            // and a rule that looked further (which projection lies less far outside)
            // switched between them from one Newton iterate to the next
            Some((b, held)) if Some(b) == start && score.ties(&held) => false,
            Some((_, held)) => score.better_than(&held),
        };
        if replaces {
            best = Some((f, score));
        }
    }
    best.map(|(f, _)| f)
}

/// How a slave projects onto one candidate facet ([`locate`]): how far its `ξ` lies outside
/// `[−1, 1]²`, its `|ζ|`, its distance to the facet itself, and the facet's size (a
/// diagonal).
#[derive(Debug, Clone, Copy)]
struct FacetScore {
    excess: f64,
    gap: f64,
    distance: f64,
    size: f64,
}

impl FacetScore {
    /// As near as `other`, to round-off of the distance and of the facets' coordinates.
    fn ties(&self, other: &FacetScore) -> bool {
        let tie = 1e-9 * self.distance.max(other.distance) + 1e-12 * self.size.max(other.size);
        (self.distance - other.distance).abs() <= tie
    }

    fn inside(&self) -> bool {
        self.excess <= INSIDE_TOLERANCE
    }

    /// The nearer facet; of two as near (to round-off of the distance and of the
    /// facets' coordinates), one the point projects inside, else the one it lies least
    /// outside of.
    fn better_than(&self, other: &FacetScore) -> bool {
        if !self.ties(other) {
            return self.distance < other.distance;
        }
        match (self.inside(), other.inside()) {
            (true, false) => true,
            (false, true) => false,
            (true, true) => self.gap < other.gap,
            (false, false) => self.excess < other.excess,
        }
    }
}
