//! The 3D contact state of a model: per node-to-surface pair ([`SurfacePair`]) and slave
//! node, the history of the last converged increment and the evaluation at the current
//! iterate. It pairs each slave with a facet of its master ([`locate`]), carries the
//! friction history onto a new facet by the pair's transfer scheme ([`super::transfer`]),
//! evaluates the point kernels ([`super::master`]) and hands their local residuals and
//! tangents to the caller's assembler by global DOF — as the 2D system does.
//!
//! Enforcement: the seed's penalty law, each point's state decided by its own trial
//! (closed while `ε_N ⟨−ζ⟩ > 0`, stick while the trial traction is inside Coulomb's cone):
//! the 3D points have no force unknowns of Newton's iterate yet (the 2D semismooth rule of
//! `contact::decision` is not carried over), so the complementarity residuals are zero and
//! Newton's merit is the equilibrium residual.

use super::master::{facet_point, plane_facet, slave_block, sphere_point};
use super::point::{History, PointEval, DOFS};
use super::projection::{project, INSIDE_TOLERANCE};
use super::search::{bounding_box, free_borders, past_free_border, FacetGrid, FREE_BORDER_HOLD};
use super::surface::Facet;
use super::transfer::transfer;
use crate::contact::law::ContactState;
use crate::contact::system::{Decision, LocalSink};
use crate::model::{Model, RigidSurfaceShape, Solid, SurfaceMaster, SurfacePair};

/// Node positions and time the 3D contact evaluation works on.
pub struct SurfaceConfig<'a> {
    pub model: &'a Model<Solid>,
    /// Full displacement vector (3 per node).
    pub u: &'a [f64],
    pub t: f64,
}

impl SurfaceConfig<'_> {
    /// Current position of node `n`.
    pub fn node(&self, n: usize) -> [f64; 3] {
        let x = self.model.nodes[n];
        std::array::from_fn(|c| x[c] + self.u[3 * n + c])
    }

    /// Current position of node `n` about `origin` (reference difference first).
    fn node_about(&self, n: usize, origin: [f64; 3]) -> [f64; 3] {
        let x = self.model.nodes[n];
        std::array::from_fn(|c| (x[c] - origin[c]) + self.u[3 * n + c])
    }

    fn facet_about(&self, nodes: &[usize; 4], origin: [f64; 3]) -> [[f64; 3]; 4] {
        nodes.map(|n| self.node_about(n, origin))
    }
}

/// A point's state at the last converged increment.
#[derive(Debug, Clone, Copy, Default)]
pub struct SurfaceHistory {
    /// The facet it was paired with (`None`: beyond reach; always `Some(0)` for a rigid
    /// master).
    pub facet: Option<usize>,
    pub closed: bool,
    /// `(ξ, T_α)` on `facet` of a closed point.
    pub history: Option<History>,
}

/// A point's evaluation at the current iterate.
#[derive(Debug, Clone, Copy, Default)]
pub struct SurfaceNow {
    pub facet: Option<usize>,
    pub eval: Option<PointEval<f64>>,
    /// The contact force on the slave node as assembled (`−r_s`).
    pub force: [f64; 3],
    /// The friction history could not be carried onto this facet from the last converged
    /// one ([`super::transfer::TransferError`]: the facets folded onto each other, or the old
    /// point not found on the new facet): the point starts it afresh, as a point closing now.
    pub history_lost: bool,
    /// The history carried onto `facet` from another one in this increment: where it was,
    /// and what it became (see [`Carried`]).
    pub carried: Option<Carried>,
}

/// A friction history carried from the facet of the last converged increment onto another
/// one (the seed's transfer across a master boundary, eqs. 2–4 on surfaces): the facet it
/// left, the history there (`ξ_A`, `T_α` on A) and the history on the new facet (`ξ_B`,
/// `T_α` on B) as the pair's scheme made it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Carried {
    pub from_facet: usize,
    pub from: History,
    pub to: History,
}

/// One point at a converged increment, for records, monitors and the equilibrium check.
#[derive(Debug, Clone, Copy)]
pub struct SurfaceSnapshot {
    pub pair: usize,
    pub slave: usize,
    pub node: usize,
    pub facet: Option<usize>,
    pub previous_facet: Option<usize>,
    pub eval: Option<PointEval<f64>>,
    pub force: [f64; 3],
    /// Closed now and at the last converged increment, on another facet.
    pub crossing: bool,
    /// See [`SurfaceNow::history_lost`].
    pub history_lost: bool,
    /// See [`SurfaceNow::carried`].
    pub carried: Option<Carried>,
}

/// The 3D contact state of all pairs.
#[derive(Debug, Clone, Default)]
pub struct SurfaceSystem {
    pub committed: Vec<Vec<SurfaceHistory>>,
    pub current: Vec<Vec<SurfaceNow>>,
    /// The iterate a line search starts from.
    base: Vec<Vec<SurfaceNow>>,
    grids: Vec<Option<FacetGrid>>,
    /// Per pair with a facet master, its facets' free border edges ([`free_borders`]).
    borders: Vec<Vec<[bool; 4]>>,
    /// Half-width of a rigid plane's fixed facet ([`plane_facet`]).
    plane_half: f64,
}

impl SurfaceSystem {
    /// The empty state of the pairs of `model` (none for a 2D model).
    pub fn new(model: Option<&Model<Solid>>) -> Self {
        let Some(model) = model else {
            return SurfaceSystem::default();
        };
        let per_point = |p: &SurfacePair| vec![SurfaceNow::default(); p.slaves.len()];
        let travel = (model.surface_contacts.iter())
            .filter_map(|p| match &p.master {
                SurfaceMaster::Rigid(r) => Some(
                    r.motion
                        .iter()
                        .flat_map(|m| m.knots.iter().map(|k| k.1.abs()))
                        .sum::<f64>(),
                ),
                SurfaceMaster::Facets { .. } => None,
            })
            .fold(0.0, f64::max);
        SurfaceSystem {
            committed: (model.surface_contacts.iter())
                .map(|p| vec![SurfaceHistory::default(); p.slaves.len()])
                .collect(),
            current: model.surface_contacts.iter().map(per_point).collect(),
            base: model.surface_contacts.iter().map(per_point).collect(),
            grids: vec![None; model.surface_contacts.len()],
            borders: (model.surface_contacts.iter())
                .map(|p| match &p.master {
                    SurfaceMaster::Facets { facets, .. } => free_borders(facets),
                    SurfaceMaster::Rigid(_) => vec![],
                })
                .collect(),
            plane_half: 4.0 * (model.size() + travel),
        }
    }

    /// Points over all pairs.
    pub fn len(&self) -> usize {
        self.current.iter().map(Vec::len).sum()
    }

    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// `(state, facet)` of every point at the current iterate, appended to `out`.
    pub fn signature_into(&self, out: &mut Vec<Decision>) {
        out.extend(self.current.iter().flatten().map(|p| {
            let state = p.eval.map_or(ContactState::Open, |e| e.state);
            Decision {
                state,
                segment: p.facet.filter(|_| state != ContactState::Open),
            }
        }));
    }

    /// Forget the current iterate (a new attempt at an increment): the search grids are
    /// rebuilt at its first evaluation.
    pub fn reset_current(&mut self) {
        self.current
            .iter_mut()
            .flatten()
            .for_each(|p| *p = SurfaceNow::default());
        self.grids.iter_mut().for_each(|g| *g = None);
    }

    /// Keep the current evaluation (the start of a correction).
    pub fn save_iterate(&mut self) {
        for (b, c) in self.base.iter_mut().zip(&self.current) {
            b.copy_from_slice(c);
        }
    }

    /// Go back to the evaluation kept by [`Self::save_iterate`].
    pub fn restore_iterate(&mut self) {
        for (c, b) in self.current.iter_mut().zip(&self.base) {
            c.copy_from_slice(b);
        }
    }

    /// Make this state's iterate `other`'s, without allocating.
    pub fn copy_iterate_from(&mut self, other: &SurfaceSystem) {
        for (t, f) in self.current.iter_mut().zip(&other.current) {
            t.copy_from_slice(f);
        }
        for (t, f) in self.base.iter_mut().zip(&other.base) {
            t.copy_from_slice(f);
        }
    }

    /// Pair and evaluate every slave point; hand each closed point's residual and tangent to
    /// `assemble` (its global DOFs, `r`, `r` again as the force residual — penalty points
    /// have no force unknowns — `k`, and the round-off weights of its coordinates).
    pub fn evaluate(&mut self, cfg: &SurfaceConfig, assemble: &mut LocalSink) {
        for (ip, pair) in cfg.model.surface_contacts.iter().enumerate() {
            if self.grids[ip].is_none() {
                self.grids[ip] = facet_grid(cfg, pair);
            }
            for is in 0..pair.slaves.len() {
                let hist = self.committed[ip][is];
                let start = self.current[ip][is].facet.or(hist.facet);
                let search = (self.grids[ip].as_ref(), start, self.borders[ip].as_slice());
                let now = evaluate_point(cfg, pair, is, &hist, search, self.plane_half, assemble);
                self.current[ip][is] = now;
            }
        }
    }

    /// Take the initial configuration as the converged state the first increment starts
    /// from (points touching at the start keep where they are).
    pub fn start_from_initial_configuration(&mut self, cfg: &SurfaceConfig) {
        self.evaluate(cfg, &mut |_, _, _, _, _| {});
        self.commit();
        self.reset_current();
    }

    /// The converged iterate's points (before [`Self::commit`]).
    pub fn snapshots(&self, cfg: &SurfaceConfig) -> Vec<SurfaceSnapshot> {
        let mut out = Vec::with_capacity(self.len());
        for (ip, pair) in cfg.model.surface_contacts.iter().enumerate() {
            for (is, now) in self.current[ip].iter().enumerate() {
                let hist = &self.committed[ip][is];
                let closed = now.eval.is_some_and(|e| e.state != ContactState::Open);
                out.push(SurfaceSnapshot {
                    pair: ip,
                    slave: is,
                    node: pair.slaves[is],
                    facet: now.facet,
                    previous_facet: hist.facet,
                    eval: now.eval,
                    force: now.force,
                    crossing: closed && hist.closed && hist.facet != now.facet,
                    history_lost: now.history_lost,
                    carried: now.carried,
                });
            }
        }
        out
    }

    /// Make the current iterate the converged state; returns the number of crossings
    /// (points closed before and now, on another facet).
    pub fn commit(&mut self) -> usize {
        let mut crossings = 0;
        for (hist, now) in self.committed.iter_mut().flatten().zip(self.current.iter().flatten()) {
            let closed = now.eval.is_some_and(|e| e.state != ContactState::Open);
            crossings += usize::from(closed && hist.closed && hist.facet != now.facet);
            *hist = SurfaceHistory {
                facet: now.facet,
                closed,
                history: now.eval.as_ref().and_then(super::point::PointProblem::next_history),
            };
        }
        crossings
    }
}

/// The search grid of a pair with a deformable master (`None` for a rigid one).
fn facet_grid(cfg: &SurfaceConfig, pair: &SurfacePair) -> Option<FacetGrid> {
    let SurfaceMaster::Facets { facets, .. } = &pair.master else {
        return None;
    };
    let boxes: Vec<[[f64; 3]; 2]> = facets.iter().map(|f| bounding_box(f.map(|n| cfg.node(n)))).collect();
    Some(FacetGrid::new(&boxes, pair.search_radius))
}

/// The facet slave `x` (current position) is paired with: `start` while `x` projects
/// inside it within reach; else, of the facets within reach, the one it projects inside
/// with the smallest `|ζ|`; else (`x` beyond every facet's edge: a convex edge or the
/// face's border) the one whose projection lies least outside it, its extension then
/// carrying the point (past the face's free border the caller leaves it unpaired, see
/// [`on_facets`]). `None`: no facet within the search radius.
pub fn locate(
    cfg: &SurfaceConfig,
    facets: &[[usize; 4]],
    grid: &FacetGrid,
    x: [f64; 3],
    start: Option<usize>,
    radius: f64,
) -> Option<usize> {
    let try_facet = |f: usize| -> Option<(f64, f64)> {
        let facet = Facet {
            x: facets[f].map(|n| cfg.node(n)),
        };
        let p = project(&facet, x).ok()?;
        let excess = p.point.xi.iter().map(|v| v.abs() - 1.0).fold(0.0, f64::max);
        (p.gap.abs() <= radius).then_some((excess, p.gap.abs()))
    };
    if let Some(s) = start {
        if try_facet(s).is_some_and(|(excess, _)| excess <= INSIDE_TOLERANCE) {
            return Some(s);
        }
    }
    let mut best: Option<(usize, (f64, f64))> = None;
    for &f in grid.candidates(x) {
        let Some(score) = try_facet(f) else { continue };
        let inside = |s: (f64, f64)| s.0 <= INSIDE_TOLERANCE;
        let better = match best {
            None => true,
            Some((_, b)) => match (inside(score), inside(b)) {
                (true, true) => score.1 < b.1,
                (true, false) => true,
                (false, true) => false,
                (false, false) => score.0 < b.0,
            },
        };
        if better {
            best = Some((f, score));
        }
    }
    best.map(|(f, _)| f)
}

/// Pair and evaluate slave `is` of `pair`; assemble it when closed.
fn evaluate_point(
    cfg: &SurfaceConfig,
    pair: &SurfacePair,
    is: usize,
    hist: &SurfaceHistory,
    (grid, start, borders): (Option<&FacetGrid>, Option<usize>, &[[bool; 4]]),
    plane_half: f64,
    assemble: &mut LocalSink,
) -> SurfaceNow {
    match &pair.master {
        SurfaceMaster::Facets { facets, .. } => {
            let grid = grid.expect("a facet master has a grid");
            on_facets(cfg, pair, is, hist, facets, (grid, start, borders), assemble)
        }
        SurfaceMaster::Rigid(rigid) => on_rigid(cfg, pair, is, hist, rigid, plane_half, assemble),
    }
}

/// Slave `is` against the facets of a deformable face: located (from `start`), its history
/// carried onto the facet it is on now, evaluated, and assembled on its 5 nodes when closed.
/// A point whose contact point lies past the face's free border (`borders`) is not paired
/// ([`past_free_border`]), unless it was closed on that facet at the last converged
/// increment and is still penetrating, within [`FREE_BORDER_HOLD`] of the border.
fn on_facets(
    cfg: &SurfaceConfig,
    pair: &SurfacePair,
    is: usize,
    hist: &SurfaceHistory,
    facets: &[[usize; 4]],
    (grid, start, borders): (&FacetGrid, Option<usize>, &[[bool; 4]]),
    assemble: &mut LocalSink,
) -> SurfaceNow {
    let node = pair.slaves[is];
    let origin = cfg.model.nodes[node];
    let mut now = SurfaceNow::default();
    let Some(f) = locate(cfg, facets, grid, cfg.node(node), start, pair.search_radius) else {
        return now;
    };
    now.facet = Some(f);
    let facet_b = cfg.facet_about(&facets[f], origin);
    let carried = match (hist.history.filter(|_| hist.closed), hist.facet) {
        (Some(h), Some(a)) if a != f => {
            let facet_a = Facet {
                x: cfg.facet_about(&facets[a], origin),
            };
            let carried = transfer(pair.transfer, &facet_a, &h, &Facet { x: facet_b }).ok();
            now.history_lost = carried.is_none();
            now.carried = carried.map(|to| Carried {
                from_facet: a,
                from: h,
                to,
            });
            carried
        }
        (h, _) => h,
    };
    let (mut r, mut k) = ([0.0; DOFS], [0.0; DOFS * DOFS]);
    let x_s = cfg.node_about(node, origin);
    let Ok(e) = facet_point(pair.law_of(is), x_s, facet_b, carried, &mut r, &mut k) else {
        now.facet = None;
        return now;
    };
    let past = past_free_border(e.projection.point.xi, borders[f]);
    let held = hist.closed && hist.facet == Some(f) && e.projection.gap < 0.0 && past <= FREE_BORDER_HOLD;
    if past > INSIDE_TOLERANCE && !held {
        return SurfaceNow::default();
    }
    now.eval = Some(in_model_coordinates(e, origin));
    if e.state != ContactState::Open {
        let nodes = [node, facets[f][0], facets[f][1], facets[f][2], facets[f][3]];
        let dofs: [usize; DOFS] = std::array::from_fn(|i| 3 * nodes[i / 3] + i % 3);
        let locals = [x_s, facet_b[0], facet_b[1], facet_b[2], facet_b[3]];
        let weights: [f64; DOFS] = std::array::from_fn(|j| locals[j / 3][j % 3].abs());
        now.force = [-r[0], -r[1], -r[2]];
        assemble(&dofs, &r, &r, &k, &weights);
    }
    now
}

/// Slave `is` against a rigid plane (a fixed facet: the slave's block of the facet kernel)
/// or a rigid sphere; assembled on the slave's 3 DOFs when closed.
fn on_rigid(
    cfg: &SurfaceConfig,
    pair: &SurfacePair,
    is: usize,
    hist: &SurfaceHistory,
    rigid: &crate::model::RigidSurface,
    plane_half: f64,
    assemble: &mut LocalSink,
) -> SurfaceNow {
    let node = pair.slaves[is];
    let origin = cfg.model.nodes[node];
    let x_s = cfg.node_about(node, origin);
    let law = pair.law_of(is);
    let mut now = SurfaceNow::default();
    let offset = rigid.offset(cfg.t);
    let (mut rs, mut ks) = ([0.0; 3], [0.0; 9]);
    let (e, scale) = match rigid.shape {
        RigidSurfaceShape::Plane { point, normal } => {
            let facet = plane_facet(point, normal, plane_half, offset, origin);
            let (mut r, mut k) = ([0.0; DOFS], [0.0; DOFS * DOFS]);
            let history = hist.history.filter(|_| hist.closed);
            let Ok(e) = facet_point(law, x_s, facet, history, &mut r, &mut k) else {
                return now;
            };
            slave_block(&r, &k, &mut rs, &mut ks);
            (e, plane_half)
        }
        RigidSurfaceShape::Sphere { centre, radius } => {
            let centre: [f64; 3] = std::array::from_fn(|c| (centre[c] - origin[c]) + offset[c]);
            (
                sphere_point(&law, x_s, centre, radius, &mut rs, &mut ks),
                crate::contact3d::vec3::norm(centre) + radius,
            )
        }
    };
    if e.projection.gap > pair.search_radius {
        return now;
    }
    now.facet = Some(0);
    now.eval = Some(in_model_coordinates(e, origin));
    if e.state != ContactState::Open {
        // the gap is computed from the rigid geometry's coordinates about the origin
        let weights: [f64; 3] = std::array::from_fn(|j| x_s[j].abs().max(scale));
        now.force = [-rs[0], -rs[1], -rs[2]];
        assemble(&[3 * node, 3 * node + 1, 3 * node + 2], &rs, &rs, &ks, &weights);
    }
    now
}

/// The evaluation with its contact point in the model's coordinates again (the kernel
/// computed about the slave's origin).
fn in_model_coordinates(mut e: PointEval<f64>, origin: [f64; 3]) -> PointEval<f64> {
    let rho = &mut e.projection.point.rho;
    *rho = std::array::from_fn(|c| rho[c] + origin[c]);
    e
}

#[cfg(test)]
#[path = "system_tests.rs"]
mod tests;
