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

#[cfg(test)]
mod tests {
    use clap::CommandFactory;

    /// The long help of every subcommand (and of their subcommands).
    fn helps(cmd: &mut clap::Command, path: &str, out: &mut Vec<(String, String)>) {
        let path = format!("{path} {}", cmd.get_name());
        out.push((path.clone(), cmd.render_long_help().to_string()));
        for sub in cmd.get_subcommands_mut() {
            helps(sub, &path, out);
        }
    }

    #[test]
    fn figures_are_recognised() {
        assert!(is_figure("the file is 6.94 MB"));
        assert!(is_figure("(iterations are 4 % of the file)"));
        assert!(is_figure("about 40ms"));
        assert!(!is_figure("every 2 increments, level 19"));
    }

    #[test]
    fn help_says_what_options_do_without_rustdoc_links_or_measurements() {
        let mut all = Vec::new();
        helps(&mut super::Cli::command(), "", &mut all);
        assert!(all.len() > 15, "{} help texts", all.len());
        let run = &all.iter().find(|(p, _)| p.trim() == "contrail run").expect("run").1;
        assert!(run.contains("--compression <KIND>"), "{run}");
        // a rustdoc link (`[`Type::item`]`) means a doc comment written for the API reached
        // the user; a size or a time is the result of one run on one machine, not what the
        // option does (those go to docs/ with date and command)
        for (path, text) in &all {
            assert!(!text.contains("[`"), "{path}: a rustdoc link in the help:\n{text}");
            for line in text.lines() {
                assert!(!is_figure(line), "{path}: a measurement in the help: {line}");
            }
        }
    }

    /// A number followed by a unit of size or time or by a percent sign (`6.9 MB`, `40 ms`,
    /// `4 %`).
    fn is_figure(line: &str) -> bool {
        let words: Vec<&str> = line.split_whitespace().collect();
        let number = |w: &str| w.trim_start_matches(['(', '≈', '~']).parse::<f64>().is_ok();
        words
            .windows(2)
            .any(|w| number(w[0]) && ["MB", "kB", "KB", "GB", "ms", "%", "%,", "%)"].contains(&w[1]))
            || words.iter().any(|w| {
                let w = w.trim_end_matches([',', ')', ';', '.']);
                ["MB", "ms", "%"]
                    .iter()
                    .any(|u| w.strip_suffix(u).is_some_and(|n| !n.is_empty() && number(n)))
            })
    }
}
