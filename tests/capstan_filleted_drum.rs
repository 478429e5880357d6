//! A belt held by contact alone: the capstan over a drum whose 16 vertices are rounded by
//! fillets, the belt laid on the fillets' tops.
//!
//! ```text
//!        belt (120 or 240 elements, one layer, h = 0.005, E = 1e6) on the drum's upper half,
//!        x free everywhere, y held at the start only: nothing but contact holds it
//!    T1 ↓ ╭─╮──╭─╮──╭─╮ ↓ pull (held, pulled down 0.06, let up 0.12)
//!         rigid 16-gon inscribed in R = 1, each vertex a fillet of radius r
//! ```
//! Scene `capstan-polygon` with `rigid.drum.polygon.sides = 16`, `rigid.drum.fillet = r` and
//! the belt's inner radius `1 − r (1/cos(π/16) − 1)` (the fillets' tops), μ = 0.3. The belt
//! starts touching the fillets with gaps of round-off size and carries its first load on
//! nothing: the first tangent is singular in the belt's rigid motions, the line search along
//! Newton's correction finds no decrease, and the pseudo-transient continuation
//! (`solver::continuation`) takes over until contact closes.
//!
//! Reference: the rope over a drum with no sharp vertex, `exp(μπ)` = 2.56633, on the mean
//! pull over t ∈ [1.2, 1.5]. Measured 2026-11-27 (radii to 6 digits, as in the methods
//! sweep): r = 0.25 −2.24 % (120 elements, 100 increments), −2.42 % (120, 200, 1 cut-back),
//! −0.45 % (240, 100); r = 0.5 −0.55 %, −0.55 % (1 cut-back), −0.57 %; the continuation took
//! 9–10 corrections in the first increment on 120 elements, none on 240. Still failing (not
//! asserted): r = 0.25 on 120 elements at 200 increments with the radius unrounded (gaps of
//! round-off size), whose line searches accept steps of 1e-6 without failing, so the
//! continuation never starts. Asserted: every run
//! completes with at most one cut-back, each increment in equilibrium to 1e-8; the
//! continuation acted on 120 elements; the pull within 3 % on 120 elements and 1 % on 240
//! (a fillet of r = 0.25 spans 1.5 elements of 120: its arc is resolved on 240).

mod common;

use contrail::analysis::analytic::capstan;
use contrail::record::Memory;
use std::f64::consts::PI;

const MU: f64 = 0.3;

fn mean_pull(m: &Memory) -> f64 {
    let f: Vec<f64> = (m.increments.iter())
        .filter(|i| i.t >= 1.2 - 1e-9 && i.t <= 1.5 + 1e-9)
        .map(|i| i.monitor.as_ref().expect("monitored").force)
        .collect();
    assert!(f.len() >= 3);
    f.iter().sum::<f64>() / f.len() as f64
}

/// `(relative error of the pull, stabilised corrections)` of one run.
fn run(fillet: f64, elements: usize, increments: usize) -> (f64, usize) {
    let inner = 1.0 - fillet * (1.0 / (PI / 16.0).cos() - 1.0);
    let sets = [
        "rigid.drum.polygon.sides=16".to_string(),
        format!("rigid.drum.fillet={fillet}"),
        format!("body.belt.mesh.radius=[{inner:.6}, {:.6}]", inner + 0.005),
        format!("body.belt.mesh.elements=[{elements},1]"),
        format!("stepping.increments={increments}"),
    ];
    let sets: Vec<&str> = sets.iter().map(String::as_str).collect();
    let (s, m) = common::solve_ok(&common::scene("capstan-polygon", &sets));
    let error = mean_pull(&m) / capstan(MU, PI) - 1.0;
    println!(
        "r = {fillet}, {elements} elements, {increments} increments: pull {:+.2} %, {} cut-backs, {} stabilised corrections (work {:.3e}), equilibrium {:.1e}",
        100.0 * error,
        s.cutbacks,
        s.stabilised_corrections,
        s.stabilisation_work,
        s.equilibrium.unwrap_or(f64::NAN)
    );
    assert!(
        s.cutbacks <= 1,
        "r = {fillet}, {elements} elements: {} cut-backs",
        s.cutbacks
    );
    assert!(s.equilibrium.is_some_and(|e| e < 1e-8), "{:?}", s.equilibrium);
    (error, s.stabilised_corrections)
}

#[test]
fn capstan_filleted_drum_belt_held_by_contact_alone_refined_in_mesh_and_step() {
    for fillet in [0.25, 0.5] {
        for (elements, increments, tol) in [(120, 100, 3e-2), (120, 200, 3e-2), (240, 100, 1e-2)] {
            let (error, stabilised) = run(fillet, elements, increments);
            assert!(error.abs() < tol, "r = {fillet}, {elements}/{increments}: {error}");
            if elements == 120 {
                assert!(stabilised > 0, "r = {fillet}: the continuation did not act");
            }
        }
    }
}
