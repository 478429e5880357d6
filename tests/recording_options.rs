//! The MCAP recorder's options of format 3: which Newton iterations are written, which
//! increments get a Foxglove scene, and whether slave nodes out of reach are left out.

use contrail::analysis::recording::Recording;
use contrail::record::mcap::sink::{Iterations, McapOptions, McapSink, SceneEvery};
use contrail::record::{Fanout, Memory};
use std::collections::BTreeMap;
use std::io::Cursor;
use std::sync::atomic::AtomicBool;

fn record(scene: &str, sets: &[&str], opts: McapOptions) -> (Vec<u8>, Memory) {
    let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
    let (src, problem) = contrail::load_scene(scene, &sets).unwrap_or_else(|e| panic!("{e}"));
    let info = contrail::run_info(&src, &sets, &problem);
    let mut sink = McapSink::new(Cursor::new(Vec::new()), "memory", opts).unwrap();
    let mut mem = Memory::default();
    let mut fan = Fanout::default();
    fan.sinks.push(&mut sink);
    fan.sinks.push(&mut mem);
    let _ = contrail::solver::run(&problem, &info, &mut fan, &AtomicBool::new(false));
    drop(fan);
    (sink.into_inner().unwrap().into_inner(), mem)
}

/// Messages per topic.
fn topics(bytes: &[u8]) -> BTreeMap<String, usize> {
    let mut n = BTreeMap::new();
    for m in mcap::MessageStream::new(bytes).unwrap() {
        *n.entry(m.unwrap().channel.topic.clone()).or_default() += 1;
    }
    n
}

#[test]
fn only_the_iterations_of_failed_attempts_are_written_when_asked() {
    // two iterations allowed (none more while the active set settles): some increments are
    // cut back and converge at the next attempt
    let sets = ["solver.max_iterations=2"];
    let (bytes, mem) = record("crossing", &sets, opts_failed());
    let r = Recording::from_bytes(&bytes, "failed-only.mcap").unwrap();
    let converged: BTreeMap<usize, usize> = mem
        .increments
        .iter()
        .map(|inc| {
            let last = (mem.iterations.iter())
                .filter(|i| i.increment == inc.increment)
                .map(|i| i.attempt)
                .max()
                .unwrap_or(0);
            (inc.increment, last)
        })
        .collect();
    let key = |i: &contrail::record::IterationRecord| (i.increment, i.attempt, i.iteration);
    let expected: Vec<_> = (mem.iterations.iter())
        .filter(|i| converged.get(&i.increment) != Some(&i.attempt))
        .map(key)
        .collect();
    let written: Vec<_> = r.iterations.iter().map(key).collect();
    assert_eq!(written, expected);
    assert!(!written.is_empty() && written.len() < mem.iterations.len());
    assert!(r.outcome.is_some() && r.increments.len() == mem.increments.len());
    assert!(mem.increments.iter().any(|i| i.cutbacks > 0));
    // a failed run keeps the iterations of the increment it failed in
    let sets = ["solver.max_iterations=2", "stepping.max_cutbacks=0"];
    let (bytes, mem) = record("crossing", &sets, opts_failed());
    let r = Recording::from_bytes(&bytes, "failed.mcap").unwrap();
    let failed = mem
        .outcome
        .as_ref()
        .map(|o| matches!(o, contrail::record::Outcome::Failed { .. }));
    assert_eq!(failed, Some(true));
    let last = mem.iterations.last().map(key);
    assert_eq!(r.iterations.last().map(key), last);
}

fn opts_failed() -> McapOptions {
    McapOptions {
        iterations: Iterations::Failed,
        ..McapOptions::default()
    }
}

#[test]
fn scenes_are_drawn_at_the_stride_asked_for_and_at_the_last_increment() {
    let sets = ["stepping.increments=30", "fix.1.value=-0.1"];
    let scenes = |scene| {
        let opts = McapOptions {
            scene,
            positions_every: 7,
            ..McapOptions::default()
        };
        let (bytes, mem) = record("strip-channel", &sets, opts);
        let n = topics(&bytes);
        assert_eq!(mem.increments.len(), 30);
        let count = |t: &str| n.get(t).copied().unwrap_or(0);
        (count("/foxglove/scene"), count("/foxglove/reference"))
    };
    // the reference configuration, every 4th increment of 30, and the last
    assert_eq!(scenes(SceneEvery::Every(4)), (1 + 7 + 1, 1));
    assert_eq!(scenes(SceneEvery::Every(1)), (1 + 30, 1));
    // auto: about 200 per run (every increment of a 30-increment run), but only at the
    // increments with positions: every 7th (4 of them) and the last
    assert_eq!(scenes(SceneEvery::Auto), (1 + 4 + 1, 1));
    assert_eq!(scenes(SceneEvery::Off), (0, 0));
    assert_eq!(SceneEvery::Auto.stride(4800), 24);
}
