use super::progress::Progress;
use super::{BadInput, RunFailed};
use contrail::record::csv::CsvSink;
use contrail::record::jsonl::JsonlSink;
use contrail::record::mcap_sink::{McapOptions, McapSink};
use contrail::record::rerun_sink::{self, RerunSink};
use contrail::record::{Fanout, Observer};
use contrail::solver::{run as solve, SolveError};
use std::io::{BufWriter, IsTerminal};
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(clap::Args, Debug)]
pub struct RunArgs {
    /// Built-in scene name or path to a scene TOML file.
    pub scene: String,
    /// Write the run to FILE: `.csv` (load–displacement history), `.jsonl` (every record) or
    /// `.mcap` (every record, JSON messages with JSON Schemas, zstd chunks).
    #[arg(long, value_name = "FILE")]
    pub out: Option<PathBuf>,
    /// In an `.mcap` recording, write node positions every N-th increment (and the last).
    #[arg(long, value_name = "N", default_value_t = 1, value_parser = clap::value_parser!(u64).range(1..))]
    pub positions_every: u64,
    #[command(flatten)]
    pub rerun: super::replay::RerunArgs,
    /// Override a scene value, e.g. --set contact.mu=0.1 (repeatable).
    #[arg(long = "set", value_name = "KEY=VALUE")]
    pub sets: Vec<String>,
    /// No progress bar.
    #[arg(long)]
    pub quiet: bool,
}

fn open(path: &PathBuf) -> anyhow::Result<BufWriter<std::fs::File>> {
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir)
            .map_err(|e| BadInput(format!("{}: cannot create directory: {e}", dir.display())))?;
    }
    let f = std::fs::File::create(path).map_err(|e| BadInput(format!("{}: cannot create: {e}", path.display())))?;
    Ok(BufWriter::new(f))
}

pub fn run(a: RunArgs) -> anyhow::Result<ExitCode> {
    let (src, model) = contrail::load_scene(&a.scene, &a.sets)?;
    let info = contrail::run_info(&src, &a.sets, &model);
    let stop = super::signal::stop_flag();
    let mut sinks: Vec<Box<dyn Observer>> = Vec::new();
    if let Some(path) = &a.out {
        let name = path.display().to_string();
        match path.extension().and_then(|e| e.to_str()) {
            Some("csv") => sinks.push(Box::new(CsvSink::new(open(path)?, &name))),
            Some("jsonl") => sinks.push(Box::new(JsonlSink::new(open(path)?, &name))),
            Some("mcap") => {
                let opts = McapOptions {
                    positions_every: a.positions_every as usize,
                    ..McapOptions::default()
                };
                sinks.push(Box::new(
                    McapSink::new(open(path)?, &name, opts).map_err(|e| BadInput(e.to_string()))?,
                ));
            }
            _ => return Err(BadInput(format!("{name}: unknown output kind; use .csv, .jsonl or .mcap")).into()),
        }
    }
    let targets = a.rerun.targets();
    if targets.any() {
        let stream = rerun_sink::open(&targets, &model.name).map_err(|e| BadInput(e.to_string()))?;
        sinks.push(Box::new(RerunSink::new(stream, "rerun")));
    }
    if !a.quiet && std::io::stdout().is_terminal() {
        sinks.push(Box::new(Progress::new(model.stepping.end)));
    }
    let mut fan = Fanout {
        sinks: sinks.iter_mut().map(|s| s.as_mut() as &mut dyn Observer).collect(),
    };
    let result = solve(&model, &info, &mut fan, &stop);
    match result {
        Ok(s) => {
            println!("scene        {} ({})", model.name, src.origin);
            println!("transfer     {}", info.transfer.join(", "));
            println!("increments   {} to t = {}", s.increments, s.t);
            println!(
                "newton       {} iterations ({:.2} per increment), {} cut-backs",
                s.newton_iterations,
                s.newton_iterations as f64 / s.increments.max(1) as f64,
                s.cutbacks
            );
            println!("crossings    {}", s.crossings);
            println!("wall time    {:.3} s", s.wall_time_s);
            if let Some(m) = &s.monitor {
                println!(
                    "final point  {} = {:.6e}, force = {:.6e}",
                    m.label, m.displacement, m.force
                );
            }
            if let Some(p) = &a.out {
                println!("written      {}", p.display());
            }
            if let Some(p) = &a.rerun.rerun_save {
                println!("written      {}", p.display());
            }
            Ok(ExitCode::SUCCESS)
        }
        Err(e) => {
            let interrupted = matches!(e, SolveError::Interrupted { .. });
            let mut message = format!("{} ({}): {e}", model.name, src.origin);
            if let Some(p) = &a.out {
                message.push_str(&format!("\n  the record up to this point is in {}", p.display()));
            }
            Err(RunFailed { message, interrupted }.into())
        }
    }
}
