//! The end of a run, whatever the backend: the outcome line of its progress stream (or, when
//! the solver died without one, what its exit says) into the catalogue; a partial recording
//! salvaged with `contrail recover`'s library; the run's metrics from the sweep scorer.

use super::catalogue::{Finish, RunRow};
use super::state::Service;
use contrail::analysis::recover::recover;
use contrail::record::atomic_file::AtomicFile;
use contrail::record::ChangingPoint;
use contrail::study::{Status, StudyOutcome};
use contrail::sweep::{score, Metrics, Plan, RunRecord};
use std::path::{Path, PathBuf};

/// How a solver process (or job) ended, when it gave no outcome line.
pub struct Exit {
    /// Its exit code (None: killed by a signal, or unknown).
    pub code: Option<i32>,
    /// A description (`signal 9`, `exit code 2`, a Slurm state).
    pub how: String,
    /// The last lines of its error output.
    pub stderr: String,
}

/// Partial recordings (`runs/.ID.mcap.PID.N.part`) a killed solver left.
pub fn part_files(data: &Path, id: &str) -> Vec<PathBuf> {
    let prefix = format!(".{id}.mcap.");
    let Ok(dir) = std::fs::read_dir(data.join("runs")) else {
        return Vec::new();
    };
    let mut parts: Vec<PathBuf> = dir
        .flatten()
        .map(|e| e.path())
        .filter(|p| {
            p.file_name()
                .and_then(|n| n.to_str())
                .is_some_and(|n| n.starts_with(&prefix) && n.ends_with(".part"))
        })
        .collect();
    parts.sort_by_key(|p| std::cmp::Reverse(std::fs::metadata(p).map_or(0, |m| m.len())));
    parts
}

/// Salvage the largest partial recording of a run into `runs/ID.mcap` and remove the
/// partial files. Returns what was done (None: there was nothing to salvage).
pub fn salvage(svc: &Service, id: &str) -> Option<String> {
    let parts = part_files(&svc.data, id);
    let first = parts.first()?;
    let name = first.display().to_string();
    let said = match std::fs::read(first) {
        Err(e) => format!("the partial recording {name} could not be read: {e}"),
        Ok(bytes) => {
            let target = svc.recording(id);
            match AtomicFile::create(&target) {
                Err(e) => format!("the partial recording could not be recovered: {e}"),
                Ok(mut out) => match recover(&bytes, &name, &mut out) {
                    Ok((_, rep)) => match out.commit() {
                        Ok(_) => format!(
                            "its partial recording was recovered ({} increments, stopped at {})",
                            rep.increments, rep.stopped
                        ),
                        Err(e) => format!("the recovered recording could not be written: {e}"),
                    },
                    Err(e) => {
                        out.discard();
                        format!("the partial recording could not be recovered: {e}")
                    }
                },
            }
        }
    };
    for p in &parts {
        let _ = std::fs::remove_file(p);
    }
    Some(said)
}

/// The sweep scorer's metrics of one run (crossing jumps, roughness; no reference curve).
pub fn metrics(run: &RunRow, outcome: &StudyOutcome) -> Option<Metrics> {
    let plan: Plan = serde_json::from_value(serde_json::json!({
        "name": run.id,
        "study": [{ "name": "run", "scene": run.scene_ref, "set": run.sets }],
    }))
    .ok()?;
    let rec = RunRecord {
        id: run.id.clone(),
        ordinal: 0,
        study: "run".into(),
        scene: run.scene.clone(),
        params: run.params.clone(),
        sets: run.sets.clone(),
        family: "run".into(),
        outcome: outcome.clone(),
    };
    score(&plan, &[rec], &|_| String::new()).ok()?.pop().map(|r| r.metrics)
}

/// Write how a run ended: from its outcome line when there is one, else from its exit.
pub fn conclude(svc: &Service, run: &RunRow, end: Option<(StudyOutcome, Vec<ChangingPoint>)>, exit: Exit, log: &str) {
    let cancelled = svc.live.get(&run.id).is_some_and(|l| l.cancel);
    let (status, kind, mut message, outcome, culprit, metrics) = match end {
        Some((outcome, culprit)) => {
            let (kind, message) = match &outcome.status {
                Status::Failed { kind, message, .. } => (Some(kind.as_str().to_string()), message.clone()),
                Status::Interrupted { increment, .. } => (None, format!("interrupted during increment {increment}")),
                Status::Completed => (None, String::new()),
            };
            let m = metrics(run, &outcome).and_then(|m| serde_json::to_string(&m).ok());
            (
                outcome.status.name().to_string(),
                kind,
                message,
                serde_json::to_string(&outcome).ok(),
                serde_json::to_string(&culprit).ok(),
                m,
            )
        }
        None if exit.code == Some(2) => (
            "failed".to_string(),
            Some("bad-input".to_string()),
            exit.stderr.trim().to_string(),
            None,
            None,
            None,
        ),
        None if cancelled => (
            "interrupted".into(),
            None,
            format!("cancelled; the solver ended without an outcome ({})", exit.how),
            None,
            None,
            None,
        ),
        None => (
            "failed".into(),
            Some("aborted".to_string()),
            format!(
                "the solver process ended without an outcome ({}){}",
                exit.how,
                if exit.stderr.trim().is_empty() {
                    String::new()
                } else {
                    format!(": {}", exit.stderr.trim())
                }
            ),
            None,
            None,
            None,
        ),
    };
    if let Some(said) = salvage(svc, &run.id) {
        message = format!("{message}; {said}");
    }
    let f = Finish {
        status: &status,
        failure_kind: kind.as_deref(),
        message: &message,
        outcome,
        culprit,
        metrics,
        log,
    };
    if let Err(e) = svc.catalogue.finish(&run.id, &f) {
        eprintln!(
            "contrail serve: run {}: cannot write its end to the catalogue: {e}",
            run.id
        );
    }
    svc.live.end(&run.id);
    svc.live.send(
        "status",
        &run.id,
        serde_json::json!({ "status": status, "failure_kind": kind, "message": message }),
    );
}
