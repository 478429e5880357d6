//! Pure bending of a one-layer strip: shear locking check (beam theory, plane strain).
//!
//! ```text
//!   symmetry (u_x = 0)                      → +F (top node)
//!  |===============================|
//!  u_y = 0 at the bottom node              ← −F (bottom node)    M = F h
//! ```
//! L = 10, h = 0.5, 10 × 1 elements, E = 2.1e4, ν = 0.3, EI = E h³/(12(1 − ν²)); a small
//! moment M = 0.05 (tip rotation ≈ 2e-3, linear regime). Beam theory: tip deflection
//! w = M L² / (2 EI). Tolerance: EAS within 1 %; the plain Q4 element is shown locking
//! (deflection below 70 % of beam theory with 2:1 elements in one layer; the classical
//! estimate of the locking ratio is ≈ 1/(1 + (1 − ν)/2 · (a/b)²) ≈ 0.4).

mod common;

const EI: f64 = 2.1e4 * 0.125 / (12.0 * 0.91);

fn tip_deflection(element: &str) -> f64 {
    let text = format!(
        "name = \"bending\"\n[[body]]\nname = \"s\"\nelement = \"{element}\"\n\
         material = {{ model = \"saint-venant-kirchhoff\", young = 2.1e4, poisson = 0.3 }}\n\
         mesh = {{ kind = \"rectangle\", origin = [0.0, 0.0], size = [10.0, 0.5], elements = [10, 1] }}\n\
         [[fix]]\nbody = \"s\"\nnodes = \"left\"\ncomponents = [\"x\"]\n\
         [[fix]]\nbody = \"s\"\nnodes = \"bottom-left\"\ncomponents = [\"y\"]\n\
         [[load]]\nbody = \"s\"\nnodes = \"top-right\"\ncomponent = \"x\"\ntotal = 0.1\n\
         [[load]]\nbody = \"s\"\nnodes = \"bottom-right\"\ncomponent = \"x\"\ntotal = -0.1\n\
         [stepping]\nincrements = 1\n[solver]\nresidual_tol = 1e-12\n"
    );
    let m = common::scene_text(&text);
    let (_, mem) = common::solve_ok(&m);
    let right = &m.model.bodies[0].node_sets["right"];
    // tension on top, compression below: the strip bends downwards
    -right.iter().map(|&n| mem.final_u[2 * n + 1]).sum::<f64>() / 2.0
}

#[test]
fn pure_bending_one_layer_does_not_lock() {
    let m = 0.1 * 0.5;
    let beam = m * 100.0 / (2.0 * EI);
    let eas = tip_deflection("q4-eas");
    let q4 = tip_deflection("q4");
    println!(
        "beam theory {beam:.6e}, EAS {eas:.6e} (ratio {:.4}), Q4 {q4:.6e} (ratio {:.4})",
        eas / beam,
        q4 / beam
    );
    assert!((eas / beam - 1.0).abs() < 0.01, "EAS ratio {}", eas / beam);
    assert!(q4 / beam < 0.7, "plain Q4 should lock here, ratio {}", q4 / beam);
}
