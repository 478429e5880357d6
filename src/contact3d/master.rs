//! One 3D contact point against its master, in the form the system assembles: the local
//! problem of a slave node and a facet of a deformable face (15 DOFs, [`super::point`]), of a
//! slave node and a rigid plane (the plane as a fixed bilinear facet, the slave's 3 DOFs
//! kept), of a slave node and a rigid cylinder (the facet kernel on the cylinder's convective
//! coordinates, [`super::cylinder`]; the slave's 3 DOFs kept), or of a slave node and a rigid
//! sphere (closed form, 3 DOFs, frictionless).
//!
//! Every position is taken about the slave's reference position (its own origin), as in 2D:
//! gaps and convective coordinates are differences of nearby points, computed from the same
//! digits wherever the model sits.

use super::cylinder::CylinderChart;
use super::decision::{self, SurfaceRule};
use super::point::{History, PointEval, PointProblem, SurfaceLinearization, DOFS, TOUCH};
use super::projection::{Location, Projection, ProjectionError};
use super::surface::{Bend, FacetPoint};
use super::vec3::{add, cross, dot, norm, scale, sub};
use crate::contact::law::ContactState;
use crate::model::ContactLaw;

/// The four corners of a rigid plane as a fixed bilinear facet about `origin`: the square
/// of half-width `half` centred on the plane's reference point, moved by `offset`, its
/// nodes counter-clockwise seen from the side `normal` points to (`ρ_1 × ρ_2 ∥ n`). The
/// square is fixed in the plane's frame, so convective coordinates (and a stick anchor) keep
/// their meaning from increment to increment; `half` is larger than the model, so every
/// slave projects inside.
pub fn plane_facet(point: [f64; 3], normal: [f64; 3], half: f64, offset: [f64; 3], origin: [f64; 3]) -> [[f64; 3]; 4] {
    let [e1, e2] = plane_axes(normal);
    let centre = add(sub(point, origin), offset);
    [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
        .map(|(a, b)| add(centre, add(scale(e1, a * half), scale(e2, b * half))))
}

/// Unit axes `e_1, e_2` of a plane with unit normal `n`, `e_1 × e_2 = n`.
pub fn plane_axes(n: [f64; 3]) -> [[f64; 3]; 2] {
    let pick = if n[0].abs() < 0.9 {
        [1.0, 0.0, 0.0]
    } else {
        [0.0, 1.0, 0.0]
    };
    let e1 = sub(pick, scale(n, dot(pick, n)));
    let e1 = scale(e1, 1.0 / norm(e1));
    [e1, cross(n, e1)]
}

/// The local arrays of one point as the system assembles them: `len` DOFs (15 for a slave
/// and a deformable facet, 3 for a slave against a rigid surface), the penalty residual `r`,
/// the force unknowns' residual `r_eq`, the condensed tangent `k` (row-major, `len × len`)
/// and the linearised penalty forces (gradients in their first `len` entries); see
/// [`PointProblem::local`].
#[derive(Debug, Clone, Copy)]
pub struct PointLocal {
    pub len: usize,
    pub r: [f64; DOFS],
    pub r_eq: [f64; DOFS],
    pub k: [f64; DOFS * DOFS],
    pub lin: SurfaceLinearization,
}

impl Default for PointLocal {
    fn default() -> Self {
        PointLocal {
            len: 0,
            r: [0.0; DOFS],
            r_eq: [0.0; DOFS],
            k: [0.0; DOFS * DOFS],
            lin: SurfaceLinearization::default(),
        }
    }
}

impl PointLocal {
    /// Keep the slave's 3 DOFs of a 15-DOF point (a rigid facet: nodes 1–4 do not move).
    pub fn keep_slave(&mut self) {
        for i in 0..3 {
            for j in 0..3 {
                self.k[3 * i + j] = self.k[DOFS * i + j];
            }
        }
        self.len = 3;
    }
}

/// A rigid round surface about the slave's origin: a sphere (`axis` `None`) or an infinite
/// circular cylinder through `centre` along the unit `axis`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Round {
    pub centre: [f64; 3],
    pub axis: Option<[f64; 3]>,
    pub radius: f64,
}

/// A slave at `x` (about its origin) against a rigid sphere or cylinder `round`,
/// frictionless, its state decided by `rule` ([`super::decision`]; `warm`: by the force
/// unknowns alone). With `d = P (x − c)`, `P = I` for a sphere and `P = I − a aᵀ` for a
/// cylinder of axis `a`: `ζ = |d| − R`, `n = d/|d|`, `N_ε = −ε_N ζ`, `r = −N_ε n` while closed,
/// `r_eq = −N̄ n` with the normal force unknown `N̄`, and `k = ε_N n nᵀ − N̄ (P − n nᵀ)/|d|`
/// (`∂n/∂x = (P − n nᵀ)/|d|`; 3 DOFs; `r`, `k` zero when open).
pub fn round_point(
    law: &ContactLaw,
    x: [f64; 3],
    round: Round,
    (rule, warm): (SurfaceRule, bool),
    out: &mut PointLocal,
) -> PointEval<f64> {
    let Round { centre, axis, radius } = round;
    let project = |v: [f64; 3]| match axis {
        Some(a) => sub(v, scale(a, dot(v, a))),
        None => v,
    };
    let d = project(sub(x, centre));
    let dist = norm(d);
    let n = scale(d, 1.0 / dist);
    let gap = dist - radius;
    let [t1, t2] = plane_axes(n);
    let identity = [[1.0, 0.0], [0.0, 1.0]];
    let point = FacetPoint {
        xi: [0.0, 0.0],
        rho: sub(x, scale(n, gap)),
        tangents: [t1, t2],
        metric: identity,
        inverse: identity,
        normal: n,
        curvature: [[0.0; 2]; 2],
    };
    let n_eps = -law.eps_n * gap;
    let deciding = if warm { rule.deciding_by_forces() } else { rule };
    let (closed, n_hat) = decision::normal(&deciding, n_eps, law.eps_n * TOUCH * radius);
    let state = if closed { ContactState::Slip } else { ContactState::Open };
    let n_bar = rule.forces().map_or(n_eps, |f| f.normal);
    *out = PointLocal {
        len: 3,
        ..PointLocal::default()
    };
    for (r, n) in out.r_eq.iter_mut().zip(n) {
        *r = -n_bar * n;
    }
    if closed {
        out.lin.normal = n_eps;
        for i in 0..3 {
            out.r[i] = -n_eps * n[i];
            out.lin.d_normal[i] = -law.eps_n * n[i];
            let e_i = project(std::array::from_fn(|c| if c == i { 1.0 } else { 0.0 }));
            for j in 0..3 {
                out.k[3 * i + j] = law.eps_n * n[i] * n[j] - n_bar * (e_i[j] - n[i] * n[j]) / dist;
            }
        }
    }
    PointEval {
        projection: Projection {
            point,
            gap,
            location: Location::Inside,
            iterations: 0,
        },
        normal_force: if closed { n_eps } else { 0.0 },
        trial: [0.0; 2],
        traction: [0.0; 2],
        state,
        complementarity: decision::complementarity(&rule, state, (n_eps, n_hat), None, None),
    }
}

/// Evaluate the facet kernel: slave `x_s` and facet corners `facet` (about the slave's
/// origin) with its bend (`None`: bilinear), the history transferred to this facet, the state decided by `rule` (`warm`: by
/// the force unknowns alone); the local arrays into `out` (15 DOFs).
pub fn facet_point(
    law: ContactLaw,
    (x_s, facet, bend): ([f64; 3], [[f64; 3]; 4], Option<Bend>),
    history: Option<History>,
    (rule, warm): (SurfaceRule, bool),
    out: &mut PointLocal,
) -> Result<PointEval<f64>, ProjectionError> {
    let mut problem = PointProblem::new(law, [x_s, facet[0], facet[1], facet[2], facet[3]]);
    problem.bend = bend;
    problem.history = history;
    problem.rule = rule;
    problem.warm = warm;
    out.len = DOFS;
    problem.local(&mut out.r, &mut out.r_eq, &mut out.k, &mut out.lin)
}

/// Evaluate the kernel of a slave `x_s` (about its origin) against the rigid cylinder
/// `chart` ([`super::cylinder`]: convective coordinates on it, so with friction), the history
/// on the cylinder, the state decided by `rule` (`warm`: by the force unknowns alone); the
/// slave's 3 DOFs of the local arrays into `out`.
pub fn cylinder_point(
    law: ContactLaw,
    x_s: [f64; 3],
    chart: CylinderChart,
    history: Option<History>,
    (rule, warm): (SurfaceRule, bool),
    out: &mut PointLocal,
) -> Result<PointEval<f64>, ProjectionError> {
    let mut problem = PointProblem::new(law, [x_s, [0.0; 3], [0.0; 3], [0.0; 3], [0.0; 3]]);
    problem.cylinder = Some(chart);
    problem.history = history;
    problem.rule = rule;
    problem.warm = warm;
    out.len = DOFS;
    let e = problem.local(&mut out.r, &mut out.r_eq, &mut out.k, &mut out.lin)?;
    out.keep_slave();
    Ok(e)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact3d::surface::Facet;

    /// The tangent of a sphere and of a tilted cylinder against central differences of the
    /// residual (1e-6 of ε_N); the slave's force points away from the centre or the axis and,
    /// on the cylinder, has no component along the axis (1e-12).
    #[test]
    fn the_round_tangents_are_the_derivatives_of_their_residuals() {
        let law = ContactLaw {
            eps_n: 1e3,
            eps_t: 0.0,
            mu: 0.0,
        };
        let c = [0.1, -0.2, 1.0];
        let tilted = scale([0.3, 1.0, 0.2], 1.0 / norm([0.3, 1.0, 0.2]));
        let x = [0.05, 0.02, 0.05];
        let penalty = (SurfaceRule::Penalty, false);
        for axis in [None, Some(tilted)] {
            let round = Round {
                centre: c,
                axis,
                radius: 1.0,
            };
            let mut out = PointLocal::default();
            let e = round_point(&law, x, round, penalty, &mut out);
            assert_eq!(e.state, ContactState::Slip, "{axis:?}");
            let (r, k) = (out.r, out.k);
            let h = 1e-7;
            for j in 0..3 {
                let (mut op, mut om) = (PointLocal::default(), PointLocal::default());
                let mut xp = x;
                xp[j] += h;
                round_point(&law, xp, round, penalty, &mut op);
                let mut xm = x;
                xm[j] -= h;
                round_point(&law, xm, round, penalty, &mut om);
                for i in 0..3 {
                    let fd = (op.r[i] - om.r[i]) / (2.0 * h);
                    assert!(
                        (fd - k[3 * i + j]).abs() <= 1e-6 * law.eps_n,
                        "{axis:?}: k[{i}{j}] {} vs {fd}",
                        k[3 * i + j]
                    );
                }
            }
            let force = scale([r[0], r[1], r[2]], -1.0);
            let outward = sub(x, c);
            assert!(dot(force, outward) > 0.0);
            if let Some(a) = axis {
                assert!(dot(force, a).abs() <= 1e-12 * norm(force));
            }
        }
    }

    #[test]
    fn a_plane_facet_has_the_plane_normal_and_projects_the_point_inside() {
        let n = [0.0, 0.6, 0.8];
        let f = plane_facet([1.0, 2.0, 3.0], n, 10.0, [0.0, 0.0, 0.5], [1.0, 2.0, 3.0]);
        let p = Facet::flat(f).point([0.3, -0.2]).unwrap();
        for (got, want) in p.normal.iter().zip(n) {
            assert!((got - want).abs() < 1e-14);
        }
        let law = ContactLaw {
            eps_n: 1.0,
            eps_t: 0.0,
            mu: 0.0,
        };
        let mut out = PointLocal::default();
        let e = facet_point(
            law,
            ([0.2, 0.1, 0.3], f, None),
            None,
            (SurfaceRule::Penalty, false),
            &mut out,
        )
        .unwrap();
        assert_eq!(e.projection.location, Location::Inside);
        // the offset moved the plane by 0.5 along z: gap = (x − c)·n
        let gap = dot(sub([0.2, 0.1, 0.3], [0.0, 0.0, 0.5]), n);
        assert!((e.projection.gap - gap).abs() < 1e-14);
    }
}
