//! Watching the contact active set across the Newton iterations of one attempt at an
//! increment: which points change state (open/stick/slip) or segment, whether the set is
//! still changing when the attempt ends (a cycle), and who to name when it fails. The
//! watch decides nothing: the states are the complementarity functions' (see
//! [`crate::contact::decision`]).

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
    /// Hashes of the decision patterns met in this attempt, and whether the last one
    /// observed was new.
    seen: std::collections::HashSet<u64>,
    last_new: bool,
}

/// A hash of a pattern of decisions (the points' states and segments, in order).
fn pattern_hash(decisions: &[Decision]) -> u64 {
    use std::hash::{Hash, Hasher};
    let mut h = std::collections::hash_map::DefaultHasher::new();
    for d in decisions {
        d.state.code().hash(&mut h);
        d.segment.hash(&mut h);
    }
    h.finish()
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
        self.seen.clear();
        self.seen.insert(pattern_hash(&self.now));
        self.last_new = false;
        self.push();
    }

    /// Whether the pattern of decisions last observed had not been met before in the
    /// attempt (a cycle meets its patterns again; a moving contact front does not).
    pub fn new_pattern(&self) -> bool {
        self.last_new
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
        self.last_new = self.seen.insert(pattern_hash(&self.now));
        self.push();
        changed
    }

    /// Whether some point changed within the last `window` iterations.
    pub fn cycling(&self, window: usize) -> bool {
        self.last_change
            .iter()
            .zip(&self.changes)
            .any(|(&l, &c)| c > 0 && l + window > self.iteration)
    }

    /// How many points, 2D and 3D, changed state or segment in this attempt.
    pub fn changed_points(&self) -> usize {
        self.changes.iter().filter(|&&c| c > 0).count()
    }

    /// The points that changed in this attempt, those still changing at the end first, then
    /// the most changes (at most `max`): the points to blame are the ones that never settled.
    /// 2D points are named from `model`, 3D ones (after the 2D ones in the watch) from
    /// `solid`.
    pub fn report(
        &self,
        contact: &ContactSystem,
        model: &crate::model::Model,
        solid: Option<&crate::model::Model<crate::model::Solid>>,
        max: usize,
    ) -> Vec<ChangingPoint> {
        let plane = contact.plane_len().min(self.now.len());
        let mut idx: Vec<usize> = (0..self.now.len()).filter(|&i| self.changes[i] > 0).collect();
        idx.sort_by_key(|&i| {
            (
                std::cmp::Reverse(self.last_change[i]),
                std::cmp::Reverse(self.changes[i]),
            )
        });
        idx.truncate(max);
        let kept = self.filled.min(KEEP);
        let history = |i: usize| -> Vec<PointDecision> {
            (self.filled - kept..self.filled)
                .map(|k| {
                    let d = self.ring[k % KEEP][i];
                    PointDecision {
                        state: d.state,
                        segment: d.segment,
                    }
                })
                .collect()
        };
        idx.into_iter()
            .filter_map(|i| {
                let named = match i < plane {
                    true => plane_point(contact, model, i),
                    false => surface_point(contact, solid?, i - plane)?,
                };
                Some(ChangingPoint {
                    changes: self.changes[i],
                    first_change: self.first_change[i],
                    history: history(i),
                    ..named
                })
            })
            .collect()
    }
}

/// A 2D point's names and `ξ` (its changes and history filled in by the caller).
fn plane_point(contact: &ContactSystem, model: &crate::model::Model, flat: usize) -> ChangingPoint {
    let (ip, is) = contact.point_index(flat);
    let pair = &model.contacts[ip];
    ChangingPoint {
        pair: ip,
        pair_name: pair.name.clone(),
        slave: is,
        slave_label: model.slave_label(pair.slaves[is]),
        changes: 0,
        first_change: 0,
        history: Vec::new(),
        xi: contact.xi(flat),
        surface: false,
        xi2: f64::NAN,
    }
}

/// A 3D point's names and `(ξ¹, ξ²)` (`None` if the watch holds more points than the model).
fn surface_point(
    contact: &ContactSystem,
    solid: &crate::model::Model<crate::model::Solid>,
    flat: usize,
) -> Option<ChangingPoint> {
    let (ip, is) = contact.surface.point_index(flat)?;
    let pair = solid.surface_contacts.get(ip)?;
    let xi = contact.surface.xi(ip, is);
    Some(ChangingPoint {
        pair: ip,
        pair_name: pair.name.clone(),
        slave: is,
        slave_label: format!("node {}", pair.slaves[is]),
        changes: 0,
        first_change: 0,
        history: Vec::new(),
        xi: xi.map_or(f64::NAN, |x| x[0]),
        surface: true,
        xi2: xi.map_or(f64::NAN, |x| x[1]),
    })
}
