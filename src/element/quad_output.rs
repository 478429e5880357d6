//! Output quantities of the quadrilateral at its centre (strain, stress, deformation
//! gradient), for the recorded fields; the equations of the element are in its parent.

use super::{dn_dxi, enhanced, jacobian, kinematics, ElementError, ElementKind, QuadGeometry};
use crate::element::material::Material;
use nalgebra::{Matrix2, Vector3};

/// Green–Lagrange strain and second Piola–Kirchhoff stress at the element centre (for output).
pub fn quad_centre_stress(
    kind: ElementKind,
    material: &Material,
    x: &[[f64; 2]; 4],
    u: &[[f64; 2]; 4],
    alpha: &[f64; 4],
) -> Result<(Vector3<f64>, Vector3<f64>), ElementError> {
    let geo = QuadGeometry::new(kind, x)?;
    // centre value = Gauss average (the enhanced field averages to zero)
    let mut e = Vector3::zeros();
    for g in &geo.gp {
        let (ec, en) = (kinematics(g, u).ec, enhanced(&g.g, alpha));
        e += 0.25 * Vector3::new(ec[0] + en[0], ec[1] + en[1], ec[2] + en[2]);
    }
    let (s, _) = material.stress_tangent(&e)?;
    Ok((e, s))
}

/// Compatible deformation gradient `F = I + Σ u_I ⊗ ∇_X N_I` at the element centre
/// (for output; fails like [`QuadGeometry::new`] on a non-positive reference Jacobian).
pub fn quad_centre_deformation_gradient(x: &[[f64; 2]; 4], u: &[[f64; 2]; 4]) -> Result<Matrix2<f64>, ElementError> {
    let d = dn_dxi(0.0, 0.0);
    let j = jacobian(x, &d);
    let det = j.determinant();
    let inv = j
        .try_inverse()
        .filter(|_| det > 0.0)
        .ok_or(ElementError::BadGeometry(det))?;
    let mut f = Matrix2::identity();
    for i in 0..4 {
        // ∇_X N_I = J⁻ᵀ ∂N_I/∂ξ
        let g = inv.transpose() * nalgebra::Vector2::new(d[0][i], d[1][i]);
        for a in 0..2 {
            for b in 0..2 {
                f[(a, b)] += u[i][a] * g[b];
            }
        }
    }
    Ok(f)
}
