//! The interface of a two-pass contact pair (channel `/interface`): the two passes combined
//! into the traction that one face of the interface receives, at the increments that have
//! `/positions`.
//!
//! A two-pass pair `NAME` is two node-to-segment pairs: the first pass `NAME` (the slave
//! nodes of body A against the face of body B) and the second pass `NAME/second-pass` (the
//! nodes of B's face against A's face), each with half the penalties. Each pass carries
//! part of the load — how much depends on the meshes (from about 7 % to about 50 % for
//! the second) — so neither pass's `/pressure` profile is the interface's pressure, and their
//! profiles lie along different faces.
//!
//! The rule: the interface is described on the first pass's master face (B's face), by the
//! contact force that each of its nodes `j` receives from both passes,
//!
//! ```text
//!   F_j = f²_j − Σ_i φ_j(ξ_i) f¹_i,        f = N n + t τ  (the force on a slave),
//! ```
//!
//! `f²_j` the force on node `j` as a slave of the second pass, `f¹_i` the force on slave `i`
//! of the first pass, whose reaction `−f¹_i` B's face takes at the ends of the segment the
//! slave projects on with the linear shares `φ_a = (1 − ξ)/2`, `φ_b = (1 + ξ)/2` (`ξ` clamped
//! to [−1, 1]). Then, with `l_j` the node's tributary length (half of each face segment at
//! it), `n_j` the face's outward unit normal and `τ_j` its unit tangent at the node (the mean
//! of its segments' directions, along increasing `s`):
//!
//! ```text
//!   p_j = −F_j · n_j / l_j   (pressure),     q_j = F_j · τ_j / l_j   (shear traction).
//! ```
//!
//! Every contact force is counted once: `Σ_j p_j l_j` is the interface's normal force, equal
//! on a straight interface to `Σ N¹ + Σ N²` (the shares of a slave sum to 1). A uniform
//! pressure `p` gives `F_j` = B's consistent nodal loads `p l_j`, hence `p_j = p` (not `p/2`
//! nor `2p`). The coordinate `s` is the arc length along the first pass's master, as in its
//! `/pressure` profile. With a smoothed master face (Hermite, Bézier) the solver spreads a
//! slave's reaction over four nodes, not two: the profile is then the linear-share
//! approximation of it (the total is exact).
//!
//! State of the interface at node `j` (its stick map): `open` when no closed point
//! contributes to `F_j` (the second pass's slave at `j`, or a first-pass slave with a
//! positive share), `slip` when every closed contributor slips, `stick` otherwise.

use super::real::{Real, Real2, Real2s, Reals};
use super::ContactPointRecord;
use crate::contact::law::ContactState;
use crate::contact::system::Config;
use crate::model::{Master, Model, Slave, SECOND_PASS_SUFFIX};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};
use std::collections::HashMap;

/// The interface of one two-pass pair at one increment: totals, then arrays over the nodes
/// of the first pass's master face in the order of their arc length `s`.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema, PartialEq)]
pub struct InterfaceRecord {
    pub increment: usize,
    #[serde(with = "Real")]
    pub t: f64,
    /// The interface's name (its first pass's pair name) and the indices of its passes.
    pub name: String,
    pub first_pass: usize,
    pub second_pass: usize,
    /// `Σ N` of the closed points of each pass, and the interface's normal force `Σ p_j l_j`
    /// (each contact force once).
    #[serde(with = "Real")]
    pub first_pass_force: f64,
    #[serde(with = "Real")]
    pub second_pass_force: f64,
    #[serde(with = "Real")]
    pub normal_force: f64,
    /// Node of the first pass's master face (a slave node of the second pass).
    pub node: Vec<usize>,
    /// Arc length of the node along the first pass's master (current configuration).
    #[serde(with = "Reals")]
    pub s: Vec<f64>,
    /// Current position of the node, and the face's outward unit normal there.
    #[schemars(with = "Vec<Real2>")]
    #[serde(with = "Real2s")]
    pub position: Vec<[f64; 2]>,
    #[schemars(with = "Vec<Real2>")]
    #[serde(with = "Real2s")]
    pub normal: Vec<[f64; 2]>,
    /// Tributary length `l_j`, pressure `p_j` and shear traction `q_j` (see the module).
    #[serde(with = "Reals")]
    pub tributary: Vec<f64>,
    #[serde(with = "Reals")]
    pub pressure: Vec<f64>,
    #[serde(with = "Reals")]
    pub shear: Vec<f64>,
    /// Open, stick or slip (the interface's stick map).
    pub state: Vec<ContactState>,
}

impl InterfaceRecord {
    /// The arrays' lengths disagree (what a reader checks of a message).
    pub fn check(&self) -> Result<(), String> {
        let n = self.node.len();
        let lengths = [
            self.s.len(),
            self.position.len(),
            self.normal.len(),
            self.tributary.len(),
            self.pressure.len(),
            self.shear.len(),
            self.state.len(),
        ];
        if lengths.iter().any(|&l| l != n) {
            return Err(format!(
                "the arrays of interface `{}` at increment {} have different lengths ({n} nodes, then {lengths:?})",
                self.name, self.increment
            ));
        }
        Ok(())
    }
}

/// One two-pass interface of a model, worked out once per run.
#[derive(Debug, Clone)]
struct Passes {
    first: usize,
    second: usize,
}

/// The two-pass interfaces of a model: pairs `NAME` and `NAME/second-pass` where the first
/// has a deformable master face and the second node slaves.
#[derive(Debug, Clone, Default)]
pub struct InterfaceLayout {
    interfaces: Vec<Passes>,
}

impl InterfaceLayout {
    pub fn new(model: &Model) -> Self {
        let mut interfaces = Vec::new();
        for (first, pair) in model.contacts.iter().enumerate() {
            let name = format!("{}{SECOND_PASS_SUFFIX}", pair.name);
            let Some(second) = model.contacts.iter().position(|p| p.name == name) else {
                continue;
            };
            if !matches!(pair.master, Master::Face { .. }) {
                continue;
            }
            if model.contacts[second]
                .slaves
                .iter()
                .all(|s| matches!(s, Slave::Node(_)))
            {
                interfaces.push(Passes { first, second });
            }
        }
        InterfaceLayout { interfaces }
    }

    /// Whether the model has no two-pass interface.
    pub fn is_empty(&self) -> bool {
        self.interfaces.is_empty()
    }
}

/// The force on a closed slave (`N n + t τ`), or `None` for a point that carries none.
fn slave_force(c: &ContactPointRecord) -> Option<[f64; 2]> {
    if c.state == ContactState::Open || c.segment.is_none() {
        return None;
    }
    let (n, t) = (c.normal_force, c.traction);
    Some([n * c.normal[0] + t * c.tangent[0], n * c.normal[1] + t * c.tangent[1]])
}

/// The master face of an interface in the current configuration: its nodes in the order of
/// `s`, with `s`, tributary length, unit tangent (along increasing `s`).
struct Face {
    nodes: Vec<usize>,
    index: HashMap<usize, usize>,
    s: Vec<f64>,
    tributary: Vec<f64>,
    tangent: Vec<[f64; 2]>,
}

/// Per node of a face: its arc length, tributary length and the sum of its segments' unit
/// directions.
type NodeSum = (f64, f64, [f64; 2]);

fn face(model: &Model, u: &[f64], t: f64, first: usize) -> Option<Face> {
    let pair = &model.contacts[first];
    let Master::Face { segments, .. } = &pair.master else {
        return None;
    };
    let cfg = Config { model, u, t };
    let at = |n: usize| [model.nodes[n][0] + u[2 * n], model.nodes[n][1] + u[2 * n + 1]];
    let mut start = vec![0.0; segments.len() + 1];
    for k in 0..segments.len() {
        start[k + 1] = start[k] + cfg.segment(pair, k).length();
    }
    let mut acc: HashMap<usize, NodeSum> = HashMap::new();
    for (k, &[a, b]) in segments.iter().enumerate() {
        let (pa, pb) = (at(a), at(b));
        let len = (pb[0] - pa[0]).hypot(pb[1] - pa[1]);
        let dir = if len > 0.0 {
            [(pb[0] - pa[0]) / len, (pb[1] - pa[1]) / len]
        } else {
            [0.0; 2]
        };
        for (n, s) in [(a, start[k]), (b, start[k + 1])] {
            let e = acc.entry(n).or_insert((s, 0.0, [0.0; 2]));
            e.1 += 0.5 * len;
            e.2 = [e.2[0] + dir[0], e.2[1] + dir[1]];
        }
    }
    let mut nodes: Vec<(usize, NodeSum)> = acc.into_iter().collect();
    nodes.sort_by(|x, y| x.1 .0.total_cmp(&y.1 .0).then(x.0.cmp(&y.0)));
    let unit = |v: [f64; 2]| {
        let l = v[0].hypot(v[1]);
        if l > 0.0 {
            [v[0] / l, v[1] / l]
        } else {
            v
        }
    };
    Some(Face {
        index: nodes.iter().enumerate().map(|(j, (n, _))| (*n, j)).collect(),
        s: nodes.iter().map(|(_, v)| v.0).collect(),
        tributary: nodes.iter().map(|(_, v)| v.1).collect(),
        tangent: nodes.iter().map(|(_, v)| unit(v.2)).collect(),
        nodes: nodes.into_iter().map(|(n, _)| n).collect(),
    })
}

/// Per node of the face: the contact force it receives and its closed and slipping
/// contributors.
struct Gathered {
    force: Vec<[f64; 2]>,
    closed: Vec<usize>,
    slipping: Vec<usize>,
    first_pass_force: f64,
    second_pass_force: f64,
}

fn gather(model: &Model, passes: &Passes, face: &Face, contact: &[ContactPointRecord]) -> Gathered {
    let n = face.nodes.len();
    let mut g = Gathered {
        force: vec![[0.0; 2]; n],
        closed: vec![0; n],
        slipping: vec![0; n],
        first_pass_force: 0.0,
        second_pass_force: 0.0,
    };
    let Master::Face { segments, .. } = &model.contacts[passes.first].master else {
        return g;
    };
    let slaves2 = &model.contacts[passes.second].slaves;
    let add = |g: &mut Gathered, node: usize, share: f64, f: [f64; 2], state: ContactState| {
        let Some(&j) = face.index.get(&node) else { return };
        g.force[j] = [g.force[j][0] + share * f[0], g.force[j][1] + share * f[1]];
        if share.abs() > 0.0 {
            g.closed[j] += 1;
            g.slipping[j] += usize::from(state == ContactState::Slip);
        }
    };
    for c in contact {
        let Some(f) = slave_force(c) else { continue };
        if c.pair == passes.second {
            let Some(Slave::Node(node)) = slaves2.get(c.slave) else {
                continue;
            };
            g.second_pass_force += c.normal_force;
            add(&mut g, *node, 1.0, f, c.state);
        } else if c.pair == passes.first {
            let Some(&[a, b]) = c.segment.and_then(|k| segments.get(k)) else {
                continue;
            };
            g.first_pass_force += c.normal_force;
            let xi = c.xi.clamp(-1.0, 1.0);
            add(&mut g, a, -0.5 * (1.0 - xi), f, c.state);
            add(&mut g, b, -0.5 * (1.0 + xi), f, c.state);
        }
    }
    g
}

/// The interfaces of `model` (whose [`InterfaceLayout`] is `layout`) at the converged state
/// `u`, load level `t`, from its contact point records.
pub fn interfaces(
    layout: &InterfaceLayout,
    model: &Model,
    u: &[f64],
    t: f64,
    increment: usize,
    contact: &[ContactPointRecord],
) -> Vec<InterfaceRecord> {
    let at = |n: usize| [model.nodes[n][0] + u[2 * n], model.nodes[n][1] + u[2 * n + 1]];
    (layout.interfaces.iter())
        .filter_map(|passes| {
            let face = face(model, u, t, passes.first)?;
            let g = gather(model, passes, &face, contact);
            // outward normal of a face with its body on the left: the tangent turned by −90°
            let normal: Vec<[f64; 2]> = face.tangent.iter().map(|d| [d[1], -d[0]]).collect();
            let per_length = |j: usize, v: f64| {
                if face.tributary[j] > 0.0 {
                    v / face.tributary[j]
                } else {
                    f64::NAN
                }
            };
            let fn_: Vec<f64> = (0..face.nodes.len())
                .map(|j| -(g.force[j][0] * normal[j][0] + g.force[j][1] * normal[j][1]))
                .collect();
            let state = (0..face.nodes.len())
                .map(|j| match (g.closed[j], g.slipping[j]) {
                    (0, _) => ContactState::Open,
                    (c, s) if c == s => ContactState::Slip,
                    _ => ContactState::Stick,
                })
                .collect();
            Some(InterfaceRecord {
                increment,
                t,
                name: model.contacts[passes.first].name.clone(),
                first_pass: passes.first,
                second_pass: passes.second,
                first_pass_force: g.first_pass_force,
                second_pass_force: g.second_pass_force,
                normal_force: fn_.iter().sum(),
                position: face.nodes.iter().map(|&n| at(n)).collect(),
                pressure: (0..face.nodes.len()).map(|j| per_length(j, fn_[j])).collect(),
                shear: (0..face.nodes.len())
                    .map(|j| {
                        let f = g.force[j];
                        per_length(j, f[0] * face.tangent[j][0] + f[1] * face.tangent[j][1])
                    })
                    .collect(),
                normal,
                state,
                node: face.nodes,
                s: face.s,
                tributary: face.tributary,
            })
        })
        .collect()
}
