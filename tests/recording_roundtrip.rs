//! MCAP recordings read back to what the solver reported: every record, NaN included; runs
//! that fail or are interrupted still leave a complete recording whose last message says why.

use contrail::analysis::diff::{diff, Align};
use contrail::analysis::inspect::inspect;
use contrail::analysis::recording::Recording;
use contrail::problem::Problem;
use contrail::record::mcap::sink::{McapOptions, McapSink};
use contrail::record::rrd::sink::{self as rerun_sink, RerunSink, RerunTargets, RerunView};
use contrail::record::{
    ContactPointRecord, Fanout, IterationRecord, Memory, Observer, ObserverError, Outcome, RunInfo,
};
use contrail::solver::run;
use std::io::Cursor;
use std::sync::atomic::{AtomicBool, Ordering};

fn load(name: &str, sets: &[&str]) -> (Problem, RunInfo) {
    let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
    let (src, model) = contrail::load_scene(name, &sets).unwrap_or_else(|e| panic!("{e}"));
    let info = contrail::run_info(&src, &sets, &model);
    (model, info)
}

/// Run into an in-memory MCAP and a `Memory`; return the bytes, the memory and whether the
/// run completed. `extra` sees every call too (it may set `stop`).
fn record(
    model: &Problem,
    info: &RunInfo,
    opts: McapOptions,
    extra: Option<&mut dyn Observer>,
    stop: &AtomicBool,
) -> (Vec<u8>, Memory, bool) {
    let mut sink = McapSink::new(Cursor::new(Vec::new()), "memory", opts).unwrap();
    let mut mem = Memory::default();
    let mut fan = Fanout::default();
    fan.sinks.push(&mut sink);
    fan.sinks.push(&mut mem);
    if let Some(e) = extra {
        fan.sinks.push(e);
    }
    let ok = run(model, info, &mut fan, stop).is_ok();
    drop(fan);
    (sink.into_inner().unwrap().into_inner(), mem, ok)
}

fn same(a: f64, b: f64) -> bool {
    a == b || (a.is_nan() && b.is_nan())
}

fn same_point(a: &ContactPointRecord, b: &ContactPointRecord) -> bool {
    let pairs = |x: [f64; 2], y: [f64; 2]| same(x[0], y[0]) && same(x[1], y[1]);
    a.pair == b.pair
        && a.slave == b.slave
        && a.slave_label == b.slave_label
        && a.segment == b.segment
        && a.previous_segment == b.previous_segment
        && same(a.xi, b.xi)
        && same(a.xi_anchor, b.xi_anchor)
        && same(a.gap, b.gap)
        && same(a.normal_force, b.normal_force)
        && same(a.trial_traction, b.trial_traction)
        && same(a.traction, b.traction)
        && a.state == b.state
        && a.crossing == b.crossing
        && pairs(a.position, b.position)
        && pairs(a.contact_point, b.contact_point)
        && pairs(a.normal, b.normal)
        && pairs(a.tangent, b.tangent)
}

#[test]
fn a_recording_reads_back_to_what_the_solver_reported() {
    let (model, info) = load("crossing", &[]);
    let opts = McapOptions {
        positions_every: 7,
        ..McapOptions::default()
    };
    let (bytes, mem, ok) = record(&model, &info, opts, None, &AtomicBool::new(false));
    assert!(ok);
    let r = Recording::from_bytes(&bytes, "crossing.mcap").unwrap();
    assert_eq!(r.scene(), "crossing");
    assert_eq!(r.metadata["crate_version"], contrail::VERSION);
    assert_eq!(r.metadata["git_revision"], contrail::GIT_REVISION);
    assert_eq!(r.scene_file.as_ref().unwrap().1, info.scene_text);
    assert_eq!(r.model.nodes, model.model.nodes);
    assert_eq!(r.increments.len(), mem.increments.len());
    assert_eq!(r.iterations.len(), mem.iterations.len());
    for (a, b) in r.increments.iter().zip(&mem.increments) {
        assert_eq!(
            (a.increment, a.iterations, a.cutbacks),
            (b.increment, b.iterations, b.cutbacks)
        );
        assert_eq!(a.t, b.t);
        assert_eq!(a.residuals, b.residuals);
    }
    assert_restored(&r, &mem.contact);
    assert_eq!(r.crossings.len(), mem.crossings.len());
    for (a, (inc, b)) in r.crossings.iter().zip(&mem.crossings) {
        assert_eq!(a.increment, *inc);
        assert_eq!(
            (a.crossing.from_segment, a.crossing.to_segment),
            (b.from_segment, b.to_segment)
        );
        assert!(same(a.crossing.trial_after, b.trial_after));
    }
    assert_eq!(r.logs.len(), mem.logs.len());
    assert_eq!(r.outcome, mem.outcome);
    let n = r.increments.len();
    let expected: Vec<usize> = (1..=n).filter(|i| i % 7 == 0 || *i == n).collect();
    let got: Vec<usize> = r.positions.iter().map(|p| p.increment).collect();
    assert_eq!(got, expected, "positions every 7th increment and the last");
    let last = r.positions.last().unwrap();
    for (i, x) in model.model.nodes.iter().enumerate() {
        assert_eq!(
            last.nodes[i],
            [x[0] + mem.final_u[2 * i], x[1] + mem.final_u[2 * i + 1]]
        );
    }
    let s = inspect(&r);
    assert_eq!(
        (s.status.as_str(), s.increments, s.crossings),
        ("completed", n, mem.crossings.len())
    );
    let d = diff(&r, &r, Align::Increment, 0.0).unwrap();
    assert!(d.within_tolerance);
    assert!(d
        .fields
        .iter()
        .all(|f| f.compared > 0 && f.beyond_tolerance == 0 && f.max_abs == 0.0));
}

/// A block held 0.1 above a rigid plane: its contact points stay open (NaN anchor ξ).
const HOVERING: &str = r#"
name = "hovering"
[[body]]
name = "block"
material = { model = "neo-hookean", young = 1.0e3, poisson = 0.3 }
mesh = { kind = "rectangle", origin = [0.0, 0.1], size = [1.0, 0.5], elements = [2, 1] }
[[fix]]
body = "block"
nodes = "top"
components = ["x", "y"]
[[rigid]]
name = "plane"
polyline = [[3.0, 0.0], [-2.0, 0.0]]
[[contact]]
name = "base"
slave = { body = "block", nodes = "bottom" }
master = { rigid = "plane" }
eps_n = 1.0e4
eps_t = 1.0e3
mu = 0.3
[stepping]
end = 1.0
increments = 3
"#;

#[test]
fn non_finite_values_are_written_as_strings_and_read_back() {
    let src = contrail::scene::SceneSource {
        origin: "hovering.toml".into(),
        text: HOVERING.into(),
    };
    let file = contrail::scene::parse(&src, &[]).unwrap_or_else(|e| panic!("{e}"));
    let model = contrail::scene::build(&src, &file).unwrap_or_else(|e| panic!("{e}"));
    let info = contrail::run_info(&src, &[], &model);
    let (bytes, mem, ok) = record(&model, &info, McapOptions::default(), None, &AtomicBool::new(false));
    assert!(ok);
    let mut nan_strings = 0;
    for m in mcap::MessageStream::new(&bytes).unwrap() {
        let m = m.unwrap();
        let text = std::str::from_utf8(&m.data).unwrap();
        if m.channel.topic == "/contact" {
            // format 3: every field an array; only segment ids may be null (none within reach)
            let v: serde_json::Value = serde_json::from_str(text).unwrap();
            for (k, x) in v.as_object().unwrap() {
                let values = x.as_array().map_or_else(|| vec![x.clone()], |a| a.clone());
                let flat: Vec<_> = (values.iter())
                    .flat_map(|y| y.as_array().cloned().unwrap_or_else(|| vec![y.clone()]))
                    .collect();
                assert!(
                    flat.iter().all(|y| !y.is_null()) || k.ends_with("segment"),
                    "{k} has a null: NaN must be a string"
                );
            }
        }
        nan_strings += text.matches("\"NaN\"").count();
    }
    assert!(nan_strings > 0);
    let r = Recording::from_bytes(&bytes, "strip.mcap").unwrap();
    let mut nan_read = 0;
    for (inc, points) in r.increments.iter().zip(&mem.contact) {
        for (a, b) in r.contact_at(inc.increment).iter().zip(points) {
            assert!(same_point(a, b), "increment {}: {a:?} != {b:?}", inc.increment);
            nan_read += (a.xi.is_nan() || a.xi_anchor.is_nan()) as usize;
        }
    }
    assert!(nan_read > 0);
}

/// Sets the stop flag after `after` Newton iterations (as Ctrl-C does).
struct StopAfter<'a> {
    after: usize,
    seen: usize,
    stop: &'a AtomicBool,
}

impl Observer for StopAfter<'_> {
    fn iteration(&mut self, _r: &IterationRecord) -> Result<(), ObserverError> {
        self.seen += 1;
        if self.seen >= self.after {
            self.stop.store(true, Ordering::SeqCst);
        }
        Ok(())
    }
}

#[test]
fn an_interrupted_run_leaves_a_complete_recording_that_says_so() {
    let (model, info) = load("block-slide", &[]);
    let stop = AtomicBool::new(false);
    let mut stopper = StopAfter {
        after: 40,
        seen: 0,
        stop: &stop,
    };
    let (bytes, mem, ok) = record(&model, &info, McapOptions::default(), Some(&mut stopper), &stop);
    assert!(!ok);
    let r = Recording::from_bytes(&bytes, "interrupted.mcap").unwrap();
    assert!(
        matches!(r.outcome, Some(Outcome::Interrupted { .. })),
        "{:?}",
        r.outcome
    );
    assert_eq!(r.outcome, mem.outcome);
    assert_eq!(r.iterations.len(), 40);
    assert!(r.logs.last().unwrap().message.contains("interrupted"));
    let last = mcap::MessageStream::new(&bytes).unwrap().last().unwrap().unwrap();
    assert_eq!(last.channel.topic, "/outcome");
    assert_eq!(inspect(&r).status, "interrupted");
}

#[test]
fn a_failed_run_records_where_and_why_with_the_failed_iterations() {
    let (model, info) = load(
        "strip-channel",
        &[
            "solver.max_iterations=2",
            "stepping.max_cutbacks=1",
            "stepping.end=0.05",
        ],
    );
    let (bytes, _, ok) = record(&model, &info, McapOptions::default(), None, &AtomicBool::new(false));
    assert!(!ok, "the run was meant to fail");
    let r = Recording::from_bytes(&bytes, "failed.mcap").unwrap();
    let Some(Outcome::Failed {
        increment, residuals, ..
    }) = &r.outcome
    else {
        panic!("{:?}", r.outcome)
    };
    let failed: Vec<_> = r.iterations.iter().filter(|i| i.increment == *increment).collect();
    assert!(
        !failed.is_empty(),
        "the failed increment's Newton iterations are recorded"
    );
    assert!(failed.iter().any(|i| i.attempt == 1), "its cut-back attempt too");
    assert!(!residuals.is_empty());
    let s = inspect(&r);
    assert_eq!(s.status, "failed");
    assert!(s.first_failure.is_some_and(|f| f <= *increment));
    assert!(s.errors >= 1);
    let last = mcap::MessageStream::new(&bytes).unwrap().last().unwrap().unwrap();
    assert_eq!(last.channel.topic, "/outcome");
}

#[test]
fn the_rerun_file_of_a_run_and_of_its_replay_are_written() {
    let dir = std::env::temp_dir().join(format!("contrail-rerun-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let (model, info) = load("crossing", &[]);
    let live = dir.join("live.rrd");
    let stream = rerun_sink::open(
        &RerunTargets {
            save: Some(live.clone()),
            ..RerunTargets::default()
        },
        "crossing",
        2,
    )
    .unwrap();
    let mut rr = RerunSink::new(stream, "rerun");
    let (bytes, _, ok) = record(
        &model,
        &info,
        McapOptions::default(),
        Some(&mut rr),
        &AtomicBool::new(false),
    );
    assert!(ok);
    let r = Recording::from_bytes(&bytes, "crossing.mcap").unwrap();
    let replayed = dir.join("replay.rrd");
    let stream = rerun_sink::open(
        &RerunTargets {
            save: Some(replayed.clone()),
            ..RerunTargets::default()
        },
        "crossing",
        2,
    )
    .unwrap();
    let mut view = RerunView::new(stream, &r.model).unwrap();
    for inc in &r.increments {
        view.increment(inc, None, r.contact_at(inc.increment), &[]).unwrap();
    }
    view.finish().unwrap();
    for f in [&live, &replayed] {
        let b = std::fs::read(f).unwrap();
        assert!(
            b.len() > 1000 && b.starts_with(b"RRF"),
            "{}: {} bytes",
            f.display(),
            b.len()
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// The points written on `/contact` (format 3: the entries of the messages' `slave` arrays).
fn written_points(bytes: &[u8]) -> usize {
    mcap::MessageStream::new(bytes)
        .unwrap()
        .map(|m| m.unwrap())
        .filter(|m| m.channel.topic == "/contact")
        .map(|m| {
            let v: serde_json::Value = serde_json::from_slice(&m.data).unwrap();
            v["slave"].as_array().unwrap().len()
        })
        .sum()
}

/// Every point of `r` as the solver made it (`solver`, per increment), but that a slave out
/// of reach at an increment without `/positions` has no position there (its record is its
/// position, which is not kept there); returns how many such points there are.
fn assert_restored(r: &Recording, solver: &[Vec<ContactPointRecord>]) -> usize {
    let mut unkept = 0;
    assert_eq!(r.increments.len(), solver.len());
    for (inc, points) in r.increments.iter().zip(solver) {
        let got = r.contact_at(inc.increment);
        assert_eq!(got.len(), points.len(), "increment {}", inc.increment);
        let has_positions = r.positions.iter().any(|p| p.increment == inc.increment);
        for (a, b) in got.iter().zip(points) {
            if !has_positions && b.segment.is_none() && a.position.iter().all(|x| x.is_nan()) {
                unkept += 1;
                let kept = ContactPointRecord {
                    position: b.position,
                    ..a.clone()
                };
                assert!(same_point(&kept, b), "increment {}: {a:?} != {b:?}", inc.increment);
                continue;
            }
            assert!(same_point(a, b), "increment {}: {a:?} != {b:?}", inc.increment);
        }
    }
    unkept
}

/// With `--positions-every 7` the strip's slaves that stay out of reach are left out at the
/// increments without `/positions` too: read back, they are there, as the solver made them
/// but for their position (NaN), and the file is smaller than with positions at every
/// increment thinned alike.
#[test]
fn points_out_of_reach_are_left_out_where_no_positions_are_kept() {
    let (model, info) = load("strip-channel", &["stepping.increments=4800", "stepping.end=0.05"]);
    let stop = AtomicBool::new(false);
    let every_7 = McapOptions {
        positions_every: 7,
        ..McapOptions::default()
    };
    let (bytes, mem, ok) = record(&model, &info, every_7, None, &stop);
    assert!(ok);
    let r = Recording::from_bytes(&bytes, "every-7.mcap").unwrap();
    let unkept = assert_restored(&r, &mem.contact);
    let out_of_reach: usize = (mem.contact.iter().flatten()).filter(|p| p.segment.is_none()).count();
    println!("{unkept} of {out_of_reach} records out of reach read back without a position");
    assert!(
        unkept * 2 > out_of_reach,
        "most of them lie between the increments with positions"
    );
    let all_points = McapOptions {
        positions_every: 7,
        thin_out_of_reach: false,
        ..McapOptions::default()
    };
    let (bytes_all, _, _) = record(&model, &info, all_points, None, &stop);
    assert!(bytes.len() < bytes_all.len());
}

/// Format versions 2 and 3 leave out the `/contact` entries of slave nodes that stay out of
/// reach (`mcap_sink::OutOfReach`): the strip-channel has many (the strip's nodes far from
/// the block). Read back, every point of every increment is there again, bit for bit, and
/// the recording is the one written without thinning, point for point.
#[test]
fn points_out_of_reach_are_left_out_and_restored_bit_for_bit() {
    let (model, info) = load("strip-channel", &["stepping.increments=4800", "stepping.end=0.05"]);
    let thinned = McapOptions::default();
    assert!(thinned.thin_out_of_reach, "thinning is the default");
    let every = McapOptions {
        thin_out_of_reach: false,
        ..McapOptions::default()
    };
    let stop = AtomicBool::new(false);
    let (bytes, mem, ok) = record(&model, &info, thinned, None, &stop);
    let (bytes_all, _, ok_all) = record(&model, &info, every, None, &stop);
    assert!(ok && ok_all);
    let r = Recording::from_bytes(&bytes, "thinned.mcap").unwrap();
    let r_all = Recording::from_bytes(&bytes_all, "every.mcap").unwrap();
    let all: usize = mem.contact.iter().map(Vec::len).sum();
    let written = written_points(&bytes);
    assert_eq!(written_points(&bytes_all), all);
    let pairs = model.model.contacts.len();
    assert_eq!(
        r.message_counts["/contact"] as usize,
        pairs * r.increments.len(),
        "one /contact message per increment and pair"
    );
    assert!(
        written * 2 < all,
        "{written} of {all} /contact messages written: expected most out-of-reach points left out"
    );
    assert!(bytes.len() < bytes_all.len());
    assert_eq!(r.increments.len(), mem.contact.len());
    for (inc, points) in r.increments.iter().zip(&mem.contact) {
        let got = r.contact_at(inc.increment);
        assert_eq!(got.len(), points.len(), "increment {}", inc.increment);
        for (a, b) in got.iter().zip(points) {
            assert!(same_point(a, b), "increment {}: {a:?} != {b:?}", inc.increment);
        }
        for (a, b) in got.iter().zip(r_all.contact_at(inc.increment)) {
            assert!(same_point(a, b), "increment {}: {a:?} != {b:?}", inc.increment);
        }
    }
}
