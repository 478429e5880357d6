//! `contrail replay FILE.mcap`: rebuild the rerun stream of a run from its recording alone.

use super::out::outln;
use super::BadInput;
use contrail::analysis::recording::Recording;
use contrail::record::rrd::sink::{self as rerun_sink, RerunTargets, RerunView};
use contrail::record::CrossingRecord;
use std::collections::HashMap;
use std::path::PathBuf;
use std::process::ExitCode;

/// Where a rerun stream goes (shared by `run` and `replay`).
#[derive(clap::Args, Debug, Default, Clone)]
pub struct RerunArgs {
    /// Save a rerun stream of the run to FILE.rrd (open it with `rerun FILE.rrd`).
    #[arg(long, value_name = "FILE.rrd")]
    pub rerun_save: Option<PathBuf>,
    /// Start a rerun viewer (`rerun` on PATH) and stream the run to it.
    #[arg(long)]
    pub rerun_spawn: bool,
    /// Stream the run to a running rerun viewer, e.g. rerun+http://127.0.0.1:9876/proxy.
    #[arg(long, value_name = "URL")]
    pub rerun_connect: Option<String>,
}

impl RerunArgs {
    pub fn targets(&self) -> RerunTargets {
        RerunTargets {
            save: self.rerun_save.clone(),
            spawn: self.rerun_spawn,
            connect: self.rerun_connect.clone(),
        }
    }
}

#[derive(clap::Args, Debug)]
pub struct ReplayArgs {
    /// A recording made with `contrail run --out FILE.mcap`.
    pub file: PathBuf,
    #[command(flatten)]
    pub rerun: RerunArgs,
}

/// Send the records of `r` to `view` in the order the run produced them.
pub fn replay_into(r: &Recording, view: &mut RerunView) -> Result<(), rerun_sink::RerunError> {
    let positions: HashMap<usize, _> = r.positions.iter().map(|p| (p.increment, p)).collect();
    let mut crossings: HashMap<usize, Vec<CrossingRecord>> = HashMap::new();
    for c in &r.crossings {
        crossings.entry(c.increment).or_default().push(c.crossing.clone());
    }
    let (mut it, mut lg) = (r.iterations.iter().peekable(), r.logs.iter().peekable());
    for inc in &r.increments {
        while let Some(i) = it.next_if(|i| i.increment <= inc.increment) {
            view.iteration(i)?;
        }
        while let Some(l) = lg.next_if(|l| l.increment > 0 && l.increment <= inc.increment) {
            view.log(l)?;
        }
        let cr = crossings.get(&inc.increment).map_or(&[][..], Vec::as_slice);
        let offsets = r.surface_offsets.get(&inc.increment).map_or(&[][..], Vec::as_slice);
        view.surface(inc.increment, r.surface_at(inc.increment), offsets)?;
        view.increment(
            inc,
            positions.get(&inc.increment).copied(),
            r.contact_at(inc.increment),
            cr,
        )?;
        let joined: Vec<_> = r
            .interface
            .iter()
            .filter(|f| f.increment == inc.increment)
            .cloned()
            .collect();
        if !joined.is_empty() {
            view.interfaces(inc.increment, &joined)?;
        }
    }
    for i in it {
        view.iteration(i)?;
    }
    for l in lg {
        view.log(l)?;
    }
    if let Some(o) = &r.outcome {
        view.outcome(o)?;
    }
    Ok(())
}

pub fn replay(a: ReplayArgs) -> anyhow::Result<ExitCode> {
    let targets = a.rerun.targets();
    if !targets.any() {
        return Err(BadInput(
            "replay needs a target: --rerun-save FILE.rrd, --rerun-spawn or --rerun-connect URL".into(),
        )
        .into());
    }
    let r = Recording::open(&a.file).map_err(|e| BadInput(e.to_string()))?;
    let stream = rerun_sink::open(&targets, r.scene(), r.model.dim()).map_err(|e| BadInput(e.to_string()))?;
    let mut view = RerunView::new(stream, &r.model)?;
    replay_into(&r, &mut view)?;
    view.finish()?;
    outln!(
        "replayed     {} ({} increments, {} contact records)",
        a.file.display(),
        r.increments.len(),
        r.contact.values().map(Vec::len).sum::<usize>() + r.surface.values().map(Vec::len).sum::<usize>()
    )?;
    if let Some(p) = &targets.save {
        outln!("written      {}", p.display())?;
    }
    Ok(ExitCode::SUCCESS)
}
