//! Uniaxial stretch of a 3D bar of hexahedra to λ = 1.5 (St. Venant–Kirchhoff): force and
//! lateral contraction against the closed-form answer.
//!
//! ```text
//!   xmin: u_x = 0, ymin: u_y = 0, zmin: u_z = 0 (symmetry planes), xmax: u_x = (λ − 1) L
//! ```
//!
//! Reference (homogeneous uniaxial stress, `S₂₂ = S₃₃ = 0`): `E₁₁ = (λ² − 1)/2`,
//! `E₂₂ = −ν E₁₁`, `S₁₁ = E E₁₁`, force `F = λ S₁₁ A₀` (first Piola–Kirchhoff times the
//! reference area), lateral stretch `λ_t = √(1 + 2 E₂₂)`.
//! Parameters: bar 4 × 1 × 2 on a 4×2×2 mesh, E = 200, ν = 0.3, 10 increments.
//! Tolerance: 1e-8 relative on the force and the lateral displacement (a homogeneous state:
//! exact up to round-off).

use contrail::record::Memory;
use std::sync::atomic::AtomicBool;

const SCENE: &str = r#"
name = "bar-stretch-3d"
[[body]]
name = "bar"
material = { model = "saint-venant-kirchhoff", young = 200.0, poisson = 0.3 }
mesh = { kind = "box", origin = [0.0, 0.0, 0.0], size = [4.0, 1.0, 2.0], elements = [4, 2, 2] }
[[fix]]
body = "bar"
nodes = "xmin"
components = ["x"]
[[fix]]
body = "bar"
nodes = "ymin"
components = ["y"]
[[fix]]
body = "bar"
nodes = "zmin"
components = ["z"]
[[fix]]
body = "bar"
nodes = "xmax"
components = ["x"]
value = 2.0
[[monitor]]
label = "end force"
body = "bar"
nodes = "xmax"
component = "x"
[[monitor]]
label = "side"
body = "bar"
nodes = "ymax"
component = "y"
[stepping]
increments = 10
[solver]
residual_tol = 1e-12
"#;

#[test]
fn a_bar_stretched_to_one_and_a_half_has_the_closed_form_force_and_contraction() {
    let src = contrail::scene::SceneSource {
        origin: "bar-stretch-3d.toml".into(),
        text: SCENE.into(),
    };
    let file = contrail::scene::parse(&src, &[]).expect("parses");
    let contrail::scene::AnyProblem::Solid(problem) = contrail::scene::build_any(&src, &file).expect("builds") else {
        panic!("a 3D scene")
    };
    let info = contrail::run_info(&src, &[], &problem);
    let mut mem = Memory::default();
    let s = contrail::solver::run(&problem, &info, &mut mem, &AtomicBool::new(false)).expect("converges");
    let (young, nu, stretch, area): (f64, f64, f64, f64) = (200.0, 0.3, 1.5, 2.0);
    let e11 = (stretch * stretch - 1.0) / 2.0;
    let force = stretch * young * e11 * area;
    let lateral = (1.0 - 2.0 * nu * e11).sqrt() - 1.0; // y = 1: u_y = (λ_t − 1) · 1
    let [end, side] = [&s.monitors[0], &s.monitors[1]];
    let rel = |a: f64, b: f64| (a - b).abs() / b.abs();
    println!(
        "force {:.12} (exact {force:.12}, rel {:.1e}); u_y {:.12} (exact {lateral:.12}, rel {:.1e}); {} Newton iterations",
        end.force,
        rel(end.force, force),
        side.displacement,
        rel(side.displacement, lateral),
        s.newton_iterations
    );
    assert!(rel(end.force, force) < 1e-8);
    assert!(rel(side.displacement, lateral) < 1e-8);
    assert!((end.displacement - 2.0).abs() < 1e-12);
}
