//! The elements' stability check on one element: quadrilaterals (rest, stretch, the tall EAS
//! element compressed across its short side, the Cholesky screen against the eigenvalues)
//! and their hexahedral counterparts (`element_check.rs`).

use super::*;
use crate::element::material::{lame, Material};
use crate::element::quad::{
    hourglass_holds, quad_residual_tangent, quad_residual_tangent_with, ElementKind, QuadGeometry,
};

#[test]
fn an_element_at_rest_and_a_stretched_one_are_stable() {
    let (l, m) = lame(1e3, 0.3);
    let mat = Material::NeoHookean { lambda: l, mu: m };
    let x = [[0.0, 0.0], [1.0, 0.0], [1.0, 0.5], [0.0, 0.5]];
    for u in [[[0.0; 2]; 4], [[0.0, 0.0], [0.1, 0.0], [0.1, 0.01], [0.0, 0.01]]] {
        let (mut a, mut r, mut k) = ([0.0; 4], [0.0; 8], [0.0; 64]);
        quad_residual_tangent(ElementKind::Q4Eas, &mat, &x, &u, &mut a, &mut r, Some(&mut k)).unwrap();
        let cur: [[f64; 2]; 4] = std::array::from_fn(|i| [x[i][0] + u[i][0], x[i][1] + u[i][1]]);
        let ratio = smallest_deformation_eigenvalue(&k, &cur).unwrap();
        assert!(ratio > 0.0, "{ratio}");
    }
}

#[test]
fn a_tall_eas_element_compressed_across_its_short_side_is_unstable_and_the_safe_one_is_not() {
    // 12 times taller than long, compressed by 5 % along x: beyond (a/b)² ≈ 0.7 %
    let (l, m) = lame(2.1e4, 0.3);
    let mat = Material::NeoHookean { lambda: l, mu: m };
    let x = [[0.0, 0.0], [0.1, 0.0], [0.1, 1.2], [0.0, 1.2]];
    let u: [[f64; 2]; 4] = std::array::from_fn(|i| [-0.05 * x[i][0], 0.0]);
    let cur: [[f64; 2]; 4] = std::array::from_fn(|i| [x[i][0] + u[i][0], x[i][1]]);
    let ratio = |kind| {
        let (mut a, mut r, mut k) = ([0.0; 4], [0.0; 8], [0.0; 64]);
        let mut geo = QuadGeometry::for_material(kind, &mat, &x).unwrap();
        if kind == ElementKind::Q4EasSafe {
            // held from the converged state (as the assembler does after each increment)
            geo.set_alpha_penalty(hourglass_holds(&geo, &mat, &u), &mat);
        }
        quad_residual_tangent_with(kind, &mat, &geo, &u, &mut a, &mut r, Some(&mut k)).unwrap();
        smallest_deformation_eigenvalue(&k, &cur).unwrap()
    };
    assert!(
        ratio(ElementKind::Q4Eas) < -UNSTABLE_RATIO,
        "{}",
        ratio(ElementKind::Q4Eas)
    );
    assert!(ratio(ElementKind::Q4EasSafe) > 0.0, "{}", ratio(ElementKind::Q4EasSafe));
}

/// The Cholesky screen never calls an element stable that the eigenvalues call unstable,
/// and passes the stable ones that are not near the threshold: tall and square elements
/// of both kinds compressed from 0 to 30 % across and sheared.
#[test]
fn the_cholesky_screen_agrees_with_the_eigenvalues() {
    let (l, m) = lame(2.1e4, 0.3);
    let mat = Material::NeoHookean { lambda: l, mu: m };
    let (mut passed, mut unstable) = (0, 0);
    for height in [0.1, 0.5, 1.2] {
        let x = [[0.0, 0.0], [0.1, 0.0], [0.1, height], [0.0, height]];
        for step in 0..=30 {
            let (c, g) = (0.01 * f64::from(step), 0.002 * f64::from(step));
            let u: [[f64; 2]; 4] = std::array::from_fn(|i| [-c * x[i][0] + g * x[i][1], 0.0]);
            let cur: [[f64; 2]; 4] = std::array::from_fn(|i| [x[i][0] + u[i][0], x[i][1] + u[i][1]]);
            for kind in [ElementKind::Q4Eas, ElementKind::Q4] {
                let (mut a, mut r, mut k) = ([0.0; 4], [0.0; 8], [0.0; 64]);
                quad_residual_tangent(kind, &mat, &x, &u, &mut a, &mut r, Some(&mut k)).unwrap();
                let ratio = smallest_deformation_eigenvalue(&k, &cur).unwrap();
                let screened = certainly_stable(&k, &cur);
                assert!(
                    !(screened && ratio < -UNSTABLE_RATIO),
                    "{height} {step} {kind:?}: {ratio}"
                );
                if ratio > 1e-6 {
                    assert!(screened, "{height} {step} {kind:?}: {ratio} not screened");
                }
                passed += usize::from(screened);
                unstable += usize::from(ratio < -UNSTABLE_RATIO);
            }
        }
    }
    assert!(passed > 50 && unstable > 5, "{passed} screened, {unstable} unstable");
}

/// Hexahedron helpers: the nodes of a box `a × b × c` (Gmsh/VTK order) and the ratio of an
/// element `kind` at `u`, with the holds of the converged state when `hold`.
mod hex {
    use super::super::*;
    use crate::element::hex8::{
        hex8_hourglass_holds, hex8_residual_tangent_with, Hex8Geometry, Hex8Kind, EAS_COUNT, HEX8_NODES,
    };
    use crate::element::material::Material;

    pub fn brick(size: [f64; 3]) -> [[f64; 3]; 8] {
        HEX8_NODES.map(|n| std::array::from_fn(|c| 0.5 * size[c] * (n[c] + 1.0)))
    }

    /// `(λ_min/λ_max, screened)` of the element's tangent at `u`.
    pub fn ratio(kind: Hex8Kind, hold: bool, mat: &Material, x: &[[f64; 3]; 8], u: &[[f64; 3]; 8]) -> (f64, bool) {
        let mut geo = Hex8Geometry::new(kind, x).unwrap();
        if hold {
            // held from the converged state (as the assembler does after each increment)
            geo.set_alpha_penalty(hex8_hourglass_holds(&geo, mat, u));
        }
        let (mut a, mut r, mut k) = ([0.0; EAS_COUNT], [0.0; 24], [0.0; 576]);
        hex8_residual_tangent_with(kind, mat, &geo, u, &mut a, &mut r, Some(&mut k)).unwrap();
        let cur: [[f64; 3]; 8] = std::array::from_fn(|i| std::array::from_fn(|c| x[i][c] + u[i][c]));
        (
            hex8_smallest_deformation_eigenvalue(&k, &cur).unwrap(),
            hex8_certainly_stable(&k, &cur),
        )
    }
}

/// A hexahedron at rest, stretched by 10 % with some shear, and rigidly rotated by 0.4 rad
/// after a 2 % compression: every ratio positive (the six rigid modes shifted out), screened.
#[test]
fn a_hexahedron_at_rest_and_a_moderately_strained_one_are_stable() {
    use crate::element::hex8::Hex8Kind;
    use nalgebra::Rotation3;
    let (l, m) = lame(1e3, 0.3);
    let mat = Material::NeoHookean { lambda: l, mu: m };
    let x = hex::brick([1.0, 0.5, 0.7]);
    let rot = Rotation3::from_euler_angles(0.4, -0.2, 0.1);
    let states: [[[f64; 3]; 8]; 3] = [
        [[0.0; 3]; 8],
        x.map(|p| [0.1 * p[0] + 0.02 * p[1], 0.0, 0.01 * p[0]]),
        x.map(|p| {
            let q = rot * nalgebra::Vector3::new(0.98 * p[0], p[1], p[2]);
            [q[0] - p[0], q[1] - p[1], q[2] - p[2]]
        }),
    ];
    for (s, u) in states.iter().enumerate() {
        for kind in [Hex8Kind::Hex8, Hex8Kind::Hex8Eas] {
            let (ratio, screened) = hex::ratio(kind, false, &mat, &x, u);
            assert!(ratio > 0.0 && screened, "state {s} {kind:?}: {ratio} {screened}");
        }
    }
}

/// The 3D form of the tall EAS element: a plate 0.1 × 1.2 × 1.2 compressed by 5 % across its
/// thickness, beyond the critical `(0.1/1.2)² ≈ 0.7 %` of its zig-zag modes (`hex8_stab.rs`),
/// is flagged as EAS-21 (measured ratio −6.7e-3) and not passed by the screen; the same plate
/// compressed by 0.2 % is not flagged (+2.0e-6).
///
/// Not asserted, measured (`λ_min/λ_max`, neo-Hooke, E = 2.1e4, ν = 0.3, uniaxial strain):
/// unlike the 2D check, the 3D one also flags the held EAS element (−2.0e-3 at 5 %) and the
/// plain trilinear one (−1.2e-4 at 5 %, −1.7e-5 at 1 %; a cube from about 25 %), whose lowest
/// mode is the twist `(yz, −xz, −xy)` of the thin axis `x` — a field of one element (it does
/// not continue across a face), which the prestress softens like the rigid rotations.
#[test]
fn a_thin_eas_hexahedron_compressed_across_its_thickness_is_flagged_and_a_mildly_compressed_one_is_not() {
    use crate::element::hex8::Hex8Kind;
    let (l, m) = lame(2.1e4, 0.3);
    let mat = Material::NeoHookean { lambda: l, mu: m };
    let x = hex::brick([0.1, 1.2, 1.2]);
    let compressed = |c: f64| -> [[f64; 3]; 8] { std::array::from_fn(|i| [-c * x[i][0], 0.0, 0.0]) };
    let (eas, eas_screened) = hex::ratio(Hex8Kind::Hex8Eas, false, &mat, &x, &compressed(0.05));
    assert!(eas < -UNSTABLE_RATIO && !eas_screened, "{eas}");
    let (mild, mild_screened) = hex::ratio(Hex8Kind::Hex8Eas, false, &mat, &x, &compressed(0.002));
    assert!(mild > 0.0 && mild_screened, "{mild}");
}

/// The hexahedron's Cholesky screen against its eigenvalues: thin, flat and cubic elements of
/// both kinds compressed from 0 to 30 % across their first axis and sheared.
#[test]
fn the_hexahedron_cholesky_screen_agrees_with_the_eigenvalues() {
    use crate::element::hex8::Hex8Kind;
    let (l, m) = lame(2.1e4, 0.3);
    let mat = Material::NeoHookean { lambda: l, mu: m };
    let (mut passed, mut unstable) = (0, 0);
    for size in [[0.1, 0.1, 0.1], [0.1, 0.5, 0.1], [0.1, 1.2, 0.8]] {
        let x = hex::brick(size);
        for step in (0..=30).step_by(2) {
            let (c, g) = (0.01 * f64::from(step), 0.002 * f64::from(step));
            let u: [[f64; 3]; 8] = x.map(|p| [-c * p[0] + g * p[1], 0.0, g * p[0]]);
            for kind in [Hex8Kind::Hex8Eas, Hex8Kind::Hex8] {
                let (ratio, screened) = hex::ratio(kind, false, &mat, &x, &u);
                assert!(
                    !(screened && ratio < -UNSTABLE_RATIO),
                    "{size:?} {step} {kind:?}: {ratio}"
                );
                if ratio > 1e-6 {
                    assert!(screened, "{size:?} {step} {kind:?}: {ratio} not screened");
                }
                passed += usize::from(screened);
                unstable += usize::from(ratio < -UNSTABLE_RATIO);
            }
        }
    }
    assert!(passed > 20 && unstable > 3, "{passed} screened, {unstable} unstable");
}
