//! An observer that keeps the few things a study needs from a run: counts, the
//! load–displacement curve, the crossing jumps, the final contact points, the contact pairs
//! that opened after having closed, and the failing attempt's iterations (for
//! [`super::classify`]).

use super::classify::FailureEvidence;
use crate::contact::law::ContactState;
use crate::record::{IncrementRecord, IterationRecord, Observer, ObserverError, RunInfo, StepView};
use serde::{Deserialize, Serialize};

/// A crossing of a contact point from one master segment to the next.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CrossingJump {
    pub increment: usize,
    pub t: f64,
    /// Monitored displacement at that increment (`t` when the scene has no monitor).
    pub x: f64,
    pub pair: usize,
    /// Trial traction on the old segment extended, and after the transfer.
    pub trial_before: f64,
    pub trial_after: f64,
}

/// A contact pair that had closed points and then had none.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ContactLoss {
    pub pair: String,
    pub increment: usize,
    pub t: f64,
}

/// What a run produced, beyond its recording (small: a few numbers per increment).
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct RunData {
    /// `[t, displacement, force]` of the monitor at each converged increment (empty when the
    /// scene has no monitor).
    pub curve: Vec<[f64; 3]>,
    pub crossings: Vec<CrossingJump>,
    /// `[x, normal force]` of every contact point with a position at the last converged
    /// increment: `x` of a slave node at rest (the reference configuration, where
    /// small-strain analytic solutions are stated), of a rigid slave where it is.
    pub final_contact: Vec<[f64; 2]>,
    /// `[x, y, normal force]` of every node-to-surface point (3D) at the last converged
    /// increment, its slave node at rest.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub final_surface_contact: Vec<[f64; 3]>,
    /// Sum of the reactions `[x, y]` at the last converged increment.
    pub final_reaction: [f64; 2],
    pub contact_lost: Vec<ContactLoss>,
}

/// Counts and data gathered while a run goes.
#[derive(Debug, Default)]
pub struct Collector {
    pub data: RunData,
    pub increments: usize,
    pub newton_iterations: usize,
    pub cutbacks: usize,
    pub last_t: f64,
    pub evidence: FailureEvidence,
    attempt: (usize, usize),
    pair_names: Vec<String>,
    /// Per pair: has had a closed point; is already recorded as lost.
    pair_state: Vec<(bool, bool)>,
}

impl Collector {
    /// The last increment's contact points where a slave node sits at rest (small-strain
    /// analytic references are in the reference configuration), a rigid slave where it is.
    fn final_contact(&mut self, view: &StepView) {
        let plane = view.model.plane();
        let at_rest = |p: &crate::record::ContactPointRecord| {
            let slave = plane.contacts.get(p.pair).and_then(|c| c.slaves.get(p.slave));
            match slave {
                Some(crate::model::Slave::Node(n)) => plane.nodes[*n][0],
                _ => p.position[0],
            }
        };
        self.data.final_contact = (view.contact.iter())
            .map(|p| [at_rest(p), p.normal_force])
            .filter(|v| v.iter().all(|x| x.is_finite()))
            .collect();
        let nodes = match view.model {
            crate::model::ModelRef::Solid(m) => Some(&m.nodes),
            crate::model::ModelRef::Plane(_) => None,
        };
        self.data.final_surface_contact = (view.surface.iter())
            .filter_map(|p| nodes.and_then(|n| n.get(p.node)).map(|x| [x[0], x[1], p.normal_force]))
            .filter(|v| v.iter().all(|x| x.is_finite()))
            .collect();
    }
}

impl Observer for Collector {
    fn start(&mut self, model: crate::model::ModelRef<'_>, _info: &RunInfo) -> Result<(), ObserverError> {
        let model = model.plane();
        self.pair_names = model.contacts.iter().map(|c| c.name.clone()).collect();
        self.pair_state = vec![(false, false); model.contacts.len()];
        Ok(())
    }

    fn iteration(&mut self, rec: &IterationRecord) -> Result<(), ObserverError> {
        if (rec.increment, rec.attempt) != self.attempt {
            self.attempt = (rec.increment, rec.attempt);
            self.evidence.active_set_changes.clear();
        }
        self.evidence.active_set_changes.push(rec.active_set_changes);
        Ok(())
    }

    fn increment(&mut self, rec: &IncrementRecord, view: &StepView) -> Result<(), ObserverError> {
        self.increments = rec.increment;
        self.newton_iterations += rec.iterations;
        self.cutbacks += rec.cutbacks;
        self.last_t = rec.t;
        self.evidence.active_set_changes.clear();
        let x = rec.monitor.as_ref().map_or(rec.t, |m| m.displacement);
        if let Some(m) = &rec.monitor {
            self.data.curve.push([rec.t, m.displacement, m.force]);
        }
        self.data.crossings.extend(view.crossings.iter().map(|c| CrossingJump {
            increment: rec.increment,
            t: rec.t,
            x,
            pair: c.pair,
            trial_before: c.trial_before,
            trial_after: c.trial_after,
        }));
        // a point without a position (a rigid vertex open on its face: NaN) is left out, so
        // that the run record holds finite numbers only (JSON has no NaN: it would be written
        // as null and the record would not read back)
        self.final_contact(view);
        self.data.final_reaction = rec.reaction_total;
        let mut closed = vec![false; self.pair_state.len()];
        for p in view.contact {
            if p.state != ContactState::Open {
                if let Some(c) = closed.get_mut(p.pair) {
                    *c = true;
                }
            }
        }
        for (i, (ever, lost)) in self.pair_state.iter_mut().enumerate() {
            if closed[i] {
                *ever = true;
            } else if *ever && !*lost {
                *lost = true;
                self.data.contact_lost.push(ContactLoss {
                    pair: self.pair_names[i].clone(),
                    increment: rec.increment,
                    t: rec.t,
                });
            }
        }
        Ok(())
    }
}
