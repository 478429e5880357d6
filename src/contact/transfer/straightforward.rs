//! Straightforward transfer (seed eq. 1 applied across segments as is).

use super::{Transfer, TransferInput};
use crate::contact::scalar::Scalar;

/// `T_1^tr = T_1^(n) − ε_T a11^B (ξ_B − ξ_A)`: the stored covariant component and the
/// convective increment are used as if `A` and `B` were one segment. On one segment this is
/// seed eq. (1); across a boundary (`ξ_A ≈ +1`, `ξ_B ≈ −1`) the increment is off by about
/// 2, and the trial traction jumps by about `2 ε_T √a11^B = ε_T ℓ_B` (seed ref. [5]).
pub struct Straightforward;

impl Transfer for Straightforward {
    fn trial<S: Scalar>(&self, i: &TransferInput<S>) -> S {
        let dxi = i.current.xi - i.stored.xi;
        S::from(i.stored.t1) - i.current.a11 * dxi * i.eps_t
    }
}
