//! The methods the seed compares against on its benchmark (strip-channel, μ = 0.2,
//! continuous transfer, the scene's adaptive stepping to full insertion, v = 12).
//!
//! ```text
//!   x = 0 (u_x = 0; u_y = −v)                  C (6.5, 0): rigid corner, slave on the face
//!   |==================================== strip, bottom face = master of C (smoothed or not)
//!   |                                  ●━━━━━━━━━━━ block
//! ```
//! 1. **C1 smoothing of the strip's face** (`master_smoothing`): the force of a faceted face
//!    spikes each time C crosses a node (the normal jumps by the kink, which grows under
//!    refinement as the face wraps C more sharply). Measure: the largest |F − cubic fit|
//!    over v ∈ [4, 5.5], over the peak force (`analysis::metrics::spike`). Reference: none
//!    (a smooth curve has none); the faceted face of the same mesh for comparison.
//!    The issue's bound (Hermite face below 0.1 % on every mesh to 240×8) is **not met**:
//!    what remains is not a jump but a smooth oscillation of one period per segment, the
//!    tilt of the face's normal at C. C's own load dents the face around the node that
//!    carries it; C sits on the dent's flank, on one side in the first half of a segment,
//!    on the other in the second, and an interpolating face (faceted, Hermite) follows the
//!    dent. The dent's slope under a point load grows like 1/h, and so do the spikes
//!    (`crossing_spikes_are_the_tilt_of_the_normal_at_the_corner`,
//!    `hermite_face_meets_the_issue_spike_bound_on_every_mesh`, ignored: it fails).
//! 2. **Augmented Lagrangian**: the peak force must not depend on ε_N = ε_T over two decades
//!    (2.1e3 … 2.1e5, the seed's value at the top) to 0.1 %; the penalty alone moves it by
//!    its compliance (measured 0.05 % on 24×1).
//!
//! The CI tier (release) runs 24×1 and 48×2; the table over 24×1 … 240×8 in docs/methods.md
//! comes from `cargo test --release --test methods_strip methods_strip_full_study -- --ignored
//! --nocapture` (5 minutes); `--ignored` alone also runs the issue's Hermite bound, which fails.

mod common;

use contrail::analysis::metrics::spike;
use contrail::record::Memory;
use std::time::Instant;

#[derive(Debug, Clone)]
struct Row {
    mesh: [usize; 2],
    sets: Vec<String>,
    complete: bool,
    /// The last converged v.
    reached: f64,
    peak: f64,
    spike: f64,
    augmentations: usize,
    iterations: usize,
    wall: f64,
    /// Over v ∈ [4, 5.5]: the largest |θ − cubic fit| of the angle θ of the face's normal
    /// at C (rad), and the correlation of that residual with the force's.
    tilt: f64,
    tilt_force_correlation: f64,
}

/// Residuals of a least-squares cubic through `(x, y)` (x scaled to [−1, 1]).
fn cubic_residuals(x: &[f64], y: &[f64]) -> Vec<f64> {
    let (lo, hi) = x.iter().fold((f64::MAX, f64::MIN), |a, v| (a.0.min(*v), a.1.max(*v)));
    let basis = |v: f64| {
        let s = (2.0 * v - lo - hi) / (hi - lo);
        nalgebra::Vector4::new(1.0, s, s * s, s * s * s)
    };
    let mut a = nalgebra::Matrix4::<f64>::zeros();
    let mut b = nalgebra::Vector4::<f64>::zeros();
    for (&xi, &yi) in x.iter().zip(y) {
        let phi = basis(xi);
        a += phi * phi.transpose();
        b += phi * yi;
    }
    let c = a.lu().solve(&b).expect("a cubic through the window");
    x.iter().zip(y).map(|(&xi, &yi)| yi - c.dot(&basis(xi))).collect()
}

/// The tilt of the normal at C over v ∈ [4, 5.5] and its correlation with the force's
/// oscillation (see [`Row::tilt`]).
fn normal_tilt(mem: &Memory) -> (f64, f64) {
    let (mut v, mut f, mut theta) = (Vec::new(), Vec::new(), Vec::new());
    for (inc, points) in mem.increments.iter().zip(&mem.contact) {
        let (Some(m), Some(c)) = (&inc.monitor, points.iter().find(|p| &*p.pair_name == "corner")) else {
            continue;
        };
        if (4.0..=5.5).contains(&m.displacement) {
            v.push(m.displacement);
            f.push(m.force);
            theta.push(c.normal[1].atan2(c.normal[0]));
        }
    }
    if v.len() < 5 {
        return (f64::NAN, f64::NAN);
    }
    let (rf, rt) = (cubic_residuals(&v, &f), cubic_residuals(&v, &theta));
    let dot = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>();
    let corr = dot(&rf, &rt) / (dot(&rf, &rf) * dot(&rt, &rt)).sqrt();
    (rt.iter().fold(0.0, |m, r| m.max(r.abs())), corr)
}

fn run(mesh: [usize; 2], sets: &[&str]) -> Row {
    let mut all = vec![format!("body.strip.mesh.elements=[{},{}]", mesh[0], mesh[1])];
    all.extend(sets.iter().map(|s| s.to_string()));
    let refs: Vec<&str> = all.iter().map(String::as_str).collect();
    let p = common::scene("strip-channel", &refs);
    let t0 = Instant::now();
    let (r, mem) = common::solve(&p);
    let wall = t0.elapsed().as_secs_f64();
    let curve: Vec<(f64, f64)> = (mem.increments.iter())
        .filter_map(|i| i.monitor.as_ref().map(|m| (m.displacement, m.force)))
        .collect();
    let peak = curve.iter().map(|p| p.1).fold(f64::MIN, f64::max);
    let (tilt, tilt_force_correlation) = normal_tilt(&mem);
    let row = Row {
        mesh,
        sets: sets.iter().map(|s| s.to_string()).collect(),
        complete: r.is_ok(),
        reached: curve.last().map_or(0.0, |p| p.0),
        peak,
        spike: spike(&curve, [4.0, 5.5]).unwrap_or(f64::NAN),
        augmentations: r.as_ref().map_or(0, |s| s.augmentations),
        iterations: r.as_ref().map_or(0, |s| s.newton_iterations),
        wall,
        tilt,
        tilt_force_correlation,
    };
    println!(
        "{}×{} {:?}: {}, peak {:.5}, spikes {:.4} % of it, normal tilt at C {:.2e} rad \
         (correlation with F {:+.4}), {} iterations, {} updates, {:.1} s",
        mesh[0],
        mesh[1],
        row.sets,
        if row.complete { "full insertion" } else { "FAILED" },
        row.peak,
        100.0 * row.spike,
        row.tilt,
        row.tilt_force_correlation,
        row.iterations,
        row.augmentations,
        wall
    );
    row
}

fn smoothing(mesh: [usize; 2]) -> [Row; 3] {
    ["none", "hermite", "bezier"].map(|s| run(mesh, &[&format!("contact.master_smoothing={s}")]))
}

#[test]
#[cfg_attr(debug_assertions, ignore = "release tier")]
fn smoothed_faces_reach_full_insertion_with_smaller_crossing_spikes() {
    // measured (docs/methods.md): spikes 24×1 0.059 / 0.071 / 0.028 %, 48×2 0.148 / 0.100 /
    // 0.029 % (none / hermite / bezier)
    for (mesh, bound) in [([24, 1], [0.0007, 0.0008, 0.0004]), ([48, 2], [0.0017, 0.0012, 0.0004])] {
        let rows = smoothing(mesh);
        for (r, b) in rows.iter().zip(bound) {
            assert!(r.complete, "{r:?}");
            assert!(r.spike < b, "{r:?}: spikes above {b}");
        }
        let [none, hermite, bezier] = &rows;
        assert!(bezier.spike < hermite.spike && bezier.spike < none.spike, "{rows:?}");
        // the smoothed face changes the peak by less than its spikes
        for r in [hermite, bezier] {
            assert!((r.peak / none.peak - 1.0).abs() < 2e-3, "{r:?} vs {none:?}");
        }
    }
}

/// Why the Hermite face does not meet the issue's bound: the force's oscillation over
/// v ∈ [4, 5.5] is the tilt of the face's normal at C (correlation of the two cubic-fit
/// residuals below −0.99, the normal force itself smooth), and that tilt grows under
/// refinement (measured 0.91e-3, 1.13e-3, 2.68e-3, 5.14e-3 rad on 24×1 … 240×8).
#[test]
#[cfg_attr(debug_assertions, ignore = "release tier")]
fn crossing_spikes_are_the_tilt_of_the_normal_at_the_corner() {
    let coarse = run([24, 1], &["contact.master_smoothing=hermite"]);
    let fine = run([48, 2], &["contact.master_smoothing=hermite"]);
    for r in [&coarse, &fine] {
        assert!(r.complete && r.tilt_force_correlation < -0.99, "{r:?}");
        // dF/dθ ≈ −4.5 here: the spikes are the tilt times the force's lever, not more
        assert!(
            r.spike * r.peak < 6.0 * r.tilt && r.spike * r.peak > 3.0 * r.tilt,
            "{r:?}"
        );
    }
    assert!(
        fine.tilt > 1.1 * coarse.tilt,
        "the tilt grows under refinement: {coarse:?} {fine:?}"
    );
}

/// The issue's criterion as it stands: the Hermite face's spikes below 0.1 % of the peak on
/// every mesh from 24×1 to 240×8. It fails from 120×4 on (see the header).
#[test]
#[ignore = "fails: Hermite spikes 0.071, 0.100, 0.235, 0.450 % on 24×1, 48×2, 120×4, 240×8 (bound 0.1 %); \
            cargo test --release --test methods_strip hermite_face -- --ignored --nocapture"]
fn hermite_face_meets_the_issue_spike_bound_on_every_mesh() {
    let rows: Vec<Row> = [[24, 1], [48, 2], [120, 4], [240, 8]]
        .into_iter()
        .map(|m| run(m, &["contact.master_smoothing=hermite"]))
        .collect();
    let over: Vec<String> = (rows.iter())
        .filter(|r| !r.complete || r.spike >= 1e-3)
        .map(|r| format!("{}×{}: {:.3} %", r.mesh[0], r.mesh[1], 100.0 * r.spike))
        .collect();
    assert!(
        over.is_empty(),
        "spikes at or above 0.1 % of the peak: {}",
        over.join(", ")
    );
}

#[test]
#[cfg_attr(debug_assertions, ignore = "release tier")]
fn augmented_peak_force_does_not_depend_on_the_penalty() {
    let eps = [2.1e3, 2.1e4, 2.1e5];
    let spread = |enforcement: &str, smoothing: &str, mesh: [usize; 2]| {
        let peaks: Vec<f64> = eps
            .iter()
            .map(|e| {
                let r = run(
                    mesh,
                    &[
                        &format!("contact.eps_n={e}"),
                        &format!("contact.eps_t={e}"),
                        &format!("contact.enforcement={enforcement}"),
                        &format!("contact.master_smoothing={smoothing}"),
                    ],
                );
                // Known failure of the contact Newton (docs/methods.md): the soft penalty
                // (ε = 0.1 E) stops where the strip's end passes C (v ≈ 9.14: C leaves the
                // face's last segment while the end node meets the block at its vertex),
                // long after the peak (v ≈ 3.4) this study compares.
                let soft_penalty_end = enforcement == "penalty" && *e < 2.1e4 && r.reached > 9.0;
                assert!(r.complete || soft_penalty_end, "{r:?}");
                r.peak
            })
            .collect();
        let (lo, hi) = peaks
            .iter()
            .fold((f64::MAX, f64::MIN), |a, p| (a.0.min(*p), a.1.max(*p)));
        hi / lo - 1.0
    };
    let augmented = spread("augmented", "none", [24, 1]);
    let penalty = spread("penalty", "none", [24, 1]);
    println!("24×1: peak spread over eps = 2.1e3 … 2.1e5: augmented {augmented:.2e}, penalty {penalty:.2e}");
    assert!(augmented < 1e-3, "the issue's bound: {augmented}");
    // measured 4.6e-10 against 4.9e-4 with the penalty alone
    assert!(
        augmented < 1e-5 && penalty > 3e-4 && penalty < 1e-3,
        "{augmented} {penalty}"
    );
    let smooth = spread("augmented", "hermite", [48, 2]);
    println!("48×2 Hermite face: augmented spread {smooth:.2e}");
    assert!(smooth < 1e-4, "{smooth}");
}

/// The table of docs/methods.md: every smoothing on every mesh to 240×8, and the penalty
/// study over five decades.
#[test]
#[ignore = "minutes: cargo test --release --test methods_strip methods_strip_full_study -- --ignored --nocapture"]
fn methods_strip_full_study() {
    let mut rows = Vec::new();
    for mesh in [[24, 1], [48, 2], [120, 4], [240, 8]] {
        rows.extend(smoothing(mesh));
    }
    println!("| mesh | smoothing | outcome | peak force | spikes / peak | normal tilt at C | Newton its | wall |");
    println!("|---|---|---|---|---|---|---|---|");
    for r in &rows {
        println!(
            "| {}×{} | {} | {} | {:.5} | {:.3} % | {:.2e} rad | {} | {:.1} s |",
            r.mesh[0],
            r.mesh[1],
            r.sets[0].trim_start_matches("contact.master_smoothing="),
            if r.complete { "full insertion" } else { "failed" },
            r.peak,
            100.0 * r.spike,
            r.tilt,
            r.iterations,
            r.wall
        );
    }
    for r in &rows {
        assert!(r.complete, "{r:?}");
    }
    // measured (docs/methods.md): spikes / peak in % (none, hermite, bezier) 24×1 0.059,
    // 0.071, 0.028; 48×2 0.148, 0.100, 0.029; 120×4 0.418, 0.235, 0.061; 240×8 0.825, 0.450,
    // 0.117: both smoothings cut them from 48×2 on, Bézier most, none below 0.1 % on 240×8
    for chunk in rows.chunks(3).skip(1) {
        let [none, hermite, bezier] = chunk else { unreachable!() };
        assert!(
            bezier.spike < hermite.spike && hermite.spike < 0.7 * none.spike,
            "{chunk:?}"
        );
        assert!(bezier.spike < 1.5e-3, "{chunk:?}");
    }
    for e in [2.1e2, 2.1e3, 2.1e4, 2.1e5, 2.1e6] {
        for en in ["penalty", "augmented"] {
            run(
                [24, 1],
                &[
                    &format!("contact.eps_n={e}"),
                    &format!("contact.eps_t={e}"),
                    &format!("contact.enforcement={en}"),
                ],
            );
        }
    }
}
