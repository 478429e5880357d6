//! The 3D contact state of a model: per node-to-surface pair ([`SurfacePair`]) and slave
//! node, the history of the last converged increment and the evaluation at the current
//! iterate. It pairs each slave with a facet of its master ([`locate`]), carries the
//! friction history onto a new facet by the pair's transfer scheme ([`super::transfer`]),
//! evaluates the point kernels ([`super::master`]) and hands their local residuals and
//! tangents to the caller's assembler by global DOF — as the 2D system does.
//!
//! Enforcement: the seed's penalty law with the contact Newton of 2D: each point's normal
//! force and tangential force are unknowns of Newton's iterate, its state decided by their
//! Alart–Curnier functions with the pair's weights ([`super::decision`],
//! [`super::unknowns`]); the complementarity residuals enter Newton's merit.

use super::decision::{SurfaceForces, SurfaceRule};
use super::evaluate::{evaluate_point, is_closed, SearchStart};
use super::master::PointLocal;
use super::nagata::FacetBends;
use super::point::{History, PointEval};
use super::search::{bounding_box, free_borders, FacetGrid};
use super::unknowns::PointLinearization;
use crate::contact::law::ContactState;
use crate::contact::system::{Decision, LocalSink};
use crate::model::{Model, Smoothing, Solid, SurfaceMaster, SurfacePair};

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
    pub(super) fn node_about(&self, n: usize, origin: [f64; 3]) -> [f64; 3] {
        let x = self.model.nodes[n];
        std::array::from_fn(|c| (x[c] - origin[c]) + self.u[3 * n + c])
    }

    pub(super) fn facet_about(&self, nodes: &[usize; 4], origin: [f64; 3]) -> [[f64; 3]; 4] {
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
    /// The converged contact forces (`N`, `T_α ρ^α`), from which the force unknowns of the
    /// next increment start.
    pub forces: SurfaceForces,
}

/// A point's evaluation at the current iterate.
#[derive(Debug, Clone, Copy, Default)]
pub struct SurfaceNow {
    pub facet: Option<usize>,
    pub eval: Option<PointEval<f64>>,
    /// The contact force on the slave node as assembled (`−r_s` of the force unknowns).
    pub force: [f64; 3],
    /// A closed point's linearised penalty forces (Newton's update of its force unknowns).
    pub linearization: Option<PointLinearization>,
    /// The kernel had a friction history on this facet and `μ > 0`: the traction is the
    /// return map's (otherwise zero: frictionless, or closing now).
    pub frictional: bool,
    /// The friction history could not be carried onto this facet from the last converged
    /// one ([`super::transfer::TransferError`]: the facets folded onto each other, or the old
    /// point not found on the new facet): the point starts it afresh, as a point closing now.
    pub history_lost: bool,
    /// The history carried onto `facet` from another one in this increment: where it was,
    /// and what it became (see [`Carried`]).
    pub carried: Option<Carried>,
    /// With a scheme other than the parallel translation: the trial tractions of its carried
    /// history and of the translated one, `(continuous, scheme)`
    /// ([`super::transfer::trial_against_continuous`]).
    pub trial_jump: Option<(f64, f64)>,
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
    /// Per pair whose master's facets are Nagata patches, their bends (at the positions an
    /// attempt at the increment starts from, as the search grid).
    bends: Vec<Option<FacetBends>>,
    /// Half-width of a rigid plane's fixed facet ([`super::master::plane_facet`]).
    plane_half: f64,
    /// The force unknowns of every point at the iterate, at the iterate a correction
    /// started from, and at the full correction.
    pub(super) forces: Vec<Vec<SurfaceForces>>,
    pub(super) forces_base: Vec<Vec<SurfaceForces>>,
    pub(super) forces_step: Vec<Vec<SurfaceForces>>,
    /// Per pair and point, the weights `(ρ_N, ρ_T)` of the augmented forces (1: the penalty
    /// rule).
    pub(super) weights: Vec<Vec<(f64, f64)>>,
    /// Decide by the force unknowns alone (the first iterate of an attempt).
    pub(super) warm: bool,
    /// `Σ C²` of the complementarity residuals at the last evaluation.
    pub(super) complementarity2: f64,
}

impl SurfaceSystem {
    /// The empty state of the pairs of `model` (none for a 2D model).
    pub fn new(model: Option<&Model<Solid>>) -> Self {
        let Some(model) = model else {
            return SurfaceSystem::default();
        };
        let per_point = |p: &SurfacePair| vec![SurfaceNow::default(); p.slaves.len()];
        let per_pair_forces = |p: &SurfacePair| vec![SurfaceForces::default(); p.slaves.len()];
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
            bends: (model.surface_contacts.iter())
                .map(|p| match &p.master {
                    SurfaceMaster::Facets { facets, .. } if p.smoothing == Smoothing::Nagata => {
                        Some(FacetBends::new(facets))
                    }
                    _ => None,
                })
                .collect(),
            plane_half: 4.0 * (model.size() + travel),
            forces: model.surface_contacts.iter().map(per_pair_forces).collect(),
            forces_base: model.surface_contacts.iter().map(per_pair_forces).collect(),
            forces_step: model.surface_contacts.iter().map(per_pair_forces).collect(),
            weights: (model.surface_contacts.iter())
                .map(|p| vec![(1.0, 1.0); p.slaves.len()])
                .collect(),
            warm: false,
            complementarity2: 0.0,
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
    /// rebuilt at its first evaluation, the force unknowns start from the converged forces.
    pub fn reset_current(&mut self) {
        self.current
            .iter_mut()
            .flatten()
            .for_each(|p| *p = SurfaceNow::default());
        self.grids.iter_mut().for_each(|g| *g = None);
        self.warm = false;
        self.reset_forces();
    }

    /// Keep the current evaluation and force unknowns (the start of a correction).
    pub fn save_iterate(&mut self) {
        for (b, c) in self.base.iter_mut().zip(&self.current) {
            b.copy_from_slice(c);
        }
        for (b, f) in self.forces_base.iter_mut().zip(&self.forces) {
            b.copy_from_slice(f);
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
        let copy_all = |to: &mut [Vec<SurfaceForces>], from: &[Vec<SurfaceForces>]| {
            to.iter_mut().zip(from).for_each(|(t, f)| t.copy_from_slice(f));
        };
        copy_all(&mut self.forces, &other.forces);
        copy_all(&mut self.forces_base, &other.forces_base);
        copy_all(&mut self.forces_step, &other.forces_step);
        self.warm = other.warm;
        self.complementarity2 = other.complementarity2;
    }

    /// Pair and evaluate every slave point, its state decided by the augmented forces of its
    /// unknowns; hand each point that carries a force, penalty or unknown, to `assemble`
    /// (its global DOFs, the penalty residual `r`, the unknowns' residual `r_eq`, `k`, and
    /// the round-off weights of its coordinates, scaled by `ρ` as in 2D).
    pub fn evaluate(&mut self, cfg: &SurfaceConfig, assemble: &mut LocalSink) {
        self.complementarity2 = 0.0;
        let mut local = PointLocal::default();
        for (ip, pair) in cfg.model.surface_contacts.iter().enumerate() {
            if self.grids[ip].is_none() {
                self.grids[ip] = facet_grid(cfg, pair);
                // the bends of an attempt: fixed while Newton iterates, so that the residual
                // is a function of the positions alone and the tangent its derivative
                // (see `nagata`)
                if let (Some(bends), SurfaceMaster::Facets { facets, .. }) = (&mut self.bends[ip], &pair.master) {
                    bends.update(facets, |n| cfg.node(n));
                }
            }
            for is in 0..pair.slaves.len() {
                let (rho_n, rho_t) = self.weights[ip][is];
                let hist = self.committed[ip][is];
                let forces = self.forces[ip][is];
                let rule = SurfaceRule::AlartCurnier { forces, rho_n, rho_t };
                let last = &self.current[ip][is];
                let search = SearchStart {
                    grid: self.grids[ip].as_ref(),
                    facet: last.facet.or(hist.facet),
                    closed_at_last_iterate: last.facet.is_some() && is_closed(last),
                    borders: self.borders[ip].as_slice(),
                    bends: self.bends[ip].as_ref(),
                };
                let point = (pair, is, &hist);
                let decider = (rule, self.warm && hist.closed);
                let mut ev = evaluate_point(cfg, point, search, self.plane_half, decider, &mut local);
                self.complementarity2 += match &ev.now.eval {
                    Some(e) => e.complementarity.iter().map(|c| c * c).sum::<f64>(),
                    // out of reach: no force can act; its unknowns go to zero
                    None => forces.normal.powi(2) + forces.tangential.iter().map(|c| c * c).sum::<f64>(),
                };
                let closed = is_closed(&ev.now);
                if ev.now.eval.is_some() && (closed || forces != SurfaceForces::default()) {
                    let n = local.len;
                    let rho = rho_n.max(rho_t);
                    let weights = ev.positions.map(|x| rho * x);
                    ev.now.force = [-local.r_eq[0], -local.r_eq[1], -local.r_eq[2]];
                    assemble(
                        &ev.dofs[..n],
                        &local.r[..n],
                        &local.r_eq[..n],
                        &local.k[..n * n],
                        &weights[..n],
                    );
                }
                if closed {
                    ev.now.linearization = Some(PointLinearization {
                        dofs: ev.dofs,
                        len: local.len,
                        lin: local.lin,
                    });
                }
                self.current[ip][is] = ev.now;
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
    pub fn commit(&mut self) -> SurfaceCommit {
        let mut out = SurfaceCommit::default();
        for (pair, (hists, nows)) in self.committed.iter_mut().zip(&self.current).enumerate() {
            for (slave, (hist, now)) in hists.iter_mut().zip(nows).enumerate() {
                let closed = now.eval.is_some_and(|e| e.state != ContactState::Open);
                let crossing = closed && hist.closed && hist.facet != now.facet;
                out.crossings += usize::from(crossing);
                if let (true, Some(trial), Some(carried), Some(to_facet)) =
                    (crossing, now.trial_jump, now.carried, now.facet)
                {
                    out.trials.push(SurfaceCrossingTrial {
                        pair,
                        slave,
                        from_facet: carried.from_facet,
                        to_facet,
                        trial,
                    });
                }
                *hist = SurfaceHistory {
                    facet: now.facet,
                    closed,
                    history: now.eval.as_ref().and_then(super::point::PointProblem::next_history),
                    forces: (now.eval.filter(|_| closed)).map_or(SurfaceForces::default(), |e| SurfaceForces {
                        normal: e.normal_force,
                        tangential: e.projection.point.vector(e.traction),
                    }),
                };
            }
        }
        out
    }
}

impl SurfaceSystem {
    /// `(pair, slave)` of the `flat`-th 3D point (pairs, then slaves: the order of
    /// [`SurfaceSystem::signature_into`]).
    pub fn point_index(&self, flat: usize) -> Option<(usize, usize)> {
        let mut k = flat;
        for (ip, pts) in self.current.iter().enumerate() {
            if k < pts.len() {
                return Some((ip, k));
            }
            k -= pts.len();
        }
        None
    }

    /// `(ξ¹, ξ²)` of a point at the current iterate (`None`: unpaired).
    pub fn xi(&self, pair: usize, slave: usize) -> Option<[f64; 2]> {
        self.current[pair][slave].eval.map(|e| e.projection.point.xi)
    }

    /// The facet a point is paired with at the current iterate.
    pub fn facet(&self, pair: usize, slave: usize) -> Option<usize> {
        self.current[pair][slave].facet
    }
}

/// What a converged increment's commit found: the crossings, and at those whose history a
/// scheme other than the parallel translation carried, its trial traction against the
/// translation's.
#[derive(Debug, Clone, Default)]
pub struct SurfaceCommit {
    pub crossings: usize,
    pub trials: Vec<SurfaceCrossingTrial>,
}

/// One crossing's trial tractions `(continuous, scheme)` (see [`SurfaceNow::trial_jump`]).
#[derive(Debug, Clone, Copy)]
pub struct SurfaceCrossingTrial {
    pub pair: usize,
    pub slave: usize,
    pub from_facet: usize,
    pub to_facet: usize,
    pub trial: (f64, f64),
}

/// The search grid of a pair with a deformable master (`None` for a rigid one).
fn facet_grid(cfg: &SurfaceConfig, pair: &SurfacePair) -> Option<FacetGrid> {
    let SurfaceMaster::Facets { facets, .. } = &pair.master else {
        return None;
    };
    let boxes: Vec<[[f64; 3]; 2]> = facets.iter().map(|f| bounding_box(f.map(|n| cfg.node(n)))).collect();
    Some(FacetGrid::new(&boxes, pair.search_radius))
}

#[cfg(test)]
#[path = "system_tests.rs"]
mod tests;
