//! The Slurm backend: each run is an `sbatch` job on a cluster that shares the data folder.
//! The job runs `contrail run ... --progress runs/ID.progress.jsonl`; the service follows it
//! with `squeue` and reads its progress and outcome from that file (no accounting needed).
//! Jobs outlive the service: after a restart their runs are followed again.

use super::catalogue::RunRow;
use super::conclude::{conclude, Exit};
use super::state::{Backend, Service};
use super::worker::{run_args, tail, take_line, StreamEnd};
use std::io::{Read, Seek, SeekFrom};
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Duration;

/// `'text'` for a POSIX shell.
fn quote(s: &str) -> String {
    format!("'{}'", s.replace('\'', "'\\''"))
}

fn progress_file(run: &RunRow) -> String {
    format!("runs/{}.progress.jsonl", run.id)
}

/// The batch script of a run.
pub fn script(svc: &Service, run: &RunRow) -> String {
    let mut line = quote(&svc.exe.display().to_string());
    for a in run_args(run, &progress_file(run), svc.threads_per_run) {
        line.push(' ');
        line.push_str(&quote(&a));
    }
    format!(
        "#!/bin/sh\n# contrail run {} (written by contrail serve)\ncd {} || exit 2\nexec {line}\n",
        run.id,
        quote(&svc.data.display().to_string())
    )
}

fn submit(svc: &Service, run: &RunRow) -> Result<String, String> {
    let Backend::Slurm { sbatch_args, .. } = &svc.backend else {
        return Err("not the Slurm backend".into());
    };
    let path = svc.data.join("runs").join(format!("{}.sbatch", run.id));
    let _ = std::fs::remove_file(svc.data.join(progress_file(run)));
    std::fs::write(&path, script(svc, run)).map_err(|e| format!("{}: {e}", path.display()))?;
    let out = Command::new("sbatch")
        .arg("--parsable")
        .arg(format!("--job-name=contrail-{}", run.id))
        .arg(format!("--chdir={}", svc.data.display()))
        .arg(format!(
            "--output={}",
            svc.data.join("runs").join(format!("{}.slurm.out", run.id)).display()
        ))
        .arg(format!("--cpus-per-task={}", svc.threads_per_run))
        .args(sbatch_args)
        .arg(&path)
        .output()
        .map_err(|e| format!("cannot run sbatch: {e}"))?;
    if !out.status.success() {
        return Err(format!(
            "sbatch failed: {}",
            String::from_utf8_lossy(&out.stderr).trim()
        ));
    }
    let text = String::from_utf8_lossy(&out.stdout);
    let job = text.trim().split(';').next().unwrap_or("").to_string();
    if job.is_empty() || !job.chars().all(|c| c.is_ascii_digit() || c == '_') {
        return Err(format!("sbatch printed no job id: {text}"));
    }
    Ok(job)
}

/// The job's state in the queue (None: it has left the queue).
fn queue_state(job: &str) -> Result<Option<String>, String> {
    let out = Command::new("squeue")
        .args(["-h", "-j", job, "-o", "%T"])
        .output()
        .map_err(|e| format!("cannot run squeue: {e}"))?;
    let text = String::from_utf8_lossy(&out.stdout).trim().to_string();
    if !out.status.success() {
        // an unknown (finished and purged) job id is an error for squeue
        return Ok(None);
    }
    Ok((!text.is_empty()).then_some(text))
}

/// Whether a job in this state is still to run or running (squeue also lists jobs that
/// ended a moment ago, as COMPLETED, FAILED, CANCELLED ...).
fn in_queue(state: &str) -> bool {
    matches!(
        state,
        "PENDING" | "CONFIGURING" | "RUNNING" | "COMPLETING" | "SUSPENDED" | "REQUEUED" | "RESIZING" | "STAGE_OUT"
    )
}

/// New complete lines of a file from `offset` on.
fn read_new(path: &Path, offset: &mut u64, partial: &mut String) -> Vec<String> {
    let Ok(mut f) = std::fs::File::open(path) else {
        return Vec::new();
    };
    let mut buf = String::new();
    if f.seek(SeekFrom::Start(*offset)).is_err() || f.read_to_string(&mut buf).is_err() {
        return Vec::new();
    }
    *offset += buf.len() as u64;
    partial.push_str(&buf);
    let mut lines: Vec<String> = partial.split('\n').map(String::from).collect();
    *partial = lines.pop().unwrap_or_default();
    lines
}

/// Submit a run as a job and follow it to its end.
pub fn solve(svc: &Service, run: &RunRow) {
    match submit(svc, run) {
        Ok(job) => {
            let _ = svc.catalogue.set_job(&run.id, &job);
            follow(svc, run, &job);
        }
        Err(e) => {
            let exit = Exit {
                code: None,
                how: "not submitted".into(),
                stderr: e,
            };
            conclude(svc, run, None, exit, "");
        }
    }
}

/// Follow a submitted job until it leaves the queue, then conclude its run.
pub fn follow(svc: &Service, run: &RunRow, job: &str) {
    let poll = match &svc.backend {
        Backend::Slurm { poll, .. } => *poll,
        Backend::Local => Duration::from_secs(1),
    };
    let progress: PathBuf = svc.data.join(progress_file(run));
    let (mut offset, mut partial, mut acc) = (0u64, String::new(), StreamEnd::default());
    let mut cancel_sent = false;
    let mut last_state = String::new();
    loop {
        for l in read_new(&progress, &mut offset, &mut partial) {
            take_line(svc, &run.id, &l, &mut acc);
        }
        if !cancel_sent && svc.live.get(&run.id).is_some_and(|l| l.cancel) {
            cancel(job);
            cancel_sent = true;
        }
        match queue_state(job) {
            Ok(Some(state)) if in_queue(&state) => last_state = state,
            Ok(Some(state)) => {
                last_state = state;
                break;
            }
            Ok(None) => break,
            Err(e) => last_state = e,
        }
        std::thread::sleep(poll);
    }
    for l in read_new(&progress, &mut offset, &mut partial)
        .into_iter()
        .chain(std::iter::once(std::mem::take(&mut partial)))
    {
        take_line(svc, &run.id, &l, &mut acc);
    }
    let out = std::fs::read_to_string(svc.data.join("runs").join(format!("{}.slurm.out", run.id))).unwrap_or_default();
    let exit = Exit {
        code: None,
        how: format!("Slurm job {job} left the queue (last seen {last_state})"),
        stderr: tail(&out, 4096),
    };
    conclude(svc, run, acc.end, exit, &acc.text);
}

/// Interrupt a job: SIGINT to its processes (the run finalises its recording); a job still
/// pending is simply removed.
pub fn cancel(job: &str) {
    let _ = Command::new("scancel").args(["--signal=INT", "--full", job]).status();
    if queue_state(job).ok().flatten().is_some_and(|s| s == "PENDING") {
        let _ = Command::new("scancel").arg(job).status();
    }
}
