//! `contrail plot`: load–displacement curves of several runs on one chart, from CSV files of
//! `run --out FILE.csv` or directly from MCAP recordings.

use super::out::outln;
use super::BadInput;
use contrail::analysis::plot::{line_chart, Series};
use contrail::analysis::recording::Recording;
use std::collections::BTreeSet;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

#[derive(clap::Args, Debug)]
pub struct PlotArgs {
    /// Runs to draw: MCAP recordings (`run --out FILE.mcap`) or CSV files (`run --out
    /// FILE.csv`), each optionally `FILE=LABEL`.
    #[arg(required = true)]
    pub runs: Vec<String>,
    /// Output chart (.svg or .png).
    #[arg(long, short)]
    pub out: PathBuf,
    /// Chart title [default: "Load–displacement", or "Contact pressure" with --pressure].
    #[arg(long)]
    pub title: Option<String>,
    /// [default: "displacement", or "arc length along the master" with --pressure]
    #[arg(long)]
    pub x_label: Option<String>,
    /// [default: "force", or "pressure" with --pressure]
    #[arg(long)]
    pub y_label: Option<String>,
    /// Which monitor to draw, by label (default: the scene's first monitor).
    #[arg(long)]
    pub monitor: Option<String>,
    /// Draw the contact pressure against arc length along the master at this increment (a
    /// number or `last`) instead of load–displacement curves (MCAP recordings only).
    #[arg(long, value_name = "INC")]
    pub pressure: Option<String>,
    /// With --pressure: only this contact pair (a two-pass pair's name: its interface).
    #[arg(long, requires = "pressure")]
    pub pair: Option<String>,
    /// With --pressure: draw each pass of a two-pass pair by itself (its own `/pressure`
    /// profile, along its own master) instead of the interface of both passes.
    #[arg(long, requires = "pressure")]
    pub passes: bool,
}

fn split(spec: &str) -> (String, String) {
    match spec.split_once('=') {
        Some((p, l)) => (p.to_string(), l.to_string()),
        None => (
            spec.to_string(),
            Path::new(spec)
                .file_stem()
                .map_or(spec.to_string(), |s| s.to_string_lossy().into_owned()),
        ),
    }
}

/// The load–displacement series of a recording: the `/increment` records of the monitor
/// labelled `monitor` (the first without one), with a marker at every increment with a
/// crossing.
pub fn from_recording(r: &Recording, label: String, monitor: Option<&str>) -> Result<Series, BadInput> {
    let crossed: BTreeSet<usize> = r.crossings.iter().map(|c| c.increment).collect();
    let mut s = Series {
        label,
        points: Vec::new(),
        markers: Vec::new(),
    };
    for inc in &r.increments {
        if let Some(m) = inc.monitor_named(monitor) {
            let p = (m.displacement, m.force);
            s.points.push(p);
            if crossed.contains(&inc.increment) {
                s.markers.push(p);
            }
        }
    }
    if s.points.is_empty() && !r.increments.is_empty() {
        let known: Vec<String> = (r.increments.iter())
            .flat_map(|i| i.all_monitors())
            .map(|m| m.label.clone())
            .collect::<BTreeSet<_>>()
            .into_iter()
            .collect();
        return Err(BadInput(match monitor {
            Some(l) if !known.is_empty() => format!(
                "{}: the recording has no monitor `{l}`\n  hint: its monitors are {}",
                r.path,
                known.join(", ")
            ),
            _ => format!(
                "{}: the scene `{}` has no [monitor], so the recording has no load–displacement pair",
                r.path,
                r.scene()
            ),
        }));
    }
    Ok(s)
}

fn read_csv(path: &str, label: String, monitor: Option<&str>) -> anyhow::Result<Series> {
    let bytes = std::fs::read(path).map_err(|e| BadInput(format!("{path}: cannot read: {e}")))?;
    let text = String::from_utf8(bytes).map_err(|_| {
        BadInput(format!(
            "{path}: not a text (CSV) file\n  hint: contrail plot reads .csv and .mcap files"
        ))
    })?;
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap_or("").split(',').collect();
    let col = |n: &str| header.iter().position(|h| h.trim_matches('"') == n);
    let (xd, yf) = match monitor {
        Some(l) => (format!("{l}.displacement"), format!("{l}.force")),
        None => ("displacement".to_string(), "force".to_string()),
    };
    let (Some(dx), Some(fy), Some(cr)) = (col(&xd), col(&yf), col("crossings")) else {
        return Err(BadInput(format!(
            "{path}:1: not a contrail CSV with the columns {xd}, {yf}, crossings"
        ))
        .into());
    };
    let mut s = Series {
        label,
        points: Vec::new(),
        markers: Vec::new(),
    };
    for (i, l) in lines.enumerate() {
        let f: Vec<&str> = l.split(',').collect();
        let num = |k: usize| -> anyhow::Result<f64> {
            f.get(k)
                .and_then(|v| v.parse::<f64>().ok())
                .ok_or_else(|| BadInput(format!("{path}:{}: column {} is not a number", i + 2, k + 1)).into())
        };
        let p = (num(dx)?, num(fy)?);
        s.points.push(p);
        if num(cr)? > 0.0 {
            s.markers.push(p);
        }
    }
    Ok(s)
}

fn read(spec: &str, monitor: Option<&str>) -> anyhow::Result<Series> {
    let (path, label) = split(spec);
    let mcap = Path::new(&path).extension().is_some_and(|e| e == "mcap")
        || std::fs::read(&path).is_ok_and(|b| b.starts_with(b"\x89MCAP"));
    if mcap {
        let r = Recording::open(Path::new(&path)).map_err(|e| BadInput(e.to_string()))?;
        return Ok(from_recording(&r, label, monitor)?);
    }
    read_csv(&path, label, monitor)
}

fn read_pressure(spec: &str, increment: Option<usize>, a: &PlotArgs) -> anyhow::Result<Vec<Series>> {
    let (path, label) = split(spec);
    let r = Recording::open(Path::new(&path)).map_err(|e| BadInput(e.to_string()))?;
    Ok(super::plot_pressure::series(
        &r,
        &label,
        increment,
        a.pair.as_deref(),
        a.passes,
    )?)
}

pub fn plot(a: PlotArgs) -> anyhow::Result<ExitCode> {
    let (series, defaults) = match &a.pressure {
        Some(inc) => {
            let inc = super::plot_pressure::parse_increment(inc).map_err(|e| BadInput(format!("--pressure: {e}")))?;
            let mut all = Vec::new();
            for r in &a.runs {
                all.extend(read_pressure(r, inc, &a)?);
            }
            (all, ["Contact pressure", "arc length along the master", "pressure"])
        }
        None => (
            (a.runs.iter().map(|r| read(r, a.monitor.as_deref()))).collect::<anyhow::Result<Vec<_>>>()?,
            ["Load–displacement", "displacement", "force"],
        ),
    };
    let pick = |o: &Option<String>, d: &str| o.clone().unwrap_or_else(|| d.to_string());
    let (title, x, y) = (
        pick(&a.title, defaults[0]),
        pick(&a.x_label, defaults[1]),
        pick(&a.y_label, defaults[2]),
    );
    line_chart(&a.out, &title, &x, &y, &series).map_err(|e| BadInput(e.to_string()))?;
    outln!("written {}", a.out.display())?;
    Ok(ExitCode::SUCCESS)
}
