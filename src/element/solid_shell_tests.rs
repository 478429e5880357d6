//! Tests of the solid-shell on small meshes: the patch test where the thickness direction is
//! straight, thin plates without shear, membrane or thickness locking. (One-element tests —
//! finite-difference tangent, energy gradient, rigid-body modes, objectivity — run for every
//! kind in `hex8_tests.rs`.)

use super::mesh_tests::{block, jitter, solve, Mesh};
use super::tests::{materials, YOUNG};
use super::*;
use nalgebra::{DVector, Matrix3, Vector3};

/// A 3×3×2 patch of `[0, 1]² × [0, 0.2]` whose node columns are moved in-plane by up to 0.08
/// (the same move for the nodes of a column) and whose two layers have unequal thickness:
/// every element is distorted in its plane and straight through its thickness.
fn straight_through_patch() -> Mesh {
    let mut mesh = block([3, 3, 2], [1.0, 1.0, 0.2]);
    let mut seed = 11u64;
    let moves: Vec<[f64; 2]> = (0..16)
        .map(|_| [0.08 * jitter(&mut seed), 0.08 * jitter(&mut seed)])
        .collect();
    for (i, p) in mesh.nodes.iter_mut().enumerate() {
        let column = i % 16;
        let interior = |v: usize| v != 0 && v != 3;
        if interior(column % 4) || interior(column / 4) {
            p[0] += moves[column][0];
            p[1] += moves[column][1];
        }
        if i / 16 == 1 {
            p[2] = 0.13;
        }
    }
    mesh
}

/// Patch test (Irons) of the solid-shell on [`straight_through_patch`]: the boundary nodes
/// at a homogeneous deformation `x = F X + c` (every component of `F` non-zero), the interior
/// nodes free; a small `F − I` (linear solve) and a finite one (Newton), both materials. The
/// interior nodes land on `F X + c` and every Gauss point carries `½(FᵀF − I)`. Tolerance
/// 1e-9 of `|F − I|`. Where the thickness direction varies within an element (the fully
/// distorted patch of `hex8_mesh_tests.rs`) the assumed strains of a homogeneous state are not
/// interpolated exactly and the test does not hold to round-off (printed, not asserted).
#[test]
fn a_patch_straight_through_its_thickness_reproduces_homogeneous_states() {
    let mesh = straight_through_patch();
    let node_count = mesh.nodes.len();
    let on_boundary = |i: usize| {
        let (a, b, c) = (i % 4, (i / 4) % 4, i / 16);
        a == 0 || a == 3 || b == 0 || b == 3 || c == 0 || c == 2
    };
    // with one interior layer of 4 nodes per layer: free the middle layer's interior
    let fixed: Vec<bool> = (0..3 * node_count).map(|d| on_boundary(d / 3)).collect();
    assert_eq!(fixed.iter().filter(|f| !**f).count(), 12);
    let general = Matrix3::new(0.25, 0.1, -0.05, -0.08, -0.15, 0.12, 0.06, 0.2, 0.1);
    for (scale, linear) in [(4e-4, true), (1.0, false)] {
        let f_minus_i = general * scale;
        let exact = |p: &[f64; 3]| f_minus_i * Vector3::from(*p) + Vector3::new(0.1, -0.2, 0.05) * scale;
        let c = Matrix3::identity() + f_minus_i;
        let e_hom = 0.5 * (c.transpose() * c - Matrix3::identity());
        for m in materials(0.3) {
            let mut u = DVector::zeros(3 * node_count);
            let mut seed = 5u64;
            for (i, p) in mesh.nodes.iter().enumerate() {
                let off = if on_boundary(i) || linear {
                    Vector3::zeros()
                } else {
                    Vector3::from_fn(|_, _| 0.01 * jitter(&mut seed))
                };
                if on_boundary(i) || !linear {
                    u.rows_mut(3 * i, 3).copy_from(&(exact(p) + off));
                }
            }
            solve(
                Hex8Kind::SolidShell,
                &m,
                &mesh,
                &fixed,
                &DVector::zeros(u.len()),
                &mut u,
                linear,
            );
            let err = (0..node_count)
                .map(|i| (u.rows(3 * i, 3) - exact(&mesh.nodes[i])).amax())
                .fold(0.0, f64::max);
            let mut strain_err = 0.0f64;
            for el in &mesh.elems {
                let x = el.map(|i| mesh.nodes[i]);
                let ue = el.map(|i| [u[3 * i], u[3 * i + 1], u[3 * i + 2]]);
                let geo = Hex8Geometry::new(Hex8Kind::SolidShell, &x).unwrap();
                let (mut al, mut r) = ([1e-6; EAS_COUNT], [0.0; 24]);
                hex8_residual_tangent_with(Hex8Kind::SolidShell, &m, &geo, &ue, &mut al, &mut r, None).unwrap();
                for e in hex8_gauss_strains(&geo, &ue, &al).unwrap() {
                    let t = crate::element::material3d::strain_tensor(&e);
                    strain_err = strain_err.max((t - e_hom).amax());
                }
            }
            let size = f_minus_i.amax();
            println!(
                "shell patch {m:?} |F−I| {size:.1e}: node error {:.2e}, strain error {:.2e} (relative)",
                err / size,
                strain_err / size
            );
            assert!(err <= 1e-9 * size && strain_err <= 1e-9 * size);
        }
    }
}

/// Tip deflection of a cantilever plate `[0, len] × [0, 1] × [0, t]` of `n × 1 × 1`
/// elements, clamped at `x = 0` (`u_y = 0` at one root node only: the section contracts
/// freely), under a force `p` along `z` shared by the four tip nodes; linear response.
/// `skew` moves the inner node columns along `x` by `±skew` times the element length
/// (alternating with `y`): trapezoidal elements in the plate's plane.
fn plate_tip_deflection(kind: Hex8Kind, m: &Material, n: usize, len: f64, t: f64, skew: f64) -> f64 {
    let mut mesh = block([n, 1, 1], [len, 1.0, t]);
    for (i, p) in mesh.nodes.iter_mut().enumerate() {
        let (ix, iy) = (i % (n + 1), (i / (n + 1)) % 2);
        if ix != 0 && ix != n {
            let sign = if (ix + iy) % 2 == 0 { 1.0 } else { -1.0 };
            p[0] += sign * skew * len / n as f64;
        }
    }
    let dofs = 3 * mesh.nodes.len();
    let fixed: Vec<bool> = (0..dofs)
        .map(|d| match d % 3 {
            1 => d == 1,
            _ => mesh.nodes[d / 3][0] == 0.0,
        })
        .collect();
    let tip: Vec<usize> = (0..mesh.nodes.len()).filter(|&i| mesh.nodes[i][0] == len).collect();
    let mut f = DVector::zeros(dofs);
    for &i in &tip {
        f[3 * i + 2] = 0.25;
    }
    let mut u = DVector::zeros(dofs);
    solve(kind, m, &mesh, &fixed, &f, &mut u, true);
    tip.iter().map(|&i| u[3 * i + 2]).sum::<f64>() / tip.len() as f64
}

/// Timoshenko's tip deflection of a cantilever of unit width and thickness `t` under a unit
/// end force: `L³/(3EI) + L/(κGA)`, `I = t³/12`, `A = t`, `κ = 5/6`.
fn timoshenko_plate(len: f64, t: f64, nu: f64) -> f64 {
    let shear = YOUNG / (2.0 * (1.0 + nu));
    len.powi(3) / (3.0 * YOUNG * t.powi(3) / 12.0) + len / (5.0 / 6.0 * shear * t)
}

/// No transverse shear locking in a thin plate: a cantilever `L/t = 100` (`L = 10`,
/// `t = 0.1`, ν = 0.3) of 10 one-layer elements under an end force. Reference: Timoshenko
/// (beam theory: the plate is free to contract across its width). Solid-shell within 2 % on
/// rectangles and on trapezoids (skew 0.2 of the element length); the plain trilinear element
/// locks (≤ 0.05).
#[test]
fn a_thin_plate_does_not_lock_in_bending() {
    let (len, t, nu) = (10.0, 0.1, 0.3);
    let m = materials(nu)[0];
    let reference = timoshenko_plate(len, t, nu);
    for skew in [0.0, 0.2] {
        let ratio = |kind| plate_tip_deflection(kind, &m, 10, len, t, skew) / reference;
        let (shell, eas, plain) = (
            ratio(Hex8Kind::SolidShell),
            ratio(Hex8Kind::Hex8Eas),
            ratio(Hex8Kind::Hex8),
        );
        println!(
            "plate L/t = 100, skew {skew}: δ/δ_Timoshenko solid-shell {shell:.4}, hex8-eas {eas:.4}, hex8 {plain:.4}"
        );
        assert!((shell - 1.0).abs() <= 0.02, "solid-shell {shell}");
        assert!(plain <= 0.05, "hex8 {plain}");
    }
}
