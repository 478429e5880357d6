//! A thick disc compressed between rigid plates with friction: the axisymmetric model
//! against the 3D model of the same scene (`tests/data/disc-axisym.toml`,
//! `tests/data/disc-3d.toml`).
//!
//! ```text
//!   ═════════ rigid plate, moved down 0.02, μ = 0.3 ═════════
//!   │  disc: radius 1, height 1 (the upper half modelled:  │
//!   │  symmetry at z = 0), neo-Hooke, E = 1000, ν = 0.3     │   barrels: the rim bulges at
//!   ──────────────────── symmetry plane ────────────────────    mid-height, held at the plate
//! ```
//! Reference: no closed form with friction (the plates restrain the faces, the disc
//! barrels); the two models of one body must agree. The force is the total over the full
//! circle in the axisymmetric model and four times the quarter's in 3D, both the reaction on
//! the symmetry plane.
//! Parameters: compression 4 % of the height in 8 increments; ε_N = ε_T = 1e6 per slave ring
//! and unit length (axisymmetric), 1e7 per unit area (3D); axisymmetric 16×8, 32×16, 64×32
//! (radius × height); 3D quarter "butterfly" meshes 4·4·4 and 6·6·6 (core edge · core to rim ·
//! height, `tests/data/make-disc-quarter.py`; 8·8·8 in docs/models.md).
//! Tolerances: each 3D force within 1 % of the finest axisymmetric one, the finer 3D mesh
//! closer; both models barrel (rim at mid-height out by more than at the plate, by at least
//! 20 % of the mid-height bulge). Measured 2026-11-27: axisymmetric 145.223, 145.137, 145.096;
//! 3D 144.378 (−0.50 %), 144.802 (−0.20 %); 8·8·8 144.934 (−0.11 %).
//! Release tier (the 3D meshes take 0.9 s and 3 s optimised, with the axisymmetric 64×32).

mod common;

use contrail::record::Memory;

const AXISYM: &str = include_str!("data/disc-axisym.toml");
const SOLID: &str = include_str!("data/disc-3d.toml");

/// Force and the rim's radial displacement at mid-height and at the plate.
struct Barrel {
    force: f64,
    bulge_mid: f64,
    bulge_top: f64,
}

fn force(mem: &Memory) -> f64 {
    mem.increments.last().unwrap().all_monitors()[0].force
}

fn axisymmetric(elements: &str) -> Barrel {
    let el = format!("body.disc.mesh.elements={elements}");
    let problem = common::scene_file("tests/data/disc-axisym.toml", AXISYM, &[&el]);
    let (_, mem) = common::solve_ok(&problem);
    let radial = |y: f64| {
        let n = (problem.model.nodes.iter())
            .position(|p| (p[0] - 1.0).abs() < 1e-9 && (p[1] - y).abs() < 1e-9)
            .unwrap();
        mem.final_u[2 * n]
    };
    Barrel {
        force: force(&mem),
        bulge_mid: radial(0.0),
        bulge_top: radial(0.5),
    }
}

fn solid(mesh: &str) -> Barrel {
    let text = SOLID.replace("disc-quarter.msh", mesh);
    let origin = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/disc-3d.toml");
    let (problem, summary, mem) = common::solve_solid_text(origin, &text);
    let nodes = &problem.model.nodes;
    // the rim's node on the x axis (y = 0) at height z
    let radial = |z: f64| {
        let n = (nodes.iter())
            .position(|p| (p[0] - 1.0).abs() < 1e-9 && p[1].abs() < 1e-9 && (p[2] - z).abs() < 1e-9)
            .unwrap();
        mem.final_u[3 * n]
    };
    println!("{mesh}: {} Newton iterations", summary.newton_iterations);
    Barrel {
        force: 4.0 * force(&mem),
        bulge_mid: radial(0.0),
        bulge_top: radial(0.5),
    }
}

fn assert_barrels(what: &str, b: &Barrel) {
    println!(
        "{what}: F = {:.3}, rim out by {:.5} at mid-height, {:.5} at the plate",
        b.force, b.bulge_mid, b.bulge_top
    );
    assert!(
        b.bulge_mid > 0.0 && b.bulge_mid - b.bulge_top > 0.2 * b.bulge_mid,
        "{what} does not barrel"
    );
}

#[test]
#[cfg_attr(debug_assertions, ignore = "release tier")]
fn disc_barrels_alike_in_the_axisymmetric_and_the_3d_model() {
    let axi: Vec<Barrel> = ["[16, 8]", "[32, 16]", "[64, 32]"]
        .iter()
        .map(|e| axisymmetric(e))
        .collect();
    for (b, e) in axi.iter().zip(["16×8", "32×16", "64×32"]) {
        assert_barrels(&format!("axisymmetric {e}"), b);
    }
    let reference = axi[2].force;
    assert!((axi[1].force / reference - 1.0).abs() < 2e-3, "axisymmetric converged");
    let mut last = f64::INFINITY;
    for mesh in ["disc-quarter-4.msh", "disc-quarter-6.msh"] {
        let b = solid(mesh);
        assert_barrels(&format!("3D {mesh}"), &b);
        let e = (b.force / reference - 1.0).abs();
        println!(
            "3D {mesh}: {:+.3} % against the axisymmetric 64×32",
            100.0 * (b.force / reference - 1.0)
        );
        assert!(e < 0.01, "{mesh}: the 3D force {} against {reference}", b.force);
        assert!(e < last, "the finer 3D mesh is closer");
        last = e;
    }
}
