//! 3D contact in the recordings: `/surface_contact` (one message of arrays per increment and
//! pair) reads back to the records the solver handed its observers, bit for bit (NaN
//! included); the crossings of facet edges carry the history before and after transfer;
//! `/model` describes the pairs and the rigid master, whose offset each message states;
//! `inspect` summarises the 3D contact and a replay writes the 3D rerun view.

mod common;

use contrail::analysis::diff::{diff, Align, SURFACE_FIELDS};
use contrail::analysis::inspect::{inspect, render};
use contrail::analysis::recording::Recording;
use contrail::record::mcap::sink::{McapOptions, McapSink};
use contrail::record::rrd::sink::{self as rerun_sink, RerunTargets, RerunView};
use contrail::record::surface_contact::{RigidShapeInfo, SurfacePointRecord};
use contrail::record::{Fanout, Memory};
use contrail::solver::run;
use std::io::Cursor;
use std::sync::atomic::AtomicBool;

/// A block pressed onto a slab, then dragged at 30° to the slab's mesh lines across its
/// facets (μ = 0.3); the slab's nodes are offset from the block's, so that no slave node
/// starts on a facet edge.
const SLIDE_BASE: &str = include_str!("data/slide-3d-small.toml");

/// Run into an in-memory MCAP and a `Memory`.
fn record(origin: &str, text: &str) -> (Recording, Memory) {
    let (bytes, mem) = record_bytes(origin, text);
    (Recording::from_bytes(&bytes, origin).unwrap(), mem)
}

/// Run into an in-memory MCAP (its bytes) and a `Memory`.
fn record_bytes(origin: &str, text: &str) -> (Vec<u8>, Memory) {
    let (p, info) = common::solid_problem(origin, text);
    let mut sink = McapSink::new(Cursor::new(Vec::new()), "memory", McapOptions::default()).unwrap();
    let mut mem = Memory::default();
    let mut fan = Fanout::default();
    fan.sinks.push(&mut sink);
    fan.sinks.push(&mut mem);
    run(&p, &info, &mut fan, &AtomicBool::new(false)).unwrap_or_else(|e| panic!("{origin}: {e}"));
    drop(fan);
    (sink.into_inner().unwrap().into_inner(), mem)
}

fn json(p: &SurfacePointRecord) -> String {
    serde_json::to_string(p).unwrap()
}

#[test]
fn a_sliding_block_reads_back_bit_for_bit_with_its_crossings_and_carried_histories() {
    let (r, mem) = record("slide-3d-small.toml", &format!("{SLIDE_BASE}increments = 8\n"));
    assert_eq!(r.model.surface_contacts.len(), 1);
    let pair = &r.model.surface_contacts[0];
    assert_eq!((pair.slave_nodes.len(), pair.master_facets.len()), (9, 48));
    assert_eq!(pair.master, "body slab");
    assert!(
        (pair.areas.iter().sum::<f64>() - 1.0).abs() < 1e-12,
        "the block's face is 1 × 1"
    );
    assert_eq!(r.surface.len(), mem.surface.len());
    for (inc, written) in mem.surface.iter().enumerate() {
        let read = r.surface_at(inc + 1);
        assert_eq!(read.len(), written.len(), "increment {}", inc + 1);
        for (a, b) in written.iter().zip(read) {
            // JSON of both sides: NaN compares equal, and every bit of every double counts
            assert_eq!(json(a), json(b), "increment {}", inc + 1);
            assert_eq!(a.xi.map(f64::to_bits), b.xi.map(f64::to_bits));
        }
    }
    let crossings: Vec<&SurfacePointRecord> = r.surface.values().flatten().filter(|p| p.crossing).collect();
    assert!(crossings.len() >= 4, "{} crossings", crossings.len());
    for c in &crossings {
        let carried = c.carried.expect("a frictional crossing carries its history");
        assert_eq!(Some(carried.from_facet), c.previous_facet);
        assert_ne!(c.previous_facet, c.facet);
        // the old contact point, seen from the new facet, lies beyond its edge
        assert!(carried.xi_to.iter().any(|x| x.abs() > 1.0), "{carried:?}");
        assert!(!c.history_lost);
    }
    let report = inspect(&r);
    assert_eq!(report.crossings, crossings.len());
    let text = render(&report);
    assert!(
        text.contains("base: 9 slave nodes against the master body slab (48 facets) (continuous, μ = 0.3)"),
        "{text}"
    );
    assert!(
        text.contains("3D contact         base: 9 of 9 closed at increment 8"),
        "{text}"
    );
    assert!(text.contains("/surface_contact"), "{text}");
}

#[test]
fn the_rigid_sphere_is_described_once_and_its_offset_recorded_at_every_increment() {
    let (r, _) = record("hertz-3d", contrail::scene::builtin::find("hertz-3d").unwrap().text);
    let pair = &r.model.surface_contacts[0];
    assert_eq!(pair.master, "rigid ball");
    assert!(pair.master_facets.is_empty());
    assert_eq!(
        pair.rigid,
        Some(RigidShapeInfo::Sphere {
            centre: [0.0, 0.0, 1.0],
            radius: 1.0
        })
    );
    assert_eq!(r.surface_offsets.len(), 4);
    for (inc, offsets) in &r.surface_offsets {
        let t = r.increments[inc - 1].t;
        assert_eq!(offsets.len(), 1);
        assert!((offsets[0][2] + 0.005 * t).abs() < 1e-15, "{offsets:?} at t = {t}");
    }
    let last = r.surface.values().last().unwrap();
    assert!(last.iter().filter(|p| p.facet == Some(0)).count() >= 4);
    // an open point out of reach has no contact point: NaN survives the recording
    assert!(last.iter().any(|p| p.contact_point[0].is_nan() || p.gap > 0.0));
    // the 3D rerun view of a replay
    let dir = std::env::temp_dir().join(format!("contrail-rerun-3d-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("replay.rrd");
    let targets = RerunTargets {
        save: Some(path.clone()),
        ..RerunTargets::default()
    };
    let mut view = RerunView::new(rerun_sink::open(&targets, "hertz-3d", 3).unwrap(), &r.model).unwrap();
    for inc in &r.increments {
        let offsets = r.surface_offsets.get(&inc.increment).map_or(&[][..], Vec::as_slice);
        view.surface(inc.increment, r.surface_at(inc.increment), offsets)
            .unwrap();
        let positions = r.positions.iter().find(|p| p.increment == inc.increment);
        view.increment(inc, positions, &[], &[]).unwrap();
    }
    view.finish().unwrap();
    assert!(std::fs::metadata(&path).unwrap().len() > 10_000);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn diff_compares_the_3d_points_field_by_field() {
    let text = contrail::scene::builtin::find("hertz-3d").unwrap().text;
    let (a, _) = record("hertz-3d", text);
    let same = diff(&a, &a, Align::Increment, 1e-12).unwrap();
    assert!(same.within_tolerance);
    for f in SURFACE_FIELDS {
        let fd = same.fields.iter().find(|d| d.field == *f).unwrap();
        assert_eq!(fd.compared, 4 * 81, "{f}");
    }
    let (b, _) = record("hertz-3d", &text.replace("eps_n = 1.0e7", "eps_n = 2.0e7"));
    let report = diff(&a, &b, Align::Increment, 1e-6).unwrap();
    assert!(!report.within_tolerance);
    let normal = report.fields.iter().find(|d| d.field == "normal_force").unwrap();
    let at = normal
        .first_divergence
        .as_ref()
        .expect("a stiffer penalty changes the forces");
    assert!(at.point.as_deref().unwrap().starts_with("indent/"), "{at:?}");
    let facets = report.fields.iter().find(|d| d.field == "facet").unwrap();
    assert_eq!(facets.beyond_tolerance, 0);
}

#[test]
fn the_csv_counts_the_closed_3d_points_and_their_crossings() {
    use contrail::record::text::csv::CsvSink;
    let (p, info) = common::solid_problem("slide-3d-small.toml", &format!("{SLIDE_BASE}increments = 8\n"));
    let mut csv = CsvSink::new(Vec::new(), "csv");
    let mut mem = Memory::default();
    let mut fan = Fanout::default();
    fan.sinks.push(&mut csv);
    fan.sinks.push(&mut mem);
    run(&p, &info, &mut fan, &AtomicBool::new(false)).unwrap();
    drop(fan);
    let text = String::from_utf8(csv.into_inner()).unwrap();
    let rows: Vec<Vec<&str>> = text.lines().skip(1).map(|l| l.split(',').collect()).collect();
    assert_eq!(rows.len(), mem.surface.len());
    let (mut closed_total, mut crossings_total) = (0, 0);
    for (row, points) in rows.iter().zip(&mem.surface) {
        let closed = points
            .iter()
            .filter(|q| q.state != contrail::contact::law::ContactState::Open)
            .count();
        let crossings = points.iter().filter(|q| q.crossing).count();
        assert_eq!(
            (row[8].parse::<usize>().unwrap(), row[9].parse::<usize>().unwrap()),
            (closed, crossings)
        );
        closed_total += closed;
        crossings_total += crossings;
    }
    // they used to be 0 in 3D: only the 2D points were counted
    assert!(
        closed_total > 0 && crossings_total > 0,
        "{closed_total} closed, {crossings_total} crossings"
    );
}

/// The JSON of every message on `topic`, in order.
fn messages_on(bytes: &[u8], topic: &str) -> Vec<serde_json::Value> {
    (mcap::MessageStream::new(bytes).unwrap())
        .map(|m| m.unwrap())
        .filter(|m| m.channel.topic == topic)
        .map(|m| serde_json::from_slice(&m.data).unwrap())
        .collect()
}

/// The entity `id` of a `foxglove.SceneUpdate`.
fn entity<'a>(scene: &'a serde_json::Value, id: &str) -> &'a serde_json::Value {
    (scene["entities"].as_array().unwrap().iter())
        .find(|e| e["id"] == id)
        .unwrap_or_else(|| panic!("no entity {id}"))
}

fn xyz(p: &serde_json::Value) -> [f64; 3] {
    ["x", "y", "z"].map(|c| p[c].as_f64().unwrap())
}

#[test]
fn a_3d_run_has_a_foxglove_scene_of_its_mesh_rigid_master_and_contact_points() {
    let (bytes, mem) = record_bytes("hertz-3d", contrail::scene::builtin::find("hertz-3d").unwrap().text);
    let r = Recording::from_bytes(&bytes, "hertz-3d").unwrap();
    assert_eq!(messages_on(&bytes, "/foxglove/reference").len(), 1);
    let scenes = messages_on(&bytes, "/foxglove/scene");
    // the reference configuration, then every increment (4: `scene_every` auto)
    assert_eq!(scenes.len(), 1 + r.increments.len());
    let last = scenes.last().unwrap();
    // the mesh: the boundary's nodes (in node order) at their last positions (single
    // precision), its edges
    let lines = &entity(last, "mesh")["lines"][0];
    let points = lines["points"].as_array().unwrap();
    let positions = &r.positions.last().expect("positions").nodes_3d;
    let mut boundary: Vec<usize> = contrail::model::hex_boundary::boundary_quads(&r.model.hexahedra)
        .into_iter()
        .flatten()
        .collect();
    boundary.sort_unstable();
    boundary.dedup();
    assert!(boundary.len() < positions.len(), "a block has interior nodes");
    assert_eq!(points.len(), boundary.len());
    for (p, &n) in points.iter().zip(&boundary) {
        let (p, x) = (xyz(p), positions[n]);
        assert!(
            (0..3).all(|c| (p[c] - x[c]).abs() <= 1e-6 * (1.0 + x[c].abs())),
            "{p:?} {x:?}"
        );
    }
    let indices = lines["indices"].as_array().unwrap();
    assert!(indices.len().is_multiple_of(2) && indices.iter().all(|i| (i.as_u64().unwrap() as usize) < points.len()));
    // the rigid ball, moved down by its offset, drawn with its diameter
    let ball = &entity(last, "rigid")["spheres"][0];
    let centre = xyz(&ball["pose"]["position"]);
    let offset = r.surface_offsets.values().last().unwrap()[0];
    assert!((centre[2] - (1.0 + offset[2])).abs() < 1e-7, "{centre:?}");
    assert_eq!(ball["size"]["x"].as_f64(), Some(2.0));
    // one sphere per slave point within reach, where the record puts it
    let within: Vec<_> = mem
        .surface
        .last()
        .unwrap()
        .iter()
        .filter(|p| p.facet.is_some())
        .collect();
    let drawn = entity(last, "contact points")["spheres"].as_array().unwrap();
    assert_eq!(drawn.len(), within.len());
    for (d, p) in drawn.iter().zip(&within) {
        let at = xyz(&d["pose"]["position"]);
        assert!(
            (0..3).all(|c| (at[c] - p.position[c]).abs() <= 1e-6),
            "{at:?} {:?}",
            p.position
        );
    }
}
