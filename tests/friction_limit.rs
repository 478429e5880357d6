//! A load beyond what friction can hold stops the run where the friction gives out, and the
//! failure says so.
//!
//! ```text
//!        ┌──────────┐   block 1 × 0.25, E = 1e3, weight W = 5 (body load, t ∈ [0, 1]),
//!   P →  │          │   nothing fixed: only the floor's contact holds it
//!   ═════╧══════════╧═  rigid floor, μ = 0.4, resting at zero gap
//! ```
//! Scene `tests/data/block-push.toml`: the push `P` on the left face ramps from 0 at t = 1 to
//! 2.4 = 1.2 μW at t = 3.
//!
//! Reference (Coulomb): the floor holds at most `μW = 2.0`, reached at `t* = 1 + 2 · 2.0 / 2.4
//! = 2.6667`; beyond it no static equilibrium exists, so no quasi-static solver can go on.
//! The run must stop there, as a failure (never a completed run), and its reason must name the
//! body at its friction limit rather than only "no convergence".
//!
//! Asserted (release tier) on 20 × 5 (60 and 120 increments) and 40 × 10 (60): the run fails
//! within 0.2 % of t* (measured 2026-11-26: at t = 2.666675–2.666699, the last converged
//! increment at 2.666650, on all three) and its reason names the block held only by contact at
//! its friction limit; pushed to 0.9 μW instead, the run completes with the push balanced (1.8).

mod common;

use contrail::solver::run::SolveError;

const T_STAR: f64 = 1.0 + 2.0 * 2.0 / 2.4;

fn push(elements: [usize; 2], increments: usize, peak: f64) -> Result<contrail::solver::RunSummary, SolveError> {
    let sets = [
        format!("body.block.mesh.elements=[{}, {}]", elements[0], elements[1]),
        format!("stepping.increments={increments}"),
        format!("load.0.total=[[0.0, 0.0], [1.0, 0.0], [3.0, {peak}]]"),
    ];
    let sets: Vec<&str> = sets.iter().map(String::as_str).collect();
    let text = include_str!("data/block-push.toml");
    common::solve(&common::scene_file("tests/data/block-push.toml", text, &sets)).0
}

#[test]
#[cfg_attr(debug_assertions, ignore = "release tier")]
fn a_push_beyond_mu_w_stops_at_the_friction_limit_and_says_so() {
    for (elements, increments) in [([20, 5], 60), ([20, 5], 120), ([40, 10], 60)] {
        match push(elements, increments, 2.4) {
            Err(SolveError::StepFailed { t, reason, .. }) => {
                println!("{elements:?}, {increments} increments: failed at t = {t:.6} (t* = {T_STAR:.6}): {reason}");
                assert!(
                    (t - T_STAR).abs() <= 2e-3 * T_STAR,
                    "failed at t = {t}, not at t* = {T_STAR}"
                );
                assert!(
                    reason.contains("body `block` is held only by contact") && reason.contains("Coulomb friction"),
                    "{reason}"
                );
            }
            other => panic!("{elements:?}, {increments} increments: the run did not fail: {other:?}"),
        }
    }
}

#[test]
#[cfg_attr(debug_assertions, ignore = "release tier")]
fn a_push_below_mu_w_is_held() {
    let summary = push([20, 5], 60, 1.8).unwrap_or_else(|e| panic!("{e}"));
    let force = summary.monitor.as_ref().expect("a push monitor").force;
    assert!((force - 1.8).abs() < 1e-6, "push {force}");
    assert!((summary.t - 3.0).abs() < 1e-12);
}
