//! Golden traces: each scene is run again and its recording compared with the one in
//! `recordings/golden/format3/` by `diff` (aligned by increment, tolerance [`TOL`]: values
//! agree when `|a − b| ≤ TOL · max(1, |a|, |b|)`; segment ids, states, iteration counts and
//! crossings must be equal).
//!
//! After an intended change of the physics, refresh them with
//! `CONTRAIL_BLESS=1 cargo test --test recording_golden` and commit `recordings/golden/format3/`.
//! The older recordings are kept as they are (`recordings/golden/*.mcap`, format 1;
//! `recordings/golden/format2/`, format 2): `tests/recording_formats.rs` converts them to
//! format 3 and asserts identical `inspect` reports, `diff` results and records.

use contrail::analysis::diff::{diff, Align, DiffReport};
use contrail::analysis::recording::Recording;
use contrail::record::mcap::sink::{ChunkCompression, McapOptions, McapSink};
use std::io::Cursor;
use std::path::PathBuf;
use std::sync::atomic::AtomicBool;

const TOL: f64 = 1e-6;

fn path(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("recordings/golden/format3")
        .join(format!("{name}.mcap"))
}

/// Run a built-in scene into an in-memory recording (positions thinned, zstd level 19).
fn record(scene: &str, sets: &[&str], positions_every: usize) -> Vec<u8> {
    let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
    let (src, model) = contrail::load_scene(scene, &sets).unwrap_or_else(|e| panic!("{e}"));
    let info = contrail::run_info(&src, &sets, &model);
    let opts = McapOptions {
        positions_every,
        compression: ChunkCompression::Zstd,
        compression_level: 19,
        message_indexes: false,
        ..McapOptions::default()
    };
    let mut sink = McapSink::new(Cursor::new(Vec::new()), scene, opts).unwrap();
    // a golden run may end in a failure: that is recorded and compared like the rest
    let _ = contrail::solver::run(&model, &info, &mut sink, &AtomicBool::new(false));
    sink.into_inner().unwrap().into_inner()
}

fn summary(d: &DiffReport) -> String {
    let mut s = format!(
        "golden: {} {} increments, now: {} {} increments\n",
        d.a.status, d.a.increments, d.b.status, d.b.increments
    );
    for f in d.fields.iter().filter(|f| f.beyond_tolerance > 0) {
        s += &format!(
            "  {}: {} of {} beyond tolerance, max abs {:.3e}, first {:?}\n",
            f.field, f.beyond_tolerance, f.compared, f.max_abs, f.first_divergence
        );
    }
    s += &format!(
        "  crossings only in golden {:?}, only now {:?}\n",
        d.crossings_only_in_a, d.crossings_only_in_b
    );
    s
}

fn check(name: &str, scene: &str, sets: &[&str], positions_every: usize) {
    let now = record(scene, sets, positions_every);
    let file = path(name);
    if std::env::var_os("CONTRAIL_BLESS").is_some() {
        std::fs::create_dir_all(file.parent().unwrap()).unwrap();
        std::fs::write(&file, &now).unwrap();
    }
    let golden = Recording::open(&file).unwrap_or_else(|e| {
        panic!("{e}\n  hint: CONTRAIL_BLESS=1 cargo test --test recording_golden writes the golden files")
    });
    let now = Recording::from_bytes(&now, "this run").unwrap();
    assert_eq!(golden.metadata_list("overrides"), now.metadata_list("overrides"));
    let d = diff(&golden, &now, Align::Increment, TOL).unwrap_or_else(|e| {
        panic!("{e}\n  if the scene changed on purpose: CONTRAIL_BLESS=1 cargo test --test recording_golden")
    });
    assert!(
        d.within_tolerance,
        "{name} differs from {} beyond {TOL:e}:\n{}\n  if the change is intended: \
         CONTRAIL_BLESS=1 cargo test --test recording_golden",
        file.display(),
        summary(&d)
    );
}

#[test]
fn crossing_matches_its_golden_trace() {
    check("crossing", "crossing", &[], 10);
}

#[test]
fn block_slide_matches_its_golden_trace() {
    check("block-slide", "block-slide", &[], 10);
}

#[test]
fn short_strip_channel_matches_its_golden_trace() {
    check(
        "strip-channel",
        "strip-channel",
        &["fix.1.value=-0.55", "stepping.increments=220"],
        20,
    );
}
