//! Issue 10 regression tests for recordings: damaged files neither hang nor panic the reader,
//! `/model` records that name missing nodes are refused before `replay` uses them, NaN in
//! `/model` is written like on every other channel, a full disk is an error with its cause,
//! concurrent writers of one file do not corrupt it, and an unfinished file is recovered.

use contrail::analysis::recording::{Recording, RecordingError};
use contrail::analysis::recover::{recover, RECOVERED};
use contrail::model::Model;
use contrail::problem::Problem;
use contrail::record::mcap::sink::{ChunkCompression, McapOptions, McapSink};
use contrail::record::{Observer, Outcome, RunInfo};
use std::io::{Cursor, Seek, SeekFrom, Write};
use std::sync::atomic::AtomicBool;
use std::sync::mpsc;
use std::time::Duration;

fn load(sets: &[&str]) -> (Problem, RunInfo) {
    let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
    let (src, model) = contrail::load_scene("crossing", &sets).unwrap_or_else(|e| panic!("{e}"));
    let info = contrail::run_info(&src, &sets, &model);
    (model, info)
}

/// A small real recording: crossing, 12 increments (small chunks so there are several).
fn small_recording() -> Vec<u8> {
    recording_with(ChunkCompression::default())
}

fn recording_with(compression: ChunkCompression) -> Vec<u8> {
    let (model, info) = load(&["stepping.increments=12", "stepping.end=0.3"]);
    let opts = McapOptions {
        compression,
        ..McapOptions::default()
    };
    let mut sink = McapSink::new(Cursor::new(Vec::new()), "memory", opts).unwrap();
    let _ = contrail::solver::run(&model, &info, &mut sink, &AtomicBool::new(false));
    sink.into_inner().unwrap().into_inner()
}

#[test]
fn lz4_zstd_and_uncompressed_recordings_read_back_alike() {
    let read = |c| Recording::from_bytes(&recording_with(c), "memory.mcap").unwrap();
    let (zstd, lz4, none) = (
        read(ChunkCompression::Zstd),
        read(ChunkCompression::Lz4),
        read(ChunkCompression::None),
    );
    let contact = |r: &Recording| serde_json::to_string(r.contact_at(12)).unwrap();
    assert!(!zstd.contact_at(12).is_empty());
    assert_eq!(contact(&zstd), contact(&lz4));
    assert_eq!(contact(&zstd), contact(&none));
}

/// Read `bytes` on another thread; fail if it takes longer than `secs` (a hang).
fn read_within(bytes: Vec<u8>, secs: u64) -> Result<Recording, String> {
    let (tx, rx) = mpsc::channel();
    std::thread::spawn(move || {
        let r = Recording::from_bytes(&bytes, "damaged.mcap").map_err(|e| e.to_string());
        let _ = tx.send(r);
    });
    rx.recv_timeout(Duration::from_secs(secs))
        .unwrap_or_else(|_| panic!("reading took longer than {secs} s"))
}

#[test]
fn zeroed_bytes_inside_compressed_chunks_do_not_hang_the_reader() {
    let good = small_recording();
    Recording::from_bytes(&good, "good.mcap").unwrap();
    // zero single bytes and short ranges all over the file (the issue: one zeroed byte in a
    // zstd chunk made inspect, diff and replay spin forever)
    let n = good.len();
    for (k, at) in (8..n).step_by((n / 300).max(1)).enumerate() {
        let mut bad = good.clone();
        let len = 1 + k % 4;
        bad[at..(at + len).min(n)].fill(0);
        let _ = read_within(bad, 20);
    }
}

#[test]
fn flips_truncations_and_junk_are_errors() {
    let good = small_recording();
    let n = good.len();
    for cut in [9, n / 4, n / 2, n - 30, n - 1] {
        assert!(read_within(good[..cut].to_vec(), 20).is_err(), "cut at {cut}");
    }
    let mut junk = good.clone();
    junk.extend_from_slice(b"appended junk \x00\xff");
    assert!(read_within(junk, 20).is_err());
    for at in (8..n).step_by(97) {
        let mut bad = good.clone();
        bad[at] ^= 0xff;
        let _ = read_within(bad, 20);
    }
}

/// Write a recording of `model` with no increments (its `/model` record as given).
fn model_only(model: &Model, info: &RunInfo) -> Vec<u8> {
    let mut sink = McapSink::new(Cursor::new(Vec::new()), "memory", McapOptions::default()).unwrap();
    sink.start(model.view(), info).unwrap();
    sink.finish(&Outcome::Completed { increments: 0, t: 0.0 }).unwrap();
    sink.into_inner().unwrap().into_inner()
}

#[test]
fn a_model_element_naming_a_missing_node_is_refused() {
    let (mut model, info) = load(&[]);
    model.model.elements[0].nodes[2] = 10_000;
    let bytes = model_only(&model.model, &info);
    let e = Recording::from_bytes(&bytes, "bad-model.mcap").unwrap_err();
    assert!(matches!(e, RecordingError::Invalid { .. }), "{e}");
    let msg = e.to_string();
    assert!(msg.contains("/model") && msg.contains("node 10000"), "{msg}");
}

#[test]
fn nan_in_the_model_is_written_as_a_string_and_read_back() {
    let (mut model, info) = load(&[]);
    model.model.contacts[0].law.eps_t = f64::NAN;
    model.model.nodes[0][1] = f64::INFINITY;
    let bytes = model_only(&model.model, &info);
    let r = Recording::from_bytes(&bytes, "nan-model.mcap").unwrap();
    assert!(r.model.contacts[0].eps_t.is_nan());
    assert_eq!(r.model.nodes[0][1], f64::INFINITY);
}

/// A `Cursor` that fails like a full disk beyond `room` bytes.
struct Full {
    inner: Cursor<Vec<u8>>,
    room: u64,
}

impl Write for Full {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        if self.inner.position() + buf.len() as u64 > self.room {
            return Err(std::io::Error::from_raw_os_error(28));
        }
        self.inner.write(buf)
    }
    fn flush(&mut self) -> std::io::Result<()> {
        Ok(())
    }
}

impl Seek for Full {
    fn seek(&mut self, pos: SeekFrom) -> std::io::Result<u64> {
        self.inner.seek(pos)
    }
}

#[test]
fn a_full_disk_is_an_error_with_its_cause_not_a_panic() {
    let (model, info) = load(&["stepping.increments=12", "stepping.end=0.3"]);
    let size = small_recording().len() as u64;
    // (not `size − 10`: wall times in the records make sizes vary by a few bytes run to run)
    for room in [0, 8, 100, size / 3, size * 9 / 10] {
        let out = Full {
            inner: Cursor::new(Vec::new()),
            room,
        };
        let msg = match McapSink::new(out, "full.mcap", McapOptions::default()) {
            Err(e) => e.to_string(),
            Ok(mut sink) => {
                let r = contrail::solver::run(&model, &info, &mut sink, &AtomicBool::new(false));
                r.map_or_else(|e| e.to_string(), |_| "completed".into())
            }
        };
        assert!(msg.contains("No space left on device"), "room {room}: {msg}");
    }
}

fn temp_dir(tag: &str) -> std::path::PathBuf {
    let d = std::env::temp_dir().join(format!("contrail-hardening-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

#[test]
fn concurrent_writers_of_one_file_leave_a_complete_recording() {
    let dir = temp_dir("concurrent");
    let path = dir.join("same.mcap");
    let (model, info) = load(&["stepping.increments=12", "stepping.end=0.3"]);
    let mut a = McapSink::create(&path, McapOptions::default()).unwrap();
    let mut b = McapSink::create(&path, McapOptions::default()).unwrap();
    a.start(model.model.view(), &info).unwrap();
    b.start(model.model.view(), &info).unwrap();
    assert!(
        !path.exists(),
        "the final name appears only when a recording is complete"
    );
    a.finish(&Outcome::Completed { increments: 0, t: 0.0 }).unwrap();
    let r = Recording::open(&path).unwrap();
    assert_eq!(r.model.nodes.len(), model.model.nodes.len());
    b.finish(&Outcome::Interrupted { increment: 1, t: 0.0 }).unwrap();
    let r = Recording::open(&path).unwrap();
    assert!(matches!(r.outcome, Some(Outcome::Interrupted { .. })));
    let left: Vec<_> = std::fs::read_dir(&dir).unwrap().collect();
    assert_eq!(left.len(), 1, "temporary files left: {left:?}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn an_unfinished_recording_is_recovered() {
    let good = small_recording();
    let full = Recording::from_bytes(&good, "good.mcap").unwrap();
    // cut where a killed run would have stopped writing: before the summary, mid-chunk …
    for cut in [good.len() * 2 / 3, good.len() - 200, good.len() - 1] {
        let (fixed, rep) = recover(&good[..cut], "cut.mcap", Cursor::new(Vec::new())).unwrap();
        let r = Recording::from_bytes(&fixed.into_inner(), "fixed.mcap").unwrap();
        assert!(r.increments.len() <= full.increments.len());
        assert!(rep.chunks_kept >= 1);
        if rep.outcome_appended {
            match &r.outcome {
                Some(Outcome::Failed { reason, .. }) => assert!(reason.starts_with(RECOVERED), "{reason}"),
                o => panic!("{o:?}"),
            }
        }
        assert_eq!(r.scene_file, full.scene_file);
        assert_eq!(r.model, full.model);
    }
    assert!(recover(b"not an mcap", "x", Cursor::new(Vec::new())).is_err());
    assert!(recover(&good[..20], "x", Cursor::new(Vec::new())).is_err());
}

#[test]
fn a_complete_recording_survives_recovery_unchanged() {
    let good = small_recording();
    let full = Recording::from_bytes(&good, "good.mcap").unwrap();
    let (fixed, rep) = recover(&good, "good.mcap", Cursor::new(Vec::new())).unwrap();
    assert!(!rep.outcome_appended && rep.chunks_dropped == 0);
    let r = Recording::from_bytes(&fixed.into_inner(), "fixed.mcap").unwrap();
    assert_eq!(r.increments.len(), full.increments.len());
    assert_eq!(r.outcome, full.outcome);
}
