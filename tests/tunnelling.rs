//! A rigid point driven through a thin plate: the contact must not be lost silently.
//!
//! ```text
//!            ● P (0.5, 0.01), driven 0.21 down in one increment
//!   ┌────────────────────────────┐ y = 0     plate 1 × 0.1, 40 × 4 elements, E = 1e3,
//!   └────────────────────────────┘ y = −0.1  fixed at its bottom; ε_N = 1e4
//! ```
//! Scene `tests/data/point-through-plate.toml`. The search radius is twice the largest
//! element edge (0.05): deeper inside the plate than that, a point cannot be told from one
//! beyond its far side, and the pairing drops it.
//!
//! Reference: the motion cannot be balanced by the plate (it would have to be squashed to
//! less than nothing), so the run must not complete with the point through the plate and
//! no force on it — what it did before: one increment, zero Newton iterations, force 0,
//! exit 0. Remedy: a point paired at the previous iterate (or, at the first iterate, at
//! the last converged increment or in the initial configuration) that is found deeper
//! inside its master than the search radius has passed through it; such an iterate is
//! inadmissible (a Newton correction is shortened, the start of an increment cut back).
//! Asserted on 40 × 4 (1 and 2 increments) and 80 × 8 (1 increment): the run fails and its
//! log names the point that passed through; a motion the plate can take (0.03 down, 0.02 into
//! the plate; on 80 × 8 0.015 down) completes with a positive force.

mod common;

const SCENE: &str = include_str!("data/point-through-plate.toml");

fn run(
    sets: &[&str],
) -> (
    Result<contrail::solver::RunSummary, contrail::solver::SolveError>,
    contrail::record::Memory,
) {
    common::solve(&common::scene_file("tests/data/point-through-plate.toml", SCENE, sets))
}

/// The mesh and the number of increments as overrides.
fn refined(elements: [usize; 2], increments: usize) -> [String; 2] {
    [
        format!("body.plate.mesh.elements=[{}, {}]", elements[0], elements[1]),
        format!("stepping.increments={increments}"),
    ]
}

#[test]
fn point_driven_through_a_plate_is_not_lost_silently() {
    for (elements, increments) in [([40, 4], 1), ([80, 8], 1), ([40, 4], 2)] {
        let sets = refined(elements, increments);
        let (r, m) = run(&[&sets[0], &sets[1]]);
        assert!(
            r.is_err(),
            "{elements:?}, {increments} increments: the run completed: {:?}",
            m.increments.last().map(|i| &i.monitor)
        );
        let named = m
            .logs
            .iter()
            .any(|l| l.message.contains("passed through their master") && l.message.contains("rigid P of `point`"));
        assert!(
            named,
            "{elements:?}, {increments} increments: {:#?}",
            m.logs.iter().map(|l| &l.message).collect::<Vec<_>>()
        );
    }
}

#[test]
fn point_pressed_within_reach_completes_with_a_force() {
    // 0.02 into the plate on 40 × 4 (in 1 and 2 increments); 0.005 on 80 × 8, where 0.02
    // (1.6 elements deep under a point load) inverts the element under the point and the
    // run stops saying so
    for (elements, increments, depth) in [([40, 4], 1, 0.03), ([40, 4], 2, 0.03), ([80, 8], 1, 0.015)] {
        let sets = refined(elements, increments);
        let motion = format!("rigid.P.move.y=[[0.0, 0.0], [1.0, -{depth}]]");
        let (r, m) = run(&[&sets[0], &sets[1], &motion]);
        r.unwrap_or_else(|e| panic!("{elements:?}, {increments} increments: {e}"));
        let f = m.increments.last().unwrap().monitor.as_ref().unwrap().force;
        assert!(f > 0.0, "{elements:?}, {increments} increments: {f}");
    }
}
