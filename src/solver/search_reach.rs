//! The step a contact search can follow: a rigid body may not move farther in one step than
//! the search radius of the pairs it belongs to.

use super::newton::NewtonFailure;
use crate::model::{ContactPair, Master, Model, Slave};

/// Samples of a step at which a rigid body's travel is measured (its motion is piecewise
/// linear in `t`: the largest distance from the start is at a sample or the step's end
/// where the step spans at most this many pieces).
const TRAVEL_SAMPLES: usize = 16;

/// The first rigid body of a contact pair that would move farther than the pair's search
/// radius between `t` and `t_new` (largest distance from its position at `t`).
///
/// The rule of the contact search (a search radius bounds what one step may bring into
/// contact): a point out of reach at the converged state is untracked, and the search finds
/// it again only within the radius of the master's segments. A rigid body driven farther
/// than that in one step can carry its outline over untracked points, or its points deep
/// into a body, with nothing found — a run that completes with the points inside and no
/// force (measured: a rigid point driven 0.47 in one step, 0.07 into a plate of radius
/// 0.05, completed with zero force). Such a step is cut back.
pub fn rigid_step_beyond_search(model: &Model, t: f64, t_new: f64) -> Option<NewtonFailure> {
    for pair in &model.contacts {
        for r in pair_rigid_bodies(pair) {
            let body = &model.rigid[r];
            let start = body.offset(t);
            let travel = (1..=TRAVEL_SAMPLES)
                .map(|k| {
                    let o = body.offset(t + (t_new - t) * k as f64 / TRAVEL_SAMPLES as f64);
                    (o[0] - start[0]).hypot(o[1] - start[1])
                })
                .fold(0.0, f64::max);
            if travel > pair.search_radius {
                return Some(NewtonFailure::StepBeyondSearch {
                    body: body.name.clone(),
                    pair: pair.name.clone(),
                    travel,
                    radius: pair.search_radius,
                });
            }
        }
    }
    None
}

/// The rigid bodies a pair involves: its rigid master, or the body of its rigid slaves.
fn pair_rigid_bodies(pair: &ContactPair) -> Vec<usize> {
    let mut bodies: Vec<usize> = pair
        .slaves
        .iter()
        .filter_map(|s| match s {
            Slave::RigidPoint(b) | Slave::RigidVertex(b, _) => Some(*b),
            Slave::Node(_) => None,
        })
        .collect();
    if let Master::Rigid { body, .. } = pair.master {
        bodies.push(body);
    }
    bodies.sort_unstable();
    bodies.dedup();
    bodies
}
