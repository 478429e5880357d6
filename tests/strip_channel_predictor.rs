//! The secant predictor at the sharp corner (issue 8, item 2): strip-channel, μ = 0.2,
//! pulled to v = 5.6 at Δv = 0.01 (the scene's nominal step), on 120×4 EAS elements and,
//! refined once, on 240×8.
//!
//! From v ≈ 5.4 on, the predictor's extrapolated strip is the chord past the corner C, so C
//! comes out *open* at the predicted start of most increments. Without a start from the
//! converged contact set the first correction then let the strip swing about its last
//! support and the line search cut it to s = 0.001 (302 of the full run's 1 200 increments).
//! The contact Newton now starts each increment from the converged contact set (the first
//! iterate decides contact by the converged normal forces, `contact::decision`): the same
//! remedy, as a rule of the method.
//!
//! Reference and tolerances:
//! * at most 2 increments with v ≥ 5.39 whose first correction is cut below s = 0.01, at
//!   both meshes (without the hold: 10 on 120×4 and 16 on 240×8 — checked by disabling
//!   it; at Δv = 0.005 on 120×4 there were none either way, so the step is not refined here);
//! * on 120×4, the same equilibrium path as the run without the predictor (`stepping.predictor =
//!   "last"`, whose first iterate is the converged state): the monitored force at every
//!   pseudo-time both runs converged at within 1e-6 relative (at least 30: the run without
//!   the predictor cuts back near v = 0.33, measured 6 cut-backs, and its later
//!   increments fall at other times) (both runs converge to `residual_tol = 1e-9`), but for
//!   at most 2 increments in which the corner C crosses to the next face segment in either
//!   run: there C sits within round-off of a face node, the equilibrium is not unique (which
//!   segment C converges on depends on where Newton starts), and the two forces only agree
//!   within 1 % (measured 2026-11-24: one such increment, v = 4.67, 5.1153 against 5.1061).

mod common;

use contrail::record::Memory;

/// The run to v = 5.6 in `increments` steps.
fn window(mesh: &str, predictor: &str, increments: usize) -> Memory {
    let sets = [
        &format!("body.strip.mesh.elements={mesh}"),
        "fix.1.value=-5.6",
        &format!("stepping.increments={increments}"),
        &format!("stepping.predictor={predictor}"),
    ];
    common::solve_ok(&common::scene("strip-channel", &sets)).1
}

/// Increments with v ≥ 5.39 whose first correction the line search cut below s = 0.01.
fn cut_first_corrections(m: &Memory, increments: usize) -> Vec<usize> {
    let from = (5.39 / 5.6 * increments as f64).ceil() as usize;
    m.iterations
        .iter()
        .filter(|r| r.increment >= from && r.iteration == 1 && r.line_search < 0.01)
        .map(|r| r.increment)
        .collect()
}

#[test]
fn predicted_starts_do_not_lose_the_corner_and_the_path_is_the_same() {
    let with = window("[120,4]", "secant", 560);
    let cut = cut_first_corrections(&with, 560);
    let fine = cut_first_corrections(&window("[240,8]", "secant", 560), 560);
    println!("cut first corrections: {} on 120×4, {} on 240×8", cut.len(), fine.len());
    assert!(
        cut.len() <= 2,
        "120×4: first corrections cut below s = 0.01 in increments {cut:?}"
    );
    assert!(
        fine.len() <= 2,
        "240×8: first corrections cut below s = 0.01 in increments {fine:?}"
    );

    let without = window("[120,4]", "last", 560);
    let crossing = |m: &Memory, inc: usize| m.crossings.iter().any(|(i, _)| *i == inc);
    let mut at_crossings = Vec::new();
    // the runs' converged increments at the same pseudo-times (a cut-back adds increments)
    let same_t: Vec<_> = (with.increments.iter())
        .filter_map(|a| {
            without
                .increments
                .iter()
                .find(|b| (b.t - a.t).abs() < 1e-12)
                .map(|b| (a, b))
        })
        .collect();
    assert!(same_t.len() >= 30, "{} increments at the same times", same_t.len());
    for (a, b) in same_t {
        let (fa, fb) = (a.monitor.as_ref().unwrap().force, b.monitor.as_ref().unwrap().force);
        let tol = if crossing(&with, a.increment) || crossing(&without, a.increment) {
            1e-2
        } else {
            1e-6
        };
        if (fa - fb).abs() > 1e-6 * fb.abs().max(1e-3) {
            at_crossings.push(a.increment);
        }
        assert!(
            (fa - fb).abs() <= tol * fb.abs().max(1e-3),
            "increment {}: force {fa} with the predictor, {fb} without",
            a.increment
        );
    }
    println!("increments where the two paths differ beyond 1e-6 (crossings): {at_crossings:?}");
    assert!(at_crossings.len() <= 2, "{at_crossings:?}");
    let its = |m: &Memory| m.increments.iter().map(|i| i.iterations).sum::<usize>();
    println!(
        "Newton iterations: {} predicted, {} from the last state",
        its(&with),
        its(&without)
    );
}
