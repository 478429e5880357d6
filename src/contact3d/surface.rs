//! Geometry of a 4-node bilinear master facet in the current configuration (covariant
//! description: Konyukhov & Schweizerhof, Comput Mech 35 (2005) 190–213, §2; notes
//! `contact-3d.md` §"Surfaces").
//!
//! Conventions:
//! - nodes `x_1..x_4` run counter-clockwise seen from *outside* the master body; node `I`
//!   sits at `(ξ¹, ξ²) = ` [`NODE_XI`]`[I]`, i.e. `(−1,−1), (1,−1), (1,1), (−1,1)`;
//! - `ρ(ξ) = N_I(ξ) x_I` with `N_I = ¼ (1 + ξ¹_I ξ¹)(1 + ξ²_I ξ²)`;
//! - covariant tangents `ρ_α = ∂ρ/∂ξ^α`, metric `a_αβ = ρ_α·ρ_β`, inverse `a^αβ`,
//!   contravariant tangents `ρ^α = a^αβ ρ_β`;
//! - unit normal `n = ρ_1 × ρ_2 / |ρ_1 × ρ_2|`, outward by the node order above;
//! - curvature `h_αβ = ρ_αβ·n`: for a bilinear facet `ρ_11 = ρ_22 = 0` and
//!   `ρ_12 = ¼ Σ ξ¹_I ξ²_I x_I` (the *twist*, zero on a parallelogram), so only `h_12 = h_21`
//!   can be non-zero (a warped facet).

use super::vec3::{add, combine, cross, dot, norm, scale, Scalar, V3};
use thiserror::Error;

/// Convective coordinates of the facet's nodes, in node order.
pub const NODE_XI: [[f64; 2]; 4] = [[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]];

/// Smallest `|ρ_1 × ρ_2|² / (a_11 a_22)` (the squared sine of the angle between the
/// tangents) of a usable facet point: below it the metric is taken as singular.
pub const MIN_SIN2: f64 = 1e-20;

/// A facet point where the geometry is unusable.
#[derive(Debug, Clone, Copy, PartialEq, Error)]
pub enum GeometryError {
    /// The tangents are (nearly) parallel or zero: `a_αβ` cannot be inverted.
    #[error("degenerate facet at xi = {xi:?}: sin^2 of the tangents' angle is {sin2:e}")]
    Degenerate { xi: [f64; 2], sin2: f64 },
    /// A coordinate or a derived quantity is not finite.
    #[error("non-finite facet geometry at xi = {xi:?}")]
    NonFinite { xi: [f64; 2] },
}

/// A bilinear facet: its four nodes' current positions.
#[derive(Debug, Clone, Copy)]
pub struct Facet<S: Scalar> {
    pub x: [V3<S>; 4],
}

/// The local geometry of a facet at one point `ξ`.
#[derive(Debug, Clone, Copy)]
pub struct FacetPoint<S: Scalar> {
    pub xi: [S; 2],
    /// `ρ(ξ)`.
    pub rho: V3<S>,
    /// `ρ_1, ρ_2`.
    pub tangents: [V3<S>; 2],
    /// `a_αβ`.
    pub metric: [[S; 2]; 2],
    /// `a^αβ`.
    pub inverse: [[S; 2]; 2],
    /// Unit outward normal `n`.
    pub normal: V3<S>,
    /// `h_αβ = ρ_αβ·n` (only the twist term of a bilinear facet).
    pub curvature: [[S; 2]; 2],
}

impl<S: Scalar> Facet<S> {
    /// Lift a plain facet into scalar type `S` (constants: no derivatives).
    pub fn lift(x: &[[f64; 3]; 4]) -> Self {
        Facet {
            x: x.map(super::vec3::lift),
        }
    }

    /// Shape functions `N_I(ξ)`.
    pub fn shape(xi: [S; 2]) -> [S; 4] {
        NODE_XI.map(|[a, b]| (xi[0] * a + 1.0) * (xi[1] * b + 1.0) * 0.25)
    }

    /// `ρ(ξ) = N_I x_I`.
    pub fn position(&self, xi: [S; 2]) -> V3<S> {
        let n = Self::shape(xi);
        let mut p = scale(self.x[0], n[0]);
        for (x, ni) in self.x.iter().zip(n).skip(1) {
            p = add(p, scale(*x, ni));
        }
        p
    }

    /// Shape function derivatives `[∂N_I/∂ξ¹, ∂N_I/∂ξ²]` of each node `I`.
    pub fn shape_gradients(xi: [S; 2]) -> [[S; 2]; 4] {
        NODE_XI.map(|[a, b]| [(xi[1] * b + 1.0) * (0.25 * a), (xi[0] * a + 1.0) * (0.25 * b)])
    }

    /// `ρ_α(ξ) = ∂N_I/∂ξ^α x_I`.
    pub fn tangents(&self, xi: [S; 2]) -> [V3<S>; 2] {
        let zero = S::from(0.0);
        let mut t = [[zero; 3]; 2];
        for (x, [d1, d2]) in self.x.iter().zip(Self::shape_gradients(xi)) {
            t[0] = add(t[0], scale(*x, d1));
            t[1] = add(t[1], scale(*x, d2));
        }
        t
    }

    /// The twist `ρ_12 = ¼ Σ ξ¹_I ξ²_I x_I` (constant over the facet; `ρ_11 = ρ_22 = 0`).
    pub fn twist(&self) -> V3<S> {
        let mut t = scale(self.x[0], S::from(0.25));
        for (i, [a, b]) in NODE_XI.iter().enumerate().skip(1) {
            t = add(t, scale(self.x[i], S::from(0.25 * a * b)));
        }
        t
    }

    /// Every local quantity at `ξ`, or why the facet is unusable there.
    pub fn point(&self, xi: [S; 2]) -> Result<FacetPoint<S>, GeometryError> {
        let xr = [xi[0].re(), xi[1].re()];
        let rho = self.position(xi);
        let tangents = self.tangents(xi);
        let [t1, t2] = tangents;
        let (a11, a12, a22) = (dot(t1, t1), dot(t1, t2), dot(t2, t2));
        let c = cross(t1, t2);
        let j2 = dot(c, c);
        let sin2 = j2.re() / (a11.re() * a22.re());
        if !sin2.is_finite() || !rho.iter().all(|v| v.re().is_finite()) {
            return Err(if a11.re() * a22.re() == 0.0 {
                GeometryError::Degenerate { xi: xr, sin2: 0.0 }
            } else {
                GeometryError::NonFinite { xi: xr }
            });
        }
        if sin2 < MIN_SIN2 {
            return Err(GeometryError::Degenerate { xi: xr, sin2 });
        }
        // det a = a11 a22 − a12² = |ρ_1 × ρ_2|²
        let inv_det = j2.recip();
        let normal = scale(c, j2.sqrt().recip());
        let h12 = dot(self.twist(), normal);
        let zero = S::from(0.0);
        Ok(FacetPoint {
            xi,
            rho,
            tangents,
            metric: [[a11, a12], [a12, a22]],
            inverse: [[a22 * inv_det, -a12 * inv_det], [-a12 * inv_det, a11 * inv_det]],
            normal,
            curvature: [[zero, h12], [h12, zero]],
        })
    }

    /// The longest edge or diagonal of the facet (a length scale for tolerances).
    pub fn size(&self) -> f64 {
        let r = self.x.map(super::vec3::re::<S>);
        let mut s: f64 = 0.0;
        for i in 0..4 {
            for j in i + 1..4 {
                s = s.max(norm(super::vec3::sub(r[i], r[j])));
            }
        }
        s
    }
}

impl<S: Scalar> FacetPoint<S> {
    /// Contravariant tangents `ρ^α = a^αβ ρ_β`.
    pub fn dual_basis(&self) -> [V3<S>; 2] {
        let a = &self.inverse;
        [
            combine([a[0][0], a[0][1]], self.tangents),
            combine([a[1][0], a[1][1]], self.tangents),
        ]
    }

    /// The spatial vector `T = T_α ρ^α = T_α a^αβ ρ_β` of covariant components `T_α`.
    pub fn vector(&self, covariant: [S; 2]) -> V3<S> {
        combine(covariant, self.dual_basis())
    }

    /// Covariant components `v·ρ_α` of a spatial vector (its normal part drops out).
    pub fn covariant(&self, v: V3<S>) -> [S; 2] {
        [dot(v, self.tangents[0]), dot(v, self.tangents[1])]
    }

    /// `a_αβ v^β`: lower an index.
    pub fn lower(&self, v: [S; 2]) -> [S; 2] {
        let a = &self.metric;
        [a[0][0] * v[0] + a[0][1] * v[1], a[1][0] * v[0] + a[1][1] * v[1]]
    }

    /// `a^αβ v_β`: raise an index.
    pub fn raise(&self, v: [S; 2]) -> [S; 2] {
        let a = &self.inverse;
        [a[0][0] * v[0] + a[0][1] * v[1], a[1][0] * v[0] + a[1][1] * v[1]]
    }

    /// The surface norm `‖T‖ = √(T_α a^αβ T_β)` of covariant components.
    pub fn norm(&self, covariant: [S; 2]) -> S {
        let up = self.raise(covariant);
        (covariant[0] * up[0] + covariant[1] * up[1]).sqrt()
    }
}
