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

use super::decision::{self, Kink, Rule};
use super::geometry::{Projection, SegmentGeom};
use super::law::{ContactLaw, ContactState};
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
    /// Who decides the point's state: the penalty function alone, or the augmented force
    /// unknowns of Newton's iterate ([`super::decision`]).
    pub rule: Rule,
    /// Which side of the normal kink a point touching without force takes
    /// ([`decision::Kink`]).
    pub kink: Kink,
    /// The state is decided by the force unknowns alone ([`Rule::deciding_by_forces`]: the
    /// first iterate of an attempt); the complementarity residuals keep the rule's weights.
    pub warm: bool,
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
    /// The complementarity residuals `[C_N, C_T]` of the rule at this state (zero under
    /// [`Rule::Penalty`]; see [`decision::complementarity`]).
    pub complementarity: [f64; 2],
}

/// What Newton's update of the force unknowns needs of a closed point: the penalty forces
/// in the decided state and their gradients with respect to the local unknowns (slot `i`
/// owns `2i, 2i + 1`), and the metric that turns `T_1` into the physical traction.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Linearization {
    pub normal: f64,
    pub d_normal: [f64; 2 * MAX_NODES],
    pub t1: f64,
    pub d_t1: [f64; 2 * MAX_NODES],
    pub a11: f64,
}

impl Default for Linearization {
    fn default() -> Self {
        Linearization {
            normal: 0.0,
            d_normal: [0.0; 2 * MAX_NODES],
            t1: 0.0,
            d_t1: [0.0; 2 * MAX_NODES],
            a11: 1.0,
        }
    }
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

    /// Evaluate gap, projection, trial and returned traction for node positions `q`, the
    /// state decided by [`Self::rule`].
    pub fn evaluate<S: Scalar>(&self, q: &[V2<S>]) -> PointEval<S> {
        let rs = self.slave_position(q);
        let gb = seg_geom(&self.seg_b, q);
        let proj = match self.at_vertex {
            Some(end) => vertex::pinned_projection(&gb, rs, end),
            None => gb.project(rs),
        };
        let lambda_n = self.multiplier.map_or(0.0, |m| m.normal);
        let n_eps = -proj.gap * self.law.eps_n + lambda_n;
        let sq = proj.a11.re().sqrt();
        let touch = self.law.eps_n * TOUCH_TOLERANCE * 2.0 * sq;
        let resting = self.law.eps_n * RESTING_TOLERANCE * 2.0 * sq;
        let deciding = if self.warm {
            self.rule.deciding_by_forces()
        } else {
            self.rule
        };
        let (closed, n_hat) = decision::normal(&deciding, n_eps.re(), (touch, resting), self.kink);
        // a point taken closed at the kink (resting without force) sticks: the tangential kink
        // `|t̂| = μ N̂ = 0` taken on the same side
        let at_kink = self.kink == Kink::Resting && n_hat <= resting;
        let mut eval = self.open_eval(proj);
        if !closed {
            return eval;
        }
        let frictional = self.law.mu > 0.0;
        let Some(c) = self.closed.filter(|_| frictional) else {
            // frictionless, or the first closing increment (frictionless: its end fixes the
            // anchor)
            let state = if frictional {
                ContactState::Stick
            } else {
                ContactState::Slip
            };
            eval.normal_force = n_eps;
            eval.state = state;
            eval.complementarity =
                decision::complementarity(&self.rule, state, false, (n_eps.re(), n_hat), 0.0, 0.0, 0.0);
            return eval;
        };
        // a first touch's fraction `s` (see [`Closed`]) from the normal force: under the
        // augmented rule from the augmented force `N̂`, held within the linearisation and
        // updated at each iterate (at a solution `N̂ = N_ε`). Its variation is left out: with
        // a stiff penalty it is the penalty's amplification of a gap still settling, and the
        // first touch's trial, `ε_T (1 − s)` times the slide since the increment began,
        // would swing between its extremes from one iterate to the next
        let touch_force = match self.rule {
            Rule::Penalty => n_eps,
            Rule::AlartCurnier { .. } => S::from(n_hat),
        };
        let (t1_trial, carried) = self.trial(&c, q, &gb, proj, touch_force);
        let mu = self.law.mu;
        let rule = self.rule;
        let slip = |rule: &Rule, n_hat: f64| decision::tangential(rule, mu, t1_trial.re() / sq, n_hat, n_eps.re());
        eval.t1_trial = t1_trial;
        eval.t1_carried = carried;
        let sign = slip(&deciding, n_hat).filter(|_| !at_kink);
        let (t1, state) = match sign {
            None => (t1_trial, ContactState::Stick),
            Some(s) => (n_eps * proj.a11.sqrt() * (mu * s), ContactState::Slip),
        };
        let c_t = (n_eps.re(), n_hat);
        eval.complementarity =
            decision::complementarity(&rule, state, true, c_t, t1_trial.re() / sq, sign.unwrap_or(0.0), mu);
        PointEval {
            normal_force: n_eps,
            t1,
            state,
            ..eval
        }
    }

    /// The evaluation of an open point at projection `proj`: no force, and the open state's
    /// complementarity residuals under the point's rule.
    fn open_eval<S: Scalar>(&self, proj: Projection<S>) -> PointEval<S> {
        let zero = S::from(0.0);
        PointEval {
            proj,
            normal_force: zero,
            t1_trial: zero,
            t1: zero,
            state: ContactState::Open,
            t1_carried: 0.0,
            complementarity: decision::complementarity(
                &self.rule,
                ContactState::Open,
                false,
                (0.0, 0.0),
                0.0,
                0.0,
                0.0,
            ),
        }
    }

    /// The trial traction `T_1^tr` of a point closed at the last converged increment (or
    /// touching then), and the traction carried into this increment (augmented points).
    fn trial<S: Scalar>(
        &self,
        c: &Closed,
        q: &[V2<S>],
        gb: &SegmentGeom<S>,
        proj: Projection<S>,
        normal: S,
    ) -> (S, f64) {
        let input = self.transfer_input(c, q, gb, proj);
        let mut t1_trial = self.scheme.trial(&input);
        let mut carried = match self.multiplier {
            Some(_) => self.scheme.trial(&TransferInput { eps_t: 0.0, ..input }).re(),
            None => 0.0,
        };
        if let Some(g0) = c.touch_gap.filter(|g| *g > 0.0) {
            // anchor at the point of first touch (see [`Closed`]), with the penetration the
            // normal force stands for, `(N − λ_N)/ε_N = −ζ`. Under the penalty rule a closed
            // point penetrates; the augmented rule may take a point closed a little before it
            // does (its force unknown says it carries load), and there the interpolation goes
            // on smoothly through zero penetration (down to −ζ_A/2, then held): the trial is
            // then a smooth function of the gap for Newton, and at a solution the point
            // penetrates as under the penalty rule
            let lambda_n = self.multiplier.map_or(0.0, |m| m.normal);
            let penetration = (normal - lambda_n) / self.law.eps_n;
            let one_minus_s = match (self.rule, penetration.re()) {
                (_, p) if p > 0.0 => penetration / (penetration + g0), // 1 − s = −ζ / (ζ_A − ζ)
                (Rule::AlartCurnier { .. }, p) if p > -0.5 * g0 => penetration / (penetration + g0),
                (Rule::AlartCurnier { .. }, _) => S::from(-1.0),
                (Rule::Penalty, _) => S::from(0.0),
            };
            t1_trial *= one_minus_s;
            carried *= one_minus_s.re();
        }
        if let Some(m) = self.multiplier {
            t1_trial += proj.a11.sqrt() * m.tangential;
            carried += proj.a11.re().sqrt() * m.tangential;
        }
        (t1_trial, carried)
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
        let nd = 2 * self.n_nodes;
        let mut r_eq = [0.0; 2 * MAX_NODES];
        let mut lin = Linearization::default();
        self.local(r, &mut r_eq[..nd], k, &mut lin)
    }

    /// Everything Newton needs of this point: the residual `r` of the penalty forces in
    /// the decided state (the condensed system's right-hand side), the residual `r_eq` of
    /// the force unknowns (`−N ∇ζ − T_1 ∇ξ` with the unknowns of [`Rule::AlartCurnier`]; equal
    /// to `r` under [`Rule::Penalty`]), the condensed tangent `k` and the linearisation of
    /// the penalty forces (of an open point: of the normal force it would have closed).
    /// Returns the plain evaluation.
    ///
    /// `k = −∇ζ ∇Nᵀ − N̄ ∇²ζ − ∇ξ ∇T_1ᵀ − T̄_1 ∇²ξ`: the gradients are the penalty forces'
    /// in the decided state (`∇N = −ε_N ∇ζ`), the Hessian terms weigh the geometry by the
    /// force unknowns `N̄`, `T̄_1` (the penalty's own under [`Rule::Penalty`]): the Newton
    /// matrix of the mixed system with the force unknowns condensed (see
    /// [`super::decision`]).
    pub fn local(&self, r: &mut [f64], r_eq: &mut [f64], k: &mut [f64], lin: &mut Linearization) -> PointEval<f64> {
        match self.n_nodes {
            0 => self.evaluate_f64(),
            1 => self.rk::<2>(r, r_eq, k, lin),
            2 => self.rk::<4>(r, r_eq, k, lin),
            3 => self.rk::<6>(r, r_eq, k, lin),
            4 => self.rk::<8>(r, r_eq, k, lin),
            5 => self.rk::<10>(r, r_eq, k, lin),
            6 => self.rk::<12>(r, r_eq, k, lin),
            7 => self.rk::<14>(r, r_eq, k, lin),
            8 => self.rk::<16>(r, r_eq, k, lin),
            _ => self.rk::<18>(r, r_eq, k, lin),
        }
    }

    fn rk<const N: usize>(
        &self,
        r: &mut [f64],
        r_eq: &mut [f64],
        k: &mut [f64],
        lin: &mut Linearization,
    ) -> PointEval<f64> {
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
        r_eq[..N].fill(0.0);
        k[..N * N].fill(0.0);
        *lin = Linearization {
            a11: e.proj.a11.re,
            ..Linearization::default()
        };
        let zeta = e.proj.gap;
        let xi = e.proj.xi;
        let gz = zeta.v1.unwrap_generic(U1, Const::<N>);
        let gx = xi.v1.unwrap_generic(U1, Const::<N>);
        // the force unknowns (the penalty's own forces under the penalty rule)
        let (n_bar, t_bar) = match self.rule {
            Rule::AlartCurnier { forces, .. } => (forces.normal, forces.tangential * e.proj.a11.re.sqrt()),
            Rule::Penalty => (e.normal_force.re, e.t1.re),
        };
        if e.state == ContactState::Open {
            // the force unknowns of an open point go to zero in one correction (`ΔN = −N`):
            // no force in the condensed right-hand side, and their geometric terms are left
            // out of the Newton matrix (with a tensile unknown on a curved master they
            // stiffen a flimsy body against the correction that opens it; measured on the
            // capstan belt: 29 cut-backs with them, 5 without)
            for i in 0..N {
                r_eq[i] = -n_bar * gz[i] - t_bar * gx[i];
            }
            // the penalty's normal force had the point been closed, `N_ε = λ_N − ε_N ζ` and
            // `∇N_ε = −ε_N ∇ζ`: whether a correction drives an open point in
            let lambda_n = self.multiplier.map_or(0.0, |m| m.normal);
            lin.normal = lambda_n - self.law.eps_n * zeta.re;
            for i in 0..N {
                lin.d_normal[i] = -self.law.eps_n * gz[i];
            }
        } else {
            // r = −N ∇ζ − T_1 ∇ξ with the penalty forces; K as in the docs above
            let hz = zeta.v2.unwrap_generic(Const::<N>, Const::<N>);
            let hx = xi.v2.unwrap_generic(Const::<N>, Const::<N>);
            let gn = e.normal_force.v1.unwrap_generic(U1, Const::<N>);
            let gt = e.t1.v1.unwrap_generic(U1, Const::<N>);
            let (n, t) = (e.normal_force.re, e.t1.re);
            for i in 0..N {
                r[i] = -n * gz[i] - t * gx[i];
                r_eq[i] = -n_bar * gz[i] - t_bar * gx[i];
                lin.d_normal[i] = gn[i];
                lin.d_t1[i] = gt[i];
                for j in 0..N {
                    k[N * i + j] = -gz[i] * gn[j] - n_bar * hz[(i, j)] - gx[i] * gt[j] - t_bar * hx[(i, j)];
                }
            }
            (lin.normal, lin.t1) = (n, t);
            if self.at_vertex.is_some() && self.law.mu > 0.0 {
                // ξ is pinned (∇ξ = 0 above): the traction acts along the vertex tangent
                let rs = self.slave_position(&q[..self.n_nodes]);
                vertex::add_tangential(rs, e.proj.rho, e.t1, e.proj.a11, &mut r[..N], &mut k[..N * N]);
                if matches!(self.rule, Rule::Penalty) {
                    r_eq[..N].copy_from_slice(&r[..N]);
                }
            }
        }
        real_part(&e)
    }
}

/// The values of an evaluation in dual numbers, without their derivatives.
fn real_part<const N: usize>(e: &PointEval<Dual2SVec64<N>>) -> PointEval<f64> {
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
        complementarity: e.complementarity,
    }
}

/// Relative size of the gap, against the segment's length `2√a11`, within which a point is
/// *touching*: the round-off of a projection (coordinates of order one carry about 1e-16).
pub const TOUCH_TOLERANCE: f64 = 1e-12;

/// Whether a point with gap `ζ` on a segment of metric `a11` penetrates the master beyond
/// round-off (`ζ < −10⁻¹² · 2√a11`): the point is closed. A point that merely touches is
/// open — it carries no force either way; which side of the normal kink it takes in the
/// Newton matrix is the contact Newton's choice ([`decision::Kink`]: open, or resting
/// where the open tangent is singular).
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
/// master: where the tangent with every such point open is singular (a body held only by
/// what it rests on), the solver takes them resting ([`decision::Kink::Resting`]).
pub fn touching(gap: f64, a11: f64) -> bool {
    gap.abs() <= RESTING_TOLERANCE * 2.0 * a11.sqrt()
}

#[cfg(test)]
#[path = "point_tests.rs"]
mod tests;

#[cfg(test)]
#[path = "point_methods_tests.rs"]
mod methods_tests;
