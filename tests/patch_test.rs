//! Patch test (Taylor; MacNeal & Harder, Finite Elem Anal Des 1 (1985) 3–20), large-strain
//! version: a distorted 2×2 mesh whose boundary nodes follow a homogeneous deformation
//! `u = H X` must reproduce the homogeneous state everywhere — the interior node lands on
//! `H X` and every element carries the same stress `S(E(I + H))` — to round-off.
//!
//! ```text
//!  6-----7-----8
//!  |    /  \   |       interior node 4 moved off-centre to (1.25, 0.8)
//!  3---4----- 5
//!  |  /    \   |
//!  0-----1-----2
//! ```
//! Parameters: 2 × 2 square, E = 100, ν = 0.3, both materials, both element kinds.
//! Tolerance: 1e-10 relative (interior displacement and element stresses).

mod common;

use contrail::element::quad::{quad_centre_stress, ElementKind};
use contrail::model::{Prescribed, Ramp};

const H: [[f64; 2]; 2] = [[0.05, 0.02], [-0.03, 0.08]];

fn patch(material: &str, element: &str) {
    let text = format!(
        "name = \"patch\"\n[[body]]\nname = \"p\"\nelement = \"{element}\"\n\
         material = {{ model = \"{material}\", young = 100.0, poisson = 0.3 }}\n\
         mesh = {{ kind = \"rectangle\", origin = [0.0, 0.0], size = [2.0, 2.0], elements = [2, 2] }}\n\
         [stepping]\nincrements = 2\n[solver]\nresidual_tol = 1e-13\n"
    );
    let mut p = common::scene_text(&text);
    let m = &mut p.model;
    m.nodes[4] = [1.25, 0.8];
    for n in [0, 1, 2, 3, 5, 6, 7, 8] {
        let x = m.nodes[n];
        for (c, h) in H.iter().enumerate() {
            let u = h[0] * x[0] + h[1] * x[1];
            m.prescribed.push(Prescribed::along(2 * n + c, Ramp::linear(u, 1.0)));
        }
    }
    let (_, mem) = common::solve_ok(&p);
    let m = &p.model;
    let u = &mem.final_u;
    let x4 = m.nodes[4];
    for (c, h) in H.iter().enumerate() {
        let exact = h[0] * x4[0] + h[1] * x4[1];
        assert!(
            (u[8 + c] - exact).abs() < 1e-10 * exact.abs(),
            "{material}/{element}: u4[{c}] = {} vs {exact}",
            u[8 + c]
        );
    }
    let body = &m.bodies[0];
    let kind = body.kind;
    let mut stresses = Vec::new();
    for e in &m.elements {
        let x = e.nodes.map(|n| m.nodes[n]);
        let ue = e.nodes.map(|n| [u[2 * n], u[2 * n + 1]]);
        // α of the converged state: re-solve it for this u (the kernel is a function of u)
        let mut alpha = [0.0; 4];
        let mut r = [0.0; 8];
        contrail::element::quad::quad_residual_tangent(kind, &body.material, &x, &ue, &mut alpha, &mut r, None)
            .unwrap();
        if kind == ElementKind::Q4Eas {
            assert!(
                alpha.iter().all(|a| a.abs() < 1e-10),
                "no enhanced strain in a homogeneous state: {alpha:?}"
            );
        }
        stresses.push(quad_centre_stress(kind, &body.material, &x, &ue, &alpha).unwrap().1);
    }
    for s in &stresses {
        let d = (s - stresses[0]).norm();
        assert!(
            d < 1e-10 * stresses[0].norm(),
            "{material}/{element}: stress differs by {d:e}"
        );
    }
}

#[test]
fn patch_test_distorted_mesh_reproduces_homogeneous_state() {
    for mat in ["saint-venant-kirchhoff", "neo-hookean"] {
        for el in ["q4", "q4-eas"] {
            patch(mat, el);
        }
    }
}
