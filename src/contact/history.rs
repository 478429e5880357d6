//! What each slave point carries: its history at the last converged increment (segment,
//! convective coordinate, covariant traction, the spatial and augmented data), its
//! evaluation at the current iterate, and its contact decision.

use super::law::ContactState;
use super::point::{Path, PointEval};

/// History of one slave point at the last converged increment.
#[derive(Debug, Clone, Copy)]
pub struct PointHistory {
    /// Segment the point is tracked on (kept while open, for the neighbour walk).
    pub segment: Option<usize>,
    /// Closed (in contact) at the last converged increment.
    pub closed: bool,
    pub xi: f64,
    /// Covariant traction `T_1` on `segment`.
    pub t1: f64,
    /// Normal force `N` (zero when open).
    pub normal: f64,
    pub a11: f64,
    /// Gap at the last converged increment of a point that was paired but open (NaN
    /// otherwise): its first touch is interpolated from it.
    pub gap: f64,
    pub crossings: u32,
    /// Closed and sticking at the last converged increment.
    pub stuck: bool,
    /// Paired (within reach of its master, open or closed) at the last converged increment,
    /// or in the initial configuration before the first.
    pub within_reach: bool,
    /// The slave's position and the master's unit tangent at the contact point at the last
    /// converged increment (the spatial scheme's history).
    pub slave: [f64; 2],
    pub tangent: [f64; 2],
}

impl PointHistory {
    /// Keep the spatial history of a point paired at the converged increment.
    pub(super) fn store_spatial(&mut self, slave: [f64; 2], e: &PointEval<f64>) {
        self.slave = slave;
        let sq = e.proj.a11.sqrt();
        self.tangent = [e.proj.rho1[0] / sq, e.proj.rho1[1] / sq];
    }
}

impl Default for PointHistory {
    fn default() -> Self {
        PointHistory {
            segment: None,
            closed: false,
            xi: f64::NAN,
            t1: 0.0,
            normal: 0.0,
            a11: f64::NAN,
            gap: f64::NAN,
            crossings: 0,
            stuck: false,
            within_reach: false,
            slave: [f64::NAN; 2],
            tangent: [f64::NAN; 2],
        }
    }
}

/// Evaluation of one slave point at the current iterate.
#[derive(Debug, Clone, Copy)]
pub struct PointNow {
    pub segment: Option<usize>,
    pub eval: Option<PointEval<f64>>,
    pub path: Path,
    /// The contact force the slave receives, as assembled ([`slave_force`]).
    pub force: [f64; 2],
}

/// The contact force a point's slave receives, from its assembled local residual `r_eq`
/// (internal-force sign: the force on a node is `−r`): `−r` of the slave node's slot
/// (slot 0), or, for a rigid slave, the sum of `r` over the master's nodes (the point's
/// forces sum to zero, its residual being invariant under a translation of its nodes). It
/// is exact for every master geometry, the curvature factor of a curved master included.
pub fn slave_force(slave_is_node: bool, r_eq: &[f64]) -> [f64; 2] {
    match slave_is_node {
        true if r_eq.len() >= 2 => [-r_eq[0], -r_eq[1]],
        true => [0.0; 2],
        false => {
            let sum = |c: usize| r_eq.iter().skip(c).step_by(2).sum();
            [sum(0), sum(1)]
        }
    }
}

impl Default for PointNow {
    fn default() -> Self {
        PointNow {
            segment: None,
            eval: None,
            path: Path {
                direction: 0,
                between: 0.0,
            },
            force: [0.0; 2],
        }
    }
}

/// A point's contact decision at one iterate: its state and the segment it is tracked on.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Decision {
    pub state: ContactState,
    pub segment: Option<usize>,
}
