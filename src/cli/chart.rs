//! `contrail chart pareto INDEX` and `contrail chart stability INDEX --x KEY --y KEY`.

use super::BadInput;
use contrail::sweep::{Index, IndexRow};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

#[derive(clap::Args, Debug)]
pub struct ChartArgs {
    #[command(subcommand)]
    pub kind: ChartKind,
}

#[derive(clap::Subcommand, Debug)]
pub enum ChartKind {
    /// Error against wall time (log–log), one series per family, Pareto front marked.
    Pareto(ParetoArgs),
    /// Pass/fail map over two swept keys, one panel per transfer scheme (or `--panel`).
    Stability(StabilityArgs),
}

#[derive(clap::Args, Debug)]
pub struct Common {
    /// A sweep's index.json (or its folder).
    pub index: PathBuf,
    /// Output file; both FILE.svg and FILE.png are written (default: next to the index).
    #[arg(long, short)]
    pub out: Option<PathBuf>,
    /// Only the runs of this study of the plan.
    #[arg(long)]
    pub study: Option<String>,
    /// Chart title (default: the plan's name).
    #[arg(long)]
    pub title: Option<String>,
}

#[derive(clap::Args, Debug)]
pub struct ParetoArgs {
    #[command(flatten)]
    pub common: Common,
    /// The error metric (an index column: err_max_rel, err_max, err_rms, peak_err,
    /// plateau_err, jump_max, jump_rel_max, roughness, analytic_err).
    #[arg(long, default_value = "err_max_rel")]
    pub metric: String,
}

#[derive(clap::Args, Debug)]
pub struct StabilityArgs {
    #[command(flatten)]
    pub common: Common,
    /// Swept key on the horizontal axis, e.g. stepping.increments.
    #[arg(long)]
    pub x: String,
    /// Swept key on the vertical axis, e.g. contact.eps_t.
    #[arg(long)]
    pub y: String,
    /// One panel per value of this swept key, or `family` (the plan's family of the run);
    /// default: per transfer scheme.
    #[arg(long)]
    pub panel: Option<String>,
}

fn load(c: &Common) -> anyhow::Result<(Index, Vec<IndexRow>)> {
    let index = Index::load(&c.index).map_err(|e| BadInput(e.to_string()))?;
    let rows: Vec<IndexRow> = index
        .runs
        .iter()
        .filter(|r| c.study.as_ref().is_none_or(|s| r.study == *s))
        .cloned()
        .collect();
    if rows.is_empty() {
        return Err(BadInput(format!(
            "{}: no runs{}",
            c.index.display(),
            c.study.as_ref().map_or(String::new(), |s| format!(" of study `{s}`"))
        ))
        .into());
    }
    Ok((index, rows))
}

fn outputs(c: &Common, default: &str) -> [PathBuf; 2] {
    let base = c.out.clone().unwrap_or_else(|| {
        let dir = if c.index.is_dir() {
            c.index.clone()
        } else {
            c.index.parent().unwrap_or(Path::new("")).to_path_buf()
        };
        dir.join(default)
    });
    [base.with_extension("svg"), base.with_extension("png")]
}

pub fn chart(a: ChartArgs) -> anyhow::Result<ExitCode> {
    match a.kind {
        ChartKind::Pareto(p) => {
            let (index, rows) = load(&p.common)?;
            let title = p
                .common
                .title
                .clone()
                .unwrap_or_else(|| format!("{}: error vs wall time", index.plan));
            for out in outputs(&p.common, "pareto") {
                let pts =
                    contrail::chart::pareto(&rows, &p.metric, &title, &out).map_err(|e| BadInput(e.to_string()))?;
                println!(
                    "written {} ({} runs, {} on the front)",
                    out.display(),
                    pts.len(),
                    pts.iter().filter(|p| p.on_front).count()
                );
            }
        }
        ChartKind::Stability(s) => {
            let (index, rows) = load(&s.common)?;
            let title = s.common.title.clone().unwrap_or_else(|| index.plan.clone());
            for out in outputs(&s.common, "stability") {
                let cells = contrail::chart::stability_by(&rows, (&s.x, &s.y), s.panel.as_deref(), &title, &out)
                    .map_err(|e| BadInput(e.to_string()))?;
                println!(
                    "written {} ({} runs, {} passed)",
                    out.display(),
                    cells.len(),
                    cells.iter().filter(|c| c.passed).count()
                );
            }
        }
    }
    Ok(ExitCode::SUCCESS)
}
