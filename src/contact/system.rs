//! The contact state of a whole model: per contact pair and slave point, the history of the
//! last converged increment and the evaluation at the current iterate. It locates each
//! slave, builds the local [`PointProblem`] (slots = the nodes the point couples), and hands
//! local residuals and tangents to the caller's assembler — it never sees global equation
//! numbers.

pub use super::config::Config;
use super::config::SegNodes;
use super::events::{crossing_event, CrossingEvent, PointSnapshot};
pub use super::history::{Decision, PointHistory, PointNow};
use super::law::ContactState;
use super::pairing::{self, Pairing};
use super::point::{Closed, Multiplier, Path, PointProblem, SegSource, SlaveSource, MAX_NODES};
use super::search::SegmentGrid;
use super::transfer::StoredTraction;
use crate::model::{ContactPair, Enforcement, Model, Slave, Smoothing};

/// Contact state of all pairs.
#[derive(Debug, Clone, Default)]
pub struct ContactSystem {
    pub committed: Vec<Vec<PointHistory>>,
    pub current: Vec<Vec<PointNow>>,
    /// Pairing of every point at the current iterate.
    pub pairings: Vec<Vec<Pairing>>,
    /// Search grid of each pair for points not yet tracked (built once per increment).
    grids: Vec<Option<SegmentGrid>>,
    /// Decisions held fixed by the solver for the rest of the increment (chattering
    /// points): the segment and the open/closed decision are kept (the kernel's `forced`
    /// state); stick or slip is still decided by the return mapping.
    frozen: Vec<Vec<Option<Decision>>>,
    /// Points whose stick is held for the first correction of an attempt (see
    /// [`super::point::PointProblem::stick_held`]); released with the frozen ones.
    stick_held: Vec<Vec<bool>>,
    /// Verification of frozen points: their states are free again, their segments are kept
    /// where the projection is still (to 1 %) on the segment.
    verifying: bool,
    /// Augmented-Lagrangian multipliers of every point (zero, and unused, in penalty pairs;
    /// see [`super::augmented`]).
    pub(super) multipliers: Vec<Vec<Multiplier>>,
    /// Points found at the last pairing to have passed through their master (see
    /// [`Self::tunnelled`]), as `(pair, slave)`.
    tunnelled: Vec<(usize, usize)>,
}

/// Receives the local residual and tangent of one contact point: `(nodes, r, k)`.
pub type LocalSink<'a> = dyn FnMut(&[usize], &[f64], &[f64], f64) + 'a;

/// Local node slots of one contact point (at most [`MAX_NODES`], kept on the stack: the
/// contact evaluation allocates nothing per point and iteration).
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

/// The local problem of one slave point on segment `b`, with the history `(stored, A, path)`
/// of a point that was closed at the last converged increment; returns it with the global
/// nodes of its slots.
pub(super) fn local_problem(
    cfg: &Config,
    pair: &ContactPair,
    slave: Slave,
    b: usize,
    closed: Option<(StoredTraction, usize, Path, Option<f64>)>,
) -> (PointProblem, Slots) {
    let mut slots = Slots {
        ids: [0; MAX_NODES],
        len: 0,
    };
    let slave_src = match slave {
        Slave::Node(n) => SlaveSource::Node(slots.slot(n)),
        Slave::RigidPoint(_) | Slave::RigidVertex(..) => SlaveSource::Fixed(cfg.slave_pos(slave)),
    };
    let seg_b = slots.source(cfg, pair, b);
    let closed = closed.map(|(stored, a, path, touch_gap)| Closed {
        stored,
        seg_a: slots.source(cfg, pair, a),
        path,
        touch_gap,
    });
    let mut x = [[0.0; 2]; MAX_NODES];
    for (i, &n) in slots.nodes().iter().enumerate() {
        x[i] = cfg.node(n);
    }
    let problem = PointProblem {
        law: pair.law,
        scheme: pair.transfer,
        x,
        n_nodes: slots.len,
        slave: slave_src,
        seg_b,
        closed,
        forced: None,
        stick_held: false,
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
        let current = model
            .contacts
            .iter()
            .map(|p| vec![PointNow::default(); p.slaves.len()])
            .collect();
        let pairings = model
            .contacts
            .iter()
            .map(|p| vec![Pairing::default(); p.slaves.len()])
            .collect();
        let frozen = model.contacts.iter().map(|p| vec![None; p.slaves.len()]).collect();
        let stick_held = model.contacts.iter().map(|p| vec![false; p.slaves.len()]).collect();
        let multipliers = (model.contacts.iter())
            .map(|p| vec![Multiplier::default(); p.slaves.len()])
            .collect();
        ContactSystem {
            committed,
            current,
            pairings,
            grids: vec![None; model.contacts.len()],
            frozen,
            stick_held,
            verifying: false,
            multipliers,
            tunnelled: Vec::new(),
        }
    }

    /// Forget the current iterate (at the start of an attempt at an increment); the search
    /// grids are rebuilt once for the new increment.
    pub fn reset_current(&mut self) {
        for pair in &mut self.current {
            pair.iter_mut().for_each(|p| *p = PointNow::default());
        }
        self.grids.iter_mut().for_each(|g| *g = None);
        self.unfreeze();
    }

    /// Release every frozen point.
    pub fn unfreeze(&mut self) {
        self.frozen.iter_mut().flatten().for_each(|f| *f = None);
        self.stick_held.iter_mut().flatten().for_each(|f| *f = false);
        self.verifying = false;
    }

    /// Start verifying the frozen points: states decided by the data again, segments kept
    /// where the point still projects onto them or onto their extension by
    /// [`pairing::HELD_EXTENSION`] (a point at a kink of the master has two admissible
    /// closest points, or none; the held one is as admissible as the walk's).
    pub fn verify_frozen(&mut self) {
        self.verifying = true;
    }

    /// Whether the contact forces of the current iterate derive from a potential: every
    /// closed point sticks or is frictionless (a slipping frictional point is not
    /// conservative, and the slope of an energy along a correction means nothing there).
    pub fn conservative(&self, model: &Model) -> bool {
        self.current.iter().zip(&model.contacts).all(|(pts, pair)| {
            pair.law.mu == 0.0 || pts.iter().all(|p| p.eval.is_none_or(|e| e.state != ContactState::Slip))
        })
    }

    /// Number of frozen points (and points whose stick is held).
    pub fn frozen_count(&self) -> usize {
        let held = self.frozen.iter().flatten().zip(self.stick_held.iter().flatten());
        held.filter(|(f, s)| f.is_some() || **s).count()
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

    /// Hold the `flat`-th point at `frozen` for the rest of the increment.
    pub fn freeze(&mut self, flat: usize, frozen: Decision) {
        let (ip, is) = self.point_index(flat);
        self.frozen[ip][is] = Some(frozen);
    }

    /// Number of points whose stick is held.
    pub fn stick_held_count(&self) -> usize {
        self.stick_held.iter().flatten().filter(|s| **s).count()
    }

    /// Hold the `flat`-th point in stick (see [`super::point::PointProblem::stick_held`]).
    pub fn hold_stick(&mut self, flat: usize) {
        let (ip, is) = self.point_index(flat);
        self.stick_held[ip][is] = true;
    }

    /// Release the `flat`-th point (see [`Self::freeze`], [`Self::hold_stick`]).
    pub fn release(&mut self, flat: usize) {
        let (ip, is) = self.point_index(flat);
        self.frozen[ip][is] = None;
        self.stick_held[ip][is] = false;
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
    }

    /// Number of slave points over all pairs.
    pub fn signature_len(&self) -> usize {
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
                let shift = self.multipliers[ip][is].normal / pair.law.eps_n;
                self.pairings[ip][is] = pairing::locate(cfg, pair, slave, start, closed_before, grid, shift);
                if paired_before && self.pairings[ip][is].beyond_reach_inside {
                    self.tunnelled.push((ip, is));
                }
            }
        }
        let committed = &self.committed;
        pairing::exclude_owned_vertices(cfg, &mut self.pairings, &|ip, is| {
            (committed[ip][is].segment, committed[ip][is].closed)
        });
        for (ip, pair) in cfg.model.contacts.iter().enumerate() {
            for (is, &slave) in pair.slaves.iter().enumerate() {
                if let Some(f) = self.frozen[ip][is] {
                    let held = pairing::held(cfg, pair, slave, f.segment);
                    let admissible = held.pinned
                        || held
                            .located
                            .is_some_and(|l| l.xi.abs() <= 1.0 + pairing::HELD_EXTENSION);
                    if !self.verifying || admissible {
                        self.pairings[ip][is] = held;
                    }
                }
            }
        }
    }

    /// The points that, at the last pairing, were found deeper inside their master than the
    /// search radius although they were paired (within reach) at the previous iterate: they
    /// passed through it in one step. Unpaired, they would carry no force, and a body could
    /// go on through a rigid outline or another body with no residual to say so; the solver
    /// takes such a step as inadmissible (`solver::newton`).
    pub fn tunnelled(&self) -> &[(usize, usize)] {
        &self.tunnelled
    }

    /// Pair, then evaluate every paired slave point; for each closed point call
    /// `assemble(nodes, r, k)` with its local residual (`2·nodes.len()`) and tangent.
    pub fn evaluate(&mut self, cfg: &Config, assemble: &mut LocalSink) {
        self.pair(cfg);
        let mut r = [0.0; 2 * MAX_NODES];
        let mut k = [0.0; 4 * MAX_NODES * MAX_NODES];
        for (ip, pair) in cfg.model.contacts.iter().enumerate() {
            for (is, &slave) in pair.slaves.iter().enumerate() {
                let hist = self.committed[ip][is];
                let paired = self.pairings[ip][is];
                let now = &mut self.current[ip][is];
                *now = PointNow {
                    segment: paired.segment,
                    ..PointNow::default()
                };
                let Some(loc) = paired.located else { continue };
                let touch = !hist.closed && hist.gap.is_finite() && pair.law.mu > 0.0;
                let closed = match (hist.closed || touch, hist.segment) {
                    (true, Some(a)) => {
                        now.path = path_between(cfg, pair, a, loc.segment);
                        Some((stored(&hist), a, now.path, touch.then_some(hist.gap)))
                    }
                    _ => None,
                };
                let (mut problem, slots) = local_problem(cfg, pair, slave, loc.segment, closed);
                if !self.verifying {
                    problem.forced = self.frozen[ip][is].map(|f| f.state);
                    problem.stick_held = self.stick_held[ip][is];
                }
                problem.at_vertex = paired.pinned.then_some(loc.xi.signum());
                if matches!(pair.enforcement, Enforcement::Augmented { .. }) {
                    problem.multiplier = Some(self.multipliers[ip][is]);
                }
                let nd = 2 * slots.len;
                let e = problem.residual_tangent(&mut r[..nd], &mut k[..nd * nd]);
                now.eval = Some(e);
                if e.state != ContactState::Open && nd > 0 {
                    assemble(slots.nodes(), &r[..nd], &k[..nd * nd], problem.fixed_coordinate_scale());
                }
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
        self.evaluate(cfg, &mut |_, _, _, _| {});
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
                        h.a11 = e.proj.a11;
                        h.store_spatial(cfg.slave_pos(pair.slaves[is]), &e);
                    }
                    Some(e) => {
                        // paired but open: where it is, for the first touch (a point resting
                        // on the master to the precision of the geometry touches already)
                        h.closed = false;
                        h.stuck = false;
                        h.t1 = 0.0;
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
