//! Fuzzing the recording reader (issue 10): a small real recording — one written now (format
//! 3: `/contact` and `/pressure` as arrays, Foxglove channels) and one of format 2 (slave
//! nodes out of reach left out) — is damaged by byte flips, truncations, zeroed ranges,
//! appended junk, and mutated JSON inside a file with valid CRCs;
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
use contrail::record::mcap::schemas;
use contrail::record::mcap::sink::{McapOptions, McapSink};
use contrail::record::rrd::sink::RerunView;
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

/// The recordings the cases start from: 0 written now (format 3; the strip-channel pulled
/// down by 0.1 in 12 increments: contact points within and out of reach, pressure profiles,
/// Foxglove scenes), 1 of format 2 (`recordings/golden/format2/`).
fn bases() -> &'static [Vec<u8>; 2] {
    static B: OnceLock<[Vec<u8>; 2]> = OnceLock::new();
    B.get_or_init(|| {
        let sets = vec!["stepping.increments=12".to_string(), "fix.1.value=-0.1".into()];
        let (src, model) = contrail::load_scene("strip-channel", &sets).unwrap();
        let info = contrail::run_info(&src, &sets, &model);
        let opts = McapOptions::default();
        let mut sink = McapSink::new(Cursor::new(Vec::new()), "memory", opts).unwrap();
        let _ = contrail::solver::run(&model, &info, &mut sink, &AtomicBool::new(false));
        let now = sink.into_inner().unwrap().into_inner();
        let path = concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/recordings/golden/format2/strip-channel.mcap"
        );
        let older = std::fs::read(path).unwrap();
        assert_eq!(
            Recording::from_bytes(&older, "f2").unwrap().metadata["format_version"],
            "2"
        );
        [now, older]
    })
}

fn base(b: usize) -> &'static [u8] {
    &bases()[b % 2]
}

/// A message of a base recording: topic, schema (name and text), sequence, log time, JSON.
struct Message {
    topic: String,
    schema: (String, Vec<u8>),
    sequence: u32,
    log_time: u64,
    data: Vec<u8>,
}

/// A base recording's messages and its metadata.
type Base = (Vec<Message>, BTreeMap<String, String>);

fn messages(b: usize) -> &'static Base {
    static M: OnceLock<[Base; 2]> = OnceLock::new();
    let all = M.get_or_init(|| {
        [0, 1].map(|b| {
            let r = Recording::from_bytes(base(b), "base").unwrap();
            let mut out = Vec::new();
            for m in mcap::MessageStream::new(base(b)).unwrap() {
                let m = m.unwrap();
                let schema = m.channel.schema.as_ref().unwrap();
                out.push(Message {
                    topic: m.channel.topic.clone(),
                    schema: (schema.name.clone(), schema.data.to_vec()),
                    sequence: m.sequence,
                    log_time: m.log_time,
                    data: m.data.into_owned(),
                });
            }
            (out, r.metadata)
        })
    });
    &all[b % 2]
}

/// A recording with valid CRCs (and the schemas of base `b`) whose message `k` has JSON `data`.
fn reencode(b: usize, k: usize, data: &[u8]) -> Vec<u8> {
    let (msgs, metadata) = messages(b);
    let mut w = mcap::WriteOptions::new()
        .profile(schemas::PROFILE)
        .create(Cursor::new(Vec::new()))
        .unwrap();
    let mut ids = HashMap::new();
    for m in msgs {
        if ids.contains_key(&m.topic) {
            continue;
        }
        let s = w.add_schema(&m.schema.0, "jsonschema", &m.schema.1).unwrap();
        ids.insert(
            m.topic.clone(),
            w.add_channel(s, &m.topic, "json", &BTreeMap::new()).unwrap(),
        );
    }
    w.write_metadata(&mcap::records::Metadata {
        name: schemas::METADATA_NAME.into(),
        metadata: metadata.clone(),
    })
    .unwrap();
    for (i, m) in msgs.iter().enumerate() {
        let header = mcap::records::MessageHeader {
            channel_id: ids[&m.topic],
            sequence: m.sequence,
            log_time: m.log_time,
            publish_time: m.log_time,
        };
        w.write_to_known_channel(&header, if i == k { data } else { &m.data })
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

fn apply(b: usize, d: &Damage) -> Vec<u8> {
    let good = base(b);
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
            let (msgs, _) = messages(b);
            let k = k % msgs.len();
            let mut json = msgs[k].data.clone();
            let at = at % (json.len() + 1);
            let end = (at + len).min(json.len());
            json.splice(at..end, with.bytes());
            reencode(b, k, &json)
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
    fn damaged_recordings_never_panic_or_hang(b in 0..2usize, d in damage()) {
        let bytes = apply(b, &d);
        prop_assert!(exercise(bytes, 20).is_ok(), "base {b}: {:?}", d);
    }

    #[test]
    fn several_damages_at_once(b in 0..2usize, ds in proptest::collection::vec((any::<usize>(), 1..=255u8), 1..16)) {
        let mut bytes = base(b).to_vec();
        let n = bytes.len();
        for (at, xor) in &ds {
            bytes[at % n] ^= xor;
        }
        prop_assert!(exercise(bytes, 20).is_ok(), "base {b}: {:?}", ds);
    }

    /// Format 3 only: the arrays of `/contact` and `/pressure` made ragged, indices out of
    /// range, or other types, in a file with valid CRCs.
    #[test]
    fn damaged_arrays_are_errors_not_panics(k in any::<usize>(), field in 0..20usize, edit in 0..4usize) {
        let (msgs, _) = messages(0);
        let arrays: Vec<usize> = (0..msgs.len())
            .filter(|&i| msgs[i].topic == "/contact" || msgs[i].topic == "/pressure")
            .collect();
        let k = arrays[k % arrays.len()];
        let mut v: serde_json::Value = serde_json::from_slice(&msgs[k].data).unwrap();
        let obj = v.as_object_mut().unwrap();
        let key = obj.keys().nth(field % obj.len()).unwrap().clone();
        let x = &mut obj[&key];
        match (edit, x.as_array_mut()) {
            (0, Some(a)) => { a.pop(); }
            (1, Some(a)) => a.push(serde_json::json!(4_000_000_000u64)),
            (2, _) => *x = serde_json::json!(9_999_999),
            _ => *x = serde_json::json!([null, "NaN", {}]),
        }
        let bytes = reencode(0, k, &serde_json::to_vec(&v).unwrap());
        prop_assert!(exercise(bytes, 20).is_ok(), "{key} edit {edit}");
    }
}
