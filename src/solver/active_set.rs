//! Watching the contact active set across the Newton iterations of one attempt at an
//! increment: which points change state (open/stick/slip) or segment, when to hold a
//! chattering point fixed, and who to name when the attempt fails.
//!
//! Remedy (the standard one of implicit contact codes, e.g. Wriggers, Computational Contact
//! Mechanics (2006) §5.3 and the "chattering" controls of commercial codes): a point whose
//! decision changed `freeze_after` times within the attempt is *frozen* — its segment and
//! its open/closed decision are held for the rest of the attempt (the kernel keeps the
//! penalty active or inactive). Stick or slip stays the return mapping's, which is
//! continuous in the trial traction: holding the slip branch made the traction jump by
//! `2 μ N` when the trial reversed along a Newton step, and the residual had no zero. When Newton converges with frozen points,
//! they are released and the residual is evaluated again with every point free to choose;
//! the increment is accepted only if that residual still meets the tolerance (the frozen
//! state was the consistent one, to tolerance). Otherwise the attempt continues without
//! freezing and, failing that, the step is cut back. (Updating the frozen decisions from the
//! failed verification instead, a primal–dual active-set round, was tried: on the 120×4
//! strip at rest on the block it cycled between two active sets at the lift-off point.)

use crate::contact::law::ContactState;
use crate::contact::system::{ContactSystem, Decision};
use crate::record::{ChangingPoint, PointDecision};

/// How many past iterates of each point are kept for the failure report.
const KEEP: usize = 6;

/// Active-set history of one attempt.
#[derive(Debug, Default)]
pub struct ActiveSetWatch {
    now: Vec<Decision>,
    before: Vec<Decision>,
    changes: Vec<u32>,
    first_change: Vec<usize>,
    last_change: Vec<usize>,
    last_closed: Vec<Option<Decision>>,
    /// The last `KEEP` decision vectors (ring buffer) and how many are filled.
    ring: Vec<Vec<Decision>>,
    filled: usize,
    iteration: usize,
}

impl ActiveSetWatch {
    /// Start watching at the first iterate of an attempt.
    pub fn start(&mut self, contact: &ContactSystem) {
        contact.signature_into(&mut self.now);
        let n = self.now.len();
        self.before.clone_from(&self.now);
        self.changes.clear();
        self.changes.resize(n, 0);
        for v in [&mut self.first_change, &mut self.last_change] {
            v.clear();
            v.resize(n, 0);
        }
        self.last_closed.clear();
        self.last_closed.resize(n, None);
        self.ring.resize_with(KEEP, Vec::new);
        self.filled = 0;
        self.iteration = 0;
        self.push();
    }

    fn push(&mut self) {
        let slot = self.filled % KEEP;
        self.ring[slot].clone_from(&self.now);
        self.filled += 1;
        for (c, d) in self.last_closed.iter_mut().zip(&self.now) {
            if d.state != ContactState::Open {
                *c = Some(*d);
            }
        }
    }

    /// Record the decisions after Newton iteration `iteration` (1-based); returns how many
    /// points changed.
    pub fn observe(&mut self, contact: &ContactSystem, iteration: usize) -> usize {
        std::mem::swap(&mut self.before, &mut self.now);
        contact.signature_into(&mut self.now);
        self.iteration = iteration;
        let mut changed = 0;
        for i in 0..self.now.len() {
            if self.now[i] != self.before[i] {
                changed += 1;
                if self.changes[i] == 0 {
                    self.first_change[i] = iteration;
                }
                self.changes[i] += 1;
                self.last_change[i] = iteration;
            }
        }
        self.push();
        changed
    }

    /// Freeze every point that changed at least `after` times and is not frozen yet (held
    /// at its last closed decision when it is open now); returns how many were frozen.
    pub fn freeze_chattering(&mut self, contact: &mut ContactSystem, after: u32, frozen: &mut [bool]) -> usize {
        let mut n = 0;
        for (i, held) in frozen.iter_mut().enumerate().take(self.now.len()) {
            if after > 0 && self.changes[i] >= after && !*held {
                let hold = match self.now[i].state {
                    ContactState::Open => self.last_closed[i].unwrap_or(self.now[i]),
                    _ => self.now[i],
                };
                contact.freeze(i, hold);
                *held = true;
                n += 1;
            }
        }
        n
    }

    /// Whether some point changed within the last `window` iterations.
    pub fn cycling(&self, window: usize) -> bool {
        self.last_change
            .iter()
            .zip(&self.changes)
            .any(|(&l, &c)| c > 0 && l + window > self.iteration)
    }

    /// The points that changed in this attempt, those still changing at the end first, then
    /// the most changes (at most `max`): the points to blame are the ones that never settled.
    pub fn report(&self, contact: &ContactSystem, model: &crate::model::Model, max: usize) -> Vec<ChangingPoint> {
        let mut idx: Vec<usize> = (0..self.now.len()).filter(|&i| self.changes[i] > 0).collect();
        idx.sort_by_key(|&i| {
            (
                std::cmp::Reverse(self.last_change[i]),
                std::cmp::Reverse(self.changes[i]),
            )
        });
        idx.truncate(max);
        let kept = self.filled.min(KEEP);
        idx.into_iter()
            .map(|i| {
                let (ip, is) = contact.point_index(i);
                let pair = &model.contacts[ip];
                let history = (self.filled - kept..self.filled)
                    .map(|k| {
                        let d = self.ring[k % KEEP][i];
                        PointDecision {
                            state: d.state,
                            segment: d.segment,
                        }
                    })
                    .collect();
                ChangingPoint {
                    pair: ip,
                    pair_name: pair.name.clone(),
                    slave: is,
                    slave_label: model.slave_label(pair.slaves[is]),
                    changes: self.changes[i],
                    first_change: self.first_change[i],
                    history,
                    xi: contact.xi(i),
                }
            })
            .collect()
    }
}

/// Points that were closed at the last converged increment, are found open at the first
/// iterate of a *predicted* start and are still paired with a segment: hold them closed on
/// that segment (the kernel's penalty stays on, pulling where the gap opened) for the first
/// correction only; their indices go into `held`, the count is returned.
///
/// Why: the secant predictor moves every node along its last increment, so where the strip
/// wraps the sharp corner C the extrapolated face is the chord past C, and C comes out
/// open by a little more than its penetration. The tangent without C's penalty leaves the
/// strip free to swing about its last support: on the 120×4 strip-channel the first
/// correction was ≈ 8 units long, the slope line search cut it to `s = 0.001` (8
/// assemblies) and the next residual was 1e3 — in 302 of 1 200 increments. The predicted
/// lift-off is an artefact of the extrapolation: with the last converged active set the
/// first correction is a good one, and the decisions are free again from the second
/// iterate on (a real lift-off then opens there).
pub fn hold_predicted_lift_offs(contact: &mut ContactSystem, held: &mut Vec<usize>) -> usize {
    held.clear();
    let points = contact.committed.iter().flatten().zip(contact.current.iter().flatten());
    for (flat, (was, now)) in points.enumerate() {
        let located_open = now.eval.is_some_and(|e| e.state == ContactState::Open);
        if was.closed && located_open && now.segment.is_some() {
            held.push(flat);
        }
    }
    for &flat in held.iter() {
        let (ip, is) = contact.point_index(flat);
        let hold = Decision {
            state: ContactState::Stick,
            segment: contact.current[ip][is].segment,
        };
        contact.freeze(flat, hold);
    }
    held.len()
}
