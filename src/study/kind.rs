//! Why a run did not give a usable answer: the failure kinds kept as a type.

use serde::{Deserialize, Serialize};

/// The kind of a failed (or flagged) run.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum FailureKind {
    /// Newton reached its iteration limit without the active set flipping back and forth.
    NoConvergence,
    /// Newton reached its iteration limit while contact points kept changing state or segment.
    Cycling,
    /// The residual grew beyond the divergence bound or became non-finite.
    Diverged,
    /// An element turned inside out (det F ≤ 0) or its enhanced strains did not converge.
    InvertedElement,
    /// The tangent matrix could not be factorised (singular system).
    Singular,
    /// The run completed but a contact pair that must stay closed opened (flagged by a check).
    LostContact,
    /// The run completed but an error metric exceeds the plan's bound (flagged by a check).
    WrongAnswer,
    /// The scene or an override is invalid; the run never started.
    BadInput,
    /// A sink failed (disk full, unwritable file); says nothing about the method.
    Recording,
}

impl FailureKind {
    /// Every kind, in the order of the charts' legends.
    pub const ALL: [FailureKind; 9] = [
        FailureKind::NoConvergence,
        FailureKind::Cycling,
        FailureKind::Diverged,
        FailureKind::InvertedElement,
        FailureKind::Singular,
        FailureKind::LostContact,
        FailureKind::WrongAnswer,
        FailureKind::BadInput,
        FailureKind::Recording,
    ];

    /// The kebab-case name used in indexes and charts.
    pub fn as_str(self) -> &'static str {
        match self {
            FailureKind::NoConvergence => "no-convergence",
            FailureKind::Cycling => "cycling",
            FailureKind::Diverged => "diverged",
            FailureKind::InvertedElement => "inverted-element",
            FailureKind::Singular => "singular",
            FailureKind::LostContact => "lost-contact",
            FailureKind::WrongAnswer => "wrong-answer",
            FailureKind::BadInput => "bad-input",
            FailureKind::Recording => "recording",
        }
    }

    /// Parse a kebab-case name (None when unknown).
    pub fn parse(s: &str) -> Option<FailureKind> {
        FailureKind::ALL.into_iter().find(|k| k.as_str() == s)
    }
}

impl std::fmt::Display for FailureKind {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.as_str())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_round_trip_and_match_serde() {
        for k in FailureKind::ALL {
            assert_eq!(FailureKind::parse(k.as_str()), Some(k));
            assert_eq!(serde_json::to_string(&k).unwrap(), format!("\"{}\"", k.as_str()));
        }
        assert_eq!(FailureKind::parse("nope"), None);
    }
}
