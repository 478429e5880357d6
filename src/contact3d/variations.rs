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
use super::surface::{Bend, Facet, EDGES};
use super::vec3::{dot, Scalar};

/// `∇ζ` and `∇ξ^α` over the 15 local DOFs (see the module docs).
#[derive(Debug, Clone, Copy)]
pub struct Variations<S: Scalar> {
    pub gap: [S; DOFS],
    pub xi: [[S; DOFS]; 2],
}

/// The closed-form first variations at the closest point `p` of a facet bent by `bend`
/// (`None`: bilinear). A bent facet's `ρ` depends on node `I` through the matrix
/// `∂ρ/∂x_I = N_I 1 − Σ_e φ_e σ_eI Q_e` (`σ_eI = +1` at the edge's end `b`, `−1` at its start
/// `a`, [`super::surface::Bend`]) in place of `N_I 1`, and `ρ_α` through its `ξ^α`-derivative.
pub fn variations<S: Scalar>(p: &Projection<S>, bend: Option<&Bend>) -> Variations<S> {
    let point = &p.point;
    let (zeta, n, rho) = (p.gap, point.normal, point.tangents);
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
    let weights = node_weights(point.xi, bend);
    for (slot, w) in weights.iter().enumerate() {
        for c in 0..3 {
            let k = 3 * (slot + 1) + c;
            // the columns `∂ρ/∂x_Ic`, `∂ρ_α/∂x_Ic`
            let col = |m: &[[S; 3]; 3]| [m[0][c], m[1][c], m[2][c]];
            let (dr, dr1, dr2) = (col(&w[0]), col(&w[1]), col(&w[2]));
            out.gap[k] = -dot(dr, n);
            let x = solve([
                zeta * dot(dr1, n) - dot(dr, rho[0]),
                zeta * dot(dr2, n) - dot(dr, rho[1]),
            ]);
            out.xi[0][k] = x[0];
            out.xi[1][k] = x[1];
        }
    }
    out
}

/// Per facet node `I`: `[∂ρ/∂x_I, ∂ρ_1/∂x_I, ∂ρ_2/∂x_I]` at `ξ` as 3×3 matrices (row-major).
fn node_weights<S: Scalar>(xi: [S; 2], bend: Option<&Bend>) -> [[[[S; 3]; 3]; 3]; 4] {
    let zero = S::from(0.0);
    let diag = |v: S| {
        let mut m = [[zero; 3]; 3];
        (0..3).for_each(|i| m[i][i] = v);
        m
    };
    let shape = Facet::<S>::shape(xi);
    let gradients = Facet::<S>::shape_gradients(xi);
    let mut w: [[[[S; 3]; 3]; 3]; 4] =
        std::array::from_fn(|i| [diag(shape[i]), diag(gradients[i][0]), diag(gradients[i][1])]);
    if let Some(bend) = bend {
        for (e, bubble) in Bend::bubbles(xi).into_iter().enumerate() {
            let (a, b) = EDGES[e];
            let factors = [bubble.value, bubble.d[0], bubble.d[1]];
            for (which, f) in factors.into_iter().enumerate() {
                for (i, row) in bend.q[e].iter().enumerate() {
                    for (j, &q) in row.iter().enumerate() {
                        let v = f * q;
                        let (at_b, at_a) = (w[b][which][i][j], w[a][which][i][j]);
                        w[b][which][i][j] = at_b - v;
                        w[a][which][i][j] = at_a + v;
                    }
                }
            }
        }
    }
    w
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact3d::nagata::bend_of;
    use crate::contact3d::projection::project;
    use crate::contact3d::vec3::V3;
    use num_dual::Dual2SVec64;

    /// A warped facet and a slave off it, bilinear and bent into a Nagata patch (normals
    /// tilted off the facet's): the closed forms equal the gradients that second-order duals
    /// give, and their dual parts the Hessians.
    #[test]
    fn closed_forms_equal_the_derivatives_of_the_projection() {
        let x: [[f64; 3]; 5] = [
            [0.2, 0.1, 0.3],
            [-1.0, -1.1, 0.05],
            [1.2, -0.9, -0.1],
            [0.9, 1.0, 0.2],
            [-1.1, 0.8, -0.05],
        ];
        let normals = [[-0.3, -0.3, 1.0], [0.3, -0.2, 1.0], [0.25, 0.3, 1.0], [-0.3, 0.2, 1.0]];
        let bend = bend_of(&normals.map(|n| crate::contact3d::vec3::scale(n, 1.0 / crate::contact3d::vec3::norm(n))));
        type D = Dual2SVec64<DOFS>;
        let q: [V3<D>; 5] = std::array::from_fn(|i| std::array::from_fn(|c| D::from_re(x[i][c]).derivative(3 * i + c)));
        for bend in [None, Some(bend)] {
            let facet = Facet {
                x: [q[1], q[2], q[3], q[4]],
                bend,
            };
            let p = project(&facet, q[0]).unwrap();
            let v = variations(&p, bend.as_ref());
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
            assert!(
                worst < 1e-11,
                "closed forms against second-order duals (bent: {}): {worst:e}",
                bend.is_some()
            );
        }
    }
}
