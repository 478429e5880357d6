//! Tests of the axisymmetric quadrilaterals (`quad_models.rs`): `x = r`, `y = z`, forces
//! totals over the full circle.

use super::model_mesh::{eigenvalues, eval, fd_errors, linspace, patch, solve, solve_in_steps, Mesh};
use super::*;
use crate::element::material::lame;
use nalgebra::DVector;
use std::f64::consts::PI;

const KINDS: [ElementKind; 4] = [
    ElementKind::Q4,
    ElementKind::Q4Eas,
    ElementKind::Q4EasStab,
    ElementKind::Q4EasSafe,
];

fn materials(young: f64, poisson: f64) -> [Material; 2] {
    let (l, m) = lame(young, poisson);
    [
        Material::SaintVenantKirchhoff { lambda: l, mu: m },
        Material::NeoHookean { lambda: l, mu: m },
    ]
}

/// A distorted element off the axis (r ∈ [0.2, 1.6]) and one with two nodes on it.
const X_OFF: [[f64; 2]; 4] = [[0.3, 0.0], [1.6, 0.1], [1.4, 0.9], [0.2, 0.7]];
const X_AXIS: [[f64; 2]; 4] = [[0.0, 0.0], [1.0, 0.1], [0.9, 0.8], [0.0, 0.7]];
const U_LARGE: [[f64; 2]; 4] = [[0.0, 0.0], [0.12, 0.05], [0.02, 0.21], [-0.08, 0.03]];

/// The tangent is the derivative of the residual and the residual that of the energy
/// (central differences, h = 1e-6): every kind × St. Venant–Kirchhoff and Neo-Hooke
/// (E = 2.1e4, ν = 0.3), at rest and at a finite deformation (strains up to ≈ 20 %), off
/// the axis and on it; tolerance 1e-7 of `max |K|` (measured: 1.0e-10 and 3.9e-11).
#[test]
fn tangent_and_residual_match_finite_differences() {
    let mut worst = (0.0f64, 0.0f64);
    for m in materials(2.1e4, 0.3) {
        for kind in KINDS {
            for x in [X_OFF, X_AXIS] {
                let geo = QuadGeometry::with_kinematics(kind, &m, Kinematics::Axisymmetric, &x).unwrap();
                for u in [U_LARGE, [[0.0; 2]; 4]] {
                    let (ek, er) = fd_errors(kind, &m, &geo, u);
                    assert!(ek < 1e-7 && er < 1e-7, "{kind:?} {m:?}: {ek:.2e} {er:.2e}");
                    worst = (worst.0.max(ek), worst.1.max(er));
                }
            }
        }
    }
    eprintln!("axisymmetric FD: tangent {:.1e}, residual {:.1e}", worst.0, worst.1);
}

/// A body of revolution has one rigid motion in its plane, the axial translation: the
/// tangent at rest has exactly one zero eigenvalue (≤ 1e-12 of the largest; the next one
/// above 1e-4 of it) for the bilinear and the EAS element, and the axial translation
/// leaves the element free of force (1e-12) while a radial one (hoop strain) does not.
#[test]
fn the_axial_translation_is_the_only_zero_energy_mode() {
    let m = materials(2.1e4, 0.3)[0];
    for kind in [ElementKind::Q4, ElementKind::Q4Eas] {
        for x in [X_OFF, X_AXIS] {
            let geo = QuadGeometry::with_kinematics(kind, &m, Kinematics::Axisymmetric, &x).unwrap();
            let (_, k, _) = eval(kind, &m, &geo, &[[0.0; 2]; 4]);
            let ev = eigenvalues(&k);
            let top = ev[7];
            assert!(ev[0].abs() <= 1e-12 * top && ev[1] > 1e-4 * top, "{kind:?}: {ev:?}");
            let (r, _, _) = eval(kind, &m, &geo, &[[0.0, 0.3]; 4]);
            assert!(r.iter().all(|v| v.abs() < 1e-12 * top));
            let (r, _, _) = eval(kind, &m, &geo, &[[0.01, 0.0]; 4]);
            assert!(r.iter().any(|v| v.abs() > 1e-4 * top));
        }
    }
}

/// The axisymmetric patch test: the linear radial field `u_r = a r`, `u_z = b z` is a
/// homogeneous deformation `F = diag(1 + a, 1 + b, 1 + a)` whose constant stress
/// (`S_rr = S_θθ`) is in equilibrium without body force (`∂P_rr/∂R + (P_rr − P_θθ)/R = 0`),
/// the constant-strain state of an axisymmetric element (Zienkiewicz & Taylor, *The Finite
/// Element Method*, vol. 1, §9.4; the patch of MacNeal & Harder 1985). With the boundary
/// nodes prescribed, the interior nodes of the distorted patch must follow it exactly
/// (to 1e-10 of the displacement), off the axis and touching it (`r ∈ [0, 0.24]`, where
/// `u_r = 0` on the axis follows from the field), at small (1e-3) and finite (0.2, −0.1)
/// strain, every kind and both materials.
#[test]
fn the_linear_radial_field_passes_the_patch_test() {
    for dx in [0.0, 0.1] {
        let mesh = patch(dx);
        for (a, b) in [(1e-3, -4e-4), (0.2, -0.1)] {
            let exact = |p: &[f64; 2]| [a * p[0], b * p[1]];
            let fixed: Vec<(usize, f64)> = (0..4)
                .flat_map(|i| {
                    let e = exact(&mesh.nodes[i]);
                    [(2 * i, e[0]), (2 * i + 1, e[1])]
                })
                .collect();
            for m in materials(2.1e4, 0.3) {
                for kind in KINDS {
                    let f = DVector::zeros(16);
                    let (u, _) = solve_in_steps(&mesh, kind, &m, Kinematics::Axisymmetric, &fixed, &f, 4);
                    for i in 4..8 {
                        let e = exact(&mesh.nodes[i]);
                        let err = (u[2 * i] - e[0]).abs().max((u[2 * i + 1] - e[1]).abs());
                        assert!(err <= 1e-10 * a.abs(), "{kind:?} {m:?} dx {dx} a {a}: {err:.2e}");
                    }
                }
            }
        }
    }
}

/// Reactions are totals over the circle: a hollow cylinder (r ∈ [0.5, 1.5], height 1,
/// interior nodes displaced) stretched axially by `u_z = 0.1 z` (ends held axially, free
/// radially) is in homogeneous uniaxial tension; for St. Venant–Kirchhoff
/// `E_rr = E_θθ = −ν E_zz`, `S_zz = E E_zz`, and the axial reaction on the top is
/// `(1 + b) S_zz π (r_o² − r_i²)` — the first Piola–Kirchhoff stress times the area of the
/// annulus — to 1e-10 (per radian: that over 2π).
#[test]
fn the_reactions_are_totals_over_the_circle() {
    let (young, nu, b) = (2.1e4, 0.3, 0.1);
    let m = materials(young, nu)[0];
    let mut mesh = Mesh::grid(&linspace(0.5, 1.5, 3), &linspace(0.0, 1.0, 2));
    mesh.nodes[5] = [0.9, 0.55];
    mesh.nodes[6] = [1.2, 0.45];
    let (top, bottom): (Vec<usize>, Vec<usize>) = ((8..12).collect(), (0..4).collect());
    let mut fixed: Vec<(usize, f64)> = bottom.iter().map(|&i| (2 * i + 1, 0.0)).collect();
    fixed.extend(top.iter().map(|&i| (2 * i + 1, b)));
    let ezz = b + 0.5 * b * b;
    let total = (1.0 + b) * young * ezz * PI * (1.5f64 * 1.5 - 0.5 * 0.5);
    let a = (1.0 - 2.0 * nu * ezz).sqrt() - 1.0;
    for kind in [ElementKind::Q4, ElementKind::Q4Eas] {
        let (u, reactions) = solve(&mesh, kind, &m, Kinematics::Axisymmetric, &fixed, &DVector::zeros(24));
        let fz: f64 = top.iter().map(|&i| reactions[2 * i + 1]).sum();
        assert!((fz - total).abs() <= 1e-10 * total, "{kind:?}: {fz} vs {total}");
        assert!(((fz / (2.0 * PI)) - total / (2.0 * PI)).abs() <= 1e-10 * total);
        for (i, p) in mesh.nodes.iter().enumerate() {
            assert!((u[2 * i] - a * p[0]).abs() <= 1e-10 * a.abs(), "{kind:?}: node {i}");
        }
    }
}

/// Lamé's thick cylinder in plane strain (`u_z = 0`), inner radius `a = 1`, outer `b = 2`,
/// internal pressure `p` (E = 1000, p = 1e-3: strains ≈ 1e-6, so the geometric
/// nonlinearity is ≈ 1e-6 of the answer); a strip of `n` equal elements along `r`, one
/// of height 0.1 along `z`, the pressure as nodal forces `p 2π a h / 2` on the two inner
/// nodes (totals). Exact (Timoshenko & Goodier, *Theory of Elasticity*, §28):
/// `u_r(r) = (1 + ν) p a² / (E (b² − a²)) ((1 − 2ν) r + b²/r)`. Returns the relative error
/// of `u_r(a)`.
fn lame_error(kind: ElementKind, nu: f64, n: usize) -> f64 {
    let (young, p, a, b, h) = (1000.0, 1e-3, 1.0, 2.0, 0.1);
    let m = materials(young, nu)[1];
    let mesh = Mesh::grid(&linspace(a, b, n), &[0.0, h]);
    let fixed: Vec<(usize, f64)> = (0..mesh.nodes.len()).map(|i| (2 * i + 1, 0.0)).collect();
    let mut f = DVector::zeros(2 * mesh.nodes.len());
    let (i0, i1) = (mesh.node_at([a, 0.0]), mesh.node_at([a, h]));
    f[2 * i0] = p * 2.0 * PI * a * h / 2.0;
    f[2 * i1] = f[2 * i0];
    let (u, _) = solve(&mesh, kind, &m, Kinematics::Axisymmetric, &fixed, &f);
    let exact = (1.0 + nu) * p * a * a / (young * (b * b - a * a)) * ((1.0 - 2.0 * nu) * a + b * b / a);
    (u[2 * i0] - exact).abs() / exact
}

/// Lamé (see [`lame_error`]), ν = 0.3, Neo-Hooke: the EAS element within 0.1 % on 16
/// elements, converging at second order (error ratio between 3.5 and 4.5 per halving, from
/// 4 to 32 elements; measured 0.81 %, 0.21 %, 0.053 %, 0.013 %); the bilinear element
/// within 0.1 % on 16 too (no locking at ν = 0.3).
#[test]
fn lame_cylinder_under_internal_pressure() {
    let errs: Vec<f64> = [4, 8, 16, 32]
        .iter()
        .map(|&n| lame_error(ElementKind::Q4Eas, 0.3, n))
        .collect();
    eprintln!("Lamé ν = 0.3, Q4Eas, n = 4, 8, 16, 32: {errs:?}");
    assert!(errs[2] < 1e-3, "{errs:?}");
    for w in errs.windows(2) {
        assert!((3.5..4.5).contains(&(w[0] / w[1])), "{errs:?}");
    }
    let q4 = lame_error(ElementKind::Q4, 0.3, 16);
    eprintln!("Lamé ν = 0.3, Q4, n = 16: {q4:.3e}");
    assert!(q4 < 1e-3);
}

/// Lamé (see [`lame_error`]) nearly incompressible, ν = 0.4999, 8 elements: the EAS
/// element does not lock (within 0.5 %), the bilinear element does (more than 20 % too
/// stiff).
#[test]
fn nearly_incompressible_lame_cylinder_does_not_lock_with_eas() {
    let eas = lame_error(ElementKind::Q4Eas, 0.4999, 8);
    let q4 = lame_error(ElementKind::Q4, 0.4999, 8);
    let safe = lame_error(ElementKind::Q4EasSafe, 0.4999, 8);
    eprintln!("Lamé ν = 0.4999, n = 8: Q4Eas {eas:.3e}, Q4EasSafe {safe:.3e}, Q4 {q4:.3e}");
    assert!(eas < 5e-3 && safe < 5e-3, "{eas} {safe}");
    assert!(q4 > 0.2, "{q4}");
}
