//! 3D patch test: a homogeneous finite deformation `u = A X` prescribed on the boundary of a
//! distorted 2×2×2 mesh of EAS hexahedra (the centre node moved off the middle, the
//! face-centre nodes moved within their faces) is reproduced at the free nodes.
//!
//! ```text
//!      z                 unit cube, 8 hexahedra; boundary nodes: u = A X (prescribed);
//!      |  y              free: the centre node, moved to (0.58, 0.43, 0.54) — it must
//!      | /               land at (I + A) X exactly
//!      +---- x
//! ```
//!
//! Reference: any homogeneous deformation is an equilibrium state of a homogeneous
//! hyperelastic body (uniform stress, no divergence); an element that passes the patch test
//! (Taylor, Beresford & Wilson 1976; for EAS, Simo & Rifai 1990: `∫ Ẽ dV = 0`) reproduces it.
//! Parameters: `A = [[0.08, 0.03, −0.02], [0.01, −0.05, 0.04], [0.02, 0.03, 0.06]]`,
//! E = 100, ν = 0.3, St. Venant–Kirchhoff and neo-Hooke, one increment.
//! Tolerance: 1e-10 on the free nodes' displacement (measured about 1e-16).

use contrail::element::material::{lame, Material};
use contrail::element::quad::ElementKind;
use contrail::model::box_mesh::BoxMesh;
use contrail::model::{Body, Element, Model, Prescribed, Ramp, Solid, SolidKind};
use contrail::problem::Problem;
use contrail::record::Memory;
use std::sync::atomic::AtomicBool;

const A: [[f64; 3]; 3] = [[0.08, 0.03, -0.02], [0.01, -0.05, 0.04], [0.02, 0.03, 0.06]];

fn distorted_cube(material: Material) -> Model<Solid> {
    let mut mesh = BoxMesh::new([0.0; 3], [1.0; 3], [2, 2, 2], [1.0; 3]);
    // node (i, j, k) is (k·3 + j)·3 + i; the centre is 13, face centres 4, 10, 12, 14, 16, 22
    mesh.nodes[13] = [0.58, 0.43, 0.54];
    mesh.nodes[12] = [0.0, 0.6, 0.45]; // x = 0 face
    mesh.nodes[14] = [1.0, 0.42, 0.57]; // x = 1 face
    mesh.nodes[10] = [0.44, 0.0, 0.6]; // y = 0 face
    mesh.nodes[16] = [0.55, 1.0, 0.41]; // y = 1 face
    mesh.nodes[4] = [0.6, 0.55, 0.0]; // z = 0 face
    mesh.nodes[22] = [0.43, 0.45, 1.0]; // z = 1 face
    let boundary = |x: &[f64; 3]| x.iter().any(|&c| c == 0.0 || c == 1.0);
    let mut prescribed = Vec::new();
    for (n, x) in mesh.nodes.iter().enumerate().filter(|(_, x)| boundary(x)) {
        for (c, row) in A.iter().enumerate() {
            let v: f64 = (0..3).map(|j| row[j] * x[j]).sum();
            prescribed.push(Prescribed::along(3 * n + c, Ramp::linear(v, 1.0)));
        }
    }
    Model {
        name: "patch-3d".into(),
        elements: mesh.hexes.iter().map(|&h| Element { nodes: h, body: 0 }).collect(),
        bodies: vec![Body {
            name: "cube".into(),
            material,
            kind: SolidKind::from_element(ElementKind::Q4EasSafe),
            kinematics: (),
            first_node: 0,
            node_count: mesh.nodes.len(),
            node_sets: mesh.node_sets,
            faces: mesh.faces,
        }],
        nodes: mesh.nodes,
        prescribed,
        ..Model::default()
    }
}

fn patch_error(material: Material) -> f64 {
    let problem = Problem {
        model: distorted_cube(material),
        settings: Default::default(),
    };
    let src = contrail::scene::SceneSource {
        origin: "patch-3d".into(),
        text: String::new(),
    };
    let info = contrail::run_info(&src, &[], &problem);
    let mut mem = Memory::default();
    contrail::solver::run(&problem, &info, &mut mem, &AtomicBool::new(false)).expect("the patch converges");
    let free = [13usize];
    let mut err = 0.0f64;
    for n in free {
        let x = problem.model.nodes[n];
        for (c, row) in A.iter().enumerate() {
            let exact: f64 = (0..3).map(|j| row[j] * x[j]).sum();
            err = err.max((mem.final_u[3 * n + c] - exact).abs());
        }
    }
    err
}

#[test]
fn a_homogeneous_deformation_is_exact_on_a_distorted_hex_mesh() {
    let (lambda, mu) = lame(100.0, 0.3);
    for material in [
        Material::SaintVenantKirchhoff { lambda, mu },
        Material::NeoHookean { lambda, mu },
    ] {
        let err = patch_error(material);
        println!("{material:?}: max |u − A X| at the free node = {err:.3e}");
        assert!(err < 1e-10, "{material:?}: patch error {err:e}");
    }
}
