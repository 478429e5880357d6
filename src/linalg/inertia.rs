//! What a factorisation of a symmetric tangent says about its definiteness: the number of
//! negative eigenvalues (its *inertia*), from the pivots the factorisation made anyway.
//!
//! - `LDLᵀ` (no pivoting, `K = L D Lᵀ` with `L` unit lower triangular): `K` and `D` are
//!   congruent, so by Sylvester's law of inertia `K` has exactly as many negative eigenvalues
//!   as `D` has negative entries ([`Inertia::from_pivots`]).
//! - `P K = L U` (partial pivoting): `det K = (−1)^s Π u_jj` for `s` row interchanges; its
//!   sign says whether the number of negative eigenvalues is odd — the parity, not the
//!   count ([`Inertia::from_lu`]). The first eigenvalue to cross zero flips it.
//!
//! The tangent of a conservative problem (hyperelastic bodies, frictionless penalty contact)
//! is the Hessian of its potential energy, positive definite at a stable equilibrium; a
//! negative eigenvalue at a converged state means the path has passed a limit or bifurcation
//! point (buckling, a snap). Pivots within [`ROUND_OFF`] of the largest in magnitude are not
//! counted: a tangent that is singular up to round-off (a body held by contact that has not
//! closed yet) is not called unstable for the sign of its round-off.

/// Pivots of magnitude at most `ROUND_OFF × max |pivot|` are taken for zeros (neither sign
/// counted). The factorisations here reach a relative accuracy near 1e-16 × the condition
/// number; a margin of six orders keeps round-off out on tangents with condition numbers up
/// to 1e10 (a penalty of 1e7 E on a graded mesh).
pub const ROUND_OFF: f64 = 1e-10;

/// The definiteness of one factorised tangent.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Inertia {
    /// Negative eigenvalues: the count (`exact`) or its parity, 0 or 1 (an LU's determinant).
    pub negative: usize,
    /// `true`: `negative` is the count (`LDLᵀ`); `false`: only its parity is known (LU).
    pub exact: bool,
}

impl Inertia {
    /// From the diagonal `D` of an `LDLᵀ` factorisation: the negative entries, ignoring
    /// those within [`ROUND_OFF`] of the largest.
    pub fn from_pivots(pivots: impl Iterator<Item = f64> + Clone) -> Self {
        let floor = ROUND_OFF * pivots.clone().fold(0.0, |m: f64, d| m.max(d.abs()));
        Inertia {
            negative: pivots.filter(|&d| d < -floor).count(),
            exact: true,
        }
    }

    /// From `P K = L U`: `odd`, whether the negative pivots of `U` and the row interchanges
    /// are odd in number together (the determinant is negative), and the smallest and
    /// largest pivot magnitude. `None` when a pivot lies within [`ROUND_OFF`] of zero (the
    /// sign is round-off).
    pub fn from_lu(odd: bool, (min_abs, max_abs): (f64, f64)) -> Option<Self> {
        (min_abs > ROUND_OFF * max_abs).then_some(Inertia {
            negative: usize::from(odd),
            exact: false,
        })
    }

    /// Whether the tangent is positive definite as far as this tells: no negative eigenvalue
    /// (`exact`) or a positive determinant.
    pub fn positive(&self) -> bool {
        self.negative == 0
    }

    /// "1 negative eigenvalue", "3 negative eigenvalues" or "a negative determinant (an odd
    /// number of negative eigenvalues)".
    pub fn describe(&self) -> String {
        match (self.exact, self.negative) {
            (true, 1) => "1 negative eigenvalue".to_string(),
            (true, k) => format!("{k} negative eigenvalues"),
            (false, 0) => "a positive determinant".to_string(),
            (false, _) => "a negative determinant (an odd number of negative eigenvalues)".to_string(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pivots_count_negatives_above_round_off() {
        let i = Inertia::from_pivots([4.0, -1.0, 2.0, -3e-12, -0.5].into_iter());
        assert_eq!(
            i,
            Inertia {
                negative: 2,
                exact: true
            }
        );
        assert!(!i.positive());
        assert!(Inertia::from_pivots([1.0, 2.0, -1e-11].into_iter()).positive());
    }

    #[test]
    fn lu_gives_the_determinants_sign() {
        let det = |odd, range| Inertia::from_lu(odd, range).map(|i| (i.negative, i.exact));
        assert_eq!(det(false, (1.0, 3.0)), Some((0, false)));
        assert_eq!(det(true, (1.0, 3.0)), Some((1, false)));
        assert_eq!(det(true, (1e-12, 3.0)), None, "a pivot at round-off");
    }
}
