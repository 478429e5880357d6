//! Convective coordinates on a rigid sphere, so that a slave can stick to it and slide on it
//! with Coulomb friction in the covariant form of the facet kernel ([`super::point`]), as on
//! the cylinder ([`super::cylinder`]).
//!
//! No chart covers a sphere without a singular point, so each slave gets its own: the
//! **stereographic projection** from the pole `c + R p`, `p` the unit vector from the slave's
//! reference position to the sphere's reference centre — the point of the sphere farthest
//! from where the slave meets it (a slave would have to slide half round the ball to reach
//! it). With `e_1, e_2 ⊥ p`, `e_1 × e_2 = −p`, and `u = ξ / R`, `s = |u|²`:
//!
//! `ρ(ξ) = c + R σ(u)`, `σ = (2 u_β e_β + (s − 1) p) / (1 + s)` (`ξ = 0` is the point nearest
//! the slave's reference position);
//!
//! - `ρ_α = ∂σ/∂u_α = (2 e_α (1 + s) − 4 u_α u_β e_β + 4 u_α p) / (1 + s)²`;
//! - the metric is conformal: `a_αβ = λ² δ_αβ`, `λ = 2 / (1 + s)`;
//! - `n = σ` (outward), `h_αβ = −a_αβ / R`.
//!
//! The closest point is closed-form: `q = (x − c)/|x − c|`, `u_α = q·e_α / (1 − q·p)`,
//! `ζ = |x − c| − R`; in the scalar type every quantity carries its derivatives, so the
//! kernel's closed-form variations (the slave's slot: `∇ζ = n`, `∇ξ^α = a^αβ ρ_β / (1 + ζ/R)`)
//! and their dual parts are exact. The chart is fixed in the sphere's frame (it moves by
//! translation), so a stick anchor keeps its meaning from increment to increment.

use super::projection::{Projection, ProjectionError};
use super::surface::{FacetPoint, GeometryError};
use super::vec3::{add, dot, lift, norm, scale, sub, Scalar, V3};

/// A rigid sphere about the slave's origin, with the pole of the slave's chart (see the
/// module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SphereChart {
    pub centre: [f64; 3],
    pub radius: f64,
    /// Unit vector from the centre to the chart's pole.
    pub pole: [f64; 3],
}

/// A chart point this close to the pole (`1 − q·p`) has no usable coordinates: the
/// stereographic coordinates grow as `R/(1 − q·p)`, so here they reach 10⁶ R and the metric
/// 10⁻¹² of its value at the slave's own point (the slave at the antipode of where it started
/// on the ball: a guard against the chart's singular point, not a contact rule).
const NEAR_POLE: f64 = 1e-6;

impl SphereChart {
    /// The chart of a slave at reference position `slave` against the sphere of reference
    /// centre `reference`, now centred at `centre` (about the slave's origin): the pole is
    /// the far side from the slave (`+z` if the slave sits at the centre).
    pub fn for_slave(centre: [f64; 3], radius: f64, reference: [f64; 3], slave: [f64; 3]) -> Self {
        let away = sub(reference, slave);
        let len = norm(away);
        let pole = if len > 0.0 {
            scale(away, 1.0 / len)
        } else {
            [0.0, 0.0, 1.0]
        };
        SphereChart { centre, radius, pole }
    }

    /// The closest point of `x` and its gap in this chart's coordinates. A slave at the
    /// centre, or seen from the centre at the pole, has none.
    pub fn project<S: Scalar>(&self, x: V3<S>) -> Result<Projection<S>, ProjectionError> {
        let r = self.radius;
        let p: V3<S> = lift(self.pole);
        let [e1, e2] = super::master::plane_axes(scale(self.pole, -1.0)).map(lift::<S>);
        let d = sub(x, lift(self.centre));
        let dist = norm(d);
        let q = scale(d, dist.recip());
        let below = S::from(1.0) - dot(q, p);
        let usable = dist.re() > 1e-12 * r && below.re() > NEAR_POLE;
        if !usable || !dist.re().is_finite() {
            return Err(GeometryError::Degenerate {
                xi: [0.0, 0.0],
                sin2: below.re(),
            }
            .into());
        }
        let u = [dot(q, e1) / below, dot(q, e2) / below];
        let s = u[0] * u[0] + u[1] * u[1];
        let one_s = s + 1.0;
        let ue = add(scale(e1, u[0]), scale(e2, u[1]));
        let tangent = |e: V3<S>, ua: S| -> V3<S> {
            let v = add(sub(scale(e, one_s * 2.0), scale(ue, ua * 4.0)), scale(p, ua * 4.0));
            scale(v, (one_s * one_s).recip())
        };
        let lambda2 = (S::from(2.0) / one_s).powi(2);
        let zero = S::from(0.0);
        let point = FacetPoint {
            xi: [u[0] * r, u[1] * r],
            rho: add(lift(self.centre), scale(q, S::from(r))),
            tangents: [tangent(e1, u[0]), tangent(e2, u[1])],
            metric: [[lambda2, zero], [zero, lambda2]],
            inverse: [[lambda2.recip(), zero], [zero, lambda2.recip()]],
            normal: q,
            curvature: [[lambda2 * (-1.0 / r), zero], [zero, lambda2 * (-1.0 / r)]],
        };
        Ok(Projection::closed_form(point, dist - r))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use num_dual::Dual2SVec64;

    /// The chart's point is the slave's nearest point of the sphere; its tangents are the
    /// derivatives of `ρ(ξ)` (central differences of the inverse projection), orthogonal, of
    /// length `λ`, and `ρ_1 × ρ_2` points out; `(a − ζ h) ∇ξ^α = ρ_α` and `∇ζ = n` (1e-12).
    #[test]
    fn the_stereographic_chart_is_the_closest_point_parametrisation() {
        let chart = SphereChart::for_slave([0.1, -0.2, 1.0], 0.8, [0.1, -0.2, 1.0], [0.3, -0.1, 0.0]);
        type D = Dual2SVec64<3>;
        let x0 = [0.5, 0.2, 0.1];
        let x: V3<D> = std::array::from_fn(|i| D::from_re(x0[i]).derivative(i));
        let pr = chart.project(x).unwrap();
        let pt = &pr.point;
        let grad = |s: &D| s.v1.unwrap_generic(nalgebra::U1, nalgebra::Const::<3>);
        let re3 = |v: &V3<D>| v.map(|c| c.re);
        let rho = re3(&pt.rho);
        let off = sub(x0, chart.centre);
        let nearest = add(chart.centre, scale(off, chart.radius / norm(off)));
        assert!(norm(sub(rho, nearest)) < 1e-12);
        // ρ(ξ) from the chart's formula, differentiated numerically
        let [e1, e2] = crate::contact3d::master::plane_axes(scale(chart.pole, -1.0));
        let at = |xi: [f64; 2]| {
            let u = xi.map(|v| v / chart.radius);
            let s = u[0] * u[0] + u[1] * u[1];
            let sigma = add(
                add(scale(e1, 2.0 * u[0]), scale(e2, 2.0 * u[1])),
                scale(chart.pole, s - 1.0),
            );
            add(chart.centre, scale(sigma, chart.radius / (1.0 + s)))
        };
        let xi = pt.xi.map(|v| v.re);
        assert!(norm(sub(at(xi), rho)) < 1e-12);
        let h = 1e-6;
        for al in 0..2 {
            let (mut up, mut down) = (xi, xi);
            up[al] += h;
            down[al] -= h;
            let fd = scale(sub(at(up), at(down)), 0.5 / h);
            assert!(norm(sub(fd, re3(&pt.tangents[al]))) < 1e-8, "ρ_{al}");
        }
        let [t1, t2] = [re3(&pt.tangents[0]), re3(&pt.tangents[1])];
        assert!(dot(t1, t2).abs() < 1e-12);
        assert!((dot(t1, t1) - pt.metric[0][0].re).abs() < 1e-12);
        let n = re3(&pt.normal);
        assert!(dot(crate::contact3d::vec3::cross(t1, t2), n) > 0.0);
        let (zeta, r) = (pr.gap.re, chart.radius);
        let g = grad(&pr.gap);
        for k in 0..3 {
            assert!((g[k] - n[k]).abs() < 1e-12);
        }
        // ∇ξ^α = a^αβ ρ_β / (1 + ζ/R)
        let inv = 1.0 / (pt.metric[0][0].re * (1.0 + zeta / r));
        for (al, t) in [t1, t2].iter().enumerate() {
            let g = grad(&pt.xi[al]);
            for k in 0..3 {
                assert!((g[k] - t[k] * inv).abs() < 1e-12, "∇ξ^{al}");
            }
        }
        // the pole itself has no coordinates
        let pole = add(chart.centre, scale(chart.pole, 1.3));
        assert!(chart.project(pole).is_err());
    }
}
