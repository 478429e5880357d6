//! Dead body loads (gravity) against statics and beam theory.
//!
//! 1. Equilibrium: a 2 × 1 block (4 × 2 EAS elements, Neo-Hooke) standing on its fixed
//!    bottom under `b = (0.7, −3.0)` per unit volume: the support reaction is `−b · A` to
//!    1e-9 relative (the consistent nodal forces integrate `b` exactly).
//! 2. Cantilever under self-weight (plane strain, L = 10, h = 0.5, E = 2.1e4, ν = 0.3,
//!    `EI' = E h³ / (12 (1 − ν²)) = 240.38`), `b_y = −0.01`, so `q = b_y h = −0.005` per unit
//!    length: Euler–Bernoulli tip deflection `w = q L⁴ / (8 EI') = 0.0260` (L/385, linear
//!    range). Tolerance 1 % with 24 × 1 and 48 × 2 EAS elements (shear deformation at L/h = 20 adds
//!    ≈ 0.1 %).
//! 3. A body load on a body that does not exist is refused with its name.

mod common;

const BLOCK: &str = r#"
name = "block-gravity"
description = "a block under its own weight on a fixed base"

[[body]]
name = "block"
material = { model = "neo-hookean", young = 1.0e3, poisson = 0.3 }
mesh = { kind = "rectangle", origin = [0.0, 0.0], size = [2.0, 1.0], elements = [4, 2] }

[[fix]]
body = "block"
nodes = "bottom"
components = ["x", "y"]

[[body_load]]
body = "block"
force = [0.7, -3.0]

[stepping]
increments = 4
"#;

#[test]
fn body_load_block_reaction_balances_the_weight() {
    let model = common::scene_text(BLOCK);
    let (_, mem) = common::solve_ok(&model);
    let [rx, ry] = mem.increments.last().unwrap().reaction_total;
    let area = 2.0;
    println!("reaction ({rx}, {ry}) against ({}, {})", -0.7 * area, 3.0 * area);
    assert!((rx + 0.7 * area).abs() < 1e-9 * 3.0 * area, "{rx}");
    assert!((ry - 3.0 * area).abs() < 1e-9 * 3.0 * area, "{ry}");
}

#[test]
fn body_load_cantilever_under_self_weight_matches_beam_theory() {
    let ei = 2.1e4 * 0.125 / (12.0 * 0.91);
    let q: f64 = -0.01 * 0.5;
    let w = q.abs() * 1e4 / (8.0 * ei);
    // the seed's mesh and one refinement
    for mesh in ["[24,1]", "[48,2]"] {
        let elements = format!("body.strip.mesh.elements={mesh}");
        let model = common::scene(
            "cantilever",
            &[
                "load.0.total=0.0",
                "stepping.increments=2",
                "body_load=[{ body = \"strip\", force = [0.0, -0.01] }]",
                &elements,
            ],
        );
        let (summary, _) = common::solve_ok(&model);
        let tip = summary.monitor.unwrap().displacement;
        println!(
            "{mesh}: tip {tip:.6} against q L^4 / (8 EI) = {w:.6} ({:+.3} %)",
            100.0 * (tip / w - 1.0)
        );
        assert!((tip / w - 1.0).abs() < 0.01, "{mesh}: {tip} vs {w}");
    }
}

#[test]
fn body_load_on_an_unknown_body_is_refused() {
    let err = common::scene_text_err(&BLOCK.replace("body = \"block\"\nforce", "body = \"blok\"\nforce"));
    assert!(err.contains("blok"), "{err}");
}
