//! One scene, several models: the plane scene `tests/data/cylinder-plane.toml` (Hertz line
//! contact: a rigid cylinder R = 1 pressed 0.01 into a neo-Hookean block, E = 1000, ν = 0.3,
//! half model, ε_N = 1e6 per node) built as written and, with `extrusion.build = true`, as its
//! 3D extrusion (`src/scene/extrude.rs`). References and tolerances:
//! - the slice (u_y = 0 at every node) reports the plane-strain force per unit length within
//!   1e-4 on the section meshes 20 × 15 and 40 × 30 (measured +1.1e-5 and below: the 3D
//!   penalty per unit area is the 2D one over the finest slave spacing), in one and two
//!   hexahedra along the extrusion;
//! - it is the model of the hand-written 3D slice `tests/data/cylinder-slice-3d.toml`: the same
//!   number of nodes and DOFs, the same force within 1e-4 (the two scenes' penalties differ);
//! - as a plane-stress plate 0.2 thick (half the plate in one and two hexahedra through its
//!   half thickness) it reports the plate's total within 1 % of the 2D plane-stress model
//!   (measured +0.41 %: the plate is 0.1 of the block's width, a 3D plate, not plane stress
//!   near the contact);
//! - what has no 3D counterpart is refused with the reason (an axisymmetric body, a bent
//!   rigid polyline, a plate held at u_y = 0).

use contrail::record::Memory;
use std::sync::atomic::AtomicBool;

const SCENE: &str = "tests/data/cylinder-plane.toml";

/// The base monitor's force at the last increment of the scene with overrides, and the
/// model's DOFs.
fn base_force(sets: &[String]) -> (f64, usize) {
    let (src, problem) = contrail::load_any_scene(SCENE, sets).unwrap_or_else(|e| panic!("{e}"));
    let mut mem = Memory::default();
    let dofs = match &problem {
        contrail::scene::AnyProblem::Plane(p) => {
            let info = contrail::run_info(&src, sets, p);
            contrail::solver::run(p, &info, &mut mem, &AtomicBool::new(false)).unwrap_or_else(|e| panic!("{e}"));
            p.model.dof_count()
        }
        contrail::scene::AnyProblem::Solid(p) => {
            let info = contrail::run_info(&src, sets, p);
            contrail::solver::run(p, &info, &mut mem, &AtomicBool::new(false)).unwrap_or_else(|e| panic!("{e}"));
            p.model.dof_count()
        }
    };
    let last = mem.increments.last().expect("increments");
    let base = last
        .monitors
        .iter()
        .find(|m| m.label == "base")
        .expect("the base monitor");
    (base.force, dofs)
}

fn sets(list: &[&str]) -> Vec<String> {
    list.iter().map(|s| s.to_string()).collect()
}

#[test]
fn the_extruded_slice_reports_the_plane_strain_force_per_unit_length() {
    for (mesh, along) in [("[20, 15]", 1), ("[40, 30]", 1), ("[20, 15]", 2)] {
        let m = format!("body.block.mesh.elements={mesh}");
        let (plane, _) = base_force(&sets(&[&m]));
        let n = format!("extrusion.elements={along}");
        let (slice, _) = base_force(&sets(&[&m, "extrusion.build=true", &n]));
        let diff = slice / plane - 1.0;
        println!("{mesh}, {along} along: plane strain {plane:.7}, extruded slice {slice:.7} ({diff:+.1e})");
        assert!(diff.abs() <= 1e-4, "{diff:e}");
    }
}

#[test]
fn the_extruded_slice_is_the_hand_written_3d_slice() {
    let (extruded, dofs) = base_force(&sets(&["body.block.mesh.elements=[20, 15]", "extrusion.build=true"]));
    let hand = ["body.block.mesh.elements=[20, 1, 15]".to_string()];
    let (src, problem) = contrail::load_any_scene("tests/data/cylinder-slice-3d.toml", &hand).expect("loads");
    let contrail::scene::AnyProblem::Solid(p) = problem else {
        panic!("3D")
    };
    let info = contrail::run_info(&src, &hand, &p);
    let mut mem = Memory::default();
    contrail::solver::run(&p, &info, &mut mem, &AtomicBool::new(false)).unwrap_or_else(|e| panic!("{e}"));
    let written = mem
        .increments
        .last()
        .and_then(|i| i.monitors.iter().find(|m| m.label == "base"))
        .expect("base")
        .force
        / 0.1;
    println!(
        "extruded {extruded:.7} ({dofs} DOFs), hand-written {written:.7} ({} DOFs)",
        p.model.dof_count()
    );
    assert_eq!(dofs, p.model.dof_count());
    assert!((extruded / written - 1.0).abs() <= 1e-4, "{extruded} against {written}");
}

#[test]
fn the_extruded_plate_reports_the_plane_stress_total_within_a_per_cent() {
    let plate = [
        "body.block.mesh.elements=[20, 15]",
        "body.block.model=\"plane-stress\"",
        "body.block.thickness=0.2",
    ];
    let (plane, _) = base_force(&sets(&plate));
    for along in [1, 2] {
        let n = format!("extrusion.elements={along}");
        let mut s = sets(&plate);
        s.extend(sets(&["extrusion.build=true", &n]));
        let (solid, _) = base_force(&s);
        let diff = solid / plane - 1.0;
        println!(
            "plate 0.2 thick, {along} through the half: plane stress {plane:.6}, 3D {solid:.6} ({:+.2} %)",
            100.0 * diff
        );
        assert!(diff.abs() <= 0.01, "{diff}");
    }
}

#[test]
fn what_has_no_3d_extrusion_is_refused_with_the_reason() {
    let refused = |extra: &[&str], said: &str| {
        let mut s = sets(&["extrusion.build=true"]);
        s.extend(sets(extra));
        let e = contrail::load_any_scene(SCENE, &s)
            .err()
            .unwrap_or_else(|| panic!("{extra:?} is refused"))
            .to_string();
        assert!(e.contains(said) && e.contains("[extrusion]"), "{e}");
    };
    refused(&["body.block.model=\"axisymmetric\""], "revolved, not extruded");
    refused(
        &["rigid.cylinder.arc.from_deg=-30", "rigid.cylinder.arc.to_deg=-150"],
        "cavity",
    );
    refused(
        &[
            "body.block.model=\"plane-stress\"",
            "body.block.thickness=0.2",
            "extrusion.ends=\"held\"",
        ],
        "plane strain",
    );
    refused(&["extrusion.length=0"], "positive `length`");
    refused(&["body.block.mesh.bias=[\"both\", \"end\"]"], "graded from end to end");
}
