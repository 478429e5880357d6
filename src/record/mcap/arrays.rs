//! Format 3 of the per-increment channels `/contact` and `/pressure`: one message per
//! converged increment and contact pair whose fields are columns (struct of arrays), so a
//! key is written once per message instead of once per point, and a reader gets each
//! field as one array (`numpy.array(msg["gap"], dtype=float)`).
//!
//! The owned types ([`ContactArrays`], [`PressureArrays`]) are what readers parse and what
//! the JSON Schemas are generated from; the writer serialises borrowed views of the
//! solver's records ([`ContactColumns`], [`PressureColumns`]) into the same JSON without
//! building the arrays first. `tests` below check that both give the same JSON.

use crate::contact::law::ContactState;
use crate::record::messages::ModelRecord;
use crate::record::pressure::{PressurePoint, PressureRecord};
use crate::record::real::{Item, Item2, Real, Real2, Real2s, Reals};
use crate::record::ContactPointRecord;
use schemars::JsonSchema;
use serde::ser::{SerializeSeq, SerializeStruct, Serializer};
use serde::{Deserialize, Serialize};
use std::sync::Arc;

/// The contact slave points of one pair at the end of a converged increment (channel
/// `/contact`, format 3): every array has one entry per point, in the order of `slave`.
/// Slave nodes that stay out of reach are left out at the increments that have
/// `/positions` (see `OutOfReach` in `mcap_sink`), so `slave` need not list every slave.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct ContactArrays {
    pub increment: usize,
    #[serde(with = "Real")]
    pub t: f64,
    /// Index of the pair in the model's `contacts`, and its name.
    pub pair: usize,
    pub pair_name: String,
    /// Index of each point's slave within the pair (ascending; its label is
    /// `/model` `contacts[pair].slaves[slave]`).
    pub slave: Vec<usize>,
    /// Master segment of the current projection (null: no segment within reach).
    pub segment: Vec<Option<usize>>,
    /// Segment at the previous converged increment.
    pub previous_segment: Vec<Option<usize>>,
    /// Convective coordinate `ξ` of the projection on `segment`.
    #[serde(with = "Reals")]
    pub xi: Vec<f64>,
    /// Centre of the elastic region (sliding anchor) `ξ_sl = ξ + T_1/(ε_T a11)`.
    #[serde(with = "Reals")]
    pub xi_anchor: Vec<f64>,
    /// Signed gap `ζ` (negative = penetration).
    #[serde(with = "Reals")]
    pub gap: Vec<f64>,
    #[serde(with = "Reals")]
    pub normal_force: Vec<f64>,
    /// Trial tangential traction along the unit tangent (before return mapping).
    #[serde(with = "Reals")]
    pub trial_traction: Vec<f64>,
    /// Returned tangential traction along the unit tangent.
    #[serde(with = "Reals")]
    pub traction: Vec<f64>,
    /// `open`, `stick` or `slip`; a closed point of a frictionless pair (`μ = 0`) is `slip`
    /// (without friction there is no stick).
    pub state: Vec<ContactState>,
    /// The point is closed and was closed at the last converged increment, on another
    /// segment: a crossing that carries friction history across a segment boundary (one
    /// `/crossing` event each). A point that closes on another segment than the one it was
    /// tracked on while open, or opens, is not crossing.
    pub crossing: Vec<bool>,
    /// Slave position (current configuration).
    #[schemars(with = "Vec<Real2>")]
    #[serde(with = "Real2s")]
    pub position: Vec<[f64; 2]>,
    /// Contact point `ρ(ξ)` on the master.
    #[schemars(with = "Vec<Real2>")]
    #[serde(with = "Real2s")]
    pub contact_point: Vec<[f64; 2]>,
    /// Unit normal of the master at the contact point.
    #[schemars(with = "Vec<Real2>")]
    #[serde(with = "Real2s")]
    pub normal: Vec<[f64; 2]>,
    /// Unit tangent of the master at the contact point.
    #[schemars(with = "Vec<Real2>")]
    #[serde(with = "Real2s")]
    pub tangent: Vec<[f64; 2]>,
    /// Augmented-Lagrangian multiplier estimates `[λ_N, λ_T]` of each point (written only
    /// for pairs with `enforcement = "augmented"`; absent or empty: NaN, penalty pairs).
    #[serde(default, skip_serializing_if = "Vec::is_empty", with = "Real2s")]
    #[schemars(with = "Vec<Real2>")]
    pub multiplier: Vec<[f64; 2]>,
    /// The contact force each slave receives (x, y), as assembled: `N n + T τ` on a straight
    /// master, with the curvature factor of `∇ξ` on a curved one; zero for an open point
    /// (absent in older recordings: NaN).
    #[serde(default, with = "Real2s")]
    #[schemars(with = "Vec<Real2>")]
    pub force: Vec<[f64; 2]>,
}

impl ContactArrays {
    /// The points as records, labelled from `model` (refused when a column has the wrong
    /// length or a pair or slave is not in the model).
    pub fn records(&self, model: &ModelRecord) -> Result<Vec<ContactPointRecord>, String> {
        let n = self.slave.len();
        let lengths = [
            self.segment.len(),
            self.previous_segment.len(),
            self.xi.len(),
            self.xi_anchor.len(),
            self.gap.len(),
            self.normal_force.len(),
            self.trial_traction.len(),
            self.traction.len(),
            self.state.len(),
            self.crossing.len(),
            self.position.len(),
            self.contact_point.len(),
            self.normal.len(),
            self.tangent.len(),
        ];
        let optional_ok = [self.multiplier.len(), self.force.len()]
            .iter()
            .all(|&l| l == 0 || l == n);
        if lengths.iter().any(|&l| l != n) || !optional_ok {
            return Err(format!(
                "the arrays of pair {} at increment {} have different lengths ({n} slaves, then {lengths:?})",
                self.pair, self.increment
            ));
        }
        let info = model.contacts.get(self.pair).ok_or_else(|| {
            format!(
                "increment {} names pair {}; the model has {} pairs",
                self.increment,
                self.pair,
                model.contacts.len()
            )
        })?;
        let pair_name: Arc<str> = Arc::from(self.pair_name.as_str());
        (0..n)
            .map(|k| {
                let slave = self.slave[k];
                let label = info.slaves.get(slave).ok_or_else(|| {
                    format!(
                        "increment {} names slave {slave} of pair `{}`, which has {}",
                        self.increment,
                        info.name,
                        info.slaves.len()
                    )
                })?;
                Ok(ContactPointRecord {
                    pair: self.pair,
                    pair_name: pair_name.clone(),
                    slave,
                    slave_label: Arc::from(label.as_str()),
                    segment: self.segment[k],
                    previous_segment: self.previous_segment[k],
                    xi: self.xi[k],
                    xi_anchor: self.xi_anchor[k],
                    gap: self.gap[k],
                    normal_force: self.normal_force[k],
                    trial_traction: self.trial_traction[k],
                    traction: self.traction[k],
                    state: self.state[k],
                    crossing: self.crossing[k],
                    position: self.position[k],
                    contact_point: self.contact_point[k],
                    normal: self.normal[k],
                    tangent: self.tangent[k],
                    multiplier: self.multiplier.get(k).copied().unwrap_or([f64::NAN; 2]),
                    force: self.force.get(k).copied().unwrap_or([f64::NAN; 2]),
                })
            })
            .collect()
    }
}

/// A column of values taken from a slice's items (all of them, or those at `take`).
struct Column<'a, T, F> {
    items: &'a [T],
    take: Option<&'a [usize]>,
    value: F,
}

impl<T, V: Serialize, F: Fn(&T) -> V> Serialize for Column<'_, T, F> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        match self.take {
            Some(take) => {
                let mut seq = s.serialize_seq(Some(take.len()))?;
                for &i in take {
                    seq.serialize_element(&(self.value)(&self.items[i]))?;
                }
                seq.end()
            }
            None => {
                let mut seq = s.serialize_seq(Some(self.items.len()))?;
                for x in self.items {
                    seq.serialize_element(&(self.value)(x))?;
                }
                seq.end()
            }
        }
    }
}

fn column<'a, T, V, F: Fn(&T) -> V>(items: &'a [T], take: Option<&'a [usize]>, value: F) -> Column<'a, T, F> {
    Column { items, take, value }
}

/// [`ContactArrays`] as written: the points `take` (indices into `points`, all of one
/// pair, in slave order) serialised column by column.
pub struct ContactColumns<'a> {
    pub increment: usize,
    pub t: f64,
    pub pair: usize,
    pub pair_name: &'a str,
    pub points: &'a [ContactPointRecord],
    pub take: &'a [usize],
}

impl Serialize for ContactColumns<'_> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let (p, k) = (self.points, Some(self.take));
        let augmented = self.take.iter().any(|&i| p[i].multiplier.iter().any(|x| x.is_finite()));
        let mut m = s.serialize_struct("ContactArrays", 20 + usize::from(augmented))?;
        m.serialize_field("increment", &self.increment)?;
        m.serialize_field("t", &Item(self.t))?;
        m.serialize_field("pair", &self.pair)?;
        m.serialize_field("pair_name", self.pair_name)?;
        m.serialize_field("slave", &column(p, k, |r| r.slave))?;
        m.serialize_field("segment", &column(p, k, |r| r.segment))?;
        m.serialize_field("previous_segment", &column(p, k, |r| r.previous_segment))?;
        m.serialize_field("xi", &column(p, k, |r| Item(r.xi)))?;
        m.serialize_field("xi_anchor", &column(p, k, |r| Item(r.xi_anchor)))?;
        m.serialize_field("gap", &column(p, k, |r| Item(r.gap)))?;
        m.serialize_field("normal_force", &column(p, k, |r| Item(r.normal_force)))?;
        m.serialize_field("trial_traction", &column(p, k, |r| Item(r.trial_traction)))?;
        m.serialize_field("traction", &column(p, k, |r| Item(r.traction)))?;
        m.serialize_field("state", &column(p, k, |r| r.state))?;
        m.serialize_field("crossing", &column(p, k, |r| r.crossing))?;
        m.serialize_field("position", &column(p, k, |r| Item2(r.position)))?;
        m.serialize_field("contact_point", &column(p, k, |r| Item2(r.contact_point)))?;
        m.serialize_field("normal", &column(p, k, |r| Item2(r.normal)))?;
        m.serialize_field("tangent", &column(p, k, |r| Item2(r.tangent)))?;
        if augmented {
            m.serialize_field("multiplier", &column(p, k, |r| Item2(r.multiplier)))?;
        }
        m.serialize_field("force", &column(p, k, |r| Item2(r.force)))?;
        m.end()
    }
}

/// The contact pressure profile of one pair at one increment (channel `/pressure`, format
/// 3; see [`crate::record::pressure`]): one entry per paired slave node, in the order of the arc
/// length `s` along the master.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct PressureArrays {
    pub increment: usize,
    #[serde(with = "Real")]
    pub t: f64,
    pub pair: usize,
    pub pair_name: String,
    /// Index of the slave within the pair, and its node.
    pub slave: Vec<usize>,
    pub node: Vec<usize>,
    /// Master segment of the contact point.
    pub segment: Vec<usize>,
    /// Arc length of the contact point along the master (current segment lengths,
    /// segments in index order).
    #[serde(with = "Reals")]
    pub s: Vec<f64>,
    /// Contact point `ρ(ξ)` (current configuration).
    #[schemars(with = "Vec<Real2>")]
    #[serde(with = "Real2s")]
    pub contact_point: Vec<[f64; 2]>,
    /// Normal force `N` of the node (0 when open).
    #[serde(with = "Reals")]
    pub normal_force: Vec<f64>,
    /// Tributary length `l`: half of each slave face segment joining the node to another
    /// slave node (current configuration).
    #[serde(with = "Reals")]
    pub tributary: Vec<f64>,
    /// `p = N / l` (NaN when `l = 0`).
    #[serde(with = "Reals")]
    pub pressure: Vec<f64>,
}

impl PressureArrays {
    /// The profile as a record (refused when a column has the wrong length).
    pub fn record(&self) -> Result<PressureRecord, String> {
        let n = self.slave.len();
        let lengths = [
            self.node.len(),
            self.segment.len(),
            self.s.len(),
            self.contact_point.len(),
            self.normal_force.len(),
            self.tributary.len(),
            self.pressure.len(),
        ];
        if lengths.iter().any(|&l| l != n) {
            return Err(format!(
                "the pressure arrays of pair {} at increment {} have different lengths ({n} slaves, then {lengths:?})",
                self.pair, self.increment
            ));
        }
        let points = (0..n)
            .map(|k| PressurePoint {
                slave: self.slave[k],
                node: self.node[k],
                segment: self.segment[k],
                s: self.s[k],
                contact_point: self.contact_point[k],
                normal_force: self.normal_force[k],
                tributary: self.tributary[k],
                pressure: self.pressure[k],
            })
            .collect();
        Ok(PressureRecord {
            increment: self.increment,
            t: self.t,
            pair: self.pair,
            pair_name: self.pair_name.clone(),
            points,
        })
    }
}

/// [`PressureArrays`] as written, from a profile record.
pub struct PressureColumns<'a>(pub &'a PressureRecord);

impl Serialize for PressureColumns<'_> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let r = self.0;
        let (p, k) = (r.points.as_slice(), None);
        let mut m = s.serialize_struct("PressureArrays", 12)?;
        m.serialize_field("increment", &r.increment)?;
        m.serialize_field("t", &Item(r.t))?;
        m.serialize_field("pair", &r.pair)?;
        m.serialize_field("pair_name", &r.pair_name)?;
        m.serialize_field("slave", &column(p, k, |q| q.slave))?;
        m.serialize_field("node", &column(p, k, |q| q.node))?;
        m.serialize_field("segment", &column(p, k, |q| q.segment))?;
        m.serialize_field("s", &column(p, k, |q| Item(q.s)))?;
        m.serialize_field("contact_point", &column(p, k, |q| Item2(q.contact_point)))?;
        m.serialize_field("normal_force", &column(p, k, |q| Item(q.normal_force)))?;
        m.serialize_field("tributary", &column(p, k, |q| Item(q.tributary)))?;
        m.serialize_field("pressure", &column(p, k, |q| Item(q.pressure)))?;
        m.end()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::record::messages::PairInfo;

    fn point(slave: usize, xi: f64) -> ContactPointRecord {
        ContactPointRecord {
            pair: 0,
            pair_name: Arc::from("base"),
            slave,
            slave_label: Arc::from(format!("node {}", 10 + slave).as_str()),
            segment: (slave != 1).then_some(3),
            previous_segment: None,
            xi,
            xi_anchor: f64::NAN,
            gap: -1e-3,
            normal_force: 2.5,
            trial_traction: f64::INFINITY,
            traction: 0.1,
            state: ContactState::Slip,
            crossing: slave == 2,
            position: [1.0, 2.0],
            contact_point: [f64::NAN, 0.5],
            normal: [0.0, 1.0],
            tangent: [-1.0, 0.0],
            multiplier: [f64::NAN; 2],
            force: [-0.1, 2.5],
        }
    }

    fn model() -> ModelRecord {
        ModelRecord {
            name: "m".into(),
            description: String::new(),
            nodes: vec![],
            elements: vec![],
            element_body: vec![],
            bodies: vec![],
            rigid: vec![],
            contacts: vec![PairInfo {
                name: "base".into(),
                slaves: (0..4).map(|k| format!("node {}", 10 + k)).collect(),
                master: "rigid plane".into(),
                master_segments: vec![],
                transfer: "continuous".into(),
                eps_n: 1.0,
                eps_t: 1.0,
                mu: 0.2,
            }],
            end: 1.0,
            ..ModelRecord::default()
        }
    }

    #[test]
    fn columns_are_written_as_the_arrays_read_and_read_back_bit_for_bit() {
        let points: Vec<_> = (0..4).map(|k| point(k, 0.1 * k as f64 - 0.7)).collect();
        let take = [0, 2, 3];
        let text = serde_json::to_string(&ContactColumns {
            increment: 7,
            t: 0.25,
            pair: 0,
            pair_name: "base",
            points: &points,
            take: &take,
        })
        .unwrap();
        assert!(text.contains(r#""xi_anchor":["NaN","NaN","NaN"]"#), "{text}");
        let arrays: ContactArrays = serde_json::from_str(&text).unwrap();
        assert_eq!(serde_json::to_string(&arrays).unwrap(), text);
        assert_eq!(arrays.slave, vec![0, 2, 3]);
        let back = arrays.records(&model()).unwrap();
        for (b, &k) in back.iter().zip(&take) {
            let a = &points[k];
            assert_eq!(serde_json::to_string(a).unwrap(), serde_json::to_string(b).unwrap());
        }
    }

    #[test]
    fn multipliers_are_a_column_only_where_a_point_has_one() {
        let mut points: Vec<_> = (0..3).map(|k| point(k, 0.2 * k as f64)).collect();
        let columns = |points: &[ContactPointRecord]| {
            serde_json::to_string(&ContactColumns {
                increment: 1,
                t: 0.5,
                pair: 0,
                pair_name: "base",
                points,
                take: &[0, 1, 2],
            })
            .unwrap()
        };
        assert!(!columns(&points).contains("multiplier"));
        points[1].multiplier = [3.5, -0.25];
        let text = columns(&points);
        let arrays: ContactArrays = serde_json::from_str(&text).unwrap();
        assert_eq!(arrays.multiplier.len(), 3);
        let back = arrays.records(&model()).unwrap();
        assert_eq!(back[1].multiplier, [3.5, -0.25]);
        assert!(back[0].multiplier[0].is_nan());
        let mut ragged = arrays.clone();
        ragged.multiplier.pop();
        assert!(ragged.records(&model()).is_err());
    }

    #[test]
    fn ragged_arrays_and_unknown_slaves_are_refused() {
        let points: Vec<_> = (0..2).map(|k| point(k, 0.0)).collect();
        let text = serde_json::to_string(&ContactColumns {
            increment: 1,
            t: 0.0,
            pair: 0,
            pair_name: "base",
            points: &points,
            take: &[0, 1],
        })
        .unwrap();
        let mut a: ContactArrays = serde_json::from_str(&text).unwrap();
        a.gap.pop();
        assert!(a.records(&model()).unwrap_err().contains("different lengths"));
        let mut a: ContactArrays = serde_json::from_str(&text).unwrap();
        a.slave[1] = 9;
        assert!(a.records(&model()).unwrap_err().contains("slave 9"));
        let mut a: ContactArrays = serde_json::from_str(&text).unwrap();
        a.pair = 1;
        assert!(a.records(&model()).unwrap_err().contains("pair 1"));
    }

    #[test]
    fn pressure_columns_read_back_as_the_profile() {
        let rec = PressureRecord {
            increment: 3,
            t: 0.5,
            pair: 1,
            pair_name: "block".into(),
            points: (0..3)
                .map(|k| PressurePoint {
                    slave: k,
                    node: 20 + k,
                    segment: k / 2,
                    s: 0.3 * k as f64,
                    contact_point: [k as f64, -0.0],
                    normal_force: 1.5,
                    tributary: if k == 2 { 0.0 } else { 0.25 },
                    pressure: if k == 2 { f64::NAN } else { 6.0 },
                })
                .collect(),
        };
        let text = serde_json::to_string(&PressureColumns(&rec)).unwrap();
        let arrays: PressureArrays = serde_json::from_str(&text).unwrap();
        assert_eq!(serde_json::to_string(&arrays).unwrap(), text);
        let back = arrays.record().unwrap();
        assert_eq!(
            serde_json::to_string(&back).unwrap(),
            serde_json::to_string(&rec).unwrap()
        );
        let mut bad = arrays.clone();
        bad.s.push(1.0);
        assert!(bad.record().is_err());
    }
}
