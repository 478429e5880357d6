//! Hertz line contact (the built-in `hertz` scene, 40 × 30 mesh: rigid cylinder R = 1 pressed
//! into a Neo-Hookean block, frictionless penalty contact) solved with faer's sparse `LDLᵀ`
//! (AMD ordering, chosen because the tangent is symmetric; `linalg::ldlt`) and with faer's
//! sparse LU (`solver.linear_solver = "sparse-lu"`); and the frictional `block-slide` scene
//! (μ = 0.3, slip tangents are unsymmetric) the same two ways.
//!
//! Reference: the LU runs. Tolerances: Hertz — every factorisation of the `LDLᵀ` run made
//! by it (no fallback), the same Newton iteration count, no cut-back, every contact point's
//! normal force equal to 1e-9 of the largest (the two factorisations differ in round-off
//! only). Block slide — the `LDLᵀ` plan is retired at the first unsymmetric tangent (the
//! fallback reason is `Unsymmetric`), the LU serves the rest, and the final displacements
//! equal the LU run's to 1e-9 of the largest.

mod common;

use contrail::linalg::ldlt::LdltFailure;

#[test]
fn symmetric_and_general_factorisations_give_the_same_contact() {
    // Hertz: symmetric throughout
    let mut runs = Vec::new();
    for solver in ["sparse-lu", "general"] {
        let set = format!("solver.linear_solver={solver}");
        runs.push(common::solve_ok(&common::scene(
            "hertz",
            &["body.block.mesh.elements=[40, 30]", &set],
        )));
    }
    let ((lu, lu_mem), (ld, ld_mem)) = (&runs[0], &runs[1]);
    println!(
        "Hertz: LU {} Newton iterations, LDLT {} ({:?})",
        lu.newton_iterations, ld.newton_iterations, ld.ldlt
    );
    assert_eq!(lu.ldlt.solves, 0, "the LU run used LDLT");
    assert_eq!(ld.ldlt.solves, ld.timings.factorizations, "{:?}", ld.ldlt);
    assert_eq!(ld.ldlt.fallbacks, 0);
    assert_eq!(ld.newton_iterations, lu.newton_iterations);
    assert_eq!((ld.cutbacks, lu.cutbacks), (0, 0));
    common::assert_same_normal_forces(lu_mem, ld_mem, 1e-9, ("LU", "LDLT"));

    // block slide: friction makes the tangent unsymmetric once the block slips
    let mut runs = Vec::new();
    for solver in ["sparse-lu", "general"] {
        let set = format!("solver.linear_solver={solver}");
        runs.push(common::solve_ok(&common::scene("block-slide", &[&set])));
    }
    let ((lu, lu_mem), (ld, ld_mem)) = (&runs[0], &runs[1]);
    println!("block slide: {:?}", ld.ldlt);
    assert!(ld.ldlt.fallbacks >= 1, "{:?}", ld.ldlt);
    assert_eq!(ld.ldlt.last_failure, Some(LdltFailure::Unsymmetric));
    assert!(ld.ldlt.solves < ld.timings.factorizations);
    let scale = lu_mem.final_u.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    assert!(scale > 0.0);
    for (i, (p, q)) in lu_mem.final_u.iter().zip(&ld_mem.final_u).enumerate() {
        assert!((p - q).abs() <= 1e-9 * scale, "u[{i}]: {p} (LU) vs {q}");
    }
    assert_eq!(ld.newton_iterations, lu.newton_iterations);
}
