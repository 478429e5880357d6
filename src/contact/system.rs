//! The contact state of a whole model: per contact pair and slave point, the history of the
//! last converged increment and the evaluation at the current iterate. It locates each
//! slave, builds the local [`PointProblem`] (slots = the nodes the point couples), and hands
//! local residuals and tangents to the caller's assembler — it never sees global equation
//! numbers.

pub use super::config::Config;
use super::config::SegNodes;
use super::decision::{Forces, Kink, Rule};
use super::events::{crossing_event, CrossingEvent, PointSnapshot};
pub use super::history::{Decision, PointHistory, PointNow};
use super::law::ContactState;
use super::pairing::{self, Pairing};
use super::point::{
    Closed, Linearization, Multiplier, Path, PointEval, PointProblem, SegSource, SlaveSource, MAX_NODES,
};
use super::search::SegmentGrid;
use super::transfer::StoredTraction;
use crate::contact3d::system::SurfaceSystem;
use crate::model::{ContactPair, Enforcement, Master, Model, Slave, Smoothing};

mod unknowns;
pub use unknowns::RestingForces;

/// Contact state of all pairs.
#[derive(Debug, Clone, Default)]
pub struct ContactSystem {
    pub committed: Vec<Vec<PointHistory>>,
    pub current: Vec<Vec<PointNow>>,
    /// Pairing of every point at the current iterate.
    pub pairings: Vec<Vec<Pairing>>,
    /// Search grid of each pair for points not yet tracked (built once per increment).
    grids: Vec<Option<SegmentGrid>>,
    /// The force unknowns of Newton's iterate per point (see [`super::decision`]), those it
    /// started the last correction from, and those at the correction's full step.
    forces: Vec<Vec<Forces>>,
    forces_base: Vec<Vec<Forces>>,
    forces_step: Vec<Vec<Forces>>,
    /// Each point's local nodes and penalty linearisation at the last evaluation (`None`
    /// where it was not evaluated), for the update of its force unknowns (of the closed
    /// points) and the choice of the kink's side (of the open ones).
    lin: Vec<Vec<Option<(Slots, Linearization)>>>,
    /// The weights `ρ_N, ρ_T` of each pair's augmented forces (1: the penalty rule).
    weights: Vec<(f64, f64)>,
    /// Every point decided by the penalty rule (the check of a converged iterate).
    penalty_rule: bool,
    /// Which side of the normal kink touching points take ([`Kink`]); with `resting_some`,
    /// [`Kink::Resting`] only for the points marked in `resting`.
    kink: Kink,
    resting_some: bool,
    resting: Vec<Vec<bool>>,
    /// Decide the points closed at the last converged increment by their force unknowns
    /// alone (the first iterate of an attempt).
    warm: bool,
    /// `Σ C²` of the complementarity residuals at the last evaluation.
    complementarity2: f64,
    /// The evaluation of the iterate a line search starts from (its trials are paired
    /// against it, not against a rejected trial).
    current_base: Vec<Vec<PointNow>>,
    /// Per point, the segment it left at its last change of segment in this attempt (a
    /// return to it is a crossing back: see [`Self::pair`]).
    left: Vec<Vec<Option<usize>>>,
    /// Augmented-Lagrangian multipliers of every point (zero, and unused, in penalty pairs;
    /// see [`super::augmented`]).
    pub(super) multipliers: Vec<Vec<Multiplier>>,
    /// Points found at the last pairing to have passed through their master (see
    /// [`Self::tunnelled`]), as `(pair, slave)`.
    tunnelled: Vec<(usize, usize)>,
    /// The 3D (node-to-surface) pairs: empty in 2D (see [`crate::contact3d::system`]).
    pub surface: SurfaceSystem,
}

/// Receives one contact point's local contributions: its global DOFs, the residual of the penalty
/// forces, the residual of the force unknowns, the tangent, and per local DOF the weight of
/// its coordinate in the round-off of the residual: the slot's position about the point's
/// own origin (or the fixed geometry's entering the gap where that is larger: see
/// [`PointProblem::fixed_coordinate_scale`]) times the weight `ρ` of the complementarity
/// residual through which the penalty force's round-off reaches Newton's residual.
pub type LocalSink<'a> = dyn FnMut(&[usize], &[f64], &[f64], &[f64], &[f64]) + 'a;

/// Local node slots of one contact point (at most [`MAX_NODES`], kept on the stack: the
/// contact evaluation allocates nothing per point and iteration).
#[derive(Debug, Clone, Copy)]
pub(super) struct Slots {
    ids: [usize; MAX_NODES],
    len: usize,
}

impl Slots {
    /// The global nodes of the slots, in slot order.
    pub(super) fn nodes(&self) -> &[usize] {
        &self.ids[..self.len]
    }
    fn slot(&mut self, n: usize) -> usize {
        if let Some(i) = self.nodes().iter().position(|&m| m == n) {
            return i;
        }
        self.ids[self.len] = n;
        self.len += 1;
        self.len - 1
    }
    fn source(&mut self, cfg: &Config, pair: &ContactPair, k: usize) -> SegSource {
        match cfg.seg_nodes(pair, k) {
            SegNodes::Linear([a, b]) => SegSource::Face([self.slot(a), self.slot(b)]),
            SegNodes::Smooth(kind, nodes) => {
                let slots = nodes.map(|n| n.map(|n| self.slot(n)));
                match kind {
                    Smoothing::Bezier => SegSource::Bezier(slots),
                    _ => SegSource::Hermite(slots),
                }
            }
            SegNodes::Rigid(p, o) => SegSource::Rigid(p, o),
        }
    }
}

pub(super) fn stored(h: &PointHistory) -> StoredTraction {
    StoredTraction {
        xi: h.xi,
        t1: h.t1,
        a11: h.a11,
        slave: h.slave,
        tangent: h.tangent,
    }
}

/// The local problem of slave point `is` of the pair on segment `b` (its law:
/// [`ContactPair::law_of`], the pair's penalties times the point's weight), with the history `(stored, A, path)`
/// of a point that was closed at the last converged increment; returns it with the global
/// nodes of its slots.
///
/// Positions are taken about the slave's reference position (its own origin): gaps and
/// convective coordinates are differences of nearby points, and a model placed far from
/// the coordinate origin (or moved there) then computes them from the same digits — its
/// convergence and its round-off floor do not depend on where it sits.
pub(super) fn local_problem(
    cfg: &Config,
    pair: &ContactPair,
    is: usize,
    b: usize,
    closed: Option<(StoredTraction, usize, Path, Option<f64>)>,
) -> (PointProblem, Slots) {
    let slave = pair.slaves[is];
    let mut slots = Slots {
        ids: [0; MAX_NODES],
        len: 0,
    };
    let origin = cfg.slave_origin(slave);
    let about = |p: [f64; 2]| [p[0] - origin[0], p[1] - origin[1]];
    let shift = |src: SegSource| match src {
        SegSource::Rigid(piece, o) => SegSource::Rigid(piece, about(o)),
        other => other,
    };
    let slave_src = match slave {
        Slave::Node(n) => SlaveSource::Node(slots.slot(n)),
        Slave::RigidPoint(_) | Slave::RigidVertex(..) => SlaveSource::Fixed(cfg.slave_pos_about(slave, origin)),
    };
    let seg_b = shift(slots.source(cfg, pair, b));
    let closed = closed.map(|(stored, a, path, touch_gap)| Closed {
        stored: StoredTraction {
            slave: about(stored.slave),
            ..stored
        },
        seg_a: shift(slots.source(cfg, pair, a)),
        path,
        touch_gap,
    });
    let mut x = [[0.0; 2]; MAX_NODES];
    for (i, &n) in slots.nodes().iter().enumerate() {
        x[i] = cfg.node_about(n, origin);
    }
    let problem = PointProblem {
        law: pair.law_of(is),
        scheme: pair.transfer,
        x,
        n_nodes: slots.len,
        slave: slave_src,
        seg_b,
        closed,
        rule: Rule::Penalty,
        kink: super::decision::Kink::Open,
        warm: false,
        at_vertex: None,
        multiplier: None,
    };
    (problem, slots)
}

/// Path from `a` to `b` along the chain (direction and length of the segments between).
fn path_between(cfg: &Config, pair: &ContactPair, a: usize, b: usize) -> Path {
    if a == b {
        return Path {
            direction: 0,
            between: 0.0,
        };
    }
    for (dir, pick) in [(1i8, 1usize), (-1, 0)] {
        let mut k = a;
        let mut between = 0.0;
        for _ in 0..pair.master.segment_count() {
            let nb = pair.master.neighbours(k);
            let Some(n) = (if pick == 1 { nb.1 } else { nb.0 }) else {
                break;
            };
            if n == b {
                return Path {
                    direction: dir,
                    between,
                };
            }
            between += cfg.segment(pair, n).length();
            k = n;
        }
    }
    Path {
        direction: 1,
        between: 0.0,
    }
}

impl ContactSystem {
    pub fn new(model: &Model) -> Self {
        let committed: Vec<Vec<PointHistory>> = model
            .contacts
            .iter()
            .map(|p| vec![PointHistory::default(); p.slaves.len()])
            .collect();
        let current: Vec<Vec<PointNow>> = model
            .contacts
            .iter()
            .map(|p| vec![PointNow::default(); p.slaves.len()])
            .collect();
        let pairings = model
            .contacts
            .iter()
            .map(|p| vec![Pairing::default(); p.slaves.len()])
            .collect();
        let per_point =
            |f: Forces| -> Vec<Vec<Forces>> { model.contacts.iter().map(|p| vec![f; p.slaves.len()]).collect() };
        let multipliers = (model.contacts.iter())
            .map(|p| vec![Multiplier::default(); p.slaves.len()])
            .collect();
        ContactSystem {
            committed,
            current: current.clone(),
            pairings,
            grids: vec![None; model.contacts.len()],
            forces: per_point(Forces::default()),
            forces_base: per_point(Forces::default()),
            forces_step: per_point(Forces::default()),
            lin: model.contacts.iter().map(|p| vec![None; p.slaves.len()]).collect(),
            weights: model.contacts.iter().map(|p| augmented_weights(model, p)).collect(),
            penalty_rule: false,
            kink: Kink::Open,
            resting_some: false,
            resting: model.contacts.iter().map(|p| vec![false; p.slaves.len()]).collect(),
            warm: false,
            complementarity2: 0.0,
            current_base: current,
            left: model.contacts.iter().map(|p| vec![None; p.slaves.len()]).collect(),
            multipliers,
            tunnelled: Vec::new(),
            surface: SurfaceSystem::default(),
        }
    }

    /// The contact state of a model of either dimension: its 2D pairs and its 3D ones.
    pub fn of<S: crate::model::Dim>(model: &crate::model::Model<S>) -> Self {
        ContactSystem {
            surface: SurfaceSystem::new(S::solid(model)),
            ..ContactSystem::new(S::plane(model))
        }
    }

    /// `(pair, slave)` of the `flat`-th point in [`Self::signature`] order.
    pub fn point_index(&self, flat: usize) -> (usize, usize) {
        let mut k = flat;
        for (ip, pts) in self.current.iter().enumerate() {
            if k < pts.len() {
                return (ip, k);
            }
            k -= pts.len();
        }
        panic!("point {flat} out of range")
    }

    /// `(state, segment)` of every point at the current iterate, written into `out`
    /// (active-set changes; the order is pairs, then slaves).
    pub fn signature_into(&self, out: &mut Vec<Decision>) {
        out.clear();
        // the segment an open point is tracked on changes nothing in the residual
        out.extend(self.current.iter().flatten().map(|p| {
            let state = p.eval.map_or(ContactState::Open, |e| e.state);
            Decision {
                state,
                segment: p.segment.filter(|_| state != ContactState::Open),
            }
        }));
        self.surface.signature_into(out);
    }

    /// Number of slave points over all pairs (the 2D pairs' first, as in
    /// [`Self::signature_into`]).
    pub fn signature_len(&self) -> usize {
        self.current.iter().map(Vec::len).sum::<usize>() + self.surface.len()
    }

    /// Number of slave points of the 2D pairs (the first in [`Self::signature_into`];
    /// [`Self::point_index`] and [`Self::xi`] take these).
    pub fn plane_len(&self) -> usize {
        self.current.iter().map(Vec::len).sum()
    }

    /// `ξ` of the `flat`-th point at the current iterate (NaN when unpaired).
    pub fn xi(&self, flat: usize) -> f64 {
        let (ip, is) = self.point_index(flat);
        self.current[ip][is].eval.map_or(f64::NAN, |e| e.proj.xi)
    }

    /// Pairing step: locate every slave point of every pair (tracking, search, vertex
    /// rules; see [`super::pairing`]) before any kernel runs.
    pub fn pair(&mut self, cfg: &Config) {
        self.tunnelled.clear();
        for (ip, pair) in cfg.model.contacts.iter().enumerate() {
            let grid = &mut self.grids[ip];
            for (is, &slave) in pair.slaves.iter().enumerate() {
                let now = &self.current[ip][is];
                let hist = &self.committed[ip][is];
                let start = now.segment.or(hist.segment);
                // paired (within reach, open or closed) at the previous iterate of this
                // attempt, or (at its first iterate) at the last converged increment
                let paired_before = match (now.segment, now.eval) {
                    (None, None) => hist.within_reach,
                    (_, e) => e.is_some(),
                };
                // closed at the previous iterate of this attempt, or (at its first iterate) at
                // the last converged increment
                let closed_before = match (now.segment, now.eval) {
                    (None, None) => self.committed[ip][is].closed,
                    (_, e) => e.is_some_and(|e| e.state != ContactState::Open),
                };
                // an augmented point is closed while `λ_N − ε_N ζ > 0`: the rules see that gap
                let shift = self.multipliers[ip][is].normal / pair.law_of(is).eps_n;
                let mut paired = pairing::locate(cfg, pair, slave, start, closed_before, grid, shift);
                if let (true, Some(before), Some(after)) = (closed_before, now.segment, paired.segment) {
                    if after != before {
                        let left = &mut self.left[ip][is];
                        paired = crossing_back(cfg, pair, slave, left, (before, after)).unwrap_or(paired);
                    }
                }
                self.pairings[ip][is] = paired;
                if paired_before && paired.beyond_reach_inside {
                    self.tunnelled.push((ip, is));
                }
            }
        }
        let committed = &self.committed;
        pairing::exclude_owned_vertices(cfg, &mut self.pairings, &|ip, is| {
            (committed[ip][is].segment, committed[ip][is].closed)
        });
    }

    /// Points closed at the current iterate whose projection lies on an extension of their
    /// segment (`|ξ| > 1` beyond round-off; see [`Self::crossing_back`]).
    pub fn on_extensions(&self) -> usize {
        let beyond =
            |e: &PointEval<f64>| e.state != ContactState::Open && e.proj.xi.abs() > 1.0 + super::search::XI_TOL;
        self.current
            .iter()
            .flatten()
            .filter(|p| p.eval.as_ref().is_some_and(beyond))
            .count()
    }

    /// The points that, at the last pairing, were found deeper inside their master than the
    /// search radius although they were paired (within reach) at the previous iterate: they
    /// passed through it in one step. Unpaired, they would carry no force, and a body could
    /// go on through a rigid outline or another body with no residual to say so; the solver
    /// takes such a step as inadmissible (`solver::newton`).
    pub fn tunnelled(&self) -> &[(usize, usize)] {
        &self.tunnelled
    }

    /// Pair, then evaluate every paired slave point, its state decided by its rule (the
    /// augmented forces, or the penalty rule: [`Self::use_penalty_rule`]); hand each point
    /// that carries a force, penalty or unknown, to `assemble` (see [`LocalSink`]).
    pub fn evaluate(&mut self, cfg: &Config, assemble: &mut LocalSink) {
        self.pair(cfg);
        let mut r = [0.0; 2 * MAX_NODES];
        let mut r_eq = [0.0; 2 * MAX_NODES];
        let mut k = [0.0; 4 * MAX_NODES * MAX_NODES];
        self.complementarity2 = 0.0;
        for (ip, pair) in cfg.model.contacts.iter().enumerate() {
            let (rho_n, rho_t) = self.weights[ip];
            for (is, &slave) in pair.slaves.iter().enumerate() {
                let hist = self.committed[ip][is];
                let paired = self.pairings[ip][is];
                let forces = self.forces[ip][is];
                let now = &mut self.current[ip][is];
                *now = PointNow {
                    segment: paired.segment,
                    ..PointNow::default()
                };
                self.lin[ip][is] = None;
                let Some(loc) = paired.located else {
                    // out of reach: no force can act; its unknowns go to zero
                    self.complementarity2 += forces.normal.powi(2) + forces.tangential.powi(2);
                    continue;
                };
                let touch = !hist.closed && hist.gap.is_finite() && pair.law.mu > 0.0;
                let closed = match (hist.closed || touch, hist.segment) {
                    (true, Some(a)) => {
                        now.path = path_between(cfg, pair, a, loc.segment);
                        Some((stored(&hist), a, now.path, touch.then_some(hist.gap)))
                    }
                    _ => None,
                };
                let (mut problem, slots) = local_problem(cfg, pair, is, loc.segment, closed);
                problem.rule = match self.penalty_rule {
                    true => Rule::Penalty,
                    false => Rule::AlartCurnier { forces, rho_n, rho_t },
                };
                problem.kink = match self.resting_some && !self.resting[ip][is] {
                    true => Kink::Open,
                    false => self.kink,
                };
                // the first iterate's active set is the converged one where there is one
                problem.warm = self.warm && hist.closed;
                problem.at_vertex = paired.pinned.then_some(loc.xi.signum());
                if matches!(pair.enforcement, Enforcement::Augmented { .. }) {
                    problem.multiplier = Some(self.multipliers[ip][is]);
                }
                let nd = 2 * slots.len;
                let mut lin = Linearization::default();
                let mut e = problem.local(&mut r[..nd], &mut r_eq[..nd], &mut k[..nd * nd], &mut lin);
                // the kernel computed about the slave's origin: the contact point in the
                // model's coordinates again
                let origin = cfg.slave_origin(slave);
                e.proj.rho = [e.proj.rho[0] + origin[0], e.proj.rho[1] + origin[1]];
                now.eval = Some(e);
                self.complementarity2 += e.complementarity[0].powi(2) + e.complementarity[1].powi(2);
                let carries = e.state != ContactState::Open || forces != Forces::default();
                if carries {
                    now.force = super::history::slave_force(matches!(slave, Slave::Node(_)), &r_eq[..nd]);
                }
                if carries && nd > 0 {
                    // the penalty force's round-off (ε ε_mach |x|) enters the residual Newton
                    // is judged by through the complementarity residual, weighted by ρ
                    let rho = if self.penalty_rule { 1.0 } else { rho_n.max(rho_t) };
                    let scale = problem.fixed_coordinate_scale();
                    let weights: [f64; 2 * MAX_NODES] = std::array::from_fn(|j| match j < nd {
                        true => rho * problem.x[j / 2][j % 2].abs().max(scale),
                        false => 0.0,
                    });
                    let dofs: [usize; 2 * MAX_NODES] = std::array::from_fn(|j| match j < nd {
                        true => 2 * slots.nodes()[j / 2] + j % 2,
                        false => 0,
                    });
                    assemble(&dofs[..nd], &r[..nd], &r_eq[..nd], &k[..nd * nd], &weights[..nd]);
                }
                self.lin[ip][is] = Some((slots, lin));
            }
        }
    }

    /// Take the initial configuration (`cfg` at `u = 0`, `t = 0`) as the converged state the
    /// first increment starts from: every point within reach of its master is tracked on
    /// its segment and keeps where it is, as at any converged increment. A point that
    /// touches at the start (a block resting on a floor, a sheet lying on a facet) then
    /// has its stick anchor where it rests, so friction holds it from the first increment
    /// (without it, a block on an incline under its weight slides freely in that increment
    /// and the tangent is singular); and a point driven through its master in the first
    /// increment is found on the far side, not lost (see [`Self::tunnelled`]).
    pub fn start_from_initial_configuration(&mut self, cfg: &Config) {
        self.evaluate(cfg, &mut |_, _, _, _, _| {});
        self.commit(cfg);
        self.reset_current();
        self.tunnelled.clear();
    }

    /// Accept the current iterate as converged; returns the crossing events of this increment.
    pub fn commit(&mut self, cfg: &Config) -> Vec<CrossingEvent> {
        let mut events = Vec::new();
        for (ip, pair) in cfg.model.contacts.iter().enumerate() {
            for is in 0..pair.slaves.len() {
                let now = self.current[ip][is];
                let old = self.committed[ip][is];
                let h = &mut self.committed[ip][is];
                h.segment = now.segment;
                h.within_reach = now.eval.is_some();
                match now.eval {
                    Some(e) if e.state != ContactState::Open => {
                        if let (true, Some(a), Some(b)) = (old.closed, old.segment, now.segment) {
                            if a != b {
                                h.crossings += 1;
                                let m = matches!(pair.enforcement, Enforcement::Augmented { .. })
                                    .then_some(self.multipliers[ip][is]);
                                events.push(crossing_event(cfg, ip, is, a, b, &old, &e, now.path, m));
                            }
                        }
                        h.closed = true;
                        h.stuck = e.state == ContactState::Stick && pair.law.mu > 0.0;
                        h.gap = f64::NAN;
                        h.xi = e.proj.xi;
                        h.t1 = e.t1;
                        h.normal = e.normal_force;
                        h.a11 = e.proj.a11;
                        h.store_spatial(cfg.slave_pos(pair.slaves[is]), &e);
                    }
                    Some(e) => {
                        // paired but open: where it is, for the first touch (a point resting
                        // on the master to the precision of the geometry touches already)
                        h.closed = false;
                        h.stuck = false;
                        h.t1 = 0.0;
                        h.normal = 0.0;
                        h.xi = e.proj.xi;
                        h.a11 = e.proj.a11;
                        h.gap = if super::point::touching(e.proj.gap, e.proj.a11) {
                            0.0
                        } else {
                            e.proj.gap
                        };
                        h.store_spatial(cfg.slave_pos(pair.slaves[is]), &e);
                    }
                    None => {
                        h.closed = false;
                        h.stuck = false;
                        h.t1 = 0.0;
                        h.normal = 0.0;
                        h.gap = f64::NAN;
                    }
                }
                if matches!(pair.enforcement, Enforcement::Augmented { .. }) {
                    // the next increment starts from the converged normal force, and its
                    // tangential correction from the traction carried into it
                    let closed = now.eval.filter(|e| e.state != ContactState::Open);
                    self.multipliers[ip][is] = Multiplier {
                        normal: closed.map_or(0.0, |e| e.normal_force.max(0.0)),
                        tangential: 0.0,
                    };
                }
            }
        }
        events
    }

    /// Snapshot of every point at the current iterate (against the last converged increment).
    pub fn snapshots(&self, cfg: &Config) -> Vec<PointSnapshot> {
        let mut out = Vec::new();
        for (ip, pair) in cfg.model.contacts.iter().enumerate() {
            for (is, &slave) in pair.slaves.iter().enumerate() {
                let now = &self.current[ip][is];
                let hist = &self.committed[ip][is];
                let multiplier = self.multipliers[ip][is];
                out.push(PointSnapshot::new(cfg, (ip, is), slave, pair, now, hist, multiplier));
            }
        }
        out
    }
}

/// The weights `ρ = min(1, c/ε)` of a pair's augmented forces (see [`super::decision`]),
/// with `c` the smaller plane-strain modulus of the deformable bodies it joins: the
/// stiffness of the model's own scale against which a penalty is stiff or soft.
fn augmented_weights(model: &Model, pair: &ContactPair) -> (f64, f64) {
    let slaves = pair.slaves.iter().filter_map(|s| match s {
        Slave::Node(n) => Some(*n),
        _ => None,
    });
    let master = match pair.master {
        Master::Face { body, .. } => Some(body),
        _ => None,
    };
    let c = model.contact_stiffness(slaves, master);
    if !c.is_finite() {
        return (1.0, 1.0);
    }
    super::decision::weights(c, pair.law.eps_n, pair.law.eps_t)
}

/// A closed point that Newton moves from segment `before` back to `after`, the segment
/// it left at its last change in this attempt, keeps `before` while its projection stays
/// on it or its extension by [`pairing::HELD_EXTENSION`] (returns that pairing; `None`
/// when it moves on, and the change is noted). At a node of a faceted master the contact
/// normal jumps: the residual is no function of the positions there, and a point whose
/// equilibrium lies just past the node on either segment is carried back and forth
/// across it by every correction. On the extended segment the point has an equilibrium,
/// as in node-to-segment codes (Wriggers, Computational Contact Mechanics (2006) §9.1);
/// a converged point on an extension is reported ([`ContactSystem::on_extensions`]).
fn crossing_back(
    cfg: &Config,
    pair: &ContactPair,
    slave: Slave,
    left: &mut Option<usize>,
    (before, after): (usize, usize),
) -> Option<Pairing> {
    if *left == Some(after) {
        let held = pairing::held(cfg, pair, slave, Some(before));
        if held.pinned
            || held
                .located
                .is_some_and(|l| l.xi.abs() <= 1.0 + pairing::HELD_EXTENSION)
        {
            return Some(held);
        }
    }
    *left = Some(before);
    None
}
