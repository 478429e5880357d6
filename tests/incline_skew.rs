//! A block on a rigid incline dragged along it by a skew fix: the incline statics.
//!
//! ```text
//!            drag: u · d = v(t) on the left face, d = (cos α, sin α), free across d
//!          ╱▔▔▔▔╲
//!        ╱ block ╱   1 × 0.25 (20 × 5 Neo-Hookean EAS), E = 1e3, ν = 0.3, turned by α
//!      ╱▁▁▁▁▁▁▁╱     weight W = 20 · 0.25 = 5 along −y (body load, t ∈ [0, 1])
//!   ╱ rigid incline at α = 20°: ε_N = ε_T = 1e4, μ = 0.5
//! ```
//! Scene `tests/data/incline-skew.toml`: the rectangle mesh turned by `rotate`, the incline the
//! x axis turned likewise, the drag a `[[fix]]` with a `direction`; the drag `v` ramps from 0
//! at t = 1 to +0.05 (up the incline) or −0.05 (down) at t = 3.
//!
//! Reference (Coulomb, rigid-body statics): across the incline the support is free, so the
//! incline carries `N = W cos α`; at gross sliding (every contact point slipping) friction
//! is `μ N` against the motion, and the drag along `d` is `F = W (sin α + μ cos α)` up,
//! `W (sin α − μ cos α)` down (a pull here: μ cos α > sin α). Asserted: the reaction of the
//! skew fix along `d` (the sum of the reactions of the run, as the records report it) equals
//! `F` (sign included: positive along `d`) to 1e-6 relative at every increment at gross
//! sliding (measured: ≤ 1.2e-13 up, ≤ 2.5e-12 down), and has no component across `d`
//! (≤ 1e-6 W); the left face's mean displacement along `d` is `v(t)` to 1e-12.

mod common;

use contrail::contact::law::ContactState;

const W: f64 = 5.0;
const MU: f64 = 0.5;
const ALPHA_DEG: f64 = 20.0;

/// Drag the block by `to` along the incline; returns the drag reactions along `d` at the
/// increments at gross sliding, after checking each against `expected`.
fn drag(to: f64, expected: f64) -> Vec<f64> {
    let set = format!("fix.drag.value=[[0.0, 0.0], [1.0, 0.0], [3.0, {to}]]");
    let text = include_str!("data/incline-skew.toml");
    let problem = common::scene_file("tests/data/incline-skew.toml", text, &[&set]);
    assert_eq!(problem.model.skew.len(), 6, "the left face's 6 nodes are skew-fixed");
    let (_, mem) = common::solve_ok(&problem);
    let (s, c) = ALPHA_DEG.to_radians().sin_cos();
    let mut at_sliding = Vec::new();
    for (inc, points) in mem.increments.iter().zip(&mem.contact) {
        let [rx, ry] = inc.reaction_total;
        let along = rx * c + ry * s;
        let across = -rx * s + ry * c;
        assert!(across.abs() <= 1e-6 * W, "t = {}: reaction across d {across:e}", inc.t);
        // the left face's mean displacement along d is the prescribed drag
        let [mx, my] = [&inc.monitors[0], &inc.monitors[1]].map(|m| m.displacement);
        let v = if inc.t <= 1.0 { 0.0 } else { to * (inc.t - 1.0) / 2.0 };
        assert!(
            (mx * c + my * s - v).abs() <= 1e-12,
            "t = {}: u · d = {} vs {v}",
            inc.t,
            mx * c + my * s
        );
        // the monitors' forces are the reactions of the fixed set
        assert!((inc.monitors[0].force - rx).abs() <= 1e-9 * W && (inc.monitors[1].force - ry).abs() <= 1e-9 * W);
        if inc.t > 1.0 && points.iter().all(|p| p.state == ContactState::Slip) {
            let rel = (along - expected) / expected;
            println!("t = {:.3}: drag {along:.10} vs {expected:.10}: {rel:+.2e}", inc.t);
            assert!(
                rel.abs() <= 1e-6,
                "t = {}: drag {along} vs W (sin α ± μ cos α) = {expected}",
                inc.t
            );
            at_sliding.push(along);
        }
    }
    assert!(
        at_sliding.len() >= 10,
        "only {} increments at gross sliding",
        at_sliding.len()
    );
    at_sliding
}

#[test]
fn dragged_up_the_incline_the_skew_reaction_is_w_sin_plus_mu_cos() {
    let (s, c) = ALPHA_DEG.to_radians().sin_cos();
    // the residual's sign: the support pushes the block up the incline, positive along d
    assert!(drag(0.05, W * (s + MU * c)).iter().all(|f| *f > 0.0));
}

#[test]
fn dragged_down_the_incline_the_skew_reaction_is_w_sin_minus_mu_cos() {
    let (s, c) = ALPHA_DEG.to_radians().sin_cos();
    // μ cos α > sin α: the block must be pulled down, the reaction is negative along d
    assert!(drag(-0.05, W * (s - MU * c)).iter().all(|f| *f < 0.0));
}
