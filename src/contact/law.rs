//! Contact constitutive law at one slave point: penalty normal force and Coulomb friction by
//! return mapping (seed §3; Konyukhov & Schweizerhof, Comput Mech 35 (2005) 190–213).
//!
//! Conventions:
//! - `ζ = (r_s − ρ(ξ))·n` is the signed normal gap (negative = penetration, see
//!   [`super::geometry`]); the normal force magnitude is `N = ε_N ⟨−ζ⟩ ≥ 0`.
//! - `T_1` is the covariant component of the tangential traction *acting on the slave*,
//!   `T = T_1 ρ^1`; its physical value along the unit tangent is `t = T_1 / √a11`.
//! - Stick trial (seed eq. 1): `T_1^tr = T_1^(n) − ε_T a11 Δξ` (the history-transfer schemes
//!   in [`super::transfer`] generalise it across segments).
//! - Slip function `Φ = ‖T^tr‖ − μ N` with `‖T‖ = √(T_1 a^11 T_1)`; `Φ ≤ 0`: stick, `T = T^tr`;
//!   `Φ > 0`: slip, `T = μ N T^tr / ‖T^tr‖`.

use crate::contact::scalar::Scalar;
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

pub use crate::model::ContactLaw;

/// Contact state of a slave point.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "lowercase")]
pub enum ContactState {
    #[default]
    Open,
    Stick,
    Slip,
}

impl ContactState {
    pub fn code(self) -> u8 {
        match self {
            ContactState::Open => 0,
            ContactState::Stick => 1,
            ContactState::Slip => 2,
        }
    }
}

/// Return mapping: the returned covariant traction `T_1` and the state, for a trial `T_1^tr`,
/// normal force `N` and metric `a11` (seed §3, "standard return mapping").
///
/// The branch is always chosen on the real parts of the data, also for a point whose state
/// the solver froze: freezing holds a point's segment and its open/closed decision, never
/// the stick/slip branch. Forcing the slip branch on a point whose trial traction reverses
/// along a Newton step makes the returned traction jump by `2 μ N √a11` (from `−μN` to
/// `+μN` in physical terms) although the trial is continuous, so the residual has no zero
/// when the equilibrium is in stick (the 240×8, μ = 0.1 stall of the strip-channel study).
/// The returned value carries derivatives, so the tangent of the slip branch,
/// `∂(μ N √a11 sign T^tr)`, is the consistent one; the map is continuous in `T^tr` at the
/// cone (`|T^tr| = μ N`).
pub fn return_map<S: Scalar>(law: &ContactLaw, t1_trial: S, normal: S, a11: S) -> (S, ContactState) {
    if law.mu <= 0.0 {
        return (S::from(0.0), ContactState::Slip);
    }
    let norm_tr = t1_trial.re().abs() / a11.re().sqrt();
    if norm_tr <= law.mu * normal.re() {
        (t1_trial, ContactState::Stick)
    } else {
        let sign = if t1_trial.re() >= 0.0 { 1.0 } else { -1.0 };
        (normal * a11.sqrt() * (law.mu * sign), ContactState::Slip)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stick_inside_the_cone_slip_on_it() {
        let law = ContactLaw {
            eps_n: 1.0,
            eps_t: 1.0,
            mu: 0.5,
        };
        let (t, s) = return_map(&law, 0.4, 1.0, 1.0);
        assert_eq!((t, s), (0.4, ContactState::Stick));
        let (t, s) = return_map(&law, -3.0, 2.0, 4.0);
        assert_eq!(s, ContactState::Slip);
        // |T| = |T_1|/sqrt(a11) = μ N
        assert!((t.abs() / 2.0 - 1.0).abs() < 1e-15 && t < 0.0);
        let law0 = ContactLaw { mu: 0.0, ..law };
        assert_eq!(return_map(&law0, 5.0, 1.0, 1.0).0, 0.0);
    }
}
