//! The record of one 3D (node-to-surface) contact point at a converged increment: its facet
//! and convective coordinates `(ξ¹, ξ²)`, gap, normal force, trial and returned covariant
//! tractions `T_α`, state, crossing flag, and the slave's position, contact point, normal
//! and the force it receives as assembled.

use crate::contact::law::ContactState;
use crate::contact3d::system::SurfaceSnapshot;
use crate::model::{Model, Solid};
use serde::{Deserialize, Serialize};

/// State of one 3D contact slave node at the end of an increment (NaN where a field has no
/// value: an unpaired point's `xi`, `gap`, …).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SurfacePointRecord {
    pub pair: usize,
    pub pair_name: String,
    /// Index of the slave within the pair, and its node.
    pub slave: usize,
    pub node: usize,
    /// The master facet of the current projection (index into the pair's facets; 0 for a
    /// rigid surface; `None`: nothing within reach), and at the last converged increment.
    pub facet: Option<usize>,
    pub previous_facet: Option<usize>,
    /// Convective coordinates `(ξ¹, ξ²)` of the contact point on `facet`.
    pub xi: [f64; 2],
    /// Signed gap `ζ` (negative: penetration).
    pub gap: f64,
    pub normal_force: f64,
    /// Covariant trial and returned tangential tractions `T_α` on `facet`.
    pub trial_traction: [f64; 2],
    pub traction: [f64; 2],
    /// `open`, `stick` or `slip` (a closed point of a frictionless pair is `slip`).
    pub state: ContactState,
    /// Closed now and at the last converged increment, on another facet.
    pub crossing: bool,
    /// The friction history could not be carried onto `facet` (see
    /// `contact3d::system::SurfaceNow::history_lost`): the run warns at the first.
    pub history_lost: bool,
    pub position: [f64; 3],
    pub contact_point: [f64; 3],
    /// Unit outward normal of the master at the contact point.
    pub normal: [f64; 3],
    /// The contact force the slave node receives, as assembled (the master its negative).
    pub force: [f64; 3],
}

impl SurfacePointRecord {
    /// The record of a snapshot at displacements `u`.
    pub fn of(model: &Model<Solid>, u: &[f64], s: &SurfaceSnapshot) -> Self {
        let x = model.nodes[s.node];
        let position = std::array::from_fn(|c| x[c] + u[3 * s.node + c]);
        let nan3 = [f64::NAN; 3];
        let e = s.eval;
        SurfacePointRecord {
            pair: s.pair,
            pair_name: model.surface_contacts[s.pair].name.clone(),
            slave: s.slave,
            node: s.node,
            facet: s.facet,
            previous_facet: s.previous_facet,
            xi: e.map_or([f64::NAN; 2], |e| e.projection.point.xi),
            gap: e.map_or(f64::NAN, |e| e.projection.gap),
            normal_force: e.map_or(0.0, |e| e.normal_force),
            trial_traction: e.map_or([0.0; 2], |e| e.trial),
            traction: e.map_or([0.0; 2], |e| e.traction),
            state: e.map_or(ContactState::Open, |e| e.state),
            crossing: s.crossing,
            history_lost: s.history_lost,
            position,
            contact_point: e.map_or(nan3, |e| e.projection.point.rho),
            normal: e.map_or(nan3, |e| e.projection.point.normal),
            force: s.force,
        }
    }
}
