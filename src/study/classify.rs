//! The one place that turns a [`SolveError`] into a [`FailureKind`].
//!
//! Today `SolveError::StepFailed` carries its reason as text (the `Display` of the Newton
//! failure), so this reads the text; once the solver gives the reason as a type, only this
//! function changes. Cycling is told apart from plain non-convergence by the active-set
//! changes of the failing attempt's last iterations (from the `/iteration` records).

use super::kind::FailureKind;
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
        SolveError::StepFailed { reason, .. } => Some(classify_reason(reason, evidence)),
    }
}

fn classify_reason(reason: &str, evidence: &FailureEvidence) -> FailureKind {
    let r = reason.to_ascii_lowercase();
    if r.contains("jacobian") || r.contains("det f") || r.contains("det j") || r.contains("enhanced-strain") {
        FailureKind::InvertedElement
    } else if r.contains("diverged") || r.contains("non-finite") {
        FailureKind::Diverged
    } else if r.contains("sparse lu") {
        FailureKind::Singular
    } else if evidence.cycling() {
        FailureKind::Cycling
    } else {
        FailureKind::NoConvergence
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn step(reason: &str) -> SolveError {
        SolveError::StepFailed {
            increment: 3,
            t: 0.5,
            dt: 0.1,
            cutbacks: 0,
            reason: reason.into(),
            residuals: vec![],
        }
    }

    #[test]
    fn reasons_map_to_kinds() {
        let quiet = FailureEvidence::default();
        let busy = FailureEvidence {
            active_set_changes: vec![0, 0, 1, 1, 0, 1, 1],
        };
        let cases = [
            ("no convergence in 25 iterations", &quiet, FailureKind::NoConvergence),
            ("no convergence in 25 iterations", &busy, FailureKind::Cycling),
            ("residual diverged (‖R‖ = 1e20)", &quiet, FailureKind::Diverged),
            ("non-finite residual", &busy, FailureKind::Diverged),
            (
                "element 3: non-positive Jacobian det F = -1e-3",
                &quiet,
                FailureKind::InvertedElement,
            ),
            ("sparse LU failed: singular", &quiet, FailureKind::Singular),
            ("linear solve produced non-finite values", &quiet, FailureKind::Diverged),
        ];
        for (reason, ev, kind) in cases {
            assert_eq!(classify(&step(reason), ev), Some(kind), "{reason}");
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
