//! Command-line verbs, one file each.

mod chart;
mod check;
mod client;
mod convert;
mod diff;
mod export;
mod inspect;
pub(crate) mod out;
mod plot;
mod plot_pressure;
mod progress;
mod recover;
mod replay;
mod run;
mod scenes;
mod serve;
pub mod signal;
mod suggest;
mod summary;
mod sweep;

use clap::{Parser, Subcommand};
use std::process::ExitCode;

/// 2D frictional contact FE solver that records everything it does.
#[derive(Parser, Debug)]
#[command(name = "contrail", version, about, long_about = None)]
pub struct Cli {
    #[command(subcommand)]
    pub command: Command,
}

#[derive(Subcommand, Debug)]
pub enum Command {
    /// List the built-in scenes, or print one as a template (`--show NAME`).
    Scenes(scenes::ScenesArgs),
    /// Run a scene (a built-in name or a TOML file).
    Run(run::RunArgs),
    /// Validate a scene without running it.
    Check(check::CheckArgs),
    /// Draw load–displacement curves of several runs (MCAP recordings or CSV files from
    /// `run --out`) on one chart.
    Plot(plot::PlotArgs),
    /// Print the JSON Schema of the scene format.
    Schema,
    /// Rebuild the rerun stream of a run from its MCAP recording alone.
    Replay(replay::ReplayArgs),
    /// Summarise an MCAP recording: scene, scheme, increments, how the run ended, crossings.
    Inspect(inspect::InspectArgs),
    /// Compare two MCAP recordings of one scene (exit 0 within --tol, 1 beyond, 2 bad input).
    Diff(diff::DiffArgs),
    /// Write a recording's fields as a ParaView VTU series (`export FILE.mcap --vtu DIR`).
    Export(export::ExportArgs),
    /// Salvage the complete chunks of an unfinished or damaged recording (a killed run's
    /// `.NAME.PID.N.part` file) into a finalised one that ends with a "recovered" outcome.
    Recover(recover::RecoverArgs),
    /// Write a recording of an older format again in the current one (format 3, with the
    /// Foxglove channels).
    Convert(convert::ConvertArgs),
    /// Run a plan of many runs in parallel (`sweep PLAN.toml --out DIR`), or join shard
    /// folders (`sweep merge DIR... --out DIR`).
    Sweep(sweep::SweepArgs),
    /// Charts of a sweep index: `pareto` (error vs wall time) and `stability` (pass/fail maps).
    Chart(chart::ChartArgs),
    /// Serve a run catalogue: HTTP API, live progress, web page (`serve`, then open
    /// http://127.0.0.1:8717). See docs/service.md.
    Serve(serve::ServeArgs),
    /// Send a run (or with --plan a sweep) to a `contrail serve` service.
    Submit(client::SubmitArgs),
    /// List the runs of a `contrail serve` service, filtered by scene, status, failure kind
    /// or parameter values.
    Runs(client::RunsArgs),
    /// Download a run's recording from a `contrail serve` service.
    Fetch(client::FetchArgs),
}

/// Input the user must fix (exit code 2).
#[derive(Debug, thiserror::Error)]
#[error("{0}")]
pub struct BadInput(pub String);

/// A run that started but did not complete (exit code 1, or 130 when interrupted).
#[derive(Debug, thiserror::Error)]
#[error("{message}")]
pub struct RunFailed {
    pub message: String,
    pub interrupted: bool,
}

pub fn exit_code(e: &anyhow::Error) -> u8 {
    if let Some(r) = e.downcast_ref::<RunFailed>() {
        return if r.interrupted { 130 } else { 1 };
    }
    if e.downcast_ref::<contrail::scene::SceneError>().is_some() || e.downcast_ref::<BadInput>().is_some() {
        return 2;
    }
    1
}

/// Parse the command line; an unknown subcommand gets our suggestion where we have one
/// (clap's similarity measure misses short ones such as `rn` for `run`, or picks `runs`).
pub fn parse() -> Cli {
    use clap::error::{ContextKind, ContextValue, ErrorKind};
    use clap::CommandFactory;
    match Cli::try_parse() {
        Ok(c) => c,
        Err(mut e) => {
            // ours, when we have one, is the closest by edit distance (clap prefers `runs` for `rn`)
            if e.kind() == ErrorKind::InvalidSubcommand {
                let cmd = Cli::command();
                let typed = match e.get(ContextKind::InvalidSubcommand) {
                    Some(ContextValue::String(s)) => s.clone(),
                    _ => String::new(),
                };
                let names: Vec<String> = cmd.get_subcommands().map(|c| c.get_name().to_string()).collect();
                if let Some(s) = suggest::closest(&typed, names.iter().map(String::as_str)) {
                    e.insert(
                        ContextKind::SuggestedSubcommand,
                        ContextValue::Strings(vec![s.to_string()]),
                    );
                }
            }
            e.exit()
        }
    }
}

pub fn dispatch(cli: Cli) -> anyhow::Result<ExitCode> {
    match cli.command {
        Command::Scenes(a) => scenes::scenes(a),
        Command::Run(a) => run::run(a),
        Command::Check(a) => check::check(a),
        Command::Plot(a) => plot::plot(a),
        Command::Replay(a) => replay::replay(a),
        Command::Inspect(a) => inspect::inspect(a),
        Command::Diff(a) => diff::diff(a),
        Command::Export(a) => export::export(a),
        Command::Recover(a) => recover::recover(a),
        Command::Convert(a) => convert::convert(a),
        Command::Sweep(a) => sweep::sweep(a),
        Command::Chart(a) => chart::chart(a),
        Command::Serve(a) => serve::serve(a),
        Command::Submit(a) => client::submit(a),
        Command::Runs(a) => client::runs(a),
        Command::Fetch(a) => client::fetch(a),
        Command::Schema => {
            out::outln!(
                "{}",
                serde_json::to_string_pretty(&schemars::schema_for!(contrail::scene::SceneFile))?
            )?;
            Ok(ExitCode::SUCCESS)
        }
    }
}
