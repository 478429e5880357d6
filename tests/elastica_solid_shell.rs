//! The elastica in 3D with solid-shells: the plane-strain cantilever of `cantilever_elastica.rs`
//! as one layer of solid-shell elements of unit width with `u_y = 0` at every node
//! (`tests/data/elastica-solid-shell.toml`) — the seed's way of computing a 2D strip in 3D
//! (Harnau, Konyukhov & Schweizerhof, Comput Struct 83 (2005): solid-shells, one element
//! across the width, plane-strain constraints).
//!
//! ```text
//!  |=========================================|  ↓ P (dead, on the 4 tip nodes)
//!  clamped            L = 10, h = 0.5, width 1
//! ```
//! E = 2.1e4, ν = 0.3, St. Venant–Kirchhoff; EI = E h³/(12 (1 − ν²)) = 240.3846 per unit
//! width; k = P L²/EI = 1, 2, 4 in 2, 4, 8 increments.
//! References: Mattiasson (IJNME 17 (1981) 145–153, Table 1): v/L = 0.30172, 0.49346,
//! 0.66996; and the 2D strip of the same mesh (24 × 1 `q4-eas`, the built-in `cantilever`).
//! Tolerances: v within 2 % of Mattiasson (the 2D test's), and within 0.2 % of the 2D strip
//! on 24 × 1 × 1 and on 48 × 1 × 2; the hexahedron with EAS-21 on the same 3D mesh equals the
//! 2D strip to 1e-6 (it contains the 2D element in plane strain).
//! Measured 2026-11-28: k = 4: 2D 6.71367, solid-shell 6.72012 (+0.10 %), hex8-eas 6.71367.

mod common;

use contrail::record::Memory;
use std::sync::atomic::AtomicBool;

const SCENE: &str = include_str!("data/elastica-solid-shell.toml");
const EI: f64 = 2.1e4 * 0.125 / (12.0 * 0.91);
const L: f64 = 10.0;
const MATTIASSON: [(f64, f64); 3] = [(1.0, 0.30172), (2.0, 0.49346), (4.0, 0.66996)];

/// Tip deflection of the 3D scene with overrides.
fn tip_3d(sets: &[String]) -> f64 {
    let src = contrail::scene::SceneSource {
        origin: "elastica-solid-shell.toml".into(),
        text: SCENE.into(),
    };
    let file = contrail::scene::parse(&src, sets).unwrap_or_else(|e| panic!("{e}"));
    let built = contrail::scene::build_any(&src, &file).unwrap_or_else(|e| panic!("{e}"));
    let contrail::scene::AnyProblem::Solid(problem) = built else {
        panic!("a 3D scene")
    };
    let info = contrail::run_info(&src, sets, &problem);
    let summary = contrail::solver::run(&problem, &info, &mut Memory::default(), &AtomicBool::new(false))
        .unwrap_or_else(|e| panic!("{sets:?}: {e}"));
    summary.monitor.expect("a monitor").displacement
}

/// Tip deflection of the 2D strip (`cantilever`) on `elements`.
fn tip_2d(total: &str, elements: [usize; 2], increments: &str) -> f64 {
    let mesh = format!("body.strip.mesh.elements=[{}, {}]", elements[0], elements[1]);
    let m = common::scene("cantilever", &[total, &mesh, increments, "body.strip.element=q4-eas"]);
    common::solve_ok(&m).0.monitor.unwrap().displacement
}

#[test]
fn solid_shells_in_plane_strain_bend_as_the_2d_strip_and_mattiasson() {
    for (k, v_ref) in MATTIASSON {
        let total = format!("load.0.total={}", -k * EI / (L * L));
        let increments = format!("stepping.increments={}", (2.0 * k) as usize);
        for (mesh3, mesh2) in [([24, 1, 1], [24, 1]), ([48, 1, 2], [48, 2])] {
            let elements = format!("body.strip.mesh.elements=[{}, {}, {}]", mesh3[0], mesh3[1], mesh3[2]);
            let sets = |element: &str| {
                vec![
                    total.clone(),
                    increments.clone(),
                    elements.clone(),
                    format!("body.strip.element={element}"),
                ]
            };
            let shell = tip_3d(&sets("solid-shell"));
            let plane = tip_2d(&total, mesh2, &increments);
            let vs_2d = shell / plane - 1.0;
            let vs_ref = shell / L / v_ref - 1.0;
            println!(
                "k = {k}, {mesh3:?}: solid-shell {shell:.5}, 2D {plane:.5} ({:+.3} %), Mattiasson {:+.3} %",
                100.0 * vs_2d,
                100.0 * vs_ref
            );
            assert!(
                vs_2d.abs() <= 2e-3,
                "k = {k} {mesh3:?}: {shell} vs the 2D strip's {plane}"
            );
            assert!(vs_ref.abs() <= 0.02, "k = {k} {mesh3:?}: v/L {} vs {v_ref}", shell / L);
            if mesh3 == [24, 1, 1] {
                let hex = tip_3d(&sets("q4-eas"));
                assert!((hex / plane - 1.0).abs() <= 1e-6, "hex8-eas {hex} vs 2D {plane}");
            }
        }
    }
}
