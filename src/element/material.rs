//! Hyperelastic materials in plane strain, total Lagrangian form.
//!
//! Conventions (used by every kernel in [`crate::element`]):
//! - strains and stresses in Voigt order `[11, 22, 12]`;
//! - the strain vector carries the *engineering* shear, `E = [E11, E22, 2 E12]`,
//!   the stress vector the tensor shear, `S = [S11, S22, S12]`, so that `δE · S` is the
//!   virtual work density and `D = ∂S/∂E` is symmetric;
//! - plane strain: `E33 = 0`, `C33 = 1`; the out-of-plane stress is not needed by the
//!   in-plane equations and is not returned.

use nalgebra::{Matrix3, Vector3};
use serde::{Deserialize, Serialize};

/// Constitutive model with its Lamé constants.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub enum Material {
    /// St. Venant–Kirchhoff: `S = λ tr(E) I + 2 μ E`.
    SaintVenantKirchhoff { lambda: f64, mu: f64 },
    /// Compressible Neo-Hookean (Simo–Pister/Ciarlet form):
    /// `W = μ/2 (I₁ − 3) − μ ln J + λ/2 (ln J)²`, hence
    /// `S = μ (I − C⁻¹) + λ ln J C⁻¹`.
    NeoHookean { lambda: f64, mu: f64 },
}

/// Failure of a constitutive evaluation.
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
pub enum MaterialError {
    /// `det C = J² ≤ 0` (the strain is not that of any deformation): the Neo-Hookean energy
    /// is undefined. (A folded element has `det C > 0`: the element kernel checks `det F`.)
    #[error("non-positive det C = {0:.3e} (the strain of no deformation)")]
    InvertedJacobian(f64),
}

/// Lamé constants `(λ, μ)` from Young's modulus and Poisson's ratio.
pub fn lame(young: f64, poisson: f64) -> (f64, f64) {
    let lambda = young * poisson / ((1.0 + poisson) * (1.0 - 2.0 * poisson));
    let mu = young / (2.0 * (1.0 + poisson));
    (lambda, mu)
}

/// `D = ∂S/∂E` of St. Venant–Kirchhoff in plane strain (Voigt, engineering shear).
fn svk_tangent(lambda: f64, mu: f64) -> Matrix3<f64> {
    Matrix3::new(
        lambda + 2.0 * mu,
        lambda,
        0.0,
        lambda,
        lambda + 2.0 * mu,
        0.0,
        0.0,
        0.0,
        mu,
    )
}

impl Material {
    /// `D = ∂S/∂E` when it does not depend on `E` (St. Venant–Kirchhoff), else `None`.
    pub fn constant_tangent(&self) -> Option<Matrix3<f64>> {
        match *self {
            Material::SaintVenantKirchhoff { lambda, mu } => Some(svk_tangent(lambda, mu)),
            Material::NeoHookean { .. } => None,
        }
    }

    /// Second Piola–Kirchhoff stress `S` and material tangent `D = ∂S/∂E` for a
    /// Green–Lagrange strain `e = [E11, E22, 2E12]` (plane strain).
    pub fn stress_tangent(&self, e: &Vector3<f64>) -> Result<(Vector3<f64>, Matrix3<f64>), MaterialError> {
        match *self {
            Material::SaintVenantKirchhoff { lambda, mu } => {
                let d = svk_tangent(lambda, mu);
                Ok((d * e, d))
            }
            Material::NeoHookean { lambda, mu } => {
                // C = 2E + I (in-plane block; C33 = 1)
                let c11 = 2.0 * e[0] + 1.0;
                let c22 = 2.0 * e[1] + 1.0;
                let c12 = e[2];
                let det_c = c11 * c22 - c12 * c12;
                if det_c <= 0.0 || !det_c.is_finite() {
                    return Err(MaterialError::InvertedJacobian(det_c));
                }
                let ln_j = 0.5 * det_c.ln();
                // C^{-1}
                let i11 = c22 / det_c;
                let i22 = c11 / det_c;
                let i12 = -c12 / det_c;
                let s = Vector3::new(
                    mu * (1.0 - i11) + lambda * ln_j * i11,
                    mu * (1.0 - i22) + lambda * ln_j * i22,
                    -mu * i12 + lambda * ln_j * i12,
                );
                // D_ijkl = λ Ci_ij Ci_kl + (μ − λ ln J)(Ci_ik Ci_jl + Ci_il Ci_jk)
                let f = mu - lambda * ln_j;
                let ci = [[i11, i12], [i12, i22]];
                let idx = [(0usize, 0usize), (1, 1), (0, 1)];
                let mut d = Matrix3::zeros();
                for (a, &(i, j)) in idx.iter().enumerate() {
                    for (b, &(k, l)) in idx.iter().enumerate() {
                        d[(a, b)] = lambda * ci[i][j] * ci[k][l] + f * (ci[i][k] * ci[j][l] + ci[i][l] * ci[j][k]);
                    }
                }
                Ok((s, d))
            }
        }
    }

    /// Out-of-plane second Piola–Kirchhoff stress `S33` of plane strain (`E33 = 0`) for the
    /// in-plane strain `e` (for output: the in-plane equations do not need it).
    pub fn out_of_plane_stress(&self, e: &Vector3<f64>) -> Result<f64, MaterialError> {
        match *self {
            Material::SaintVenantKirchhoff { lambda, .. } => Ok(lambda * (e[0] + e[1])),
            Material::NeoHookean { lambda, .. } => {
                // S33 = μ (1 − C33⁻¹) + λ ln J C33⁻¹ with C33 = 1
                let det_c = (2.0 * e[0] + 1.0) * (2.0 * e[1] + 1.0) - e[2] * e[2];
                if det_c <= 0.0 || !det_c.is_finite() {
                    return Err(MaterialError::InvertedJacobian(det_c));
                }
                Ok(lambda * 0.5 * det_c.ln())
            }
        }
    }

    /// Strain energy density `W(E)` (used by tests and by energy diagnostics).
    pub fn energy(&self, e: &Vector3<f64>) -> Result<f64, MaterialError> {
        match *self {
            Material::SaintVenantKirchhoff { lambda, mu } => {
                let tr = e[0] + e[1];
                let ee = e[0] * e[0] + e[1] * e[1] + 0.5 * e[2] * e[2];
                Ok(0.5 * lambda * tr * tr + mu * ee)
            }
            Material::NeoHookean { lambda, mu } => {
                let c11 = 2.0 * e[0] + 1.0;
                let c22 = 2.0 * e[1] + 1.0;
                let det_c = c11 * c22 - e[2] * e[2];
                if det_c <= 0.0 {
                    return Err(MaterialError::InvertedJacobian(det_c));
                }
                let ln_j = 0.5 * det_c.ln();
                Ok(0.5 * mu * (c11 + c22 + 1.0 - 3.0) - mu * ln_j + 0.5 * lambda * ln_j * ln_j)
            }
        }
    }

    /// Small-strain plane-strain modulus `E/(1−ν²)` recovered from the Lamé constants.
    pub fn plane_strain_modulus(&self) -> f64 {
        let (lambda, mu) = match *self {
            Material::SaintVenantKirchhoff { lambda, mu } | Material::NeoHookean { lambda, mu } => (lambda, mu),
        };
        let young = mu * (3.0 * lambda + 2.0 * mu) / (lambda + mu);
        let nu = lambda / (2.0 * (lambda + mu));
        young / (1.0 - nu * nu)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn check_fd(m: Material) {
        let e = Vector3::new(0.03, -0.02, 0.05);
        let (s, d) = m.stress_tangent(&e).unwrap();
        let h = 1e-6;
        for b in 0..3 {
            let mut ep = e;
            let mut em = e;
            ep[b] += h;
            em[b] -= h;
            // stress = dW/dE (engineering shear makes this exact in Voigt form)
            let ds = (m.stress_tangent(&ep).unwrap().0 - m.stress_tangent(&em).unwrap().0) / (2.0 * h);
            let dw = (m.energy(&ep).unwrap() - m.energy(&em).unwrap()) / (2.0 * h);
            assert!(
                (dw - s[b]).abs() < 1e-6 * (1.0 + s.norm()),
                "dW/dE[{b}] {dw} vs S {}",
                s[b]
            );
            for a in 0..3 {
                assert!((ds[a] - d[(a, b)]).abs() < 1e-5 * (1.0 + d.norm()), "D[{a},{b}]");
            }
        }
        assert!((d - d.transpose()).norm() < 1e-12 * d.norm());
    }

    #[test]
    fn svk_stress_and_tangent_match_finite_differences() {
        let (l, m) = lame(2.1e4, 0.3);
        check_fd(Material::SaintVenantKirchhoff { lambda: l, mu: m });
    }

    #[test]
    fn neo_hookean_stress_and_tangent_match_finite_differences() {
        let (l, m) = lame(2.1e4, 0.3);
        check_fd(Material::NeoHookean { lambda: l, mu: m });
    }

    #[test]
    fn neo_hookean_reduces_to_linear_elasticity_at_the_origin() {
        let (l, m) = lame(1.0, 0.25);
        let (s0, d0) = Material::NeoHookean { lambda: l, mu: m }
            .stress_tangent(&Vector3::zeros())
            .unwrap();
        let (_, dl) = Material::SaintVenantKirchhoff { lambda: l, mu: m }
            .stress_tangent(&Vector3::zeros())
            .unwrap();
        assert!(s0.norm() < 1e-15);
        assert!((d0 - dl).norm() < 1e-12);
        let pm = Material::NeoHookean { lambda: l, mu: m }.plane_strain_modulus();
        assert!((pm - 1.0 / (1.0 - 0.0625)).abs() < 1e-12);
    }

    #[test]
    fn inverted_state_is_an_error_not_a_nan() {
        let (l, m) = lame(1.0, 0.3);
        let r = Material::NeoHookean { lambda: l, mu: m }.stress_tangent(&Vector3::new(-0.6, 0.0, 0.0));
        assert!(matches!(r, Err(MaterialError::InvertedJacobian(_))));
    }
}
