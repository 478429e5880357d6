//! Cost of recording: the shortened strip-channel scene solved with no sink, with the MCAP
//! recorder (file, positions every increment) and with the rerun file sink.
//!
//! `cargo bench --bench recording_overhead`. On a busy 2-core machine wall times are noisy;
//! pinning to one core (`taskset -c 1 target/release/deps/recording_overhead-* --bench`)
//! counts the compression and batcher threads in full and gives steadier ratios.

use contrail::problem::Problem;
use contrail::record::mcap::sink::{ChunkCompression, McapOptions, McapSink};
use contrail::record::rrd::sink::{self as rerun_sink, RerunSink, RerunTargets};
use contrail::record::{Observer, RunInfo};
use criterion::{criterion_group, criterion_main, Criterion};
use std::io::BufWriter;
use std::path::PathBuf;
use std::sync::atomic::AtomicBool;

struct Nothing;
impl Observer for Nothing {}

fn strip() -> (Problem, RunInfo) {
    let sets = vec!["fix.1.value=-0.55".to_string(), "stepping.increments=220".to_string()];
    let (src, problem) = contrail::load_scene("strip-channel", &sets).expect("strip-channel");
    let info = contrail::run_info(&src, &sets, &problem);
    (problem, info)
}

fn out_dir() -> PathBuf {
    let d = std::env::temp_dir().join(format!("contrail-bench-{}", std::process::id()));
    std::fs::create_dir_all(&d).expect("temp dir");
    d
}

fn bench(c: &mut Criterion) {
    let (problem, info) = strip();
    let stop = AtomicBool::new(false);
    let dir = out_dir();
    let mut g = c.benchmark_group("strip-channel (v to 0.55 in 220 increments)");
    g.sample_size(10);
    g.bench_function("solve", |b| {
        b.iter(|| contrail::solver::run(&problem, &info, &mut Nothing, &stop).map(|s| s.increments))
    });
    let mcap = dir.join("bench.mcap");
    g.bench_function("solve + mcap", |b| {
        b.iter(|| {
            let file = BufWriter::new(std::fs::File::create(&mcap).expect("create"));
            let mut sink = McapSink::new(file, "bench.mcap", McapOptions::default()).expect("mcap");
            contrail::solver::run(&problem, &info, &mut sink, &stop).map(|s| s.increments)
        })
    });
    for (label, compression) in [
        ("lz4", ChunkCompression::Lz4),
        ("no compression", ChunkCompression::None),
    ] {
        g.bench_function(format!("solve + mcap, {label}"), |b| {
            b.iter(|| {
                let file = BufWriter::new(std::fs::File::create(&mcap).expect("create"));
                let opts = McapOptions {
                    compression,
                    ..McapOptions::default()
                };
                let mut sink = McapSink::new(file, "bench.mcap", opts).expect("mcap");
                contrail::solver::run(&problem, &info, &mut sink, &stop).map(|s| s.increments)
            })
        });
    }
    let rrd = dir.join("bench.rrd");
    g.bench_function("solve + rerun file", |b| {
        b.iter(|| {
            let targets = RerunTargets {
                save: Some(rrd.clone()),
                ..RerunTargets::default()
            };
            let stream = rerun_sink::open(&targets, "bench", 2).expect("rerun");
            let mut sink = RerunSink::new(stream, "rerun");
            contrail::solver::run(&problem, &info, &mut sink, &stop).map(|s| s.increments)
        })
    });
    g.finish();
    let _ = std::fs::remove_dir_all(&dir);
}

criterion_group!(benches, bench);
criterion_main!(benches);
