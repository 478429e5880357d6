//! What the contact system reports about itself, in its own types: a snapshot of every slave
//! point at the end of an increment and the crossing events of the increment. `record/`
//! converts them into serialisable records; contact never depends on `record/`.

use super::law::ContactState;
use super::point::{Multiplier, Path, PointEval};
use super::system::{local_problem, stored, Config, PointHistory, PointNow};
use crate::model::{ContactPair, Enforcement, Slave};

/// State of one contact slave point at the current iterate, compared with the last
/// converged increment.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PointSnapshot {
    /// Index of the contact pair and of the slave within it.
    pub pair: usize,
    pub slave: usize,
    /// The slave itself (a node or a rigid point).
    pub slave_id: Slave,
    /// Master segment of the current projection (None: no segment within reach).
    pub segment: Option<usize>,
    /// Segment at the previous converged increment.
    pub previous_segment: Option<usize>,
    pub xi: f64,
    /// Centre of the elastic region `ξ_sl = ξ + T_1/(ε_T a11)` on `segment`.
    pub xi_anchor: f64,
    /// Signed gap `ζ` (negative = penetration).
    pub gap: f64,
    pub normal_force: f64,
    /// Trial and returned tangential traction along the unit tangent.
    pub trial_traction: f64,
    pub traction: f64,
    pub state: ContactState,
    /// The point is closed on another segment than at the last converged increment.
    pub crossing: bool,
    /// Slave position and contact point `ρ(ξ)`.
    pub position: [f64; 2],
    pub contact_point: [f64; 2],
    /// Unit normal and unit tangent of the master at the contact point.
    pub normal: [f64; 2],
    pub tangent: [f64; 2],
    /// The contact force the slave receives, as assembled (x, y): `N n + T τ` on a
    /// straight master, with the curvature factor of `∇ξ` on a curved one; zero for an
    /// open point.
    pub force: [f64; 2],
    /// Augmented-Lagrangian multiplier estimates the last solve of the increment used: the
    /// normal force `λ_N` and the tangential traction `λ_T` along the unit tangent (NaN in a
    /// penalty pair, and `λ_T` NaN for a point without friction history).
    pub multiplier: [f64; 2],
}

impl PointSnapshot {
    pub(super) fn new(
        cfg: &Config,
        (pair_index, slave_index): (usize, usize),
        slave: Slave,
        pair: &ContactPair,
        now: &PointNow,
        hist: &PointHistory,
        multiplier: Multiplier,
    ) -> Self {
        let pos = match (slave, now.eval) {
            (Slave::Node(n), _) => {
                let x = cfg.model.nodes[n];
                [x[0] + cfg.u[2 * n], x[1] + cfg.u[2 * n + 1]]
            }
            (_, Some(e)) => {
                let n = e.proj.normal();
                [e.proj.rho[0] + e.proj.gap * n[0], e.proj.rho[1] + e.proj.gap * n[1]]
            }
            _ => [f64::NAN; 2],
        };
        let mut r = PointSnapshot {
            pair: pair_index,
            slave: slave_index,
            slave_id: slave,
            segment: now.segment,
            previous_segment: hist.segment,
            xi: f64::NAN,
            xi_anchor: f64::NAN,
            gap: f64::NAN,
            normal_force: 0.0,
            trial_traction: 0.0,
            traction: 0.0,
            state: ContactState::Open,
            crossing: false,
            position: pos,
            contact_point: [f64::NAN; 2],
            normal: [f64::NAN; 2],
            tangent: [f64::NAN; 2],
            multiplier: [f64::NAN; 2],
            force: now.force,
        };
        let augmented = matches!(pair.enforcement, Enforcement::Augmented { .. });
        if augmented {
            r.multiplier[0] = multiplier.normal;
        }
        if let Some(e) = now.eval {
            let sq = e.proj.a11.sqrt();
            r.xi = e.proj.xi;
            r.gap = e.proj.gap;
            r.normal_force = e.normal_force;
            r.trial_traction = e.t1_trial / sq;
            r.traction = e.t1 / sq;
            r.state = e.state;
            let eps_t = pair.law_of(slave_index).eps_t;
            r.xi_anchor = if e.state == ContactState::Open || eps_t == 0.0 {
                f64::NAN
            } else {
                e.proj.xi + e.t1 / (eps_t * e.proj.a11)
            };
            r.crossing = e.state != ContactState::Open && hist.closed && hist.segment != now.segment;
            r.contact_point = e.proj.rho;
            r.normal = e.proj.normal();
            r.tangent = [e.proj.rho1[0] / sq, e.proj.rho1[1] / sq];
            if augmented && e.state != ContactState::Open && hist.closed {
                r.multiplier[1] = e.t1_carried / sq;
            }
        }
        r
    }
}

/// A contact point moved from segment `A` to `B` in a converged increment (seed §3).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CrossingEvent {
    pub pair: usize,
    pub slave: usize,
    pub from_segment: usize,
    pub to_segment: usize,
    /// `ξ_A` (stored) and `ξ_B` (current).
    pub xi_from: f64,
    pub xi_to: f64,
    /// Projection of the current slave position on `A`'s extension (`|ξ| > 1`).
    pub xi_from_extended: f64,
    /// `Δρ = ρ_B(ξ_B) − ρ_A(ξ_A)` in the current configuration (seed eq. 2).
    pub delta_rho: [f64; 2],
    /// +1 forward along the chain, −1 backward.
    pub direction: i8,
    /// Signed angle between the unit tangents of `A` and `B` (current configuration).
    pub kink_angle: f64,
    /// Trial traction on `A` extended (same-segment formula), along `A`'s unit tangent.
    pub trial_before: f64,
    /// Trial traction on `B` after transfer by the pair's scheme, along `B`'s unit tangent.
    pub trial_after: f64,
    /// Returned traction on `B`.
    pub returned_after: f64,
}

/// Crossing event: the trial traction just before transfer (the old segment `A` extended,
/// same-segment formula) and just after (the pair's scheme on `B`), in the converged
/// configuration, as physical tractions along each segment's unit tangent.
#[allow(clippy::too_many_arguments)]
pub(super) fn crossing_event(
    cfg: &Config,
    ip: usize,
    is: usize,
    a: usize,
    b: usize,
    old: &PointHistory,
    e: &PointEval<f64>,
    path: Path,
    multiplier: Option<Multiplier>,
) -> CrossingEvent {
    let pair = &cfg.model.contacts[ip];
    let ga = cfg.segment(pair, a);
    let (rho_a, rho1_a) = ga.eval(old.xi);
    let rho1_b = e.proj.rho1;
    let kink_angle =
        (rho1_a[0] * rho1_b[1] - rho1_a[1] * rho1_b[0]).atan2(rho1_a[0] * rho1_b[0] + rho1_a[1] * rho1_b[1]);
    // A extended: same-segment trial on A's line at the current slave position
    let same = Path {
        direction: 0,
        between: 0.0,
    };
    let (mut ext, _) = local_problem(cfg, pair, is, a, Some((stored(old), a, same, None)));
    ext.multiplier = multiplier;
    let ext = ext.evaluate_f64();
    CrossingEvent {
        pair: ip,
        slave: is,
        from_segment: a,
        to_segment: b,
        xi_from: old.xi,
        xi_to: e.proj.xi,
        xi_from_extended: ext.proj.xi,
        delta_rho: [e.proj.rho[0] - rho_a[0], e.proj.rho[1] - rho_a[1]],
        direction: path.direction,
        kink_angle,
        trial_before: ext.t1_trial / ext.proj.a11.sqrt(),
        trial_after: e.t1_trial / e.proj.a11.sqrt(),
        returned_after: e.t1 / e.proj.a11.sqrt(),
    }
}
