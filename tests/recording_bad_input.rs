//! `inspect`, `replay` and `diff` on input that is not a usable recording: a clear message
//! and exit code 2, never a panic. Also the exit codes of `diff` on good input (0 within
//! tolerance, 1 beyond) and of an interrupted run (130, with a complete recording).

use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::sync::OnceLock;

fn contrail(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_contrail"))
        .args(args)
        .output()
        .expect("run contrail")
}

fn dir() -> &'static Path {
    static DIR: OnceLock<PathBuf> = OnceLock::new();
    DIR.get_or_init(|| {
        let d = std::env::temp_dir().join(format!("contrail-bad-input-{}", std::process::id()));
        std::fs::create_dir_all(&d).unwrap();
        d
    })
}

/// A recording of a built-in scene (made once per test process).
fn recording(scene: &str, sets: &[&str], file: &str) -> String {
    static MAKING: std::sync::Mutex<()> = std::sync::Mutex::new(());
    let _one_at_a_time = MAKING.lock().unwrap_or_else(|e| e.into_inner());
    let path = dir().join(file);
    if !path.exists() {
        let tmp = dir().join(format!("{file}.part.mcap"));
        let mut args = vec!["run", scene, "--quiet", "--out", tmp.to_str().unwrap()];
        for s in sets {
            args.extend(["--set", s]);
        }
        let out = contrail(&args);
        // a run that fails (exit 1) still leaves a complete recording
        let code = out.status.code();
        assert!(matches!(code, Some(0 | 1)), "{}", String::from_utf8_lossy(&out.stderr));
        std::fs::rename(&tmp, &path).unwrap();
    }
    path.to_str().unwrap().to_string()
}

fn crossing() -> String {
    recording("crossing", &[], "crossing.mcap")
}

fn write(name: &str, bytes: &[u8]) -> String {
    let p = dir().join(name);
    std::fs::write(&p, bytes).unwrap();
    p.to_str().unwrap().to_string()
}

/// Exit code 2, the expected words in the message, no panic.
fn assert_bad(args: &[&str], words: &str) {
    let out = contrail(args);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
    assert!(err.contains(words), "{args:?}: expected `{words}` in: {err}");
    assert!(!err.contains("panicked"), "{args:?}: {err}");
}

fn every_verb(file: &str, words: &str) {
    let good = crossing();
    let rrd = dir().join(format!(
        "{}.rrd",
        Path::new(file).file_name().unwrap().to_str().unwrap()
    ));
    assert_bad(&["inspect", file], words);
    assert_bad(&["inspect", "--json", file], words);
    assert_bad(&["replay", file, "--rerun-save", rrd.to_str().unwrap()], words);
    assert_bad(&["diff", file, &good], words);
    assert_bad(&["diff", &good, file], words);
}

#[test]
fn a_truncated_recording_is_bad_input() {
    let bytes = std::fs::read(crossing()).unwrap();
    for (name, len) in [
        ("half.mcap", bytes.len() / 2),
        ("nearly.mcap", bytes.len() - 3),
        ("head.mcap", 5),
    ] {
        let f = write(name, &bytes[..len]);
        every_verb(&f, "truncated or corrupt");
    }
}

#[test]
fn a_corrupt_recording_is_bad_input() {
    let mut bytes = std::fs::read(crossing()).unwrap();
    let n = bytes.len();
    for b in &mut bytes[n / 3..n / 3 + 16] {
        *b ^= 0x5a;
    }
    every_verb(&write("corrupt.mcap", &bytes), "truncated or corrupt");
    every_verb(&write("text.mcap", b"increment,t\n1,0.5\n"), "truncated or corrupt");
    every_verb(&write("empty.mcap", b""), "truncated or corrupt");
}

#[test]
fn a_missing_file_is_bad_input() {
    let f = dir().join("no-such-file.mcap");
    every_verb(f.to_str().unwrap(), "cannot read");
}

#[test]
fn a_recording_of_another_program_is_bad_input() {
    let mut w = mcap::WriteOptions::new()
        .profile("ros2")
        .library("some-robot")
        .create(std::io::Cursor::new(Vec::new()))
        .unwrap();
    let schema = w.add_schema("std_msgs/String", "jsonschema", b"{}").unwrap();
    let ch = w.add_channel(schema, "/chatter", "json", &Default::default()).unwrap();
    let header = mcap::records::MessageHeader {
        channel_id: ch,
        sequence: 0,
        log_time: 1,
        publish_time: 1,
    };
    w.write_to_known_channel(&header, br#"{"data":"hello"}"#).unwrap();
    w.finish().unwrap();
    let bytes = w.into_inner().into_inner();
    every_verb(&write("other.mcap", &bytes), "not a contrail recording");
}

#[test]
fn recordings_of_different_scenes_are_bad_input_to_diff() {
    let a = crossing();
    let b = recording("block-slide", &[], "block-slide.mcap");
    assert_bad(&["diff", &a, &b], "diff compares runs of one scene");
    assert_bad(&["diff", "--json", &b, &a], "diff compares runs of one scene");
}

#[test]
fn diff_exits_0_within_tolerance_and_1_beyond() {
    let a = crossing();
    let out = contrail(&["diff", &a, &a]);
    assert_eq!(out.status.code(), Some(0), "{}", String::from_utf8_lossy(&out.stdout));
    assert!(String::from_utf8_lossy(&out.stdout).contains("within tolerance"));
    let a = recording("block-slide", &[], "block-slide.mcap");
    let b = recording("block-slide", &["contact.mu=0.2"], "block-slide-mu.mcap");
    let svg = dir().join("traction.svg");
    let out = contrail(&["diff", &a, &b, "--plot", svg.to_str().unwrap(), "--field", "traction"]);
    let text = String::from_utf8_lossy(&out.stdout);
    assert_eq!(
        out.status.code(),
        Some(1),
        "{text}{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(text.contains("differ beyond tolerance"), "{text}");
    assert!(std::fs::read_to_string(&svg).unwrap().contains("<svg"));
    let out = contrail(&["diff", "--json", "--align", "load", &a, &b]);
    assert_eq!(out.status.code(), Some(1));
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(v["within_tolerance"], false);
    assert_bad(
        &["diff", &a, &b, "--plot", svg.to_str().unwrap(), "--field", "nonsense"],
        "unknown field",
    );
    assert_bad(
        &["diff", &a, &b, "--plot", dir().join("x.txt").to_str().unwrap()],
        ".svg or .png",
    );
}

#[cfg(unix)]
#[test]
fn ctrl_c_leaves_a_complete_recording_and_exit_code_130() {
    let out = dir().join("interrupted.mcap");
    // block-slide with a million increments runs for minutes unless stopped
    let mut child = Command::new(env!("CARGO_BIN_EXE_contrail"))
        .args(["run", "block-slide", "--quiet", "--set", "stepping.increments=1000000"])
        .args(["--out", out.to_str().unwrap()])
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    // wait until the recording has started, then press Ctrl-C
    let t0 = std::time::Instant::now();
    // (the recording is written as `.interrupted.mcap.PID.N.part` and renamed at the end)
    let started = || {
        std::fs::read_dir(out.parent().unwrap())
            .unwrap()
            .filter_map(|e| e.ok())
            .any(|e| {
                let f = e.file_name().to_string_lossy().to_string();
                f.starts_with(".interrupted.mcap.") && f.ends_with(".part") && e.metadata().is_ok_and(|m| m.len() > 0)
            })
    };
    while !started() && t0.elapsed().as_secs() < 30 {
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
    std::thread::sleep(std::time::Duration::from_millis(300));
    let kill = Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .unwrap();
    assert!(kill.success());
    let t1 = std::time::Instant::now();
    while child.try_wait().unwrap().is_none() {
        if t1.elapsed().as_secs() > 60 {
            let _ = child.kill();
            panic!("contrail did not stop within 60 s of Ctrl-C");
        }
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
    let res = child.wait_with_output().unwrap();
    let err = String::from_utf8_lossy(&res.stderr);
    let code = res.status.code();
    // (a run that ended on its own before the signal exits 0 or 1; it must not here)
    assert_eq!(code, Some(130), "{err}");
    let r = contrail::analysis::recording::Recording::open(&out).unwrap();
    assert!(
        matches!(r.outcome, Some(contrail::record::Outcome::Interrupted { .. })),
        "{:?}",
        r.outcome
    );
    let s = contrail(&["inspect", out.to_str().unwrap()]);
    assert!(String::from_utf8_lossy(&s.stdout).contains("interrupted"));
}
