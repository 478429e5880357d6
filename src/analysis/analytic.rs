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
