//! The readers give the same answers on every recording format: the golden recordings
//! checked in before format 3 existed (`recordings/golden/*.mcap`, format 1: every contact
//! point of every increment; `recordings/golden/format2/strip-channel.mcap`, format 2: slave
//! nodes out of reach left out, written by contrail 0b42312) and the same runs written in
//! format 3 (by `contrail convert`, through the MCAP sink's own writer) give identical
//! `inspect` and `diff` results and the same records, bit for bit.
//!
//! The format-3 goldens in `recordings/golden/format3/` are runs of the current solver (see
//! `tests/recording_golden.rs`), not conversions of these files, so the comparison is made
//! with conversions written in memory.

use contrail::analysis::convert::{convert, ConvertOptions};
use contrail::analysis::diff::{diff, Align};
use contrail::analysis::inspect::inspect;
use contrail::analysis::recording::Recording;
use contrail::record::mcap::out::{ChunkCompression, Compression};
use contrail::record::mcap::sink::SceneEvery;
use std::io::Cursor;
use std::path::PathBuf;

/// The recordings of older formats (path under `recordings/golden`, format version).
const OLDER: [(&str, &str); 4] = [
    ("crossing.mcap", "1"),
    ("block-slide.mcap", "1"),
    ("strip-channel.mcap", "1"),
    ("format2/strip-channel.mcap", "2"),
];

fn golden(name: &str) -> Recording {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("recordings/golden")
        .join(name);
    Recording::open(&path).unwrap_or_else(|e| panic!("{e}"))
}

/// `r` written in format 3, read back.
fn in_format_3(r: &Recording) -> Recording {
    let opts = ConvertOptions {
        compression: Compression {
            kind: ChunkCompression::Zstd,
            zstd_level: 19,
        },
        message_indexes: false,
        scene: SceneEvery::Auto,
    };
    let (out, _) = convert(r, Cursor::new(Vec::new()), &opts).unwrap();
    Recording::from_bytes(&out.into_inner(), &r.path).unwrap_or_else(|e| panic!("{e}"))
}

/// The report without what describes the file rather than the run (size, chunks, message
/// counts, writer and format).
fn run_part(r: &Recording) -> serde_json::Value {
    let mut v = serde_json::to_value(inspect(r)).unwrap();
    let m = v.as_object_mut().unwrap();
    for k in [
        "file",
        "size_bytes",
        "bytes_per_increment",
        "writer",
        "format_version",
        "message_counts",
        "chunks",
    ] {
        assert!(m.remove(k).is_some(), "inspect has no `{k}` any more");
    }
    v
}

fn json<T: serde::Serialize + ?Sized>(x: &T) -> String {
    serde_json::to_string(x).unwrap()
}

/// Every record of the two recordings, compared as JSON text (NaN and every bit included).
fn same_records(a: &Recording, b: &Recording) {
    assert_eq!(json(&a.model), json(&b.model));
    assert_eq!(json(&a.increments), json(&b.increments));
    assert_eq!(json(&a.iterations), json(&b.iterations));
    assert_eq!(json(&a.crossings), json(&b.crossings));
    assert_eq!(json(&a.positions), json(&b.positions));
    assert_eq!(json(&a.logs), json(&b.logs));
    assert_eq!(json(&a.outcome), json(&b.outcome));
    assert_eq!(json(&a.pressure), json(&b.pressure));
    assert_eq!(a.contact.len(), b.contact.len());
    for (inc, points) in &a.contact {
        assert_eq!(
            json(points),
            json(b.contact_at(*inc)),
            "contact points of increment {inc}"
        );
    }
}

#[test]
fn recordings_of_formats_1_and_2_and_the_same_runs_in_format_3_give_identical_answers() {
    for (name, version) in OLDER {
        let r2 = golden(name);
        assert_eq!(r2.metadata["format_version"], version, "{name}");
        let r3 = in_format_3(&r2);
        assert_eq!(r3.metadata["format_version"], "3", "{name}");
        assert!(r3.message_counts.contains_key("/foxglove/scene"), "{name}");
        same_records(&r2, &r3);
        assert_eq!(run_part(&r2), run_part(&r3), "{name}: inspect");
        // each against itself, and against each other
        let own = |r: &Recording| {
            let d = diff(r, r, Align::Increment, 1e-6).unwrap();
            let mut v = serde_json::to_value(&d).unwrap();
            v["a"]["file"] = "A".into();
            v["b"]["file"] = "B".into();
            v
        };
        assert_eq!(own(&r2), own(&r3), "{name}: diff");
        let d = diff(&r2, &r3, Align::Increment, 0.0).unwrap();
        assert!(d.within_tolerance, "{name}");
        assert_eq!(d.matched_increments, r2.increments.len());
        for f in &d.fields {
            assert_eq!((f.beyond_tolerance, f.max_abs), (0, 0.0), "{name}: {}", f.field);
        }
        let by_load = diff(&r3, &r2, Align::Load, 0.0).unwrap();
        assert!(by_load.within_tolerance, "{name}");
    }
}
