//! A one-layer beam refined along its length under large bending: the default element must
//! not hourglass when its elements become many times taller than long.
//!
//! ```text
//!  |▯▯▯▯▯▯▯▯▯▯▯▯▯▯▯▯▯▯▯▯▯▯▯▯▯▯▯▯▯▯▯▯▯▯▯▯▯▯▯▯▯|  ↓ P = k EI/L² (dead, at the tip)
//!  clamped     L = 10, h = 0.5; 24 … 480 elements along, 1 or 2 through the thickness
//! ```
//! Scene `cantilever` (plane strain, St. Venant–Kirchhoff, E = 2.1e4, ν = 0.3), k = 10 and
//! 16 (the built-in scene's k is 4). At k = 10 the fibres near the clamp are compressed by
//! ≈ 25 %; 240 × 1 elements are 12 times taller than long, 480 × 1 24 times.
//!
//! Reference: the tip deflection of Reissner's geometrically exact beam with the strip's
//! axial and shear compliance (`analysis::elastica`: EI = E h³/(12(1 − ν²)),
//! EA = E h/(1 − ν²), GA = 5/6 G h), v/L = 0.81371 (k = 10) and 0.85738 (k = 16); the
//! inextensible elastica (Mattiasson 1981) gives 0.81061 and 0.85275.
//!
//! Measured (2026-11-25, 40 increments): the default element `q4-eas-safe` within
//! −0.03 … +0.07 % of the reference on every mesh; plain `q4-eas` on 240 × 1 at k = 10
//! reports v/L = 0.967 (+19 %) and on 480 × 2 0.932 (+15 %), with elements that lost
//! stability from increment 19 (3) on; at k = 16 it fails on 240 × 1 and 480 × 1.
//! Asserted:
//! * the default element within 0.5 % of the reference on every mesh of the study
//!   (24, 60, 120, 240 × 1 and 240 × 2 here; 480 × 1 and 480 × 2 in the full study), at 40
//!   increments and at 80 (the step refined), and no element reported unstable;
//! * plain EAS forced on 240 × 1: the run's log warns that elements lost stability; if the
//!   run completes, its answer is more than 10 % off — the warning is not idle (since the
//!   element checks det F, measured 2026-11-26, the run stops at t ≈ 0.61 where an element
//!   folds, after the warning).
//!
//! Release tier (`cargo test --release --test one_layer_beam`); the full study is
//! `-- --include-ignored`.

mod common;

use contrail::analysis::elastica::{beam_stiffness, cantilever_tip};
use contrail::solver::RunSummary;

const L: f64 = 10.0;
const TOLERANCE: f64 = 5e-3;

/// `(v/L, summary)` of the cantilever scene at load factor `k`.
fn tip(k: f64, mesh: [usize; 2], increments: usize, element: Option<&str>) -> (f64, RunSummary) {
    let section = beam_stiffness(2.1e4, 0.3, 0.5);
    let total = format!("load.0.total={}", -k * section.ei / (L * L));
    let elements = format!("body.strip.mesh.elements=[{}, {}]", mesh[0], mesh[1]);
    let incs = format!("stepping.increments={increments}");
    let mut sets = vec![total, elements, incs];
    if let Some(e) = element {
        sets.push(format!("body.strip.element={e}"));
    }
    let sets: Vec<&str> = sets.iter().map(String::as_str).collect();
    let (s, _) = common::solve_ok(&common::scene("cantilever", &sets));
    (s.monitor.as_ref().unwrap().displacement / L, s)
}

fn study(meshes: &[[usize; 2]]) {
    let section = beam_stiffness(2.1e4, 0.3, 0.5);
    for k in [10.0, 16.0] {
        let (reference, _) = cantilever_tip(section, L, k);
        for &mesh in meshes {
            for increments in [40, 80] {
                let (v, s) = tip(k, mesh, increments, None);
                let error = v / reference - 1.0;
                println!(
                    "k = {k}, {mesh:?}, {increments} increments: v/L = {v:.5} ({:+.3} % of {reference:.5}), {} Newton iterations",
                    100.0 * error,
                    s.newton_iterations
                );
                assert!(error.abs() < TOLERANCE, "k = {k}, {mesh:?}: {v} vs {reference}");
                assert!(s.unstable_elements.is_none(), "{mesh:?}: {:?}", s.unstable_elements);
            }
        }
    }
}

#[test]
#[cfg_attr(debug_assertions, ignore = "release tier")]
fn one_layer_beam_default_element_holds_on_meshes_refined_along_the_length() {
    study(&[[24, 1], [60, 1], [120, 1], [240, 1], [240, 2]]);
}

#[test]
#[ignore = "full study"]
fn one_layer_beam_full_refinement_study() {
    study(&[[24, 1], [60, 1], [120, 1], [240, 1], [480, 1], [240, 2], [480, 2]]);
}

#[test]
#[cfg_attr(debug_assertions, ignore = "release tier")]
fn one_layer_beam_plain_eas_forced_is_reported_unstable_and_wrong() {
    let (reference, _) = cantilever_tip(beam_stiffness(2.1e4, 0.3, 0.5), L, 10.0);
    let section = beam_stiffness(2.1e4, 0.3, 0.5);
    let sets = [
        format!("load.0.total={}", -10.0 * section.ei / (L * L)),
        "body.strip.mesh.elements=[240, 1]".to_string(),
        "stepping.increments=40".to_string(),
        "body.strip.element=q4-eas".to_string(),
    ];
    let sets: Vec<&str> = sets.iter().map(String::as_str).collect();
    let (outcome, memory) = common::solve(&common::scene("cantilever", &sets));
    // the warning is in the run's log whether the run completes (with a wrong answer) or
    // stops where an element folds (det F < 0 is inadmissible)
    let warned = memory.logs.iter().any(|l| l.message.contains("have lost stability"));
    assert!(warned, "plain EAS on 240 × 1 logged no instability warning");
    match outcome {
        Ok(s) => {
            let v = s.monitor.as_ref().unwrap().displacement / L;
            let unstable = s
                .unstable_elements
                .expect("plain EAS on 240 × 1 reported no unstable element");
            println!(
                "q4-eas 240 × 1, k = 10: v/L = {v:.5} ({:+.1} %), unstable from increment {}, up to {} elements",
                100.0 * (v / reference - 1.0),
                unstable.first_increment,
                unstable.most
            );
            assert!((v / reference - 1.0).abs() > 0.1, "{v} vs {reference}");
            assert!(unstable.most >= 1 && unstable.worst_ratio < 0.0);
        }
        Err(e) => println!("q4-eas 240 × 1, k = 10: stops after the instability warning: {e}"),
    }
}
