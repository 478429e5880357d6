//! Contact pressure along a master face (channel `/pressure`): for each contact pair whose
//! slaves are nodes, the normal pressure of every paired slave node against the arc length of
//! its contact point along the master, at a converged increment.
//!
//! Node-to-segment contact gives a normal *force* `N` per slave node; the pressure is
//! `p = N / l`, `l` the node's tributary length: half the current length of each slave face
//! segment that joins it to another slave node of the pair (a node at the end of the slave
//! chain — a free end or a symmetry plane — has one such segment). Beyond plane strain the
//! force is divided by the measure of the point too, its contact weight `w`
//! ([`crate::model::ContactPair::weights`]): `p = N / (w l)`, with `w = t` for a plate and
//! `w = 2π r̄` for a ring of an axisymmetric body (`N` there the total over the full circle,
//! `2π r̄ l` the ring's tributary area). The arc length `s` runs
//! along the master's segments in index order (current lengths; a rigid surface's pieces in
//! the order they are listed), `s = s_k + L_k (ξ + 1)/2` on segment `k` (linear in ξ on
//! straight segments and on arcs). Open points have `p = 0`; points with no master segment
//! within reach are left out. Computed from the records of the converged state by the sinks
//! that write it; the solver is not involved.

use super::real::{Real, Real2};
use super::ContactPointRecord;
use crate::contact::law::ContactState;
use crate::contact::system::Config;
use crate::model::{Model, Slave};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};
use std::collections::{HashMap, HashSet};

/// The pressure profile of one contact pair at one increment.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
pub struct PressureRecord {
    pub increment: usize,
    #[serde(with = "Real")]
    pub t: f64,
    pub pair: usize,
    pub pair_name: String,
    /// Paired slave points in the order of their arc length along the master.
    pub points: Vec<PressurePoint>,
}

/// One slave node of a pressure profile.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
pub struct PressurePoint {
    /// Index of the slave within the pair, and its node.
    pub slave: usize,
    pub node: usize,
    /// Master segment and arc length of the contact point along the master.
    pub segment: usize,
    #[serde(with = "Real")]
    pub s: f64,
    /// Contact point `ρ(ξ)` (current configuration).
    #[serde(with = "Real2")]
    pub contact_point: [f64; 2],
    /// Normal force `N` of the node, its tributary length `l`, and `p = N / (w l)` (`w` = 1 in
    /// plane strain, the thickness in plane stress, `2π r̄` axisymmetric; NaN when the node is
    /// on no face segment joining it to another slave node: `l = 0`).
    #[serde(with = "Real")]
    pub normal_force: f64,
    #[serde(with = "Real")]
    pub tributary: f64,
    #[serde(with = "Real")]
    pub pressure: f64,
}

/// What the pressure profiles need of the model, worked out once per run: for each pair
/// with node slaves, its slave nodes and the slave face segments that join two of them
/// (as slave indices, each segment once, in the order of the bodies' faces).
#[derive(Debug, Clone, Default)]
pub struct PressureLayout {
    pairs: Vec<Option<PairLayout>>,
}

#[derive(Debug, Clone)]
struct PairLayout {
    nodes: Vec<usize>,
    /// `(i, j)`: slaves `i` and `j` share a face segment.
    links: Vec<(usize, usize)>,
}

impl PressureLayout {
    pub fn new(model: &Model) -> Self {
        let pairs = (model.contacts.iter())
            .map(|pair| {
                let nodes: Vec<usize> = (pair.slaves.iter())
                    .map(|s| match s {
                        Slave::Node(n) => Some(*n),
                        _ => None,
                    })
                    .collect::<Option<_>>()?;
                let index: HashMap<usize, usize> = nodes.iter().enumerate().map(|(i, n)| (*n, i)).collect();
                let mut seen = HashSet::new();
                let mut links = Vec::new();
                for body in &model.bodies {
                    for seg in body.faces.values().flatten() {
                        if !seen.insert((seg[0].min(seg[1]), seg[0].max(seg[1]))) {
                            continue;
                        }
                        if let (Some(&i), Some(&j)) = (index.get(&seg[0]), index.get(&seg[1])) {
                            links.push((i, j));
                        }
                    }
                }
                Some(PairLayout { nodes, links })
            })
            .collect();
        PressureLayout { pairs }
    }
}

/// The pressure profiles of the node-slave pairs of `model` (whose [`PressureLayout`] is
/// `layout`) at the converged state `u`, load level `t`, from its contact point records.
pub fn profiles(
    layout: &PressureLayout,
    model: &Model,
    u: &[f64],
    t: f64,
    increment: usize,
    contact: &[ContactPointRecord],
) -> Vec<PressureRecord> {
    let cfg = Config { model, u, t };
    let at = |n: usize| [model.nodes[n][0] + u[2 * n], model.nodes[n][1] + u[2 * n + 1]];
    let mut out = Vec::new();
    for ((ip, pair), lay) in model.contacts.iter().enumerate().zip(&layout.pairs) {
        let Some(PairLayout { nodes, links }) = lay else {
            continue;
        };
        // tributary lengths: half of each slave face segment joining two slave nodes
        let mut tributary = vec![0.0; nodes.len()];
        for &(i, j) in links {
            let (a, b) = (at(nodes[i]), at(nodes[j]));
            let half = 0.5 * (b[0] - a[0]).hypot(b[1] - a[1]);
            tributary[i] += half;
            tributary[j] += half;
        }
        let mut start = vec![0.0; pair.master.segment_count() + 1];
        for k in 0..pair.master.segment_count() {
            start[k + 1] = start[k] + cfg.segment(pair, k).length();
        }
        let mut points: Vec<PressurePoint> = (contact.iter())
            .filter(|c| c.pair == ip && c.slave < nodes.len())
            .filter_map(|c| {
                let k = c.segment.filter(|k| *k < pair.master.segment_count())?;
                let l = tributary[c.slave];
                let n = if c.state == ContactState::Open {
                    0.0
                } else {
                    c.normal_force
                };
                Some(PressurePoint {
                    slave: c.slave,
                    node: nodes[c.slave],
                    segment: k,
                    s: start[k] + (start[k + 1] - start[k]) * 0.5 * (c.xi + 1.0),
                    contact_point: c.contact_point,
                    normal_force: n,
                    tributary: l,
                    pressure: if l > 0.0 {
                        n / (pair.weight(c.slave) * l)
                    } else {
                        f64::NAN
                    },
                })
            })
            .collect();
        points.sort_by(|a, b| a.s.total_cmp(&b.s));
        out.push(PressureRecord {
            increment,
            t,
            pair: ip,
            pair_name: pair.name.clone(),
            points,
        });
    }
    out
}
