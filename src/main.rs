//! `contrail`: the command-line front end. This is the one place that turns outcomes into
//! exit codes: 0 success, 1 a run that failed (diverged) or a diff beyond tolerance,
//! 2 bad input, 130 interrupted.

mod cli;

use std::process::ExitCode;

fn main() -> ExitCode {
    // first thing: a signal from now on is handled (see `cli::signal`)
    cli::signal::install();
    let args = cli::parse();
    match cli::dispatch(args) {
        Ok(code) => code,
        Err(e) => {
            eprintln!("error: {e:#}");
            ExitCode::from(cli::exit_code(&e))
        }
    }
}
