//! A circular-arc piece of a rigid outline (already translated by the body's motion).
//!
//! `ρ = c + r (cos θ, sin θ)`, `θ = θ₀ + (ξ + 1)(θ₁ − θ₀)/2`,
//! `ρ_1 = r (θ₁ − θ₀)/2 (−sin θ, cos θ)`; closest point: `ξ` from the polar angle of
//! `r_s − c`, unwrapped about the arc's mid-angle. Counter-clockwise (`θ₁ > θ₀`) the outward
//! normal points away from the centre (a convex rigid body such as a cylinder); clockwise,
//! towards it (a concave seat).

use super::MasterSegment;
use crate::contact::scalar::{lift, sub, Scalar, V2};

/// Rigid arc of `radius` about `centre` from angle `theta0` (`ξ = −1`) to `theta1`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RigidArc {
    pub centre: [f64; 2],
    pub radius: f64,
    pub theta0: f64,
    pub theta1: f64,
}

impl<S: Scalar> MasterSegment<S> for RigidArc {
    fn eval(&self, xi: S) -> (V2<S>, V2<S>) {
        let dth = 0.5 * (self.theta1 - self.theta0);
        let th = xi * dth + (self.theta0 + dth);
        let (s, c) = (th.sin(), th.cos());
        let r = self.radius;
        (
            [c * r + self.centre[0], s * r + self.centre[1]],
            [s * (-r * dth), c * (r * dth)],
        )
    }
    fn closest_xi(&self, rs: V2<S>) -> S {
        let d = sub(rs, lift(self.centre));
        let mid = 0.5 * (self.theta0 + self.theta1);
        // rotate d by −mid, then atan2 gives the angle relative to the mid-angle
        let (sm, cm) = mid.sin_cos();
        let dx = d[0] * cm + d[1] * sm;
        let dy = d[1] * cm - d[0] * sm;
        dy.atan2(dx) * (2.0 / (self.theta1 - self.theta0))
    }
    fn length(&self) -> S {
        S::from(self.radius * (self.theta1 - self.theta0).abs())
    }
}
