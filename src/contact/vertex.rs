//! Contact of a slave point with a *vertex* of the master: the point-to-node form used in the
//! wedge of a concave master vertex (see [`super::pairing`], rule 3b).
//!
//! ```text
//!          segment A          │ n_A        n_B  /   segment B
//!   ──────────────────────────●  x_m  ─────────/──────────
//!          ↑ n_A    wedge:    ╱ ╲   ← r_s inside the body, past the end of A (ξ_A > 1)
//!                       (n_A) ╱   ╲ (n_B)   and before the start of B (ξ_B < −1)
//! ```
//!
//! Inside the body at a concave vertex `x_m` of a faceted face (the strip's bottom face
//! wrapped round the corner C), a penetrating slave point `r_s` between the two segment
//! normals projects onto neither segment. Node-to-segment contact then has no closest point;
//! holding the point on the extension of one segment makes the gap and normal jump when it
//! is handed to the other segment, and Newton cycles between the two (the 240×8, μ = 0
//! strip-channel failure). In the wedge the closest point of the master is the vertex
//! itself, so the point is pinned to it (`ξ = ±1` of the tracked segment, the end at `x_m`):
//!
//! - gap `ζ = −‖r_s − x_m‖` (always penetrating in the wedge), outward normal
//!   `n = −(r_s − x_m)/‖r_s − x_m‖`, so the normal energy is `½ ε_N ‖r_s − x_m‖²`: a spring
//!   between the slave and the vertex, force `ε_N (r_s − x_m)`;
//! - tangential force on the slave `t τ`, `τ = n` turned by +90° (the direction of `ρ_1`
//!   on the segments), `t = T_1/√a11` the physical traction returned by the law from the
//!   trial of the point held at the vertex (the transfer schemes see `ξ = ±1`): no slip
//!   accumulates while the point turns round the vertex.
//!
//! Both are continuous with the node-to-segment form at the wedge's boundaries: there
//! `r_s − x_m` is normal to the adjacent segment, so `ζ`, `n` and `τ` coincide with that
//! segment's at `ξ = ±1`, and so do the normal residual and the force on the slave; the
//! tangential shares of the adjacent segment's two nodes differ by a term of order `t ζ / l`
//! (the rotation of the segment moves the projected point, not the vertex). This is the node-to-node element of
//! the vertex region in Wriggers, Computational Contact Mechanics (2006), §9.1, in the
//! covariant notation of Konyukhov & Schweizerhof.

use super::geometry::{Projection, SegmentGeom};
use super::scalar::{dot, sub, Scalar, V2};
use nalgebra::{Const, U1};
use num_dual::{Dual2SVec64, DualNum};

/// Projection of `r_s` pinned to the end `end = ±1` of segment `g` (its vertex `x_m`):
/// `ξ = end`, `ρ = x_m`, `ρ_1 = ρ_1(end)`, `ζ = −‖r_s − x_m‖`.
pub fn pinned_projection<S: Scalar>(g: &SegmentGeom<S>, rs: V2<S>, end: f64) -> Projection<S> {
    let (rho, rho1) = g.eval(S::from(end));
    let d = sub(rs, rho);
    Projection {
        xi: S::from(end),
        gap: -dot(d, d).sqrt(),
        rho,
        rho1,
        a11: dot(rho1, rho1),
    }
}

/// Adds the tangential part of the point-to-vertex residual and its tangent:
/// `r_i −= f·∂(r_s − x_m)/∂q_i`, `K_ij −= ∂f/∂q_j · ∂(r_s − x_m)/∂q_i`, with the tangential
/// force on the slave `f = t τ`, `t = T_1/√a11`, `τ = ((r_s − x_m)_y, −(r_s − x_m)_x)/‖r_s − x_m‖`.
/// `r_s − x_m` is linear in the local unknowns, so it has no second derivative.
pub fn add_tangential<const N: usize>(
    rs: V2<Dual2SVec64<N>>,
    rho: V2<Dual2SVec64<N>>,
    t1: Dual2SVec64<N>,
    a11: Dual2SVec64<N>,
    r: &mut [f64],
    k: &mut [f64],
) {
    let d = sub(rs, rho);
    let dist = dot(d, d).sqrt();
    let t = t1 / a11.sqrt();
    let f = [t * d[1] / dist, -(t * d[0]) / dist];
    for c in 0..2 {
        let gd = d[c].v1.unwrap_generic(U1, Const::<N>);
        let gf = f[c].v1.unwrap_generic(U1, Const::<N>);
        for i in 0..N {
            r[i] -= f[c].re * gd[i];
            for j in 0..N {
                k[N * i + j] -= gf[j] * gd[i];
            }
        }
    }
}
