//! Committing a converged increment: the records of the converged iterate, the contact
//! history committed (crossings, history jumps, lost histories), the checks of a converged
//! state (penetration, each body's equilibrium, the elements' stability) and the records
//! handed to the observer.

use super::*;

/// The warning for elements that lost stability: how many, the first five, and the remedy.
fn unstable_warning<S: Dim>(model: &Model<S>, unstable: &[crate::solver::element_check::UnstableElement]) -> String {
    let names: Vec<String> = unstable.iter().take(5).map(|e| e.element.to_string()).collect();
    let safe = unstable
        .iter()
        .all(|e| S::holds_hourglass(&model.bodies[model.elements[e.element].body].kind));
    let safe_kind = if S::D == 3 { "hex8-eas-safe" } else { "q4-eas-safe" };
    let remedy = if safe {
        format!("the elements are already `{safe_kind}`: they are deformed beyond what one element resolves (refine the mesh where they are)")
    } else {
        format!("the element kind `{safe_kind}` does not hourglass in compression")
    };
    format!(
        "{} elements have lost stability (their tangent is not positive definite in a deformation mode: an hourglass pattern; the answer may be wrong): elements {}{}; {remedy}",
        unstable.len(),
        names.join(", "),
        if unstable.len() > 5 { ", …" } else { "" }
    )
}

/// Check the elements at a converged increment; log a warning when the unstable set changes
/// in size (the first time too), and keep the run's account.
fn check_elements<S: Dim>(
    model: &Model<S>,
    asm: &Assembler<S>,
    state: &TrialState,
    (increment, t): (usize, f64),
    last_count: &mut usize,
    summary: &mut RunSummary,
    obs: &mut dyn Observer,
) -> Result<(), ObserverError> {
    let unstable = match crate::solver::element_check::unstable_elements(model, asm, &state.u, &state.alphas) {
        Ok(unstable) => unstable,
        Err(e) => {
            // the state converged, but an element's tangent could not be evaluated for the
            // check: said once, counted in the summary
            summary.element_check_errors += 1;
            if summary.element_check_errors == 1 {
                let message =
                    format!("the elements' stability could not be checked at this converged increment: {e}; not checked where this recurs");
                log(obs, LogLevel::Warning, increment, t, message)?;
            }
            return Ok(());
        }
    };
    if unstable.len() != *last_count && !unstable.is_empty() {
        log(obs, LogLevel::Warning, increment, t, unstable_warning(model, &unstable))?;
    }
    *last_count = unstable.len();
    if let Some(worst) = unstable.first() {
        let s = summary.unstable_elements.get_or_insert(UnstableSummary {
            first_increment: increment,
            most: 0,
            worst_element: worst.element,
            worst_ratio: worst.ratio,
        });
        s.most = s.most.max(unstable.len());
        if worst.ratio < s.worst_ratio {
            (s.worst_element, s.worst_ratio) = (worst.element, worst.ratio);
        }
    }
    Ok(())
}

/// What committing the contact history of a converged increment gives the records.
pub(super) struct ContactCommit {
    points: Vec<ContactPointRecord>,
    monitors: Vec<MonitorRecord>,
    crossings: Vec<CrossingRecord>,
    imbalance: Option<Imbalance>,
    /// The time the commit itself took (physics, not recording).
    commit_time: std::time::Duration,
    /// The 3D contact points, how many crossed to another facet and the trial tractions of
    /// those a scheme other than the parallel translation carried.
    surface_points: Vec<SurfacePointRecord>,
    surface: crate::contact3d::system::SurfaceCommit,
}

impl<S: Dim> Stepping<'_, S> {
    /// Add what Newton's method did in a converged increment to the run's summary.
    fn count_newton(&mut self, conv: &Converged, on_extension: usize) {
        let s = &mut self.summary;
        s.newton_iterations += conv.iterations;
        s.augmentations += conv.augmentations;
        s.on_extension += usize::from(on_extension > 0);
        s.line_search_failures += conv.line_search_failures;
        s.stabilised_corrections += conv.stabilised;
        s.stabilisation_work += conv.stabilisation_work;
        s.front_iterations += conv.front_iterations;
    }

    /// Make the converged increment the committed state: records of the converged iterate
    /// (compared with the previous increment), the contact history committed, the records
    /// handed to `obs`, the elements checked.
    pub(super) fn commit(
        &mut self,
        done: ConvergedIncrement,
        t_inc: Instant,
        obs: &mut dyn Observer,
    ) -> Result<(), SolveError> {
        for ((d, a), b) in self.last_du.iter_mut().zip(&done.state.u).zip(&self.committed.u) {
            *d = a - b;
        }
        self.last_dt = Some(done.t_new - self.t);
        self.committed = done.state;
        let t_prev = self.t;
        self.t = done.t_new;
        self.fref = self.fref.max(done.conv.reference);
        self.count_newton(&done.conv, done.on_extension);
        let handed = Instant::now();
        let ContactCommit {
            points,
            monitors,
            crossings,
            imbalance,
            commit_time,
            surface_points,
            surface,
        } = self.commit_contact();
        self.check_equilibrium(imbalance)?;
        self.check_penetration(&points, &surface_points, obs)?;
        self.summary.crossings += crossings.len() + surface.crossings;
        self.report_history_jumps(&crossings, obs)?;
        self.report_surface_history_jumps(&surface.trials, obs)?;
        self.report_lost_histories(&surface_points, obs)?;
        let equilibrium = imbalance.map_or(0.0, |i| i.relative);
        let (conv, cutbacks, on_extension) = (done.conv, done.cutbacks, done.on_extension);
        let inertia = conv.inertia;
        let rec = self.increment_record((conv, cutbacks, on_extension), t_prev, t_inc, monitors, equilibrium);
        self.summary.monitor = rec.monitor.clone();
        self.summary.monitors = rec.monitors.clone();
        let view = StepView {
            model: self.model.view(),
            u: &self.committed.u,
            contact: &points,
            crossings: &crossings,
            surface: &surface_points,
        };
        obs.increment(&rec, &view)?;
        self.recording += handed.elapsed().saturating_sub(commit_time);
        let at = (self.increment, self.t);
        check_elements(
            self.model,
            &self.asm,
            &self.committed,
            at,
            &mut self.unstable_count,
            &mut self.summary,
            obs,
        )?;
        self.tangent.converged();
        if let Some(inertia) = inertia {
            self.watch_tangent(inertia, obs)?;
        }
        self.asm.update_hourglass_holds(self.model, &self.committed.u);
        self.summary.increments = self.increment;
        Ok(())
    }

    /// Take the converged increment's tangent definiteness: a warning when it is lost (or
    /// changes while lost), a note when it returns ([`super::stability`]).
    fn watch_tangent(
        &mut self,
        inertia: crate::linalg::inertia::Inertia,
        obs: &mut dyn Observer,
    ) -> Result<(), ObserverError> {
        use crate::solver::stability::StabilityChange;
        let change = self.tangent.observe(self.increment, self.t, inertia);
        self.summary.instability = self.tangent.first;
        match change {
            Some(StabilityChange::Lost(m)) => log(obs, LogLevel::Warning, self.increment, self.t, m),
            Some(StabilityChange::Regained(m)) => log(obs, LogLevel::Info, self.increment, self.t, m),
            None => Ok(()),
        }
    }

    /// The record of the increment just committed (at `self.t`, from `t_prev`): its Newton
    /// outcome, cut-backs and points on a segment's extension.
    fn increment_record(
        &self,
        (conv, cutbacks, on_extension): (Converged, usize, usize),
        t_prev: f64,
        t_inc: Instant,
        monitors: Vec<MonitorRecord>,
        equilibrium: f64,
    ) -> IncrementRecord {
        let (reaction_total, reaction_z) = self.reaction_total();
        IncrementRecord {
            increment: self.increment,
            t: self.t,
            dt: self.t - t_prev,
            iterations: conv.iterations,
            cutbacks,
            converged: true,
            wall_time_s: t_inc.elapsed().as_secs_f64(),
            residuals: conv.residuals,
            monitor: monitors.first().cloned(),
            monitors,
            reaction_total,
            reaction_z,
            accepted_by: conv.accepted_by.as_str().into(),
            line_search_failures: conv.line_search_failures,
            stabilised_corrections: conv.stabilised,
            stabilisation_work: conv.stabilisation_work,
            on_extension,
            front_iterations: conv.front_iterations,
            equilibrium,
            tangent: conv.inertia.map(crate::record::TangentRecord::of),
        }
    }

    /// The contact records, monitors and equilibrium check of the converged iterate (they
    /// compare it with the previous increment, so they come first), then the contact
    /// history committed and its crossings.
    fn commit_contact(&mut self) -> ContactCommit {
        let cfg = Config {
            model: self.model.plane(),
            u: &self.committed.u,
            t: self.t,
        };
        let snapshots = self.committed.contact.snapshots(&cfg);
        let points: Vec<ContactPointRecord> = (snapshots.iter())
            .map(|p| ContactPointRecord::from_snapshot(&self.labels, p))
            .collect();
        let solid = S::solid(self.model).map(|model| SurfaceConfig {
            model,
            u: &self.committed.u,
            t: self.t,
        });
        let (surface, surface_points) = match &solid {
            Some(c) => {
                let snapshots = self.committed.contact.surface.snapshots(c);
                let records = (snapshots.iter())
                    .map(|p| SurfacePointRecord::of(c.model, &self.committed.u, p))
                    .collect();
                (snapshots, records)
            }
            None => (Vec::new(), Vec::new()),
        };
        let monitors =
            crate::solver::monitor::records(self.model, &self.asm, &self.committed.u, self.t, (&snapshots, &surface));
        let imbalance =
            crate::solver::equilibrium::worst_imbalance(self.model, &self.asm, self.t, &snapshots, &surface, self.fref);
        let committing = Instant::now();
        let events = self.committed.contact.commit(&cfg);
        let surface = self.committed.contact.surface.commit();
        let commit_time = committing.elapsed();
        let crossings: Vec<CrossingRecord> = events.iter().map(CrossingRecord::from).collect();
        ContactCommit {
            points,
            monitors,
            crossings,
            imbalance,
            commit_time,
            surface_points,
            surface,
        }
    }

    /// Count the crossings at which the friction history jumped (see
    /// [`RunSummary::history_jumps`]) and warn at the first one: the run goes on, but its
    /// force history is then not the method's.
    fn report_history_jumps(&mut self, crossings: &[CrossingRecord], obs: &mut dyn Observer) -> Result<(), SolveError> {
        for c in crossings {
            let (before, after) = (c.trial_before, c.trial_after);
            // a point that carried no traction into the crossing has no history to lose
            let carried = before.abs() > 1e-9 * after.abs();
            if !carried || (after - before).abs() <= crate::solver::run::HISTORY_JUMP * before.abs().max(after.abs()) {
                continue;
            }
            self.summary.history_jumps += 1;
            if self.summary.history_jumps == 1 {
                let pair = &self.model.contacts[c.pair];
                let message = format!(
                    "crossing of {} of `{}` from segment {} to {}: the trial traction jumped from {before:.4e} to {after:.4e} — \
                     the `{}` transfer does not carry the friction history across segments, and the force history is wrong from \
                     here on (use transfer = \"continuous\"; seed Fig. 4)",
                    self.model.slave_label(pair.slaves[c.slave]),
                    pair.name,
                    c.from_segment,
                    c.to_segment,
                    pair.transfer.name()
                );
                log(obs, LogLevel::Warning, self.increment, self.t, message)?;
            }
        }
        Ok(())
    }

    /// The 3D crossings at which the pair's scheme changed the friction history: its trial
    /// traction differs from the parallel translation's by more than
    /// [`crate::solver::run::HISTORY_JUMP`] of the larger (counted with the 2D jumps in
    /// [`RunSummary::history_jumps`], warned at the first).
    fn report_surface_history_jumps(
        &mut self,
        trials: &[crate::contact3d::system::SurfaceCrossingTrial],
        obs: &mut dyn Observer,
    ) -> Result<(), SolveError> {
        for c in trials {
            let (translated, carried) = c.trial;
            if (carried - translated).abs() <= crate::solver::run::HISTORY_JUMP * translated.max(carried) {
                continue;
            }
            self.summary.history_jumps += 1;
            if self.summary.history_jumps == 1 {
                let Some(solid) = S::solid(self.model) else { continue };
                let pair = &solid.surface_contacts[c.pair];
                let message = format!(
                    "crossing of node {} of `{}` from facet {} to {}: the trial traction is {carried:.4e} where the parallel \
                     translation of the history gives {translated:.4e} — the `{}` transfer does not carry the friction history \
                     across facets, and the force history is wrong from here on (use transfer = \"continuous\"; seed Fig. 4)",
                    pair.slaves[c.slave],
                    pair.name,
                    c.from_facet,
                    c.to_facet,
                    crate::contact3d::transfer::scheme_name(pair.transfer)
                );
                log(obs, LogLevel::Warning, self.increment, self.t, message)?;
            }
        }
        Ok(())
    }

    /// Warn the first time a converged increment penetrates deeper than
    /// [`crate::solver::penetration::DEEP_PENETRATION`] of the local element size, and keep the
    /// deepest for the run's summary.
    /// Count the 3D points whose friction history could not be carried onto their new facet
    /// (counted with [`RunSummary::history_jumps`]) and warn at the first: the run goes on,
    /// those points starting their friction afresh.
    fn report_lost_histories(
        &mut self,
        points: &[SurfacePointRecord],
        obs: &mut dyn Observer,
    ) -> Result<(), SolveError> {
        for p in points.iter().filter(|p| p.history_lost) {
            self.summary.history_jumps += 1;
            if self.summary.history_jumps == 1 {
                let message = format!(
                    "node {} of `{}` moved from facet {:?} to {:?}: its friction history could not be carried onto the new \
                     facet (the facets fold onto each other, or the old contact point has no projection on it) and starts \
                     afresh — the force history is not the method's from here on",
                    p.node, p.pair_name, p.previous_facet, p.facet
                );
                log(obs, LogLevel::Warning, self.increment, self.t, message)?;
            }
        }
        Ok(())
    }

    fn check_penetration(
        &mut self,
        points: &[ContactPointRecord],
        surface: &[SurfacePointRecord],
        obs: &mut dyn Observer,
    ) -> Result<(), SolveError> {
        use crate::solver::penetration::{deepest, deepest_surface, warning, DEEP_PENETRATION};
        let (plane, solid) = match S::solid(self.model) {
            Some(_) => (None, deepest_surface(&self.node_sizes, surface)),
            None => (deepest(self.model.plane(), &self.node_sizes, points), None),
        };
        let Some(p) = plane.or(solid) else {
            return Ok(());
        };
        if p.ratio <= DEEP_PENETRATION {
            return Ok(());
        }
        let first = self.summary.deep_penetration.is_none();
        if first {
            log(obs, LogLevel::Warning, self.increment, self.t, warning(&p))?;
        }
        if self.summary.deep_penetration.as_ref().is_none_or(|w| p.ratio > w.ratio) {
            self.summary.deep_penetration = Some(p);
        }
        Ok(())
    }

    /// Keep the worst equilibrium imbalance of the run ([`super::equilibrium`]) and stop the
    /// run, saying which body and by how much, when a converged increment is out of
    /// equilibrium: a force was lost between the assembly and the records, and every figure
    /// from here on would be wrong.
    fn check_equilibrium(&mut self, imbalance: Option<Imbalance>) -> Result<(), SolveError> {
        let Some(i) = imbalance else {
            return Ok(());
        };
        if self.summary.equilibrium.is_none_or(|w| i.relative > w) {
            self.summary.equilibrium = Some(i.relative);
        }
        if i.relative <= EQUILIBRIUM_TOLERANCE {
            return Ok(());
        }
        let message = format!(
            "body `{}` is out of equilibrium at the converged increment {}: its loads, reactions and contact forces sum to \
             ({:.4e}, {:.4e}), {:.2e} of the force scale (tolerance {EQUILIBRIUM_TOLERANCE:.0e}) — a force was lost between \
             the assembly and the records; the run stops rather than record a wrong answer (please report it with this recording)",
            self.model.bodies[i.body].name, self.increment, i.resultant[0], i.resultant[1], i.relative
        );
        Err(SolveError::StepFailed {
            increment: self.increment,
            t: self.t,
            dt: self.last_dt.unwrap_or(self.dt),
            cutbacks: 0,
            reason: message,
            residuals: Vec::new(),
            kind: FailureKind::WrongAnswer,
            points: Vec::new(),
        })
    }

    /// Sum of the reactions at the prescribed DOFs, per direction (x, y; z in 3D).
    fn reaction_total(&self) -> ([f64; 2], Option<f64>) {
        let mut total = [0.0; 3];
        for &d in &self.asm.dofs.prescribed {
            total[d % S::D] += self.asm.r_full[d];
        }
        ([total[0], total[1]], (S::D == 3).then_some(total[2]))
    }
}
