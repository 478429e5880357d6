//! The records of 3D (node-to-surface) contact: one [`SurfacePointRecord`] per slave node
//! at a converged increment (its facet and convective coordinates `(ξ¹, ξ²)`, gap, normal
//! force, trial and returned covariant tractions `T_α`, state, the history carried across
//! a facet edge), and the pairs as the `/model` message describes them
//! ([`SurfacePairInfo`]).

use super::real::{Real, Real2, Real3, Reals};
use crate::contact::law::ContactState;
use crate::contact3d::system::{Carried, SurfaceSnapshot};
use crate::contact3d::transfer::scheme_name;
use crate::model::{Model, RigidSurfaceShape, Solid, SurfaceMaster, SurfacePair};
use schemars::JsonSchema;
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
    #[serde(with = "Real2")]
    pub xi: [f64; 2],
    /// Signed gap `ζ` (negative: penetration).
    #[serde(with = "Real")]
    pub gap: f64,
    #[serde(with = "Real")]
    pub normal_force: f64,
    /// Covariant trial and returned tangential tractions `T_α` on `facet`.
    #[serde(with = "Real2")]
    pub trial_traction: [f64; 2],
    #[serde(with = "Real2")]
    pub traction: [f64; 2],
    /// `open`, `stick` or `slip` (a closed point of a frictionless pair is `slip`).
    pub state: ContactState,
    /// Closed now and at the last converged increment, on another facet.
    pub crossing: bool,
    /// The friction history could not be carried onto `facet` (see
    /// `contact3d::system::SurfaceNow::history_lost`): the run warns at the first.
    pub history_lost: bool,
    /// The friction history carried onto `facet` from `previous_facet` in this increment.
    pub carried: Option<CarriedRecord>,
    #[serde(with = "Real3")]
    pub position: [f64; 3],
    #[serde(with = "Real3")]
    pub contact_point: [f64; 3],
    /// Unit outward normal of the master at the contact point.
    #[serde(with = "Real3")]
    pub normal: [f64; 3],
    /// The contact force the slave node receives, as assembled (the master its negative).
    #[serde(with = "Real3")]
    pub force: [f64; 3],
}

/// A friction history carried across a facet edge (seed eqs. 2–4 on surfaces): the facet
/// the point left, its last converged contact point `ξ_A` and covariant traction `T_α` there,
/// and both as the pair's transfer scheme made them on the new facet (`ξ_B`, `T_α` on B).
/// The returned traction after the return map is the point's `traction`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct CarriedRecord {
    pub from_facet: usize,
    #[serde(with = "Real2")]
    pub xi_from: [f64; 2],
    #[serde(with = "Real2")]
    pub traction_from: [f64; 2],
    #[serde(with = "Real2")]
    pub xi_to: [f64; 2],
    #[serde(with = "Real2")]
    pub traction_to: [f64; 2],
}

impl CarriedRecord {
    pub fn of(c: &Carried) -> Self {
        CarriedRecord {
            from_facet: c.from_facet,
            xi_from: c.from.xi,
            traction_from: c.from.traction,
            xi_to: c.to.xi,
            traction_to: c.to.traction,
        }
    }
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
            carried: s.carried.as_ref().map(CarriedRecord::of),
            position,
            contact_point: e.map_or(nan3, |e| e.projection.point.rho),
            normal: e.map_or(nan3, |e| e.projection.point.normal),
            force: s.force,
        }
    }
}

impl SurfacePointRecord {
    /// The record of slave `slave` (node `node`) of pair `pair` when it has stayed out of
    /// reach since the last converged increment: open, no facet now or before, nothing
    /// carried, no force, NaN where a field needs a projection; `position` is the node's.
    /// Recordings leave such records out and readers put them back with this.
    pub fn out_of_reach((pair, pair_name): (usize, &str), (slave, node): (usize, usize), position: [f64; 3]) -> Self {
        SurfacePointRecord {
            pair,
            pair_name: pair_name.to_string(),
            slave,
            node,
            facet: None,
            previous_facet: None,
            xi: [f64::NAN; 2],
            gap: f64::NAN,
            normal_force: 0.0,
            trial_traction: [0.0; 2],
            traction: [0.0; 2],
            state: ContactState::Open,
            crossing: false,
            history_lost: false,
            carried: None,
            position,
            contact_point: [f64::NAN; 3],
            normal: [f64::NAN; 3],
            force: [0.0; 3],
        }
    }

    /// Whether this record is, bit for bit, [`SurfacePointRecord::out_of_reach`] at its
    /// position (so that a reader puts back exactly what was left out).
    pub fn is_bare_out_of_reach(&self) -> bool {
        let bare = Self::out_of_reach((self.pair, ""), (self.slave, self.node), self.position);
        let reals = |r: &Self| -> [u64; 17] {
            let [x1, x2] = r.xi;
            let [a1, a2] = r.trial_traction;
            let [b1, b2] = r.traction;
            let [c1, c2, c3] = r.contact_point;
            let [n1, n2, n3] = r.normal;
            let [f1, f2, f3] = r.force;
            let v = [
                r.gap,
                r.normal_force,
                x1,
                x2,
                a1,
                a2,
                b1,
                b2,
                c1,
                c2,
                c3,
                n1,
                n2,
                n3,
                f1,
                f2,
                f3,
            ];
            v.map(f64::to_bits)
        };
        self.facet.is_none()
            && self.previous_facet.is_none()
            && self.state == ContactState::Open
            && !self.crossing
            && !self.history_lost
            && self.carried.is_none()
            && reals(self) == reals(&bare)
    }
}

/// A 3D contact pair in `/model`: its slave nodes with their tributary areas, its master
/// (a body's facets or a rigid surface) and its law.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct SurfacePairInfo {
    pub name: String,
    /// Slave nodes, in slave order (`slave` of `/surface_contact` indexes this list).
    pub slave_nodes: Vec<usize>,
    /// Tributary area of each slave (the penalties are per unit area).
    #[serde(with = "Reals")]
    pub areas: Vec<f64>,
    /// `body NAME` or `rigid NAME`.
    pub master: String,
    /// The master facets of a deformable face: four node ids each, counter-clockwise seen
    /// from outside (`facet` of `/surface_contact` indexes this list; empty for a rigid
    /// master).
    pub master_facets: Vec<[usize; 4]>,
    /// The rigid master's shape in its reference position (absent for facets); its
    /// displacement at each increment is `/surface_contact` `master_offset`.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub rigid: Option<RigidShapeInfo>,
    pub transfer: String,
    /// Penalties per unit area and the friction coefficient.
    #[serde(with = "Real")]
    pub eps_n: f64,
    #[serde(with = "Real")]
    pub eps_t: f64,
    #[serde(with = "Real")]
    pub mu: f64,
}

/// A rigid analytic surface in its reference position.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "lowercase")]
pub enum RigidShapeInfo {
    /// The plane through `point` with unit outward `normal`.
    Plane {
        #[serde(with = "Real3")]
        #[schemars(with = "Real3")]
        point: [f64; 3],
        #[serde(with = "Real3")]
        #[schemars(with = "Real3")]
        normal: [f64; 3],
    },
    Sphere {
        #[serde(with = "Real3")]
        #[schemars(with = "Real3")]
        centre: [f64; 3],
        #[serde(with = "Real")]
        #[schemars(with = "Real")]
        radius: f64,
    },
    /// The infinite circular cylinder through `point` along the unit `axis`.
    Cylinder {
        #[serde(with = "Real3")]
        #[schemars(with = "Real3")]
        point: [f64; 3],
        #[serde(with = "Real3")]
        #[schemars(with = "Real3")]
        axis: [f64; 3],
        #[serde(with = "Real")]
        #[schemars(with = "Real")]
        radius: f64,
    },
}

impl SurfacePairInfo {
    /// The description of `pair` of `model`.
    pub fn of(model: &Model<Solid>, pair: &SurfacePair) -> Self {
        let (master, master_facets, rigid) = match &pair.master {
            SurfaceMaster::Facets { body, facets } => {
                (format!("body {}", model.bodies[*body].name), facets.clone(), None)
            }
            SurfaceMaster::Rigid(r) => {
                let shape = match r.shape {
                    RigidSurfaceShape::Plane { point, normal } => RigidShapeInfo::Plane { point, normal },
                    RigidSurfaceShape::Sphere { centre, radius } => RigidShapeInfo::Sphere { centre, radius },
                    RigidSurfaceShape::Cylinder { point, axis, radius } => {
                        RigidShapeInfo::Cylinder { point, axis, radius }
                    }
                };
                (format!("rigid {}", r.name), Vec::new(), Some(shape))
            }
        };
        SurfacePairInfo {
            name: pair.name.clone(),
            slave_nodes: pair.slaves.clone(),
            areas: pair.areas.clone(),
            master,
            master_facets,
            rigid,
            transfer: scheme_name(pair.transfer).into(),
            eps_n: pair.law.eps_n,
            eps_t: pair.law.eps_t,
            mu: pair.law.mu,
        }
    }
}

/// The displacement of a pair's rigid master at `t` (zero for facets).
pub fn master_offset(pair: &SurfacePair, t: f64) -> [f64; 3] {
    match &pair.master {
        SurfaceMaster::Rigid(r) => r.offset(t),
        SurfaceMaster::Facets { .. } => [0.0; 3],
    }
}
