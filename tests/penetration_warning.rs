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
//! Asserted on 40 × 4 (4 and 8 increments) and 80 × 8 (4 increments): with ε_N = 10 the
//! summary's deepest penetration is beyond 0.1 of the element size (measured 0.79, 0.79 and
//! 1.56: the overlap stays 0.0196 while the element halves), names the pair, and the log
//! carries the warning once; with ε_N = 1e6 the summary has no such entry.

mod common;

use contrail::solver::penetration::DEEP_PENETRATION;

/// The point pressed `depth` down (0.01 above the plate) with `eps_n` on `elements` in
/// `increments`.
fn run(
    eps_n: &str,
    elements: [usize; 2],
    increments: usize,
    depth: f64,
) -> (contrail::solver::RunSummary, contrail::record::Memory) {
    let sets = [
        format!("rigid.P.move.y=[[0.0, 0.0], [1.0, -{depth}]]"),
        format!("contact.eps_n={eps_n}"),
        format!("stepping.increments={increments}"),
        format!("body.plate.mesh.elements=[{}, {}]", elements[0], elements[1]),
    ];
    let sets: Vec<&str> = sets.iter().map(String::as_str).collect();
    let text = include_str!("data/point-through-plate.toml");
    common::solve_ok(&common::scene_file("tests/data/point-through-plate.toml", text, &sets))
}

#[test]
fn soft_penalty_is_reported_as_deep_penetration() {
    for (elements, increments) in [([40, 4], 4), ([80, 8], 4), ([40, 4], 8)] {
        let (summary, m) = run("10", elements, increments, 0.03);
        let p = summary.deep_penetration.expect("no penetration warning");
        println!(
            "ε_N = 10, {elements:?}, {increments} increments: depth {:.4e}, ratio {:.3}",
            p.depth, p.ratio
        );
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
}

#[test]
fn stiff_penalty_is_not_reported() {
    // 0.015 down on 80 × 8: 0.03 (1.6 elements deep under a point load) inverts the element
    // under the point there (`tunnelling.rs`)
    for (elements, increments, depth) in [([40, 4], 4, 0.03), ([40, 4], 8, 0.03), ([80, 8], 4, 0.015)] {
        let (summary, _) = run("1e6", elements, increments, depth);
        assert!(
            summary.deep_penetration.is_none(),
            "{elements:?}: {:?}",
            summary.deep_penetration
        );
    }
}

/// In 3D too: the small sliding block (`tests/data/slide-3d-small.toml`, element edge 0.5)
/// pressed 0.2 into the slab with ε_N = 10 per unit area (a hundredth of E) sinks most of the
/// 0.2 (beyond 0.1 of its edge: reported, naming the pair); at the scene's own ε_N = 1e6 and
/// 0.01 it is not.
#[test]
fn a_soft_penalty_in_3d_is_reported_as_deep_penetration() {
    const SLIDE: &str = include_str!("data/slide-3d-small.toml");
    let soft = SLIDE
        .replace("eps_n = 1.0e6", "eps_n = 10.0")
        .replace("[1.0, -0.01], [2.0, -0.01]", "[1.0, -0.2], [2.0, -0.2]");
    let (_, summary, _) = common::solve_solid_text("soft-slide.toml", &format!("{soft}increments = 4\n"));
    let deep = summary.deep_penetration.expect("reported");
    println!(
        "3D, ε_N = 10: {} sinks {:.3e}, {:.2} of its element edge",
        deep.slave, deep.depth, deep.ratio
    );
    assert!(deep.ratio > DEEP_PENETRATION && deep.pair == "base", "{deep:?}");
    let (_, stiff, _) = common::solve_solid_text("slide.toml", &format!("{SLIDE}increments = 4\n"));
    assert!(stiff.deep_penetration.is_none(), "{:?}", stiff.deep_penetration);
}
