//! Fuzzing the recording reader (issue 10): a small real recording is damaged by byte flips,
//! truncations, zeroed ranges, appended junk, and mutated JSON inside a file with valid CRCs;
//! reading it must end (within a time limit) in a recording or an error — never a panic or a
//! hang — and a recording that reads must survive `inspect`, `diff` against itself and a
//! replay into a rerun stream, and `recover` must not panic either.
//!
//! CI runs a bounded number of cases (64 per property); a long run:
//! `CONTRAIL_FUZZ_CASES=20000 cargo test --release --test fuzz_recordings`.

use contrail::analysis::diff::{diff, Align};
use contrail::analysis::inspect::{inspect, render};
use contrail::analysis::recording::Recording;
use contrail::analysis::recover::recover;
use contrail::record::mcap_sink::{McapOptions, McapSink};
use contrail::record::rerun_sink::RerunView;
use contrail::record::schemas::{self, CHANNELS};
use proptest::prelude::*;
use std::collections::{BTreeMap, HashMap};
use std::io::Cursor;
use std::sync::atomic::AtomicBool;
use std::sync::{mpsc, OnceLock};
use std::time::Duration;

fn cases() -> u32 {
    std::env::var("CONTRAIL_FUZZ_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(64)
}

/// The recording every case starts from (crossing, 12 increments).
fn base() -> &'static [u8] {
    static B: OnceLock<Vec<u8>> = OnceLock::new();
    B.get_or_init(|| {
        let sets = vec!["stepping.increments=12".to_string(), "stepping.end=0.3".into()];
        let (src, model) = contrail::load_scene("crossing", &sets).unwrap();
        let info = contrail::run_info(&src, &sets, &model);
        let opts = McapOptions::default();
        let mut sink = McapSink::new(Cursor::new(Vec::new()), "memory", opts).unwrap();
        let _ = contrail::solver::run(&model, &info, &mut sink, &AtomicBool::new(false));
        sink.into_inner().unwrap().into_inner()
    })
}

/// The messages of the base recording, (topic, sequence, log time, JSON).
type Messages = Vec<(String, u32, u64, Vec<u8>)>;

fn messages() -> &'static (Messages, BTreeMap<String, String>) {
    static M: OnceLock<(Messages, BTreeMap<String, String>)> = OnceLock::new();
    M.get_or_init(|| {
        let r = Recording::from_bytes(base(), "base").unwrap();
        let mut out = Vec::new();
        for m in mcap::MessageStream::new(base()).unwrap() {
            let m = m.unwrap();
            out.push((m.channel.topic.clone(), m.sequence, m.log_time, m.data.into_owned()));
        }
        (out, r.metadata)
    })
}

/// A recording with valid CRCs whose message `k` has JSON `data`.
fn reencode(k: usize, data: &[u8]) -> Vec<u8> {
    let (msgs, metadata) = messages();
    let mut w = mcap::WriteOptions::new()
        .profile(schemas::PROFILE)
        .create(Cursor::new(Vec::new()))
        .unwrap();
    let mut ids = HashMap::new();
    for c in CHANNELS {
        let s = w
            .add_schema(c.schema_name, "jsonschema", c.schema_text().as_bytes())
            .unwrap();
        ids.insert(
            c.topic.to_string(),
            w.add_channel(s, c.topic, "json", &BTreeMap::new()).unwrap(),
        );
    }
    w.write_metadata(&mcap::records::Metadata {
        name: schemas::METADATA_NAME.into(),
        metadata: metadata.clone(),
    })
    .unwrap();
    for (i, (topic, seq, time, json)) in msgs.iter().enumerate() {
        let header = mcap::records::MessageHeader {
            channel_id: ids[topic],
            sequence: *seq,
            log_time: *time,
            publish_time: *time,
        };
        w.write_to_known_channel(&header, if i == k { data } else { json })
            .unwrap();
    }
    w.finish().unwrap();
    w.into_inner().into_inner()
}

#[derive(Debug, Clone)]
enum Damage {
    Flip {
        at: usize,
        xor: u8,
    },
    Truncate {
        keep: usize,
    },
    Zero {
        at: usize,
        len: usize,
    },
    Append {
        junk: Vec<u8>,
    },
    /// Replace `len` bytes of message `k`'s JSON at `at` by `with` (CRCs stay valid).
    Json {
        k: usize,
        at: usize,
        len: usize,
        with: String,
    },
}

fn damage() -> impl Strategy<Value = Damage> {
    let tokens = prop_oneof![
        Just("-1".to_string()),
        Just("1e308".into()),
        Just("18446744073709551615".into()),
        Just("4294967296".into()),
        Just("null".into()),
        Just("\"NaN\"".into()),
        Just("[]".into()),
        Just("{}".into()),
        Just("0".into()),
        Just("999999".into()),
        Just("\"".into()),
        Just(",".into()),
        "[a-z0-9\\[\\]{}\":,.-]{0,6}",
    ];
    prop_oneof![
        (any::<usize>(), 1..=255u8).prop_map(|(at, xor)| Damage::Flip { at, xor }),
        any::<usize>().prop_map(|keep| Damage::Truncate { keep }),
        (any::<usize>(), 1..64usize).prop_map(|(at, len)| Damage::Zero { at, len }),
        proptest::collection::vec(any::<u8>(), 1..64).prop_map(|junk| Damage::Append { junk }),
        (any::<usize>(), any::<usize>(), 0..8usize, tokens).prop_map(|(k, at, len, with)| Damage::Json {
            k,
            at,
            len,
            with
        }),
    ]
}

fn apply(d: &Damage) -> Vec<u8> {
    let good = base();
    let n = good.len();
    match d {
        Damage::Flip { at, xor } => {
            let mut b = good.to_vec();
            b[at % n] ^= xor;
            b
        }
        Damage::Truncate { keep } => good[..keep % n].to_vec(),
        Damage::Zero { at, len } => {
            let mut b = good.to_vec();
            let at = at % n;
            b[at..(at + len).min(n)].fill(0);
            b
        }
        Damage::Append { junk } => [good, junk.as_slice()].concat(),
        Damage::Json { k, at, len, with } => {
            let (msgs, _) = messages();
            let k = k % msgs.len();
            let mut json = msgs[k].3.clone();
            let at = at % (json.len() + 1);
            let end = (at + len).min(json.len());
            json.splice(at..end, with.bytes());
            reencode(k, &json)
        }
    }
}

/// Everything a reader does with a recording, on another thread, within `secs`.
fn exercise(bytes: Vec<u8>, secs: u64) -> Result<(), String> {
    let (tx, rx) = mpsc::channel();
    std::thread::spawn(move || {
        let outcome = std::panic::catch_unwind(|| {
            let _ = recover(&bytes, "fuzz", Cursor::new(Vec::new()));
            let Ok(r) = Recording::from_bytes(&bytes, "fuzz") else {
                return;
            };
            let _ = render(&inspect(&r));
            let _ = diff(&r, &r, Align::Increment, 1e-6);
            let _ = diff(&r, &r, Align::Load, 1e-6);
            let (stream, _mem) = rerun::RecordingStreamBuilder::new("fuzz").memory().unwrap();
            let Ok(mut view) = RerunView::new(stream, &r.model) else {
                return;
            };
            for i in &r.iterations {
                let _ = view.iteration(i);
            }
            for inc in &r.increments {
                let p = r.positions.iter().find(|p| p.increment == inc.increment);
                let _ = view.increment(inc, p, r.contact_at(inc.increment), &[]);
            }
            for l in &r.logs {
                let _ = view.log(l);
            }
            if let Some(o) = &r.outcome {
                let _ = view.outcome(o);
            }
        });
        let _ = tx.send(outcome.map_err(|_| "panicked".to_string()));
    });
    rx.recv_timeout(Duration::from_secs(secs))
        .map_err(|_| format!("no answer within {secs} s (a hang)"))?
}

proptest! {
    #![proptest_config(ProptestConfig { cases: cases(), failure_persistence: Some(Box::new(proptest::test_runner::FileFailurePersistence::SourceParallel("proptest-regressions"))), ..ProptestConfig::default() })]

    #[test]
    fn damaged_recordings_never_panic_or_hang(d in damage()) {
        let bytes = apply(&d);
        prop_assert!(exercise(bytes, 20).is_ok(), "{:?}", d);
    }

    #[test]
    fn several_damages_at_once(ds in proptest::collection::vec((any::<usize>(), 1..=255u8), 1..16)) {
        let mut b = base().to_vec();
        let n = b.len();
        for (at, xor) in &ds {
            b[at % n] ^= xor;
        }
        prop_assert!(exercise(b, 20).is_ok(), "{:?}", ds);
    }
}
