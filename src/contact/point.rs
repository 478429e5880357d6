//! Residual and consistent tangent of one node-to-segment contact point (all states: open,
//! stick, slip, and the crossing step in which the element spans segments `A` and `B`).
//!
//! Virtual work of the point (Konyukhov & Schweizerhof, Comput Mech 35 (2005); notes
//! §"Variations"): `δW = −N δζ − T_1 δξ` with the normal force `N = λ_N − ε_N ζ` while it is
//! positive (`λ_N = 0` for a penalty pair; an augmented pair's multiplier, see [`Multiplier`]),
//! zero otherwise, so the local residual (internal force) is `r = −N ∇ζ − T_1 ∇ξ` and the
//! tangent `K = ε_N ∇ζ ∇ζᵀ − N ∇²ζ − ∇ξ ∇T_1ᵀ − T_1 ∇²ξ`,
//! where `∇` is taken with respect to the current positions of the nodes involved (slave,
//! nodes of `B` and, during a crossing step, nodes of `A`; four nodes per segment on a
//! C1-smoothed face). `ζ(q)`, `ξ(q)` and `T_1(q)` are
//! evaluated in second-order dual numbers, which yields `δζ`, `δξ` (notes formulas,
//! including the `ζ n·δρ_1` term) and their linearisations exactly; the unsymmetric
//! frictional blocks come from `∇T_1`. Each state's tangent is checked against finite
//! differences in the tests (`point_tests.rs`, and `point_methods_tests.rs` for every scheme
//! on faceted and smoothed faces and for augmented points).
//!
//! Sign: `T_1` acts on the slave (see [`super::law`]), so the slave's share of `r` is
//! `−T_1 ρ^1` and the force on the slave is `+T`.

use super::geometry::{Projection, SegmentGeom};
use super::law::{return_map, ContactLaw, ContactState};
use super::scalar::{lift, Scalar, V2};
use super::transfer::{OldPoint, StoredTraction, TransferInput, TransferKind};
use super::vertex;
use crate::model::Piece;
use nalgebra::{Const, U1};
use num_dual::Dual2SVec64;

/// Largest number of nodes one contact point couples: the slave and two segments `A`, `B`
/// of up to four nodes each (a C1-smoothed segment with its two neighbours).
pub const MAX_NODES: usize = 9;

/// Where a point or segment end comes from: a local unknown (node slot) or fixed geometry.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SegSource {
    /// A deformable segment whose ends are local node slots.
    Face([usize; 2]),
    /// A C1-smoothed deformable segment: the slots of the neighbour before (none at a free
    /// end), the two ends, and the neighbour after.
    Hermite([Option<usize>; 4]),
    /// The same slots, smoothed by quadratic Bézier arcs (see `surface::bezier`).
    Bezier([Option<usize>; 4]),
    /// A rigid piece translated by an offset.
    Rigid(Piece, [f64; 2]),
}

/// The slave position: a local node slot or a fixed (rigid, prescribed) point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SlaveSource {
    Node(usize),
    Fixed([f64; 2]),
}

/// How the current segment `B` was reached from `A` along the chain.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Path {
    /// +1: `B` lies after `A` (walking `next`), −1: before, 0: `A = B`.
    pub direction: i8,
    /// Summed current length of the segments strictly between `A` and `B` (held fixed).
    pub between: f64,
}

/// History input of a point that was closed at the last converged increment — or, with
/// `touch_gap`, of a point that was open then and paired with segment `A` at `ξ_A`
/// (`stored.t1 = 0`) with gap `ζ_A = touch_gap ≥ 0`.
///
/// First touch: the point closes during this increment at the fraction
/// `s = ζ_A / (ζ_A − ζ)` of its way from the stored point to the current one (linear in the
/// pseudo-time), so the anchor of stick is put there instead of at the increment's end:
/// `T_1^tr = (1 − s) T_1^tr(ξ_A, T = 0)`, which on one segment is exactly
/// `−ε_T a11 (ξ − ξ_touch)`, `ξ_touch = ξ_A + s (ξ − ξ_A)`. `s` depends on the current gap and
/// is differentiated with everything else.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Closed {
    pub stored: StoredTraction,
    pub seg_a: SegSource,
    pub path: Path,
    pub touch_gap: Option<f64>,
}

/// Local data of one contact point: everything the kernel sees.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PointProblem {
    pub law: ContactLaw,
    pub scheme: TransferKind,
    /// Current positions of the local node slots.
    pub x: [[f64; 2]; MAX_NODES],
    pub n_nodes: usize,
    pub slave: SlaveSource,
    pub seg_b: SegSource,
    /// `None` when the point was open at the last converged increment (no friction
    /// history: the first closing increment is frictionless, its end fixes the anchor).
    pub closed: Option<Closed>,
    /// A state held fixed by the solver (a point that chattered within an increment):
    /// `Open` ignores penetration, `Stick`/`Slip` keep the penalty active whatever the sign
    /// of the gap. Stick or slip is still the return mapping's, on the data (see
    /// [`return_map`]): only open/closed is held. `None`: decided by the data.
    pub forced: Option<ContactState>,
    /// Stick held by the solver for the first correction of an attempt (an elastic
    /// predictor, see `solver/active_set.rs`): a closed point returns its trial traction
    /// `T_1 = T_1^tr` and the stick tangent, whatever the cone says. `false`: the return
    /// mapping decides.
    pub stick_held: bool,
    /// `Some(±1)`: the point is in the wedge of a concave vertex of the master at that end of
    /// `B` and is pinned to the vertex (point-to-node form, [`super::vertex`]).
    pub at_vertex: Option<f64>,
    /// The augmented-Lagrangian multipliers of the point (`None`: penalty alone).
    pub multiplier: Option<Multiplier>,
}

/// Multipliers of an augmented-Lagrangian point, held fixed within a Newton solve and
/// updated between solves (see `contact::augmented`):
///
/// - the normal force is `N = ⟨λ_N − ε_N ζ⟩` (the point is closed when it is positive), so
///   the penalty only has to supply the difference to the multiplier;
/// - the tangential trial traction is the scheme's trial from the last converged increment
///   plus `Λ` (a physical traction along the unit tangent, `+ Λ √a11` in covariant form):
///   `λ_T = t^(n) + Λ` is the tangential multiplier, and the penalty part only measures the
///   slip of this increment.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Multiplier {
    /// `λ_N ≥ 0`.
    pub normal: f64,
    /// `Λ`, the correction of this increment to the carried traction.
    pub tangential: f64,
}

/// Result of a point evaluation in scalar type `S`.
#[derive(Debug, Clone, Copy)]
pub struct PointEval<S: Scalar> {
    pub proj: Projection<S>,
    pub normal_force: S,
    pub t1_trial: S,
    pub t1: S,
    pub state: ContactState,
    /// The scheme's trial without the slip of this increment (`ε_T = 0`): the traction
    /// carried from the last converged increment to `B`, covariant, plus the multiplier
    /// correction `Λ √a11` (the tangential multiplier `λ_T`). Only worked out for an
    /// augmented point (zero otherwise).
    pub t1_carried: f64,
}

fn seg_geom<S: Scalar>(src: &SegSource, q: &[V2<S>]) -> SegmentGeom<S> {
    match src {
        SegSource::Face([a, b]) => SegmentGeom::linear(q[*a], q[*b]),
        SegSource::Hermite([p, a, b, n]) => {
            let at = |i: &Option<usize>| i.map(|i| q[i]);
            SegmentGeom::hermite(at(p), q[a.expect("end")], q[b.expect("end")], at(n))
        }
        SegSource::Bezier([p, a, b, n]) => {
            let at = |i: &Option<usize>| i.map(|i| q[i]);
            SegmentGeom::bezier(at(p), q[a.expect("end")], q[b.expect("end")], at(n))
        }
        SegSource::Rigid(p, off) => SegmentGeom::from_piece(p, *off),
    }
}

impl PointProblem {
    /// The largest magnitude of the coordinates that enter this point's gap and slip without
    /// being node slots: a rigid slave's position, a rigid master piece's points (an arc's
    /// centre plus its radius) with their offset, for `B` and the history segment `A`; 0 when
    /// every coordinate is a node. A penalty force is `ε` times a difference of such
    /// coordinates, so its round-off is `≈ ε ε_mach` times this (plus the nodes' own
    /// magnitudes, which the assembler takes from the node positions): a rigid arc of radius
    /// 1 centred 1 above a slave node at the origin cancels `|x − c| − R` at magnitude 2
    /// although `|x| = 0`.
    pub fn fixed_coordinate_scale(&self) -> f64 {
        let piece_scale = |s: &SegSource| match s {
            SegSource::Rigid(Piece::Segment { a, b }, o) => {
                let m = |p: &[f64; 2]| (p[0] + o[0]).hypot(p[1] + o[1]);
                m(a).max(m(b))
            }
            SegSource::Rigid(Piece::Arc { centre, radius, .. }, o) => {
                (centre[0] + o[0]).hypot(centre[1] + o[1]) + radius.abs()
            }
            _ => 0.0,
        };
        let slave = match self.slave {
            SlaveSource::Fixed(p) => p[0].hypot(p[1]),
            SlaveSource::Node(_) => 0.0,
        };
        let history = self.closed.as_ref().map_or(0.0, |c| piece_scale(&c.seg_a));
        slave.max(piece_scale(&self.seg_b)).max(history)
    }

    /// Evaluate gap, projection, trial and returned traction for node positions `q`.
    pub fn evaluate<S: Scalar>(&self, q: &[V2<S>]) -> PointEval<S> {
        let rs = self.slave_position(q);
        let gb = seg_geom(&self.seg_b, q);
        let proj = match self.at_vertex {
            Some(end) => vertex::pinned_projection(&gb, rs, end),
            None => gb.project(rs),
        };
        let zero = S::from(0.0);
        let lambda_n = self.multiplier.map_or(0.0, |m| m.normal);
        let open = match self.forced {
            Some(state) => state == ContactState::Open,
            None => !penetrating(proj.gap.re() - lambda_n / self.law.eps_n, proj.a11.re()),
        };
        let mut eval = PointEval {
            proj,
            normal_force: zero,
            t1_trial: zero,
            t1: zero,
            state: ContactState::Open,
            t1_carried: 0.0,
        };
        if open {
            return eval;
        }
        eval.normal_force = -proj.gap * self.law.eps_n + lambda_n;
        let Some(c) = self.closed else {
            // the first closing increment is frictionless: its end fixes the anchor
            eval.state = if self.law.mu > 0.0 {
                ContactState::Stick
            } else {
                ContactState::Slip
            };
            return eval;
        };
        let input = self.transfer_input(&c, q, &gb, proj);
        let mut t1_trial = self.scheme.trial(&input);
        let mut carried = match self.multiplier {
            Some(_) => self.scheme.trial(&TransferInput { eps_t: 0.0, ..input }).re(),
            None => 0.0,
        };
        if let Some(g0) = c.touch_gap.filter(|g| *g > 0.0) {
            // anchor at the point of first touch (see [`Closed`]); a point held closed by
            // the solver before it penetrates has not touched yet: no traction (the limit
            // of the interpolation as the penetration falls to zero)
            let penetration = -proj.gap;
            let one_minus_s = if penetration.re() > 0.0 {
                penetration / (penetration + g0) // 1 − s = −ζ / (ζ_A − ζ)
            } else {
                zero
            };
            t1_trial *= one_minus_s;
            carried *= one_minus_s.re();
        }
        if let Some(m) = self.multiplier {
            t1_trial += proj.a11.sqrt() * m.tangential;
            carried += proj.a11.re().sqrt() * m.tangential;
        }
        let normal_force = eval.normal_force;
        let (t1, state) = if self.stick_held && self.law.mu > 0.0 {
            // the elastic predictor: also at a point touching without pressure yet (a body
            // resting on it, whose first correction must not slide freely along it)
            (t1_trial, ContactState::Stick)
        } else if self.law.mu > 0.0 && normal_force.re() <= 0.0 {
            // touching without pressure (see [`touching`]): no friction to transmit, and no
            // friction stiffness either (the slip branch's `μ ∂N` would couple the normal
            // and tangential motion of a point that carries nothing)
            (zero, ContactState::Slip)
        } else {
            return_map(&self.law, t1_trial, normal_force, proj.a11)
        };
        PointEval {
            t1_trial,
            t1,
            state,
            t1_carried: carried,
            ..eval
        }
    }

    fn slave_position<S: Scalar>(&self, q: &[V2<S>]) -> V2<S> {
        match self.slave {
            SlaveSource::Node(i) => q[i],
            SlaveSource::Fixed(p) => lift(p),
        }
    }

    /// What the transfer schemes see of a point closed at the last converged increment:
    /// the old contact point on `A` now, the arc length travelled along the (smoothed)
    /// master surface, and, for the spatial scheme, the stored slave position's closest
    /// point on `B`.
    fn transfer_input<S: Scalar>(
        &self,
        c: &Closed,
        q: &[V2<S>],
        gb: &SegmentGeom<S>,
        proj: Projection<S>,
    ) -> TransferInput<S> {
        let ga = seg_geom(&c.seg_a, q);
        let xi_a = S::from(c.stored.xi);
        let (rho_a, rho1_a) = ga.eval(xi_a);
        let one = S::from(1.0);
        let arc_length = match c.path.direction {
            0 => gb.arc_length(xi_a, proj.xi),
            1 => ga.arc_length(xi_a, one) + c.path.between + gb.arc_length(-one, proj.xi),
            _ => -(ga.arc_length(-one, xi_a) + c.path.between + gb.arc_length(proj.xi, one)),
        };
        let stored_slave_xi = match self.scheme {
            TransferKind::Spatial => gb.project(lift(c.stored.slave)).xi,
            _ => S::from(0.0),
        };
        TransferInput {
            eps_t: self.law.eps_t,
            stored: c.stored,
            current: proj,
            old: OldPoint {
                rho: rho_a,
                rho1: rho1_a,
            },
            arc_length,
            crossing: c.path.direction != 0,
            stored_slave_xi,
        }
    }

    /// Plain evaluation (for recording and search).
    pub fn evaluate_f64(&self) -> PointEval<f64> {
        self.evaluate(&self.x[..self.n_nodes])
    }

    /// Local residual `r` (length `2 n_nodes`) and tangent `k` (row-major) for this point;
    /// returns the plain evaluation. Slot `i` owns local DOFs `2i, 2i + 1`.
    pub fn residual_tangent(&self, r: &mut [f64], k: &mut [f64]) -> PointEval<f64> {
        match self.n_nodes {
            0 => self.evaluate_f64(),
            1 => self.rk::<2>(r, k),
            2 => self.rk::<4>(r, k),
            3 => self.rk::<6>(r, k),
            4 => self.rk::<8>(r, k),
            5 => self.rk::<10>(r, k),
            6 => self.rk::<12>(r, k),
            7 => self.rk::<14>(r, k),
            8 => self.rk::<16>(r, k),
            _ => self.rk::<18>(r, k),
        }
    }

    fn rk<const N: usize>(&self, r: &mut [f64], k: &mut [f64]) -> PointEval<f64> {
        // slot positions as dual numbers, on the stack (no allocation per point)
        let q: [V2<Dual2SVec64<N>>; MAX_NODES] = std::array::from_fn(|i| {
            if i < self.n_nodes {
                [
                    Dual2SVec64::<N>::from_re(self.x[i][0]).derivative(2 * i),
                    Dual2SVec64::<N>::from_re(self.x[i][1]).derivative(2 * i + 1),
                ]
            } else {
                [Dual2SVec64::<N>::from_re(0.0), Dual2SVec64::<N>::from_re(0.0)]
            }
        });
        let e = self.evaluate(&q[..self.n_nodes]);
        r[..N].fill(0.0);
        k[..N * N].fill(0.0);
        if e.state != ContactState::Open {
            // r = −N ∇ζ − T_1 ∇ξ, K = −∇ζ ∇Nᵀ − N ∇²ζ − ∇ξ ∇T_1ᵀ − T_1 ∇²ξ; with the penalty
            // N = λ_N − ε_N ζ, so ∇N = −ε_N ∇ζ
            let zeta = e.proj.gap;
            let xi = e.proj.xi;
            let gz = zeta.v1.unwrap_generic(U1, Const::<N>);
            let hz = zeta.v2.unwrap_generic(Const::<N>, Const::<N>);
            let gx = xi.v1.unwrap_generic(U1, Const::<N>);
            let hx = xi.v2.unwrap_generic(Const::<N>, Const::<N>);
            let gt = e.t1.v1.unwrap_generic(U1, Const::<N>);
            let (en, n, t) = (self.law.eps_n, e.normal_force.re, e.t1.re);
            for i in 0..N {
                r[i] = -n * gz[i] - t * gx[i];
                for j in 0..N {
                    k[N * i + j] = en * gz[i] * gz[j] - n * hz[(i, j)] - gx[i] * gt[j] - t * hx[(i, j)];
                }
            }
            if self.at_vertex.is_some() && self.law.mu > 0.0 {
                // ξ is pinned (∇ξ = 0 above): the traction acts along the vertex tangent
                let rs = self.slave_position(&q[..self.n_nodes]);
                vertex::add_tangential(rs, e.proj.rho, e.t1, e.proj.a11, &mut r[..N], &mut k[..N * N]);
            }
        }
        PointEval {
            proj: Projection {
                xi: e.proj.xi.re,
                gap: e.proj.gap.re,
                rho: [e.proj.rho[0].re, e.proj.rho[1].re],
                rho1: [e.proj.rho1[0].re, e.proj.rho1[1].re],
                a11: e.proj.a11.re,
            },
            normal_force: e.normal_force.re,
            t1_trial: e.t1_trial.re,
            t1: e.t1.re,
            state: e.state,
            t1_carried: e.t1_carried,
        }
    }
}

/// Relative size of the gap, against the segment's length `2√a11`, within which a point is
/// *touching*: the round-off of a projection (coordinates of order one carry about 1e-16).
pub const TOUCH_TOLERANCE: f64 = 1e-12;

/// Whether a point with gap `ζ` on a segment of metric `a11` penetrates the master beyond
/// round-off (`ζ < −10⁻¹² · 2√a11`): the point is closed. A point that merely touches is
/// open — it carries no force either way; whether the first correction of an increment
/// should see it closed is decided by the solver from the motion (see
/// `solver::active_set::touching_pushed_in`).
pub fn penetrating(gap: f64, a11: f64) -> bool {
    gap < -TOUCH_TOLERANCE * 2.0 * a11.sqrt()
}

/// Relative size of the gap, against the segment's length, within which a point counts as
/// *resting* on its master for the start of an increment ([`touching`]): the precision to
/// which meshes and outlines are written (coordinates to 7 or 8 digits leave gaps of
/// 1e-8 between a body and the incline it was drawn on).
pub const RESTING_TOLERANCE: f64 = 1e-6;

/// Whether a point with gap `ζ` touches the master, `|ζ| ≤ 10⁻⁶ · 2√a11` (a zero-gap
/// start: two bodies meshed against each other, a sheet resting on a rigid facet, a block
/// drawn on an incline to the digits of its file). Such a point may be resting on the
/// master: the solver asks the first correction of an increment whether it is
/// (`solver::active_set::touching_pushed_in`).
pub fn touching(gap: f64, a11: f64) -> bool {
    gap.abs() <= RESTING_TOLERANCE * 2.0 * a11.sqrt()
}

#[cfg(test)]
#[path = "point_tests.rs"]
mod tests;

#[cfg(test)]
#[path = "point_methods_tests.rs"]
mod methods_tests;
