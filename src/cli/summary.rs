//! What `contrail run` prints at the end, for a completed and for a failed run: how far the
//! load went, where it stopped and why, the contact points involved, the Newton work (counted
//! the way `contrail inspect` counts it) and the command to look at the recording.

use contrail::contact::law::ContactState;
use contrail::format::{count, plain};

use contrail::record::{
    ContactPointRecord, IncrementRecord, IterationRecord, Observer, ObserverError, RunInfo, StepView,
};
use std::fmt::Write;

/// Collects, while the run goes, what the summary needs.
#[derive(Default)]
pub struct Tracker {
    pub end: f64,
    /// Every Newton iteration record (the count `contrail inspect` shows).
    pub iterations: usize,
    /// Iterations of the converged attempts (the solver's own count).
    pub converged_iterations: usize,
    pub cutbacks: usize,
    pub increments: usize,
    pub last: Option<IncrementRecord>,
    pub contact: Vec<ContactPointRecord>,
    /// 3D contact points at the last increment: closed, and all.
    pub surface: (usize, usize),
    pub crossings: usize,
    /// The last crossing: increment, point, from and to segment.
    pub last_crossing: Option<(usize, String, usize, usize)>,
    slaves: Vec<Vec<String>>,
    /// Each body's model and the measure of its forces (`block: axisymmetric (forces are
    /// totals over the full circle)`), for the summary's `model` line.
    pub models: Vec<String>,
}

impl Tracker {
    fn point_name(&self, pair: usize, name: &str, slave: usize) -> String {
        let label = self.slaves.get(pair).and_then(|s| s.get(slave)).cloned();
        format!("{name}/{}", label.unwrap_or_else(|| slave.to_string()))
    }
}

impl Observer for Tracker {
    fn start(&mut self, model: contrail::model::ModelRef<'_>, info: &RunInfo) -> Result<(), ObserverError> {
        self.end = info.settings.stepping.end;
        self.models = match model {
            contrail::model::ModelRef::Plane(m) => (m.bodies.iter())
                .map(|b| format!("{}: {}", b.name, b.kinematics.label()))
                .collect(),
            contrail::model::ModelRef::Solid(m) => (m.bodies.iter())
                .map(|b| format!("{}: 3d, {} elements", b.name, b.kind.name()))
                .collect(),
        };
        let model = model.plane();
        self.slaves = model
            .contacts
            .iter()
            .map(|c| c.slaves.iter().map(|s| model.slave_label(*s)).collect())
            .collect();
        Ok(())
    }
    fn iteration(&mut self, _rec: &IterationRecord) -> Result<(), ObserverError> {
        self.iterations += 1;
        Ok(())
    }
    fn increment(&mut self, rec: &IncrementRecord, view: &StepView) -> Result<(), ObserverError> {
        self.increments += 1;
        self.converged_iterations += rec.iterations;
        self.cutbacks += rec.cutbacks;
        self.crossings += view.crossings.len() + view.surface.iter().filter(|p| p.crossing).count();
        if let Some(c) = view.crossings.last() {
            let name = view
                .model
                .plane()
                .contacts
                .get(c.pair)
                .map_or(String::new(), |p| p.name.clone());
            self.last_crossing = Some((
                rec.increment,
                self.point_name(c.pair, &name, c.slave),
                c.from_segment,
                c.to_segment,
            ));
        }
        let surface_crossing = view.surface.iter().rev().find(|p| p.crossing);
        if let Some(p) = surface_crossing.filter(|_| view.crossings.is_empty()) {
            let (a, b) = (p.previous_facet.unwrap_or(0), p.facet.unwrap_or(0));
            let name = format!("{} node {}", p.pair_name, p.node);
            self.last_crossing = Some((rec.increment, name, a, b));
        }
        self.last = Some(rec.clone());
        self.contact = view.contact.to_vec();
        let closed = view.surface.iter().filter(|p| p.state != ContactState::Open).count();
        self.surface = (closed, view.surface.len());
        Ok(())
    }
}

fn state(s: ContactState) -> &'static str {
    match s {
        ContactState::Open => "open",
        ContactState::Stick => "stick",
        ContactState::Slip => "slip",
    }
}

/// The contact points worth naming: rigid slave points, and points within 5 % of a segment
/// end (about to cross).
pub fn involved(contact: &[ContactPointRecord]) -> Vec<String> {
    contact
        .iter()
        .filter(|c| c.state != ContactState::Open)
        .filter(|c| c.slave_label.starts_with("rigid ") || c.xi.abs() > 0.95)
        .take(6)
        .map(|c| match c.segment {
            Some(s) => format!(
                "{}/{} at ξ = {} of segment {s} ({})",
                c.pair_name,
                c.slave_label,
                plain((c.xi * 1e3).round() / 1e3),
                state(c.state)
            ),
            None => format!("{}/{} ({})", c.pair_name, c.slave_label, state(c.state)),
        })
        .collect()
}

/// The lines shared by both summaries: load reached, Newton work, crossings, contact points.
pub fn progress_lines(o: &mut String, t: &Tracker) {
    let row = |o: &mut String, k: &str, v: String| {
        let _ = writeln!(o, "{k:<12} {v}");
    };
    let reached = t.last.as_ref().map_or(0.0, |l| l.t);
    row(
        o,
        "reached",
        format!(
            "t = {} of {} in {}",
            plain(reached),
            plain(t.end),
            count(t.increments, "increment", "increments")
        ),
    );
    if !t.models.is_empty() {
        row(o, "model", t.models.join("; "));
    }
    let monitors = t.last.as_ref().map_or(Vec::new(), |l| l.all_monitors());
    if !monitors.is_empty() {
        let points: Vec<String> = (monitors.iter())
            .map(|m| format!("{} = {}, force = {}", m.label, plain(m.displacement), plain(m.force)))
            .collect();
        row(o, "last point", points.join("; "));
    }
    let failed = t.iterations.saturating_sub(t.converged_iterations);
    row(
        o,
        "newton",
        format!(
            "{} in all (as `contrail inspect` counts): {} in converged increments ({} per increment), {} in failed attempts; {}",
            count(t.iterations, "iteration", "iterations"),
            t.converged_iterations,
            plain((100.0 * t.converged_iterations as f64 / t.increments.max(1) as f64).round() / 100.0),
            failed,
            count(t.cutbacks, "cut-back", "cut-backs")
        ),
    );
    let mut cr = count(t.crossings, "crossing", "crossings");
    if let Some((inc, p, a, b)) = &t.last_crossing {
        let what = if t.surface.1 > 0 { "facet" } else { "segment" };
        let _ = write!(cr, " (last: {p}, {what} {a} → {b} in increment {inc})");
    }
    row(o, "crossings", cr);
    if !t.contact.is_empty() {
        let closed = t.contact.iter().filter(|c| c.state != ContactState::Open).count();
        row(
            o,
            "in contact",
            format!("{closed} of {} contact points at the last increment", t.contact.len()),
        );
    }
    if t.surface.1 > 0 {
        let (closed, all) = t.surface;
        row(
            o,
            "in contact",
            format!("{closed} of {all} 3D contact points at the last increment"),
        );
    }
    for p in involved(&t.contact) {
        row(o, "contact", p);
    }
}

/// The command that shows a recording, or how to make one.
pub fn inspect_hint(mcap: Option<&std::path::Path>, scene: &str) -> String {
    match mcap {
        Some(p) => format!("contrail inspect {}", p.display()),
        None => format!("run again with `--out run.mcap` and `contrail inspect run.mcap` (scene {scene})"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn point(label: &str, xi: f64, state: ContactState) -> ContactPointRecord {
        ContactPointRecord {
            pair: 0,
            pair_name: "corner".into(),
            slave: 0,
            slave_label: label.into(),
            segment: Some(17),
            previous_segment: Some(17),
            xi,
            xi_anchor: f64::NAN,
            gap: -1e-5,
            normal_force: 1.0,
            trial_traction: 0.0,
            traction: 0.0,
            state,
            crossing: false,
            position: [0.0; 2],
            contact_point: [0.0; 2],
            normal: [0.0, 1.0],
            tangent: [1.0, 0.0],
            multiplier: [f64::NAN; 2],
            force: [0.0, 1.0],
        }
    }

    #[test]
    fn rigid_slaves_and_points_near_a_segment_end_are_named() {
        let pts = [
            point("rigid C", 0.99812, ContactState::Slip),
            point("node 3", 0.2, ContactState::Stick),
            point("node 4", -0.97, ContactState::Stick),
            point("node 5", 0.99, ContactState::Open),
        ];
        let v = involved(&pts);
        assert_eq!(
            v,
            [
                "corner/rigid C at ξ = 0.998 of segment 17 (slip)",
                "corner/node 4 at ξ = -0.97 of segment 17 (stick)"
            ]
        );
    }

    #[test]
    fn the_summary_counts_iterations_like_inspect_and_uses_plurals() {
        let t = Tracker {
            end: 11.0,
            iterations: 20,
            converged_iterations: 12,
            cutbacks: 1,
            increments: 3,
            ..Tracker::default()
        };
        let mut o = String::new();
        progress_lines(&mut o, &t);
        assert!(o.contains("t = 0 of 11 in 3 increments"), "{o}");
        assert!(
            o.contains("20 iterations in all (as `contrail inspect` counts): 12 in converged increments (4 per increment), 8 in failed attempts; 1 cut-back"),
            "{o}"
        );
        assert!(o.contains("0 crossings"), "{o}");
    }
}
