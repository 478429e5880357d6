//! Cross-check of the `/contact` and `/crossing` channels of an MCAP recording: every
//! crossing event has a `/contact` record of the same point in the same increment with
//! `crossing == true`, `previous_segment == from_segment` and `segment == to_segment`, and
//! no `/contact` record claims a crossing that `/crossing` does not have.
//!
//! Scenes: `crossing` (a rigid point dragged across three segment boundaries in stick) and
//! `block-slide`. On the code before the contact refactor the previous segment is read after
//! the history is committed, so `/contact` never showed a crossing (fixed: the records are
//! taken before the commit).

use contrail::analysis::recording::Recording;
use contrail::record::mcap::sink::{McapOptions, McapSink};
use std::io::Cursor;
use std::sync::atomic::AtomicBool;

fn record(scene: &str, sets: &[&str]) -> Recording {
    let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
    let (src, model) = contrail::load_scene(scene, &sets).unwrap_or_else(|e| panic!("{e}"));
    let info = contrail::run_info(&src, &sets, &model);
    let mut buf = Cursor::new(Vec::new());
    {
        let mut sink = McapSink::new(&mut buf, "test.mcap", McapOptions::default()).unwrap();
        let _ = contrail::solver::run(&model, &info, &mut sink, &AtomicBool::new(false));
    }
    Recording::from_bytes(buf.get_ref(), &format!("{scene}.mcap")).unwrap_or_else(|e| panic!("{e}"))
}

fn check(r: &Recording) -> usize {
    for c in &r.crossings {
        let x = &c.crossing;
        let point = r
            .contact_at(c.increment)
            .iter()
            .find(|p| p.pair == x.pair && p.slave == x.slave)
            .unwrap_or_else(|| {
                panic!(
                    "{}: no /contact record for the crossing in increment {}",
                    r.path, c.increment
                )
            });
        assert!(
            point.crossing,
            "{}: increment {}: /crossing {} → {} but /contact says crossing = false (segment {:?}, previous {:?})",
            r.path, c.increment, x.from_segment, x.to_segment, point.segment, point.previous_segment
        );
        assert_eq!(
            point.previous_segment,
            Some(x.from_segment),
            "{}: increment {}",
            r.path,
            c.increment
        );
        assert_eq!(
            point.segment,
            Some(x.to_segment),
            "{}: increment {}",
            r.path,
            c.increment
        );
    }
    for (inc, points) in &r.contact {
        for p in points.iter().filter(|p| p.crossing) {
            assert!(
                r.crossings
                    .iter()
                    .any(|c| c.increment == *inc && c.crossing.pair == p.pair && c.crossing.slave == p.slave),
                "{}: increment {inc}: /contact claims a crossing of {} that /crossing does not have",
                r.path,
                p.slave_label
            );
        }
    }
    r.crossings.len()
}

#[test]
fn every_crossing_event_has_a_matching_contact_record() {
    let r = record("crossing", &[]);
    assert_eq!(check(&r), 3, "the crossing scene crosses three boundaries");
    for scheme in ["straightforward", "path-length"] {
        let r = record("crossing", &[&format!("contact.transfer={scheme}")]);
        assert_eq!(check(&r), 3, "{scheme}");
    }
    check(&record("block-slide", &[]));
}
