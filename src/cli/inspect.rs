//! `contrail inspect FILE.mcap`: a summary of a recording.

use super::out::{out, outln};
use super::BadInput;
use contrail::analysis::inspect::{inspect as summarise, render};
use contrail::analysis::recording::Recording;
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(clap::Args, Debug)]
pub struct InspectArgs {
    /// A recording made with `contrail run --out FILE.mcap`.
    pub file: PathBuf,
    /// Print the summary as JSON.
    #[arg(long)]
    pub json: bool,
}

pub fn inspect(a: InspectArgs) -> anyhow::Result<ExitCode> {
    let r = Recording::open(&a.file).map_err(|e| BadInput(e.to_string()))?;
    let s = summarise(&r);
    if a.json {
        outln!("{}", serde_json::to_string_pretty(&s)?)?;
    } else {
        out!("{}", render(&s))?;
    }
    Ok(ExitCode::SUCCESS)
}
