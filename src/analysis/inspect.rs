//! `contrail inspect`: what a recording holds and how its run ended.

use super::recording::Recording;
use crate::contact::law::ContactState;
use crate::format::{compact_list, count, plain, sig};
use crate::model::SECOND_PASS_SUFFIX;
use crate::record::{LogLevel, Outcome};
use serde::Serialize;
use std::fmt::Write;

/// Crossings of one slave point.
#[derive(Debug, Clone, Serialize)]
pub struct PointCrossings {
    pub pair: usize,
    pub pair_name: String,
    pub slave: usize,
    pub slave_label: String,
    pub crossings: usize,
    /// Increments in which the point crossed.
    pub increments: Vec<usize>,
}

/// The summary of a recording.
#[derive(Debug, Clone, Serialize)]
pub struct InspectReport {
    pub file: String,
    pub size_bytes: u64,
    pub bytes_per_increment: f64,
    pub scene: String,
    pub scene_origin: String,
    pub description: String,
    pub overrides: Vec<String>,
    pub transfer: Vec<String>,
    pub crate_version: String,
    pub git_revision: String,
    pub writer: String,
    /// Recording format version (`format_version` of the metadata).
    pub format_version: String,
    pub nodes: usize,
    pub elements: usize,
    pub contact_pairs: Vec<String>,
    /// Each two-pass interface at the last increment with `/interface` (both passes
    /// combined, see [`crate::record::interface`]).
    pub interfaces: Vec<String>,
    /// Each 3D contact pair at the last increment: closed points by state, normal force,
    /// histories lost (see [`super::inspect_surface::state_rows`]).
    pub surface_contact: Vec<String>,
    pub increments: usize,
    pub final_t: f64,
    pub end: f64,
    /// Every Newton iteration recorded on `/iteration`, failed attempts included (the count
    /// `contrail run` prints as "in all").
    pub newton_iterations: usize,
    /// Iterations of the converged increments (sum of `/increment` `iterations`).
    pub converged_iterations: usize,
    pub cutbacks: usize,
    /// `completed`, `failed`, `interrupted`, or `unknown` (no outcome message).
    pub status: String,
    /// Why and where it stopped (failure reason, interruption), empty when completed.
    pub stopped: String,
    /// First increment whose Newton iteration failed (a cut-back or the final failure).
    pub first_failure: Option<usize>,
    pub crossings: usize,
    pub crossings_per_point: Vec<PointCrossings>,
    pub warnings: usize,
    pub errors: usize,
    pub last_log: Option<String>,
    pub message_counts: std::collections::BTreeMap<String, u64>,
    pub positions_every: String,
    /// What `/positions` keeps beyond every node in double precision (empty: that).
    pub positions_kept: String,
    pub chunks: usize,
    /// The tangent's definiteness over the converged increments (`/increment` `tangent`;
    /// empty where no increment recorded it).
    pub stability: String,
}

/// Summarise a recording.
pub fn inspect(r: &Recording) -> InspectReport {
    let meta = |k: &str| r.metadata.get(k).cloned().unwrap_or_default();
    let (status, stopped, failed_at) = how_it_ended(r);
    let first_cutback = r.iterations.iter().find(|i| i.attempt > 0).map(|i| i.increment);
    let first_failure = match (first_cutback, failed_at) {
        (Some(a), Some(b)) if matches!(r.outcome, Some(Outcome::Failed { .. })) => Some(a.min(b)),
        (None, Some(b)) if matches!(r.outcome, Some(Outcome::Failed { .. })) => Some(b),
        (a, _) => a,
    };
    let mut per_point = crossings_per_point(r);
    per_point.extend(super::inspect_surface::crossings_per_point(r));
    let surface_crossings: usize = (per_point.iter())
        .filter(|p| p.pair >= r.model.contacts.len())
        .map(|p| p.crossings)
        .sum();
    let mut contact_pairs = contact_pair_rows(r);
    contact_pairs.extend(super::inspect_surface::pair_rows(r));
    let last = r.increments.last();
    InspectReport {
        file: r.path.clone(),
        size_bytes: r.size_bytes,
        bytes_per_increment: r.size_bytes as f64 / r.increments.len().max(1) as f64,
        scene: r.scene().to_string(),
        scene_origin: meta("scene_origin"),
        description: r.model.description.clone(),
        overrides: r.metadata_list("overrides"),
        transfer: r.metadata_list("transfer"),
        crate_version: meta("crate_version"),
        git_revision: meta("git_revision"),
        writer: r.library.clone(),
        format_version: meta("format_version"),
        nodes: r.model.node_count(),
        elements: r.model.elements.len() + r.model.hexahedra.len(),
        contact_pairs,
        interfaces: interface_rows(r),
        surface_contact: super::inspect_surface::state_rows(r),
        increments: r.increments.len(),
        final_t: last.map_or(0.0, |i| i.t),
        end: r.model.end,
        newton_iterations: r.iterations.len(),
        converged_iterations: r.increments.iter().map(|i| i.iterations).sum(),
        cutbacks: r.increments.iter().map(|i| i.cutbacks).sum(),
        status,
        stopped,
        first_failure,
        crossings: r.crossings.len() + surface_crossings,
        crossings_per_point: per_point,
        warnings: r.logs.iter().filter(|l| l.level == LogLevel::Warning).count(),
        errors: r.logs.iter().filter(|l| l.level == LogLevel::Error).count(),
        last_log: r.logs.last().map(|l| l.message.clone()),
        message_counts: r.message_counts.clone(),
        positions_every: meta("positions_every"),
        positions_kept: positions_kept(r),
        chunks: r.chunks,
        stability: stability(&r.increments),
    }
}

/// The tangent's definiteness along the path: positive definite at every increment that
/// recorded it, or the first increment with a negative eigenvalue (count, or an odd number
/// from a determinant's sign) after the last one seen positive definite.
fn stability(increments: &[crate::record::IncrementRecord]) -> String {
    let judged: Vec<(&crate::record::IncrementRecord, crate::record::TangentRecord)> =
        (increments.iter()).filter_map(|i| i.tangent.map(|t| (i, t))).collect();
    if judged.is_empty() {
        return String::new();
    }
    let Some(k) = judged.iter().position(|(_, t)| t.negative_eigenvalues > 0) else {
        return format!(
            "tangent positive definite at every increment that tells ({} of {})",
            judged.len(),
            increments.len()
        );
    };
    let (first, t) = judged[k];
    let how = if t.exact {
        count(t.negative_eigenvalues, "negative eigenvalue", "negative eigenvalues")
    } else {
        "an odd number of negative eigenvalues (negative determinant)".to_string()
    };
    let after = match k.checked_sub(1).map(|j| judged[j].0) {
        Some(p) => format!(
            ", positive definite at increment {} (t = {}): a limit or bifurcation point lies between",
            p.increment,
            plain(p.t)
        ),
        None => ": the path starts past a limit or bifurcation point".to_string(),
    };
    format!("{how} at increment {} (t = {}){after}", first.increment, plain(first.t))
}

/// One line per 2D contact pair: its slaves, master and transfer scheme.
fn contact_pair_rows(r: &Recording) -> Vec<String> {
    r.model
        .contacts
        .iter()
        .map(|p| {
            let pass = match p.name.strip_suffix(SECOND_PASS_SUFFIX) {
                Some(first) => format!("; the second pass of `{first}`: see its interface"),
                None => String::new(),
            };
            format!(
                "{}: {} against the master {} ({}{pass})",
                p.name,
                count(p.slaves.len(), "slave", "slaves"),
                p.master,
                p.transfer
            )
        })
        .collect()
}

/// One line per two-pass interface, at the last increment that has `/interface`: its normal
/// force and how the passes share it, its pressure, its stick zone.
fn interface_rows(r: &Recording) -> Vec<String> {
    let Some(last) = r.interface.iter().map(|f| f.increment).max() else {
        return Vec::new();
    };
    (r.interface.iter().filter(|f| f.increment == last))
        .map(|f| {
            let mu = r.model.contacts.get(f.first_pass).map_or(0.0, |p| p.mu);
            let closed: Vec<usize> = (0..f.node.len())
                .filter(|&j| f.state[j] != ContactState::Open)
                .collect();
            let passes = f.first_pass_force + f.second_pass_force;
            let share = |x: f64| if passes != 0.0 { 100.0 * x / passes } else { f64::NAN };
            let (lo, hi) = (closed.iter().map(|&j| f.pressure[j]))
                .filter(|p| p.is_finite())
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| (a.min(p), b.max(p)));
            let length: f64 = closed.iter().map(|&j| f.tributary[j]).sum();
            let zone = if mu == 0.0 {
                "frictionless".to_string()
            } else {
                let stick: Vec<f64> = (0..f.node.len())
                    .filter(|&j| f.state[j] == ContactState::Stick)
                    .map(|j| f.s[j])
                    .collect();
                match (stick.first(), stick.last()) {
                    (Some(a), Some(b)) => format!(
                        "{} stick in s ∈ [{}, {}], {} slip",
                        stick.len(),
                        sig(*a, 4),
                        sig(*b, 4),
                        closed.len() - stick.len()
                    ),
                    _ => format!("no stick, {} slip", closed.len()),
                }
            };
            format!(
                "{} at increment {last}: normal force {} (first pass {:.1} %, second pass {:.1} %), \
                 mean pressure {} (nodes {} to {}), {} of {} nodes closed ({zone})",
                f.name,
                sig(f.normal_force, 6),
                share(f.first_pass_force),
                share(f.second_pass_force),
                sig(
                    if length > 0.0 {
                        f.normal_force / length
                    } else {
                        f64::NAN
                    },
                    6
                ),
                sig(lo, 4),
                sig(hi, 4),
                closed.len(),
                f.node.len()
            )
        })
        .collect()
}

/// How the run ended: its status, where and why it stopped (empty when it completed), and
/// the increment it stopped in.
fn how_it_ended(r: &Recording) -> (String, String, Option<usize>) {
    match &r.outcome {
        Some(Outcome::Completed { .. }) => ("completed".to_string(), String::new(), None),
        Some(Outcome::Failed {
            increment,
            t,
            reason,
            residuals,
            ..
        }) => (
            "failed".into(),
            format!(
                "increment {increment} at t = {}: {reason} (last residuals {})",
                plain(*t),
                compact_list(residuals, 8)
            ),
            Some(*increment),
        ),
        Some(Outcome::Interrupted { increment, t }) => (
            "interrupted".into(),
            format!(
                "interrupted during increment {increment} (last converged t = {})",
                plain(*t)
            ),
            Some(*increment),
        ),
        None => ("unknown".into(), "the recording has no outcome message".into(), None),
    }
}

/// The crossings of each contact point that crossed, in pair and slave order.
fn crossings_per_point(r: &Recording) -> Vec<PointCrossings> {
    let mut per_point: Vec<PointCrossings> = Vec::new();
    for c in &r.crossings {
        let (pair, slave) = (c.crossing.pair, c.crossing.slave);
        let idx = match per_point.iter().position(|p| p.pair == pair && p.slave == slave) {
            Some(i) => i,
            None => {
                let info = r.model.contacts.get(pair);
                per_point.push(PointCrossings {
                    pair,
                    pair_name: info.map(|p| p.name.clone()).unwrap_or_default(),
                    slave,
                    slave_label: info.and_then(|p| p.slaves.get(slave).cloned()).unwrap_or_default(),
                    crossings: 0,
                    increments: Vec::new(),
                });
                per_point.len() - 1
            }
        };
        per_point[idx].crossings += 1;
        per_point[idx].increments.push(c.increment);
    }
    per_point.sort_by_key(|p| (p.pair, p.slave));
    per_point
}

/// The report as a human-readable table.
pub fn render(s: &InspectReport) -> String {
    let mut o = String::new();
    render_rows(s, &mut o);
    render_crossings(s, &mut o);
    render_channels(s, &mut o);
    o
}

/// The report's key–value rows: the file, the scene and model, how the run went.
fn render_rows(s: &InspectReport, o: &mut String) {
    let mut row = |k: &str, v: String| {
        let _ = writeln!(o, "{k:<18} {v}");
    };
    row(
        "file",
        format!(
            "{} ({} bytes, {:.0} bytes/increment, {} chunks)",
            s.file, s.size_bytes, s.bytes_per_increment, s.chunks
        ),
    );
    row("scene", format!("{} ({})", s.scene, s.scene_origin));
    if !s.description.is_empty() {
        row("description", s.description.clone());
    }
    if !s.overrides.is_empty() {
        row("overrides", s.overrides.join(" "));
    }
    row("transfer", s.transfer.join(", "));
    row(
        "written by",
        format!(
            "{} (contrail {}, git {}), format {}",
            s.writer, s.crate_version, s.git_revision, s.format_version
        ),
    );
    row(
        "model",
        format!(
            "{}, {}",
            count(s.nodes, "node", "nodes"),
            count(s.elements, "element", "elements")
        ),
    );
    for p in &s.contact_pairs {
        row("contact pair", p.clone());
    }
    for f in &s.interfaces {
        row("interface", f.clone());
    }
    for f in &s.surface_contact {
        row("3D contact", f.clone());
    }
    row(
        "increments",
        format!("{} to t = {} of {}", s.increments, plain(s.final_t), plain(s.end)),
    );
    row(
        "newton",
        format!(
            "{} in all: {} in converged increments, {} in failed attempts; {}",
            count(s.newton_iterations, "iteration", "iterations"),
            s.converged_iterations,
            s.newton_iterations.saturating_sub(s.converged_iterations),
            count(s.cutbacks, "cut-back", "cut-backs")
        ),
    );
    row("ended", s.status.clone());
    if !s.stopped.is_empty() {
        row("stopped", s.stopped.clone());
    }
    row(
        "first failure",
        s.first_failure.map_or("none".into(), |i| format!("increment {i}")),
    );
    row(
        "log",
        format!(
            "{}, {}",
            count(s.warnings, "warning", "warnings"),
            count(s.errors, "error", "errors")
        ),
    );
    if let Some(l) = &s.last_log {
        row("last log", l.clone());
    }
    row("crossings", s.crossings.to_string());
    if !s.stability.is_empty() {
        row("stability", s.stability.clone());
    }
}

/// The table of the points that crossed segments: how often, in which increments.
fn render_crossings(s: &InspectReport, o: &mut String) {
    if !s.crossings_per_point.is_empty() {
        let _ = writeln!(
            o,
            "\n  {:<12} {:<6} {:<16} {:>9}  increments",
            "pair", "slave", "label", "crossings"
        );
        for p in &s.crossings_per_point {
            let incs: Vec<String> = p.increments.iter().map(usize::to_string).collect();
            let _ = writeln!(
                o,
                "  {:<12} {:<6} {:<16} {:>9}  {}",
                p.pair_name,
                p.slave,
                p.slave_label,
                p.crossings,
                incs.join(" ")
            );
        }
    }
}

/// What `/positions` keeps, where it is less than every node in double precision.
fn positions_kept(r: &Recording) -> String {
    let mut kept = String::new();
    if !r.model.positions_nodes.is_empty() {
        let _ = write!(
            kept,
            ", the {} boundary nodes of {}",
            r.model.positions_nodes.len(),
            r.model.node_count()
        );
    }
    if r.metadata.get("positions_precision").map(String::as_str) == Some("single") {
        kept.push_str(", single precision");
    }
    kept
}

/// The table of messages per channel, and how often positions were written.
fn render_channels(s: &InspectReport, o: &mut String) {
    let _ = writeln!(o, "\n  {:<16} {:>9}", "channel", "messages");
    for (topic, n) in &s.message_counts {
        let _ = writeln!(o, "  {topic:<16} {n:>9}");
    }
    let every = match s.positions_every.as_str() {
        "1" => "every increment".to_string(),
        n => format!("every {n} increments"),
    };
    let _ = writeln!(o, "  (positions {every}{})", s.positions_kept);
}

#[cfg(test)]
mod tests {
    use super::stability;
    use crate::record::{IncrementRecord, TangentRecord};

    fn increment(increment: usize, negative: Option<usize>) -> IncrementRecord {
        IncrementRecord {
            increment,
            t: 0.25 * increment as f64,
            tangent: negative.map(|n| TangentRecord {
                negative_eigenvalues: n,
                exact: true,
            }),
            ..Default::default()
        }
    }

    #[test]
    fn the_stability_row_names_the_interval_of_the_loss() {
        assert_eq!(stability(&[increment(1, None)]), "");
        let stable = [increment(1, Some(0)), increment(2, None), increment(3, Some(0))];
        assert_eq!(
            stability(&stable),
            "tangent positive definite at every increment that tells (2 of 3)"
        );
        let lost = [increment(1, Some(0)), increment(2, Some(0)), increment(3, Some(1))];
        assert_eq!(
            stability(&lost),
            "1 negative eigenvalue at increment 3 (t = 0.75), positive definite at increment 2 \
             (t = 0.5): a limit or bifurcation point lies between"
        );
    }
}
