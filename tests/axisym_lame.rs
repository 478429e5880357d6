//! Thick-walled cylinder under internal pressure, axisymmetric, against Lamé.
//!
//! ```text
//!   z ↑   a = 1      b = 2
//!     |   |▒▒▒▒▒▒▒▒▒▒|  h = 0.5, u_z = 0 top and bottom (plane-strain ends)
//!     |  p→▒▒▒▒▒▒▒▒▒▒|
//!     +---+----------+--→ r
//! ```
//! Reference (Lamé; Timoshenko & Goodier, Theory of Elasticity, §28, plane strain
//! `ε_z = 0`): `u(r) = (1 + ν) p a² / (E (b² − a²)) · ((1 − 2ν) r + b²/r)`, hoop stress at
//! the bore `σ_θ(a) = p (b² + a²)/(b² − a²)`.
//! Parameters: `E = 1000`, `ν = 0.3`, St. Venant–Kirchhoff, `p = 0.01` (`p/E = 1e-5`: the
//! geometric nonlinearity is of the strain's order, 1e-5 relative), a dead `[[pressure]]`
//! on the bore (consistent ring forces `2π r` ds); EAS elements (the default `q4-eas-safe`).
//! Meshes 16 × 2 and 32 × 4 (radial × axial), increments 1 and 2.
//! Asserted: the bore's radial displacement `u(a)` within 0.1 % of Lamé on both meshes, the
//! error not larger on the finer one; the results of 1 and 2 increments agree to 1e-6; the
//! axial reaction total `σ_z · π (b² − a²)` with `σ_z = ν (σ_r + σ_θ) = 2ν p a²/(b² − a²)`
//! within 0.5 % (the total over the full circle, as the model says).

mod common;

const SCENE: &str = r#"
name = "lame"
description = "thick-walled cylinder under internal pressure, axisymmetric, plane-strain ends"

[[body]]
name = "tube"
model = "axisymmetric"
material = { model = "saint-venant-kirchhoff", young = 1.0e3, poisson = 0.3 }
mesh = { kind = "rectangle", origin = [1.0, 0.0], size = [1.0, 0.5], elements = [16, 2] }

[[fix]]
body = "tube"
nodes = "bottom"
components = ["y"]

[[fix]]
body = "tube"
nodes = "top"
components = ["y"]

[[pressure]]
name = "bore"
body = "tube"
face = "left"
value = 0.01

[[monitor]]
label = "bore"
body = "tube"
nodes = "left"
component = "x"

[[monitor]]
label = "end"
body = "tube"
nodes = "top"
component = "y"

[stepping]
increments = 1
"#;

const E: f64 = 1.0e3;
const NU: f64 = 0.3;
const P: f64 = 0.01;
const A: f64 = 1.0;
const B: f64 = 2.0;

fn lame_u(r: f64) -> f64 {
    (1.0 + NU) * P * A * A / (E * (B * B - A * A)) * ((1.0 - 2.0 * NU) * r + B * B / r)
}

/// The bore's radial displacement and the top face's axial reaction total.
fn run(mesh: [usize; 2], increments: usize) -> (f64, f64) {
    let el = format!("body.tube.mesh.elements=[{}, {}]", mesh[0], mesh[1]);
    let inc = format!("stepping.increments={increments}");
    let problem = common::scene_file("lame.toml", SCENE, &[&el, &inc]);
    let (_, mem) = common::solve_ok(&problem);
    let last = mem.increments.last().unwrap();
    let monitors = last.all_monitors();
    let bore = monitors.iter().find(|m| m.label == "bore").unwrap();
    let end = monitors.iter().find(|m| m.label == "end").unwrap();
    (bore.displacement, end.force)
}

#[test]
fn lame_cylinder_bore_displacement_within_a_tenth_of_a_percent() {
    let want = lame_u(A);
    let sigma_z = 2.0 * NU * P * A * A / (B * B - A * A);
    let axial = sigma_z * std::f64::consts::PI * (B * B - A * A);
    let mut last_err = f64::INFINITY;
    for mesh in [[16, 2], [32, 4]] {
        let (u, fz) = run(mesh, 1);
        let err = (u / want - 1.0).abs();
        println!(
            "mesh {mesh:?}: u(a) = {u:.9e} (Lamé {want:.9e}, {:+.4} %), axial reaction on the top {fz:.6e} (σ_z π (b² − a²) = {axial:.6e}, {:+.3} %)",
            100.0 * (u / want - 1.0),
            100.0 * (fz / axial - 1.0)
        );
        assert!(err < 1e-3, "mesh {mesh:?}: u(a) = {u} vs Lamé {want}");
        assert!(
            err <= last_err * 1.01,
            "mesh {mesh:?}: the error grew ({err} after {last_err})"
        );
        // the top support holds the cylinder from shortening: its reaction is +σ_z A (tension)
        assert!(
            (fz / axial - 1.0).abs() < 5e-3,
            "mesh {mesh:?}: axial reaction {fz} vs {axial}"
        );
        last_err = err;
    }
    let (u1, _) = run([16, 2], 1);
    let (u2, _) = run([16, 2], 2);
    println!("increments 1 and 2: u(a) = {u1:.12e}, {u2:.12e}");
    assert!((u1 - u2).abs() <= 1e-6 * u1.abs(), "{u1} vs {u2}");
}
