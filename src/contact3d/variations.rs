//! First variations of the gap and of the convective coordinates of a node-to-surface contact
//! point, in closed form at the closest point (Konyukhov & Schweizerhof, Comput Mech 35
//! (2005) §3; Wriggers, Computational Contact Mechanics, 2nd ed. (2006) §4.3).
//!
//! Slot 0 of the 15 local DOFs is the slave `x_s`, slots 1–4 the facet's nodes `x_I` with
//! shape functions `N_I(ξ)` ([`Facet::shape`]). Varying the closest-point condition
//! `(x_s − ρ)·ρ_α = 0` with `x_s − ρ = ζ n`:
//!
//! - `δζ = (δx_s − N_I δx_I)·n` (`n·δn = 0`);
//! - `A_αβ δξ^β = (δx_s − N_I δx_I)·ρ_α + ζ N_I,α δx_I·n`, with `A_αβ = a_αβ − ζ h_αβ`.
//!
//! Evaluated in first-order dual numbers whose `ξ` carries the implicit-function derivatives
//! (the projection's Newton steps in the scalar type, [`super::projection`]), the dual parts
//! of these gradients are the Hessians `∇²ζ` and `∇²ξ^α` (including the curvature terms of a
//! warped facet): the tangent needs first-order duals only.

use super::point::DOFS;
use super::projection::Projection;
use super::surface::Facet;
use super::vec3::Scalar;

/// `∇ζ` and `∇ξ^α` over the 15 local DOFs (see the module docs).
#[derive(Debug, Clone, Copy)]
pub struct Variations<S: Scalar> {
    pub gap: [S; DOFS],
    pub xi: [[S; DOFS]; 2],
}

/// The closed-form first variations at the closest point `p`.
pub fn variations<S: Scalar>(p: &Projection<S>) -> Variations<S> {
    let point = &p.point;
    let (zeta, n, rho) = (p.gap, point.normal, point.tangents);
    let shape = Facet::<S>::shape(point.xi);
    let zero = S::from(0.0);
    // B = A⁻¹, A_αβ = a_αβ − ζ h_αβ
    let a = |i: usize, j: usize| point.metric[i][j] - zeta * point.curvature[i][j];
    let det = a(0, 0) * a(1, 1) - a(0, 1) * a(1, 0);
    let inv = det.recip();
    let b = [[a(1, 1) * inv, -a(0, 1) * inv], [-a(1, 0) * inv, a(0, 0) * inv]];
    // Σ_α B^{βα} v_α for the two right-hand sides v_α
    let solve = |v: [S; 2]| [b[0][0] * v[0] + b[0][1] * v[1], b[1][0] * v[0] + b[1][1] * v[1]];
    let mut out = Variations {
        gap: [zero; DOFS],
        xi: [[zero; DOFS]; 2],
    };
    for c in 0..3 {
        out.gap[c] = n[c];
        let x = solve([rho[0][c], rho[1][c]]);
        out.xi[0][c] = x[0];
        out.xi[1][c] = x[1];
    }
    let gradients = Facet::<S>::shape_gradients(point.xi);
    for (slot, (ni, [d1, d2])) in shape.into_iter().zip(gradients).enumerate() {
        for c in 0..3 {
            let k = 3 * (slot + 1) + c;
            out.gap[k] = -(ni * n[c]);
            let x = solve([zeta * d1 * n[c] - ni * rho[0][c], zeta * d2 * n[c] - ni * rho[1][c]]);
            out.xi[0][k] = x[0];
            out.xi[1][k] = x[1];
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact3d::projection::project;
    use crate::contact3d::vec3::V3;
    use num_dual::Dual2SVec64;

    /// A warped facet and a slave off it: the closed forms equal the gradients that
    /// second-order duals give, and their dual parts the Hessians.
    #[test]
    fn closed_forms_equal_the_derivatives_of_the_projection() {
        let x: [[f64; 3]; 5] = [
            [0.2, 0.1, 0.3],
            [-1.0, -1.1, 0.05],
            [1.2, -0.9, -0.1],
            [0.9, 1.0, 0.2],
            [-1.1, 0.8, -0.05],
        ];
        type D = Dual2SVec64<DOFS>;
        let q: [V3<D>; 5] = std::array::from_fn(|i| std::array::from_fn(|c| D::from_re(x[i][c]).derivative(3 * i + c)));
        let facet = Facet {
            x: [q[1], q[2], q[3], q[4]],
        };
        let p = project(&facet, q[0]).unwrap();
        let v = variations(&p);
        let mut worst: f64 = 0.0;
        let grad = |s: &D| s.v1.unwrap_generic(nalgebra::U1, nalgebra::Const::<DOFS>);
        let hess = |s: &D| s.v2.unwrap_generic(nalgebra::Const::<DOFS>, nalgebra::Const::<DOFS>);
        let pairs = [(&p.gap, &v.gap), (&p.point.xi[0], &v.xi[0]), (&p.point.xi[1], &v.xi[1])];
        for (exact, closed) in pairs {
            let (g, h) = (grad(exact), hess(exact));
            for i in 0..DOFS {
                worst = worst.max((closed[i].re - g[i]).abs());
                for j in 0..DOFS {
                    worst = worst.max((grad(&closed[i])[j] - h[(i, j)]).abs());
                }
            }
        }
        assert!(worst < 1e-12, "closed forms against second-order duals: {worst:e}");
    }
}
