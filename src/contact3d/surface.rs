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
//!   can be non-zero (a warped facet);
//! - a **bent** facet (a Nagata patch, [`super::nagata`]) adds to the bilinear `ρ` one
//!   quadratic bubble per edge, `ρ(ξ) = N_I x_I − Σ_e φ_e(ξ) c_e` with `c_e = Q_e (x_b − x_a)`
//!   ([`Bend`]), so its `ρ_11`, `ρ_22` are not zero and `h_αβ` is a full curvature.

use super::vec3::{add, combine, cross, dot, norm, scale, sub, Scalar, V3};
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

/// A facet: its four nodes' current positions, bilinear or bent into a Nagata patch.
#[derive(Debug, Clone, Copy)]
pub struct Facet<S: Scalar> {
    pub x: [V3<S>; 4],
    /// `None`: bilinear.
    pub bend: Option<Bend>,
}

/// The edges of a facet as `(a, b)` node pairs, in the order of [`Bend::q`]: `ξ² = −1`
/// (1 → 2), `ξ¹ = 1` (2 → 3), `ξ² = 1` (4 → 3), `ξ¹ = −1` (1 → 4); each runs along
/// increasing `ξ`.
pub const EDGES: [(usize, usize); 4] = [(0, 1), (1, 2), (3, 2), (0, 3)];

/// The edge curvatures of a Nagata patch (Nagata, CAGD 22 (2005) 9–21): edge `e` from node
/// `a` to `b` is the quadratic `x(s) = x_a + s d − s(1 − s) c` (`s ∈ [0, 1]`, `d = x_b − x_a`)
/// whose end tangents are normal to the nodal normals, `c = Q d`, `Q` a 3×3 matrix of the
/// nodal normals alone ([`super::nagata::edge_matrix`]); row-major `q[e][i][j]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Bend {
    pub q: [[[f64; 3]; 3]; 4],
}

impl Bend {
    /// `c_e = Q_e (x_b − x_a)` of every edge.
    pub fn coefficients<S: Scalar>(&self, x: &[V3<S>; 4]) -> [V3<S>; 4] {
        std::array::from_fn(|e| {
            let (a, b) = EDGES[e];
            let d = super::vec3::sub(x[b], x[a]);
            self.q[e].map(|row| d[0] * row[0] + d[1] * row[1] + d[2] * row[2])
        })
    }

    /// The edge bubbles `φ_e(ξ)` and their first and second derivatives:
    /// `φ_e = b(ξ^α) · ½(1 ± ξ^γ)`, `α` the edge's direction, `γ` the other (`−` on the edges
    /// at `ξ^γ = −1`), `b(u) = ¼(1 − u²)` on the facet and continued by its tangent past
    /// `|u| = 1`, `b(u) = −½(|u| − 1)`: the patch's extension (where a point near an edge
    /// projects) goes on along the edge's tangent plane instead of curling back as the
    /// parabola would.
    pub fn bubbles<S: Scalar>(xi: [S; 2]) -> [Bubble<S>; 4] {
        // (direction α, side ±1 of the other coordinate γ)
        const EDGE_AXES: [(usize, f64); 4] = [(0, -1.0), (1, 1.0), (0, 1.0), (1, -1.0)];
        EDGE_AXES.map(|(al, side)| {
            let ga = 1 - al;
            let (u, v) = (xi[al], xi[ga]);
            let beyond = u.re().abs() > 1.0;
            let sign = S::from(u.re().signum());
            let (along, d_along, dd_along) = if beyond {
                ((S::from(1.0) - u * sign) * 0.5, sign * -0.5, S::from(0.0))
            } else {
                ((S::from(1.0) - u * u) * 0.25, u * -0.5, S::from(-0.5))
            };
            let across = (v * side + 1.0) * 0.5;
            let d_across = S::from(0.5 * side);
            let zero = S::from(0.0);
            let mut b = Bubble {
                value: along * across,
                d: [zero; 2],
                dd: [[zero; 2]; 2],
            };
            b.d[al] = d_along * across;
            b.d[ga] = along * d_across;
            b.dd[al][al] = across * dd_along;
            b.dd[al][ga] = d_along * d_across;
            b.dd[ga][al] = d_along * d_across;
            b
        })
    }
}

/// An edge bubble `φ_e(ξ)`, its gradient `φ_e,α` and Hessian `φ_e,αβ`.
#[derive(Debug, Clone, Copy)]
pub struct Bubble<S: Scalar> {
    pub value: S,
    pub d: [S; 2],
    pub dd: [[S; 2]; 2],
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
        Facet::flat(x.map(super::vec3::lift))
    }

    /// A bilinear facet on nodes `x`.
    pub fn flat(x: [V3<S>; 4]) -> Self {
        Facet { x, bend: None }
    }

    /// The same facet in plain numbers (the bend is data).
    pub fn real(&self) -> Facet<f64> {
        Facet {
            x: self.x.map(super::vec3::re::<S>),
            bend: self.bend,
        }
    }

    /// Shape functions `N_I(ξ)`.
    pub fn shape(xi: [S; 2]) -> [S; 4] {
        NODE_XI.map(|[a, b]| (xi[0] * a + 1.0) * (xi[1] * b + 1.0) * 0.25)
    }

    /// `ρ(ξ) = N_I x_I` (`− Σ_e φ_e c_e` when bent).
    pub fn position(&self, xi: [S; 2]) -> V3<S> {
        let n = Self::shape(xi);
        let mut p = scale(self.x[0], n[0]);
        for (x, ni) in self.x.iter().zip(n).skip(1) {
            p = add(p, scale(*x, ni));
        }
        if let Some(bend) = &self.bend {
            for (c, b) in bend.coefficients(&self.x).into_iter().zip(Bend::bubbles(xi)) {
                p = sub(p, scale(c, b.value));
            }
        }
        p
    }

    /// Shape function derivatives `[∂N_I/∂ξ¹, ∂N_I/∂ξ²]` of each node `I`.
    pub fn shape_gradients(xi: [S; 2]) -> [[S; 2]; 4] {
        NODE_XI.map(|[a, b]| [(xi[1] * b + 1.0) * (0.25 * a), (xi[0] * a + 1.0) * (0.25 * b)])
    }

    /// `ρ_α(ξ) = ∂N_I/∂ξ^α x_I` (`− Σ_e φ_e,α c_e` when bent).
    pub fn tangents(&self, xi: [S; 2]) -> [V3<S>; 2] {
        let zero = S::from(0.0);
        let mut t = [[zero; 3]; 2];
        for (x, [d1, d2]) in self.x.iter().zip(Self::shape_gradients(xi)) {
            t[0] = add(t[0], scale(*x, d1));
            t[1] = add(t[1], scale(*x, d2));
        }
        if let Some(bend) = &self.bend {
            for (c, b) in bend.coefficients(&self.x).into_iter().zip(Bend::bubbles(xi)) {
                t[0] = sub(t[0], scale(c, b.d[0]));
                t[1] = sub(t[1], scale(c, b.d[1]));
            }
        }
        t
    }

    /// The twist `ρ_12 = ¼ Σ ξ¹_I ξ²_I x_I` of the bilinear part (constant over the facet).
    pub fn twist(&self) -> V3<S> {
        let mut t = scale(self.x[0], S::from(0.25));
        for (i, [a, b]) in NODE_XI.iter().enumerate().skip(1) {
            t = add(t, scale(self.x[i], S::from(0.25 * a * b)));
        }
        t
    }

    /// `ρ_αβ(ξ)`: the twist alone on a bilinear facet (`ρ_11 = ρ_22 = 0`), plus
    /// `− Σ_e φ_e,αβ c_e` when bent.
    pub fn second_derivatives(&self, xi: [S; 2]) -> [[V3<S>; 2]; 2] {
        let zero = [S::from(0.0); 3];
        let twist = self.twist();
        let mut h = [[zero, twist], [twist, zero]];
        if let Some(bend) = &self.bend {
            for (c, b) in bend.coefficients(&self.x).into_iter().zip(Bend::bubbles(xi)) {
                for (row, brow) in h.iter_mut().zip(b.dd) {
                    for (v, bv) in row.iter_mut().zip(brow) {
                        *v = sub(*v, scale(c, bv));
                    }
                }
            }
        }
        h
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
        let curvature = self.second_derivatives(xi).map(|row| row.map(|v| dot(v, normal)));
        Ok(FacetPoint {
            xi,
            rho,
            tangents,
            metric: [[a11, a12], [a12, a22]],
            inverse: [[a22 * inv_det, -a12 * inv_det], [-a12 * inv_det, a11 * inv_det]],
            normal,
            curvature,
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
