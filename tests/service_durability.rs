//! `contrail serve` under kill -9 and a full disk: on restart the catalogue is consistent, the
//! run that was solving is marked interrupted with its partial recording recovered, and the
//! queued runs go on; a run whose disk fills up fails with a clear record while the service
//! goes on serving.

mod service_common;

use contrail::analysis::recording::Recording;
use contrail::analysis::recover::RECOVERED;
use contrail::record::Outcome;
use serde_json::json;
use service_common::{Server, TempDir};
use std::path::Path;
use std::time::{Duration, Instant};

/// Solver processes of run `id` in the data folder `data` (its working directory).
fn solvers(data: &Path, id: &str) -> Vec<u32> {
    let needle = format!("runs/{id}.mcap");
    let data = data.canonicalize().unwrap();
    let mut out = Vec::new();
    for e in std::fs::read_dir("/proc").unwrap().flatten() {
        let Ok(pid) = e.file_name().to_string_lossy().parse::<u32>() else {
            continue;
        };
        let cmd = std::fs::read(e.path().join("cmdline")).unwrap_or_default();
        let state = std::fs::read_to_string(e.path().join("stat")).unwrap_or_default();
        let zombie = state.split_whitespace().nth(2) == Some("Z");
        let here = std::fs::read_link(e.path().join("cwd")).is_ok_and(|c| c == data);
        if !zombie && here && String::from_utf8_lossy(&cmd).contains(&needle) {
            out.push(pid);
        }
    }
    out
}

fn part_files(data: &Path) -> Vec<String> {
    std::fs::read_dir(data.join("runs"))
        .unwrap()
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".part"))
        .collect()
}

#[test]
fn kill_9_mid_run_then_restart_interrupts_and_recovers_it_and_the_queue_goes_on() {
    let dir = TempDir::new("svc-kill");
    let data = dir.0.join("data");
    let mut srv = Server::start(&data, &["--workers", "1"]);
    let (_, a) = srv.post(
        "/api/runs",
        &json!({ "scene": "strip-channel", "set": ["stepping.increments=400000"] }),
    );
    let a = a["id"].as_str().unwrap().to_string();
    let queued: Vec<String> = [json!({ "scene": "crossing" }), json!({ "scene": "block-slide" })]
        .iter()
        .map(|b| srv.post("/api/runs", b).1["id"].as_str().unwrap().to_string())
        .collect();
    // wait until the partial recording holds complete chunks
    let t0 = Instant::now();
    loop {
        let size: u64 = part_files(&data)
            .iter()
            .map(|p| std::fs::metadata(data.join("runs").join(p)).map_or(0, |m| m.len()))
            .sum();
        if size > 3 << 20 {
            break;
        }
        assert!(t0.elapsed() < Duration::from_secs(120), "the run wrote no recording");
        std::thread::sleep(Duration::from_millis(50));
    }
    srv.kill9();
    // the solver dies with the service (parent-death signal)
    let t0 = Instant::now();
    while !solvers(&data, &a).is_empty() {
        assert!(
            t0.elapsed() < Duration::from_secs(10),
            "the solver outlived the service"
        );
        std::thread::sleep(Duration::from_millis(50));
    }
    assert!(!part_files(&data).is_empty());

    let srv = Server::start(&data, &["--workers", "1"]);
    let ra = srv.get(&format!("/api/runs/{a}")).1;
    assert_eq!(ra["status"], "interrupted", "{ra}");
    let msg = ra["message"].as_str().unwrap();
    assert!(msg.contains("service stopped") && msg.contains("recovered"), "{msg}");
    let rec = Recording::open(&data.join(format!("runs/{a}.mcap"))).unwrap();
    assert!(!rec.increments.is_empty());
    match &rec.outcome {
        Some(Outcome::Failed { reason, .. }) => assert!(reason.starts_with(RECOVERED), "{reason}"),
        other => panic!("the recovered recording ends with {other:?}"),
    }
    assert!(part_files(&data).is_empty(), "partial files are cleaned up");
    for id in &queued {
        assert_eq!(srv.wait_ended(id, 120)["status"], "completed");
    }
    // the catalogue: sound, and every run once
    let db = rusqlite::Connection::open(data.join("catalogue.sqlite")).unwrap();
    let check: String = db.query_row("PRAGMA integrity_check", [], |r| r.get(0)).unwrap();
    assert_eq!(check, "ok");
    let (rows, ids): (i64, i64) = db
        .query_row("SELECT COUNT(*), COUNT(DISTINCT id) FROM runs", [], |r| {
            Ok((r.get(0)?, r.get(1)?))
        })
        .unwrap();
    assert_eq!((rows, ids), (3, 3));
    let (_, l) = srv.get("/api/runs?status=running");
    assert_eq!(l["total"], 0);
}

/// Mount a small tmpfs (root only); None when this machine does not allow it.
fn small_tmpfs(at: &Path, size: &str) -> Option<()> {
    std::fs::create_dir_all(at).ok()?;
    let ok = std::process::Command::new("mount")
        .args(["-t", "tmpfs", "-o", &format!("size={size}"), "tmpfs"])
        .arg(at)
        .output()
        .is_ok_and(|o| o.status.success());
    ok.then_some(())
}

struct Unmount<'a>(&'a Path);
impl Drop for Unmount<'_> {
    fn drop(&mut self) {
        let _ = std::process::Command::new("umount").arg("-l").arg(self.0).status();
    }
}

#[test]
fn a_full_disk_fails_the_run_that_hit_it_and_the_service_keeps_serving() {
    let dir = TempDir::new("svc-full");
    let mnt = dir.0.join("small");
    if small_tmpfs(&mnt, "6m").is_none() {
        eprintln!("skipped: cannot mount a small tmpfs here (needs root and mount rights) to fill a disk");
        return;
    }
    let _unmount = Unmount(&mnt);
    let data = mnt.join("data");
    let srv = Server::start(&data, &["--workers", "1"]);
    let (_, big) = srv.post(
        "/api/runs",
        &json!({ "scene": "strip-channel", "set": ["stepping.increments=400000"] }),
    );
    let big = srv.wait_ended(big["id"].as_str().unwrap(), 300);
    assert_eq!(big["status"], "failed", "{big}");
    assert_eq!(big["failure_kind"], "recording", "{big}");
    let msg = big["message"].as_str().unwrap();
    assert!(msg.contains("No space left on device"), "{msg}");
    // still serving, and solving: a small run completes once the failed run's space is freed
    let (s, h) = srv.get("/api/health");
    assert_eq!((s, h["status"].as_str()), (200, Some("ok")));
    let (_, small) = srv.post(
        "/api/runs",
        &json!({ "scene": "crossing", "set": ["stepping.increments=20"] }),
    );
    let small = srv.wait_ended(small["id"].as_str().unwrap(), 120);
    assert_eq!(small["status"], "completed", "{small}");
    assert!(part_files(&data).is_empty());
}

#[test]
fn a_solver_killed_with_sigkill_fails_its_run_and_the_service_goes_on() {
    let dir = TempDir::new("svc-abort");
    let data = dir.0.join("data");
    let srv = Server::start(&data, &["--workers", "1"]);
    let (_, a) = srv.post(
        "/api/runs",
        &json!({ "scene": "strip-channel", "set": ["stepping.increments=400000"] }),
    );
    let a = a["id"].as_str().unwrap().to_string();
    srv.wait_for(&a, |v| v["progress"]["increment"].as_u64() >= Some(2000), 120);
    let pids = solvers(&data, &a);
    assert_eq!(pids.len(), 1, "one solver process");
    let _ = std::process::Command::new("kill")
        .args(["-9", &pids[0].to_string()])
        .status();
    let ra = srv.wait_ended(&a, 60);
    assert_eq!(
        (ra["status"].as_str(), ra["failure_kind"].as_str()),
        (Some("failed"), Some("aborted")),
        "{ra}"
    );
    let msg = ra["message"].as_str().unwrap();
    assert!(msg.contains("killed by signal 9") && msg.contains("recovered"), "{msg}");
    assert!(Recording::open(&data.join(format!("runs/{a}.mcap"))).is_ok());
    let (_, b) = srv.post(
        "/api/runs",
        &json!({ "scene": "crossing", "set": ["stepping.increments=20"] }),
    );
    assert_eq!(srv.wait_ended(b["id"].as_str().unwrap(), 60)["status"], "completed");
}
