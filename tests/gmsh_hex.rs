//! Gmsh MSH 4.1 hexahedra as a 3D body (`mesh = { kind = "gmsh-3d", file = … }`).
//!
//! ```text
//!   left |▓▓▓▓▓▓▓|▓▓▓▓▓▓▓| right → P_x = 5, ↓ P_z = 2     bar 2 × 1 × 1, two hexahedra,
//!   x = 0                  x = 2                          clamped at x = 0
//! ```
//!
//! Reference: the same bar as a `box` mesh (`tests/data/bar-3d-box.toml`), whose nodes the
//! hand-written `tests/data/bar-2x1x1.msh` numbers in the same order: the two runs must give
//! the same displacements. Parameters: neo-Hooke, E = 100, ν = 0.3, EAS-21 with holds (the
//! default element), two increments, residual tolerance 1e-12; tip deflection 0.368 (large
//! enough for the geometric nonlinearity to matter). Tolerance: 1e-10 on every displacement
//! component (measured: 0, the same arithmetic). The reader: node sets of every physical group, faces of the physical surfaces
//! with outward normals (also where the file's quadrilaterals face inward), an inverted
//! hexahedron and a tetrahedron refused naming the file and the element.

use contrail::model::gmsh::{read_gmsh_hex, GmshError};
use contrail::record::Memory;
use std::sync::atomic::AtomicBool;

const MSH: &str = include_str!("data/bar-2x1x1.msh");

fn final_u(scene: &str) -> Vec<f64> {
    let (src, problem) = contrail::load_any_scene(scene, &[]).expect("the scene loads");
    let contrail::scene::AnyProblem::Solid(problem) = problem else {
        panic!("{scene} is a 3D scene")
    };
    let info = contrail::run_info(&src, &[], &problem);
    let mut mem = Memory::default();
    contrail::solver::run(&problem, &info, &mut mem, &AtomicBool::new(false)).expect("converges");
    mem.final_u
}

#[test]
fn a_gmsh_bar_gives_the_box_meshs_displacements() {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/tests/data/");
    let gmsh = final_u(&format!("{dir}bar-3d-gmsh.toml"));
    let boxed = final_u(&format!("{dir}bar-3d-box.toml"));
    assert_eq!(gmsh.len(), 36);
    assert_eq!(gmsh.len(), boxed.len());
    let tip = -gmsh[3 * 2 + 2];
    assert!(tip > 0.1, "tip deflection {tip}");
    let diff = gmsh.iter().zip(&boxed).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max);
    println!("tip deflection {tip}, max difference {diff:e}");
    assert!(diff < 1e-10, "max |u_gmsh − u_box| = {diff:e}");
}

#[test]
fn physical_groups_are_node_sets_and_boundary_surfaces_outward_faces() {
    let m = read_gmsh_hex("bar-2x1x1.msh", MSH.as_bytes()).unwrap();
    assert_eq!((m.nodes.len(), m.hexes.len()), (12, 2));
    assert_eq!(m.node_sets["left"], vec![0, 3, 6, 9]);
    assert_eq!(m.node_sets["right"], vec![2, 5, 8, 11]);
    assert_eq!(m.node_sets["bottom"], vec![0, 1, 2, 3, 4, 5]);
    assert_eq!(m.node_sets["block"].len(), 12);
    assert_eq!(m.node_sets["all"].len(), 12);
    let outward = [
        ("left", [-1.0, 0.0, 0.0]),
        ("right", [1.0, 0.0, 0.0]),
        ("bottom", [0.0, 0.0, -1.0]),
    ];
    for (name, n) in outward {
        let faces = &m.faces[name];
        assert_eq!(faces.len(), if name == "bottom" { 2 } else { 1 });
        for f in faces {
            let x = f.map(|i| m.nodes[i]);
            let (a, b) = (sub(x[1], x[0]), sub(x[3], x[0]));
            let normal = [
                a[1] * b[2] - a[2] * b[1],
                a[2] * b[0] - a[0] * b[2],
                a[0] * b[1] - a[1] * b[0],
            ];
            assert_eq!(normal, n, "{name}: {f:?}");
        }
    }
    assert!(m.interior_surfaces.is_empty());
}

fn sub(p: [f64; 3], q: [f64; 3]) -> [f64; 3] {
    [p[0] - q[0], p[1] - q[1], p[2] - q[2]]
}

#[test]
fn an_inverted_hexahedron_and_a_tetrahedron_are_refused_naming_file_and_element() {
    // hexahedron 6 with its bottom and top faces swapped: det J < 0
    let inverted = MSH.replace("6 2 3 6 5 8 9 12 11", "6 8 9 12 11 2 3 6 5");
    let e = read_gmsh_hex("inverted.msh", inverted.as_bytes()).unwrap_err();
    assert!(matches!(e, GmshError::BadHex { element: 6, .. }), "{e}");
    let text = e.to_string();
    assert!(
        text.contains("inverted.msh") && text.contains("hexahedron 6") && text.contains("inverted"),
        "{text}"
    );
    let tet = MSH
        .replace("3 1 5 2\n", "3 1 5 1\n")
        .replace("6 2 3 6 5 8 9 12 11\n", "")
        .replace("4 6 1 6\n", "5 6 1 6\n")
        .replace("$EndElements", "3 1 4 1\n6 2 3 6 8\n$EndElements");
    let e = read_gmsh_hex("tet.msh", tet.as_bytes()).unwrap_err();
    assert!(matches!(e, GmshError::UnsupportedElement { code: 4, .. }), "{e}");
    assert!(e.to_string().contains("tet.msh"), "{e}");
}
