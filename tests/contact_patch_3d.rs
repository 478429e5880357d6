//! The 3D contact patch test (Taylor & Papadopoulos 1991 in 3D; code_aster SSNV167 style):
//! two elastic blocks with non-matching facets pressed together must transmit a uniform
//! pressure — node-to-surface two-pass does, one pass does not.
//!
//! Parameters: `base` 1 × 1 × 0.5 and `top` 1 × 1 × 0.5 on it, E = 1e3, ν = 0.3 (St. Venant–
//! Kirchhoff), the top face pressed down by 1e-3 in one increment, the sides x = 0 and y = 0
//! held normally (symmetry), frictionless, ε_N = 1e8 per unit area (1e5 E / length), and 1e9.
//! Interface meshes (base/top elements per side): 4/3 and 8/5.
//! Reference: a uniform state — the base's top face moves down uniformly, so every node of it
//! has the same u_z (pressure uniform ⇔ strain uniform in the base).
//! Asserted: two-pass: the largest |u_z − mean| on the base's top face ≤ 1e-3 of the mean,
//! and at ε_N = 1e9 at most a fifth of that (what is left is the penalty's error, ∝ 1/ε_N);
//! at most 3 Newton iterations; the press's force within 1 % of E ε A (uniaxial stress,
//! ε = 1e-3 overall); each body's equilibrium is checked by the run itself. One pass: the
//! same deviation > 1e-2 (it fails the patch test, as it must).
//! Measured (2026-11-27, `cargo test --release --test contact_patch_3d -- --nocapture`):
//! two-pass spread 7.2e-5 (4/3) and 2.6e-4 (8/5) at ε_N = 1e8, 7.2e-6 and 2.7e-5 at 1e9, 3
//! iterations each; one pass 0.26 and 0.27.
//! In two increments (4/3): the same press force to 1e-6 and the same spread (asserted).
mod common;

fn scene(base: usize, top: usize, two_pass: bool, eps: f64, increments: usize) -> String {
    format!(
        r#"name = "contact-patch-3d"
[[body]]
name = "base"
material = {{ model = "saint-venant-kirchhoff", young = 1.0e3, poisson = 0.3 }}
mesh = {{ kind = "box", origin = [0.0, 0.0, 0.0], size = [1.0, 1.0, 0.5], elements = [{base}, {base}, 2] }}
[[body]]
name = "top"
material = {{ model = "saint-venant-kirchhoff", young = 1.0e3, poisson = 0.3 }}
mesh = {{ kind = "box", origin = [0.0, 0.0, 0.5], size = [1.0, 1.0, 0.5], elements = [{top}, {top}, 2] }}
[[fix]]
body = "base"
nodes = "zmin"
components = ["z"]
[[fix]]
body = "base"
nodes = "xmin"
components = ["x"]
[[fix]]
body = "base"
nodes = "ymin"
components = ["y"]
[[fix]]
body = "top"
nodes = "xmin"
components = ["x"]
[[fix]]
body = "top"
nodes = "ymin"
components = ["y"]
[[fix]]
body = "top"
nodes = "zmax"
components = ["z"]
value = -1.0e-3
[[contact]]
name = "interface"
slave = {{ body = "top", nodes = "zmin" }}
master = {{ body = "base", face = "zmax" }}
eps_n = {eps}
two_pass = {two_pass}
[monitor]
label = "press"
body = "top"
nodes = "zmax"
component = "z"
sign = -1.0
[stepping]
increments = {increments}
"#
    )
}

struct Outcome {
    deviation: f64,
    iterations: usize,
    force: f64,
    closed: usize,
}

fn run(base: usize, top: usize, two_pass: bool, eps: f64, increments: usize) -> Outcome {
    let (p, summary, mem) =
        common::solve_solid_text("contact-patch-3d.toml", &scene(base, top, two_pass, eps, increments));
    let face = &p.model.bodies[0].node_sets["zmax"];
    let uz: Vec<f64> = face.iter().map(|&n| mem.final_u[3 * n + 2]).collect();
    let mean = uz.iter().sum::<f64>() / uz.len() as f64;
    let deviation = uz.iter().map(|v| (v - mean).abs()).fold(0.0, f64::max) / mean.abs();
    let closed = (mem.surface.last().unwrap().iter())
        .filter(|q| q.state != contrail::contact::law::ContactState::Open)
        .count();
    Outcome {
        deviation,
        iterations: summary.newton_iterations,
        force: summary.monitor.expect("a monitor").force,
        closed,
    }
}

#[test]
fn two_pass_node_to_surface_transmits_a_uniform_pressure_and_one_pass_does_not() {
    for (base, top) in [(4, 3), (8, 5)] {
        let two = run(base, top, true, 1e8, 1);
        let one = run(base, top, false, 1e8, 1);
        let stiffer = run(base, top, true, 1e9, 1);
        println!(
            "{base}/{top}: two-pass u_z spread {:.2e} in {} iterations, force {:.5}, {} points closed; one pass {:.2e} in {}",
            two.deviation, two.iterations, two.force, two.closed, one.deviation, one.iterations
        );
        assert!(two.deviation <= 1e-3, "two-pass spread {:.3e}", two.deviation);
        assert!(two.iterations <= 3, "{} Newton iterations", two.iterations);
        assert!((two.force - 1.0).abs() < 0.01, "force {}", two.force);
        let nodes = (base + 1).pow(2) + (top + 1).pow(2);
        assert_eq!(two.closed, nodes, "every interface node closed");
        assert!(
            one.deviation > 1e-2,
            "one pass passed the patch test: {:.3e}",
            one.deviation
        );
        // what is left is the penalty's error: it falls as 1/ε_N
        println!(
            "{base}/{top}: two-pass at eps_n = 1e9: spread {:.2e}",
            stiffer.deviation
        );
        assert!(
            stiffer.deviation <= 0.2 * two.deviation,
            "{:.3e} at 1e9",
            stiffer.deviation
        );
        assert!(
            stiffer.iterations <= 3,
            "{} Newton iterations at 1e9",
            stiffer.iterations
        );
    }
}

/// The press in two increments: the same state (elastic and frictionless) and the same
/// uniformity, in at most 3 Newton iterations per increment.
#[test]
fn the_patch_test_in_two_increments_gives_the_same_state() {
    let one = run(4, 3, true, 1e8, 1);
    let two = run(4, 3, true, 1e8, 2);
    assert!(
        (two.force - one.force).abs() <= 1e-6 * one.force,
        "{} vs {}",
        two.force,
        one.force
    );
    assert!(two.deviation <= 1e-3, "spread {:.3e}", two.deviation);
    assert!(
        two.iterations <= 6,
        "{} Newton iterations in two increments",
        two.iterations
    );
}
