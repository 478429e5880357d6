//! `contrail diff A.mcap B.mcap`: compare two recordings of one scene.

use super::out::{out, outln};
use super::BadInput;
use contrail::analysis::diff::{diff as compare, traces, Align, DiffReport, POINT_FIELDS};
use contrail::analysis::plot::line_chart;
use contrail::analysis::recording::Recording;
use std::fmt::Write;
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(clap::Args, Debug)]
pub struct DiffArgs {
    pub a: PathBuf,
    pub b: PathBuf,
    /// Pair increments by number, or by load level t (runs with different step sizes).
    #[arg(long, value_enum, default_value = "increment")]
    pub align: Align,
    /// Values agree when |a − b| ≤ tol · max(1, |a|, |b|).
    #[arg(long, default_value_t = 1e-6)]
    pub tol: f64,
    /// Print the report as JSON.
    #[arg(long)]
    pub json: bool,
    /// Draw the two traces of --field into FILE (.svg or .png), crossings marked.
    #[arg(long, value_name = "FILE")]
    pub plot: Option<PathBuf>,
    /// Field to plot: a contact field (segment, state, xi, xi_anchor, gap, normal_force,
    /// trial_traction, traction) or an increment field (t, iterations, residuals,
    /// displacement, force, reaction_x, reaction_y).
    #[arg(long, default_value = "traction")]
    pub field: String,
    /// Contact point of a contact field as PAIR/SLAVE indices (default: where the field first
    /// diverged, else 0/0).
    #[arg(long, value_name = "PAIR/SLAVE")]
    pub point: Option<String>,
}

fn parse_point(s: &str) -> Result<(usize, usize), BadInput> {
    let bad = || BadInput(format!("--point {s}: expected PAIR/SLAVE indices, e.g. 0/3"));
    let (p, q) = s.split_once('/').ok_or_else(bad)?;
    Ok((
        p.trim().parse().map_err(|_| bad())?,
        q.trim().parse().map_err(|_| bad())?,
    ))
}

fn render(d: &DiffReport) -> String {
    let mut o = String::new();
    let _ = writeln!(
        o,
        "diff of scene {} aligned by {} (tol {:e})",
        d.scene,
        format!("{:?}", d.align).to_lowercase(),
        d.tol
    );
    for (n, e) in [("A", &d.a), ("B", &d.b)] {
        let _ = writeln!(
            o,
            "{n}: {} [{}{}] {}: {} increments to t = {}{}",
            e.file,
            e.transfer.join(", "),
            if e.overrides.is_empty() {
                String::new()
            } else {
                format!("; {}", e.overrides.join(" "))
            },
            e.status,
            e.increments,
            e.final_t,
            if e.stopped.is_empty() {
                String::new()
            } else {
                format!(" (stopped: {})", e.stopped)
            }
        );
    }
    let _ = writeln!(
        o,
        "matched increments {} (only in A {}, only in B {})\n",
        d.matched_increments, d.only_in_a, d.only_in_b
    );
    let _ = writeln!(
        o,
        "{:<15} {:>9} {:>7} {:>11} {:>11}  first divergence",
        "field", "compared", "beyond", "max abs", "max rel"
    );
    for f in &d.fields {
        let first = f.first_divergence.as_ref().map_or(String::new(), |v| {
            format!(
                "increment {}{} (t = {:.6}){}: A {} B {}",
                v.increment_a,
                if v.increment_b != v.increment_a {
                    format!("/{}", v.increment_b)
                } else {
                    String::new()
                },
                v.t,
                v.point.as_ref().map_or(String::new(), |p| format!(" at {p}")),
                v.a,
                v.b
            )
        });
        let _ = writeln!(
            o,
            "{:<15} {:>9} {:>7} {:>11.3e} {:>11.3e}  {first}",
            f.field, f.compared, f.beyond_tolerance, f.max_abs, f.max_rel
        );
    }
    for (n, list) in [("A", &d.crossings_only_in_a), ("B", &d.crossings_only_in_b)] {
        for c in list {
            let _ = writeln!(
                o,
                "crossing only in {n}: increment {}, pair {} slave {}: segment {} → {}",
                c.increment, c.pair, c.slave, c.from_segment, c.to_segment
            );
        }
    }
    let _ = writeln!(
        o,
        "\n{}",
        if d.within_tolerance {
            "result: within tolerance"
        } else {
            "result: the runs differ beyond tolerance"
        }
    );
    o
}

pub fn diff(a: DiffArgs) -> anyhow::Result<ExitCode> {
    if a.tol.is_nan() || a.tol < 0.0 {
        return Err(BadInput(format!("--tol {}: must be a number ≥ 0", a.tol)).into());
    }
    let ra = Recording::open(&a.a).map_err(|e| BadInput(e.to_string()))?;
    let rb = Recording::open(&a.b).map_err(|e| BadInput(e.to_string()))?;
    let report = compare(&ra, &rb, a.align, a.tol).map_err(|e| BadInput(e.to_string()))?;
    if let Some(path) = &a.plot {
        let point = match &a.point {
            Some(p) => parse_point(p)?,
            None => report
                .fields
                .iter()
                .find(|f| f.field == a.field)
                .and_then(|f| f.first_divergence.as_ref())
                .and_then(|_| first_point(&ra, &rb, &report, &a.field))
                .unwrap_or((0, 0)),
        };
        let series = traces(&ra, &rb, a.align, &a.field, point).map_err(|e| BadInput(e.to_string()))?;
        let title = if POINT_FIELDS.contains(&a.field.as_str()) {
            format!("{}: {} at pair {} slave {}", report.scene, a.field, point.0, point.1)
        } else {
            format!("{}: {}", report.scene, a.field)
        };
        let x = match a.align {
            Align::Increment => "increment",
            Align::Load => "load level t",
        };
        line_chart(path, &title, x, &a.field, &series).map_err(|e| BadInput(e.to_string()))?;
    }
    if a.json {
        outln!("{}", serde_json::to_string_pretty(&report)?)?;
    } else {
        out!("{}", render(&report))?;
        if let Some(p) = &a.plot {
            outln!("plot         {}", p.display())?;
        }
    }
    Ok(if report.within_tolerance {
        ExitCode::SUCCESS
    } else {
        ExitCode::from(1)
    })
}

/// The point (pair, slave) of the first divergence of a contact field.
fn first_point(a: &Recording, _b: &Recording, d: &DiffReport, field: &str) -> Option<(usize, usize)> {
    let v = d.fields.iter().find(|f| f.field == field)?.first_divergence.as_ref()?;
    let label = v.point.as_ref()?;
    a.contact_at(v.increment_a)
        .iter()
        .find(|p| label.starts_with(&format!("{}/{} ", p.pair_name, p.slave)))
        .map(|p| (p.pair, p.slave))
}
