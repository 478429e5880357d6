//! Master surfaces: one file per kind of master segment, each implementing
//! [`MasterSegment`] (its parametrisation `ρ(ξ)`, `ξ ∈ [−1, 1]`, and the closest point of a
//! slave). [`super::geometry::SegmentGeom`] dispatches over them; a new surface (a
//! C1-smoothed face, later 3D facets) is one new file here and one arm there.
//!
//! Conventions (all kinds): `ρ_1 = ∂ρ/∂ξ`, `a11 = ρ_1·ρ_1`, outward normal `n = ρ_1` turned by
//! −90° (the body lies on the left of the direction of increasing `ξ`), signed gap
//! `ζ = (r_s − ρ(ξ))·n`, negative when the slave has penetrated.

pub mod bezier;
pub mod face;
pub mod hermite;
pub mod rigid_arc;
pub mod rigid_line;

use super::geometry::Projection;
use super::scalar::{dot, sub, Scalar, V2};
use face::line_closest;

/// One master segment in the current configuration, in scalar type `S` (plain or dual).
pub trait MasterSegment<S: Scalar> {
    /// `ρ(ξ)` and `ρ_1(ξ)`.
    fn eval(&self, xi: S) -> (V2<S>, V2<S>);
    /// `ξ` of the closest point of the segment's curve (extended past its ends) to `rs`.
    fn closest_xi(&self, rs: V2<S>) -> S;
    /// Current length (arc length for curved segments).
    fn length(&self) -> S;
    /// Signed arc length from `ξ = from` to `ξ = to` along the curve (extended past the
    /// ends by its own formula). The default is exact for a curve of constant speed
    /// `|ρ_1|` (lines and arcs); curved face segments integrate `|ρ_1|`.
    fn arc_length(&self, from: S, to: S) -> S {
        let (_, rho1) = self.eval(from);
        (to - from) * dot(rho1, rho1).sqrt()
    }
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

/// Newton iterations on the real parts before the two steps in `S`.
const REAL_ITERATIONS: usize = 30;

/// Closest point `ξ` of `rs` on a smooth curved segment given by `eval2(ξ) = (ρ, ρ_1, ρ_11)`
/// (`real` on the real parts, `dual` in `S`) with chord ends `chord`: Newton's method on
/// `(r_s − ρ(ξ))·ρ_1(ξ) = 0`, first on the real parts (from the chord's projection, kept in
/// `[−3, 3]`), then two more steps in `S`. From a converged real root, the Newton steps in
/// dual numbers give the exact first and second derivatives of `ξ` with respect to every
/// node (the implicit-function derivatives), so the contact kernel's tangent stays
/// consistent.
pub(crate) fn smooth_closest_xi<S: Scalar>(
    real: &dyn Fn(f64) -> (V2<f64>, V2<f64>, V2<f64>),
    dual: &dyn Fn(S) -> (V2<S>, V2<S>, V2<S>),
    chord: (V2<f64>, V2<f64>),
    rs: V2<S>,
) -> S {
    let rsr = [rs[0].re(), rs[1].re()];
    let mut xi = line_closest(chord.0, chord.1, rsr).clamp(-3.0, 3.0);
    for _ in 0..REAL_ITERATIONS {
        let (rho, r1, r11) = real(xi);
        let d = sub(rsr, rho);
        let (g, dg) = (dot(d, r1), dot(d, r11) - dot(r1, r1));
        if dg.abs() < f64::MIN_POSITIVE {
            break;
        }
        let step = g / dg;
        xi = (xi - step).clamp(-3.0, 3.0);
        if step.abs() < 1e-15 {
            break;
        }
    }
    let mut x = S::from(xi);
    for _ in 0..2 {
        let (rho, r1, r11) = dual(x);
        let d = sub(rs, rho);
        x -= dot(d, r1) / (dot(d, r11) - dot(r1, r1));
    }
    x
}

/// `∫ |ρ_1| dξ` from `from` to `to` by 5-point Gauss–Legendre (`rho1(ξ)` = `ρ_1`): exact to
/// about 1e-8 of a segment for the smooth curves of a face; in dual numbers it carries
/// the derivatives of the quadrature formula itself, so tangents built on it are consistent.
pub(crate) fn smooth_arc_length<S: Scalar>(rho1: &dyn Fn(S) -> V2<S>, from: S, to: S) -> S {
    const X: [f64; 5] = [
        0.0,
        -0.538_469_310_105_683,
        0.538_469_310_105_683,
        -0.906_179_845_938_664,
        0.906_179_845_938_664,
    ];
    const W: [f64; 5] = [
        0.568_888_888_888_889,
        0.478_628_670_499_366,
        0.478_628_670_499_366,
        0.236_926_885_056_189,
        0.236_926_885_056_189,
    ];
    let half = (to - from) * 0.5;
    let centre = (to + from) * 0.5;
    X.iter().zip(W).fold(S::from(0.0), |acc, (&x, w)| {
        let r1 = rho1(centre + half * x);
        acc + dot(r1, r1).sqrt() * half * w
    })
}
