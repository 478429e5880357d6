//! A penalty too soft for its load is reported: the run warns when a contact point sinks
//! into its master by more than a tenth of the element size there.
//!
//! ```text
//!            ● P, 0.01 above the plate, pressed 0.03 down (0.02 into the plate)
//!   ┌────────────────────────────┐ y = 0     plate 1 × 0.1, 40 × 4 elements (edge 0.025),
//!   └────────────────────────────┘ y = −0.1  E = 1e3, fixed at its bottom
//! ```
//! Scene `tests/data/point-through-plate.toml` with the motion the plate can take.
//!
//! Reference: a penalty contact lets the bodies overlap by N/ε_N. With ε_N = 10 (a hundredth
//! of E) the point carries almost nothing and sinks nearly the whole 0.02 into the plate:
//! most of an element, a contact the scene did not mean, and a run that says nothing of it
//! reports a force that is mostly penalty error. With ε_N = 1e6 the overlap is a small
//! fraction of the element.
//!
//! Asserted: with ε_N = 10 the summary's deepest penetration is beyond 0.1 of the element
//! size (measured ≈ 0.8), names the pair, and the log carries the warning once; with
//! ε_N = 1e6 the summary has no such entry.

mod common;

use contrail::solver::penetration::DEEP_PENETRATION;

fn run(eps_n: &str) -> (contrail::solver::RunSummary, contrail::record::Memory) {
    let eps_n = format!("contact.eps_n={eps_n}");
    let sets = [
        "rigid.P.move.y=[[0.0, 0.0], [1.0, -0.03]]",
        &eps_n,
        "stepping.increments=4",
    ];
    let text = include_str!("data/point-through-plate.toml");
    common::solve_ok(&common::scene_file("tests/data/point-through-plate.toml", text, &sets))
}

#[test]
fn soft_penalty_is_reported_as_deep_penetration() {
    let (summary, m) = run("10");
    let p = summary.deep_penetration.expect("no penetration warning");
    println!("ε_N = 10: depth {:.4e}, ratio {:.3}", p.depth, p.ratio);
    assert!(p.ratio > DEEP_PENETRATION, "{p:?}");
    assert_eq!(p.pair, "point");
    let warnings = m
        .logs
        .iter()
        .filter(|l| l.message.contains("penetrates its master"))
        .count();
    assert_eq!(
        warnings,
        1,
        "{:#?}",
        m.logs.iter().map(|l| &l.message).collect::<Vec<_>>()
    );
}

#[test]
fn stiff_penalty_is_not_reported() {
    let (summary, _) = run("1e6");
    assert!(summary.deep_penetration.is_none(), "{:?}", summary.deep_penetration);
}
