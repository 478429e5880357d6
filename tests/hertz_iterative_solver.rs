//! Hertz line contact (the built-in `hertz` scene, 40 × 30 mesh: rigid cylinder R = 1 pressed
//! into a Neo-Hookean block, penalty contact) solved twice: with faer's sparse LU and with
//! the multigrid-preconditioned Krylov solver (`solver.linear_solver = "iterative"`,
//! `linalg::iterative`, relative residual 1e-9 per solve).
//!
//! Reference: the LU run. Tolerances: the Newton iterations within one of the LU run's (the
//! inexact solves change the last iterate: measured 20 against 21) and no cut-back in
//! either, every contact point's normal force equal to 1e-6 of the largest, and the
//! iterative solver really used (every Newton solve converged by it, none handed to the
//! LU). The symmetric tangent is indefinite in some iterates, so the solves are BiCGStab's.

mod common;

use contrail::solver::RunSummary;

#[test]
fn iterative_and_direct_solvers_give_the_same_hertz_contact() {
    let mut runs = Vec::new();
    for solver in ["sparse-lu", "iterative"] {
        let set = format!("solver.linear_solver={solver}");
        runs.push(common::solve_ok(&common::scene(
            "hertz",
            &["body.block.mesh.elements=[40, 30]", &set],
        )));
    }
    let ((lu, lu_mem), (it, it_mem)) = (&runs[0], &runs[1]);
    assert_iterative_used_and_agrees("2D", lu, it);
    common::assert_same_normal_forces(lu_mem, it_mem, 1e-6, ("LU", "iterative"));
}

/// The 3D Hertz sphere (the built-in `hertz-3d`, 8×8×6 hexahedra with 21 enhanced modes,
/// rigid sphere pressed 0.005 into a Neo-Hookean block, 1 863 unknowns) solved with faer's
/// sparse LU and with the multigrid-preconditioned Krylov solver, whose near-null space is
/// the six rigid-body modes of each 3D node (`NearNullSpace::rigid_body`).
///
/// Tolerances as for the 2D scene above: Newton iterations within one, no cut-back, every
/// 3D contact point's normal force equal to 1e-6 of the largest; the iterative solver used
/// for every Newton solve on a hierarchy with a coarse level; at most 520 Krylov iterations
/// in all (measured 2026-11-27: 462–464, at most 45 per solve; with the three translations
/// alone as the near-null space 586, at most 56 — the rotations are what the bound checks).
#[test]
fn iterative_and_direct_solvers_give_the_same_3d_hertz_contact() {
    let mut runs = Vec::new();
    for solver in ["sparse-lu", "iterative"] {
        let text = format!(
            "{}\n[solver]\nlinear_solver = \"{solver}\"\n",
            include_str!("../scenes/hertz-3d.toml")
        );
        let (_, summary, mem) = common::solve_solid_text("scenes/hertz-3d.toml", &text);
        runs.push((summary, mem));
    }
    let ((lu, lu_mem), (it, it_mem)) = (&runs[0], &runs[1]);
    assert_iterative_used_and_agrees("3D", lu, it);
    let stats = it.iterative;
    assert_eq!(
        stats.solves, it.newton_iterations,
        "a Newton solve was not the iterative solver's"
    );
    assert!(stats.krylov_iterations <= 520, "{stats:?}");
    common::assert_same_surface_normal_forces(lu_mem, it_mem, 1e-6, ("LU", "iterative"));
}

/// Print both runs' figures and assert what both scenes share: the LU run never used the
/// iterative solver, the iterative run did without a failure on a hierarchy with a coarse
/// level, Newton iterations within one of the LU run's, no cut-back in either.
fn assert_iterative_used_and_agrees(what: &str, lu: &RunSummary, it: &RunSummary) {
    let stats = it.iterative;
    println!(
        "{what}: LU {} Newton iterations; iterative {} ({} solves, {} CG, {} Krylov iterations, at most {}, {} builds, levels {:?}, complexity {:.2}, {} failures)",
        lu.newton_iterations,
        it.newton_iterations,
        stats.solves,
        stats.cg_solves,
        stats.krylov_iterations,
        stats.max_krylov_iterations,
        stats.builds,
        stats.levels,
        stats.complexity,
        stats.failures
    );
    assert_eq!(lu.iterative.solves, 0, "the LU run used the iterative solver");
    assert!(stats.solves > 0 && stats.failures == 0, "{stats:?}");
    assert!(stats.levels[1] > 0, "no coarse level: {stats:?}");
    assert!(it.newton_iterations.abs_diff(lu.newton_iterations) <= 1);
    assert_eq!((it.cutbacks, lu.cutbacks), (0, 0));
}
