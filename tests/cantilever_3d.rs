//! 3D cantilever in bending (built-in scene `cantilever-3d`): EAS hexahedra, one and two
//! elements through the thickness, against the Euler–Bernoulli tip deflection.
//!
//! ```text
//!   |▓▓▓▓▓▓▓▓▓▓▓▓▓▓▓▓▓▓▓▓▓▓▓▓▓▓▓▓▓▓▓▓▓▓▓▓▓|  ↓ P
//!   |<-------------- L = 10 --------------->|   section 1 × 1, clamped at x = 0
//! ```
//!
//! Reference: `δ_EB = P L³ / (3 E I)`, `I = b h³/12` = 0.4 for P = 0.1, E = 1000; Timoshenko
//! adds `P L / (κ G A)` = 0.0031 (κ = 5/6), so the converged 3D answer lies about 0.8 %
//! above `δ_EB` (less the stiffening of the clamp's Poisson constraint). ν = 0.3, St.
//! Venant–Kirchhoff, δ/L = 4e-2: geometric nonlinearity below 0.1 %.
//! Tolerance: within 3 % of `δ_EB` with one element through the thickness (10×1×1) and
//! with two (20×2×2), and the 10×1×1, 20×2×2 and 40×4×4 answers within 0.5 % of each
//! other (mesh-converged); the plain trilinear element (`element = "q4"`, i.e. `hex8`)
//! locks, below 80 % of it on the coarse mesh (so the test can tell).
//! Measured: δ/δ_EB − 1 = −0.52 % (10×1×1), −0.69 % (20×2×2), −0.34 % (40×4×4); plain hex8
//! −35 %.

use contrail::record::Memory;
use std::sync::atomic::AtomicBool;

const DELTA_EB: f64 = 0.1 * 1000.0 / (3.0 * 1000.0 / 12.0);

fn tip_deflection(sets: &[&str]) -> f64 {
    let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
    let (src, problem) = contrail::load_any_scene("cantilever-3d", &sets).expect("the scene loads");
    let contrail::scene::AnyProblem::Solid(problem) = problem else {
        panic!("cantilever-3d is a 3D scene")
    };
    let info = contrail::run_info(&src, &sets, &problem);
    let mut mem = Memory::default();
    let summary = contrail::solver::run(&problem, &info, &mut mem, &AtomicBool::new(false)).expect("converges");
    summary.monitor.expect("a monitor").displacement
}

#[test]
fn eas_hexahedra_bend_without_locking_and_converge() {
    let coarse = tip_deflection(&[]);
    let fine = tip_deflection(&["body.beam.mesh.elements=[20, 2, 2]"]);
    let finest = tip_deflection(&["body.beam.mesh.elements=[40, 4, 4]"]);
    let plain = tip_deflection(&["body.beam.element=\"q4\""]);
    let err = |d: f64| d / DELTA_EB - 1.0;
    println!(
        "tip deflection / δ_EB − 1: 10×1×1 {:+.5}, 20×2×2 {:+.5}, 40×4×4 {:+.5}; plain hex8 10×1×1 {:+.4}",
        err(coarse),
        err(fine),
        err(finest),
        err(plain)
    );
    assert!(err(coarse).abs() < 0.03, "coarse: {coarse}");
    assert!(err(fine).abs() < 0.03, "fine: {fine}");
    for d in [coarse, fine] {
        assert!((d / finest - 1.0).abs() < 0.005, "{d} against the 40×4×4 {finest}");
    }
    assert!(plain < 0.8 * DELTA_EB, "the plain element should lock: {plain}");
}
