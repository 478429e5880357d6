//! The Uzawa loop of augmented-Lagrangian pairs around Newton's solve of one increment (see
//! [`crate::contact::augmented`]): solve, update the multipliers at the converged iterate,
//! solve again from there, until every augmented pair's multipliers change by at most its
//! tolerance — or fail the increment when a pair still has not converged after its cap on
//! updates (the stepping driver then cuts the step back like any failed increment).

use super::newton::{solve_increment, Converged, IncrementTarget, NewtonFailure, Workspace};
use super::state::TrialState;
use crate::assembly::Assembler;
use crate::model::{Enforcement, Model};
use crate::record::IterationRecord;
use crate::settings::NewtonSettings;

/// Solve the increment at `target` (arguments as [`solve_increment`]) and, when the model
/// has augmented pairs, repeat it with updated multipliers until they converge. The
/// iteration records of the repeated solves continue the numbering of the first; the
/// returned [`Converged`] sums the iterations and joins the residual histories
/// (`augmentations`: the number of updates made).
pub fn solve_augmented<S: crate::model::Dim>(
    model: &Model<S>,
    settings: &NewtonSettings,
    asm: &mut Assembler<S>,
    state: &mut TrialState,
    target: IncrementTarget,
    record: &mut dyn FnMut(IterationRecord) -> bool,
    ws: &mut Workspace,
) -> Result<Converged, NewtonFailure> {
    let mut conv = solve_increment(model, settings, asm, state, target, record, ws)?;
    let augmented = |p: &crate::model::ContactPair| matches!(p.enforcement, Enforcement::Augmented { .. });
    if !model.contacts.iter().any(augmented) {
        return Ok(conv);
    }
    loop {
        let changes = state.contact.augment(model.plane(), false);
        let open: Vec<_> = changes.iter().filter(|c| !c.converged()).collect();
        if open.is_empty() {
            return Ok(conv);
        }
        if let Some(c) = open.iter().find(|c| conv.augmentations >= c.max) {
            return Err(NewtonFailure::Augmentation {
                pair: model.contacts[c.pair].name.clone(),
                updates: conv.augmentations,
                relative: c.relative(),
                tol: c.tol,
            });
        }
        state.contact.augment(model.plane(), true);
        conv.augmentations += 1;
        let offset = conv.iterations;
        let mut renumbered = |mut r: IterationRecord| {
            r.iteration += offset;
            record(r)
        };
        let again = IncrementTarget {
            reference_floor: target.reference_floor.max(conv.reference),
            predicted: false,
            ..target
        };
        let next = solve_increment(model, settings, asm, state, again, &mut renumbered, ws)?;
        conv.iterations += next.iterations;
        conv.residuals.extend(next.residuals);
        conv.reference = conv.reference.max(next.reference);
        conv.line_search_failures += next.line_search_failures;
        conv.front_iterations += next.front_iterations;
        conv.accepted_by = next.accepted_by;
    }
}
