//! Local workers: threads that take queued runs from the catalogue and solve each in a child
//! process of this binary (`contrail run ... --progress -`), reading its progress line by
//! line. A child that aborts or is killed ends its run, never the service; a child dies with
//! the service (Linux: parent-death signal), leaving its partial recording for the restart.

use super::catalogue::RunRow;
use super::conclude::{conclude, Exit};
use super::state::Service;
use contrail::record::ChangingPoint;
use contrail::study::{ProgressLine, StudyOutcome};
use std::io::{BufRead, BufReader, Read};
use std::process::{Command, Stdio};
use std::sync::Arc;
use std::time::Duration;

/// The `contrail run` arguments of a run, writing its progress to `progress`.
pub fn run_args(run: &RunRow, progress: &str, threads: usize) -> Vec<String> {
    let mut a = vec!["run".to_string(), run.scene_ref.clone()];
    for s in &run.sets {
        a.push("--set".into());
        a.push(s.clone());
    }
    a.extend(
        [
            "--out",
            &format!("runs/{}.mcap", run.id),
            "--progress",
            progress,
            "--quiet",
            "--positions-every",
            &run.positions_every.max(1).to_string(),
            "--threads",
            &threads.to_string(),
        ]
        .map(String::from),
    );
    a
}

/// Start `n` worker threads (they live as long as the service).
pub fn spawn_workers(svc: &Arc<Service>, n: usize) {
    for i in 0..n {
        let svc = svc.clone();
        let _ = std::thread::Builder::new()
            .name(format!("worker-{i}"))
            .spawn(move || work(&svc));
    }
}

fn work(svc: &Service) {
    while !svc.stopping() {
        match svc.catalogue.claim(svc.backend.name()) {
            Ok(Some(run)) => {
                svc.live.start(&run.id, None);
                svc.live
                    .send("status", &run.id, serde_json::json!({ "status": "running" }));
                match &svc.backend {
                    super::state::Backend::Local => solve_local(svc, &run),
                    super::state::Backend::Slurm { .. } => super::slurm::solve(svc, &run),
                }
            }
            Ok(None) => svc.wait_for_work(Duration::from_secs(2)),
            Err(e) => {
                eprintln!("contrail serve: catalogue: {e}");
                std::thread::sleep(Duration::from_secs(1));
            }
        }
    }
}

/// What a progress stream said: the outcome line, and everything that was not a progress
/// line (the solver's summary).
#[derive(Default)]
pub struct StreamEnd {
    pub end: Option<(StudyOutcome, Vec<ChangingPoint>)>,
    pub text: String,
}

/// Take one line of a progress stream.
pub fn take_line(svc: &Service, id: &str, line: &str, acc: &mut StreamEnd) {
    match ProgressLine::parse(line) {
        Some(ProgressLine::End { outcome, culprit }) => acc.end = Some((*outcome, culprit)),
        Some(p) if svc.live.progress(id, &p) => {
            if let Ok(text) = serde_json::to_string(&p) {
                let _ = svc.catalogue.set_progress(id, &text);
            }
        }
        Some(_) => {}
        None if acc.text.len() < 64 << 10 => {
            acc.text.push_str(line);
            acc.text.push('\n');
        }
        None => {}
    }
}

/// The last `max` bytes of a text (at a char boundary).
pub fn tail(text: &str, max: usize) -> String {
    let mut start = text.len().saturating_sub(max);
    while !text.is_char_boundary(start) {
        start += 1;
    }
    text[start..].to_string()
}

fn solve_local(svc: &Service, run: &RunRow) {
    let mut cmd = Command::new(&svc.exe);
    cmd.args(run_args(run, "-", svc.threads_per_run))
        .current_dir(&svc.data)
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped());
    #[cfg(target_os = "linux")]
    {
        use std::os::unix::process::CommandExt;
        // SAFETY: prctl is async-signal-safe; nothing else runs between fork and exec.
        unsafe {
            cmd.pre_exec(|| {
                libc::prctl(libc::PR_SET_PDEATHSIG, libc::SIGKILL);
                Ok(())
            });
        }
    }
    let mut child = match cmd.spawn() {
        Ok(c) => c,
        Err(e) => {
            let exit = Exit {
                code: None,
                how: "not started".into(),
                stderr: format!("cannot start {}: {e}", svc.exe.display()),
            };
            return conclude(svc, run, None, exit, "");
        }
    };
    if svc.live.set_pid(&run.id, child.id()) {
        interrupt(child.id());
    }
    let stderr = child.stderr.take().map(|mut e| {
        std::thread::spawn(move || {
            let mut s = String::new();
            let _ = e.read_to_string(&mut s);
            tail(&s, 4096)
        })
    });
    let mut acc = StreamEnd::default();
    if let Some(out) = child.stdout.take() {
        for line in BufReader::new(out).lines() {
            match line {
                Ok(l) => take_line(svc, &run.id, &l, &mut acc),
                Err(_) => break,
            }
        }
    }
    let status = child.wait();
    let stderr = stderr.and_then(|h| h.join().ok()).unwrap_or_default();
    let exit = match status {
        Ok(s) => {
            use std::os::unix::process::ExitStatusExt;
            Exit {
                code: s.code(),
                how: match (s.code(), s.signal()) {
                    (Some(c), _) => format!("exit code {c}"),
                    (None, Some(sig)) => format!("killed by signal {sig}"),
                    _ => "unknown exit".into(),
                },
                stderr,
            }
        }
        Err(e) => Exit {
            code: None,
            how: format!("cannot wait for it: {e}"),
            stderr,
        },
    };
    conclude(svc, run, acc.end, exit, &acc.text);
}

/// Ask a solver process to stop cleanly (SIGINT: it finalises its recording with an
/// `interrupted` outcome, as Ctrl-C does).
pub fn interrupt(pid: u32) {
    // SAFETY: kill(2) with a pid this service started.
    unsafe {
        libc::kill(pid as libc::pid_t, libc::SIGINT);
    }
}
