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
    let stats = it.iterative;
    println!(
        "LU: {} Newton iterations; iterative: {} ({} solves, {} CG, {} Krylov iterations, at most {}, {} builds, levels {:?}, complexity {:.2}, {} failures)",
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
    common::assert_same_normal_forces(lu_mem, it_mem, 1e-6, ("LU", "iterative"));
}
