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

use super::newton::{apply, assemble_at, inadmissible, NewtonFailure, Workspace};
use super::state::TrialState;
use crate::assembly::Assembler;
use crate::contact::law::ContactState;
use crate::contact::system::{ContactSystem, Decision};
use crate::model::Model;
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

/// What the first correction of an attempt holds (its indices go into `held`; the count
/// is returned). From the second iterate on every point decides for itself again, so the
/// converged state is the same; only the first correction's tangent changes.
///
/// 1. **Predicted lift-offs** (only at a `predicted` start): points closed at the last
///    converged increment, found open at the first iterate and still paired with a segment,
///    are held closed on that segment (the kernel's penalty stays on, pulling where the gap
///    opened). The secant predictor moves every node along its last increment, so where the
///    strip wraps the sharp corner C the extrapolated face is the chord past C, and C comes
///    out open by a little more than its penetration. The tangent without C's penalty leaves
///    the strip free to swing about its last support: on the 120×4 strip-channel the first
///    correction was ≈ 8 units long, the slope line search cut it to `s = 0.001` (8
///    assemblies) and the next residual was 1e3 — in 302 of 1 200 increments.
/// 2. **Touching points pushed in** (`pushed_in`, see [`touching_points`]): points at zero
///    gap that a first correction with them open moves into the master are held closed.
/// 3. **Stick as the elastic predictor** of friction: frictional points closed at the last
///    converged increment and closed (or held closed) now are held in stick, returning their
///    trial traction with the stick tangent — those that stuck at the last converged
///    increment, the touching points pushed in (a body coming to rest on them: without
///    their stick stiffness a block on an incline would slide freely in its first
///    correction, and the tangent is singular), and in an attempt that `retry`s an
///    increment after a failed one, the slipping ones too (the increment in which points under a tool reverse their slip:
///    a die that stops pressing and starts dragging). At the
///    first iterate the rigid bodies and prescribed nodes have moved but the body has not
///    followed yet, so with a tangential penalty far stiffer than the body (`ε_T` = 100 E
///    per node) the trial traction of a point that will stick is already past the Coulomb
///    cone: taken as slip, the point has no tangential stiffness, the first correction
///    moves the body surface by the slip forces over the body's stiffness — hundreds of
///    times the elastic slip `μN/ε_T` — every trial reverses, and Newton cycles between
///    the two slip directions (the onset of sliding under a flat punch, or a die starting to
///    iron, failed at every step down to Δt/1024). With stick held, the first correction is
///    the body's elastic response to the motion; the return mapping then finds the slipping
///    points from a body that has moved (the elastic predictor / plastic corrector of return
///    mapping, taken to the global iteration).
pub fn hold_first_correction(
    contact: &mut ContactSystem,
    model: &Model,
    (predicted, retry): (bool, bool),
    pushed_in: &[usize],
    held: &mut Vec<usize>,
) -> usize {
    held.clear();
    held.extend_from_slice(pushed_in);
    let mut stick = Vec::new();
    let mut flat = 0;
    for (ip, pair) in model.contacts.iter().enumerate() {
        for is in 0..pair.slaves.len() {
            let (was, now) = (&contact.committed[ip][is], &contact.current[ip][is]);
            let state = now.eval.map(|e| e.state);
            let lift_off = predicted && was.closed && state == Some(ContactState::Open) && now.segment.is_some();
            if lift_off {
                held.push(flat);
            }
            let closed = lift_off || pushed_in.contains(&flat) || state.is_some_and(|s| s != ContactState::Open);
            let resting = pushed_in.contains(&flat);
            if pair.law.mu > 0.0 && closed && ((was.closed && (was.stuck || retry)) || resting) {
                stick.push(flat);
            }
            flat += 1;
        }
    }
    for &f in held.iter() {
        let (ip, is) = contact.point_index(f);
        let hold = Decision {
            state: ContactState::Stick,
            segment: contact.current[ip][is].segment,
        };
        contact.freeze(f, hold);
    }
    for &f in &stick {
        contact.hold_stick(f);
    }
    held.extend(stick);
    held.sort_unstable();
    held.dedup();
    held.len()
}

/// The points that touch their master to round-off and are open at the current iterate
/// (flat indices; [`crate::contact::point::touching`]): a zero-gap start. Whether the first
/// correction sees them closed depends on where the motion takes them: two blocks meshed
/// against each other and pressed together must see the contact at once (open, the first
/// correction moves the top block through the base and Newton thrashes), a sheet lying on a
/// facet and pulled along it must not (held closed with the penalty's stiffness, it can only
/// lift off one point per iteration: the clamp's force couple at the edge of the held set).
/// The solver probes: a correction with them open, and those it pushes in are held closed
/// for the real first correction (`solver::newton`, `touching_pushed_in`).
pub fn touching_points(contact: &ContactSystem) -> Vec<usize> {
    contact
        .current
        .iter()
        .flatten()
        .enumerate()
        .filter(|(_, p)| {
            p.eval.is_some_and(|e| {
                e.state == ContactState::Open && crate::contact::point::touching(e.proj.gap, e.proj.a11)
            })
        })
        .map(|(flat, _)| flat)
        .collect()
}

/// The touching points (see [`touching_points`]) that a first correction with them open
/// pushes into their master: one linear solve and one residual assembly at the trial, then
/// the first iterate is assembled again (nothing is done when no point touches). When the
/// tangent with them open is singular, all of them (the body rests on them).
pub(super) fn touching_pushed_in(
    model: &Model,
    asm: &mut Assembler,
    state: &mut TrialState,
    t: f64,
    ws: &mut Workspace,
) -> Result<Vec<usize>, NewtonFailure> {
    let touching = touching_points(&state.contact);
    if touching.is_empty() {
        return Ok(touching);
    }
    asm.free_residual(&mut ws.r);
    for (d, ri) in ws.du.iter_mut().zip(&ws.r) {
        *d = -ri;
    }
    // with the touching points open the tangent is singular (a zero pivot, or a correction
    // that moves nodes farther than the model is large): a body held by nothing but the
    // contacts it rests on, a block on a floor under its weight. It rests on them, so they
    // are held closed for the first correction
    let size = super::tangent_check::model_size(model);
    if asm.solve(&mut ws.du).is_err() || ws.du.iter().any(|d| d.is_nan() || d.abs() > size) {
        return Ok(touching);
    }
    // the probe only asks which way the correction moves the touching points; a correction
    // whose end is inadmissible (it carries points through their master, or inverts an
    // element) moves an unsupported body: it rests on them
    let alphas = state.alphas.clone();
    apply(&mut state.u, &asm.dofs.eq, &ws.du, 1.0);
    let pushed: Vec<usize> = match assemble_at(model, asm, state, t, false) {
        Ok(()) => {
            let closed = |flat: &usize| {
                let (ip, is) = state.contact.point_index(*flat);
                state.contact.current[ip][is]
                    .eval
                    .is_some_and(|e| e.state != ContactState::Open)
            };
            touching.into_iter().filter(closed).collect()
        }
        Err(f) if inadmissible(&f) => touching,
        Err(e) => return Err(e),
    };
    apply(&mut state.u, &asm.dofs.eq, &ws.du, -1.0);
    state.alphas.copy_from_slice(&alphas);
    assemble_at(model, asm, state, t, true)?;
    Ok(pushed)
}
