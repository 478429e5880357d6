//! `contrail recover BROKEN.mcap FIXED.mcap`: salvage the complete chunks of an unfinished
//! or damaged recording into a finalised one.

use super::out::outln;
use super::BadInput;
use contrail::analysis::recover::{recover as salvage, RecoverError};
use contrail::record::atomic_file::AtomicFile;
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(clap::Args, Debug)]
pub struct RecoverArgs {
    /// The unfinished or damaged recording (e.g. the `.NAME.PID.N.part` file of a killed run).
    pub broken: PathBuf,
    /// Where to write the recovered recording.
    pub fixed: PathBuf,
}

pub fn recover(a: RecoverArgs) -> anyhow::Result<ExitCode> {
    let name = a.broken.display().to_string();
    if a.broken == a.fixed {
        return Err(BadInput(format!("{name}: write the recovered recording to another file")).into());
    }
    let bytes = std::fs::read(&a.broken).map_err(|e| BadInput(format!("{name}: cannot read: {e}")))?;
    let mut out =
        AtomicFile::create(&a.fixed).map_err(|e| BadInput(format!("{}: cannot create: {e}", a.fixed.display())))?;
    let rep = match salvage(&bytes, &name, &mut out) {
        Ok((_, rep)) => rep,
        Err(e) => {
            out.discard();
            return Err(match e {
                RecoverError::Write { .. } => e.into(),
                _ => BadInput(e.to_string()).into(),
            });
        }
    };
    out.commit()
        .map_err(|e| anyhow::anyhow!("{}: cannot write: {e}", a.fixed.display()))?;
    outln!("recovered    {name} (stopped at {})", rep.stopped)?;
    outln!(
        "chunks       {} kept, {} damaged and dropped",
        rep.chunks_kept,
        rep.chunks_dropped
    )?;
    outln!(
        "increments   {}{}",
        rep.increments,
        rep.last_increment.map_or(String::new(), |i| format!(" (last {i})"))
    )?;
    outln!(
        "outcome      {}",
        if rep.outcome_appended {
            "appended: failed, recovered"
        } else {
            "kept from the file"
        }
    )?;
    outln!("written      {}", a.fixed.display())?;
    Ok(ExitCode::SUCCESS)
}
