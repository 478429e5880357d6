//! Hertz point contact (a rigid sphere on an elastic half-space) measured on a run, for the
//! axisymmetric and the 3D model of the same scene, so that a sweep can chart which model is
//! enough ([`super::analytic::hertz`] is the line contact of plane strain).
//!
//! Reference (Hertz 1882; Johnson, *Contact Mechanics* (1985) §4.2): with `E* = E / (1 − ν²)`
//! (rigid sphere of radius `R`) and `F` the total force, `a = (3 F R / (4 E*))^(1/3)`,
//! `p0 = 3 F / (2π a²)`, `p(r) = p0 √(1 − r²/a²)`.
//!
//! Measured: `F = copies · Σ N` over the model's contact nodes (`copies` = 4 for a quarter
//! model, 1 for an axisymmetric model whose forces are totals over the circle); `a` from the
//! second moment of the nodal normal forces, `Σ r² N / Σ N = 2a²/5` for the Hertz
//! distribution; `p0` the force of the node on the axis over its tributary area — `π h²/3` in
//! the axisymmetric model (the ring of the linear element next to the axis, `h` its length),
//! `h_x h_y / copies` on bilinear facets (`h_x`, `h_y` the facet next to the axis).

use super::analytic::HertzCheck;

/// The contact nodes of a run at its last increment, by model.
#[derive(Debug, Clone, Copy)]
pub enum PointContact<'a> {
    /// `[r, normal force]`: the nodes of an axisymmetric face (`r` the distance from the
    /// axis, forces totals over the circle).
    Axisymmetric(&'a [[f64; 2]]),
    /// `[x, y, normal force]`: the nodes of a 3D face (the sphere's axis through `x = y = 0`),
    /// of a model that is `1/copies` of the whole.
    Solid { points: &'a [[f64; 3]], copies: f64 },
}

/// `a` and `p0` of Hertz point contact on a run, with the analytic values for its force;
/// `None` when no node carries force or the node next to the axis cannot be found.
pub fn hertz_point(contact: PointContact, young: f64, poisson: f64, radius: f64) -> Option<HertzCheck> {
    let (nodes, copies): (Vec<([f64; 2], f64)>, f64) = match contact {
        PointContact::Axisymmetric(p) => (p.iter().map(|p| ([p[0], 0.0], p[1])).collect(), 1.0),
        PointContact::Solid { points, copies } => (points.iter().map(|p| ([p[0], p[1]], p[2])).collect(), copies),
    };
    let sum: f64 = nodes.iter().map(|(_, n)| n).sum();
    let measurable = sum > 0.0 && copies >= 1.0; // false for NaN too
    if !measurable || nodes.len() < 2 {
        return None;
    }
    let r2 = |x: &[f64; 2]| x[0] * x[0] + x[1] * x[1];
    let a = (2.5 * nodes.iter().map(|(x, n)| r2(x) * n).sum::<f64>() / sum).sqrt();
    let force = copies * sum;
    let e_star = young / (1.0 - poisson * poisson);
    let a_ref = (3.0 * force * radius / (4.0 * e_star)).cbrt();
    let p0_ref = 3.0 * force / (2.0 * std::f64::consts::PI * a_ref * a_ref);
    let (centre, n_centre) = nodes.iter().min_by(|p, q| r2(&p.0).total_cmp(&r2(&q.0)))?;
    // the nearest node along each axis from the centre node, on the centre's line (the facet
    // next to the axis; a graded mesh's diagonal neighbours do not count)
    let scale = nodes.iter().map(|(x, _)| r2(x)).fold(0.0, f64::max).sqrt();
    let nearest = |k: usize| {
        let on_line = nodes
            .iter()
            .filter(|(x, _)| (x[1 - k] - centre[1 - k]).abs() <= 1e-9 * scale);
        let along = on_line
            .map(|(x, _)| (x[k] - centre[k]).abs())
            .filter(|d| *d > 1e-12 * scale);
        along.fold(f64::INFINITY, f64::min)
    };
    let area = match contact {
        PointContact::Axisymmetric(_) => std::f64::consts::PI * nearest(0).powi(2) / 3.0,
        PointContact::Solid { .. } => nearest(0) * nearest(1) / copies,
    };
    (area.is_finite() && area > 0.0).then(|| HertzCheck {
        a,
        a_ref,
        p0: n_centre / area,
        p0_ref,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    const E: f64 = 1000.0;
    const NU: f64 = 0.3;

    /// Hertz's a and p0 for a contact radius `a` on a sphere of radius 1.
    fn hertz_of(a: f64) -> (f64, f64) {
        let e_star = E / (1.0 - NU * NU);
        let force = 4.0 * e_star * a.powi(3) / 3.0;
        (force, 3.0 * force / (2.0 * PI * a * a))
    }

    fn p(r: f64, a: f64, p0: f64) -> f64 {
        if r < a {
            p0 * (1.0 - r * r / (a * a)).sqrt()
        } else {
            0.0
        }
    }

    #[test]
    fn recovers_a_hertz_distribution_on_rings() {
        let a = 0.07;
        let (_, p0) = hertz_of(a);
        let h = a / 400.0;
        // ring forces of the linear element's consistent load (midpoint rule per ring)
        let pts: Vec<[f64; 2]> = (0..600)
            .map(|i| {
                let r = i as f64 * h;
                let ring = if i == 0 { PI * h * h / 3.0 } else { 2.0 * PI * r * h };
                [r, p(r, a, p0) * ring]
            })
            .collect();
        let c = hertz_point(PointContact::Axisymmetric(&pts), E, NU, 1.0).unwrap();
        let (ea, ep) = c.errors();
        assert!(ea.abs() < 3e-3 && ep.abs() < 3e-3, "{ea} {ep}");
        assert!((c.a_ref / a - 1.0).abs() < 3e-3, "{}", c.a_ref);
    }

    #[test]
    fn recovers_a_hertz_distribution_on_a_quarter_grid() {
        let a = 0.07;
        let (_, p0) = hertz_of(a);
        let h = a / 150.0;
        let mut pts = Vec::new();
        for i in 0..220 {
            for j in 0..220 {
                let (x, y) = (i as f64 * h, j as f64 * h);
                // tributary areas of a quarter model's nodes: halved on each symmetry line
                let w = if i == 0 { 0.5 } else { 1.0 } * if j == 0 { 0.5 } else { 1.0 };
                pts.push([x, y, p((x * x + y * y).sqrt(), a, p0) * w * h * h]);
            }
        }
        let quarter = PointContact::Solid {
            points: &pts,
            copies: 4.0,
        };
        let c = hertz_point(quarter, E, NU, 1.0).unwrap();
        let (ea, ep) = c.errors();
        assert!(ea.abs() < 3e-3 && ep.abs() < 3e-3, "{ea} {ep}");
        // the same nodes read as a whole model carry a quarter of the force
        let whole = hertz_point(
            PointContact::Solid {
                points: &pts,
                copies: 1.0,
            },
            E,
            NU,
            1.0,
        )
        .unwrap();
        assert!((whole.a_ref / c.a_ref - 0.25f64.cbrt()).abs() < 1e-12);
    }

    #[test]
    fn nothing_measured_without_force_or_neighbours() {
        assert!(hertz_point(PointContact::Axisymmetric(&[]), E, NU, 1.0).is_none());
        assert!(hertz_point(PointContact::Axisymmetric(&[[0.0, 0.0], [0.1, 0.0]]), E, NU, 1.0).is_none());
        assert!(hertz_point(PointContact::Axisymmetric(&[[0.0, 1.0]]), E, NU, 1.0).is_none());
        let one_line = [[0.0, 0.0, 1.0], [0.1, 0.0, 1.0]];
        let solid = PointContact::Solid {
            points: &one_line,
            copies: 4.0,
        };
        assert!(
            hertz_point(solid, E, NU, 1.0).is_none(),
            "no facet next to the axis in y"
        );
    }
}
