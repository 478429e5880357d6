//! A segment of a deformable body's boundary face: linear between the current positions of
//! its two nodes (unknowns of the contact point, so dual numbers carry their derivatives).
//!
//! `ρ(ξ) = N1 x1 + N2 x2`, `N1,2 = (1 ∓ ξ)/2`, `ρ_1 = (x2 − x1)/2`; closest point
//! `ξ = (r_s − (x1 + x2)/2)·ρ_1 / a11` (exact for a straight segment). Faces run
//! counter-clockwise round their body, so `n` is outward.

use super::MasterSegment;
use crate::contact::scalar::{add, dot, scale, sub, Scalar, V2};

/// Linear face segment from `x1` (`ξ = −1`) to `x2` (`ξ = +1`).
#[derive(Debug, Clone, Copy)]
pub struct FaceSegment<S: Scalar> {
    pub x1: V2<S>,
    pub x2: V2<S>,
}

/// `ρ(ξ)`, `ρ_1` of the straight segment `x1 → x2` (shared with rigid lines).
pub(crate) fn line_eval<S: Scalar>(x1: V2<S>, x2: V2<S>, xi: S) -> (V2<S>, V2<S>) {
    let half = S::from(0.5);
    let mid = scale(add(x1, x2), half);
    let rho1 = scale(sub(x2, x1), half);
    (add(mid, scale(rho1, xi)), rho1)
}

/// Closest-point `ξ` on the straight line through `x1`, `x2`.
pub(crate) fn line_closest<S: Scalar>(x1: V2<S>, x2: V2<S>, rs: V2<S>) -> S {
    let half = S::from(0.5);
    let mid = scale(add(x1, x2), half);
    let rho1 = scale(sub(x2, x1), half);
    dot(sub(rs, mid), rho1) / dot(rho1, rho1)
}

impl<S: Scalar> MasterSegment<S> for FaceSegment<S> {
    fn eval(&self, xi: S) -> (V2<S>, V2<S>) {
        line_eval(self.x1, self.x2, xi)
    }
    fn closest_xi(&self, rs: V2<S>) -> S {
        line_closest(self.x1, self.x2, rs)
    }
    fn length(&self) -> S {
        let d = sub(self.x2, self.x1);
        dot(d, d).sqrt()
    }
}
