//! The 3D contact points of one pair at one converged increment as one message of arrays
//! (channel `/surface_contact`, format 3): the node-to-surface counterpart of
//! [`super::arrays::ContactArrays`]. A slave node that stays out of reach is left out where
//! readers can put it back ([`crate::record::mcap::format3::Format3Writer::surface_contact`]).

use crate::contact::law::ContactState;
use crate::record::messages::ModelRecord;
use crate::record::real::{Real, Real2, Real2s, Real3, Real3s, Reals};
use crate::record::surface_contact::{CarriedRecord, SurfacePointRecord};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// The slave nodes of one 3D contact pair at the end of a converged increment: every array
/// has one entry per slave written, in slave order (`/model`
/// `surface_contacts[pair].slave_nodes`); a slave left out is open and out of reach, its
/// record [`SurfacePointRecord::out_of_reach`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct SurfaceContactArrays {
    pub increment: usize,
    #[serde(with = "Real")]
    pub t: f64,
    /// Index of the pair in `/model` `surface_contacts`, and its name.
    pub pair: usize,
    pub pair_name: String,
    /// Displacement of a rigid master from its reference position (zero for facets).
    #[serde(with = "Real3")]
    #[schemars(with = "Real3")]
    pub master_offset: [f64; 3],
    /// Index of each point's slave within the pair, and its node.
    pub slave: Vec<usize>,
    pub node: Vec<usize>,
    /// Master facet of the current projection (index into the pair's `master_facets`; 0 for
    /// a rigid surface; null: nothing within reach), and at the last converged increment.
    pub facet: Vec<Option<usize>>,
    pub previous_facet: Vec<Option<usize>>,
    /// Convective coordinates `(ξ¹, ξ²)` of the contact point on `facet`.
    #[serde(with = "Real2s")]
    #[schemars(with = "Vec<Real2>")]
    pub xi: Vec<[f64; 2]>,
    /// Signed gap `ζ` (negative = penetration).
    #[serde(with = "Reals")]
    pub gap: Vec<f64>,
    #[serde(with = "Reals")]
    pub normal_force: Vec<f64>,
    /// Covariant tangential traction `T_α` on `facet` before the return map (trial) and
    /// after it.
    #[serde(with = "Real2s")]
    #[schemars(with = "Vec<Real2>")]
    pub trial_traction: Vec<[f64; 2]>,
    #[serde(with = "Real2s")]
    #[schemars(with = "Vec<Real2>")]
    pub traction: Vec<[f64; 2]>,
    /// `open`, `stick` or `slip` (a closed point of a frictionless pair is `slip`).
    pub state: Vec<ContactState>,
    /// Closed now and at the last converged increment, on another facet.
    pub crossing: Vec<bool>,
    /// The friction history could not be carried onto `facet`: the point started afresh.
    pub history_lost: Vec<bool>,
    /// The friction history carried onto `facet` in this increment (null where none was).
    pub carried: Vec<Option<CarriedRecord>>,
    /// Slave position (current configuration).
    #[serde(with = "Real3s")]
    #[schemars(with = "Vec<Real3>")]
    pub position: Vec<[f64; 3]>,
    /// Contact point on the master (current configuration; NaN where no facet is within
    /// reach).
    #[serde(with = "Real3s")]
    #[schemars(with = "Vec<Real3>")]
    pub contact_point: Vec<[f64; 3]>,
    /// Unit outward normal of the master at the contact point.
    #[serde(with = "Real3s")]
    #[schemars(with = "Vec<Real3>")]
    pub normal: Vec<[f64; 3]>,
    /// The contact force the slave node receives, as assembled (zero when open).
    #[serde(with = "Real3s")]
    #[schemars(with = "Vec<Real3>")]
    pub force: Vec<[f64; 3]>,
}

impl SurfaceContactArrays {
    /// `points` (of pair `pair`, named `pair_name`, in slave order) as one message.
    pub fn of<'a>(
        (increment, t): (usize, f64),
        (pair, pair_name): (usize, &str),
        master_offset: [f64; 3],
        points: impl IntoIterator<Item = &'a SurfacePointRecord>,
    ) -> Self {
        let p: Vec<&SurfacePointRecord> = points.into_iter().collect();
        let col = |f: &dyn Fn(&SurfacePointRecord) -> [f64; 3]| p.iter().map(|q| f(q)).collect();
        SurfaceContactArrays {
            increment,
            t,
            pair,
            pair_name: pair_name.to_string(),
            master_offset,
            slave: p.iter().map(|q| q.slave).collect(),
            node: p.iter().map(|q| q.node).collect(),
            facet: p.iter().map(|q| q.facet).collect(),
            previous_facet: p.iter().map(|q| q.previous_facet).collect(),
            xi: p.iter().map(|q| q.xi).collect(),
            gap: p.iter().map(|q| q.gap).collect(),
            normal_force: p.iter().map(|q| q.normal_force).collect(),
            trial_traction: p.iter().map(|q| q.trial_traction).collect(),
            traction: p.iter().map(|q| q.traction).collect(),
            state: p.iter().map(|q| q.state).collect(),
            crossing: p.iter().map(|q| q.crossing).collect(),
            history_lost: p.iter().map(|q| q.history_lost).collect(),
            carried: p.iter().map(|q| q.carried).collect(),
            position: col(&|q| q.position),
            contact_point: col(&|q| q.contact_point),
            normal: col(&|q| q.normal),
            force: col(&|q| q.force),
        }
    }

    /// The points as records (refused when a column has the wrong length or a pair or
    /// slave is not in the model).
    pub fn records(&self, model: &ModelRecord) -> Result<Vec<SurfacePointRecord>, String> {
        let n = self.slave.len();
        let lengths = [
            self.node.len(),
            self.facet.len(),
            self.previous_facet.len(),
            self.xi.len(),
            self.gap.len(),
            self.normal_force.len(),
            self.trial_traction.len(),
            self.traction.len(),
            self.state.len(),
            self.crossing.len(),
            self.history_lost.len(),
            self.carried.len(),
            self.position.len(),
            self.contact_point.len(),
            self.normal.len(),
            self.force.len(),
        ];
        if lengths.iter().any(|&l| l != n) {
            return Err(format!(
                "the arrays of 3D pair {} at increment {} have different lengths ({n} slaves, then {lengths:?})",
                self.pair, self.increment
            ));
        }
        let info = model.surface_contacts.get(self.pair).ok_or_else(|| {
            format!(
                "increment {} names 3D pair {}; the model has {}",
                self.increment,
                self.pair,
                model.surface_contacts.len()
            )
        })?;
        if let Some(&s) = self.slave.iter().find(|&&s| s >= info.slave_nodes.len()) {
            return Err(format!(
                "increment {} names slave {s} of pair `{}`, which has {}",
                self.increment,
                info.name,
                info.slave_nodes.len()
            ));
        }
        Ok((0..n).map(|k| self.record(k)).collect())
    }

    fn record(&self, k: usize) -> SurfacePointRecord {
        SurfacePointRecord {
            pair: self.pair,
            pair_name: self.pair_name.clone(),
            slave: self.slave[k],
            node: self.node[k],
            facet: self.facet[k],
            previous_facet: self.previous_facet[k],
            xi: self.xi[k],
            gap: self.gap[k],
            normal_force: self.normal_force[k],
            trial_traction: self.trial_traction[k],
            traction: self.traction[k],
            state: self.state[k],
            crossing: self.crossing[k],
            history_lost: self.history_lost[k],
            carried: self.carried[k],
            position: self.position[k],
            contact_point: self.contact_point[k],
            normal: self.normal[k],
            force: self.force[k],
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::record::surface_contact::SurfacePairInfo;

    fn point(slave: usize) -> SurfacePointRecord {
        SurfacePointRecord {
            pair: 0,
            pair_name: "base".into(),
            slave,
            node: 10 + slave,
            facet: (slave != 1).then_some(3),
            previous_facet: Some(2),
            xi: [0.25 * slave as f64, f64::NAN],
            gap: -1e-3,
            normal_force: 2.5,
            trial_traction: [f64::INFINITY, 0.5],
            traction: [0.1, -0.2],
            state: ContactState::Slip,
            crossing: slave == 2,
            history_lost: false,
            carried: (slave == 2).then_some(CarriedRecord {
                from_facet: 2,
                xi_from: [0.99, 0.1],
                traction_from: [0.3, 0.0],
                xi_to: [-1.01, 0.1],
                traction_to: [0.31, 1e-3],
            }),
            position: [1.0, 2.0, -0.0],
            contact_point: [f64::NAN, 0.5, 1.0],
            normal: [0.0, 0.0, 1.0],
            force: [-0.1, 0.2, 2.5],
        }
    }

    fn model() -> ModelRecord {
        let mut m: ModelRecord = serde_json::from_str(
            r#"{"name":"m","description":"","nodes":[],"elements":[],"element_body":[],
                "bodies":[],"rigid":[],"contacts":[],"monitor":null,"end":1.0}"#,
        )
        .unwrap();
        m.surface_contacts = vec![SurfacePairInfo {
            name: "base".into(),
            slave_nodes: (10..13).collect(),
            areas: vec![0.25; 3],
            master: "body slab".into(),
            master_facets: vec![[0, 1, 2, 3]; 4],
            rigid: None,
            transfer: "continuous".into(),
            eps_n: 1.0,
            eps_t: 1.0,
            mu: 0.3,
        }];
        m
    }

    #[test]
    fn arrays_read_back_as_the_records_bit_for_bit() {
        let points: Vec<_> = (0..3).map(point).collect();
        let arrays = SurfaceContactArrays::of((4, 0.5), (0, "base"), [0.0, 0.0, -0.1], &points);
        let text = serde_json::to_string(&arrays).unwrap();
        assert!(text.contains(r#""carried":[null,null,{"from_facet":2"#), "{text}");
        let back: SurfaceContactArrays = serde_json::from_str(&text).unwrap();
        let records = back.records(&model()).unwrap();
        assert_eq!(records.len(), 3);
        for (a, b) in points.iter().zip(&records) {
            assert_eq!(serde_json::to_string(a).unwrap(), serde_json::to_string(b).unwrap());
        }
    }

    #[test]
    fn ragged_arrays_and_unknown_pairs_or_slaves_are_refused() {
        let points: Vec<_> = (0..3).map(point).collect();
        let arrays = SurfaceContactArrays::of((1, 0.0), (0, "base"), [0.0; 3], &points);
        let mut a = arrays.clone();
        a.carried.pop();
        assert!(a.records(&model()).unwrap_err().contains("different lengths"));
        let mut a = arrays.clone();
        a.slave[1] = 7;
        assert!(a.records(&model()).unwrap_err().contains("slave 7"));
        let mut a = arrays;
        a.pair = 2;
        assert!(a.records(&model()).unwrap_err().contains("3D pair 2"));
    }
}
