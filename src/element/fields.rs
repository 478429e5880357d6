//! Element fields for output: Green–Lagrange strain, Cauchy stress and the von Mises
//! equivalent stress at the centre of a quadrilateral, from its nodal displacements.
//!
//! The centre strain and second Piola–Kirchhoff stress come from
//! [`quad_centre_stress`] (for `Q4Eas` with the enhanced parameters re-solved for the given
//! displacements, as the kernel does); the Cauchy stress is `σ = J⁻¹ F S Fᵀ` with the
//! compatible `F` at the centre, and `σ33 = S33 / J` is the plane-strain out-of-plane stress.

use super::material::Material;
use super::quad::{
    quad_centre_deformation_gradient, quad_centre_stress, quad_residual_tangent, ElementError, ElementKind,
};
use nalgebra::Matrix2;

/// Fields at the centre of one element (tensors as `[[11, 12, 13], [21, 22, 23], [31, 32, 33]]`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CentreFields {
    /// Green–Lagrange strain (tensor components; `E33 = 0` in plane strain).
    pub green_lagrange: [[f64; 3]; 3],
    /// Cauchy stress, `σ33` included.
    pub cauchy: [[f64; 3]; 3],
    /// Von Mises equivalent of the Cauchy stress (with `σ33`).
    pub von_mises: f64,
}

/// Centre fields of a quadrilateral with reference nodes `x` (counter-clockwise) and nodal
/// displacements `u`.
pub fn centre_fields(
    kind: ElementKind,
    material: &Material,
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
        quad_residual_tangent(kind, material, x, u, &mut alpha, &mut r, None)?;
    }
    let (e, s) = quad_centre_stress(kind, material, x, u, &alpha)?;
    let f = quad_centre_deformation_gradient(x, u)?;
    let j = f.determinant();
    if j <= 0.0 {
        return Err(ElementError::BadGeometry(j));
    }
    let sm = Matrix2::new(s[0], s[2], s[2], s[1]);
    let sig = f * sm * f.transpose() / j;
    let s33 = material.out_of_plane_stress(&e)? / j;
    let cauchy = [
        [sig[(0, 0)], sig[(0, 1)], 0.0],
        [sig[(1, 0)], sig[(1, 1)], 0.0],
        [0.0, 0.0, s33],
    ];
    let green_lagrange = [[e[0], 0.5 * e[2], 0.0], [0.5 * e[2], e[1], 0.0], [0.0, 0.0, 0.0]];
    let (sx, sy, sz, txy) = (sig[(0, 0)], sig[(1, 1)], s33, sig[(0, 1)]);
    let von_mises = (0.5 * ((sx - sy).powi(2) + (sy - sz).powi(2) + (sz - sx).powi(2)) + 3.0 * txy * txy).sqrt();
    Ok(CentreFields {
        green_lagrange,
        cauchy,
        von_mises,
    })
}

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
}
