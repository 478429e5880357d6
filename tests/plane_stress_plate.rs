//! Thin plates in plane stress (`model = "plane-stress"`, `thickness = t`) against
//! elasticity.
//!
//! 1. Uniaxial tension of a plate 2 × 1, `t = 0.05` (and 0.1), E = 1000, ν = 0.3, St.
//!    Venant–Kirchhoff: left edge held in x, one corner in y, a traction `σ = 0.01` on the
//!    right edge (a `[[pressure]]` of −σ: consistent nodal forces, `t` times the plane ones).
//!    Reference (uniaxial stress): `u_x(L) = σ L/E`, `u_y(W) = −ν σ W/E` (plane strain would
//!    give `−ν(1 + ν) σ W/E` and a stiffer `E/(1 − ν²)`), the support's reaction `−σ W t` (for
//!    the plate). Tolerance 1e-4 relative on the displacements (the strain is 1e-5: the
//!    geometric nonlinearity is of that order; the bilinear elements hold the homogeneous
//!    field exactly), 1e-9 on the reaction, on meshes 4 × 2 and 8 × 4, increments 1 and 2.
//! 2. A thick ring in plane stress under internal pressure (a quarter annulus, a = 1, b = 2,
//!    symmetry supports, dead `[[pressure]]` p = 0.01 on the inner face, `t = 0.05`).
//!    Reference (Lamé, generalised plane stress; Timoshenko & Goodier §28):
//!    `u(r) = p a² / (E (b² − a²)) · ((1 − ν) r + (1 + ν) b²/r)`. Tolerance 0.1 % on `u(a)`
//!    on meshes 32 × 16 and 64 × 32 (around × through), the error not growing; increments 1
//!    and 2 agree to 1e-6.

mod common;

const PLATE: &str = r#"
name = "plate"
description = "a thin plate in uniaxial tension, plane stress"

[[body]]
name = "plate"
model = "plane-stress"
thickness = 0.05
material = { model = "saint-venant-kirchhoff", young = 1.0e3, poisson = 0.3 }
mesh = { kind = "rectangle", origin = [0.0, 0.0], size = [2.0, 1.0], elements = [4, 2] }

[[fix]]
body = "plate"
nodes = "left"
components = ["x"]

[[fix]]
body = "plate"
nodes = "bottom-left"
components = ["y"]

[[pressure]]
name = "pull"
body = "plate"
face = "right"
value = -0.01

[[monitor]]
label = "end"
body = "plate"
nodes = "right"
component = "x"

[[monitor]]
label = "width"
body = "plate"
nodes = "top"
component = "y"

[[monitor]]
label = "support"
body = "plate"
nodes = "left"
component = "x"

[stepping]
increments = 1
"#;

const RING: &str = r#"
name = "ring"
description = "a thick ring in plane stress under internal pressure"

[[body]]
name = "ring"
model = "plane-stress"
thickness = 0.05
material = { model = "saint-venant-kirchhoff", young = 1.0e3, poisson = 0.3 }
mesh = { kind = "annulus", centre = [0.0, 0.0], radius = [1.0, 2.0], angle_deg = [0.0, 90.0], elements = [32, 16] }

[[fix]]
body = "ring"
nodes = "start"
components = ["y"]

[[fix]]
body = "ring"
nodes = "end"
components = ["x"]

[[pressure]]
body = "ring"
face = "inner"
value = 0.01

[[monitor]]
label = "bore"
body = "ring"
nodes = { x = 1.0, y = 0.0, tol = 1e-9 }
component = "x"

[stepping]
increments = 1
"#;

/// Each monitor's displacement and force.
fn monitors(text: &str, sets: &[&str]) -> Vec<(f64, f64)> {
    let problem = common::scene_file("plate.toml", text, sets);
    let (_, mem) = common::solve_ok(&problem);
    let last = mem.increments.last().unwrap();
    last.all_monitors().iter().map(|m| (m.displacement, m.force)).collect()
}

#[test]
fn plane_stress_plate_uniaxial_tension_is_uniaxial_stress() {
    let (e, nu, l, w) = (1.0e3, 0.3, 2.0, 1.0);
    let sigma = 0.01;
    let (ux, uy) = (sigma * l / e, -nu * sigma * w / e);
    for t in [0.05, 0.1] {
        for (mesh, inc) in [("[4, 2]", 1), ("[8, 4]", 1), ("[8, 4]", 2)] {
            let sets = [
                format!("body.plate.thickness={t}"),
                format!("body.plate.mesh.elements={mesh}"),
                format!("stepping.increments={inc}"),
            ];
            let sets: Vec<&str> = sets.iter().map(|s| s.as_str()).collect();
            let got = monitors(PLATE, &sets);
            let (u_x, u_y, support) = (got[0].0, got[1].0, got[2].1);
            println!(
                "t = {t}, mesh {mesh}, {inc} increments: u_x(L) = {u_x:.9e} (σL/E = {ux:.9e}), u_y(W) = {u_y:.9e} (−νσW/E = {uy:.9e}), support reaction {support:.9e} (−σWt = {:.9e})",
                -sigma * w * t
            );
            assert!((u_x / ux - 1.0).abs() < 1e-4, "u_x {u_x} vs {ux}");
            assert!((u_y / uy - 1.0).abs() < 1e-4, "u_y {u_y} vs {uy}");
            assert!((support / (-sigma * w * t) - 1.0).abs() < 1e-9, "reaction {support}");
        }
    }
}

#[test]
fn plane_stress_ring_under_internal_pressure_matches_lame() {
    let (e, nu, p, a, b) = (1.0e3, 0.3, 0.01, 1.0, 2.0);
    let want = p * a * a / (e * (b * b - a * a)) * ((1.0 - nu) * a + (1.0 + nu) * b * b / a);
    let mut last_err = f64::INFINITY;
    for mesh in ["[32, 16]", "[64, 32]"] {
        let el = format!("body.ring.mesh.elements={mesh}");
        let u = monitors(RING, &[&el])[0].0;
        let err = (u / want - 1.0).abs();
        println!(
            "mesh {mesh}: u(a) = {u:.9e} (Lamé {want:.9e}, {:+.4} %)",
            100.0 * (u / want - 1.0)
        );
        assert!(err < 1e-3, "mesh {mesh}: {u} vs {want}");
        assert!(err <= last_err * 1.01, "mesh {mesh}: the error grew");
        last_err = err;
    }
    let u1 = monitors(RING, &[])[0].0;
    let u2 = monitors(RING, &["stepping.increments=2"])[0].0;
    assert!((u1 - u2).abs() <= 1e-6 * u1.abs(), "{u1} vs {u2}");
}
