//! History transfer when a contact point moves from the segment `A` of the last converged
//! increment to a segment `B` (seed §3). Each scheme builds the trial covariant traction
//! `T_1^tr` on `B` from the stored history and the *current* geometry, so it is evaluated
//! inside the Newton loop and differentiated with everything else (the nodes of `A` become
//! unknowns of the contact element during a crossing step).
//!
//! One scheme per file behind [`Transfer`]; [`TransferKind`] selects one per contact pair.

mod continuous;
mod path_length;
mod spatial;
mod straightforward;

pub use continuous::Continuous;
pub use path_length::PathLength;
pub use spatial::Spatial;
pub use straightforward::Straightforward;

use super::geometry::Projection;
use super::scalar::{Scalar, V2};

pub use crate::model::TransferKind;

impl TransferKind {
    /// Trial covariant traction on the current segment (dispatch to the scheme).
    pub fn trial<S: Scalar>(self, ctx: &TransferInput<S>) -> S {
        match self {
            TransferKind::Straightforward => Straightforward.trial(ctx),
            TransferKind::Continuous => Continuous.trial(ctx),
            TransferKind::PathLength => PathLength.trial(ctx),
            TransferKind::Spatial => Spatial.trial(ctx),
        }
    }
}

/// History of a closed contact point at the last converged increment, on segment `A`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StoredTraction {
    /// `ξ_A`.
    pub xi: f64,
    /// Covariant traction `T_1^(n)` on `A`.
    pub t1: f64,
    /// `a11` of `A` at `ξ_A` when it was stored (so `T^1_A = T_1 / a11`).
    pub a11: f64,
    /// Spatial history (the spatial scheme): the slave's position and the unit tangent of
    /// the master at the contact point when it was stored.
    pub slave: [f64; 2],
    pub tangent: [f64; 2],
}

/// Where the old contact point is now: segment `A` evaluated at `ξ_A` in the current
/// configuration.
#[derive(Debug, Clone, Copy)]
pub struct OldPoint<S: Scalar> {
    /// `ρ_A(ξ_A)`, current.
    pub rho: V2<S>,
    /// `ρ^A_1(ξ_A)`, current.
    pub rho1: V2<S>,
}

/// Everything a scheme may use.
#[derive(Debug, Clone, Copy)]
pub struct TransferInput<S: Scalar> {
    pub eps_t: f64,
    pub stored: StoredTraction,
    /// Current projection on `B`.
    pub current: Projection<S>,
    /// The old contact point on `A` in the current configuration (`A = B` when no crossing).
    pub old: OldPoint<S>,
    /// Signed arc length from the old contact point to the current one along the master
    /// surface (used by the path-length scheme).
    pub arc_length: S,
    /// Whether `A ≠ B`.
    pub crossing: bool,
    /// `ξ` of the closest point of the stored slave position on the current `B` (the
    /// spatial scheme; zero for the others, which do not compute it).
    pub stored_slave_xi: S,
}

/// A history-transfer scheme.
pub trait Transfer {
    /// Trial covariant traction `T_1^tr` on the current segment `B`.
    fn trial<S: Scalar>(&self, input: &TransferInput<S>) -> S;
}

#[cfg(test)]
mod tests;
