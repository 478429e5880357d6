//! The body `model` key beyond the elements: contact forces in plane stress and in the
//! axisymmetric setting, the supports on the axis, and the refusals of bad input.
//!
//! 1. Plane stress: a block 1 × 1 (4 × 4 EAS elements, E = 1000, ν = 0.3, St. Venant–Kirchhoff)
//!    on a fixed-in-y bottom, pressed by a rigid flat moved down by `d = 1e-4`, frictionless.
//!    Reference (uniaxial stress, lateral expansion free): `F = E (d/H) W t` (plane strain
//!    would give `E/(1 − ν²)`). Tolerance 0.1 % (penalty ε_N = 1e6 per unit thickness: its
//!    penetration is ≈ 2.5e-4 of `d`; strain 1e-4) for `t = 0.1` and `t = 0.2`, meshes 4 × 4
//!    and 8 × 8; doubling `t` doubles `F` to 1e-9.
//! 2. Axisymmetric: a cylinder of revolution, `R = 0.5`, `H = 1` (8 × 8 and 16 × 16), pressed
//!    the same way: the total force over the full circle `F = E (d/H) π R²` within 0.1 %, and
//!    the recorded pressure `p = N/(2π r̄ l)` of every slave node — the node on the axis
//!    included — equal to `σ = E d/H` within 0.1 % (a contact weight that were not the ring's
//!    would make it vary like `1/r`). Increments 1 and 2 agree to 1e-6.
//! 3. The nodes on the axis get `u_r = 0` with a note; bad input (a node at x < 0, plane
//!    stress without a thickness, a thickness without plane stress, mixed models) is refused
//!    with the file, the body and the fix.

mod common;

use contrail::record::pressure::{profiles, PressureLayout};

const BLOCK: &str = r#"
name = "press"
description = "a block pressed by a rigid flat"

[[body]]
name = "block"
model = "plane-stress"
thickness = 0.1
material = { model = "saint-venant-kirchhoff", young = 1.0e3, poisson = 0.3 }
mesh = { kind = "rectangle", origin = [0.0, 0.0], size = [1.0, 1.0], elements = [4, 4] }

[[fix]]
body = "block"
nodes = "bottom"
components = ["y"]

[[fix]]
body = "block"
nodes = "bottom-left"
components = ["x"]

[[rigid]]
name = "flat"
polyline = [[-0.5, 1.0], [1.5, 1.0]]
move = { y = -1.0e-4 }

[[contact]]
name = "press"
slave = { body = "block", nodes = "top" }
master = { rigid = "flat" }
eps_n = 1.0e6

[[monitor]]
label = "flat"
rigid = "flat"
component = "y"
sign = -1.0

[stepping]
increments = 1
"#;

fn axisym_block() -> String {
    BLOCK
        .replace("model = \"plane-stress\"\nthickness = 0.1", "model = \"axisymmetric\"")
        .replace("size = [1.0, 1.0]", "size = [0.5, 1.0]")
        .replace("[[-0.5, 1.0], [1.5, 1.0]]", "[[-0.5, 1.0], [1.0, 1.0]]")
        .replace(
            "[[fix]]\nbody = \"block\"\nnodes = \"bottom-left\"\ncomponents = [\"x\"]\n",
            "",
        )
}

/// The flat's force, and the pressures of the slave nodes (with their reference radii).
fn press(text: &str, sets: &[&str]) -> (f64, Vec<(f64, f64)>, Vec<String>) {
    let problem = common::scene_file("press.toml", text, sets);
    let (_, mem) = common::solve_ok(&problem);
    let last = mem.increments.last().unwrap();
    let model = &problem.model;
    let layout = PressureLayout::new(model);
    let pts = mem.contact.last().unwrap();
    let prof = profiles(&layout, model, &mem.final_u, last.t, last.increment, pts);
    let p = prof[0]
        .points
        .iter()
        .map(|p| (model.nodes[p.node][0], p.pressure))
        .collect();
    (last.all_monitors()[0].force, p, model.notes.clone())
}

#[test]
fn plane_stress_contact_force_is_for_the_plate() {
    let mut by_t = Vec::new();
    for t in [0.1, 0.2] {
        let want = 1.0e3 * 1e-4 * 1.0 * t;
        for mesh in ["[4, 4]", "[8, 8]"] {
            let sets = [
                format!("body.block.thickness={t}"),
                format!("body.block.mesh.elements={mesh}"),
            ];
            let sets: Vec<&str> = sets.iter().map(|s| s.as_str()).collect();
            let (f, _, _) = press(BLOCK, &sets);
            println!(
                "t = {t}, mesh {mesh}: F = {f:.9e} (E d/H W t = {want:.9e}, {:+.4} %)",
                100.0 * (f / want - 1.0)
            );
            assert!((f / want - 1.0).abs() < 1e-3, "t = {t}, {mesh}: {f} vs {want}");
            if mesh == "[4, 4]" {
                by_t.push(f);
            }
        }
    }
    println!("F(0.2) / F(0.1) = {:.12}", by_t[1] / by_t[0]);
    assert!((by_t[1] / by_t[0] - 2.0).abs() < 1e-9);
}

#[test]
fn axisymmetric_flat_press_total_force_and_uniform_pressure() {
    let text = axisym_block();
    let (r, h, e, d) = (0.5, 1.0, 1.0e3, 1.0e-4);
    let sigma = e * d / h;
    let want = sigma * std::f64::consts::PI * r * r;
    let mut forces = Vec::new();
    for (mesh, inc) in [("[8, 8]", 1), ("[16, 16]", 1), ("[8, 8]", 2)] {
        let sets = [
            format!("body.block.mesh.elements={mesh}"),
            format!("stepping.increments={inc}"),
        ];
        let sets: Vec<&str> = sets.iter().map(|s| s.as_str()).collect();
        let (f, p, notes) = press(&text, &sets);
        println!(
            "mesh {mesh}, {inc} increments: F = {f:.9e} (σ π R² = {want:.9e}, {:+.4} %)",
            100.0 * (f / want - 1.0)
        );
        for (x, p) in &p {
            println!("  r = {x:.4}: p = {p:.6e} ({:+.4} %)", 100.0 * (p / sigma - 1.0));
            assert!((p / sigma - 1.0).abs() < 1e-3, "r = {x}: p = {p} vs σ = {sigma}");
        }
        assert!(p.iter().any(|(x, _)| *x == 0.0), "the node on the axis is a slave");
        assert!((f / want - 1.0).abs() < 1e-3, "{mesh}: {f} vs {want}");
        assert!(
            notes
                .iter()
                .any(|n| n.contains("u_r = 0 held at its 9 nodes on the axis")
                    || n.contains("u_r = 0 held at its 17 nodes on the axis")),
            "{notes:?}"
        );
        forces.push(f);
    }
    assert!((forces[0] - forces[2]).abs() < 1e-6 * forces[0]);
}

#[test]
fn bad_models_are_refused_with_the_fix() {
    let axi = axisym_block();
    let err = common::scene_text_err(&axi.replace("origin = [0.0, 0.0]", "origin = [-0.1, 0.0]"));
    println!("{err}");
    assert!(
        err.contains("test.toml") && err.contains("body `block`") && err.contains("x = r ≥ 0"),
        "{err}"
    );
    assert!(err.contains("hint: move the mesh"), "{err}");
    let err = common::scene_text_err(&BLOCK.replace("thickness = 0.1\n", ""));
    println!("{err}");
    assert!(
        err.contains("needs the key `thickness`") && err.contains("hint: add the plate's thickness"),
        "{err}"
    );
    let err = common::scene_text_err(&BLOCK.replace("thickness = 0.1", "thickness = -1.0"));
    assert!(err.contains("must be positive"), "{err}");
    let err = common::scene_text_err(&BLOCK.replace("model = \"plane-stress\"\n", ""));
    println!("{err}");
    assert!(
        err.contains("`thickness` is given") && err.contains("plane-strain"),
        "{err}"
    );
    let two = format!(
        "{axi}\n[[body]]\nname = \"other\"\nmaterial = {{ model = \"neo-hookean\", young = 1.0, poisson = 0.3 }}\nmesh = {{ kind = \"rectangle\", origin = [2.0, 0.0], size = [1.0, 1.0], elements = [1, 1] }}\n"
    );
    let err = common::scene_text_err(&two);
    println!("{err}");
    assert!(err.contains("axisymmetric in all its bodies or in none"), "{err}");
}
