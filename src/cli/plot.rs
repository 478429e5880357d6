use super::out::outln;
use super::BadInput;
use contrail::analysis::plot::{line_chart, Series};
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(clap::Args, Debug)]
pub struct PlotArgs {
    /// CSV files written by `contrail run --out FILE.csv`, each optionally `FILE.csv=LABEL`.
    #[arg(required = true)]
    pub runs: Vec<String>,
    /// Output chart (.svg or .png).
    #[arg(long, short)]
    pub out: PathBuf,
    #[arg(long, default_value = "Load–displacement")]
    pub title: String,
    #[arg(long, default_value = "displacement")]
    pub x_label: String,
    #[arg(long, default_value = "force")]
    pub y_label: String,
}

fn read(spec: &str) -> anyhow::Result<Series> {
    let (path, label) = match spec.split_once('=') {
        Some((p, l)) => (p.to_string(), l.to_string()),
        None => (
            spec.to_string(),
            std::path::Path::new(spec)
                .file_stem()
                .map_or(spec.to_string(), |s| s.to_string_lossy().into_owned()),
        ),
    };
    let text = std::fs::read_to_string(&path).map_err(|e| BadInput(format!("{path}: cannot read: {e}")))?;
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap_or("").split(',').collect();
    let col = |n: &str| header.iter().position(|h| *h == n);
    let (Some(dx), Some(fy), Some(cr)) = (col("displacement"), col("force"), col("crossings")) else {
        return Err(BadInput(format!(
            "{path}:1: not a contrail CSV (needs displacement, force, crossings columns)"
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

pub fn plot(a: PlotArgs) -> anyhow::Result<ExitCode> {
    let series = a.runs.iter().map(|r| read(r)).collect::<anyhow::Result<Vec<_>>>()?;
    line_chart(&a.out, &a.title, &a.x_label, &a.y_label, &series).map_err(|e| BadInput(e.to_string()))?;
    outln!("written {}", a.out.display())?;
    Ok(ExitCode::SUCCESS)
}
