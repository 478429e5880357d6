//! One 3D contact point against its master, in the form the system assembles: the local
//! problem of a slave node and a facet of a deformable face (15 DOFs, [`super::point`]), of a
//! slave node and a rigid plane (the plane as a fixed bilinear facet, the slave's 3 DOFs
//! kept), or of a slave node and a rigid cylinder or sphere (the facet kernel on their
//! convective coordinates, [`super::cylinder`], [`super::sphere`]; the slave's 3 DOFs kept).
//!
//! Every position is taken about the slave's reference position (its own origin), as in 2D:
//! gaps and convective coordinates are differences of nearby points, computed from the same
//! digits wherever the model sits.

use super::decision::SurfaceRule;
use super::point::{History, PointEval, PointProblem, RigidChart, SurfaceLinearization, DOFS};
use super::projection::ProjectionError;
use super::surface::Bend;
use super::vec3::{add, cross, dot, norm, scale, sub};
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

/// Evaluate the kernel of a slave `x_s` (about its origin) against a rigid cylinder or
/// sphere with convective coordinates `chart` ([`super::cylinder`], [`super::sphere`]: so
/// with friction), the history in them, the state decided by `rule` (`warm`: by the force
/// unknowns alone); the slave's 3 DOFs of the local arrays into `out`.
pub fn rigid_point(
    law: ContactLaw,
    x_s: [f64; 3],
    chart: RigidChart,
    history: Option<History>,
    (rule, warm): (SurfaceRule, bool),
    out: &mut PointLocal,
) -> Result<PointEval<f64>, ProjectionError> {
    let mut problem = PointProblem::new(law, [x_s, [0.0; 3], [0.0; 3], [0.0; 3], [0.0; 3]]);
    problem.rigid = Some(chart);
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
    use crate::contact3d::projection::Location;
    use crate::contact3d::surface::Facet;

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
