//! What the solver reports, and to whom: record types (serde + JSON Schema) and the
//! [`Observer`] trait that sinks implement. The solver never does I/O itself.

pub mod atomic_file;
pub mod background;
mod failure;
pub mod interface;
pub mod mcap;
pub mod messages;
mod observer;
pub mod packed_positions;
pub mod pressure;
pub mod real;
pub mod rrd;
pub mod surface_contact;
pub mod text;
pub mod vtu;

pub use failure::{ChangingPoint, FailureKind, PointDecision};
pub use observer::{Fanout, Memory, Observer, ObserverError};

use crate::contact::events::{CrossingEvent, PointSnapshot};
use crate::contact::law::ContactState;
use crate::model::Model;
use crate::settings::SolverSettings;
use real::{Real, Real2, Reals};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};
use std::sync::Arc;

/// Facts about a run known before it starts.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
pub struct RunInfo {
    pub scene: String,
    /// Where the scene came from (`builtin:NAME` or a path).
    pub scene_origin: String,
    /// The scene text as given (before `--set` overrides).
    pub scene_text: String,
    /// `--set` overrides, in order.
    pub overrides: Vec<String>,
    pub crate_version: String,
    pub git_revision: String,
    /// Transfer scheme of each contact pair.
    pub transfer: Vec<String>,
    pub dofs: usize,
    pub free_dofs: usize,
    /// Stepping and Newton settings of the run.
    #[serde(default)]
    pub settings: SolverSettings,
}

/// One Newton iteration.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
pub struct IterationRecord {
    /// Increment being attempted (1-based; a cut-back retries the same number).
    pub increment: usize,
    /// Attempt of this increment (0 = first try, k = after k cut-backs).
    pub attempt: usize,
    #[serde(with = "Real")]
    pub t: f64,
    pub iteration: usize,
    /// `‖R‖` over the free DOFs at the iterate this correction started from.
    #[serde(with = "Real")]
    pub residual: f64,
    /// `|Δu · R|` of the correction.
    #[serde(with = "Real")]
    pub energy: f64,
    /// Reference force `F_ref` of the residual criterion.
    #[serde(with = "Real")]
    pub reference: f64,
    /// Line-search factor applied to the correction (1 without line search).
    #[serde(with = "Real")]
    pub line_search: f64,
    /// Contact points whose state or segment changed since the previous iterate.
    pub active_set_changes: usize,
}

/// One monitor at a converged increment: a node set's mean displacement and the sum of the
/// reactions (or loads) on it, or a rigid body's prescribed travel and the sum of the contact
/// forces it receives.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
pub struct MonitorRecord {
    pub label: String,
    /// Mean displacement of the set, or travel of the rigid body, in the monitored direction
    /// (sign as configured).
    #[serde(with = "Real")]
    pub displacement: f64,
    /// Sum of reactions/loads on the set, or of the contact forces on the rigid body, in that
    /// direction (sign as configured).
    #[serde(with = "Real")]
    pub force: f64,
}

/// A converged increment.
#[derive(Debug, Clone, Default, Serialize, Deserialize, JsonSchema)]
pub struct IncrementRecord {
    pub increment: usize,
    #[serde(with = "Real")]
    pub t: f64,
    #[serde(with = "Real")]
    pub dt: f64,
    pub iterations: usize,
    /// Cut-backs needed by this increment.
    pub cutbacks: usize,
    pub converged: bool,
    #[serde(with = "Real")]
    pub wall_time_s: f64,
    /// Residual norms of the iterations of this increment.
    #[serde(with = "Reals")]
    pub residuals: Vec<f64>,
    /// The first monitor of the scene (the same record as `monitors[0]`; kept for readers
    /// of one load–displacement pair).
    pub monitor: Option<MonitorRecord>,
    /// Every monitor of the scene, in scene order (absent in recordings made before several
    /// monitors were possible: read as empty).
    #[serde(default)]
    pub monitors: Vec<MonitorRecord>,
    /// Sum of all reaction forces (x, y).
    #[serde(with = "Real2")]
    pub reaction_total: [f64; 2],
    /// The z component of the sum of the reactions (3D models only).
    #[serde(default, skip_serializing_if = "Option::is_none", with = "real_option")]
    #[schemars(with = "Option<Real>")]
    pub reaction_z: Option<f64>,
    /// Which convergence test accepted the increment: `residual` (‖R‖ ≤ tol · F_ref and the
    /// energy test), `round-off` (‖R‖ at the assembled residual's round-off floor) or
    /// `start` (the first iterate met the residual test); empty in older recordings.
    #[serde(default)]
    pub accepted_by: String,
    /// Corrections of the converged attempt whose line search found no decrease of the
    /// merit function (the shortest step tried was taken).
    #[serde(default)]
    pub line_search_failures: usize,
    /// Corrections of the converged attempt shifted by the pseudo-transient continuation
    /// that follows a failed line search (`(K + D/δ) Δu = −R`), and the work of its drag
    /// along the steps taken (`Σ s² Δuᵀ (D/δ) Δu`, in the model's energy units); no drag
    /// acts on the converged state.
    #[serde(default)]
    pub stabilised_corrections: usize,
    #[serde(with = "Real", default)]
    pub stabilisation_work: f64,
    /// Closed contact points whose converged projection lies on an extension of their
    /// segment (kept there against a crossing back and forth at a node of the master).
    #[serde(default)]
    pub on_extension: usize,
    /// Newton iterations of the converged attempt that reached an active set not met before
    /// in it (a moving contact front); each extended the iteration limit by one.
    #[serde(default)]
    pub front_iterations: usize,
    /// The largest resultant force on a body of the converged state (its loads, reactions
    /// and recorded contact forces), relative to the convergence test's force scale: zero
    /// up to round-off in a state in equilibrium (`crate::solver::equilibrium`). NaN in
    /// older recordings.
    #[serde(with = "Real", default = "nan")]
    pub equilibrium: f64,
    /// The definiteness of the converged attempt's last factorised tangent that the
    /// continuation did not shift (absent where none told: an unsymmetric tangent with a
    /// negative determinant, faer's LU, the Krylov solver; and in older recordings).
    /// Negative eigenvalues at a converged state: the path has passed a limit or
    /// bifurcation point (`crate::solver::stability`).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub tangent: Option<TangentRecord>,
}

/// What the factorisation of a symmetric tangent says about its eigenvalues
/// ([`crate::linalg::inertia`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
pub struct TangentRecord {
    /// Negative eigenvalues: the count (`exact`, from an `LDLᵀ`'s pivots) or its parity, 0
    /// or 1 (`exact` false: the sign of a banded LU's determinant).
    pub negative_eigenvalues: usize,
    pub exact: bool,
}

impl TangentRecord {
    pub fn of(i: crate::linalg::inertia::Inertia) -> Self {
        TangentRecord {
            negative_eigenvalues: i.negative,
            exact: i.exact,
        }
    }
}

fn nan() -> f64 {
    f64::NAN
}

impl IncrementRecord {
    /// Every monitor of the increment: `monitors`, or the single `monitor` of a recording
    /// made before several monitors were possible.
    pub fn all_monitors(&self) -> Vec<&MonitorRecord> {
        if self.monitors.is_empty() {
            self.monitor.iter().collect()
        } else {
            self.monitors.iter().collect()
        }
    }

    /// The monitor labelled `label`, or the first one when `label` is `None`.
    pub fn monitor_named(&self, label: Option<&str>) -> Option<&MonitorRecord> {
        match label {
            None => self.monitor.as_ref().or(self.monitors.first()),
            Some(l) => self.all_monitors().into_iter().find(|m| m.label == l),
        }
    }
}

/// State of one contact slave point at the end of an increment.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
pub struct ContactPointRecord {
    pub pair: usize,
    // shared with the run's other records (built once: see `ContactLabels`)
    pub pair_name: Arc<str>,
    pub slave: usize,
    /// `node N` or `rigid NAME`.
    pub slave_label: Arc<str>,
    /// Master segment of the current projection (None: no segment within reach).
    pub segment: Option<usize>,
    /// Segment at the previous converged increment.
    pub previous_segment: Option<usize>,
    #[serde(with = "Real")]
    pub xi: f64,
    /// Centre of the elastic region (sliding anchor) `ξ_sl = ξ + T_1/(ε_T a11)` on `segment`.
    #[serde(with = "Real")]
    pub xi_anchor: f64,
    /// Signed gap `ζ` (negative = penetration).
    #[serde(with = "Real")]
    pub gap: f64,
    #[serde(with = "Real")]
    pub normal_force: f64,
    /// Trial tangential traction along the unit tangent (before return mapping).
    #[serde(with = "Real")]
    pub trial_traction: f64,
    /// Returned tangential traction along the unit tangent.
    #[serde(with = "Real")]
    pub traction: f64,
    /// `open`, `stick` or `slip`; a closed point of a frictionless pair (`μ = 0`) is `slip`
    /// (without friction there is no stick).
    pub state: ContactState,
    /// The point is closed and was closed at the last converged increment, on another
    /// segment: a crossing that carries friction history across a segment boundary (one
    /// `/crossing` event each). A point that closes on another segment than the one it was
    /// tracked on while open, or opens, is not crossing.
    pub crossing: bool,
    /// Slave position and contact point `ρ(ξ)`.
    #[serde(with = "Real2")]
    pub position: [f64; 2],
    #[serde(with = "Real2")]
    pub contact_point: [f64; 2],
    /// Unit normal and unit tangent of the master at the contact point.
    #[serde(with = "Real2")]
    pub normal: [f64; 2],
    #[serde(with = "Real2")]
    pub tangent: [f64; 2],
    /// Augmented-Lagrangian multiplier estimates the increment's last solve used: the normal
    /// force `λ_N` and the tangential traction `λ_T` along the unit tangent (NaN in penalty
    /// pairs; `λ_T` NaN for a point without friction history). Absent in older recordings.
    #[serde(with = "Real2", default = "nan2")]
    pub multiplier: [f64; 2],
    /// The contact force the slave receives (x, y), as assembled at the converged state:
    /// `normal_force · normal + traction · tangent` on a straight master, with the
    /// curvature factor `1/(1 − ζ κ)` of `∇ξ` on a curved one; zero for an open point; its
    /// negative acts on the master. NaN in older recordings.
    #[serde(with = "Real2", default = "nan2")]
    pub force: [f64; 2],
}

fn nan2() -> [f64; 2] {
    [f64::NAN; 2]
}

/// The names of a model's contact pairs and slaves, made once per run and shared by the
/// records of every increment (a record copied to a writer thread copies no string).
#[derive(Debug, Clone, Default)]
pub struct ContactLabels {
    /// Per pair: its name and its slaves' labels.
    pairs: Vec<(Arc<str>, Vec<Arc<str>>)>,
}

impl ContactLabels {
    pub fn new(model: &Model) -> Self {
        ContactLabels {
            pairs: (model.contacts.iter())
                .map(|c| {
                    let slaves = c.slaves.iter().map(|&s| Arc::from(model.slave_label(s))).collect();
                    (Arc::from(c.name.as_str()), slaves)
                })
                .collect(),
        }
    }

    /// The name of pair `pair` and the label of its slave `slave`.
    fn get(&self, pair: usize, slave: usize) -> (Arc<str>, Arc<str>) {
        let (name, slaves) = &self.pairs[pair];
        (name.clone(), slaves[slave].clone())
    }

    /// The same, or `None` for a pair or slave the model does not have.
    pub fn label(&self, pair: usize, slave: usize) -> Option<(Arc<str>, Arc<str>)> {
        let (name, slaves) = self.pairs.get(pair)?;
        Some((name.clone(), slaves.get(slave)?.clone()))
    }
}

impl ContactPointRecord {
    /// The record of a contact system's snapshot, named by `labels` (made once per run
    /// from the model the snapshot is of).
    pub fn from_snapshot(labels: &ContactLabels, s: &PointSnapshot) -> Self {
        let (pair_name, slave_label) = labels.get(s.pair, s.slave);
        ContactPointRecord {
            pair: s.pair,
            pair_name,
            slave: s.slave,
            slave_label,
            segment: s.segment,
            previous_segment: s.previous_segment,
            xi: s.xi,
            xi_anchor: s.xi_anchor,
            gap: s.gap,
            normal_force: s.normal_force,
            trial_traction: s.trial_traction,
            traction: s.traction,
            force: s.force,
            state: s.state,
            crossing: s.crossing,
            position: s.position,
            contact_point: s.contact_point,
            normal: s.normal,
            tangent: s.tangent,
            multiplier: s.multiplier,
        }
    }
}

/// A contact point moved from segment `A` to `B` in a converged increment.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
pub struct CrossingRecord {
    pub pair: usize,
    pub slave: usize,
    pub from_segment: usize,
    pub to_segment: usize,
    /// `ξ_A` (stored) and `ξ_B` (current).
    #[serde(with = "Real")]
    pub xi_from: f64,
    #[serde(with = "Real")]
    pub xi_to: f64,
    /// Projection of the current slave position on `A`'s extension (`|ξ| > 1`).
    #[serde(with = "Real")]
    pub xi_from_extended: f64,
    /// `Δρ = ρ_B(ξ_B) − ρ_A(ξ_A)` in the current configuration (seed eq. 2).
    #[serde(with = "Real2")]
    pub delta_rho: [f64; 2],
    /// +1 forward along the chain, −1 backward.
    pub direction: i8,
    /// Angle between the unit tangents of `A` and `B` (radians, signed, current configuration).
    #[serde(with = "Real")]
    pub kink_angle: f64,
    /// Trial traction on `A` extended (same-segment formula), along `A`'s unit tangent.
    #[serde(with = "Real")]
    pub trial_before: f64,
    /// Trial traction on `B` after transfer by the pair's scheme, along `B`'s unit tangent.
    #[serde(with = "Real")]
    pub trial_after: f64,
    /// Returned traction on `B`.
    #[serde(with = "Real")]
    pub returned_after: f64,
}

impl From<&CrossingEvent> for CrossingRecord {
    fn from(e: &CrossingEvent) -> Self {
        CrossingRecord {
            pair: e.pair,
            slave: e.slave,
            from_segment: e.from_segment,
            to_segment: e.to_segment,
            xi_from: e.xi_from,
            xi_to: e.xi_to,
            xi_from_extended: e.xi_from_extended,
            delta_rho: e.delta_rho,
            direction: e.direction,
            kink_angle: e.kink_angle,
            trial_before: e.trial_before,
            trial_after: e.trial_after,
            returned_after: e.returned_after,
        }
    }
}

/// Severity of a log message.
#[derive(Debug, Clone, Copy, Serialize, Deserialize, JsonSchema, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum LogLevel {
    Info,
    Warning,
    Error,
}

/// A message for humans (cut-backs, failures, interruption).
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
pub struct LogRecord {
    pub level: LogLevel,
    pub increment: usize,
    #[serde(with = "Real")]
    pub t: f64,
    pub message: String,
}

/// How a run ended.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema, PartialEq)]
#[serde(tag = "status", rename_all = "lowercase")]
pub enum Outcome {
    Completed {
        increments: usize,
        #[serde(with = "Real")]
        t: f64,
    },
    Failed {
        increment: usize,
        #[serde(with = "Real")]
        t: f64,
        reason: String,
        #[serde(with = "Reals")]
        residuals: Vec<f64>,
        /// What made the increment fail.
        #[serde(default)]
        kind: FailureKind,
        /// Contact points that changed state or segment in the failed attempt, most
        /// still-changing ones first.
        #[serde(default)]
        points: Vec<ChangingPoint>,
    },
    Interrupted {
        increment: usize,
        #[serde(with = "Real")]
        t: f64,
    },
}

/// What an observer sees at the end of a converged increment.
pub struct StepView<'a> {
    /// The model, of either dimension (2D sinks draw [`crate::model::ModelRef::plane`]).
    pub model: crate::model::ModelRef<'a>,
    /// Full displacement vector (`D` per node).
    pub u: &'a [f64],
    pub contact: &'a [ContactPointRecord],
    pub crossings: &'a [CrossingRecord],
    /// The 3D (node-to-surface) points (none in 2D).
    pub surface: &'a [surface_contact::SurfacePointRecord],
}

/// An optional [`Real`] (absent when `None`).
mod real_option {
    use super::real::Real;
    use serde::{Deserializer, Serializer};

    pub fn serialize<S: Serializer>(x: &Option<f64>, s: S) -> Result<S::Ok, S::Error> {
        match x {
            Some(v) => Real::serialize(v, s),
            None => s.serialize_none(),
        }
    }

    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<Option<f64>, D::Error> {
        Real::deserialize(d).map(Some)
    }
}
