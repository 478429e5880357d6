//! How a contact point's state (open, stick, slip) is decided at a Newton iterate.
//!
//! The contact forces of a point are unknowns of Newton's iteration beside the
//! displacements (a mixed method, the multipliers condensed point by point): the normal
//! force `N` and the physical tangential traction `t` (along the master's unit tangent;
//! the covariant `T_1 = t √a11`). The seed's penalty regularisation is their constitutive
//! equation, `N = N_ε(u) = λ_N − ε_N ζ(u)` and `T_1 = T_1^tr(u)` in stick (seed eq. 1,
//! with the history transfer of the pair's scheme), and Coulomb's law their inequality.
//! Both are written as Alart–Curnier complementarity functions (Alart & Curnier, CMAME 92
//! (1991) 353–375; the primal–dual active-set reading of Hüeber & Wohlmuth, CMAME 194
//! (2005) 3147–3166, and Popp, Gee & Wall, IJNME 79 (2009) 1354–1391):
//!
//! - normal: `N = max(0, N̂)`, `N̂ = N + ρ_N (N_ε(u) − N)`;
//! - tangential: `t = P_{μ N̂}(t̂)`, `t̂ = t + ρ_T (T_1^tr(u)/√a11 − t)`, `P` the projection on
//!   `[−μN̂, μN̂]`;
//!
//! with `ρ = min(1, c/ε)`, `c` a stiffness of the bodies in contact (their smaller Young's
//! modulus: [`crate::contact::system::ContactSystem`]). Their semismooth Newton step makes
//! the active set from `N̂` and `t̂` — *augmented* forces, in the model's own scale whatever
//! the penalty — and its linearisation, condensed, is the penalty's consistent tangent in
//! that state (with the Hessian terms weighted by the force unknowns). At a solution
//! `N = N_ε(u)` and `t = T_1/√a11`, so the decisions are those of the penalty rule and the
//! answer is the seed's: the method changes how Newton gets there, not where. With
//! `ε ≤ c` (`ρ = 1`) the decisions are the penalty rule's at every iterate.
//!
//! At the normal kink (`N̂ = 0`: a point touching without force) the generalised Jacobian
//! is first taken inactive, as the primal–dual active-set method does (a point is active
//! when `N̂ > 0`; Hintermüller, Ito & Kunisch, SIAM J Optim 13 (2003) 865–888): a sheet
//! lying on a facet is free to lift off it at once. Where that element of the generalised
//! Jacobian is singular — a body held by nothing but the supports it rests on at zero gap
//! — the other one is taken for that correction ([`Kink::Resting`]): the points resting on
//! their master to the precision of the geometry ([`super::point::RESTING_TOLERANCE`]) are
//! active, and at the tangential kink (`|t̂| = μ N̂ = 0`) they stick. No probe or hold
//! decides it, and from the next iterate the force unknowns do.

use super::law::ContactState;

/// The force unknowns of one point at an iterate.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Forces {
    /// `N ≥ 0` at a solution.
    pub normal: f64,
    /// Physical tangential traction `t = T_1/√a11` on the slave.
    pub tangential: f64,
}

/// Who decides a point's state.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Rule {
    /// The penalty function of the displacements alone (seed §3): closed while
    /// penetrating, slip where the trial traction leaves the cone.
    Penalty,
    /// The augmented forces of the Alart–Curnier functions (module docs).
    AlartCurnier { forces: Forces, rho_n: f64, rho_t: f64 },
}

impl Rule {
    /// The rule that decides contact by the normal force unknown alone (`ρ_N = 0` in `N̂`):
    /// Newton starts an increment from the converged contact set — closed where the
    /// converged normal force is positive, whatever gap the predicted start shows. The
    /// complementarity residuals keep their weights.
    pub fn deciding_by_forces(self) -> Rule {
        match self {
            Rule::AlartCurnier { forces, rho_t, .. } => Rule::AlartCurnier {
                forces,
                rho_n: 0.0,
                rho_t,
            },
            rule => rule,
        }
    }
}

/// Which element of the generalised Jacobian a point at the normal kink takes (module docs).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Kink {
    /// Inactive: closed only with `N̂` above the round-off of a zero gap.
    #[default]
    Open,
    /// Active for a point resting on its master within the geometry's precision.
    Resting,
}

/// The weights `ρ = min(1, c/ε)` of the augmented forces for penalties `ε` and a stiffness
/// `c` of the bodies (both in force per unit area).
pub fn weights(c: f64, eps_n: f64, eps_t: f64) -> (f64, f64) {
    let w = |eps: f64| if eps > 0.0 { (c / eps).min(1.0) } else { 1.0 };
    (w(eps_n), w(eps_t))
}

/// The normal decision: closed, and the augmented normal force `N̂` it was made from.
/// `n_eps` is the penalty's `N_ε(u)`; `touch` the force a gap of round-off size gives
/// (`ε_N · 10⁻¹² · 2√a11`), `resting` the force a gap at the geometry's precision gives
/// (`ε_N · 10⁻⁶ · 2√a11`); `kink` says which side a point between them takes.
pub fn normal(rule: &Rule, n_eps: f64, (touch, resting): (f64, f64), kink: Kink) -> (bool, f64) {
    let (n_hat, rho) = match rule {
        Rule::Penalty => (n_eps, 1.0),
        Rule::AlartCurnier { forces, rho_n, .. } => (forces.normal + rho_n * (n_eps - forces.normal), *rho_n),
    };
    let closed = match kink {
        Kink::Open => n_hat > rho * touch,
        Kink::Resting => n_hat >= -rho * resting,
    };
    (closed, n_hat)
}

/// The tangential decision of a closed frictional point: `Some(sign)` of the slip, or
/// `None` for stick. `t_trial` is the physical trial traction `T_1^tr/√a11`, `n_hat` the
/// augmented normal force of [`normal`], `n_eps` the penalty's.
pub fn tangential(rule: &Rule, mu: f64, t_trial: f64, n_hat: f64, n_eps: f64) -> Option<f64> {
    let (t_hat, radius) = match rule {
        Rule::Penalty => (t_trial, mu * n_eps),
        Rule::AlartCurnier { forces, rho_t, .. } => (
            forces.tangential + rho_t * (t_trial - forces.tangential),
            mu * n_hat.max(0.0),
        ),
    };
    if t_hat.abs() <= radius {
        None
    } else {
        Some(if t_hat >= 0.0 { 1.0 } else { -1.0 })
    }
}

/// The residuals of the complementarity functions at the decided state (force units; zero
/// at a solution), for Newton's merit function: `[C_N, C_T]` with
/// - open: `[N, t]`;
/// - closed: `C_N = ρ_N (N − N_ε)`; stick `C_T = ρ_T (t − T_1^tr/√a11)`, slip
///   `C_T = t − sign · μ N̂`, frictionless or without a history `C_T = t`.
///
/// Under [`Rule::Penalty`] the forces are the penalty's own: both are zero.
pub fn complementarity(
    rule: &Rule,
    state: ContactState,
    frictional: bool,
    (n_eps, n_hat): (f64, f64),
    t_trial: f64,
    slip_sign: f64,
    mu: f64,
) -> [f64; 2] {
    let Rule::AlartCurnier { forces, rho_n, rho_t } = rule else {
        return [0.0; 2];
    };
    let (n, t) = (forces.normal, forces.tangential);
    match state {
        ContactState::Open => [n, t],
        _ if !frictional => [rho_n * (n - n_eps), t],
        ContactState::Stick => [rho_n * (n - n_eps), rho_t * (t - t_trial)],
        ContactState::Slip => [rho_n * (n - n_eps), t - slip_sign * mu * n_hat],
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn with_unit_weights_the_augmented_rule_is_the_penalty_rule() {
        let ac = |n: f64, t: f64| Rule::AlartCurnier {
            forces: Forces {
                normal: n,
                tangential: t,
            },
            rho_n: 1.0,
            rho_t: 1.0,
        };
        for (n, t) in [(0.0, 0.0), (3.0, -1.0), (-2.0, 5.0)] {
            for n_eps in [-1.0, 0.5, 4.0] {
                let (c, nh) = normal(&ac(n, t), n_eps, (1e-12, 1e-6), Kink::Open);
                assert_eq!((c, nh), normal(&Rule::Penalty, n_eps, (1e-12, 1e-6), Kink::Open));
                for t_tr in [-3.0, 0.1, 2.5] {
                    assert_eq!(
                        tangential(&ac(n, t), 0.4, t_tr, nh, n_eps),
                        tangential(&Rule::Penalty, 0.4, t_tr, nh, n_eps)
                    );
                }
            }
        }
    }

    #[test]
    fn a_small_weight_decides_from_the_force_unknowns() {
        // a stiff penalty: the penalty force at this iterate is far off (−50), the force
        // unknown (2) says the point carries load: it stays closed
        let rule = Rule::AlartCurnier {
            forces: Forces {
                normal: 2.0,
                tangential: 0.5,
            },
            rho_n: 1e-3,
            rho_t: 1e-3,
        };
        let (closed, n_hat) = normal(&rule, -50.0, (1e-9, 1e-3), Kink::Open);
        assert!(closed && (n_hat - (2.0 - 1e-3 * 52.0)).abs() < 1e-12);
        // the trial traction overshoots the cone (mu N = 0.78), the unknown is inside: stick
        assert_eq!(tangential(&rule, 0.4, 40.0, n_hat, -50.0), None);
        // at a solution the residuals vanish
        let c = complementarity(&rule, ContactState::Stick, true, (2.0, 2.0), 0.5, 0.0, 0.4);
        assert_eq!(c, [0.0, 0.0]);
    }

    #[test]
    fn kinks_are_taken_inactive_unless_resting_is_asked_for() {
        // zero gap and no force: open by default, closed when resting is asked for
        let rule = Rule::AlartCurnier {
            forces: Forces::default(),
            rho_n: 0.01,
            rho_t: 0.01,
        };
        assert!(!normal(&rule, 0.0, (1e-9, 1e-3), Kink::Open).0);
        // a gap at the geometry's precision (a tenth of the resting force) rests too
        assert!(normal(&rule, -1e-4, (1e-9, 1e-3), Kink::Resting).0);
        let (closed, n_hat) = normal(&rule, 0.0, (1e-9, 1e-3), Kink::Resting);
        assert!(closed);
        assert_eq!(tangential(&rule, 0.5, 0.0, n_hat, 0.0), None);
        assert_eq!(weights(1.0, 1e3, 10.0), (1e-3, 0.1));
        assert_eq!(weights(1.0, 0.5, 0.0), (1.0, 1.0));
    }
}
