//! The MCAP writer's CPU on a recorded run, by option: the run is solved once into memory,
//! then its records are written again into an in-memory recording with each set of
//! `McapOptions` (best of 7, one thread: serialisation, chunking and compression, no file
//! I/O), and the time and the size printed. `CASES=default,lz4` picks cases by name.
//!
//! ```sh
//! cargo run --release --example writer_cost -- strip-channel stepping.increments=4800 \
//!     stepping.max_cutbacks=0
//! ```
use contrail::model::Model;
use contrail::record::mcap::sink::{ChunkCompression, McapOptions, McapSink, SceneEvery};
use contrail::record::*;
use std::io::Cursor;
use std::sync::atomic::AtomicBool;
use std::time::Instant;

/// An increment as the sink saw it: its record, displacements, contact points, crossings.
type TapedIncrement = (IncrementRecord, Vec<f64>, Vec<ContactPointRecord>, Vec<CrossingRecord>);

#[derive(Default)]
struct Tape {
    model: Option<Model>,
    info: Option<RunInfo>,
    its: Vec<IterationRecord>,
    incs: Vec<TapedIncrement>,
    order: Vec<bool>, // true = increment
    outcome: Option<Outcome>,
}
impl Observer for Tape {
    fn start(&mut self, m: contrail::model::ModelRef<'_>, i: &RunInfo) -> Result<(), ObserverError> {
        self.model = Some(m.plane().clone());
        self.info = Some(i.clone());
        Ok(())
    }
    fn iteration(&mut self, r: &IterationRecord) -> Result<(), ObserverError> {
        self.its.push(r.clone());
        self.order.push(false);
        Ok(())
    }
    fn increment(&mut self, r: &IncrementRecord, v: &StepView) -> Result<(), ObserverError> {
        self.incs
            .push((r.clone(), v.u.to_vec(), v.contact.to_vec(), v.crossings.to_vec()));
        self.order.push(true);
        Ok(())
    }
    fn finish(&mut self, o: &Outcome) -> Result<(), ObserverError> {
        self.outcome = Some(o.clone());
        Ok(())
    }
}

fn replay(t: &Tape, opts: McapOptions) -> (f64, usize) {
    let start = Instant::now();
    let mut sink = McapSink::new(Cursor::new(Vec::with_capacity(64 << 20)), "m", opts).unwrap();
    let model = t.model.as_ref().unwrap();
    sink.start(model.view(), t.info.as_ref().unwrap()).unwrap();
    let (mut i, mut k) = (0, 0);
    for &inc in &t.order {
        if inc {
            let (r, u, c, x) = &t.incs[k];
            k += 1;
            sink.increment(
                r,
                &StepView {
                    model: model.view(),
                    u,
                    contact: c,
                    crossings: x,
                    surface: &[],
                },
            )
            .unwrap();
        } else {
            sink.iteration(&t.its[i]).unwrap();
            i += 1;
        }
    }
    sink.finish(t.outcome.as_ref().unwrap()).unwrap();
    let n = sink.into_inner().unwrap().into_inner().len();
    (start.elapsed().as_secs_f64(), n)
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let sets: Vec<String> = args[1..].to_vec();
    let (src, problem) = contrail::load_scene(&args[0], &sets).unwrap();
    let info = contrail::run_info(&src, &sets, &problem);
    let mut tape = Tape::default();
    let _ = contrail::solver::run(&problem, &info, &mut tape, &AtomicBool::new(false));
    let cases: Vec<(&str, McapOptions)> = vec![
        ("default", McapOptions::default()),
        (
            "scene off",
            McapOptions {
                scene: SceneEvery::Off,
                ..McapOptions::default()
            },
        ),
        (
            "scene every 1",
            McapOptions {
                scene: SceneEvery::Every(1),
                ..McapOptions::default()
            },
        ),
        (
            "no compression",
            McapOptions {
                compression: ChunkCompression::None,
                ..McapOptions::default()
            },
        ),
        (
            "lz4",
            McapOptions {
                compression: ChunkCompression::Lz4,
                ..McapOptions::default()
            },
        ),
        (
            "zstd 3",
            McapOptions {
                compression_level: 3,
                ..McapOptions::default()
            },
        ),
        (
            "zstd -1",
            McapOptions {
                compression_level: -1,
                ..McapOptions::default()
            },
        ),
        (
            "no index",
            McapOptions {
                message_indexes: false,
                ..McapOptions::default()
            },
        ),
        (
            "all points",
            McapOptions {
                thin_out_of_reach: false,
                ..McapOptions::default()
            },
        ),
        (
            "failed its",
            McapOptions {
                iterations: contrail::record::mcap::sink::Iterations::Failed,
                ..McapOptions::default()
            },
        ),
        (
            "bare",
            McapOptions {
                compression: ChunkCompression::None,
                message_indexes: false,
                scene: SceneEvery::Off,
                ..McapOptions::default()
            },
        ),
    ];
    let cases: Vec<(&str, McapOptions)> = match std::env::var("CASES") {
        Ok(w) => cases
            .into_iter()
            .filter(|(n, _)| w.split(',').any(|x| x == *n))
            .collect(),
        Err(_) => cases,
    };
    let mut best = vec![f64::MAX; cases.len()];
    let mut size = vec![0; cases.len()];
    for _ in 0..7 {
        for (k, (_, o)) in cases.iter().enumerate() {
            let (t, n) = replay(&tape, o.clone());
            best[k] = best[k].min(t);
            size[k] = n;
        }
    }
    for (k, (name, _)) in cases.iter().enumerate() {
        println!("{name:16} {:7.1} ms  {:6.2} MB", best[k] * 1e3, size[k] as f64 / 1e6);
    }
}
