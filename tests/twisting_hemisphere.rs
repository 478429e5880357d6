//! The twisting hemisphere (Sauer & De Lorenzis, IJNME 101 (2015) 251–280; also FEBio,
//! Zimmerman & Ateshian 2018, and solids4foam's `twistingHemisphere`): large deformation
//! and frictional sliding in torsion.
//!
//! A hollow neo-Hookean hemisphere (outer radius 1, inner 2/3, E = 5, ν = 0.3) is pressed
//! with its flat rim 1 into a neo-Hookean block 2 × 2 × 2 (E = 1, ν = 0.3, bottom fixed) in
//! 10 frictionless increments, then turned about its axis in increments of 2° with μ = 0.5
//! (the built-in `twisting-hemisphere`). Reference: Sauer & De Lorenzis' normal force and
//! twisting torque on the rim, digitised (±1–2 %) from solids4foam's data
//! (`hyperElasticity/twistingHemisphere/data/deLorenzis{Force,Moment}.dat`):
//! 0°: 1.230; 20°: 1.234 and 0.146; 40°: 1.245 and 0.267.
//! Tolerance: 3 % in force, 5 % in torque (the issue's), checked on the built-in mesh
//! (block 13 × 13 × 6, shell 8 × 8 per cube face and 2 layers) and with the step halved
//! (1° a step). Measured 2026-11-28 (this test prints the table): force −1.5 % … −1.6 %,
//! torque −4.2 % at 20°, −3.2 % at 40°.
//!
//! Not refined in mesh: the built-in mesh is the one on which the press completes; a
//! 12 × 12 block top and shells of 10 and 12 cells per cube edge stop in the press
//! (measured 2026-11-28, docs/gallery.md), as does the twist at 67.1° on this mesh — the
//! faceted master's normal jumps at its edges. Release tier (about 1 minute).

use contrail::record::Memory;
use std::sync::atomic::AtomicBool;

/// (angle in degrees, force, torque) at each converged increment of the twist.
fn twist(sets: &[&str]) -> Vec<(f64, f64, f64)> {
    let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
    let (src, problem) = contrail::load_any_scene("twisting-hemisphere", &sets).expect("the scene loads");
    let contrail::scene::AnyProblem::Solid(problem) = problem else {
        panic!("a 3D scene")
    };
    let info = contrail::run_info(&src, &sets, &problem);
    let mut mem = Memory::default();
    contrail::solver::run(&problem, &info, &mut mem, &AtomicBool::new(false)).unwrap_or_else(|e| panic!("{e}"));
    (mem.increments.iter())
        .filter(|i| i.t >= 1.0 - 1e-9)
        .map(|i| {
            let m = &i.monitors;
            (20.0 * (i.t - 1.0), m[0].force, m[1].force)
        })
        .collect()
}

fn at(curve: &[(f64, f64, f64)], degrees: f64) -> (f64, f64) {
    let p = (curve.iter())
        .find(|p| (p.0 - degrees).abs() < 1e-6)
        .unwrap_or_else(|| panic!("no increment at {degrees}°"));
    (p.1, p.2)
}

#[test]
#[cfg_attr(debug_assertions, ignore = "release tier")]
fn the_twisting_hemisphere_carries_the_published_force_and_torque_to_40_degrees() {
    const REFERENCE: [(f64, f64, Option<f64>); 3] = [
        (0.0, 1.230, None),
        (20.0, 1.234, Some(0.146)),
        (40.0, 1.245, Some(0.267)),
    ];
    for (label, increments) in [("2° a step", 30), ("1° a step", 60)] {
        let curve = twist(&["stepping.end=3.0", &format!("stepping.increments={increments}")]);
        for (degrees, force, torque) in REFERENCE {
            let (f, m) = at(&curve, degrees);
            let force_error = f / force - 1.0;
            println!(
                "{label}, {degrees:>3}°: force {f:.4} ({:+.2} %), torque {m:.4}",
                100.0 * force_error
            );
            assert!(
                force_error.abs() <= 0.03,
                "{label}, {degrees}°: force {f} against {force}"
            );
            if let Some(torque) = torque {
                let torque_error = m / torque - 1.0;
                println!("          torque against {torque}: {:+.2} %", 100.0 * torque_error);
                assert!(
                    torque_error.abs() <= 0.05,
                    "{label}, {degrees}°: torque {m} against {torque}"
                );
            }
        }
    }
}
