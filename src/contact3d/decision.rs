//! How a 3D contact point's state (open, stick, slip) is decided at a Newton iterate: the
//! 2D contact Newton's rule ([`crate::contact::decision`]) on a surface.
//!
//! The contact forces of a point are unknowns of Newton's iteration beside the
//! displacements, condensed point by point: the normal force `N` and the tangential force
//! on the slave as a spatial vector `t` (in the tangent plane at a solution; stored as a
//! vector so that it means the same on every facet and at every metric — its covariant
//! components on the current facet are `t·ρ_α`). The seed's penalty law is their
//! constitutive equation, `N = N_ε(u) = −ε_N ζ(u)` and, in stick,
//! `T_α = T_α^tr(u) = T_α^(n) − ε_T a_αβ (ξ^β − ξ^β_(n))` (seed eq. 1 on surfaces, with the
//! history transfer of the pair's scheme); Coulomb's law their inequality. Both are written
//! as Alart–Curnier complementarity functions (Alart & Curnier, CMAME 92 (1991) 353–375; on
//! surfaces Popp, Gee & Wall, IJNME 79 (2009) 1354–1391, §3):
//!
//! - normal: `N = max(0, N̂)`, `N̂ = N + ρ_N (N_ε(u) − N)`;
//! - tangential: `t_α = P_{μ N̂}(t̂_α)`, `t̂_α = t·ρ_α + ρ_T (T_α^tr(u) − t·ρ_α)`, `P` the
//!   projection on the disc `‖t̂‖ ≤ μ N̂` in the surface metric (`‖T‖² = T_α a^αβ T_β`);
//!
//! with `ρ = min(1, c/ε)` ([`crate::contact::decision::weights`]), `c` the smaller
//! plane-strain modulus of the bodies in contact. The semismooth Newton step takes the
//! active set from `N̂` and `t̂`; its linearisation, condensed, is the penalty's consistent
//! tangent in that state with the Hessian terms weighted by the force unknowns
//! ([`super::point::PointProblem::local`]). At a solution the decisions are the penalty
//! rule's and the answer is the seed's; with `ε ≤ c` (`ρ = 1`) the decisions are the penalty
//! rule's at every iterate.
//!
//! A 3D point touching within round-off is closed (the resting side of the normal kink,
//! [`super::point::TOUCH`]): `N̂ ≥ −ρ_N ε_N TOUCH · size`, the penalty rule's `ζ ≤ TOUCH · size`
//! at `ρ_N = 1`.

use super::surface::FacetPoint;
use crate::contact::decision::{self as plane, Kink};
use crate::contact::law::ContactState;

/// The force unknowns of one 3D point at an iterate.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct SurfaceForces {
    /// `N ≥ 0` at a solution.
    pub normal: f64,
    /// The tangential force on the slave, `t = T_α ρ^α`, as a spatial vector.
    pub tangential: [f64; 3],
}

/// Who decides a 3D point's state.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SurfaceRule {
    /// The penalty function of the displacements alone (the seed's return map).
    Penalty,
    /// The augmented forces of the Alart–Curnier functions (module docs).
    AlartCurnier {
        forces: SurfaceForces,
        rho_n: f64,
        rho_t: f64,
    },
}

impl SurfaceRule {
    /// Decide by the normal force unknown alone (`ρ_N = 0` in `N̂`): the first iterate of an
    /// attempt starts from the converged contact set.
    pub fn deciding_by_forces(self) -> SurfaceRule {
        match self {
            SurfaceRule::AlartCurnier { forces, rho_t, .. } => SurfaceRule::AlartCurnier {
                forces,
                rho_n: 0.0,
                rho_t,
            },
            rule => rule,
        }
    }

    /// The force unknowns (`None` under the penalty rule: the penalty's own forces).
    pub fn forces(&self) -> Option<SurfaceForces> {
        match self {
            SurfaceRule::AlartCurnier { forces, .. } => Some(*forces),
            SurfaceRule::Penalty => None,
        }
    }
}

/// The normal decision: closed, and the augmented normal force `N̂`. `n_eps` is the
/// penalty's `N_ε(u)`, `touch` the force of a gap of round-off size (`ε_N TOUCH · size`).
pub fn normal(rule: &SurfaceRule, n_eps: f64, touch: f64) -> (bool, f64) {
    let as_plane = match *rule {
        SurfaceRule::Penalty => plane::Rule::Penalty,
        SurfaceRule::AlartCurnier { forces, rho_n, rho_t } => plane::Rule::AlartCurnier {
            forces: plane::Forces {
                normal: forces.normal,
                tangential: 0.0,
            },
            rho_n,
            rho_t,
        },
    };
    // the resting side of the kink: closed down to −ρ_N · touch
    plane::normal(&as_plane, n_eps, (touch, touch), Kink::Resting)
}

/// A slip decision: the direction `d` of the augmented traction (covariant components of a
/// unit vector in the metric) and its size `‖t̂‖`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Slip {
    pub direction: [f64; 2],
    pub size: f64,
}

/// The tangential decision of a closed frictional point with covariant trial traction
/// `trial` at contact point `p`, the penalty's normal force `n_eps` and the augmented one
/// `n_hat` of [`normal`]: `Some` slip, or `None` for stick.
pub fn tangential(
    rule: &SurfaceRule,
    mu: f64,
    trial: [f64; 2],
    p: &FacetPoint<f64>,
    (n_eps, n_hat): (f64, f64),
) -> Option<Slip> {
    let (t_hat, radius) = match rule {
        SurfaceRule::Penalty => (trial, mu * n_eps),
        SurfaceRule::AlartCurnier { forces, rho_t, .. } => {
            let t = p.covariant(forces.tangential);
            (
                [t[0] + rho_t * (trial[0] - t[0]), t[1] + rho_t * (trial[1] - t[1])],
                mu * n_hat.max(0.0),
            )
        }
    };
    let size = p.norm(t_hat);
    (size > radius).then(|| Slip {
        direction: t_hat.map(|c| c / size),
        size,
    })
}

/// The factor `c` of the slip force `t = μ N_ε d + c P T^tr` (`P = I − d dᵀ`) that the
/// condensed semismooth Newton step of the slip condition `t = μ N̂ t̂/‖t̂‖` makes of the
/// force unknowns: `c = a ρ_T / (1 − a (1 − ρ_T))`, `a = μ N̂/‖t̂‖`.
///
/// Linearising `t − μ N̂ d` with `t̂ = t + ρ_T (T^tr − t)` and eliminating the correction of
/// `t` gives, along `d`, `t = μ N_ε` (linearised), and across it `w = c P (T^tr + ∇T^tr Δu)`
/// — `P t̂ = 0` turns `P t` into `−ρ_T/(1 − ρ_T) P T^tr`. In slip `a < 1`, so the
/// denominator is above `ρ_T`. At a solution (`t ∥ T^tr`) `c = μ N/‖T^tr‖`, and under the
/// penalty rule (`ρ_T = 1`, `t̂ = T^tr`) at every iterate: `t = μ N_ε T^tr/‖T^tr‖`, the
/// seed's return map with its consistent tangent.
pub fn transverse_factor(rule: &SurfaceRule, mu: f64, n_hat: f64, size: f64) -> f64 {
    let rho = match rule {
        SurfaceRule::Penalty => 1.0,
        SurfaceRule::AlartCurnier { rho_t, .. } => *rho_t,
    };
    let a = mu * n_hat.max(0.0) / size;
    a * rho / (1.0 - a * (1.0 - rho))
}

/// The residuals of the complementarity functions at the decided state (force units; zero
/// at a solution), for Newton's merit function: `[C_N, |C_T|]` with, for force unknowns
/// `N`, `t`,
/// - open: `[N, |t|]`;
/// - closed: `C_N = ρ_N (N − N_ε)`; stick `C_T = ρ_T (t − T^tr)`, slip `C_T = t − μ N̂ d`
///   (`d` the slip direction), frictionless or without a history `C_T = t`;
///
/// `trial` and `direction` as spatial vectors (`T^tr_α ρ^α`, `d_α ρ^α`). Under
/// [`SurfaceRule::Penalty`] both are zero.
pub fn complementarity(
    rule: &SurfaceRule,
    state: ContactState,
    (n_eps, n_hat): (f64, f64),
    trial: Option<[f64; 3]>,
    slip: Option<([f64; 3], f64)>,
) -> [f64; 2] {
    let SurfaceRule::AlartCurnier { forces, rho_n, rho_t } = rule else {
        return [0.0; 2];
    };
    let (n, t) = (forces.normal, forces.tangential);
    let length = |v: [f64; 3]| (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    let minus = |a: [f64; 3], b: [f64; 3], s: f64| std::array::from_fn(|c| a[c] - s * b[c]);
    let c_n = rho_n * (n - n_eps);
    match (state, trial, slip) {
        (ContactState::Open, _, _) => [n, length(t)],
        (ContactState::Slip, _, Some((direction, mu))) => [c_n, length(minus(t, direction, mu * n_hat))],
        (ContactState::Stick, Some(trial), _) => [c_n, rho_t * length(minus(t, trial, 1.0))],
        _ => [c_n, length(t)],
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::contact3d::surface::Facet;

    fn point() -> FacetPoint<f64> {
        let f = Facet::<f64> {
            x: [[0.0, 0.0, 0.0], [1.2, 0.1, 0.0], [1.1, 0.9, 0.1], [-0.1, 1.0, 0.0]],
            bend: None,
        };
        f.point([0.2, -0.3]).unwrap()
    }

    fn ac(n: f64, t: [f64; 3], rho: f64) -> SurfaceRule {
        SurfaceRule::AlartCurnier {
            forces: SurfaceForces {
                normal: n,
                tangential: t,
            },
            rho_n: rho,
            rho_t: rho,
        }
    }

    #[test]
    fn with_unit_weights_the_augmented_rule_is_the_penalty_rule() {
        let p = point();
        for (n, t) in [(0.0, [0.0; 3]), (3.0, [-1.0, 0.5, 0.2]), (-2.0, [5.0, 0.0, -1.0])] {
            for n_eps in [-1.0, 0.5, 4.0] {
                let (c, nh) = normal(&ac(n, t, 1.0), n_eps, 1e-9);
                assert_eq!((c, nh), normal(&SurfaceRule::Penalty, n_eps, 1e-9));
                for trial in [[-3.0, 0.1], [0.1, 0.05], [2.5, -2.0]] {
                    let a = tangential(&ac(n, t, 1.0), 0.4, trial, &p, (n_eps, nh));
                    let b = tangential(&SurfaceRule::Penalty, 0.4, trial, &p, (n_eps, nh));
                    assert_eq!(a.is_some(), b.is_some());
                    if let (Some(a), Some(b)) = (a, b) {
                        let (a, b) = (a.direction, b.direction);
                        assert!((a[0] - b[0]).abs() < 1e-14 && (a[1] - b[1]).abs() < 1e-14);
                        assert!((p.norm(a) - 1.0).abs() < 1e-14);
                    }
                }
            }
        }
    }

    #[test]
    fn a_small_weight_decides_from_the_force_unknowns() {
        let p = point();
        // a stiff penalty: the penalty's normal force at this iterate is far off (−50), the
        // unknown (2) says the point carries load; the trial traction overshoots the cone
        // (μN = 0.8), the unknown (0.5 along ρ_1) is inside: closed and stuck
        let along = p.tangents[0].map(|c| 0.5 * c / p.metric[0][0].sqrt());
        let rule = ac(2.0, along, 1e-3);
        let (closed, n_hat) = normal(&rule, -50.0, 1e-9);
        assert!(closed && (n_hat - (2.0 - 1e-3 * 52.0)).abs() < 1e-12);
        assert_eq!(tangential(&rule, 0.4, [40.0, 30.0], &p, (-50.0, n_hat)), None);
        // the cone is the augmented force's: a penalty force of 50 would hold a unit
        // traction, the unknown's 2 does not (radius 0.4 · 2.05)
        let unit = p.tangents[0].map(|c| c / p.metric[0][0].sqrt());
        let slipping = ac(2.0, unit, 1e-3);
        let (_, n_hat) = normal(&slipping, 50.0, 1e-9);
        let slip = tangential(&slipping, 0.4, p.covariant(unit), &p, (50.0, n_hat)).expect("slips");
        assert!((slip.size - 1.0).abs() < 1e-12 && (n_hat - 2.048).abs() < 1e-12);
        assert_eq!(
            tangential(&SurfaceRule::Penalty, 0.4, p.covariant(unit), &p, (50.0, 50.0)),
            None
        );
        // the penalty rule would open it
        assert!(!normal(&SurfaceRule::Penalty, -50.0, 1e-9).0);
        // at a solution the residuals vanish
        let trial = p.vector(p.covariant(along));
        let c = complementarity(
            &ac(2.0, along, 1e-3),
            ContactState::Stick,
            (2.0, 2.0),
            Some(trial),
            None,
        );
        assert!(c[0] == 0.0 && c[1] < 1e-15, "{c:?}");
        // open: the unknowns themselves
        let c = complementarity(&rule, ContactState::Open, (0.0, 0.0), None, None);
        assert!((c[0] - 2.0).abs() < 1e-15 && (c[1] - 0.5).abs() < 1e-12);
        assert_eq!(
            complementarity(&SurfaceRule::Penalty, ContactState::Open, (1.0, 1.0), None, None),
            [0.0; 2]
        );
    }
}
