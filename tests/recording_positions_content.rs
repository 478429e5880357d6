//! What a recording keeps of the node positions is the user's choice (`run --positions-of
//! surface`, `--positions-precision single`) and is recorded: the boundary nodes' positions
//! (bit for bit, or rounded to singles) read back, the interior nodes read as NaN, the
//! contact data stays in full and bit for bit, and `inspect`, `diff`, `replay` and `convert`
//! work on every choice (`export` refuses a boundary-only recording and says why).
//!
//! Reference: the same run recorded with every node in double precision. Parameters: the
//! seed's strip-channel on a 48×2 mesh (240 increments of 4800 to t = 0.05) and the built-in
//! hertz-3d (8×8×6 hexahedra, 4 increments). Tolerance: bit for bit, or the
//! nearest single (relative 2⁻²⁴).

mod common;

use contrail::analysis::inspect::{inspect, render};
use contrail::analysis::recording::Recording;
use contrail::record::mcap::sink::{McapOptions, McapSink};
use contrail::record::packed_positions::{PositionsOf, Precision};
use contrail::record::{Fanout, Memory, Observer};
use std::io::Cursor;
use std::process::Command;
use std::sync::atomic::AtomicBool;

/// Record `run` (which drives the observer it is given) into memory with `opts`.
fn record(opts: McapOptions, run: impl FnOnce(&mut dyn Observer)) -> (Vec<u8>, Memory) {
    let mut sink = McapSink::new(Cursor::new(Vec::new()), "memory", opts).unwrap();
    let mut mem = Memory::default();
    let mut fan = Fanout::default();
    fan.sinks.push(&mut sink);
    fan.sinks.push(&mut mem);
    run(&mut fan);
    drop(fan);
    (sink.into_inner().unwrap().into_inner(), mem)
}

fn options(of: PositionsOf, precision: Precision) -> McapOptions {
    McapOptions {
        positions_of: of,
        positions_precision: precision,
        ..McapOptions::default()
    }
}

/// Every coordinate of `kept` is `full`'s (rounded to a single where `single`) at the
/// `surface` nodes and NaN elsewhere.
fn assert_kept(full: &[f64], kept: &[f64], dim: usize, surface: &[usize], single: bool) {
    assert_eq!(full.len(), kept.len());
    for (i, (a, b)) in full.iter().zip(kept).enumerate() {
        let on_surface = surface.binary_search(&(i / dim)).is_ok();
        let want = match (on_surface, single) {
            (false, _) => f64::NAN,
            (true, true) => f64::from(*a as f32),
            (true, false) => *a,
        };
        assert!(
            want.to_bits() == b.to_bits() || (want.is_nan() && b.is_nan()),
            "value {i} (node {}): {b} instead of {want}",
            i / dim
        );
    }
}

#[test]
fn the_strip_keeps_its_boundary_in_single_precision_and_every_contact_point_bit_for_bit() {
    let sets: Vec<String> = [
        "stepping.increments=4800",
        "stepping.end=0.05",
        "body.strip.mesh.elements=[48,2]",
    ]
    .map(String::from)
    .to_vec();
    let (src, problem) = contrail::load_scene("strip-channel", &sets).unwrap();
    let info = contrail::run_info(&src, &sets, &problem);
    let go = |o: &mut dyn Observer| {
        contrail::solver::run(&problem, &info, o, &AtomicBool::new(false)).unwrap();
    };
    let (full, _) = record(McapOptions::default(), go);
    let (kept, mem) = record(options(PositionsOf::Surface, Precision::Single), go);
    let full = Recording::from_bytes(&full, "full.mcap").unwrap();
    let kept_len = kept.len();
    let r = Recording::from_bytes(&kept, "kept.mcap").unwrap();
    // the 48×2 strip's middle row of nodes is inside, but for its two ends
    let surface = r.model.surface_nodes();
    assert_eq!(r.model.positions_nodes, surface);
    assert_eq!(surface.len(), r.model.nodes.len() - 47);
    assert_eq!(r.metadata["positions_of"], "surface");
    assert_eq!(r.metadata["positions_precision"], "single");
    assert_eq!(r.positions.len(), full.positions.len());
    for (a, b) in full.positions.iter().zip(&r.positions) {
        assert_kept(a.nodes.as_flattened(), b.nodes.as_flattened(), 2, &surface, true);
        assert_eq!(a.rigid_offsets, b.rigid_offsets);
    }
    // contact in full: every point of every increment as the solver made it (nothing is
    // left out for readers to restore from rounded positions)
    for (inc, points) in r.increments.iter().zip(&mem.contact) {
        let got = r.contact_at(inc.increment);
        assert_eq!(got.len(), points.len());
        for (a, b) in got.iter().zip(points) {
            assert_eq!(serde_json::to_string(a).unwrap(), serde_json::to_string(b).unwrap());
        }
    }
    let text = render(&inspect(&r));
    let line = format!(
        "(positions every increment, the {} boundary nodes of {}, single precision)",
        surface.len(),
        r.model.nodes.len()
    );
    assert!(text.contains(&line), "{text}");
    println!("strip-channel 48×2, 240 increments: {kept_len} bytes kept");
}

#[test]
fn a_3d_run_keeps_its_surface_bit_for_bit_and_its_contact_in_full() {
    let text = include_str!("../scenes/hertz-3d.toml");
    let (problem, info) = common::solid_problem("hertz-3d.toml", text);
    let go = |o: &mut dyn Observer| {
        contrail::solver::run(&problem, &info, o, &AtomicBool::new(false)).unwrap();
    };
    let (full_bytes, _) = record(McapOptions::default(), go);
    let (kept_bytes, mem) = record(options(PositionsOf::Surface, Precision::Double), go);
    let full = Recording::from_bytes(&full_bytes, "full.mcap").unwrap();
    let r = Recording::from_bytes(&kept_bytes, "kept.mcap").unwrap();
    let surface = r.model.surface_nodes();
    // the 8×8×6 block's 9×9×7 nodes: 7×7×5 inside
    assert_eq!(r.model.nodes_3d.len() - surface.len(), 245);
    assert_eq!(r.model.positions_nodes, surface);
    for (a, b) in full.positions.iter().zip(&r.positions) {
        assert_kept(a.nodes_3d.as_flattened(), b.nodes_3d.as_flattened(), 3, &surface, false);
    }
    assert_eq!(r.surface.len(), mem.surface.len());
    for (inc, written) in mem.surface.iter().enumerate() {
        let read = r.surface_at(r.increments[inc].increment);
        let json = |p: &contrail::record::surface_contact::SurfacePointRecord| serde_json::to_string(p).unwrap();
        assert_eq!(
            read.iter().map(json).collect::<Vec<_>>(),
            written.iter().map(json).collect::<Vec<_>>()
        );
    }
    assert!(kept_bytes.len() < full_bytes.len());
}

/// A 3D run recorded with positions every 3rd increment: the slaves that stay out of reach
/// of the ball are left out of `/surface_contact` (fewer entries than slaves in its
/// messages) and read back as the solver made them — at the increments without positions
/// with no position (NaN), since no node's position is kept there.
#[test]
fn a_3d_run_with_positions_every_nth_increment_leaves_out_the_slaves_out_of_reach() {
    // a search radius of 0.05 (the default, twice the coarse mesh's longest edge, reaches
    // every slave): the slaves farther than about 0.32 from the axis are out of reach
    let text = include_str!("../scenes/hertz-3d.toml").replace("eps_n = 1.0e7", "eps_n = 1.0e7\nsearch_radius = 0.05");
    let (problem, info) = common::solid_problem("hertz-3d.toml", &text);
    let go = |o: &mut dyn Observer| {
        contrail::solver::run(&problem, &info, o, &AtomicBool::new(false)).unwrap();
    };
    let opts = McapOptions {
        positions_every: 3,
        ..McapOptions::default()
    };
    let (bytes, mem) = record(opts, go);
    let slaves = problem.model.surface_contacts[0].slaves.len();
    let written: Vec<usize> = mcap::MessageStream::new(&bytes)
        .unwrap()
        .map(Result::unwrap)
        .filter(|m| m.channel.topic == "/surface_contact")
        .map(|m| {
            let v: serde_json::Value = serde_json::from_slice(&m.data).unwrap();
            v["slave"].as_array().unwrap().len()
        })
        .collect();
    assert_eq!(written.len(), 4);
    assert!(written.iter().all(|&n| n < slaves), "{written:?} of {slaves}");
    let r = Recording::from_bytes(&bytes, "every-3.mcap").unwrap();
    let with_positions: Vec<usize> = r.positions.iter().map(|p| p.increment).collect();
    assert_eq!(with_positions, [3, 4]);
    let json = |p: &contrail::record::surface_contact::SurfacePointRecord| serde_json::to_string(p).unwrap();
    let mut unkept = 0;
    for (inc, solver) in r.increments.iter().zip(&mem.surface) {
        let read = r.surface_at(inc.increment);
        assert_eq!(read.len(), solver.len());
        for (a, b) in read.iter().zip(solver) {
            if !with_positions.contains(&inc.increment) && b.is_bare_out_of_reach() {
                assert!(a.position.iter().all(|x| x.is_nan()), "{a:?}");
                unkept += 1;
                let kept = contrail::record::surface_contact::SurfacePointRecord {
                    position: b.position,
                    ..a.clone()
                };
                assert_eq!(json(&kept), json(b));
            } else {
                assert_eq!(json(a), json(b));
            }
        }
    }
    assert!(unkept > 0);
}

fn contrail(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_contrail"))
        .args(args)
        .output()
        .unwrap()
}

fn ok(args: &[&str]) -> String {
    let out = contrail(args);
    let text = format!(
        "{}{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(out.status.success(), "contrail {}: {text}", args.join(" "));
    text
}

/// The commands a user runs on a recording work on every choice of positions.
#[test]
fn inspect_diff_replay_and_convert_read_every_choice_and_export_says_what_it_needs() {
    let dir = std::env::temp_dir().join(format!("contrail-positions-content-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = |name: &str| dir.join(name).display().to_string();
    let base = ["run", "hertz-3d", "--quiet", "--out"];
    ok(&[&base[..], &[&path("full.mcap")]].concat());
    for (name, choice) in [
        ("surface.mcap", ["--positions-of", "surface"]),
        ("single.mcap", ["--positions-precision", "single"]),
    ] {
        ok(&[&base[..], &[&path(name)], &choice[..]].concat());
        let shown = ok(&["inspect", &path(name)]);
        assert!(shown.contains("(positions every increment"), "{shown}");
        // the contact data is the same as the full recording's, bit for bit
        let diff = ok(&["diff", &path("full.mcap"), &path(name), "--tol", "0"]);
        assert!(
            diff.contains("matched increments 4 (only in A 0, only in B 0)"),
            "{diff}"
        );
        assert!(diff.contains("result: within tolerance"), "{diff}");
        ok(&["replay", &path(name), "--rerun-save", &path(&format!("{name}.rrd"))]);
        ok(&["convert", &path(name), &path(&format!("converted-{name}"))]);
        let again = ok(&["inspect", &path(&format!("converted-{name}"))]);
        let kept = |t: &str| t.lines().find(|l| l.contains("(positions")).map(str::to_string);
        assert_eq!(kept(&again), kept(&shown), "convert keeps the choice");
    }
    let out = contrail(&["export", &path("surface.mcap"), "--vtu", &path("vtu")]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success() && err.contains("--positions-of all"), "{err}");
    std::fs::remove_dir_all(&dir).ok();
}
