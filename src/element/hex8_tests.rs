//! One-element tests of the hexahedron: tangent and residual against finite differences,
//! rigid-body modes, objectivity, typed errors, hourglass holds. (Meshes: `hex8_mesh_tests.rs`.)

use super::*;
use crate::element::material::lame;
use nalgebra::{DMatrix, Rotation3, Unit};

/// A distorted element (no two faces parallel), Gmsh/VTK order, volume ≈ 1.2.
pub(super) const X: [[f64; 3]; 8] = [
    [0.0, 0.0, 0.0],
    [1.3, 0.1, -0.05],
    [1.2, 1.0, 0.1],
    [-0.1, 0.8, 0.0],
    [0.1, -0.05, 0.9],
    [1.1, 0.05, 1.2],
    [1.25, 1.1, 1.0],
    [0.05, 0.9, 1.1],
];

/// A sizeable non-homogeneous deformation (strains up to ≈ 25 %, bending-like and
/// hourglass-like parts that activate the enhanced modes).
const U_LARGE: [[f64; 3]; 8] = [
    [0.0, 0.0, 0.0],
    [0.15, 0.05, -0.04],
    [0.05, 0.22, 0.03],
    [-0.08, 0.04, 0.06],
    [0.03, -0.06, -0.12],
    [0.2, 0.02, 0.1],
    [-0.04, 0.12, -0.15],
    [0.06, -0.1, 0.05],
];

pub(super) const YOUNG: f64 = 2.1e4;

pub(super) fn materials(nu: f64) -> [Material; 2] {
    let (l, m) = lame(YOUNG, nu);
    [
        Material::SaintVenantKirchhoff { lambda: l, mu: m },
        Material::NeoHookean { lambda: l, mu: m },
    ]
}

const KINDS: [Hex8Kind; 3] = [Hex8Kind::Hex8, Hex8Kind::Hex8Eas, Hex8Kind::SolidShell];

/// One evaluation on a given geometry: `(energy, R*, K*, α)`.
fn eval_geo(
    kind: Hex8Kind,
    m: &Material,
    geo: &Hex8Geometry,
    u: &[[f64; 3]; 8],
) -> (f64, [f64; 24], DMatrix<f64>, [f64; EAS_COUNT]) {
    let (mut a, mut r, mut k) = ([0.0; EAS_COUNT], [0.0; 24], [0.0; 576]);
    let e = hex8_residual_tangent_with(kind, m, geo, u, &mut a, &mut r, Some(&mut k)).unwrap();
    (e, r, DMatrix::from_row_slice(24, 24, &k), a)
}

fn eval(kind: Hex8Kind, m: &Material, u: &[[f64; 3]; 8]) -> (f64, [f64; 24], DMatrix<f64>, [f64; EAS_COUNT]) {
    eval_geo(kind, m, &Hex8Geometry::new(kind, &X).unwrap(), u)
}

fn shifted(u: &[[f64; 3]; 8], dof: usize, h: f64) -> [[f64; 3]; 8] {
    let mut v = *u;
    v[dof / 3][dof % 3] += h;
    v
}

/// `max |K − FD(R)| / max |K|` with central differences of step `h`.
pub(super) fn tangent_fd_error(kind: Hex8Kind, m: &Material, geo: &Hex8Geometry, u: &[[f64; 3]; 8], h: f64) -> f64 {
    let (_, _, k, _) = eval_geo(kind, m, geo, u);
    let mut err = 0.0f64;
    for j in 0..24 {
        let (_, rp, _, _) = eval_geo(kind, m, geo, &shifted(u, j, h));
        let (_, rm, _, _) = eval_geo(kind, m, geo, &shifted(u, j, -h));
        for i in 0..24 {
            err = err.max(((rp[i] - rm[i]) / (2.0 * h) - k[(i, j)]).abs());
        }
    }
    err / k.amax()
}

/// `K* = ∂R*/∂u` against central differences (`h = 1e-6`) of the condensed residual, on the
/// distorted element at a sizeable deformation (enhanced modes active: `max |α| > 1e-2`) and
/// at rest, both kinds, both materials. Reference: the FD of the kernel's own residual.
/// Tolerance 1e-7 of `max |K|` (measured ≤ 1.3e-10, at `max |α|` ≈ 0.03 for EAS).
#[test]
fn tangent_matches_finite_differences_for_both_kinds_and_materials() {
    for m in materials(0.3) {
        for kind in KINDS {
            let geo = Hex8Geometry::new(kind, &X).unwrap();
            for u in [U_LARGE, [[0.0; 3]; 8]] {
                let err = tangent_fd_error(kind, &m, &geo, &u, 1e-6);
                let al = eval(kind, &m, &u).3;
                let amax = al.iter().fold(0.0f64, |a, b| a.max(b.abs()));
                println!(
                    "{kind:?} {m:?} |u| {:.2}: FD error {err:.2e}, max |α| {amax:.3e}",
                    u[5][0]
                );
                assert!(err < 1e-7, "{kind:?} {m:?}: {err:.2e}");
                if kind == Hex8Kind::Hex8Eas && u == U_LARGE {
                    assert!(amax > 1e-2, "the enhanced modes are not active: {al:?}");
                }
            }
        }
    }
}

/// `R* = ∂Π/∂u` (the condensed element is hyperelastic in `u` alone, `α` solved for each
/// `u`) against central differences of the returned energy (`h = 1e-6`); `K*` symmetric.
/// Tolerance 1e-7 of `max |R*|`; symmetry 1e-12 of `max |K*|`.
#[test]
fn residual_is_the_energy_gradient_and_the_tangent_symmetric() {
    for m in materials(0.3) {
        for kind in KINDS {
            let (_, r, k, _) = eval(kind, &m, &U_LARGE);
            let rmax = r.iter().fold(0.0f64, |a, b| a.max(b.abs()));
            let h = 1e-6;
            for (j, rj) in r.iter().enumerate() {
                let fd = (eval(kind, &m, &shifted(&U_LARGE, j, h)).0 - eval(kind, &m, &shifted(&U_LARGE, j, -h)).0)
                    / (2.0 * h);
                assert!((fd - rj).abs() < 1e-7 * rmax, "{kind:?} {m:?} dof {j}: {fd} vs {rj}");
            }
            assert!((&k - k.transpose()).amax() <= 1e-12 * k.amax());
        }
    }
}

/// The converged `α` (and so `R*`) does not depend on the starting guess: from `α = 0` and
/// from a poor guess (`0.05` in every mode) they agree to 1e-10 (Neo-Hooke: several local
/// Newton steps).
#[test]
fn the_result_does_not_depend_on_the_starting_alpha() {
    let m = materials(0.3)[1];
    let geo = Hex8Geometry::new(Hex8Kind::Hex8Eas, &X).unwrap();
    let (mut a0, mut a1) = ([0.0; EAS_COUNT], [0.05; EAS_COUNT]);
    let (mut r0, mut r1) = ([0.0; 24], [0.0; 24]);
    hex8_residual_tangent_with(Hex8Kind::Hex8Eas, &m, &geo, &U_LARGE, &mut a0, &mut r0, None).unwrap();
    hex8_residual_tangent_with(Hex8Kind::Hex8Eas, &m, &geo, &U_LARGE, &mut a1, &mut r1, None).unwrap();
    let rmax = r0.iter().fold(0.0f64, |a, b| a.max(b.abs()));
    assert!(a0.iter().zip(&a1).all(|(x, y)| (x - y).abs() < 1e-10));
    assert!(r0.iter().zip(&r1).all(|(x, y)| (x - y).abs() < 1e-10 * rmax));
}

/// The reference tangent of the distorted element has exactly six zero eigenvalues (rigid
/// translations and rotations: `|λ| ≤ 1e-10 λ_max`) and 18 clearly positive ones
/// (`λ ≥ 1e-3 λ_max`: no spurious zero-energy mode), for both kinds (measured: zeros
/// ≤ 1.6e-16, λ₇ = 0.030 λ_max with EAS, 0.036 plain). Reference: the six rigid modes of a
/// free 3D body.
#[test]
fn the_reference_tangent_has_exactly_the_six_rigid_body_modes() {
    let m = materials(0.3)[1];
    for kind in KINDS {
        let (_, _, k, _) = eval(kind, &m, &[[0.0; 3]; 8]);
        let mut ev: Vec<f64> = k.symmetric_eigen().eigenvalues.iter().copied().collect();
        ev.sort_by(f64::total_cmp);
        let max = ev[23];
        println!(
            "{kind:?}: |λ_1..6|/λmax ≤ {:.2e}, λ_7/λmax = {:.3e}, λmax = {max:.4e}",
            ev[..6].iter().fold(0.0f64, |a, b| a.max(b.abs())) / max,
            ev[6] / max
        );
        assert!(ev[..6].iter().all(|v| v.abs() <= 1e-10 * max), "{ev:?}");
        assert!(ev[6] >= 1e-3 * max, "{ev:?}");
    }
}

/// A rotation of the nodes about `axis` by `angle` (radians), as displacements.
pub(super) fn rotated(x: &[[f64; 3]; 8], q: &Rotation3<f64>, shift: [f64; 3]) -> [[f64; 3]; 8] {
    std::array::from_fn(|i| {
        let p = q * nalgebra::Vector3::from(x[i]);
        [
            p[0] + shift[0] - x[i][0],
            p[1] + shift[1] - x[i][1],
            p[2] + shift[2] - x[i][2],
        ]
    })
}

/// A finite rigid motion (90° about `(1, 2, 2)/3` plus a translation, and 180° about `z`)
/// gives zero residual and energy to round-off (`|R*| ≤ 1e-11 E V^⅔`, measured ≤ 5e-16)
/// and `α = 0` (≤ 1e-13) from a non-zero starting guess, both kinds and materials.
#[test]
fn a_finite_rigid_rotation_is_stress_free() {
    let motions = [
        (
            Rotation3::from_axis_angle(
                &Unit::new_normalize([1.0, 2.0, 2.0].into()),
                std::f64::consts::FRAC_PI_2,
            ),
            [0.3, -2.0, 1.0],
        ),
        (
            Rotation3::from_axis_angle(&nalgebra::Vector3::z_axis(), std::f64::consts::PI),
            [0.0; 3],
        ),
    ];
    for (q, shift) in motions {
        let u = rotated(&X, &q, shift);
        for m in materials(0.3) {
            for kind in KINDS {
                let geo = Hex8Geometry::new(kind, &X).unwrap();
                let (mut a, mut r) = ([3e-3; EAS_COUNT], [0.0; 24]);
                let e = hex8_residual_tangent_with(kind, &m, &geo, &u, &mut a, &mut r, None).unwrap();
                let scale = YOUNG * geo.volume().powf(2.0 / 3.0);
                let rn = r.iter().map(|v| v * v).sum::<f64>().sqrt() / scale;
                println!("{kind:?} {m:?}: |R|/(E V^2/3) = {rn:.2e}, energy {e:.2e}");
                assert!(
                    rn <= 1e-11 && e.abs() <= 1e-11 * scale,
                    "{kind:?} {m:?}: {rn:.2e} {e:.2e}"
                );
                if kind == Hex8Kind::Hex8Eas {
                    assert!(a.iter().all(|v| v.abs() <= 1e-13), "{a:?}");
                }
            }
        }
    }
}

/// Objectivity: superposing a rotation `Q` on a deformed configuration leaves the energy
/// unchanged and rotates the nodal forces, `R*(Qx) = Q R*(x)` node by node, and the tangent,
/// `K* → Q K* Qᵀ` block by block. Tolerance 1e-10 relative.
#[test]
fn residual_and_tangent_are_objective() {
    let q = Rotation3::from_euler_angles(0.4, -1.1, 2.3);
    let big = nalgebra::DMatrix::from_fn(24, 24, |i, j| if i / 3 == j / 3 { q[(i % 3, j % 3)] } else { 0.0 });
    let deformed: [[f64; 3]; 8] = std::array::from_fn(|i| std::array::from_fn(|c| X[i][c] + U_LARGE[i][c]));
    let u1 = {
        let moved = rotated(&deformed, &q, [0.0; 3]);
        std::array::from_fn(|i| std::array::from_fn(|c| deformed[i][c] + moved[i][c] - X[i][c]))
    };
    for m in materials(0.3) {
        for kind in KINDS {
            let (e0, r0, k0, _) = eval(kind, &m, &U_LARGE);
            let (e1, r1, k1, _) = eval(kind, &m, &u1);
            let r0 = nalgebra::DVector::from_row_slice(&r0);
            let r1 = nalgebra::DVector::from_row_slice(&r1);
            assert!((e0 - e1).abs() <= 1e-10 * e0.abs());
            assert!((&big * &r0 - r1).amax() <= 1e-10 * r0.amax());
            assert!((&big * &k0 * big.transpose() - k1).amax() <= 1e-10 * k0.amax());
        }
    }
}

/// Inverted and degenerate states are typed errors, never a panic or a NaN: a mirrored
/// (wrongly ordered) reference element and a flat one (`BadGeometry`), a non-finite
/// coordinate (`BadGeometry`), a mirror image as deformation (`F = diag(−1, 1, 1)`, strain
/// free: `Inverted(−1)`), a corner pushed through the opposite face (`Inverted`), and a NaN
/// displacement (`Inverted(NaN)`).
#[test]
fn inverted_and_degenerate_states_are_typed_errors() {
    let m = materials(0.3)[1];
    let mut mirrored = X;
    mirrored.swap(1, 3);
    mirrored.swap(5, 7);
    let flat = X.map(|p| [p[0], p[1], 0.0]);
    let mut nan_x = X;
    nan_x[6][2] = f64::NAN;
    for x in [mirrored, flat, nan_x] {
        for kind in KINDS {
            let (mut a, mut r) = ([0.0; EAS_COUNT], [0.0; 24]);
            let e = hex8_residual_tangent(kind, &m, &x, &[[0.0; 3]; 8], &mut a, &mut r, None);
            assert!(matches!(e, Err(Hex8Error::BadGeometry(_))), "{kind:?}: {e:?}");
        }
    }
    let mirror_u = X.map(|p| [-2.0 * p[0], 0.0, 0.0]);
    let mut pushed = [[0.0; 3]; 8];
    pushed[6] = [-1.5, -1.5, -1.5];
    let mut nan_u = [[0.0; 3]; 8];
    nan_u[2][1] = f64::NAN;
    for kind in KINDS {
        for m in materials(0.3) {
            for (u, want_negative) in [(mirror_u, true), (pushed, true), (nan_u, false)] {
                let (mut a, mut r, mut k) = ([0.0; EAS_COUNT], [0.0; 24], [0.0; 576]);
                let e = hex8_residual_tangent(kind, &m, &X, &u, &mut a, &mut r, Some(&mut k));
                let ok = match e {
                    Err(Hex8Error::Inverted(d)) => (d < 0.0) == want_negative && (d.is_nan() != want_negative),
                    _ => false,
                };
                assert!(ok, "{kind:?} {m:?}: {e:?}");
            }
        }
    }
}

/// The hourglass holds: a thin element (0.1 × 1.2 × 1.2) compressed by 1 % across its short
/// side (`ξ`) holds exactly the two shear modes that free its zig-zags across that side
/// (`α₅`: `η` in `2ξη`, `α₉`: `ζ` in `2ξζ`; critical compression `(0.1/1.2)² = 0.7 %`, so
/// `x = 1.44`, `p = 40 (1.44 − 0.05)² K⁰ ≈ 77 K⁰`), no others; a rigid rotation of the same
/// state gives the same holds (1e-12), and with the holds set the tangent still matches
/// finite differences (1e-7, as without) and the patch state `α = 0` is kept.
#[test]
fn hourglass_holds_follow_compression_across_the_short_side() {
    let thin: [[f64; 3]; 8] = HEX8_NODES.map(|n| [0.05 * (n[0] + 1.0), 0.6 * (n[1] + 1.0), 0.6 * (n[2] + 1.0)]);
    let hg = [1.0, -1.0, 1.0, -1.0, -1.0, 1.0, -1.0, 1.0];
    let u: [[f64; 3]; 8] = std::array::from_fn(|i| [-0.01 * thin[i][0], 1e-4 * hg[i], 0.0]);
    for m in materials(0.3) {
        let mut geo = Hex8Geometry::new(Hex8Kind::Hex8Eas, &thin).unwrap();
        let holds = hex8_hourglass_holds(&geo, &m, &u);
        let expect = HOLD_GROWTH * (0.01 * 144.0 - HOLD_FROM).powi(2);
        for (mode, p) in holds.iter().enumerate() {
            let k0 = geo.mode_stiffness(&m, mode);
            if mode == 4 || mode == 8 {
                assert!((p / k0 - expect).abs() < 0.02 * expect, "mode {mode}: {} K⁰", p / k0);
            } else {
                assert_eq!(*p, 0.0, "mode {mode}: {holds:?}");
            }
        }
        let q = Rotation3::from_euler_angles(0.3, 0.2, -0.7);
        let moved: [[f64; 3]; 8] = std::array::from_fn(|i| std::array::from_fn(|c| thin[i][c] + u[i][c]));
        let u_rot: [[f64; 3]; 8] = std::array::from_fn(|i| {
            let d = rotated(&moved, &q, [0.0; 3]);
            std::array::from_fn(|c| u[i][c] + d[i][c])
        });
        let holds_rot = hex8_hourglass_holds(&geo, &m, &u_rot);
        assert!(holds
            .iter()
            .zip(&holds_rot)
            .all(|(a, b)| (a - b).abs() <= 1e-12 * a.abs().max(1.0)));
        geo.set_alpha_penalty(holds);
        let err = tangent_fd_error(Hex8Kind::Hex8Eas, &m, &geo, &u, 1e-8);
        assert!(err < 1e-7, "{m:?}: {err:.2e}");
        let homogeneous = thin.map(|p| [-0.01 * p[0], 0.02 * p[2], 0.0]);
        let (_, _, _, al) = eval_geo(Hex8Kind::Hex8Eas, &m, &geo, &homogeneous);
        assert!(al.iter().all(|a| a.abs() < 1e-13), "{al:?}");
    }
}
