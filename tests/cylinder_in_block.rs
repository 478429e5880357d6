//! A long rigid cylinder pressed into a block (Hertz line contact): which model is enough —
//! plane strain, a 3D slice with plane-strain constraints, or the 3D block with free ends
//! (the "model no more than a scene needs" check of an extruded scene).
//!
//! The built-in `hertz` (plane strain, half model: the block [0, 2] × [−2, 0], E = 1000,
//! ν = 0.3, neo-Hooke, a rigid cylinder R = 1 pressed 0.01, frictionless, ε_N = 1e6 per node)
//! against `tests/data/cylinder-slice-3d.toml`: the same section meshed alike in x–z, one
//! hexahedron 0.1 thick with `u_y = 0` at every node, against the rigid `cylinder` (ε_N = 1e8
//! per unit area). References and tolerances:
//! - the 3D slice's force per unit thickness equals the plane-strain force within 1e-4 on
//!   the section meshes 20 × 15 and 40 × 30 (measured +2.7e-5 and −2.8e-7: the two penalties'
//!   different measures);
//! - the block with free ends (half-length L/2 = 1 and 2, symmetry at y = 0, the cylinder
//!   longer than the block; 20 × 4·(L/2) × 15 elements graded towards the free end): its force
//!   per unit length lies between plane stress and plane strain of the same section mesh
//!   (measured 1.9174 and 1.9434 against 1.8462 and 2.0263: −5.4 % and −4.1 % from plane
//!   strain) and rises towards it with the length: plane strain is not the model of a
//!   free-ended block at a few per cent.

mod common;

use contrail::record::Memory;
use std::sync::atomic::AtomicBool;

const SLICE: &str = "tests/data/cylinder-slice-3d.toml";

/// The vertical force of the last increment of the 3D slice scene with overrides.
fn force_3d(sets: &[String]) -> f64 {
    let (src, problem) = contrail::load_any_scene(SLICE, sets).expect("the scene loads");
    let contrail::scene::AnyProblem::Solid(problem) = problem else {
        panic!("a 3D scene")
    };
    let info = contrail::run_info(&src, sets, &problem);
    let mut mem = Memory::default();
    contrail::solver::run(&problem, &info, &mut mem, &AtomicBool::new(false)).unwrap_or_else(|e| panic!("{e}"));
    mem.increments.last().and_then(|i| i.reaction_z).expect("a 3D reaction")
}

/// The vertical force per unit thickness of the 2D `hertz` with overrides.
fn force_2d(sets: &[&str]) -> f64 {
    let (_, mem) = common::solve_ok(&common::scene("hertz", sets));
    mem.increments.last().expect("increments").reaction_total[1]
}

#[test]
fn a_3d_slice_in_plane_strain_is_the_plane_strain_model() {
    for (nx, nz) in [(20, 15), (40, 30)] {
        let slice = force_3d(&[format!("body.block.mesh.elements=[{nx}, 1, {nz}]")]) / 0.1;
        let plane = force_2d(&[&format!("body.block.mesh.elements=[{nx}, {nz}]")]);
        let diff = slice / plane - 1.0;
        println!("{nx} × {nz}: 3D slice {slice:.7} per unit thickness, plane strain {plane:.7} ({diff:+.1e})");
        assert!(diff.abs() <= 1e-4, "{diff:e}");
    }
}

#[test]
fn a_block_with_free_ends_lies_between_plane_stress_and_plane_strain() {
    let mesh = "body.block.mesh.elements=[20, 15]";
    let strain = force_2d(&[mesh]);
    let stress = force_2d(&[mesh, "body.block.model=plane-stress", "body.block.thickness=1.0"]);
    let mut last = stress;
    for half in [1.0, 2.0] {
        let ny = (4.0 * half) as usize;
        let per_length = force_3d(&[
            format!("body.block.mesh.elements=[20, {ny}, 15]"),
            format!("body.block.mesh.size=[2.0, {half}, 2.0]"),
            "body.block.mesh.grading=[20.0, 0.1, 0.05]".into(),
            "fix.2.nodes=ymin".into(),
        ]) / half;
        println!(
            "free ends, half-length {half}: {per_length:.5} per unit length ({:+.2} % from plane strain {strain:.5}; plane stress {stress:.5})",
            100.0 * (per_length / strain - 1.0)
        );
        assert!(stress < per_length && per_length < strain);
        assert!(per_length > last, "longer is closer to plane strain");
        last = per_length;
    }
}
