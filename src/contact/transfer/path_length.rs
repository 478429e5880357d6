//! Path-length transfer (Wriggers, Krstulovic-Opara & Korelc, IJNME 51 (2001) 1469–1495).

use super::{Transfer, TransferInput};
use crate::contact::scalar::Scalar;

/// The tangential slip is the arc length `Δs` travelled by the contact point along the
/// current master surface, accumulated across segment boundaries (2D only):
/// `t^tr = t^(n) − ε_T Δs` for the physical traction along the unit tangent, with
/// `t^(n) = T_1^(n)/√a11^(n)`, and `T_1^tr = t^tr √a11^B`.
pub struct PathLength;

impl Transfer for PathLength {
    fn trial<S: Scalar>(&self, i: &TransferInput<S>) -> S {
        let t_old = i.stored.t1 / i.stored.a11.sqrt();
        (S::from(t_old) - i.arc_length * i.eps_t) * i.current.a11.sqrt()
    }
}
