//! Spatial increments (Puso & Laursen, IJNME 54 (2002) 1161–1194; the seed: "3D
//! coordinates of slave nodes are stored, but the geometry of the contact segments is no
//! longer captured").

use super::{Transfer, TransferInput};
use crate::contact::scalar::{dot, lift, Scalar};

/// The history is spatial: the slave's position `r_s^(n)` and the traction vector
/// `t^(n) = t τ^(n)` at the last converged increment (`t` the physical traction, `τ^(n)` the
/// unit tangent there). The convective increment is formed geometrically on the current
/// segment `B`: `Δξ = ξ_B − ξ_B(r_s^(n))`, where `ξ_B(r_s^(n))` is the closest point of the
/// stored slave position on `B`'s current curve (extended past its ends); the old traction
/// is the stored vector's component along `B`:
///
/// `T_1^tr = t^(n)·ρ_1^B − ε_T a11^B Δξ`.
///
/// No segment `A`, no path: a crossing costs nothing, and on a master that stays put the
/// increment is the slave's motion along the surface (on one straight segment it is seed
/// eq. (1) exactly; across a boundary of collinear segments it is exact). What it cannot
/// see is the master's own motion over the increment: the stored position is projected on
/// the *current* master, so a slave that stays put while the master slides under it (the
/// strip-channel's corner C, a rigid die dragged over nodes, a drum's vertices under a
/// belt) measures no slip at all — with the master moving, the increment is not objective.
pub struct Spatial;

impl Transfer for Spatial {
    fn trial<S: Scalar>(&self, i: &TransferInput<S>) -> S {
        let t_old = i.stored.t1 / i.stored.a11.sqrt();
        let t_vec = lift::<S>([t_old * i.stored.tangent[0], t_old * i.stored.tangent[1]]);
        let dxi = i.current.xi - i.stored_slave_xi;
        dot(t_vec, i.current.rho1) - i.current.a11 * dxi * i.eps_t
    }
}
