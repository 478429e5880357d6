//! Pairing: which master segment each slave point of each contact pair is paired with at the
//! current iterate. It runs as a step of its own before any kernel is evaluated (search,
//! segment tracking, vertex ownership), so that the kernels only see local data.
//!
//! Rules, in the order they are applied (sketch for a rigid outline with the body below
//! and left of the travel, e.g. block B1 of the strip-channel scene):
//!
//! ```text
//!              free end ──┐          vertex region (owned by the corner slave C)
//!  top face  ◄────────────●  ←  V (convex vertex)
//!  ξ: +1 ...... −1        │ wall
//!   x x x x x x x x x x   │  ξ = −1 at V
//!   x  block (rigid)  x   ▼  ξ = +1 at the free end below
//! ```
//! 1. **Tracking.** A point paired at an earlier iterate or increment walks from its last
//!    segment to the neighbour its projection points to ([`super::search::walk`]); a point
//!    never paired asks a uniform grid of segment boxes built once per increment.
//! 2. **Free ends.** A projection past a free end (`|ξ| > 1` on the last segment) has no
//!    closest point on that surface: the point is not paired (not a search-radius effect).
//! 3. **Convex vertices.** Outside the body, the Voronoi region of a convex vertex projects
//!    onto neither neighbour (`ξ > 1` on one, `ξ < −1` on the other): not paired. Inside the
//!    body both projections can be valid: the point belongs to the face it is nearest to
//!    (smallest `|ζ|`), so a node pushed into the top face next to `V` is not taken as
//!    penetrating the wall by its distance to `V`. At concave vertices the walk keeps the
//!    segment it is on while its projection is valid (hysteresis: no flip-flop); inside the
//!    body at a concave vertex (the face wrapped round an obstacle's corner) a penetrating
//!    point in the wedge between the two normals projects onto neither segment: it keeps its
//!    segment and is pinned to the vertex ([`concave_wedge`], [`super::vertex`]: gap and
//!    normal from the vertex, continuous with both segments), instead of being released.
//! 4. **Owned vertices.** When a vertex of a rigid outline is itself a slave point of another
//!    pair (the corner C against the strip's bottom face), the slave nodes of the master
//!    segment that C presses on (paired, `ζ < 0`) are not paired with the outline's pieces
//!    next to that vertex: the corner contact supports them, and the vertex is counted once,
//!    not twice. When C is open (e.g. the strip's end rests on the block's top beyond C),
//!    the nodes meet the outline themselves. When C has just passed the face's free end, the
//!    face's end node goes round the corner: it is paired with the piece after the vertex
//!    (the wall), which pushes it off the block, not with the piece before it.
//! 5. **Reach.** Points farther than the pair's search radius from the surface (derived from
//!    the mesh by default) are not paired, so a point never meets the far side of a thin body.

use super::geometry::SegmentGeom;
use super::search::{closest, walk, Located, SegmentGrid, XI_TOL};
use super::system::Config;
use crate::model::{ContactPair, Master, Slave, Smoothing};

/// How far past its end (in `ξ`, i.e. 2.5 % of the segment's length) a segment held by the
/// solver for a chattering point stays admissible when the point is verified. A point that
/// Newton drives back and forth across a kink of the master (the corner C over a node of the
/// strip's bottom face: on one segment the equilibrium lies just beyond its end, on the next
/// just before its start) has no node-to-segment equilibrium with `|ξ| ≤ 1` on either; the
/// frozen one on the held segment's extension is accepted, as master-segment extensions are
/// in node-to-segment codes, instead of cycling.
pub const HELD_EXTENSION: f64 = 0.05;

/// Pairing of one slave point at the current iterate.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Pairing {
    /// Segment the point is tracked on (also while open, for the neighbour walk).
    pub segment: Option<usize>,
    /// The projection when the point is paired (`|ξ| ≤ 1`, within reach, not excluded).
    pub located: Option<Located>,
    /// The point would be paired but its vertex region is owned by another pair.
    pub excluded: bool,
    /// The point is in the wedge of a concave vertex at the end of `segment` its `ξ` points
    /// to: it is pinned to that vertex (point-to-node form, [`super::vertex`]).
    pub pinned: bool,
    /// The tracked point projects onto the master (`|ξ| ≤ 1`) deeper inside it than the
    /// search radius: unpaired, since from the geometry alone it cannot be told from a
    /// point beyond the far side of a thin body. A point that was paired at the previous
    /// iterate has passed through the master in one step (see
    /// `ContactSystem::tunnelled`).
    pub beyond_reach_inside: bool,
}

/// Locate slave `slave` of `pair`, starting from `start` when it is tracked. `gap_shift`
/// (`λ_N/ε_N` of an augmented point, else 0) is taken off the gap the rules see: such a
/// point is in contact while `ζ < λ_N/ε_N`.
pub fn locate(
    cfg: &Config,
    pair: &ContactPair,
    slave: Slave,
    start: Option<usize>,
    closed_before: bool,
    grid: &mut Option<SegmentGrid>,
    gap_shift: f64,
) -> Pairing {
    let rs = cfg.slave_pos(slave);
    let geom = |s: usize| cfg.segment(pair, s);
    let nb = |s: usize| pair.master.neighbours(s);
    let count = pair.master.segment_count();
    let (found, wedge) = match start {
        Some(s0) => {
            let loc = nearest_face(walk(s0, rs, &geom, &nb, count), rs, &geom, &nb);
            let faceted = pair.face_smoothing() == Smoothing::None;
            match concave_wedge(loc, s0, rs, &geom, &nb).filter(|_| faceted) {
                Some(held) => (Some(held), true),
                None => (Some(loc), false),
            }
        }
        None => {
            let g =
                grid.get_or_insert_with(|| SegmentGrid::new((0..count).map(|s| bbox(&geom(s))), pair.search_radius));
            (closest(rs, g.candidates(rs), &geom, pair.search_radius), false)
        }
    };
    let Some(mut loc) = found else {
        return Pairing::default();
    };
    loc.gap -= gap_shift;
    if is_own_segment(pair, slave, loc.segment) {
        return Pairing::default();
    }
    if loc.gap.abs() > pair.search_radius {
        // out of reach: untracked
        return Pairing {
            beyond_reach_inside: start.is_some() && loc.gap < 0.0 && loc.xi.abs() <= 1.0 + XI_TOL,
            ..Pairing::default()
        };
    }
    let valid = wedge || loc.xi.abs() <= 1.0 + XI_TOL || held_at_free_end(pair, loc, start, closed_before);
    Pairing {
        segment: Some(loc.segment),
        located: valid.then_some(loc),
        excluded: false,
        pinned: wedge && loc.xi.abs() > 1.0 + XI_TOL,
        beyond_reach_inside: false,
    }
}

/// Rule 2b: a point that was closed on the last segment of a master (at the last converged
/// increment or the previous iterate) and now projects just past its free end — by at most
/// [`FREE_END_HOLD`], still penetrating — stays paired with it. The end node of a body
/// resting on another with matching edges (the contact patch test, a sheet whose end lies on
/// a facet's end) sits at `ξ = ±1` to within the penetration; released at `ξ = 1 + 10⁻⁶`
/// and paired again at `1 − 10⁻⁶`, its force switched on and off between Newton iterates
/// (the residual jumped by 10³ on the patch test). A point must move clearly past the end, or
/// open, to leave.
fn held_at_free_end(pair: &ContactPair, loc: Located, start: Option<usize>, closed_before: bool) -> bool {
    let (prev, next) = pair.master.neighbours(loc.segment);
    let free_end = if loc.xi > 0.0 { next.is_none() } else { prev.is_none() };
    closed_before && start == Some(loc.segment) && free_end && loc.gap < 0.0 && loc.xi.abs() <= 1.0 + FREE_END_HOLD
}

/// How far past a free end (in `ξ`: 0.05 % of the segment's length) a closed point stays
/// paired with it ([`held_at_free_end`]): well above the strain-level mismatch of two bodies'
/// edges pressed together, well below anything a node sliding off an end travels in an
/// increment.
pub const FREE_END_HOLD: f64 = 1e-3;

/// The pairing of a point held on `segment` by the solver (projection on the segment's
/// line even past its ends; `None`: unpaired).
pub fn held(cfg: &Config, pair: &ContactPair, slave: Slave, segment: Option<usize>) -> Pairing {
    let Some(s) = segment else {
        return Pairing::default();
    };
    let rs = cfg.slave_pos(slave);
    let p = cfg.segment(pair, s).project(rs);
    let loc = Located {
        segment: s,
        xi: p.xi,
        gap: p.gap,
    };
    let geom = |k: usize| cfg.segment(pair, k);
    let nb = |k: usize| pair.master.neighbours(k);
    Pairing {
        segment,
        located: Some(loc),
        excluded: false,
        // a C1-smoothed face has no concave kink to be pinned to
        pinned: pair.face_smoothing() == Smoothing::None && concave_wedge(loc, s, rs, &geom, &nb).is_some(),
        beyond_reach_inside: false,
    }
}

/// Rule 3: a penetrating point near a convex vertex belongs to the nearer face.
fn nearest_face(
    loc: Located,
    rs: [f64; 2],
    geom: &dyn Fn(usize) -> SegmentGeom<f64>,
    nb: &dyn Fn(usize) -> (Option<usize>, Option<usize>),
) -> Located {
    if loc.gap >= 0.0 || loc.xi.abs() > 1.0 + XI_TOL {
        return loc;
    }
    let (prev, next) = nb(loc.segment);
    let (other, forward) = if loc.xi > 0.0 { (next, true) } else { (prev, false) };
    let Some(o) = other else { return loc };
    let (gs, go) = (geom(loc.segment), geom(o));
    let convex = if forward { turn(&gs, &go) } else { turn(&go, &gs) } > 0.0;
    let p = go.project(rs);
    if convex && p.xi.abs() <= 1.0 + XI_TOL && p.gap.abs() < loc.gap.abs() {
        Located {
            segment: o,
            xi: p.xi,
            gap: p.gap,
        }
    } else {
        loc
    }
}

/// Rule 3b: inside the body at a concave vertex (a face wrapped round a convex obstacle,
/// e.g. the strip's bottom face over the corner C) the normals of the two segments meet: a
/// penetrating point in the wedge between them projects past the end of both (`ξ > 1` on
/// the one before, `ξ < −1` on the one after), although it is in contact with both. Taking
/// it as open releases it, the next iterate pushes it back in, and Newton cycles. In the
/// wedge the point keeps the segment it is tracked on (`start`, projected on its line a
/// little past the end) until the other segment's projection becomes valid; untracked, it
/// takes the segment it overshoots less. Returns `None` when `loc` is not in such a wedge.
fn concave_wedge(
    loc: Located,
    start: usize,
    rs: [f64; 2],
    geom: &dyn Fn(usize) -> SegmentGeom<f64>,
    nb: &dyn Fn(usize) -> (Option<usize>, Option<usize>),
) -> Option<Located> {
    let over = loc.xi.abs() - 1.0;
    if over <= XI_TOL || loc.gap >= 0.0 {
        return None;
    }
    let (prev, next) = nb(loc.segment);
    let o = if loc.xi > 0.0 { next } else { prev }?;
    let q = geom(o).project(rs);
    // the other segment must be overshot on its far side (past its end towards `loc`)
    let far_side = if loc.xi > 0.0 {
        q.xi < -1.0 - XI_TOL
    } else {
        q.xi > 1.0 + XI_TOL
    };
    if !far_side || q.gap >= 0.0 {
        return None;
    }
    let other = Located {
        segment: o,
        xi: q.xi,
        gap: q.gap,
    };
    Some(if start == o || (start != loc.segment && q.xi.abs() - 1.0 < over) {
        other
    } else {
        loc
    })
}

/// `ρ_1(a, ξ = 1) × ρ_1(b, ξ = −1)`: positive when the boundary turns left from `a` to `b`,
/// i.e. at a convex vertex of the body on the left.
fn turn(a: &SegmentGeom<f64>, b: &SegmentGeom<f64>) -> f64 {
    let (_, ta) = a.eval(1.0);
    let (_, tb) = b.eval(-1.0);
    ta[0] * tb[1] - ta[1] * tb[0]
}

/// Rule 4: drop the pairing of nodes next to a vertex owned by another pair's slave.
/// `pairings[ip][is]` are the pairings of every pair at the current iterate;
/// `committed(ip, is)`: the point's segment and whether it was closed at the last converged
/// increment.
///
/// - While the vertex presses on a face segment (`ζ < 0`), the segment's two nodes are not
///   paired with the outline's pieces on either side of the vertex: the vertex contact
///   supports them (an open vertex on the face supports nothing).
/// - When the vertex, closed on the face at the last converged increment, has just passed the
///   face's free end, the face's end node is going round the corner: if it was on the piece
///   before the vertex at the last converged increment and now lies past the vertex along
///   that piece, it is paired with the piece after the vertex (which pushes it off the
///   outline), not with the one before it (which would push it up through the outline by
///   the depth of the other piece). An end node coming the other way (a block dragged from
///   beyond the piece after the vertex onto the one before) is left to the nearest-face rule.
pub fn exclude_owned_vertices(
    cfg: &Config,
    pairings: &mut [Vec<Pairing>],
    committed: &dyn Fn(usize, usize) -> (Option<usize>, bool),
) {
    for (ip, pair) in cfg.model.contacts.iter().enumerate() {
        for owned in &pair.owned_vertices {
            let owner = &cfg.model.contacts[owned.owner];
            let owner_pairing = pairings[owned.owner][owned.slave];
            let Some(seg) = owner_pairing.segment else { continue };
            let Master::Face {
                segments, prev, next, ..
            } = &owner.master
            else {
                continue;
            };
            match owner_pairing.located {
                Some(l) if l.gap < 0.0 => {
                    for (is, slave) in pair.slaves.iter().enumerate() {
                        let p = &mut pairings[ip][is];
                        let near = p
                            .located
                            .is_some_and(|l| l.segment + 1 == owned.vertex || l.segment == owned.vertex);
                        if near && matches!(slave, Slave::Node(n) if segments[seg].contains(n)) {
                            p.located = None;
                            p.excluded = true;
                        }
                    }
                }
                None if committed(owned.owner, owned.slave).1 => {
                    // the face's end node on the side the vertex has passed
                    let owner_at = cfg
                        .segment(owner, seg)
                        .project(cfg.slave_pos(owner.slaves[owned.slave]));
                    let end = match (owner_at.xi > 1.0, prev[seg], next[seg]) {
                        (true, _, None) => segments[seg][1],
                        (false, None, _) => segments[seg][0],
                        _ => continue,
                    };
                    for (is, slave) in pair.slaves.iter().enumerate() {
                        let was_before = committed(ip, is).0.is_some_and(|s| s + 1 == owned.vertex);
                        // past the vertex along the piece before it: rounding the corner
                        let rounding = || cfg.segment(pair, owned.vertex - 1).project(cfg.slave_pos(*slave)).xi > 1.0;
                        if *slave == Slave::Node(end) && was_before && pairings[ip][is].located.is_some() && rounding()
                        {
                            pairings[ip][is] = held(cfg, pair, *slave, Some(owned.vertex));
                        }
                    }
                }
                _ => {}
            }
        }
    }
}

fn is_own_segment(pair: &ContactPair, slave: Slave, seg: usize) -> bool {
    match (&pair.master, slave) {
        (Master::Face { segments, .. }, Slave::Node(n)) => segments[seg].contains(&n),
        _ => false,
    }
}

fn bbox(g: &SegmentGeom<f64>) -> ([f64; 2], [f64; 2]) {
    let mut lo = [f64::MAX; 2];
    let mut hi = [f64::MIN; 2];
    for i in 0..=8 {
        let p = g.eval(-1.0 + 0.25 * i as f64).0;
        for d in 0..2 {
            lo[d] = lo[d].min(p[d]);
            hi[d] = hi[d].max(p[d]);
        }
    }
    (lo, hi)
}

#[cfg(test)]
#[path = "pairing_tests.rs"]
mod tests;
