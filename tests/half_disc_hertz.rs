//! Half-disc on a rigid plane (built-in scene `half-disc`, a Gmsh mesh): Hertz line contact
//! on an unstructured quadrilateral mesh read from MSH 4.1.
//!
//! ```text
//!   ==========  flat top (physical curve "top"): u = (0, −δ), δ = 0.02
//!   \        /
//!    \______/   curved side ("arc", R = 1): slave nodes on a rigid frictionless plane y = 0
//! ```
//! Plane strain, E = 1000, ν = 0.3 (Neo-Hookean), rigid plane: `E* = E/(1 − ν²)`.
//! Reference (Hertz, cylinder on a flat; Johnson, Contact Mechanics, §4.3):
//! `a = √(4 P' R / (π E*))`, `p0 = 2 P' / (π a)`, with `P'` the force per unit length — here
//! the sum of the nodal normal forces (the whole disc is modelled, no symmetry).
//! Measured: `a` from the second moment of the nodal normal forces (`∫x²p/∫p = a²/4` for the
//! Hertz distribution), `p0` from the force of the node nearest x = 0 over its tributary width
//! (half the distance between its neighbours in contact).
//! Checks: `a` within 5 % and `p0` within 10 % of Hertz on the shipped mesh (h ≈ 0.0125 at the
//! contact, a ≈ 0.12: 21 nodes in contact) and on the mesh made with `gmsh -clscale 2`
//! (tests/data/half-disc-coarse.msh, 11 nodes in contact), whose `a` differs by less than
//! 2 % (measured: a −2.08 % / −2.75 %, p0 +2.55 % / +2.69 %); the contact force equals the
//! reaction at the top (equilibrium, 1e-6); the binary MSH file of the same mesh
//! (tests/data/half-disc-bin.msh) gives the same nodes and the same force to 1e-12; the
//! contact is centred under the axis (|x̄| < 0.05 a: the mesh is not symmetric).

mod common;

struct Hertz {
    a: f64,
    force: f64,
    reaction: f64,
    a_err: f64,
    p0_err: f64,
    nodes: usize,
}

fn run(mesh_file: Option<&str>) -> Hertz {
    let set = mesh_file.map(|f| format!("body.disc.mesh.file={}/tests/data/{f}", env!("CARGO_MANIFEST_DIR")));
    let sets: Vec<&str> = set.iter().map(String::as_str).collect();
    let m = common::scene("half-disc", &sets);
    let (_, mem) = common::solve_ok(&m);
    let pts = mem.contact.last().unwrap();
    let mut xn: Vec<(f64, f64)> = pts
        .iter()
        .filter(|p| p.normal_force > 0.0)
        .map(|p| (p.position[0], p.normal_force))
        .collect();
    xn.sort_by(|a, b| a.0.total_cmp(&b.0));
    let p_line: f64 = xn.iter().map(|v| v.1).sum();
    let e_star = 1000.0 / (1.0 - 0.09);
    let a_ref = (4.0 * p_line / (std::f64::consts::PI * e_star)).sqrt();
    let p0_ref = 2.0 * p_line / (std::f64::consts::PI * a_ref);
    let mean: f64 = xn.iter().map(|(x, n)| x * n).sum::<f64>() / p_line;
    let m2: f64 = xn.iter().map(|(x, n)| (x - mean).powi(2) * n).sum();
    let a = 2.0 * (m2 / p_line).sqrt();
    let i0 = (1..xn.len() - 1)
        .min_by(|&i, &j| xn[i].0.abs().total_cmp(&xn[j].0.abs()))
        .unwrap();
    let p0 = xn[i0].1 / (0.5 * (xn[i0 + 1].0 - xn[i0 - 1].0));
    let reaction = mem.increments.last().unwrap().monitor.as_ref().unwrap().force;
    assert!(
        mean.abs() < 0.05 * a_ref,
        "contact centred at x = {mean}, not under the axis"
    );
    println!(
        "{}: {} nodes in contact, P' = {p_line:.5} (reaction {reaction:.5}), a = {a:.5} (Hertz {a_ref:.5}, {:+.2} %), p0 = {p0:.2} (Hertz {p0_ref:.2}, {:+.2} %), centre {mean:+.2e}",
        mesh_file.unwrap_or("half-disc.msh"),
        xn.len(),
        100.0 * (a / a_ref - 1.0),
        100.0 * (p0 / p0_ref - 1.0)
    );
    Hertz {
        a,
        force: p_line,
        reaction,
        a_err: (a / a_ref - 1.0).abs(),
        p0_err: (p0 / p0_ref - 1.0).abs(),
        nodes: m.model.nodes.len(),
    }
}

#[test]
fn half_disc_on_a_plane_matches_hertz() {
    let fine = run(None);
    assert!(fine.a_err < 0.05, "a error {}", fine.a_err);
    assert!(fine.p0_err < 0.10, "p0 error {}", fine.p0_err);
    assert!(
        (fine.force - fine.reaction).abs() < 1e-6 * fine.reaction,
        "contact force {} against reaction {}",
        fine.force,
        fine.reaction
    );
    let coarse = run(Some("half-disc-coarse.msh"));
    assert!(coarse.nodes < fine.nodes / 2, "the coarse mesh is coarser");
    assert!(coarse.a_err < 0.05, "coarse a error {}", coarse.a_err);
    assert!(coarse.p0_err < 0.10, "coarse p0 error {}", coarse.p0_err);
    // mesh independence: the half-width changes by less than 2 % when h is halved
    assert!(
        (fine.a / coarse.a - 1.0).abs() < 0.02,
        "a {} (fine) against {} (coarse)",
        fine.a,
        coarse.a
    );
}

#[test]
fn binary_msh_gives_the_same_run() {
    let ascii = run(None);
    let binary = run(Some("half-disc-bin.msh"));
    assert_eq!(ascii.nodes, binary.nodes);
    assert!(
        (ascii.force - binary.force).abs() <= 1e-12 * ascii.force,
        "{} against {}",
        ascii.force,
        binary.force
    );
}

/// A Gmsh physical curve as a master face: a rigid point pressed into the flat top
/// (physical curve "top", listed right to left in the .geo and oriented by the reader) is
/// pushed back along the outward normal ≈ (0, 1) of the face, i.e. out of the body (with the
/// face reversed the point would be "inside" at once and the normal −y).
#[test]
fn gmsh_face_normals_point_out_of_the_body() {
    let text = format!(
        r#"name = "punch-on-top"
[[body]]
name = "disc"
material = {{ model = "neo-hookean", young = 1.0e3, poisson = 0.3 }}
mesh = {{ kind = "gmsh", file = "{}/scenes/half-disc.msh" }}
[[fix]]
body = "disc"
nodes = "arc"
components = ["x", "y"]
[[rigid]]
name = "P"
point = [0.013, 1.0005]
move = {{ y = -0.003 }}
[[contact]]
name = "punch"
slave = {{ rigid = "P" }}
master = {{ body = "disc", face = "top" }}
eps_n = 1.0e4
[stepping]
increments = 2
"#,
        env!("CARGO_MANIFEST_DIR")
    );
    let m = common::scene_text(&text);
    let (_, mem) = common::solve_ok(&m);
    let p = &mem.contact.last().unwrap()[0];
    println!(
        "punch: gap {:.3e}, N = {:.4}, normal {:?}",
        p.gap, p.normal_force, p.normal
    );
    assert!(p.normal_force > 0.0, "the point must be in contact: {p:?}");
    assert!(p.gap < 0.0);
    // the face tilts a little under the point (current configuration): about (0, 1), not (0, −1)
    assert!(p.normal[1] > 0.99, "normal {:?}", p.normal);
}

/// Clockwise quadrilaterals from Gmsh: `tests/data/half-disc-cw.msh` is the coarse mesh of
/// `scenes/half-disc.geo` with its curve loop reversed (`Curve Loop(1) = {-3, -2, -1};`,
/// `gmsh -2 -format msh41 -clscale 2`): Gmsh then numbers every quadrilateral clockwise.
/// The reader renumbers all of them, and the run equals the counter-clockwise file's.
#[test]
fn clockwise_gmsh_mesh_is_renumbered() {
    let path = format!("{}/tests/data/half-disc-cw.msh", env!("CARGO_MANIFEST_DIR"));
    let mesh = contrail::model::gmsh::read_gmsh(&path, &std::fs::read(&path).unwrap()).unwrap();
    assert_eq!(
        mesh.reoriented,
        mesh.quads.len(),
        "every quadrilateral of the file is clockwise"
    );
    let cw = run(Some("half-disc-cw.msh"));
    let ccw = run(Some("half-disc-coarse.msh"));
    assert!(
        (cw.force - ccw.force).abs() < 1e-9 * ccw.force,
        "{} against {}",
        cw.force,
        ccw.force
    );
}
