//! Convective coordinates on a rigid circular cylinder, so that a slave can stick to it and
//! slide on it with Coulomb friction in the covariant form of the facet kernel
//! ([`super::point`]; Konyukhov & Schweizerhof, Comput Mech 35 (2005) §2: any
//! parametrised surface; their cylinder examples in *Computational Contact Mechanics*,
//! Springer (2013), ch. 6).
//!
//! The cylinder of radius `R` through `c` along the unit axis `a`, with the axes
//! `e_1, e_2 ⊥ a` of [`super::master::plane_axes`] (`e_1 × e_2 = a`), is the surface
//!
//! `ρ(ξ¹, ξ²) = c + R e_r(θ) + ξ² a`, `θ = ξ¹ / R`, `e_r = cos θ e_1 + sin θ e_2`:
//!
//! - `ξ¹` is arc length round the axis, `ξ²` length along it; both are fixed in the
//!   cylinder's frame (it moves by translation), so a stick anchor keeps its meaning;
//! - `ρ_1 = e_θ = a × e_r`, `ρ_2 = a`: the metric is the identity;
//! - `n = ρ_1 × ρ_2 = e_r` (outward: slaves are outside);
//! - `h_αβ = ρ_αβ·n`: `h_11 = −1/R`, the others zero.
//!
//! The closest point of a slave `x` is closed-form: `v = x − c`, `ξ² = v·a`,
//! `d = v − ξ² a`, `e_r = d/|d|`, `θ = atan2(d·e_2, d·e_1)` taken on the branch nearest the
//! point's last `ξ¹` (round the axis `θ` runs on, a slave sliding past `θ = π` keeps a
//! continuous `ξ¹`), `ζ = |d| − R`. In the scalar type every quantity carries its
//! derivatives, so the kernel's closed-form variations (slot 0 of
//! [`super::variations::variations`]: `∇ζ = n`, `∇ξ^α = (a − ζ h)^{-1,αβ} ρ_β`) and their
//! dual parts are exact.

use super::projection::{Projection, ProjectionError};
use super::surface::{FacetPoint, GeometryError};
use super::vec3::{add, cross, dot, lift, norm, re, scale, sub, Scalar, V3};
use std::f64::consts::PI;

/// A rigid circular cylinder about the slave's origin (see the module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CylinderChart {
    pub centre: [f64; 3],
    /// Unit axis.
    pub axis: [f64; 3],
    pub radius: f64,
}

impl CylinderChart {
    /// The closest point of `x` and its gap, `ξ¹` on the branch nearest `near` (the point's
    /// last `ξ¹`; `None`: `θ ∈ (−π, π]`). A slave on the axis has no closest point.
    pub fn project<S: Scalar>(&self, x: V3<S>, near: Option<f64>) -> Result<Projection<S>, ProjectionError> {
        let r = self.radius;
        let a: V3<S> = lift(self.axis);
        let [e1, e2] = super::master::plane_axes(self.axis).map(lift::<S>);
        let v = sub(x, lift(self.centre));
        let along = dot(v, a);
        let d = sub(v, scale(a, along));
        let dist = norm(d);
        // NaN fails the comparison: no closest point either
        if dist.re().partial_cmp(&(1e-12 * r)) != Some(std::cmp::Ordering::Greater) {
            return Err(GeometryError::Degenerate {
                xi: [0.0, along.re()],
                sin2: 0.0,
            }
            .into());
        }
        let e_r = scale(d, dist.recip());
        // θ = θ₀ + atan(s/c) with θ₀ the real angle and (c, s) the components of `d` on the
        // axes turned by θ₀ (s = 0, c = |d| in the real parts): the derivatives of atan2 in
        // dual numbers, which num-dual forms as atan(y/x), fail where x = 0
        let (d_re, e1_re, e2_re) = (re(d), re(e1), re(e2));
        let mut theta0 = dot(d_re, e2_re).atan2(dot(d_re, e1_re));
        let (cos0, sin0) = (theta0.cos(), theta0.sin());
        let c = dot(d, add(scale(e1, S::from(cos0)), scale(e2, S::from(sin0))));
        let s = dot(d, sub(scale(e2, S::from(cos0)), scale(e1, S::from(sin0))));
        if let Some(xi1) = near {
            theta0 += 2.0 * PI * ((xi1 / r - theta0) / (2.0 * PI)).round();
        }
        let theta = (s / c).atan() + theta0;
        let e_t = cross(a, e_r);
        let identity = [[S::from(1.0), S::from(0.0)], [S::from(0.0), S::from(1.0)]];
        let zero = S::from(0.0);
        let point = FacetPoint {
            xi: [theta * r, along],
            rho: add(add(lift(self.centre), scale(e_r, S::from(r))), scale(a, along)),
            tangents: [e_t, a],
            metric: identity,
            inverse: identity,
            normal: e_r,
            curvature: [[S::from(-1.0 / r), zero], [zero, zero]],
        };
        if !point.xi.iter().chain(&x).all(|c| c.re().is_finite()) {
            return Err(GeometryError::NonFinite {
                xi: point.xi.map(|c| c.re()),
            }
            .into());
        }
        Ok(Projection::closed_form(point, dist - r))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use num_dual::Dual2SVec64;

    fn chart() -> CylinderChart {
        let axis = [0.3, 1.0, 0.2];
        CylinderChart {
            centre: [0.1, -0.2, 1.0],
            axis: scale(axis, 1.0 / norm(axis)),
            radius: 0.8,
        }
    }

    /// The chart's point lies on the cylinder, its tangents are `∂ρ/∂ξ^α`, `a − ζ h` times
    /// the gradients of `ξ^α` is `ρ_α` (the closest-point variations, 1e-12), and `ζ`'s
    /// gradient is the normal.
    #[test]
    fn the_chart_is_the_closest_point_parametrisation() {
        let c = chart();
        type D = Dual2SVec64<3>;
        let x0 = [0.9, 0.4, 1.3];
        let x: V3<D> = std::array::from_fn(|i| D::from_re(x0[i]).derivative(i));
        let p = c.project(x, None).unwrap();
        let grad = |s: &D| s.v1.unwrap_generic(nalgebra::U1, nalgebra::Const::<3>);
        let pt = &p.point;
        let xi = pt.xi.map(|s| s.re);
        // on the cylinder
        let rho = pt.rho.map(|s| s.re);
        let off = sub(rho, c.centre);
        let radial = sub(off, scale(c.axis, dot(off, c.axis)));
        assert!((norm(radial) - c.radius).abs() < 1e-12);
        // the tangents are the derivatives of ρ(ξ) (central differences)
        let h = 1e-6;
        let at = |xi: [f64; 2]| {
            let [e1, e2] = crate::contact3d::master::plane_axes(c.axis);
            let th = xi[0] / c.radius;
            let e_r = add(scale(e1, th.cos()), scale(e2, th.sin()));
            add(add(c.centre, scale(e_r, c.radius)), scale(c.axis, xi[1]))
        };
        for al in 0..2 {
            let (mut up, mut down) = (xi, xi);
            up[al] += h;
            down[al] -= h;
            let fd = scale(sub(at(up), at(down)), 0.5 / h);
            for (f, t) in fd.iter().zip(&pt.tangents[al]) {
                assert!((f - t.re).abs() < 1e-8);
            }
        }
        for k in 0..3 {
            assert!((grad(&p.gap)[k] - pt.normal[k].re).abs() < 1e-12);
        }
        // (a − ζ h) ∇ξ = ρ_α: ∇ξ¹ (1 + ζ/R) = ρ_1, ∇ξ² = ρ_2
        let zeta = p.gap.re;
        for k in 0..3 {
            let g1 = grad(&pt.xi[0])[k] * (1.0 + zeta / c.radius);
            assert!((g1 - pt.tangents[0][k].re).abs() < 1e-12);
            assert!((grad(&pt.xi[1])[k] - pt.tangents[1][k].re).abs() < 1e-12);
        }
    }

    /// Round the axis `ξ¹` continues on the branch of the point's last `ξ¹`: a point just
    /// past `θ = π` seen from just before it is a little further on, not `2πR` back.
    #[test]
    fn the_arc_length_runs_on_past_half_a_turn() {
        let c = CylinderChart {
            centre: [0.0; 3],
            axis: [0.0, 0.0, 1.0],
            radius: 1.0,
        };
        let [e1, e2] = crate::contact3d::master::plane_axes(c.axis);
        let at = |th: f64| add(scale(e1, 1.2 * th.cos()), scale(e2, 1.2 * th.sin()));
        let before = c.project(at(PI - 0.01), None).unwrap().point.xi[0];
        let after = c.project(at(PI + 0.01), Some(before)).unwrap().point.xi[0];
        assert!((after - before - 0.02).abs() < 1e-12, "{before} → {after}");
        let plain = c.project(at(PI + 0.01), None).unwrap().point.xi[0];
        assert!((plain + PI - 0.01).abs() < 1e-12);
        assert!(c.project([0.0, 0.0, 0.3], None).is_err());
    }

    /// On the chart's axes (`d·e_1 = 0` or `d·e_2 = 0`, where num-dual's atan2 divides by
    /// zero) the derivatives of `ξ¹` are finite and those of the arc length: `e_θ / |d|` times R.
    #[test]
    fn the_arc_length_has_derivatives_on_the_axes() {
        let c = CylinderChart {
            centre: [0.0; 3],
            axis: [0.0, 1.0, 0.0],
            radius: 3.0,
        };
        let [e1, e2] = crate::contact3d::master::plane_axes(c.axis);
        type D = num_dual::DualSVec64<3>;
        for dir in [e1, e2, scale(e1, -1.0), scale(e2, -1.0)] {
            let x0 = scale(dir, 2.9);
            let x: V3<D> = std::array::from_fn(|i| D::from_re(x0[i]).derivative(i));
            let p = c.project(x, None).unwrap();
            let g = p.point.xi[0].eps.unwrap_generic(nalgebra::Const::<3>, nalgebra::U1);
            let e_t = cross(c.axis, dir);
            for k in 0..3 {
                assert!((g[k] - c.radius * e_t[k] / 2.9).abs() < 1e-12, "{dir:?}: {g:?}");
            }
        }
    }
}
