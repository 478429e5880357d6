//! Element fields for output: Green–Lagrange strain, Cauchy stress and the von Mises
//! equivalent stress at the centre of a quadrilateral, from its nodal displacements.
//!
//! The centre strain and second Piola–Kirchhoff stress come from
//! [`quad_centre_stress`] (for `Q4Eas` with the enhanced parameters re-solved for the given
//! displacements, as the kernel does); the Cauchy stress is `σ = J⁻¹ F S Fᵀ` with the
//! compatible `F` at the centre, and `σ33 = S33 / J` is the plane-strain out-of-plane stress.
//! A hexahedron's ([`hex8_centre_fields`]): the Gauss average of its Green–Lagrange strain
//! (compatible plus enhanced), `S` of the 3D law there, `σ = J⁻¹ F S Fᵀ` with the centre `F`.

use super::hex8::{
    hex8_dn_dxi, hex8_gauss_strains, hex8_jacobian, hex8_residual_tangent_with, Hex8Error, Hex8Geometry, Hex8Kind,
    EAS_COUNT,
};
use super::material::Material;
use super::material3d::strain_tensor;
use super::quad::{
    quad_centre_deformation_gradient, quad_centre_stress, quad_residual_tangent_with, ElementError, ElementKind,
    Kinematics, QuadGeometry,
};
use nalgebra::{Matrix2, Matrix3, Vector3, Vector4, Vector6};

/// Fields at the centre of one element (tensors as `[[11, 12, 13], [21, 22, 23], [31, 32, 33]]`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CentreFields {
    /// Green–Lagrange strain (tensor components; `E33 = 0` in plane strain, the thickness
    /// strain in plane stress, the hoop strain in the axisymmetric setting).
    pub green_lagrange: [[f64; 3]; 3],
    /// Cauchy stress, `σ33` included.
    pub cauchy: [[f64; 3]; 3],
    /// Von Mises equivalent of the Cauchy stress (with `σ33`).
    pub von_mises: f64,
}

/// Centre fields of a plane-strain quadrilateral with reference nodes `x`
/// (counter-clockwise) and nodal displacements `u`.
pub fn centre_fields(
    kind: ElementKind,
    material: &Material,
    x: &[[f64; 2]; 4],
    u: &[[f64; 2]; 4],
) -> Result<CentreFields, ElementError> {
    centre_fields_with(kind, material, Kinematics::PlaneStrain, x, u)
}

/// Centre fields of a quadrilateral of a body in the given setting. The in-plane strain is
/// taken as in plane strain (compatible plus enhanced, Gauss average); the out-of-plane
/// strain `E33` and stretch `F33` are the setting's: `0` and `1` in plane strain, the value
/// that makes `S33 = 0` in plane stress (`√(1 + 2E33)` the thickness stretch), the hoop
/// strain `u_r/R + ½(u_r/R)²` and `F33 = r/R` at the centre in the axisymmetric setting
/// (`R` the reference radius, `u_r` the mean radial displacement of the nodes). The
/// Cauchy stress is `σ = J⁻¹ F S Fᵀ` with `J = det F₂ · F33`, `σ33 = F33² S33 / J`.
pub fn centre_fields_with(
    kind: ElementKind,
    material: &Material,
    kinematics: Kinematics,
    x: &[[f64; 2]; 4],
    u: &[[f64; 2]; 4],
) -> Result<CentreFields, ElementError> {
    let mut alpha = [0.0; 4];
    if matches!(
        kind,
        ElementKind::Q4Eas | ElementKind::Q4EasStab | ElementKind::Q4EasSafe
    ) {
        // the enhanced parameters of this u (the kernel is a function of u alone)
        let mut r = [0.0; 8];
        let geo = QuadGeometry::with_kinematics(kind, material, kinematics, x)?;
        quad_residual_tangent_with(kind, material, &geo, u, &mut alpha, &mut r, None)?;
    }
    let (e, s_plane) = quad_centre_stress(kind, material, x, u, &alpha)?;
    let (s, e33, f33) = match kinematics {
        Kinematics::PlaneStrain => (s_plane, 0.0, 1.0),
        Kinematics::PlaneStress { .. } => {
            let st = material.plane_stress_state(&e)?;
            (st.stress, st.e33, (1.0 + 2.0 * st.e33).sqrt())
        }
        Kinematics::Axisymmetric => {
            let radius = 0.25 * x.iter().map(|p| p[0]).sum::<f64>();
            let ur = 0.25 * u.iter().map(|d| d[0]).sum::<f64>();
            let hoop = ur / radius + 0.5 * (ur / radius).powi(2);
            let (s4, _, _) = material.stress_tangent_4(&Vector4::new(e[0], e[1], e[2], hoop))?;
            (Vector3::new(s4[0], s4[1], s4[2]), hoop, 1.0 + ur / radius)
        }
    };
    let f = quad_centre_deformation_gradient(x, u)?;
    let j = f.determinant() * f33;
    if j <= 0.0 || !j.is_finite() {
        return Err(ElementError::BadGeometry(j));
    }
    let sm = Matrix2::new(s[0], s[2], s[2], s[1]);
    let sig = f * sm * f.transpose() / j;
    let s33 = match kinematics {
        Kinematics::PlaneStrain => material.out_of_plane_stress(&e)? / j,
        Kinematics::PlaneStress { .. } => 0.0,
        Kinematics::Axisymmetric => {
            let (s4, _, _) = material.stress_tangent_4(&Vector4::new(e[0], e[1], e[2], e33))?;
            f33 * f33 * s4[3] / j
        }
    };
    let cauchy = [
        [sig[(0, 0)], sig[(0, 1)], 0.0],
        [sig[(1, 0)], sig[(1, 1)], 0.0],
        [0.0, 0.0, s33],
    ];
    let green_lagrange = [[e[0], 0.5 * e[2], 0.0], [0.5 * e[2], e[1], 0.0], [0.0, 0.0, e33]];
    let (sx, sy, sz, txy) = (sig[(0, 0)], sig[(1, 1)], s33, sig[(0, 1)]);
    let von_mises = (0.5 * ((sx - sy).powi(2) + (sy - sz).powi(2) + (sz - sx).powi(2)) + 3.0 * txy * txy).sqrt();
    Ok(CentreFields {
        green_lagrange,
        cauchy,
        von_mises,
    })
}

/// Centre fields of a hexahedron with reference nodes `x` (Gmsh/VTK order) and nodal
/// displacements `u`: `E = ⅛ Σ_q (E_c + G α)_q`, the Gauss average of the strain (for
/// [`Hex8Kind::Hex8Eas`] with `α` re-solved for `u` by the kernel, without holds; in a
/// homogeneous state `α = 0` and every Gauss point has the same `E`), `S` of
/// [`Material::stress_tangent_3d`] at `E`, and the Cauchy stress `σ = J⁻¹ F S Fᵀ` with the
/// compatible `F = I + Σ_I u_I ⊗ ∇_X N_I` at the centre, `J = det F`; von Mises
/// `√(½[(σ11 − σ22)² + (σ22 − σ33)² + (σ33 − σ11)²] + 3(σ12² + σ23² + σ13²))`.
/// (Simo & Hughes, *Computational Inelasticity*, 1998, §7 for `σ = J⁻¹ F S Fᵀ`.)
pub fn hex8_centre_fields(
    kind: Hex8Kind,
    material: &Material,
    x: &[[f64; 3]; 8],
    u: &[[f64; 3]; 8],
) -> Result<CentreFields, Hex8Error> {
    let geo = Hex8Geometry::new(kind, x)?;
    let mut alpha = [0.0; EAS_COUNT];
    hex8_residual_tangent_with(kind, material, &geo, u, &mut alpha, &mut [0.0; 24], None)?;
    let e = hex8_gauss_strains(&geo, u, &alpha)?
        .iter()
        .fold(Vector6::zeros(), |a, q| a + q * 0.125);
    let (s, _) = material.stress_tangent_3d(&e)?;
    let d = hex8_dn_dxi(&[0.0; 3]);
    let jinv = hex8_jacobian(x, &d).try_inverse().ok_or(Hex8Error::BadGeometry(0.0))?;
    let f = Matrix3::identity() + hex8_jacobian(u, &d) * jinv;
    let j = f.determinant();
    if j <= 0.0 || !j.is_finite() {
        return Err(Hex8Error::Inverted(j));
    }
    let sig = f * stress_tensor(&s) * f.transpose() / j;
    let tensor = |m: &Matrix3<f64>| -> [[f64; 3]; 3] { std::array::from_fn(|r| std::array::from_fn(|c| m[(r, c)])) };
    let von_mises = (0.5
        * ((sig[(0, 0)] - sig[(1, 1)]).powi(2)
            + (sig[(1, 1)] - sig[(2, 2)]).powi(2)
            + (sig[(2, 2)] - sig[(0, 0)]).powi(2))
        + 3.0 * (sig[(0, 1)].powi(2) + sig[(1, 2)].powi(2) + sig[(0, 2)].powi(2)))
    .sqrt();
    Ok(CentreFields {
        green_lagrange: tensor(&strain_tensor(&e)),
        cauchy: tensor(&sig),
        von_mises,
    })
}

/// The symmetric tensor of a Voigt stress `[11, 22, 33, 12, 23, 13]` (no factor on shears).
fn stress_tensor(s: &Vector6<f64>) -> Matrix3<f64> {
    Matrix3::new(s[0], s[3], s[5], s[3], s[1], s[4], s[5], s[4], s[2])
}

#[cfg(test)]
#[path = "fields_hex_tests.rs"]
mod hex_tests;

#[cfg(test)]
mod tests {
    use super::*;
    use crate::element::material::lame;

    /// Uniaxial stretch λ1 in x with free lateral contraction is not plane strain; a
    /// homogeneous deformation `x = F X` is: every kernel gives the same F, and σ must equal
    /// J⁻¹ F S Fᵀ of the material at that F, with `σ33 = S33/J`.
    #[test]
    fn homogeneous_deformation_gives_the_material_stress() {
        let fm = Matrix2::new(1.05, 0.02, -0.01, 0.97);
        let x = [[0.0, 0.0], [1.2, 0.1], [1.1, 0.9], [-0.1, 1.0]];
        let u = x.map(|p| {
            let q = fm * nalgebra::Vector2::new(p[0], p[1]);
            [q[0] - p[0], q[1] - p[1]]
        });
        let (lambda, mu) = lame(200.0, 0.3);
        for material in [
            Material::SaintVenantKirchhoff { lambda, mu },
            Material::NeoHookean { lambda, mu },
        ] {
            for kind in [ElementKind::Q4, ElementKind::Q4Eas] {
                let c = centre_fields(kind, &material, &x, &u).unwrap();
                let cc = fm.transpose() * fm;
                let e = nalgebra::Vector3::new(0.5 * (cc[(0, 0)] - 1.0), 0.5 * (cc[(1, 1)] - 1.0), cc[(0, 1)]);
                let (s, _) = material.stress_tangent(&e).unwrap();
                let j = fm.determinant();
                let sig = fm * Matrix2::new(s[0], s[2], s[2], s[1]) * fm.transpose() / j;
                let tol = 1e-10 * sig.norm();
                assert!((c.cauchy[0][0] - sig[(0, 0)]).abs() < tol, "{kind:?} {material:?}");
                assert!((c.cauchy[1][1] - sig[(1, 1)]).abs() < tol);
                assert!((c.cauchy[0][1] - sig[(0, 1)]).abs() < tol);
                assert!((c.cauchy[2][2] - material.out_of_plane_stress(&e).unwrap() / j).abs() < tol);
                assert!((c.green_lagrange[0][1] - 0.5 * e[2]).abs() < 1e-14);
                assert!(c.von_mises > 0.0);
            }
        }
    }

    /// Hydrostatic plane-strain state of SVK: σ11 = σ22 and, with σ33 = ν(σ11 + σ22) in the
    /// small-strain limit, the von Mises stress is |σ11 − σ33|.
    #[test]
    fn small_strain_plane_strain_von_mises() {
        let eps = 1e-7;
        let x = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
        let u = x.map(|p| [eps * p[0], eps * p[1]]);
        let nu = 0.3;
        let (lambda, mu) = lame(1.0, nu);
        let c = centre_fields(
            ElementKind::Q4Eas,
            &Material::SaintVenantKirchhoff { lambda, mu },
            &x,
            &u,
        )
        .unwrap();
        let s = c.cauchy[0][0];
        assert!((c.cauchy[2][2] / (2.0 * nu * s) - 1.0).abs() < 1e-5);
        assert!((c.von_mises / (s - c.cauchy[2][2]).abs() - 1.0).abs() < 1e-5);
    }

    /// The 3D stress of a homogeneous 3D state, `σ = J⁻¹ F S Fᵀ` with `F = diag(F₂, F33)`
    /// and `S` from the 3D law ([`Material::stress_tangent_4`]).
    fn stress_3d(material: &Material, f2: &Matrix2<f64>, f33: f64) -> ([[f64; 2]; 2], f64) {
        let c = f2.transpose() * f2;
        let e4 = Vector4::new(
            0.5 * (c[(0, 0)] - 1.0),
            0.5 * (c[(1, 1)] - 1.0),
            c[(0, 1)],
            0.5 * (f33 * f33 - 1.0),
        );
        let (s, _, _) = material.stress_tangent_4(&e4).unwrap();
        let j = f2.determinant() * f33;
        let sig = f2 * Matrix2::new(s[0], s[2], s[2], s[1]) * f2.transpose() / j;
        (
            [[sig[(0, 0)], sig[(0, 1)]], [sig[(1, 0)], sig[(1, 1)]]],
            f33 * f33 * s[3] / j,
        )
    }

    /// Axisymmetric: `u_r = a r`, `u_z = b z` is the homogeneous 3D state
    /// `F = diag(1 + a, 1 + b, 1 + a)` (the hoop stretch `r/R = 1 + a`); plane stress: a
    /// homogeneous in-plane `F` with the thickness stretch that makes `S33 = 0`. The centre
    /// fields must be the 3D law's Cauchy stress at that `F`, `σ33` included (zero in plane
    /// stress), with the out-of-plane strain.
    #[test]
    fn axisymmetric_and_plane_stress_fields_are_the_3d_stress_of_a_homogeneous_state() {
        let (lambda, mu) = lame(200.0, 0.3);
        let x = [[1.0, 0.0], [2.2, 0.1], [2.1, 0.9], [0.9, 1.0]];
        for material in [
            Material::SaintVenantKirchhoff { lambda, mu },
            Material::NeoHookean { lambda, mu },
        ] {
            for kind in [ElementKind::Q4, ElementKind::Q4Eas, ElementKind::Q4EasSafe] {
                let (a, b) = (0.03, -0.02);
                let u = x.map(|p| [a * p[0], b * p[1]]);
                let c = centre_fields_with(kind, &material, Kinematics::Axisymmetric, &x, &u).unwrap();
                let f2 = Matrix2::new(1.0 + a, 0.0, 0.0, 1.0 + b);
                let (sig, s33) = stress_3d(&material, &f2, 1.0 + a);
                let tol = 1e-10 * sig[0][0].abs().max(sig[1][1].abs());
                assert!((c.cauchy[0][0] - sig[0][0]).abs() < tol, "{kind:?} {material:?} {c:?}");
                assert!((c.cauchy[1][1] - sig[1][1]).abs() < tol, "{kind:?} {material:?}");
                assert!((c.cauchy[2][2] - s33).abs() < tol, "{kind:?} {material:?}");
                assert!((c.green_lagrange[2][2] - (a + 0.5 * a * a)).abs() < 1e-14);

                let fm = Matrix2::new(1.04, 0.02, -0.01, 0.98);
                let u = x.map(|p| {
                    let q = fm * nalgebra::Vector2::new(p[0], p[1]);
                    [q[0] - p[0], q[1] - p[1]]
                });
                let kin = Kinematics::PlaneStress { thickness: 0.1 };
                let c = centre_fields_with(kind, &material, kin, &x, &u).unwrap();
                let f33 = (1.0 + 2.0 * c.green_lagrange[2][2]).sqrt();
                let (sig, s33) = stress_3d(&material, &fm, f33);
                let tol = 1e-9 * sig[0][0].abs().max(sig[1][1].abs());
                assert!(s33.abs() < tol, "S33 = 0 at the thickness stretch: {s33}");
                assert!((c.cauchy[0][0] - sig[0][0]).abs() < tol, "{kind:?} {material:?}");
                assert!((c.cauchy[0][1] - sig[0][1]).abs() < tol, "{kind:?} {material:?}");
                assert!((c.cauchy[1][1] - sig[1][1]).abs() < tol, "{kind:?} {material:?}");
                assert_eq!(c.cauchy[2][2], 0.0);
            }
        }
    }
}
