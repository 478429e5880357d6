//! `contrail sweep PLAN.toml --out DIR` and `contrail sweep merge DIR... --out DIR`.

use super::{BadInput, RunFailed};
use contrail::sweep::{merge, run_sweep, Plan, Shard, SweepError, SweepOptions};
use std::path::PathBuf;
use std::process::ExitCode;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::Arc;

#[derive(clap::Args, Debug)]
#[command(args_conflicts_with_subcommands = true)]
pub struct SweepArgs {
    #[command(subcommand)]
    pub command: Option<SweepCommand>,
    /// The plan (TOML; see sweeps/smoke.toml).
    pub plan: Option<PathBuf>,
    /// Output folder (recordings, run records, index.csv and index.json).
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,
    /// Runs at a time (default: one per core).
    #[arg(long, short, default_value_t = 0)]
    pub jobs: usize,
    /// Run only the I-th of N deterministic parts of the plan (for array jobs), e.g. 2/8.
    #[arg(long, value_name = "I/N")]
    pub shard: Option<Shard>,
    /// In the recordings, write node positions every N-th increment (and the last).
    #[arg(long, value_name = "N", default_value_t = 1)]
    pub positions_every: usize,
    /// No line per finished run.
    #[arg(long)]
    pub quiet: bool,
}

#[derive(clap::Subcommand, Debug)]
pub enum SweepCommand {
    /// Join the run records of shard folders of one plan into one index.
    Merge(MergeArgs),
}

#[derive(clap::Args, Debug)]
pub struct MergeArgs {
    /// Shard output folders (each with plan.json and runs/).
    #[arg(required = true)]
    pub dirs: Vec<PathBuf>,
    /// Folder for the merged index.csv and index.json.
    #[arg(long, value_name = "DIR")]
    pub out: PathBuf,
}

fn bad(e: SweepError) -> anyhow::Error {
    BadInput(e.to_string()).into()
}

pub fn sweep(a: SweepArgs) -> anyhow::Result<ExitCode> {
    if let Some(SweepCommand::Merge(m)) = a.command {
        let (rows, csv, json) = merge(&m.dirs, &m.out).map_err(bad)?;
        println!("merged {} runs from {} folders", rows.len(), m.dirs.len());
        println!("written {}\nwritten {}", csv.display(), json.display());
        return Ok(ExitCode::SUCCESS);
    }
    let (Some(plan_path), Some(out)) = (a.plan, a.out) else {
        return Err(BadInput(
            "usage: contrail sweep PLAN.toml --out DIR (or: contrail sweep merge DIR... --out DIR)".into(),
        )
        .into());
    };
    let plan = Plan::load(&plan_path).map_err(bad)?;
    let stop = Arc::new(AtomicBool::new(false));
    {
        let stop = stop.clone();
        let _ = ctrlc::set_handler(move || stop.store(true, Ordering::SeqCst));
    }
    let opts = SweepOptions {
        out: out.clone(),
        jobs: a.jobs,
        shard: a.shard,
        positions_every: a.positions_every.max(1),
    };
    let quiet = a.quiet;
    let progress = move |line: &str| {
        if !quiet {
            println!("{line}");
        }
    };
    let started = std::time::Instant::now();
    let r = run_sweep(&plan, &opts, &stop, &progress).map_err(|e| match e {
        SweepError::Io { .. } | SweepError::Study(_) | SweepError::Index { .. } => anyhow::Error::from(e),
        e => bad(e),
    })?;
    let passed = r.rows.iter().filter(|x| x.passed()).count();
    println!(
        "plan {}: {} runs{}, {} finished before, {} run now, {} passed, {} failed or flagged ({:.1} s)",
        plan.name,
        r.planned,
        a.shard.map_or(String::new(), |s| format!(
            " ({} in shard {}/{})",
            r.selected, s.index, s.count
        )),
        r.skipped,
        r.ran,
        passed,
        r.rows.len() - passed,
        started.elapsed().as_secs_f64()
    );
    println!("written {}\nwritten {}", r.index_csv.display(), r.index_json.display());
    if r.interrupted {
        return Err(RunFailed {
            message: format!(
                "sweep interrupted: {} of {} runs finished; run the same command again to resume",
                r.rows.len(),
                r.selected
            ),
            interrupted: true,
        }
        .into());
    }
    Ok(ExitCode::SUCCESS)
}
