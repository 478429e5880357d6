//! Residual and consistent tangent of one 3D node-to-surface contact point: a slave node
//! against a bilinear facet, penalty normal contact and Coulomb friction by return mapping
//! in the facet's tangent plane with its metric (seed §3 on surfaces; Konyukhov &
//! Schweizerhof, Comput Mech 35 (2005) 190–213, §§3–5; notes `contact-3d.md`).
//!
//! Local unknowns: the current positions of 5 nodes, slot 0 the slave `x_s`, slots 1–4 the
//! facet's nodes (counter-clockwise seen from outside, see [`super::surface`]); slot `i`
//! owns local DOFs `3i..3i+3` (15 in all).
//!
//! Law, in covariant components on the current facet:
//! - gap `ζ = (x_s − ρ(ξ))·n` at the closest point `ξ` ([`super::projection`]), normal force
//!   `N = −ε_N ζ` while `ζ ≤ TOUCH · size` (closed; a touching point is closed with `N = 0`),
//!   else the point is open and carries nothing;
//! - stick trial (seed eq. 1): `T_α^tr = T_α^(n) − ε_T a_αβ (ξ^β − ξ^β_(n))` with the
//!   history `(ξ_(n), T^(n))` of the last converged increment *on this facet* (carried here
//!   by [`super::transfer`] when the point has changed facet), `a_αβ` at the current `ξ`;
//! - slip function `Φ = √(T^tr_α a^αβ T^tr_β) − μ N`; `Φ ≤ 0`: stick, `T_α = T_α^tr`;
//!   `Φ > 0`: slip, `T_α = μ N T_α^tr / ‖T^tr‖`;
//! - no history (the first closing increment) or `μ = 0`: `T_α = 0` (the first closing
//!   increment is frictionless and its end fixes the anchor, as in 2D).
//!
//! Virtual work `δW = −N δζ − T_α δξ^α`, so the residual (internal force) is
//! `r = −N ∇ζ − T_α ∇ξ^α` and the tangent
//! `K = −∇ζ ∇Nᵀ − N ∇²ζ − Σ_α (∇ξ^α ∇T_αᵀ + T_α ∇²ξ^α)`, `∇` over the 15 DOFs. `ζ`, `ξ^α`,
//! `N` and `T_α` are evaluated in first-order dual numbers (`DualSVec64<15>`, on the stack);
//! `∇ζ` and `∇ξ^α` are the closed forms of [`super::variations`], whose dual parts give
//! `∇²ζ` and `∇²ξ^α` exactly (including the curvature terms of a warped facet), so no
//! second-order arithmetic is needed; the unsymmetric friction blocks come from `∇T_α`. At the
//! closest point `∇_s ζ = n`, `∇_s ξ^α = (a − ζ h)^{-1, αβ} ρ_β`, so the force on the slave is
//! `−r_s = N n + T_α ∇_s ξ^α` (`= N n + T_α ρ^α` on a flat facet): `T` acts on the slave.
//! The history is data (not differentiated).

use super::cylinder::CylinderChart;
use super::decision::{self, SurfaceRule};
use super::projection::{project_with, Projection, ProjectionError, ProjectionOptions, XI_BOX};
use super::sphere::SphereChart;
use super::surface::{Bend, Facet, FacetPoint};
use super::variations::{variations, Variations};
use super::vec3::{Scalar, V3};
use crate::contact::law::ContactState;
use crate::model::ContactLaw;
use nalgebra::{Const, U1};
use num_dual::DualSVec64;

/// A gap within `TOUCH` times the facet's size of zero is touching: the point is closed.
/// The active set of a penalty method is `ζ ≤ 0` (Wriggers, Computational Contact Mechanics,
/// 2nd ed. (2006) §6.3.1, the active set strategy's `g_N ≤ 0`): a point at zero gap takes the
/// closed side of the normal kink, so the penalty's stiffness enters the first correction of
/// bodies meshed against each other. `TOUCH` only admits the gap's round-off (a few ulps of
/// the coordinates, which are about the slave's origin and of the facet's size); the normal
/// force at such a gap is below `ε_N 1e-12 · size`.
pub const TOUCH: f64 = 1e-12;

/// Nodes of one point: the slave and the facet's four.
pub const NODES: usize = 5;
/// Local DOFs.
pub const DOFS: usize = 3 * NODES;

/// A rigid master with convective coordinates of its own: a cylinder ([`super::cylinder`])
/// or a sphere ([`super::sphere`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum RigidChart {
    Cylinder(CylinderChart),
    Sphere(SphereChart),
}

/// History of a point closed at the last converged increment, on the facet it is on now.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct History {
    /// `ξ_(n)`: the contact point of the last converged increment (on this facet's
    /// parametrisation, possibly outside `[−1, 1]²` after a transfer).
    pub xi: [f64; 2],
    /// `T_α^(n)`: covariant traction on this facet.
    pub traction: [f64; 2],
}

/// Everything the kernel sees of one contact point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PointProblem {
    pub law: ContactLaw,
    /// Current positions: slot 0 the slave, 1–4 the facet's nodes.
    pub x: [[f64; 3]; NODES],
    /// The facet's bend into a Nagata patch ([`super::nagata`]; data, not differentiated);
    /// `None`: bilinear.
    pub bend: Option<Bend>,
    /// `None`: the point was open at the last converged increment.
    pub history: Option<History>,
    /// The master is this rigid surface with its own convective coordinates (slots 1–4
    /// unused) instead of the facet.
    pub rigid: Option<RigidChart>,
    /// Newton's settings of the projection (its start is replaced by `ξ_(n)` when there is
    /// a history).
    pub projection: ProjectionOptions,
    /// Who decides the state: the penalty function alone, or the augmented force unknowns
    /// of Newton's iterate ([`super::decision`]).
    pub rule: SurfaceRule,
    /// The state is decided by the force unknowns alone ([`SurfaceRule::deciding_by_forces`]:
    /// the first iterate of an attempt); the complementarity residuals keep the rule's weights.
    pub warm: bool,
}

/// One evaluation in scalar type `S`.
#[derive(Debug, Clone, Copy)]
pub struct PointEval<S: Scalar> {
    pub projection: Projection<S>,
    /// `N` (zero when open).
    pub normal_force: S,
    /// `T_α^tr` (zero without friction history).
    pub trial: [S; 2],
    /// `T_α` after the return map.
    pub traction: [S; 2],
    pub state: ContactState,
    /// The complementarity residuals `[C_N, |C_T|]` of the rule at this state (zero under
    /// [`SurfaceRule::Penalty`]; see [`decision::complementarity`]).
    pub complementarity: [f64; 2],
}

/// What Newton's update of the force unknowns needs of a closed point: the penalty forces
/// in the decided state — `N_ε` and the tangential force on the slave as a spatial vector,
/// `T_α ρ^α` — and their gradients with respect to the 15 local DOFs.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct SurfaceLinearization {
    pub normal: f64,
    pub d_normal: [f64; DOFS],
    pub tangential: [f64; 3],
    pub d_tangential: [[f64; DOFS]; 3],
}

impl PointProblem {
    /// A point without history and with the default projection settings.
    pub fn new(law: ContactLaw, x: [[f64; 3]; NODES]) -> Self {
        PointProblem {
            law,
            x,
            bend: None,
            history: None,
            rigid: None,
            projection: ProjectionOptions::default(),
            rule: SurfaceRule::Penalty,
            warm: false,
        }
    }

    /// Projection, normal force, trial and returned traction for node positions `q`, the
    /// state decided by [`Self::rule`] ([`super::decision`]).
    pub fn evaluate<S: Scalar>(&self, q: &[V3<S>; NODES]) -> Result<PointEval<S>, ProjectionError> {
        let (projection, size) = match &self.rigid {
            Some(RigidChart::Cylinder(c)) => (c.project(q[0], self.history.map(|h| h.xi[0]))?, c.radius),
            Some(RigidChart::Sphere(c)) => (c.project(q[0])?, c.radius),
            None => {
                let facet = Facet {
                    x: [q[1], q[2], q[3], q[4]],
                    bend: self.bend,
                };
                let mut opts = self.projection;
                if let Some(h) = self.history {
                    opts.start = h.xi.map(|v| v.clamp(-0.5 * XI_BOX, 0.5 * XI_BOX));
                }
                (project_with(&facet, q[0], &opts)?, facet.size())
            }
        };
        let zero = S::from(0.0);
        let n_eps = projection.gap * (-self.law.eps_n);
        let mut eval = PointEval {
            projection,
            normal_force: zero,
            trial: [zero; 2],
            traction: [zero; 2],
            state: ContactState::Open,
            complementarity: [0.0; 2],
        };
        let deciding = if self.warm {
            self.rule.deciding_by_forces()
        } else {
            self.rule
        };
        // touching within the geometry's precision counts as closed (the resting side of
        // the normal kink): a point at zero gap then carries the penalty's stiffness into
        // the correction, and a correction that lifts it opens it at the next iterate
        let touch = self.law.eps_n * TOUCH * size;
        let (closed, n_hat) = decision::normal(&deciding, n_eps.re(), touch);
        let forces = (n_eps.re(), n_hat);
        if !closed {
            eval.complementarity = decision::complementarity(&self.rule, ContactState::Open, forces, None, None);
            return Ok(eval);
        }
        eval.normal_force = n_eps;
        let mu = self.law.mu;
        let Some(h) = self.history.filter(|_| mu > 0.0) else {
            eval.state = if mu > 0.0 {
                ContactState::Stick
            } else {
                ContactState::Slip
            };
            eval.complementarity = decision::complementarity(&self.rule, eval.state, forces, None, None);
            return Ok(eval);
        };
        self.friction(&mut eval, h, &deciding, forces);
        Ok(eval)
    }

    /// The frictional part of [`Self::evaluate`] for a closed point with history `h` on this
    /// facet: the stick trial (seed eq. 1 on surfaces), stick or slip decided by `deciding`
    /// with the penalty's and the augmented normal forces `forces`, the traction and the
    /// complementarity residuals of that state.
    fn friction<S: Scalar>(&self, eval: &mut PointEval<S>, h: History, deciding: &SurfaceRule, forces: (f64, f64)) {
        let (mu, n_eps, n_hat) = (self.law.mu, eval.normal_force, forces.1);
        let p = &eval.projection.point;
        let slip = p.lower([p.xi[0] - h.xi[0], p.xi[1] - h.xi[1]]);
        let eps_t = self.law.eps_t;
        let trial = [
            S::from(h.traction[0]) - slip[0] * eps_t,
            S::from(h.traction[1]) - slip[1] * eps_t,
        ];
        let p_re = real_point(p);
        let trial_re = trial.map(|v| v.re());
        eval.trial = trial;
        match decision::tangential(deciding, mu, trial_re, &p_re, forces) {
            None => {
                eval.traction = trial;
                eval.state = ContactState::Stick;
                let trial_vector = Some(p_re.vector(trial_re));
                eval.complementarity = decision::complementarity(&self.rule, eval.state, forces, trial_vector, None);
            }
            Some(slip) => {
                // the slip force of the condensed semismooth Newton (module docs of
                // `decision`): `μ N_ε d + c P T^tr`, the seed's return map at a solution
                let d = p_re.vector(slip.direction);
                let c = decision::transverse_factor(deciding, mu, n_hat, slip.size);
                let tv = p.vector(trial);
                let along = tv[0] * d[0] + tv[1] * d[1] + tv[2] * d[2];
                let force: V3<S> = std::array::from_fn(|i| n_eps * (mu * d[i]) + (tv[i] - along * d[i]) * c);
                eval.traction = p.covariant(force);
                eval.state = ContactState::Slip;
                let slip = Some((d, mu));
                eval.complementarity = decision::complementarity(&self.rule, eval.state, forces, None, slip);
            }
        }
    }

    /// Plain evaluation.
    pub fn evaluate_f64(&self) -> Result<PointEval<f64>, ProjectionError> {
        self.evaluate(&self.x)
    }

    /// The residual `r = −N ∇ζ − T_α ∇ξ^α` alone: a plain evaluation and the closed-form
    /// variations ([`super::variations`]).
    pub fn residual(&self, r: &mut [f64; DOFS]) -> Result<PointEval<f64>, ProjectionError> {
        let e = self.evaluate_f64()?;
        r.fill(0.0);
        if e.state != ContactState::Open {
            let var = self.variations(&e.projection);
            let (n, t) = (e.normal_force, e.traction);
            for (i, ri) in r.iter_mut().enumerate() {
                *ri = -n * var.gap[i] - t[0] * var.xi[0][i] - t[1] * var.xi[1][i];
            }
        }
        Ok(e)
    }

    /// Residual `r` and consistent tangent `k = ∂r/∂x` (row-major, `k[DOFS i + j]`) under the
    /// penalty rule, see the module docs; returns the plain evaluation. Open: both zero.
    pub fn residual_tangent(
        &self,
        r: &mut [f64; DOFS],
        k: &mut [f64; DOFS * DOFS],
    ) -> Result<PointEval<f64>, ProjectionError> {
        let mut r_eq = [0.0; DOFS];
        let mut lin = SurfaceLinearization::default();
        self.local(r, &mut r_eq, k, &mut lin)
    }

    /// Everything Newton needs of this point: the residual `r = −N_ε ∇ζ − T_α ∇ξ^α` of the
    /// penalty forces in the decided state (the condensed system's right-hand side), the
    /// residual `r_eq = −N̄ ∇ζ − T̄_α ∇ξ^α` of the force unknowns (`T̄_α = t̄·ρ_α`; equal to `r`
    /// under [`SurfaceRule::Penalty`]), the condensed tangent
    /// `k = −∇ζ ∇N_εᵀ − N̄ ∇²ζ − Σ_α (∇ξ^α ∇T_αᵀ + T̄_α ∇²ξ^α + ∇ξ^α ((t̄ − t_ε)·∇ρ_α)ᵀ)` — the
    /// penalty forces' gradients in the decided state, the geometry's Hessians weighted by
    /// the force unknowns, and the turn of the facet's basis under the unknown's covariant
    /// components (`t_ε = T_α ρ^α` the penalty's tangential force): the Newton matrix of the
    /// mixed system with the unknowns condensed, as in 2D
    /// ([`crate::contact::point::PointProblem::local`]) — and the linearisation `lin` of the
    /// penalty forces. An open point: `r`, `k` and `lin` zero (its unknowns go to zero in
    /// one correction), `r_eq` the unknowns' force.
    pub fn local(
        &self,
        r: &mut [f64; DOFS],
        r_eq: &mut [f64; DOFS],
        k: &mut [f64; DOFS * DOFS],
        lin: &mut SurfaceLinearization,
    ) -> Result<PointEval<f64>, ProjectionError> {
        type D = DualSVec64<DOFS>;
        let q: [V3<D>; NODES] =
            std::array::from_fn(|i| std::array::from_fn(|c| D::from_re(self.x[i][c]).derivative(3 * i + c)));
        let e = self.evaluate(&q)?;
        r.fill(0.0);
        r_eq.fill(0.0);
        k.fill(0.0);
        *lin = SurfaceLinearization::default();
        let grad = |s: &D| -> [f64; DOFS] {
            let g = s.eps.unwrap_generic(Const::<DOFS>, U1);
            std::array::from_fn(|j| g[j])
        };
        // ∇ζ, ∇ξ^α in closed form; their dual parts are ∇²ζ, ∇²ξ^α
        let var = self.variations(&e.projection);
        let gz: [f64; DOFS] = var.gap.map(|s| s.re);
        let gx: [[f64; DOFS]; 2] = var.xi.map(|g| g.map(|s| s.re));
        let (n_bar, t_bar) = match self.rule.forces() {
            Some(f) => (f.normal, real_point(&e.projection.point).covariant(f.tangential)),
            None => (e.normal_force.re, e.traction.map(|v| v.re)),
        };
        for i in 0..DOFS {
            r_eq[i] = -n_bar * gz[i] - t_bar[0] * gx[0][i] - t_bar[1] * gx[1][i];
        }
        if e.state == ContactState::Open {
            // the unknowns of an open point go to zero in one correction; their geometric
            // terms are left out of the Newton matrix, as in 2D
            return Ok(real_parts(&e));
        }
        let hz: [[f64; DOFS]; DOFS] = var.gap.map(|s| grad(&s));
        let hx: [[[f64; DOFS]; DOFS]; 2] = var.xi.map(|g| g.map(|s| grad(&s)));
        let gn = grad(&e.normal_force);
        let gt = [grad(&e.traction[0]), grad(&e.traction[1])];
        let (n, t) = (e.normal_force.re, e.traction.map(|v| v.re));
        for i in 0..DOFS {
            r[i] = -n * gz[i] - t[0] * gx[0][i] - t[1] * gx[1][i];
            for j in 0..DOFS {
                k[DOFS * i + j] = -gz[i] * gn[j]
                    - n_bar * hz[i][j]
                    - (gx[0][i] * gt[0][j] + t_bar[0] * hx[0][i][j])
                    - (gx[1][i] * gt[1][j] + t_bar[1] * hx[1][i][j]);
            }
        }
        let tangential = e.projection.point.vector(e.traction);
        if let Some(f) = self.rule.forces() {
            // the unknowns' covariant components `t̄·ρ_α` turn with the facet's basis while
            // the penalty force's are those of its own vector: `−∇ξ^α ⊗ ∇ρ_α·(t̄ − t_ε)`
            let excess: [f64; 3] = std::array::from_fn(|c| f.tangential[c] - tangential[c].re);
            for (alpha, rho) in e.projection.point.tangents.iter().enumerate() {
                let turned = grad(&(rho[0] * excess[0] + rho[1] * excess[1] + rho[2] * excess[2]));
                for i in 0..DOFS {
                    for j in 0..DOFS {
                        k[DOFS * i + j] -= gx[alpha][i] * turned[j];
                    }
                }
            }
        }
        lin.normal = n;
        lin.tangential = tangential.map(|c| c.re);
        lin.d_normal = gn;
        for (c, v) in tangential.iter().enumerate() {
            lin.d_tangential[c] = grad(v);
        }
        Ok(real_parts(&e))
    }

    /// `∇ζ`, `∇ξ^α` of the closest point `p` ([`variations`]); against a rigid surface only
    /// the slave's slot, the master's nodes being unused.
    fn variations<S: Scalar>(&self, p: &Projection<S>) -> Variations<S> {
        let mut var = variations(p, self.bend.as_ref());
        if self.rigid.is_some() {
            let zero = S::from(0.0);
            for g in std::iter::once(&mut var.gap).chain(&mut var.xi) {
                g[3..].fill(zero);
            }
        }
        var
    }

    /// The history to store when this evaluation is the converged state of the increment:
    /// `ξ_(n+1)` and `T_α` (zero traction for a point closing now), `None` when open.
    pub fn next_history(e: &PointEval<f64>) -> Option<History> {
        (e.state != ContactState::Open).then_some(History {
            xi: e.projection.point.xi,
            traction: e.traction,
        })
    }
}

/// The real parts of a dual evaluation.
fn real_parts<S: Scalar>(e: &PointEval<S>) -> PointEval<f64> {
    PointEval {
        projection: Projection {
            point: real_point(&e.projection.point),
            gap: e.projection.gap.re(),
            location: e.projection.location,
            iterations: e.projection.iterations,
        },
        normal_force: e.normal_force.re(),
        trial: e.trial.map(|c| c.re()),
        traction: e.traction.map(|c| c.re()),
        state: e.state,
        complementarity: e.complementarity,
    }
}

/// The real parts of a contact point in dual numbers.
fn real_point<S: Scalar>(p: &FacetPoint<S>) -> FacetPoint<f64> {
    let m = |a: [[S; 2]; 2]| a.map(|row| row.map(|v| v.re()));
    let v = |a: V3<S>| a.map(|c| c.re());
    FacetPoint {
        xi: p.xi.map(|c| c.re()),
        rho: v(p.rho),
        tangents: p.tangents.map(v),
        metric: m(p.metric),
        inverse: m(p.inverse),
        normal: v(p.normal),
        curvature: m(p.curvature),
    }
}
