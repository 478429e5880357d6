//! A very stiff penalty converges to the round-off of its own forces: a rigid cylinder pressed
//! into a block with ε_N = ε_T = 1e6 E gives the press force of ε = 1e3 E.
//!
//! ```text
//!        ╭─────╮  rigid cylinder R = 1, centre (0, 1), pressed 0.04 down, μ = 0.2
//!   ─────┴──●──┴──────  block 4.5 × 2 (x from −2), E = 1e3, ν = 0.3, Neo-Hooke, fixed at its
//!   │                │  bottom; its top node at x = 0 touches the cylinder at t = 0
//!   └────────────────┘
//! ```
//! Scene `tests/data/cylinder-press.toml`.
//!
//! Reference: the same press with ε = 1e3 E (the penalty error of the press force is of the
//! order of its overlap N/ε_N over the indentation, ≈ 1e-4 at 1e3 E; at 1e6 E it is 1000×
//! smaller). A penalty force is ε times a difference of coordinates, so with ε = 1e9 and a
//! cylinder centred 1 above the origin its round-off is ≈ ε ε_mach · 2 ≈ 4e-7 per point: the
//! residual cannot fall below that. Before the convergence test's round-off floor counted the
//! rigid geometry's coordinates (the arc's centre and radius; only the slave node's, ≈ 0
//! here, were counted) the first increment stalled at 5.7e-8 above a tolerance of 1e-13 and
//! the run failed with "no convergence" at every cut-back.
//!
//! Asserted (release tier) on 36 × 6 elements in 10 and 20 increments and 72 × 12 in 20:
//! ε = 1e6 E completes and its final press force is within 5e-4 of ε = 1e3 E's (measured
//! 2026-11-26: 2.2e-4, 2.2e-4, 1.2e-4), with at most 2 cut-backs (the contact Newton's
//! criterion; measured 0 — before it, 8, 6, 0 and 46 on 144 × 24). Also on 144 × 24,
//! frictionless (which stopped with an active-set cycle at t = 0.15 before), and the press
//! followed by a slide of 0.5 (which stopped at its onset after 247 cut-backs): at most 2
//! cut-backs each (measured 0, 0).
mod common;

fn press(elements: [usize; 2], increments: usize, eps: f64) -> (f64, contrail::solver::RunSummary) {
    let sets = [
        format!("body.block.mesh.elements=[{}, {}]", elements[0], elements[1]),
        format!("stepping.increments={increments}"),
        format!("contact.eps_n={eps:e}"),
        format!("contact.eps_t={eps:e}"),
    ];
    let sets: Vec<&str> = sets.iter().map(String::as_str).collect();
    let text = include_str!("data/cylinder-press.toml");
    let problem = common::scene_file("tests/data/cylinder-press.toml", text, &sets);
    let (summary, _) = common::solve_ok(&problem);
    let force = summary.monitor.as_ref().expect("a press monitor").force;
    (force, summary)
}

#[test]
#[cfg_attr(debug_assertions, ignore = "release tier")]
fn a_penalty_of_a_million_young_moduli_gives_the_press_force_of_a_thousand() {
    for (elements, increments) in [([36, 6], 10), ([36, 6], 20), ([72, 12], 20)] {
        let (reference, _) = press(elements, increments, 1e6);
        let (stiff, summary) = press(elements, increments, 1e9);
        let deviation = (stiff - reference).abs() / reference;
        let per_increment = summary.newton_iterations as f64 / summary.increments as f64;
        println!(
            "{elements:?}, {increments} increments: press {reference:.6} (1e3 E), {stiff:.6} (1e6 E), \
             deviation {deviation:.2e}, {per_increment:.2} Newton its per increment, {} cut-backs",
            summary.cutbacks
        );
        assert!(deviation <= 5e-4, "press {stiff} against {reference}");
        assert!(reference > 1.0, "no press force: {reference}");
        assert!(summary.cutbacks <= 2, "{} cut-backs", summary.cutbacks);
    }
}

/// The stiff press on 144 × 24 frictionless, and pressed then slid 0.5 with μ = 0.2.
#[test]
#[cfg_attr(debug_assertions, ignore = "release tier")]
fn a_penalty_of_a_million_young_moduli_presses_frictionless_and_slides_with_at_most_two_cutbacks() {
    let text = include_str!("data/cylinder-press.toml");
    let stiff = ["contact.eps_n=1e9", "contact.eps_t=1e9"];
    let frictionless = [&stiff[..], &["body.block.mesh.elements=[144, 24]", "contact.mu=0"]].concat();
    let slide = [
        &stiff[..],
        &[
            "stepping.end=3.0",
            "stepping.increments=60",
            "rigid.cyl.move.x=[[0.0, 0.0], [1.0, 0.0], [3.0, 0.5]]",
            "rigid.cyl.move.y=[[0.0, 0.0], [1.0, -0.04], [3.0, -0.04]]",
        ],
    ]
    .concat();
    for sets in [frictionless, slide] {
        let problem = common::scene_file("tests/data/cylinder-press.toml", text, &sets);
        let (s, _) = common::solve_ok(&problem);
        println!(
            "{sets:?}: {} Newton iterations, {} cut-backs",
            s.newton_iterations, s.cutbacks
        );
        assert!(s.cutbacks <= 2, "{sets:?}: {} cut-backs", s.cutbacks);
    }
}
