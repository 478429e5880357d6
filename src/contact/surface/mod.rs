//! Master surfaces: one file per kind of master segment, each implementing
//! [`MasterSegment`] (its parametrisation `ρ(ξ)`, `ξ ∈ [−1, 1]`, and the closest point of a
//! slave). [`super::geometry::SegmentGeom`] dispatches over them; a new surface (a
//! C1-smoothed face, later 3D facets) is one new file here and one arm there.
//!
//! Conventions (all kinds): `ρ_1 = ∂ρ/∂ξ`, `a11 = ρ_1·ρ_1`, outward normal `n = ρ_1` turned by
//! −90° (the body lies on the left of the direction of increasing `ξ`), signed gap
//! `ζ = (r_s − ρ(ξ))·n`, negative when the slave has penetrated.

pub mod face;
pub mod hermite;
pub mod rigid_arc;
pub mod rigid_line;

use super::geometry::Projection;
use super::scalar::{dot, sub, Scalar, V2};

/// One master segment in the current configuration, in scalar type `S` (plain or dual).
pub trait MasterSegment<S: Scalar> {
    /// `ρ(ξ)` and `ρ_1(ξ)`.
    fn eval(&self, xi: S) -> (V2<S>, V2<S>);
    /// `ξ` of the closest point of the segment's curve (extended past its ends) to `rs`.
    fn closest_xi(&self, rs: V2<S>) -> S;
    /// Current length (arc length for curved segments).
    fn length(&self) -> S;
    /// Closest-point projection: `ξ`, `ρ`, `ρ_1`, `a11` and the signed gap `ζ`.
    fn project(&self, rs: V2<S>) -> Projection<S> {
        let xi = self.closest_xi(rs);
        let (rho, rho1) = self.eval(xi);
        let a11 = dot(rho1, rho1);
        let inv = a11.sqrt().recip();
        let n = [rho1[1] * inv, -rho1[0] * inv];
        Projection {
            xi,
            gap: dot(sub(rs, rho), n),
            rho,
            rho1,
            a11,
        }
    }
}
