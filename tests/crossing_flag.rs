//! The `crossing` flag of `/contact` and the `/crossing` events mean what the schema says.
//!
//! Definition (contact.schema.json, docs/recording.md): a point is *crossing* at an increment
//! when it is closed there and was closed at the last converged increment, on another
//! segment — the crossings that carry friction history (seed §3), one `/crossing` event
//! each. A point that closes on another segment than the one it was tracked on while open
//! is not crossing (it has no history to carry), nor is a point that opens.
//! Asserted on every point of every increment of the capstan over a polygon (belt nodes
//! slide over its vertices), of the seed's strip (its corner C crosses the strip's face,
//! strip nodes close on the channel wall) and of the `crossing` scene (a point dragged
//! across unequal segments in stick), both ways after the first increment: the flag implies the
//! definition and the definition the flag, and the events are the flagged points; at the
//! first increment (from the initial configuration, whose states are not recorded) the flag
//! implies a closed point on another segment.
mod common;

use contrail::contact::law::ContactState;

fn check(scene: &str, sets: &[&str]) -> (usize, usize) {
    let p = common::scene(scene, sets);
    let (_, m) = common::solve_ok(&p);
    let (mut flagged, mut first_touch_elsewhere) = (0, 0);
    let closed = |p: &contrail::record::ContactPointRecord| p.state != ContactState::Open;
    // the first increment, from the initial configuration (whose states are not recorded):
    // a flag is a closed point on another segment; a closed point on another segment
    // without the flag closed there for the first time
    for b in &m.contact[0] {
        let moved = b.previous_segment.is_some() && b.previous_segment != b.segment;
        assert!(!b.crossing || (closed(b) && moved), "{scene}, first increment: {b:?}");
        first_touch_elsewhere += usize::from(closed(b) && moved && !b.crossing);
    }
    for (k, pair) in m.contact.windows(2).enumerate() {
        let (before, now) = (&pair[0], &pair[1]);
        let increment = m.increments[k + 1].increment;
        for (a, b) in before.iter().zip(now) {
            assert_eq!((a.pair, a.slave), (b.pair, b.slave));
            let moved = a.segment != b.segment;
            let expected = closed(a) && closed(b) && moved;
            assert_eq!(b.crossing, expected, "{scene}, increment {increment}: {a:?} then {b:?}");
            assert_eq!(b.previous_segment, a.segment, "{scene}, increment {increment}");
            flagged += usize::from(b.crossing);
            first_touch_elsewhere += usize::from(!closed(a) && closed(b) && moved && a.segment.is_some());
            let event = (m.crossings.iter()).any(|(i, c)| *i == increment && c.pair == b.pair && c.slave == b.slave);
            assert_eq!(
                event, b.crossing,
                "{scene}, increment {increment}: the event and the flag"
            );
        }
    }
    (flagged, first_touch_elsewhere)
}

#[test]
fn the_crossing_flag_is_a_closed_point_changing_segment() {
    let (flagged, _) = check("capstan-polygon", &[]);
    println!("capstan-polygon: {flagged} crossings");
    assert!(flagged > 0);
    // the strip's corner C crosses the face's segments, and a strip node closes on the
    // block's wall after being tracked open on its top face (2026-11-27: 11 and 1)
    let (flagged, elsewhere) = check("strip-channel", &[]);
    println!("strip-channel: {flagged} crossings, {elsewhere} first touches on another segment");
    assert!(flagged > 0 && elsewhere > 0, "both cases met: {flagged}, {elsewhere}");
    let (flagged, _) = check("crossing", &[]);
    assert!(flagged > 0);
}
