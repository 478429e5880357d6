//! A straight piece of a rigid outline (already translated by the body's prescribed motion):
//! fixed geometry, no unknowns. Same parametrisation as a face segment
//! ([`super::face`]); the rigid body lies on the left of `a → b`.

use super::face::{line_closest, line_eval};
use super::MasterSegment;
use crate::contact::scalar::{lift, Scalar, V2};

/// Rigid straight segment from `a` (`ξ = −1`) to `b` (`ξ = +1`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RigidLine {
    pub a: [f64; 2],
    pub b: [f64; 2],
}

impl<S: Scalar> MasterSegment<S> for RigidLine {
    fn eval(&self, xi: S) -> (V2<S>, V2<S>) {
        line_eval(lift(self.a), lift(self.b), xi)
    }
    fn closest_xi(&self, rs: V2<S>) -> S {
        line_closest(lift(self.a), lift(self.b), rs)
    }
    fn length(&self) -> S {
        S::from((self.b[0] - self.a[0]).hypot(self.b[1] - self.a[1]))
    }
}
