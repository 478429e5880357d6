//! The structure's stability along the path: the definiteness of the tangent at each
//! converged increment, from the factorisation Newton made anyway
//! ([`crate::linalg::inertia`]).
//!
//! The tangent of a conservative problem (hyperelastic bodies, frictionless penalty contact)
//! is the Hessian of its potential energy: positive definite at a stable equilibrium, with
//! an eigenvalue through zero at a limit or bifurcation point (Crisfield, *Non-linear Finite
//! Element Analysis of Solids and Structures* 2 (1997) §§21–22; Wriggers, *Nonlinear Finite
//! Element Methods* (2008) §7.4). So the first converged increment whose tangent has a
//! negative eigenvalue lies past such a point: the onset of buckling, a snap or a wrinkle is
//! between it and the last increment with a positive definite tangent. The run says so
//! (`/log`, the summary, and the reason of a failure after it) and goes on: a
//! displacement-driven quasi-static Newton may still follow the unstable branch, or fail
//! where the real structure jumps. Frictional tangents are unsymmetric and are not judged
//! (their factorisations do not report).

use crate::linalg::inertia::Inertia;

/// Where the tangent first lost positive definiteness in a run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Instability {
    /// The first converged increment with a negative eigenvalue, and its time.
    pub increment: usize,
    pub t: f64,
    /// The time of the last converged state before it with a positive definite tangent (the
    /// start, 0, when there was none).
    pub stable_until: f64,
    pub inertia: Inertia,
}

/// What changed at a converged increment ([`TangentWatch::observe`]).
#[derive(Debug, Clone, PartialEq)]
pub enum StabilityChange {
    /// The tangent has negative eigenvalues now, or more (or fewer, still some) than at the
    /// last report: the warning.
    Lost(String),
    /// Positive definite again after negative eigenvalues.
    Regained(String),
}

/// The tangent's definiteness over the converged increments of a run.
#[derive(Debug, Clone, Default)]
pub struct TangentWatch {
    /// The last converged state whose tangent was positive definite (its time).
    stable_until: f64,
    /// The definiteness last reported (`None`: positive definite or not yet known).
    reported: Option<Inertia>,
    /// The first loss of the run.
    pub first: Option<Instability>,
    /// A failed attempt since the last converged increment whose last factorised tangent had
    /// a negative eigenvalue.
    failed_negative: Option<Inertia>,
}

impl TangentWatch {
    /// Take the definiteness of the converged increment `increment` at `t` (from its
    /// attempt's last factorised tangent); what changed, if anything.
    pub fn observe(&mut self, increment: usize, t: f64, inertia: Inertia) -> Option<StabilityChange> {
        if inertia.positive() {
            self.stable_until = t;
            return self.reported.take().map(|_| {
                StabilityChange::Regained(format!(
                    "the tangent is positive definite again at t = {t:.6} (a stable equilibrium)"
                ))
            });
        }
        if self.reported == Some(inertia) {
            return None;
        }
        self.reported = Some(inertia);
        self.first.get_or_insert(Instability {
            increment,
            t,
            stable_until: self.stable_until,
            inertia,
        });
        Some(StabilityChange::Lost(format!(
            "the tangent at this converged state has {} ({}): the path passed a limit or bifurcation point \
             between t = {:.6} and t = {t:.6} (buckling, a snap-through, a wrinkle) and this equilibrium is \
             unstable; a quasi-static run driven by its prescribed motion may follow the unstable branch or \
             stop where the structure would jump",
            inertia.describe(),
            source(inertia),
            self.stable_until,
        )))
    }

    /// An increment converged: the failed attempts before it are forgotten.
    pub fn converged(&mut self) {
        self.failed_negative = None;
    }

    /// Take the last factorised tangent of a failed attempt (the first negative one since
    /// the last converged increment is kept for [`Self::failure_hint`]).
    pub fn failed_attempt(&mut self, inertia: Option<Inertia>) {
        if self.failed_negative.is_none() {
            self.failed_negative = inertia.filter(|i| !i.positive());
        }
    }

    /// A hint for a failure's reason: the last converged state's tangent, when it is not
    /// positive definite, else a failed attempt's at this increment that was not.
    pub fn failure_hint(&self) -> Option<String> {
        match (self.reported, self.failed_negative) {
            (Some(last), _) => Some(format!(
                "the tangent has not been positive definite since t = {:.6} ({} at the last converged state): \
                 past a limit or bifurcation point (buckling, a snap) a quasi-static solution driven by the \
                 prescribed motion may not exist, and contrail has neither an arc-length method nor inertia to \
                 follow a jump",
                self.stable_until,
                last.describe()
            )),
            (None, Some(now)) => Some(format!(
                "a failed attempt's last factorised tangent had {} where every converged state's was positive \
                 definite: the step leads past a limit or bifurcation point (buckling, a snap) after t = {:.6}",
                now.describe(),
                self.stable_until
            )),
            (None, None) => None,
        }
    }
}

/// Which factorisation told.
fn source(inertia: Inertia) -> &'static str {
    if inertia.exact {
        "the pivots of its LDLᵀ factorisation"
    } else {
        "the sign of its LU factorisation's determinant"
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const STABLE: Inertia = Inertia {
        negative: 0,
        exact: true,
    };

    fn negative(k: usize) -> Inertia {
        Inertia {
            negative: k,
            exact: true,
        }
    }

    #[test]
    fn a_loss_is_said_once_with_the_interval_and_a_return_is_said_too() {
        let mut w = TangentWatch::default();
        assert_eq!(w.observe(1, 0.1, STABLE), None);
        assert_eq!(w.observe(2, 0.2, STABLE), None);
        let Some(StabilityChange::Lost(m)) = w.observe(3, 0.3, negative(1)) else {
            panic!("a loss")
        };
        assert!(
            m.contains("1 negative eigenvalue") && m.contains("between t = 0.200000 and t = 0.300000"),
            "{m}"
        );
        assert_eq!(w.observe(4, 0.4, negative(1)), None, "said once");
        assert!(matches!(w.observe(5, 0.5, negative(2)), Some(StabilityChange::Lost(_))));
        assert!(w.failure_hint().is_some_and(|h| h.contains("since t = 0.200000")));
        assert!(matches!(w.observe(6, 0.6, STABLE), Some(StabilityChange::Regained(_))));
        assert_eq!(w.observe(7, 0.7, STABLE), None);
        assert_eq!(
            w.first,
            Some(Instability {
                increment: 3,
                t: 0.3,
                stable_until: 0.2,
                inertia: negative(1)
            })
        );
        w.failed_attempt(Some(STABLE));
        w.failed_attempt(None);
        assert_eq!(w.failure_hint(), None);
        w.failed_attempt(Some(negative(1)));
        w.failed_attempt(Some(STABLE));
        assert!(w.failure_hint().is_some_and(|h| h.contains("failed attempt")));
        w.converged();
        assert_eq!(
            w.failure_hint(),
            None,
            "a converged increment forgets the failed attempts"
        );
    }
}
