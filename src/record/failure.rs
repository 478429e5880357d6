//! Why a run stopped, as types: a failure kind a sweep can count without parsing strings,
//! and the contact points that changed state or segment in the iterations before it.

use super::real::Real;
use crate::contact::law::ContactState;
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// Why a run gave no usable answer: the one failure type of the solver, the recordings, the
/// sweeps and the service. The solver's kinds say what made an increment fail after every
/// allowed cut-back; a completed run may still be flagged by a sweep's checks
/// ([`FailureKind::LostContact`], [`FailureKind::WrongAnswer`]); a run that never started is
/// [`FailureKind::BadInput`]. Names are kebab-case (`active-set-cycle`); the names older
/// sweep indexes used (`cycling`, `singular`) still read.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Default, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "kebab-case")]
pub enum FailureKind {
    /// Newton reached its iteration limit without an active-set change in its last iterations.
    #[default]
    NoConvergence,
    /// Newton reached its iteration limit while contact points kept changing state or
    /// segment, or converged only with frozen points whose frozen state did not verify.
    #[serde(alias = "cycling")]
    ActiveSetCycle,
    /// The residual grew beyond the divergence limit.
    Diverged,
    /// The residual became NaN or infinite.
    NonFinite,
    /// An element could not be evaluated (inverted element, `det F ≤ 0`, or its enhanced
    /// strains did not converge).
    InvertedElement,
    /// The tangent could not be factorised (singular system).
    #[serde(alias = "singular")]
    LinearSolver,
    /// The run completed but a contact pair that must stay closed opened (a sweep's check).
    LostContact,
    /// An error metric exceeds the plan's bound (a sweep's check), or a converged increment
    /// failed the solver's own equilibrium check (`crate::solver::equilibrium`).
    WrongAnswer,
    /// The scene or an override is invalid; the run never started.
    BadInput,
    /// A sink failed (disk full, unwritable file); says nothing about the method.
    Recording,
}

impl FailureKind {
    /// Every kind, in the order of the charts' legends.
    pub const ALL: [FailureKind; 10] = [
        FailureKind::NoConvergence,
        FailureKind::ActiveSetCycle,
        FailureKind::Diverged,
        FailureKind::NonFinite,
        FailureKind::InvertedElement,
        FailureKind::LinearSolver,
        FailureKind::LostContact,
        FailureKind::WrongAnswer,
        FailureKind::BadInput,
        FailureKind::Recording,
    ];

    /// The kebab-case name (as serialised, in indexes, charts and the CLI).
    pub fn as_str(self) -> &'static str {
        match self {
            FailureKind::NoConvergence => "no-convergence",
            FailureKind::ActiveSetCycle => "active-set-cycle",
            FailureKind::Diverged => "diverged",
            FailureKind::NonFinite => "non-finite",
            FailureKind::InvertedElement => "inverted-element",
            FailureKind::LinearSolver => "linear-solver",
            FailureKind::LostContact => "lost-contact",
            FailureKind::WrongAnswer => "wrong-answer",
            FailureKind::BadInput => "bad-input",
            FailureKind::Recording => "recording",
        }
    }

    /// Parse a name, the older `cycling` and `singular` included (None when unknown).
    pub fn parse(s: &str) -> Option<FailureKind> {
        match s {
            "cycling" => Some(FailureKind::ActiveSetCycle),
            "singular" => Some(FailureKind::LinearSolver),
            _ => FailureKind::ALL.into_iter().find(|k| k.as_str() == s),
        }
    }
}

impl std::fmt::Display for FailureKind {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.as_str())
    }
}

/// A contact point that changed state or segment in the iterations of a failed increment.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct ChangingPoint {
    pub pair: usize,
    pub pair_name: String,
    pub slave: usize,
    /// `node N`, `rigid NAME` or `rigid NAME vertex K` (a 3D point: `node N`).
    pub slave_label: String,
    /// How many times its `(state, segment)` changed within the failed attempt.
    pub changes: u32,
    /// Newton iteration (1-based) of its first change in the failed attempt.
    pub first_change: usize,
    /// Its `(state, segment)` at the last iterates, oldest first.
    pub history: Vec<PointDecision>,
    /// `ξ` at the last iterate (NaN when unpaired; `ξ¹` of a 3D point).
    #[serde(with = "Real")]
    pub xi: f64,
    /// A 3D node-to-surface point: `pair` indexes the model's surface pairs, `slave` the
    /// pair's slave nodes, the segment in `history` is the facet, and `xi2` is its `ξ²`.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub surface: bool,
    /// `ξ²` of a 3D point at the last iterate (NaN, and not written, for a 2D point or an
    /// unpaired one).
    #[serde(with = "Real", default = "not_a_number", skip_serializing_if = "is_nan")]
    pub xi2: f64,
}

fn not_a_number() -> f64 {
    f64::NAN
}

fn is_nan(x: &f64) -> bool {
    x.is_nan()
}

impl ChangingPoint {
    /// One phrase: `node 12 of `base`: 5 changes, the first at iteration 2; its last 3
    /// iterates: Stick@3 → Open@- → Stick@3; ξ = 0.41` (`unpaired` where it has no
    /// projection). The iterates shown are the last ones kept, which need not include the
    /// changes counted.
    pub fn describe(&self) -> String {
        let states: Vec<String> = (self.history.iter())
            .map(|d| format!("{:?}@{}", d.state, d.segment.map_or("-".into(), |s| s.to_string())))
            .collect();
        let xi = match (self.xi.is_finite(), Some(self.xi2).filter(|v| v.is_finite())) {
            (true, Some(xi2)) => format!(
                "(ξ¹, ξ²) = ({}, {})",
                crate::format::plain(self.xi),
                crate::format::plain(xi2)
            ),
            (true, None) => format!("ξ = {}", crate::format::plain(self.xi)),
            (false, _) => "unpaired (no projection on its master)".to_string(),
        };
        format!(
            "{} of `{}`: {} {}, the first at iteration {}; its last {} iterates: {}; {}",
            self.slave_label,
            self.pair_name,
            self.changes,
            if self.changes == 1 { "change" } else { "changes" },
            self.first_change,
            states.len(),
            states.join(" → "),
            xi
        )
    }
}

/// A point's contact decision at one iterate.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct PointDecision {
    pub state: ContactState,
    pub segment: Option<usize>,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_round_trip_and_match_serde_and_older_names_still_read() {
        for k in FailureKind::ALL {
            assert_eq!(FailureKind::parse(k.as_str()), Some(k));
            assert_eq!(serde_json::to_string(&k).unwrap(), format!("\"{}\"", k.as_str()));
        }
        assert_eq!(FailureKind::parse("nope"), None);
        for (old, k) in [
            ("cycling", FailureKind::ActiveSetCycle),
            ("singular", FailureKind::LinearSolver),
        ] {
            assert_eq!(FailureKind::parse(old), Some(k));
            assert_eq!(serde_json::from_str::<FailureKind>(&format!("\"{old}\"")).unwrap(), k);
        }
    }

    #[test]
    fn a_changing_point_says_what_its_history_shows_and_when_it_is_unpaired() {
        let open = PointDecision {
            state: ContactState::Open,
            segment: None,
        };
        let p = ChangingPoint {
            pair: 0,
            pair_name: "incline".into(),
            slave: 0,
            slave_label: "node 0".into(),
            changes: 2,
            first_change: 2,
            history: vec![open; 3],
            xi: f64::NAN,
            surface: false,
            xi2: f64::NAN,
        };
        let d = p.describe();
        assert_eq!(
            d,
            "node 0 of `incline`: 2 changes, the first at iteration 2; its last 3 iterates: \
             Open@- → Open@- → Open@-; unpaired (no projection on its master)"
        );
        let one = ChangingPoint {
            changes: 1,
            xi: 0.5,
            ..p
        };
        assert!(one.describe().contains("1 change, the first") && one.describe().ends_with("ξ = 0.5"));
        let on_facet = ChangingPoint {
            surface: true,
            xi2: -0.25,
            ..one
        };
        assert!(
            on_facet.describe().ends_with("(ξ¹, ξ²) = (0.5, -0.25)"),
            "{}",
            on_facet.describe()
        );
    }
}
