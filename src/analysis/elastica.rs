//! A cantilever under a dead tip load as a geometrically exact beam (Reissner 1972; the
//! inextensible limit is Euler's elastica, tabulated by Mattiasson, IJNME 17 (1981) 145–153):
//! the reference of the one-layer beam studies.
//!
//! Beam of length `L` along `x`, clamped at `s = 0`, loaded at `s = L` by a dead force
//! `F = (0, −P)`. The section force is `F` everywhere; with the section angle `θ(s)`, its
//! axial and shear components are `n = F·t`, `q = F·t⊥` (`t = (cos θ, sin θ)`,
//! `t⊥ = (−sin θ, cos θ)`), and Reissner's strains `ε = n/EA`, `γ = q/GA`:
//!
//! `x' = (1 + ε) cos θ − γ sin θ`, `y' = (1 + ε) sin θ + γ cos θ`, `θ' = M/EI`,
//! `M' = −(x' F_y − y' F_x)`,
//!
//! with `θ(0) = 0` and `M(L) = 0`: `M(0)` is found by bisection (shooting), the equations
//! integrated by fourth-order Runge–Kutta. `EA = ∞`, `GA = ∞` gives the elastica.
//! For a plane-strain strip of thickness `h`: `EI = E h³/(12(1 − ν²))`, `EA = E h/(1 − ν²)`,
//! `GA = κ G h` with `κ = 5/6` (`beam_stiffness`).

/// Bending, axial and shear stiffness of a beam section.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BeamSection {
    pub ei: f64,
    pub ea: f64,
    pub ga: f64,
}

/// The section of a plane-strain strip of thickness `h` (shear correction 5/6).
pub fn beam_stiffness(young: f64, poisson: f64, h: f64) -> BeamSection {
    let e = young / (1.0 - poisson * poisson);
    BeamSection {
        ei: e * h.powi(3) / 12.0,
        ea: e * h,
        ga: 5.0 / 6.0 * young / (2.0 * (1.0 + poisson)) * h,
    }
}

/// The tip displacements `(v/L, u/L)` (deflection along the load, shortening along the
/// beam) of a cantilever of length `length` under the tip load `k EI/L²`.
pub fn cantilever_tip(section: BeamSection, length: f64, k: f64) -> (f64, f64) {
    let p = k * section.ei / (length * length);
    // M(0) lies between the largest possible clamp moment (−P L) and zero
    let (mut lo, mut hi) = (-1.01 * p * length, 0.0);
    let mut f_lo = integrate(section, length, p, lo)[3];
    for _ in 0..100 {
        let mid = 0.5 * (lo + hi);
        let f_mid = integrate(section, length, p, mid)[3];
        if (f_mid < 0.0) == (f_lo < 0.0) {
            (lo, f_lo) = (mid, f_mid);
        } else {
            hi = mid;
        }
    }
    let end = integrate(section, length, p, 0.5 * (lo + hi));
    (-end[1] / length, (length - end[0]) / length)
}

/// `(x, y, θ, M)` at `s = L` from `M(0) = m0`.
fn integrate(section: BeamSection, length: f64, p: f64, m0: f64) -> [f64; 4] {
    const STEPS: usize = 2000;
    let ds = length / STEPS as f64;
    let rhs = |s: [f64; 4]| -> [f64; 4] {
        let (c, sn) = (s[2].cos(), s[2].sin());
        let (n, q) = (-p * sn, -p * c);
        let (eps, gam) = (n / section.ea, q / section.ga);
        let dx = (1.0 + eps) * c - gam * sn;
        let dy = (1.0 + eps) * sn + gam * c;
        [dx, dy, s[3] / section.ei, dx * p]
    };
    let axpy = |s: [f64; 4], a: f64, d: [f64; 4]| std::array::from_fn(|i| s[i] + a * d[i]);
    let mut s = [0.0, 0.0, 0.0, m0];
    for _ in 0..STEPS {
        let k1 = rhs(s);
        let k2 = rhs(axpy(s, 0.5 * ds, k1));
        let k3 = rhs(axpy(s, 0.5 * ds, k2));
        let k4 = rhs(axpy(s, ds, k3));
        s = std::array::from_fn(|i| s[i] + ds / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]));
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_inextensible_limit_is_mattiassons_elastica() {
        let rigid = BeamSection {
            ei: 1.0,
            ea: f64::INFINITY,
            ga: f64::INFINITY,
        };
        // Mattiasson (1981), Table 1: k, v/L, u/L
        for (k, v, u) in [
            (1.0, 0.30172, 0.05643),
            (2.0, 0.49346, 0.16064),
            (4.0, 0.66996, 0.32894),
            (10.0, 0.81061, 0.55500),
        ] {
            let (vc, uc) = cantilever_tip(rigid, 10.0, k);
            assert!((vc - v).abs() < 6e-6 && (uc - u).abs() < 6e-6, "k = {k}: {vc} {uc}");
        }
    }

    #[test]
    fn small_loads_give_the_linear_deflection_with_shear() {
        // v = P L³/(3 EI) + P L/GA
        let s = beam_stiffness(2.1e4, 0.3, 0.5);
        let k = 1e-4;
        let (v, _) = cantilever_tip(s, 10.0, k);
        let p = k * s.ei / 100.0;
        let linear = (p * 1000.0 / (3.0 * s.ei) + p * 10.0 / s.ga) / 10.0;
        assert!((v / linear - 1.0).abs() < 1e-4, "{v} vs {linear}");
    }

    #[test]
    fn axial_and_shear_compliance_add_to_the_deflection() {
        let s = beam_stiffness(2.1e4, 0.3, 0.5);
        let (v, _) = cantilever_tip(s, 10.0, 10.0);
        // computed once (2026-11-25): 0.81371 against the elastica's 0.81061
        assert!((v - 0.81371).abs() < 1e-5, "{v}");
    }
}
