//! Why a run stopped, as types: a failure kind a sweep can count without parsing strings,
//! and the contact points that changed state or segment in the iterations before it.

use super::real::Real;
use crate::contact::law::ContactState;
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// What made an increment fail (after every allowed cut-back).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "kebab-case")]
pub enum FailureKind {
    /// Newton reached its iteration limit without an active-set change in its last iterations.
    #[default]
    NoConvergence,
    /// Newton reached its iteration limit while contact points kept changing state or
    /// segment, or converged only with frozen points whose frozen state did not verify.
    ActiveSetCycle,
    /// The residual grew beyond the divergence limit.
    Diverged,
    /// The residual became NaN or infinite.
    NonFinite,
    /// An element could not be evaluated (inverted element, `det F ≤ 0`).
    InvertedElement,
    /// The sparse LU failed (singular tangent).
    LinearSolver,
    /// An observer could not record.
    Recording,
}

impl FailureKind {
    pub fn name(self) -> &'static str {
        match self {
            FailureKind::NoConvergence => "no-convergence",
            FailureKind::ActiveSetCycle => "active-set-cycle",
            FailureKind::Diverged => "diverged",
            FailureKind::NonFinite => "non-finite",
            FailureKind::InvertedElement => "inverted-element",
            FailureKind::LinearSolver => "linear-solver",
            FailureKind::Recording => "recording",
        }
    }
}

/// A contact point that changed state or segment in the iterations of a failed increment.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct ChangingPoint {
    pub pair: usize,
    pub pair_name: String,
    pub slave: usize,
    /// `node N`, `rigid NAME` or `rigid NAME vertex K`.
    pub slave_label: String,
    /// How many times its `(state, segment)` changed within the failed attempt.
    pub changes: u32,
    /// Newton iteration (1-based) of its first change in the failed attempt.
    pub first_change: usize,
    /// Its `(state, segment)` at the last iterates, oldest first.
    pub history: Vec<PointDecision>,
    /// `ξ` at the last iterate (NaN when unpaired).
    #[serde(with = "Real")]
    pub xi: f64,
}

/// A point's contact decision at one iterate.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct PointDecision {
    pub state: ContactState,
    pub segment: Option<usize>,
}
