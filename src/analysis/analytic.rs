//! Analytic references where a scene offers them: Hertz line contact (half-width `a` and
//! peak pressure `p0` from the contact forces of a half model) and the Coulomb threshold
//! (the tangential over the normal reaction equals μ in sliding).

/// Hertz half-width and peak pressure measured on a run, with the analytic values for the
/// same load.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HertzCheck {
    pub a: f64,
    pub a_ref: f64,
    pub p0: f64,
    pub p0_ref: f64,
}

impl HertzCheck {
    /// Relative errors `(a/a_ref − 1, p0/p0_ref − 1)`.
    pub fn errors(&self) -> (f64, f64) {
        (self.a / self.a_ref - 1.0, self.p0 / self.p0_ref - 1.0)
    }
}

/// Hertz line contact of a rigid cylinder (radius `radius`) on a half model (symmetry at
/// `x = 0`) in plane strain: `E* = E / (1 − ν²)`, `a = √(4 P' R / (π E*))`,
/// `p0 = 2 P' / (π a)` with `P'` twice the half model's force. `points` are `[x, normal
/// force]` of the contact nodes. The measured `a` comes from the second moment of the nodal
/// forces (`∫x²p / ∫p = a²/4`), `p0` from the centre node over its tributary width.
pub fn hertz(points: &[[f64; 2]], young: f64, poisson: f64, radius: f64) -> Option<HertzCheck> {
    let half: f64 = points.iter().map(|p| p[1]).sum();
    if half.is_nan() || half <= 0.0 || points.len() < 2 {
        return None;
    }
    let p_full = 2.0 * half;
    let e_star = young / (1.0 - poisson * poisson);
    let a_ref = (4.0 * p_full * radius / (std::f64::consts::PI * e_star)).sqrt();
    let p0_ref = 2.0 * p_full / (std::f64::consts::PI * a_ref);
    let m2: f64 = points.iter().map(|p| p[0] * p[0] * p[1]).sum();
    let a = 2.0 * (m2 / half).sqrt();
    let centre = points.iter().min_by(|p, q| p[0].abs().total_cmp(&q[0].abs()))?;
    let h1 = points
        .iter()
        .map(|p| p[0])
        .filter(|x| *x > centre[0] + 1e-12)
        .fold(f64::INFINITY, f64::min)
        - centre[0];
    if !h1.is_finite() {
        return None;
    }
    Some(HertzCheck {
        a,
        a_ref,
        p0: centre[1] / (0.5 * h1),
        p0_ref,
    })
}

/// Relative error of the Coulomb threshold in sliding: `(|R_t| / |R_n|) / μ − 1`, with
/// `reaction = [R_t, R_n]` the total reactions along and across the sliding plane.
pub fn coulomb(reaction: [f64; 2], mu: f64) -> Option<f64> {
    (reaction[1] != 0.0 && mu > 0.0).then(|| (reaction[0] / reaction[1]).abs() / mu - 1.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hertz_recovers_a_hertz_distribution() {
        // nodal forces of p(x) = p0 √(1 − x²/a²) on a fine uniform grid of the half model
        let (young, nu, radius) = (1000.0, 0.3, 1.0);
        let a = 0.1;
        let e_star = young / (1.0 - nu * nu);
        // P' = π a² E* / (4 R), p0 = 2 P' / (π a)
        let p_full = std::f64::consts::PI * a * a * e_star / (4.0 * radius);
        let p0 = 2.0 * p_full / (std::f64::consts::PI * a);
        let h = a / 2000.0;
        let pts: Vec<[f64; 2]> = (0..2400)
            .map(|i| {
                let x = i as f64 * h;
                let p = if x < a {
                    p0 * (1.0 - x * x / (a * a)).sqrt()
                } else {
                    0.0
                };
                [x, p * if i == 0 { 0.5 * h } else { h }]
            })
            .collect();
        let c = hertz(&pts, young, nu, radius).unwrap();
        let (ea, ep) = c.errors();
        assert!(ea.abs() < 2e-3 && ep.abs() < 2e-3, "{ea} {ep}");
        assert!((c.a_ref - a).abs() < 1e-3 * a);
        assert!(hertz(&[], young, nu, radius).is_none());
        assert!(hertz(&[[0.0, 0.0], [1.0, 0.0]], young, nu, radius).is_none());
    }

    #[test]
    fn coulomb_ratio() {
        assert!((coulomb([-0.3, 1.0], 0.3).unwrap()).abs() < 1e-12);
        assert!((coulomb([0.33, -1.0], 0.3).unwrap() - 0.1).abs() < 1e-12);
        assert!(coulomb([0.3, 0.0], 0.3).is_none());
    }
}

/// Euler–Eytelwein: a perfectly flexible belt sliding over a cylinder through the wrap angle
/// `theta` carries `T2/T1 = exp(μθ)` (the pulled side over the held one; `exp(−μθ)` when it
/// slides the other way).
pub fn capstan(mu: f64, theta: f64) -> f64 {
    (mu * theta).exp()
}

/// The same belt, a perfectly flexible rope, over the convex vertices of a regular polygon of
/// `sides` facets that turn it by `2π/sides` each, `vertices` of them: at each frictional
/// vertex the rope's statics give `T_b/T_a = (1 + μ tan(φ/2)) / (1 − μ tan(φ/2))`, `φ = 2π/N`
/// (the contact force along the bisector of the two rope directions, inclined by `atan μ`).
pub fn rope_over_polygon(mu: f64, sides: usize, vertices: usize) -> f64 {
    let t = mu * (std::f64::consts::PI / sides as f64).tan();
    ((1.0 + t) / (1.0 - t)).powi(vertices as i32)
}

/// An elastic belt (bending stiffness `EI > 0`, however small, thin against its bending
/// length `√(EI/T)`) over the same polygon: at a vertex it bends in two elastica tails, and
/// the contact normal is the normal of the belt where it touches, not the bisector. The
/// tails' moments are equal at the contact point, `T_a (1 − cos ψ_a) = T_b (1 − cos ψ_b)`
/// (the first integral of the elastica under tension, `EI κ²/2 = T (1 − cos ψ)`, ψ the tail's
/// turn), `ψ_a + ψ_b = φ`; the contact force `F = T_a a − T_b b` makes the angle `atan μ`
/// with that normal. The ratio does not depend on `EI` (only on the tension ratio), and is
/// lower than the rope's: the belt turns more on its less tensioned side, which tilts the
/// normal against the pull. Solved per vertex by bisection; `T2/T1` over `vertices`.
pub fn elastic_belt_over_polygon(mu: f64, sides: usize, vertices: usize) -> f64 {
    let phi = 2.0 * std::f64::consts::PI / sides as f64;
    let bisect = |f: &dyn Fn(f64) -> f64, mut lo: f64, mut hi: f64| {
        let below = f(lo) < 0.0;
        for _ in 0..200 {
            let m = 0.5 * (lo + hi);
            if (f(m) < 0.0) == below {
                lo = m;
            } else {
                hi = m;
            }
        }
        0.5 * (lo + hi)
    };
    // ψ_a for a tension ratio r = T_b/T_a
    let psi_a = |r: f64| bisect(&|p: f64| (1.0 - p.cos()) - r * (1.0 - (phi - p).cos()), 0.0, phi);
    // friction residual F·τ + μ F·n with τ the belt's tangent at the contact
    let residual = |r: f64| {
        let p = psi_a(r);
        let (tau, n) = ([p.cos(), p.sin()], [p.sin(), -p.cos()]);
        let f = [1.0 - r * phi.cos(), -r * phi.sin()];
        f[0] * tau[0] + f[1] * tau[1] + mu * (f[0] * n[0] + f[1] * n[1])
    };
    let rope = rope_over_polygon(mu, sides, 1);
    bisect(&residual, 1.0, rope).powi(vertices as i32)
}

#[cfg(test)]
mod capstan_tests {
    use super::*;
    use std::f64::consts::PI;

    #[test]
    fn polygon_references_tend_to_the_capstan_and_the_elastic_belt_lies_below_the_rope() {
        let mu = 0.3;
        for n in [8, 16, 32, 64, 256] {
            let (rope, belt) = (rope_over_polygon(mu, n, n / 2), elastic_belt_over_polygon(mu, n, n / 2));
            assert!(belt < capstan(mu, PI) && capstan(mu, PI) < rope, "{n}: {belt} {rope}");
        }
        let close = |a: f64, b: f64, tol: f64| (a / b - 1.0).abs() < tol;
        assert!(close(rope_over_polygon(mu, 1024, 512), capstan(mu, PI), 1e-5));
        assert!(close(elastic_belt_over_polygon(mu, 1024, 512), capstan(mu, PI), 1e-5));
        // frictionless: no tension change either way
        assert!(close(elastic_belt_over_polygon(0.0, 8, 4), 1.0, 1e-12));
        // values used by tests/capstan.rs (μ = 0.3, N = 8, 16, 32)
        assert!(close(elastic_belt_over_polygon(mu, 8, 4), 2.50036, 1e-5));
        assert!(close(rope_over_polygon(mu, 8, 4), 2.71632, 1e-5));
    }
}
