//! 2D ironing (Yang, Laursen & Meng, IJNME 62 (2005) 1183–1225): a rigid circular die pressed
//! into a soft neo-Hookean block, then dragged along it with friction.
//!
//! ```text
//!          ╭───────╮   die R = 3 (rigid), pressed 1.4 (t ≤ 1), dragged 3.5 → (t ≤ 3)
//!   ┌──────╰───────╯────────────────┐
//!   │  block 9 × 3, E = 1, ν = 0.3  │  bottom fixed; ε_N = ε_T = 100 E per node
//!   └───────────────────────────────┘
//! ```
//! Scene `ironing`; meshes 18 × 6 (coarse), 36 × 12 (medium, the scene's), 72 × 24 (fine);
//! 120 increments nominal, 240 and 480 (half and quarter step). The measures over the
//! sliding phase t ∈ [2, 3] (after the last point under the die has begun to slip):
//! * the mean of F_x/F_y. The published curves are figures only (no numbers to compare
//!   with); what is known exactly: frictionless, an elastic body dissipates nothing, so in
//!   steady sliding the drag vanishes — here it is −0.012 F_y (the die nears the block's
//!   free end: not quite steady) on every mesh; with friction the ratio exceeds μ by the
//!   share of the pressure on the die's inclined front (measured 1.18–1.25 μ over the
//!   frictionless offset). Measured (2026-11-26, nominal step): μ = 0.1: 0.1124, 0.1101,
//!   0.1087; μ = 0.3: 0.3626, 0.3570, 0.3567 (coarse, medium, fine);
//! * the oscillation of the forces as block nodes enter and leave the contact: the largest
//!   misfit of a cubic fit of F_x over t ∈ [2, 3], over the mean F_y — measured 4.7e-3,
//!   1.3e-3, 3.6e-4 (μ = 0.3), falling as h²: node-to-segment against a smooth die.
//!
//! Asserted (release tier: coarse and medium at the nominal and half step, μ = 0, 0.1, 0.3;
//! the full study adds the fine mesh and the quarter step, `-- --include-ignored`):
//! * every run completes with default settings (the default element; μ = 0.1 used to stop
//!   at 6 % of the indentation with slip directions flipping every iteration);
//! * frictionless: |F_x/F_y| < 0.02;
//! * with friction: μ < F_x/F_y − (its frictionless value) < 1.3 μ;
//! * the ratio on consecutive meshes within 0.01, and at half the step within 0.005 of the
//!   nominal step's;
//! * the oscillation at least 2.5 times smaller on each finer mesh.

mod common;

use contrail::record::Memory;

/// `(mean F_x/F_y, oscillation)` over the sliding phase.
fn sliding(m: &Memory) -> (f64, f64) {
    let pts: Vec<(f64, f64, f64)> = m
        .increments
        .iter()
        .filter(|i| i.t >= 2.0 - 1e-9)
        .map(|i| (i.t, i.monitors[0].force, i.monitors[1].force))
        .collect();
    assert!(pts.len() >= 10, "too few increments in the sliding phase");
    let n = pts.len() as f64;
    let ratio = pts.iter().map(|p| p.1 / p.2).sum::<f64>() / n;
    let fy = pts.iter().map(|p| p.2).sum::<f64>() / n;
    let drag: Vec<(f64, f64)> = pts.iter().map(|p| (p.0, p.1)).collect();
    (ratio, cubic_misfit(&drag) / fy)
}

/// The largest |y − cubic least-squares fit| over the points.
fn cubic_misfit(pts: &[(f64, f64)]) -> f64 {
    let t0 = pts[0].0;
    let basis = |t: f64| [1.0, t - t0, (t - t0).powi(2), (t - t0).powi(3)];
    let mut a = nalgebra::Matrix4::<f64>::zeros();
    let mut b = nalgebra::Vector4::<f64>::zeros();
    for &(t, y) in pts {
        let phi = basis(t);
        for i in 0..4 {
            b[i] += phi[i] * y;
            for j in 0..4 {
                a[(i, j)] += phi[i] * phi[j];
            }
        }
    }
    let c = a.lu().solve(&b).expect("a cubic fit of the drag");
    pts.iter()
        .map(|&(t, y)| {
            let phi = basis(t);
            (y - (0..4).map(|i| c[i] * phi[i]).sum::<f64>()).abs()
        })
        .fold(0.0, f64::max)
}

fn run(mu: f64, mesh: [usize; 2], increments: usize) -> (f64, f64) {
    let sets = [
        format!("contact.mu={mu}"),
        format!("body.block.mesh.elements=[{}, {}]", mesh[0], mesh[1]),
        format!("stepping.increments={increments}"),
    ];
    let sets: Vec<&str> = sets.iter().map(String::as_str).collect();
    let (s, m) = common::solve_ok(&common::scene("ironing", &sets));
    let (ratio, oscillation) = sliding(&m);
    println!(
        "μ = {mu}, {mesh:?}, {increments} increments: F_x/F_y {ratio:.4}, oscillation {oscillation:.2e} ({} Newton iterations, {} cut-backs, {:.1} s)",
        s.newton_iterations, s.cutbacks, s.wall_time_s
    );
    (ratio, oscillation)
}

fn study(meshes: &[[usize; 2]], steps: &[usize]) {
    let mut frictionless = Vec::new();
    for mu in [0.0, 0.1, 0.3] {
        let mut last: Option<(f64, f64)> = None;
        for (im, &mesh) in meshes.iter().enumerate() {
            let (ratio, oscillation) = run(mu, mesh, steps[0]);
            if mu == 0.0 {
                assert!(ratio.abs() < 0.02, "frictionless drag {ratio}");
                frictionless.push(ratio);
            } else {
                let friction = ratio - frictionless[im];
                assert!(friction > mu && friction < 1.3 * mu, "μ = {mu}, {mesh:?}: {ratio}");
            }
            if let Some((r, o)) = last {
                assert!((ratio - r).abs() < 0.01, "μ = {mu}, {mesh:?}: {ratio} after {r}");
                assert!(oscillation < o / 2.5, "μ = {mu}, {mesh:?}: {oscillation} after {o}");
            }
            last = Some((ratio, oscillation));
            for &finer in &steps[1..] {
                let (r, _) = run(mu, mesh, finer);
                assert!((r - ratio).abs() < 5e-3, "μ = {mu}, {mesh:?}, {finer}: {r} vs {ratio}");
            }
        }
    }
}

#[test]
#[cfg_attr(debug_assertions, ignore = "release tier")]
fn ironing_completes_and_converges_on_coarse_and_medium_meshes_and_half_steps() {
    study(&[[18, 6], [36, 12]], &[120, 240]);
}

#[test]
#[ignore = "full study"]
fn ironing_full_refinement_study() {
    study(&[[18, 6], [36, 12], [72, 24]], &[120, 240, 480]);
}
