//! Master-segment geometry in the current configuration and the closest-point projection
//! (covariant description, Konyukhov & Schweizerhof, Comput Mech 35 (2005); notes §"Master
//! segment").
//!
//! Conventions:
//! - every master segment is parametrised by `ξ ∈ [−1, 1]`; `ρ(ξ)` is the surface point,
//!   `ρ_1 = ∂ρ/∂ξ` the covariant tangent, `a11 = ρ_1·ρ_1`, `ρ^1 = ρ_1 / a11`;
//! - the unit normal is `ρ_1` turned by −90°: `n = (ρ_1,y, −ρ_1,x)/√a11`, which is the
//!   *outward* normal of the master body when its boundary runs counter-clockwise
//!   (deformable faces) or with the body on the left (rigid surfaces);
//! - the signed gap is `ζ = (r_s − ρ(ξ))·n`: `ζ < 0` means the slave has penetrated.
//!
//! A projection with `|ξ| > 1` belongs to a neighbouring segment; the search in
//! [`super::search`] walks there.

use super::scalar::{Scalar, V2};
use super::surface::bezier::BezierSegment;
use super::surface::face::FaceSegment;
use super::surface::hermite::HermiteSegment;
use super::surface::rigid_arc::RigidArc;
use super::surface::rigid_line::RigidLine;
use super::surface::MasterSegment;
use crate::model::Piece;

/// A master segment with its current geometry in scalar type `S`: one arm per kind of
/// [`MasterSegment`] (one file each in [`super::surface`]).
#[derive(Debug, Clone, Copy)]
pub enum SegmentGeom<S: Scalar> {
    /// Segment of a deformable face between the current positions of two nodes.
    Face(FaceSegment<S>),
    /// C1-smoothed segment of a deformable face (cubic Hermite through its neighbours).
    Hermite(HermiteSegment<S>),
    /// C1-smoothed segment of a deformable face (quadratic Bézier arcs between midpoints).
    Bezier(BezierSegment<S>),
    /// Straight piece of a rigid outline.
    RigidLine(RigidLine),
    /// Circular-arc piece of a rigid outline.
    RigidArc(RigidArc),
}

/// Result of the closest-point projection of a slave point onto one segment.
#[derive(Debug, Clone, Copy)]
pub struct Projection<S: Scalar> {
    /// Convective coordinate of the contact point (not clamped to `[−1, 1]`).
    pub xi: S,
    /// Signed normal gap `ζ` (negative = penetration).
    pub gap: S,
    /// Contact point `ρ(ξ)`.
    pub rho: V2<S>,
    /// Covariant tangent `ρ_1(ξ)`.
    pub rho1: V2<S>,
    /// Metric `a11 = ρ_1·ρ_1`.
    pub a11: S,
}

impl<S: Scalar> Projection<S> {
    /// Unit outward normal `n`.
    pub fn normal(&self) -> V2<S> {
        let inv = self.a11.sqrt().recip();
        [self.rho1[1] * inv, -self.rho1[0] * inv]
    }
}

impl<S: Scalar> SegmentGeom<S> {
    /// Linear face segment from `x1` (`ξ = −1`) to `x2` (`ξ = +1`).
    pub fn linear(x1: V2<S>, x2: V2<S>) -> Self {
        SegmentGeom::Face(FaceSegment { x1, x2 })
    }

    /// Hermite face segment `x1 → x2` with its neighbouring nodes (see [`HermiteSegment`]).
    pub fn hermite(x0: Option<V2<S>>, x1: V2<S>, x2: V2<S>, x3: Option<V2<S>>) -> Self {
        SegmentGeom::Hermite(HermiteSegment { x0, x1, x2, x3 })
    }

    /// Bézier face segment `x1 → x2` with its neighbouring nodes (see [`BezierSegment`]).
    pub fn bezier(x0: Option<V2<S>>, x1: V2<S>, x2: V2<S>, x3: Option<V2<S>>) -> Self {
        SegmentGeom::Bezier(BezierSegment { x0, x1, x2, x3 })
    }

    /// Rigid piece translated by `offset`.
    pub fn from_piece(piece: &Piece, offset: [f64; 2]) -> Self {
        match *piece {
            Piece::Segment { a, b } => SegmentGeom::RigidLine(RigidLine {
                a: [a[0] + offset[0], a[1] + offset[1]],
                b: [b[0] + offset[0], b[1] + offset[1]],
            }),
            Piece::Arc {
                centre,
                radius,
                theta0,
                theta1,
            } => SegmentGeom::RigidArc(RigidArc {
                centre: [centre[0] + offset[0], centre[1] + offset[1]],
                radius,
                theta0,
                theta1,
            }),
        }
    }

    fn surface(&self) -> &dyn MasterSegment<S> {
        match self {
            SegmentGeom::Face(f) => f,
            SegmentGeom::Hermite(h) => h,
            SegmentGeom::Bezier(b) => b,
            SegmentGeom::RigidLine(l) => l,
            SegmentGeom::RigidArc(a) => a,
        }
    }

    /// `ρ(ξ)` and `ρ_1(ξ)` at a given convective coordinate.
    pub fn eval(&self, xi: S) -> (V2<S>, V2<S>) {
        self.surface().eval(xi)
    }

    /// Closest-point projection of `rs` (explicit for every kind, see its file).
    pub fn project(&self, rs: V2<S>) -> Projection<S> {
        self.surface().project(rs)
    }

    /// Current length of the segment (arc length for arcs).
    pub fn length(&self) -> S {
        self.surface().length()
    }

    /// Signed arc length along the segment's curve from `ξ = from` to `ξ = to`.
    pub fn arc_length(&self, from: S, to: S) -> S {
        self.surface().arc_length(from, to)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact::scalar::{dot, sub};

    #[test]
    fn linear_projection_and_sign_convention() {
        // bottom face of a body running +x: outward normal is −y
        let s = SegmentGeom::<f64>::linear([0.0, 0.0], [2.0, 0.0]);
        let p = s.project([1.5, 0.1]); // slave above the bottom face = inside the body
        assert!((p.xi - 0.5).abs() < 1e-15);
        assert!((p.gap + 0.1).abs() < 1e-15, "penetration is negative");
        assert_eq!(p.normal(), [0.0, -1.0]);
        assert!((p.a11 - 1.0).abs() < 1e-15);
    }

    #[test]
    fn arc_projection_counter_clockwise_is_outside_of_disc() {
        let s = SegmentGeom::<f64>::RigidArc(RigidArc {
            centre: [0.0, 0.0],
            radius: 2.0,
            theta0: -2.5,
            theta1: -0.6,
        });
        let mid = -1.55f64;
        let p = s.project([3.0 * mid.cos(), 3.0 * mid.sin()]);
        assert!(p.xi.abs() < 1e-12);
        assert!((p.gap - 1.0).abs() < 1e-12);
        let n = p.normal();
        assert!((n[0] - mid.cos()).abs() < 1e-12 && (n[1] - mid.sin()).abs() < 1e-12);
        // the end points map to ξ = ±1
        let (r1, _) = s.eval(1.0);
        assert!((s.project([r1[0] * 1.1, r1[1] * 1.1]).xi - 1.0).abs() < 1e-12);
        assert!((s.length() - 3.8).abs() < 1e-12);
    }

    #[test]
    fn projection_is_orthogonal() {
        let s = SegmentGeom::<f64>::linear([0.3, -0.2], [1.7, 0.9]);
        let rs = [0.4, 1.1];
        let p = s.project(rs);
        let d = sub(rs, p.rho);
        assert!(dot(d, p.rho1).abs() < 1e-14);
    }
}
