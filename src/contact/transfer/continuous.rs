//! Continuous transfer by parallel translation (seed eqs. 2–4).

use super::{Transfer, TransferInput};
use crate::contact::scalar::{dot, sub, Scalar};

/// Seed eq. (3), written for the covariant component on `B`:
///
/// `T^1_B = T^1_A (ρ^A_1 · ρ_B^1) − ε_T (Δρ · ρ_B^1)`, `T_1^B = a11^B T^1_B`,
///
/// i.e. `T_1^tr = T^1_A (ρ^A_1 · ρ^B_1) − ε_T (Δρ · ρ^B_1)` with `T^1_A = T_1^(n)/a11^(n)`,
/// `Δρ = ρ_B(ξ_B) − ρ_A(ξ_A)` (seed eq. 2), both in the current configuration. For `A = B`
/// on a linear segment `Δρ = Δξ ρ_1` and this is seed eq. (1) in contravariant form.
/// The sliding anchor follows by the same translation (seed eq. 4); see
/// [`crate::contact::point`], where it is derived from the returned traction.
pub struct Continuous;

impl Transfer for Continuous {
    fn trial<S: Scalar>(&self, i: &TransferInput<S>) -> S {
        let t_contra_a = i.stored.t1 / i.stored.a11;
        let drho = sub(i.current.rho, i.old.rho);
        dot(i.old.rho1, i.current.rho1) * t_contra_a - dot(drho, i.current.rho1) * i.eps_t
    }
}
