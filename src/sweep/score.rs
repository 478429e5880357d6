//! From finished runs to index rows: pick each study's reference (the finest run, a CSV
//! curve, or an analytic solution), measure the error metrics, and flag completed runs that
//! fail a check (lost contact, wrong answer).

use super::index::{IndexRow, Metrics, RunRecord};
use super::plan::{Checks, MonitorQuantity, Plan, Reference, StudyPlan};
use super::SweepError;
use crate::analysis::hertz_point::{hertz_point, PointContact};
use crate::analysis::{analytic, metrics};
use crate::study::{FailureKind, Status};
use std::collections::BTreeMap;

type Curve = Vec<(f64, f64)>;

fn curve(rec: &RunRecord) -> Curve {
    rec.outcome.data.curve.iter().map(|p| (p[1], p[2])).collect()
}

fn finite(v: Option<f64>) -> Option<f64> {
    v.filter(|x| x.is_finite())
}

/// Read an `x, y` CSV curve (header row; the named columns).
pub fn read_csv_curve(path: &str, x: &str, y: &str) -> Result<Curve, SweepError> {
    let text = std::fs::read_to_string(path).map_err(|source| SweepError::Io {
        path: path.to_string(),
        source,
    })?;
    let bad = |line: usize, message: String| SweepError::Reference {
        path: path.to_string(),
        line,
        message,
    };
    let mut lines = text.lines();
    let head: Vec<&str> = lines.next().unwrap_or("").split(',').map(str::trim).collect();
    let col = |n: &str| {
        head.iter()
            .position(|h| *h == n)
            .ok_or_else(|| bad(1, format!("no column `{n}` in the header {head:?}")))
    };
    let (cx, cy) = (col(x)?, col(y)?);
    let mut out = Vec::new();
    for (i, l) in lines.enumerate().filter(|(_, l)| !l.trim().is_empty()) {
        let f: Vec<&str> = l.split(',').map(str::trim).collect();
        let num = |c: usize| {
            f.get(c)
                .and_then(|v| v.parse::<f64>().ok())
                .ok_or_else(|| bad(i + 2, format!("column {} is not a number", c + 1)))
        };
        out.push((num(cx)?, num(cy)?));
    }
    Ok(out)
}

/// The finest completed run of a study among those matching `filter`.
fn finest<'a>(recs: &[&'a RunRecord], filter: &BTreeMap<String, toml::Value>) -> Option<&'a RunRecord> {
    recs.iter()
        .copied()
        .filter(|r| r.outcome.status == Status::Completed)
        .filter(|r| {
            filter.iter().all(|(k, v)| {
                let shown = match v {
                    toml::Value::String(s) => s.clone(),
                    _ => v.to_string(),
                };
                r.params.get(k) == Some(&shown)
            })
        })
        .max_by_key(|r| {
            (
                r.outcome.figures.dofs,
                r.outcome.figures.increments,
                std::cmp::Reverse(r.ordinal),
            )
        })
}

fn study_runs<'a>(records: &'a [RunRecord], study: &str) -> Vec<&'a RunRecord> {
    records.iter().filter(|r| r.study == study).collect()
}

fn analytic_metrics(s: &StudyPlan, rec: &RunRecord, m: &mut Metrics) {
    match &s.reference {
        Reference::Hertz { young, poisson, radius } => {
            if let Some(h) = analytic::hertz(&rec.outcome.data.final_contact, *young, *poisson, *radius) {
                let (ea, ep) = h.errors();
                m.analytic_err = finite(Some(ea.abs().max(ep.abs())));
                m.analytic_detail = format!("a {:+.3e}, p0 {:+.3e}", ea, ep);
            }
        }
        Reference::HertzPoint {
            young,
            poisson,
            radius,
            copies,
        } => {
            let data = &rec.outcome.data;
            let contact = if data.final_surface_contact.is_empty() {
                PointContact::Axisymmetric(&data.final_contact)
            } else {
                PointContact::Solid {
                    points: &data.final_surface_contact,
                    copies: *copies,
                }
            };
            if let Some(h) = hertz_point(contact, *young, *poisson, *radius) {
                let (ea, ep) = h.errors();
                m.analytic_err = finite(Some(ea.abs().max(ep.abs())));
                m.analytic_detail = format!("a {:+.3e}, p0 {:+.3e}", ea, ep);
            }
        }
        Reference::Coulomb { mu } => {
            let mu = mu.or_else(|| rec.params.get("contact.mu").and_then(|v| v.parse().ok()));
            if let Some(e) = mu.and_then(|mu| analytic::coulomb(rec.outcome.data.final_reaction, mu)) {
                m.analytic_err = finite(Some(e.abs()));
                m.analytic_detail = format!("|Rx/Ry|/mu - 1 = {e:+.3e}");
            }
        }
        Reference::Value {
            value,
            quantity,
            scale,
            from,
            to,
        } => {
            if let Some(mean) = monitor_mean(&rec.outcome.data.curve, *quantity, (*from, *to)) {
                let e = mean * scale / value - 1.0;
                m.analytic_err = finite(Some(e.abs()));
                m.analytic_detail = format!("{:.6} vs {value} ({e:+.3e})", mean * scale);
            }
        }
        _ => {}
    }
}

/// Mean of a monitor column over the curve points with `t ∈ [from, to]` (the last point when
/// neither is given); `None` when no point is in the window.
fn monitor_mean(curve: &[[f64; 3]], quantity: MonitorQuantity, (from, to): (Option<f64>, Option<f64>)) -> Option<f64> {
    let column = match quantity {
        MonitorQuantity::Displacement => 1,
        MonitorQuantity::Force => 2,
    };
    if from.is_none() && to.is_none() {
        return curve.last().map(|p| p[column]);
    }
    let (lo, hi) = (from.unwrap_or(f64::NEG_INFINITY), to.unwrap_or(f64::INFINITY));
    let picked: Vec<f64> = curve
        .iter()
        .filter(|p| p[0] >= lo - 1e-9 && p[0] <= hi + 1e-9)
        .map(|p| p[column])
        .collect();
    (!picked.is_empty()).then(|| picked.iter().sum::<f64>() / picked.len() as f64)
}

fn measure(s: &StudyPlan, rec: &RunRecord, reference: Option<&Curve>) -> Metrics {
    let c = curve(rec);
    let jumps: Vec<(f64, f64)> = rec
        .outcome
        .data
        .crossings
        .iter()
        .map(|j| (j.trial_before, j.trial_after))
        .collect();
    let at: Vec<f64> = rec.outcome.data.crossings.iter().map(|j| j.x).collect();
    let mut m = Metrics {
        jump_max: finite(metrics::max_jump(&jumps)),
        jump_rel_max: finite(metrics::max_relative_jump(&jumps)),
        roughness: finite(metrics::roughness(&c, &at, s.roughness_window)),
        spike_rel: finite(s.spike_window.and_then(|w| metrics::spike(&c, w))),
        ..Metrics::default()
    };
    if let Some(r) = reference {
        if let Some(e) = metrics::curve_error(&c, r) {
            m.err_max = finite(Some(e.max));
            m.err_rms = finite(Some(e.rms));
            m.err_max_rel = finite((e.scale > 0.0).then(|| e.max / e.scale));
        }
        m.peak_err = finite(metrics::peak_error(&c, r));
        m.plateau_err = finite(s.plateau_from.and_then(|from| metrics::plateau_error(&c, r, from)));
    }
    analytic_metrics(s, rec, &mut m);
    m
}

/// A check a completed run fails: the kind, the increment and time it points at, and why.
type Flag = (FailureKind, Option<(usize, f64)>, String);

/// The check a completed run fails first.
fn flag(checks: &Checks, rec: &RunRecord, m: &Metrics) -> Option<Flag> {
    if let Some(l) = rec
        .outcome
        .data
        .contact_lost
        .iter()
        .find(|l| checks.keep_contact.contains(&l.pair))
    {
        let msg = format!(
            "contact pair `{}` opened at increment {} (t = {})",
            l.pair, l.increment, l.t
        );
        return Some((FailureKind::LostContact, Some((l.increment, l.t)), msg));
    }
    let over = |v: Option<f64>, bound: Option<f64>| matches!((v, bound), (Some(v), Some(b)) if v.abs() > b);
    if over(m.err_max_rel, checks.max_error_rel) {
        let msg = format!(
            "relative curve error {:.3e} above the plan's bound",
            m.err_max_rel.unwrap_or(0.0)
        );
        return Some((FailureKind::WrongAnswer, None, msg));
    }
    if over(m.peak_err, checks.max_peak_error) {
        let msg = format!(
            "relative peak error {:.3e} above the plan's bound",
            m.peak_err.unwrap_or(0.0)
        );
        return Some((FailureKind::WrongAnswer, None, msg));
    }
    if over(m.jump_rel_max, checks.max_crossing_jump_rel) {
        let worst = rec.outcome.data.crossings.iter().max_by(|a, b| {
            let r = |j: &crate::study::CrossingJump| (j.trial_after - j.trial_before).abs() / j.trial_before.abs();
            r(a).total_cmp(&r(b))
        });
        let msg = format!(
            "relative traction jump {:.3e} at a crossing above the plan's bound",
            m.jump_rel_max.unwrap_or(0.0)
        );
        return Some((FailureKind::WrongAnswer, worst.map(|j| (j.increment, j.t)), msg));
    }
    if over(m.analytic_err, checks.max_analytic_error) {
        let msg = format!("analytic error {} above the plan's bound", m.analytic_detail);
        return Some((FailureKind::WrongAnswer, None, msg));
    }
    None
}

fn row(s: &StudyPlan, rec: &RunRecord, reference: &str, m: Metrics, recording: String) -> IndexRow {
    let o = &rec.outcome;
    let mut transfer: Vec<String> = o.figures.transfer.clone();
    transfer.dedup();
    let (status, mut kind, mut at, mut message) = match &o.status {
        Status::Completed => ("completed", None, None, String::new()),
        Status::Failed {
            kind,
            increment,
            t,
            message,
        } => ("failed", Some(*kind), Some((*increment, *t)), message.clone()),
        Status::Interrupted { increment, t } => ("interrupted", None, Some((*increment, *t)), String::new()),
    };
    if status == "completed" {
        if let Some((k, where_, msg)) = flag(&s.checks, rec, &m) {
            (kind, at, message) = (Some(k), where_, msg);
        }
    }
    IndexRow {
        id: rec.id.clone(),
        ordinal: rec.ordinal,
        study: rec.study.clone(),
        scene: rec.scene.clone(),
        family: rec.family.clone(),
        transfer: transfer.join("+"),
        params: rec.params.clone(),
        status: status.into(),
        failure_kind: kind,
        failure_increment: at.map(|a| a.0),
        failure_t: at.map(|a| a.1),
        load_fraction: o.figures.load_fraction(),
        increments: o.figures.increments,
        newton_iterations: o.figures.newton_iterations,
        cutbacks: o.figures.cutbacks,
        crossings: o.figures.crossings,
        dofs: o.figures.dofs,
        wall_time_s: o.figures.wall_time_s,
        metrics: m,
        reference: reference.to_string(),
        recording,
        message,
    }
}

/// Index rows of `records` (finished runs of `plan`, any order) in plan order;
/// `recording(id)` gives the recording path to write in the row.
pub fn score(
    plan: &Plan,
    records: &[RunRecord],
    recording: &dyn Fn(&RunRecord) -> String,
) -> Result<Vec<IndexRow>, SweepError> {
    let mut rows = Vec::new();
    for s in &plan.studies {
        let recs: Vec<&RunRecord> = records.iter().filter(|r| r.study == s.name).collect();
        let (reference, label): (Option<Curve>, String) = match &s.reference {
            Reference::None => (None, String::new()),
            Reference::Finest { filter, study } => {
                match finest(&study_runs(records, study.as_ref().unwrap_or(&s.name)), filter) {
                    Some(r) => (Some(curve(r)), r.id.clone()),
                    None => (None, String::new()),
                }
            }
            Reference::Csv { path, x, y } => (Some(read_csv_curve(path, x, y)?), format!("csv:{path}")),
            Reference::Hertz { .. } => (None, "hertz".into()),
            Reference::HertzPoint { .. } => (None, "hertz-point".into()),
            Reference::Coulomb { .. } => (None, "coulomb".into()),
            Reference::Value { value, .. } => (None, format!("value:{value}")),
        };
        for rec in recs {
            let mut m = measure(s, rec, reference.as_ref().filter(|c| !c.is_empty()));
            if rec.id == label {
                // the reference against itself: exactly zero, not interpolation round-off
                for v in [
                    &mut m.err_max,
                    &mut m.err_rms,
                    &mut m.err_max_rel,
                    &mut m.peak_err,
                    &mut m.plateau_err,
                ] {
                    *v = v.map(|_| 0.0);
                }
            }
            rows.push(row(s, rec, &label, m, recording(rec)));
        }
    }
    rows.sort_by_key(|r| r.ordinal);
    Ok(rows)
}

#[cfg(test)]
mod tests {

    #[test]
    fn a_value_reference_averages_the_monitor_over_its_window() {
        let curve = [[0.5, 0.1, 1.0], [1.0, 0.2, 2.0], [1.5, 0.3, 4.0], [2.0, 0.4, 8.0]];
        let f = MonitorQuantity::Force;
        assert_eq!(super::monitor_mean(&curve, f, (None, None)), Some(8.0));
        assert_eq!(super::monitor_mean(&curve, f, (Some(1.0), Some(1.5))), Some(3.0));
        assert_eq!(
            super::monitor_mean(&curve, MonitorQuantity::Displacement, (Some(2.0), None)),
            Some(0.4)
        );
        assert_eq!(super::monitor_mean(&curve, f, (Some(3.0), None)), None);
    }

    use super::*;
    use crate::study::{ContactLoss, CrossingJump, Figures, RunData, StudyOutcome};
    use std::path::Path;

    fn rec(id: &str, ordinal: usize, transfer: &str, dofs: usize, curve: Vec<[f64; 3]>) -> RunRecord {
        RunRecord {
            id: id.into(),
            ordinal,
            study: "s".into(),
            scene: "x".into(),
            params: [("contact.transfer".to_string(), transfer.to_string())].into(),
            sets: vec![],
            family: transfer.into(),
            outcome: StudyOutcome {
                status: Status::Completed,
                figures: Figures {
                    dofs,
                    increments: curve.len(),
                    t_end: 1.0,
                    t_reached: 1.0,
                    ..Figures::default()
                },
                data: RunData {
                    curve,
                    ..RunData::default()
                },
            },
        }
    }

    fn plan(extra: &str) -> Plan {
        let text = format!("name = \"p\"\n[[study]]\nname = \"s\"\nscene = \"crossing\"\n{extra}\n");
        Plan::parse(&text, "p.toml", Path::new("")).unwrap()
    }

    #[test]
    fn finest_matching_run_is_the_reference() {
        let p = plan("reference = { kind = \"finest\", where = { \"contact.transfer\" = \"continuous\" } }");
        let fine: Vec<[f64; 3]> = (0..=10).map(|i| [0.0, i as f64, 2.0 * i as f64]).collect();
        let coarse: Vec<[f64; 3]> = (0..=5).map(|i| [0.0, 2.0 * i as f64, 4.0 * i as f64 + 1.0]).collect();
        let recs = vec![
            rec("coarse", 0, "continuous", 10, coarse.clone()),
            rec("fine", 1, "continuous", 40, fine),
            // finer but not matching `where`
            rec("other", 2, "straightforward", 90, coarse),
        ];
        let rows = score(&p, &recs, &|r| r.id.clone()).unwrap();
        assert!(rows.iter().all(|r| r.reference == "fine"));
        assert_eq!(rows[1].metrics.err_max, Some(0.0));
        let e = rows[0].metrics.err_max.unwrap();
        assert!((e - 1.0).abs() < 1e-12, "{e}");
        assert!((rows[0].metrics.err_max_rel.unwrap() - 0.05).abs() < 1e-12);
        assert!(rows.iter().all(|r| r.passed()));
    }

    #[test]
    fn checks_flag_completed_runs() {
        let p = plan("checks = { keep_contact = [\"point\"], max_crossing_jump_rel = 0.01 }");
        let mut lost = rec("lost", 0, "continuous", 10, vec![]);
        lost.outcome.data.contact_lost.push(ContactLoss {
            pair: "point".into(),
            increment: 7,
            t: 0.5,
        });
        let mut jumpy = rec("jumpy", 1, "straightforward", 10, vec![]);
        jumpy.outcome.data.crossings.push(CrossingJump {
            increment: 3,
            t: 0.3,
            x: 0.3,
            pair: 0,
            trial_before: 10.0,
            trial_after: 12.0,
        });
        let rows = score(&p, &[lost, jumpy], &|r| r.id.clone()).unwrap();
        assert_eq!(rows[0].failure_kind, Some(FailureKind::LostContact));
        assert_eq!((rows[0].failure_increment, rows[0].failure_t), (Some(7), Some(0.5)));
        assert_eq!(rows[1].failure_kind, Some(FailureKind::WrongAnswer));
        assert_eq!(rows[1].failure_increment, Some(3));
        assert!((rows[1].metrics.jump_rel_max.unwrap() - 0.2).abs() < 1e-12);
        assert_eq!(rows[1].status, "completed");
    }

    #[test]
    fn a_peak_off_the_reference_is_a_wrong_answer() {
        let p = plan("reference = { kind = \"finest\" }\nchecks = { max_peak_error = 0.05 }");
        let curve = |peak: f64| vec![[0.0, 0.0, 0.0], [0.5, 1.0, peak], [1.0, 2.0, 1.0]];
        let recs = vec![
            rec("fine", 0, "continuous", 40, curve(10.0)),
            rec("near", 1, "continuous", 10, curve(10.4)),
            rec("off", 2, "spatial", 10, curve(8.9)),
        ];
        let rows = score(&p, &recs, &|r| r.id.clone()).unwrap();
        assert!(rows[0].passed() && rows[1].passed());
        assert!((rows[2].metrics.peak_err.unwrap() + 0.11).abs() < 1e-12);
        assert_eq!(rows[2].failure_kind, Some(FailureKind::WrongAnswer));
        assert!(rows[2].message.contains("peak error"), "{}", rows[2].message);
    }

    #[test]
    fn csv_reference_curves() {
        let dir = std::env::temp_dir().join(format!("contrail-score-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let f = dir.join("ref.csv");
        std::fs::write(&f, "v, F\n0, 0\n1, 2\n\n").unwrap();
        let c = read_csv_curve(f.to_str().unwrap(), "v", "F").unwrap();
        assert_eq!(c, vec![(0.0, 0.0), (1.0, 2.0)]);
        assert!(read_csv_curve(f.to_str().unwrap(), "x", "F").is_err());
        std::fs::write(&f, "x,y\n0,a\n").unwrap();
        let e = read_csv_curve(f.to_str().unwrap(), "x", "y").unwrap_err().to_string();
        assert!(e.contains(":2:"), "{e}");
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
