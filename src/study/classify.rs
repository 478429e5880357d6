//! The one place that turns a [`SolveError`] into the run's [`FailureKind`].
//!
//! `SolveError::StepFailed` carries the solver's failure kind; a non-convergence whose last
//! iterations kept changing the active set (from the `/iteration` records) is counted as an
//! active-set cycle.

use crate::record::FailureKind;
use crate::solver::SolveError;

/// What the iteration records of the failing attempt showed.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct FailureEvidence {
    /// `active_set_changes` of each iteration of the last (failing) attempt, in order.
    pub active_set_changes: Vec<usize>,
}

impl FailureEvidence {
    /// True when at least half of the last (up to) six iterations changed the active set.
    pub fn cycling(&self) -> bool {
        let tail = &self.active_set_changes[self.active_set_changes.len().saturating_sub(6)..];
        tail.len() >= 2 && 2 * tail.iter().filter(|&&c| c > 0).count() >= tail.len()
    }
}

/// The kind of a failed run (`None` for an interruption, which is not a failure).
pub fn classify(err: &SolveError, evidence: &FailureEvidence) -> Option<FailureKind> {
    match err {
        SolveError::Interrupted { .. } => None,
        SolveError::Observer(_) => Some(FailureKind::Recording),
        SolveError::StepFailed { kind, .. } => Some(match kind {
            FailureKind::NoConvergence if evidence.cycling() => FailureKind::ActiveSetCycle,
            other => *other,
        }),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn step(kind: FailureKind) -> SolveError {
        SolveError::StepFailed {
            increment: 3,
            t: 0.5,
            dt: 0.1,
            cutbacks: 0,
            reason: String::new(),
            residuals: vec![],
            kind,
            points: vec![],
        }
    }

    #[test]
    fn solver_kinds_map_to_sweep_kinds() {
        use FailureKind as S;
        let quiet = FailureEvidence::default();
        let busy = FailureEvidence {
            active_set_changes: vec![0, 0, 1, 1, 0, 1, 1],
        };
        let cases = [
            (S::NoConvergence, &quiet, FailureKind::NoConvergence),
            (S::NoConvergence, &busy, FailureKind::ActiveSetCycle),
            (S::ActiveSetCycle, &quiet, FailureKind::ActiveSetCycle),
            (S::Diverged, &quiet, FailureKind::Diverged),
            (S::NonFinite, &busy, FailureKind::NonFinite),
            (S::InvertedElement, &quiet, FailureKind::InvertedElement),
            (S::LinearSolver, &quiet, FailureKind::LinearSolver),
        ];
        for (kind, ev, expect) in cases {
            assert_eq!(classify(&step(kind), ev), Some(expect), "{kind:?}");
        }
        let int = SolveError::Interrupted { increment: 1, t: 0.0 };
        assert_eq!(classify(&int, &quiet), None);
    }

    #[test]
    fn cycling_needs_changes_in_most_late_iterations() {
        let ev = |v: Vec<usize>| FailureEvidence { active_set_changes: v };
        assert!(!ev(vec![]).cycling());
        assert!(!ev(vec![1]).cycling());
        assert!(ev(vec![1, 1]).cycling());
        assert!(!ev(vec![3, 3, 3, 0, 0, 0, 0, 1]).cycling());
    }
}
