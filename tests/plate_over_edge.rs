//! A thin plate pulled over an edge: plane stress against 3D, one scene built as both models
//! (the "model no more than a scene needs" check of a plate in its own plane).
//!
//! ```text
//!   x = 0 (u_x = 0; pulled down by v)          the block's corner edge C (x = 6.5)
//!   |==================================== plate 12 × 0.5 in its plane, thickness 0.1
//!   |                                  ●━━━━━━━━━━━ held block, wall down the channel
//! ```
//! `tests/data/plate-edge.toml`: the seed's strip (`strip-channel`, E = 2.1e4, ν = 0.3,
//! μ = 0.2, 1200 adaptive increments to v = 12) as a plate of thickness t = 0.1, in plane
//! stress, over a block held still (the rigid polyline of `strip-channel` as a body, so that
//! the scene has an extrusion); with `extrusion.build = true` it is half the plate in 3D
//! (0.05 thick, `u_y = 0` on its mid-plane, its face free; the block held still, its corner
//! node the corner edge; `hex8-eas` from `q4-eas`), forces reported for the plate.
//! Reference: the plane-stress answer on the same in-plane mesh. Tolerances: 1 % in the peak
//! force and in the plateau (v ≥ 10) on 24 × 1 and 48 × 2 with one hexahedron across the half
//! thickness, and on 48 × 2 with two (the 3D side refined through the thickness); one and two
//! across agree within 0.1 % at every v sampled. The held block stands for the rigid one:
//! plane stress over it equals plane stress over `strip-channel`'s polyline to 1e-6.
//! Measured 2026-11-28: peak +0.011 % (24 × 1, one across), +0.011 % / +0.012 % (48 × 2, one /
//! two across), plateau +0.006 %, +0.003 %, +0.006 %; one against two across 3.0e-5; held
//! block against polyline 3.5e-9. Not asserted: two across on 24 × 1 stops at v = 3.0
//! (docs/models.md). Release tier (about 75 s).

mod common;

use contrail::analysis::metrics::{peak_error, plateau_error};
use contrail::record::Memory;
use contrail::scene::AnyProblem;
use std::sync::atomic::AtomicBool;

const SCENE: &str = "tests/data/plate-edge.toml";

fn curve(mem: &Memory) -> Vec<(f64, f64)> {
    (mem.increments.iter())
        .filter_map(|i| i.monitor.as_ref().map(|m| (m.displacement, m.force)))
        .collect()
}

/// The plate's force–displacement curve of the scene on an in-plane mesh, in 2D or as its
/// extrusion with `across` hexahedra across the half thickness.
fn plate(mesh: [usize; 2], across: Option<usize>) -> Vec<(f64, f64)> {
    let mut sets = vec![format!("body.strip.mesh.elements=[{}, {}]", mesh[0], mesh[1])];
    if let Some(n) = across {
        sets.push("extrusion.build=true".into());
        sets.push(format!("extrusion.elements={n}"));
    }
    let (src, problem) = contrail::load_any_scene(SCENE, &sets).unwrap_or_else(|e| panic!("{e}"));
    let mut mem = Memory::default();
    let stop = AtomicBool::new(false);
    let ran = match &problem {
        AnyProblem::Plane(p) => contrail::solver::run(p, &contrail::run_info(&src, &sets, p), &mut mem, &stop),
        AnyProblem::Solid(p) => contrail::solver::run(p, &contrail::run_info(&src, &sets, p), &mut mem, &stop),
    };
    ran.unwrap_or_else(|e| panic!("{mesh:?}, {across:?} across: {e}"));
    curve(&mem)
}

/// The largest relative difference of two curves at v = 0.2, 0.3, …, 11.9.
fn largest_difference(a: &[(f64, f64)], b: &[(f64, f64)]) -> f64 {
    let at = |c: &[(f64, f64)], v: f64| {
        let k = c.iter().position(|p| p.0 >= v).expect("the curve reaches v");
        let ((v0, f0), (v1, f1)) = (c[k - 1], c[k]);
        f0 + (f1 - f0) * (v - v0) / (v1 - v0)
    };
    (2..120)
        .map(|k| 0.1 * k as f64)
        .map(|v| ((at(a, v) - at(b, v)) / at(b, v)).abs())
        .fold(0.0, f64::max)
}

#[test]
#[cfg_attr(debug_assertions, ignore = "release tier")]
fn a_plate_over_an_edge_in_plane_stress_agrees_with_its_3d_extrusion() {
    let polyline = curve(
        &common::solve_ok(&common::scene(
            "strip-channel",
            &["body.strip.model=plane-stress", "body.strip.thickness=0.1"],
        ))
        .1,
    );
    let coarse = plate([24, 1], None);
    let held_block = largest_difference(&coarse, &polyline);
    println!("plane stress over the held block against the polyline: {held_block:.1e}");
    assert!(held_block <= 1e-6, "the held block stands for the rigid polyline");
    let fine = plate([48, 2], None);
    let mut through = Vec::new();
    for (mesh, across, plane) in [([24, 1], 1, &coarse), ([48, 2], 1, &fine), ([48, 2], 2, &fine)] {
        let solid = plate(mesh, Some(across));
        let (peak, plateau) = (
            peak_error(&solid, plane).unwrap(),
            plateau_error(&solid, plane, 10.0).unwrap(),
        );
        println!(
            "{mesh:?}, {across} across the half thickness, against plane stress: peak {:+.4} %, plateau {:+.4} %",
            100.0 * peak,
            100.0 * plateau
        );
        assert!(peak.abs() <= 0.01 && plateau.abs() <= 0.01, "{mesh:?}, {across} across");
        if mesh == [48, 2] {
            through.push(solid);
        }
    }
    let refined = largest_difference(&through[1], &through[0]);
    println!("48 × 2: two across against one, largest difference {refined:.1e}");
    assert!(refined <= 1e-3, "fine enough through the thickness");
}
