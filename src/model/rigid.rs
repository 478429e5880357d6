//! Rigid analytic geometry: surfaces made of straight pieces and circular arcs, and rigid
//! points, each moving by a prescribed translation.
//!
//! Orientation rule (shared with deformable faces): a surface is listed so that the rigid
//! body lies to the *left* of the direction of travel; its outward normal is the tangent
//! turned by −90°, `n = (t_y, −t_x)`. An arc listed with increasing angle (counter-clockwise)
//! is therefore the convex outside of a disc.

use super::ramp::Ramp;

/// One smooth piece of a rigid surface, parametrised by `ξ ∈ [−1, 1]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Piece {
    /// Straight segment from `a` (`ξ = −1`) to `b` (`ξ = +1`).
    Segment { a: [f64; 2], b: [f64; 2] },
    /// Circular arc `c + r (cos θ, sin θ)`, `θ = θ₀ + (ξ + 1)(θ₁ − θ₀)/2` (radians).
    Arc {
        centre: [f64; 2],
        radius: f64,
        theta0: f64,
        theta1: f64,
    },
}

impl Piece {
    /// Reference position and covariant tangent `ρ_1 = ∂ρ/∂ξ` at `ξ` (no motion applied).
    pub fn eval(&self, xi: f64) -> ([f64; 2], [f64; 2]) {
        match *self {
            Piece::Segment { a, b } => {
                let p = [
                    0.5 * (1.0 - xi) * a[0] + 0.5 * (1.0 + xi) * b[0],
                    0.5 * (1.0 - xi) * a[1] + 0.5 * (1.0 + xi) * b[1],
                ];
                (p, [0.5 * (b[0] - a[0]), 0.5 * (b[1] - a[1])])
            }
            Piece::Arc {
                centre,
                radius,
                theta0,
                theta1,
            } => {
                let th = theta0 + 0.5 * (xi + 1.0) * (theta1 - theta0);
                let dth = 0.5 * (theta1 - theta0);
                (
                    [centre[0] + radius * th.cos(), centre[1] + radius * th.sin()],
                    [-radius * th.sin() * dth, radius * th.cos() * dth],
                )
            }
        }
    }

    /// Polyline points for drawing (reference configuration).
    pub fn polyline(&self, n: usize) -> Vec<[f64; 2]> {
        match self {
            Piece::Segment { a, b } => vec![*a, *b],
            Piece::Arc { .. } => (0..=n).map(|i| self.eval(-1.0 + 2.0 * i as f64 / n as f64).0).collect(),
        }
    }
}

/// Shape of a rigid body.
#[derive(Debug, Clone, PartialEq)]
pub enum RigidShape {
    /// A rigid point (e.g. a sharp corner used as a contact slave).
    Point { at: [f64; 2] },
    /// A chain of pieces; piece `k` neighbours `k − 1` and `k + 1` when their ends meet.
    Surface { pieces: Vec<Piece> },
}

/// A rigid body and its prescribed translation `(u_x(t), u_y(t))`.
#[derive(Debug, Clone, PartialEq)]
pub struct RigidBody {
    pub name: String,
    pub shape: RigidShape,
    pub motion: [Ramp; 2],
}

impl RigidBody {
    pub fn offset(&self, t: f64) -> [f64; 2] {
        [self.motion[0].at(t), self.motion[1].at(t)]
    }

    /// Reference position of a rigid point, or of vertex `vertex` of an outline (`None`
    /// when the body has no such vertex).
    pub fn vertex(&self, vertex: usize) -> Option<[f64; 2]> {
        match &self.shape {
            RigidShape::Point { at } => (vertex == 0).then_some(*at),
            RigidShape::Surface { pieces } => {
                let end = |p: &Piece, xi: f64| p.eval(xi).0;
                match vertex {
                    0 => pieces.first().map(|p| end(p, -1.0)),
                    v => pieces.get(v - 1).map(|p| end(p, 1.0)),
                }
            }
        }
    }
}
