use super::*;
use crate::element::material::lame;
use proptest::prelude::*;

const X: [[f64; 2]; 4] = [[0.0, 0.0], [1.3, 0.1], [1.1, 0.9], [-0.1, 0.7]];

fn materials() -> [Material; 2] {
    let (l, m) = lame(2.1e4, 0.3);
    [
        Material::SaintVenantKirchhoff { lambda: l, mu: m },
        Material::NeoHookean { lambda: l, mu: m },
    ]
}

fn eval(kind: ElementKind, m: &Material, u: &[[f64; 2]; 4]) -> ([f64; 8], [f64; 64]) {
    let mut a = [0.0; 4];
    let mut r = [0.0; 8];
    let mut k = [0.0; 64];
    quad_residual_tangent(kind, m, &X, u, &mut a, &mut r, Some(&mut k)).unwrap();
    (r, k)
}

fn fd_check(kind: ElementKind, m: &Material, u: [[f64; 2]; 4]) {
    let (_, k) = eval(kind, m, &u);
    let h = 1e-6;
    let kmax = k.iter().fold(0.0f64, |a, b| a.max(b.abs()));
    for j in 0..8 {
        let mut up = u;
        let mut um = u;
        up[j / 2][j % 2] += h;
        um[j / 2][j % 2] -= h;
        let (rp, _) = eval(kind, m, &up);
        let (rm, _) = eval(kind, m, &um);
        for i in 0..8 {
            let fd = (rp[i] - rm[i]) / (2.0 * h);
            assert!(
                (fd - k[8 * i + j]).abs() < 1e-8 * kmax,
                "{kind:?} {m:?}: K[{i},{j}] = {} vs FD {fd}",
                k[8 * i + j]
            );
        }
    }
}

const U_LARGE: [[f64; 2]; 4] = [[0.0, 0.0], [0.12, 0.05], [0.02, 0.21], [-0.08, 0.03]];

#[test]
fn tangent_matches_finite_differences_for_every_kind_and_material() {
    for m in materials() {
        for kind in [
            ElementKind::Q4,
            ElementKind::Q4Eas,
            ElementKind::Q4EasStab,
            ElementKind::Q4EasSafe,
        ] {
            fd_check(kind, &m, U_LARGE);
            fd_check(kind, &m, [[0.0; 2]; 4]);
        }
    }
}

#[test]
fn residual_is_energy_gradient() {
    // R* = dΠ/du for the condensed element (α solved for each u).
    for m in materials() {
        let kind = ElementKind::Q4Eas;
        let (r, _) = eval(kind, &m, &U_LARGE);
        let h = 1e-6;
        for j in 0..8 {
            let mut up = U_LARGE;
            let mut um = U_LARGE;
            up[j / 2][j % 2] += h;
            um[j / 2][j % 2] -= h;
            let en = |u: &[[f64; 2]; 4]| {
                let mut a = [0.0; 4];
                let mut rr = [0.0; 8];
                quad_residual_tangent(kind, &m, &X, u, &mut a, &mut rr, None).unwrap()
            };
            let fd = (en(&up) - en(&um)) / (2.0 * h);
            assert!(
                (fd - r[j]).abs() < 1e-5 * (1.0 + r[j].abs()),
                "dof {j}: {fd} vs {}",
                r[j]
            );
        }
    }
}

#[test]
fn inverted_reference_element_is_rejected() {
    let x = [X[0], X[3], X[2], X[1]]; // clockwise
    let mut a = [0.0; 4];
    let mut r = [0.0; 8];
    let m = materials()[0];
    let e = quad_residual_tangent(ElementKind::Q4Eas, &m, &x, &[[0.0; 2]; 4], &mut a, &mut r, None);
    assert!(matches!(e, Err(ElementError::BadGeometry(_))));
}

#[test]
fn a_folded_element_is_rejected_although_its_strain_is_admissible() {
    // mirrored (x → −x): F = diag(−1, 1) everywhere, C = I: no strain, det F = −1; and
    // folded over one corner: det F < 0 at some Gauss points only
    let mirrored = X.map(|p| [-2.0 * p[0], 0.0]);
    let folded = [[0.0; 2], [0.0; 2], [-1.6, -1.6], [0.0; 2]];
    for kind in [
        ElementKind::Q4,
        ElementKind::Q4Eas,
        ElementKind::Q4EasStab,
        ElementKind::Q4EasSafe,
    ] {
        for m in materials() {
            for u in [mirrored, folded] {
                let mut a = [0.0; 4];
                let mut r = [0.0; 8];
                let e = quad_residual_tangent(kind, &m, &X, &u, &mut a, &mut r, None);
                assert!(
                    matches!(e, Err(ElementError::Inverted(d)) if d < 0.0),
                    "{kind:?} {m:?}: {e:?}"
                );
            }
        }
    }
}

proptest! {
    /// Rigid motion (any rotation and translation) produces no internal force and no
    /// enhanced strain, for both materials and both formulations.
    #[test]
    fn rigid_motion_is_stress_free(theta in -3.1f64..3.1, tx in -5.0f64..5.0, ty in -5.0f64..5.0) {
        let (c, s) = (theta.cos(), theta.sin());
        let mut u = [[0.0; 2]; 4];
        for i in 0..4 {
            let (x, y) = (X[i][0], X[i][1]);
            u[i] = [c * x - s * y + tx - x, s * x + c * y + ty - y];
        }
        for m in materials() {
            for kind in [ElementKind::Q4, ElementKind::Q4Eas, ElementKind::Q4EasStab, ElementKind::Q4EasSafe] {
                let mut a = [3e-3, -2e-3, 1e-3, 5e-4];
                let mut r = [0.0; 8];
                quad_residual_tangent(kind, &m, &X, &u, &mut a, &mut r, None).unwrap();
                let n = r.iter().map(|v| v * v).sum::<f64>().sqrt();
                prop_assert!(n < 1e-8, "{:?} {:?}: |R| = {}", kind, m, n);
                if kind == ElementKind::Q4Eas {
                    prop_assert!(a.iter().all(|v| v.abs() < 1e-10));
                }
            }
        }
    }

    /// Frame independence: rotating a deformed configuration rotates the internal forces.
    #[test]
    fn internal_force_is_objective(theta in -3.1f64..3.1) {
        let (c, s) = (theta.cos(), theta.sin());
        for m in materials() {
            let (r0, _) = eval(ElementKind::Q4Eas, &m, &U_LARGE);
            let mut u = [[0.0; 2]; 4];
            for i in 0..4 {
                let (x, y) = (X[i][0] + U_LARGE[i][0], X[i][1] + U_LARGE[i][1]);
                u[i] = [c * x - s * y - X[i][0], s * x + c * y - X[i][1]];
            }
            let (r1, _) = eval(ElementKind::Q4Eas, &m, &u);
            for i in 0..4 {
                let rx = c * r0[2 * i] - s * r0[2 * i + 1];
                let ry = s * r0[2 * i] + c * r0[2 * i + 1];
                prop_assert!((rx - r1[2 * i]).abs() < 1e-7 * (1.0 + rx.abs()));
                prop_assert!((ry - r1[2 * i + 1]).abs() < 1e-7 * (1.0 + ry.abs()));
            }
        }
    }
}

#[test]
fn closed_form_alpha_agrees_with_the_local_newton_path() {
    // St. Venant–Kirchhoff: the geometry made for the material takes α(u) in closed form;
    // the plain geometry (and any other material) iterates on R_α. Same element to round-off.
    let m = materials()[0];
    for kind in [ElementKind::Q4Eas, ElementKind::Q4EasStab, ElementKind::Q4EasSafe] {
        let fitted = QuadGeometry::for_material(kind, &m, &X).unwrap();
        // the same geometry (shear-mode penalty included) without the closed form
        let mut plain = fitted;
        plain.linear = None;
        assert!(fitted.linear.is_some());
        for u in [
            U_LARGE,
            [[0.0; 2]; 4],
            [[0.0, 0.0], [-0.2, 0.1], [0.05, -0.3], [0.1, 0.02]],
        ] {
            let (mut ap, mut af) = ([0.3, -0.1, 0.2, 0.05], [9.0; 4]);
            let (mut rp, mut rf) = ([0.0; 8], [0.0; 8]);
            let (mut kp, mut kf) = ([0.0; 64], [0.0; 64]);
            let ep = quad_residual_tangent_with(kind, &m, &plain, &u, &mut ap, &mut rp, Some(&mut kp)).unwrap();
            let ef = quad_residual_tangent_with(kind, &m, &fitted, &u, &mut af, &mut rf, Some(&mut kf)).unwrap();
            let scale = kp.iter().fold(0.0f64, |a, b| a.max(b.abs()));
            for (a, b) in rp.iter().zip(&rf).chain(kp.iter().zip(&kf)) {
                assert!((a - b).abs() <= 1e-11 * scale, "{kind:?}: {a} vs {b}");
            }
            assert!((ep - ef).abs() <= 1e-11 * scale.max(ep.abs()));
            for (a, b) in ap.iter().zip(&af) {
                assert!((a - b).abs() <= 1e-10 * (1.0 + a.abs()), "α {a} vs {b}");
            }
        }
    }
    // a geometry fitted to one material is not used for another
    let other = Material::SaintVenantKirchhoff { lambda: 1.0, mu: 1.0 };
    let fitted = QuadGeometry::for_material(ElementKind::Q4Eas, &m, &X).unwrap();
    let plain = QuadGeometry::new(ElementKind::Q4Eas, &X).unwrap();
    let (mut a1, mut a2) = ([0.0; 4], [0.0; 4]);
    let (mut r1, mut r2) = ([0.0; 8], [0.0; 8]);
    quad_residual_tangent_with(ElementKind::Q4Eas, &other, &fitted, &U_LARGE, &mut a1, &mut r1, None).unwrap();
    quad_residual_tangent_with(ElementKind::Q4Eas, &other, &plain, &U_LARGE, &mut a2, &mut r2, None).unwrap();
    assert_eq!(r1, r2);
}

#[test]
fn the_safe_element_tangent_matches_fd_while_it_turns_bilinear_under_compression() {
    // compressed by 10 %, 27 % (inside the blend) and 45 % (bilinear) along x, with shear
    for squeeze in [0.10, 0.27, 0.45] {
        let u: [[f64; 2]; 4] = std::array::from_fn(|i| [-squeeze * X[i][0] + 0.03 * X[i][1], 0.02 * X[i][0]]);
        for m in materials() {
            fd_check(ElementKind::Q4EasSafe, &m, u);
        }
    }
}

#[test]
fn held_hourglass_modes_keep_the_tangent_exact_and_the_closed_form_alpha() {
    // a tall element compressed across its short side: its η shear mode is held
    let tall = [[0.0, 0.0], [0.1, 0.0], [0.1, 1.2], [0.0, 1.2]];
    let hg = [1.0, -1.0, 1.0, -1.0];
    let u: [[f64; 2]; 4] = std::array::from_fn(|i| [-0.01 * tall[i][0], 1e-4 * hg[i]]);
    for m in materials() {
        let mut geo = QuadGeometry::for_material(ElementKind::Q4EasSafe, &m, &tall).unwrap();
        let holds = hourglass_holds(&geo, &m, &u);
        assert!(
            holds[3] > 10.0 * geo.mode_stiffness(&m, 3) && holds[2] == 0.0,
            "{holds:?}"
        );
        geo.set_alpha_penalty(holds, &m);
        let eval_at = |geo: &QuadGeometry, u: &[[f64; 2]; 4]| {
            let (mut a, mut r, mut k) = ([0.0; 4], [0.0; 8], [0.0; 64]);
            let e =
                quad_residual_tangent_with(ElementKind::Q4EasSafe, &m, geo, u, &mut a, &mut r, Some(&mut k)).unwrap();
            (e, r, k)
        };
        let (_, _, k) = eval_at(&geo, &u);
        let kmax = k.iter().fold(0.0f64, |a, b| a.max(b.abs()));
        let h = 1e-8;
        for j in 0..8 {
            let (mut up, mut um) = (u, u);
            up[j / 2][j % 2] += h;
            um[j / 2][j % 2] -= h;
            let ((_, rp, _), (_, rm, _)) = (eval_at(&geo, &up), eval_at(&geo, &um));
            for i in 0..8 {
                let fd = (rp[i] - rm[i]) / (2.0 * h);
                assert!(
                    (fd - k[8 * i + j]).abs() < 1e-6 * kmax,
                    "K[{i},{j}] = {} vs FD {fd}",
                    k[8 * i + j]
                );
            }
        }
        // the same element without the closed form of α (the local Newton iteration)
        let mut plain = geo;
        plain.linear = None;
        let ((e1, r1, _), (e2, r2, _)) = (eval_at(&geo, &u), eval_at(&plain, &u));
        assert!((e1 - e2).abs() <= 1e-10 * e1.abs().max(1e-12));
        assert!(r1.iter().zip(&r2).all(|(a, b)| (a - b).abs() <= 1e-9 * (1.0 + a.abs())));
    }
}

#[test]
fn the_safe_element_is_plain_eas_at_moderate_strain_and_bilinear_under_large_compression() {
    let m = materials()[0];
    let square = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
    let hg = [1.0, -1.0, 1.0, -1.0];
    let resid = |kind, u: &[[f64; 2]; 4]| {
        let (mut a, mut r) = ([0.0; 4], [0.0; 8]);
        quad_residual_tangent(kind, &m, &square, u, &mut a, &mut r, None).unwrap();
        r
    };
    let close = |a: [f64; 8], b: [f64; 8]| a.iter().zip(&b).all(|(x, y)| (x - y).abs() <= 1e-12 * (1.0 + x.abs()));
    let mild: [[f64; 2]; 4] = std::array::from_fn(|i| [-0.1 * square[i][0], 1e-3 * hg[i]]);
    assert!(close(
        resid(ElementKind::Q4Eas, &mild),
        resid(ElementKind::Q4EasSafe, &mild)
    ));
    let hard: [[f64; 2]; 4] = std::array::from_fn(|i| [-0.45 * square[i][0], 1e-3 * hg[i]]);
    assert!(close(
        resid(ElementKind::Q4, &hard),
        resid(ElementKind::Q4EasSafe, &hard)
    ));
}

/// The AVX2 compilation of the kernel (`crate::cpu`) gives the baseline's residual, tangent,
/// enhanced parameters and energy to the last bit, for every kind and material, at rest, in
/// moderate strain and compressed past the safe element's blend.
#[test]
fn the_avx2_kernel_is_the_baselines_to_the_last_bit() {
    if !crate::cpu::wide_vectors() {
        return; // nothing to compare on this processor
    }
    let states: [[[f64; 2]; 4]; 3] = [
        [[0.0; 2]; 4],
        [[0.0, 0.0], [0.12, 0.05], [0.02, 0.21], [-0.08, 0.03]],
        [[0.0, 0.0], [-0.35, 0.02], [-0.33, -0.2], [0.01, -0.22]],
    ];
    let kinds = [
        ElementKind::Q4,
        ElementKind::Q4Eas,
        ElementKind::Q4EasStab,
        ElementKind::Q4EasSafe,
    ];
    for m in &materials() {
        for kind in kinds {
            let geo = QuadGeometry::for_material(kind, m, &X).unwrap();
            for u in &states {
                let run = |wide: bool| {
                    let (mut a, mut r, mut k) = ([0.01, -0.02, 0.0, 0.005], [0.0; 8], [0.0; 64]);
                    let e = if wide {
                        // SAFETY: the processor has AVX2 (checked above)
                        unsafe { residual_tangent_avx2(kind, m, &geo, u, &mut a, &mut r, Some(&mut k)) }
                    } else {
                        residual_tangent(kind, m, &geo, u, &mut a, &mut r, Some(&mut k))
                    };
                    let e = e.unwrap();
                    [vec![e], a.to_vec(), r.to_vec(), k.to_vec()].concat()
                };
                let (wide, base) = (run(true), run(false));
                assert!(
                    wide.iter().zip(&base).all(|(x, y)| x.to_bits() == y.to_bits()),
                    "{kind:?} {m:?} at {u:?}"
                );
            }
        }
    }
}
