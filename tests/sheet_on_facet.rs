//! A thin sheet lying at zero gap on a facet of a rigid polygon: the zero-gap start in
//! tension (the contact carries nothing) and the pull over the polygon's vertex.
//!
//! ```text
//!   pinned ↓ pulled (t > 0.5)                              T (dead, t ≤ 0.5 ramp) →
//!   ●━━━━━━━━━━━━━●━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━━●━━━━━━━━━━━━━●
//!   x = −2        ┌───────────── facet y = 1 ─────┐             x = 2
//!                 │     rigid square, R = √2      │   sheet 4 × 0.01, 400 × 1 elements,
//!                 └───────────────────────────────┘   E = 1e5, ν = 0.3 (h/R ≈ 0.007)
//! ```
//! Scene `tests/data/sheet-on-facet.toml`: the sheet's bottom face lies exactly on the
//! square's top facet (its nodes at zero gap); the right end is pulled by a dead load T = 1
//! (t ≤ 0.5), then the left end is pulled down 0.4 over the vertex at (−1, 1) (t ≤ 1.5) and
//! let back up (t ≤ 2.5): the sheet wraps the vertex, and lifts off the facet beside it by its
//! bending stiffness. μ = 0.3, ε_N = ε_T = 1e4.
//!
//! Reference: in the tension phase the exact answer is the sheet in uniform tension, its
//! bottom face on the facet with no contact force (every point touches and carries nothing).
//! Failure it guards: every point of the facet started closed with the penalty's stiffness
//! at zero force, and the slip branch's tangent `μ ∂N` coupled normal and tangential motion
//! at points that carry nothing; Newton then peeled the sheet off one point per iteration
//! and the run stopped at the first increment (tens of points changing), at every cut-back.
//! Remedies (general rules of the solver, `contact/point.rs`, `solver/active_set.rs`): a
//! point touching to round-off is open unless the first correction, probed with it open,
//! pushes it into the master (then it is held closed for that correction: the contact patch
//! test's zero-gap start in compression); a point without pressure transmits no friction and
//! has no friction stiffness.
//! Asserted: the tension phase converges in at most two Newton iterations per increment (one
//! in most) with μ = 0 and 0.3 and ε_N from 1e2 to 1e6, with no contact force anywhere (|N| ≤ 1e-9 T); the whole
//! scene with friction completes at the nominal and half step, and the sheet ends where it
//! started (|u| ≤ 1e-3 at the pulled end, the pull reversed).
//! Still failing (printed by the full study, `-- --include-ignored`): the pull over the vertex
//! frictionless, and with ε_N = 1e2 (an active-set cycle at the first increment of the pull).

mod common;

const SCENE: &str = include_str!("data/sheet-on-facet.toml");

type Outcome = (
    Result<contrail::solver::RunSummary, contrail::solver::SolveError>,
    contrail::record::Memory,
);

fn solve(sets: &[&str]) -> Outcome {
    let src = contrail::scene::SceneSource {
        origin: "tests/data/sheet-on-facet.toml".into(),
        text: SCENE.into(),
    };
    let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
    let file = contrail::scene::parse(&src, &sets).unwrap_or_else(|e| panic!("{e}"));
    common::solve(&contrail::scene::build(&src, &file).unwrap_or_else(|e| panic!("{e}")))
}

#[test]
fn sheet_on_facet_tension_from_zero_gap_converges_in_two_iterations_or_fewer() {
    for mu in ["0", "0.3"] {
        for eps in ["1e2", "1e4", "1e6"] {
            let sets = [
                "stepping.end=0.5".to_string(),
                "stepping.increments=10".to_string(),
                format!("contact.mu={mu}"),
                format!("contact.eps_n={eps}"),
                format!("contact.eps_t={eps}"),
            ];
            let sets: Vec<&str> = sets.iter().map(String::as_str).collect();
            let (r, m) = solve(&sets);
            let s = r.unwrap_or_else(|e| panic!("μ = {mu}, ε = {eps}: {e}"));
            let largest = m
                .contact
                .last()
                .unwrap()
                .iter()
                .map(|p| p.normal_force.abs())
                .fold(0.0, f64::max);
            println!(
                "μ = {mu}, ε = {eps}: {} increments, {} Newton iterations, {} cut-backs, largest |N| {largest:.1e}",
                s.increments, s.newton_iterations, s.cutbacks
            );
            assert_eq!(s.cutbacks, 0);
            let most = m.increments.iter().map(|i| i.iterations).max().unwrap();
            assert!(most <= 2, "{most} iterations in an increment");
            assert!(largest <= 1e-9, "{largest}");
        }
    }
}

#[test]
#[cfg_attr(debug_assertions, ignore = "release tier")]
fn sheet_on_facet_pulled_over_the_vertex_and_back_with_friction() {
    for inc in ["stepping.increments=100", "stepping.increments=200"] {
        let (r, m) = solve(&[inc]);
        let s = r.unwrap_or_else(|e| panic!("{inc}: {e}"));
        let end = m.increments.last().unwrap().monitor.as_ref().unwrap().displacement;
        println!(
            "{inc}: {} increments, {} Newton iterations, {} cut-backs; pulled end at {end:.2e}",
            s.increments, s.newton_iterations, s.cutbacks
        );
        assert!(end.abs() < 1e-3, "{end}");
    }
}

#[test]
#[ignore = "full study: prints the cases that still fail"]
fn sheet_on_facet_full_study() {
    for sets in [
        ["contact.mu=0", "contact.eps_n=1e4"],
        ["contact.mu=0.3", "contact.eps_n=1e2"],
        ["contact.mu=0.3", "contact.eps_n=1e6"],
    ] {
        let (r, _) = solve(&sets);
        println!(
            "{sets:?}: {:?}",
            r.map(|s| (s.increments, s.newton_iterations, s.cutbacks))
        );
    }
}
