//! The hyperelastic materials of [`super::material`] in three dimensions, total Lagrangian
//! form (for the hexahedron kernel, [`super::hex8`]).
//!
//! Conventions (the 3D counterpart of [`super::material`]'s):
//! - strains and stresses in Voigt order `[11, 22, 33, 12, 23, 13]`;
//! - the strain vector carries the *engineering* shears,
//!   `E = [E11, E22, E33, 2E12, 2E23, 2E13]`, the stress vector the tensor shears,
//!   `S = [S11, S22, S33, S12, S23, S13]`, so that `δE · S` is the virtual work density,
//!   `S = ∂W/∂E` component by component and `D = ∂S/∂E` is symmetric.
//!
//! The same [`Material`] (its Lamé constants) serves both dimensions: in 3D
//! - St. Venant–Kirchhoff: `W = λ/2 (tr E)² + μ E:E`, `S = λ tr(E) I + 2μ E`;
//! - compressible Neo-Hooke (Simo–Pister/Ciarlet form; Simo & Pister, CMAME 46 (1984)
//!   201–215; Wriggers, *Nonlinear Finite Element Methods* (2008) eq. 3.118):
//!   `W = μ/2 (tr C − 3) − μ ln J + λ/2 (ln J)²`, `S = μ (I − C⁻¹) + λ ln J C⁻¹`,
//!   `D_ijkl = λ C⁻¹_ij C⁻¹_kl + (μ − λ ln J)(C⁻¹_ik C⁻¹_jl + C⁻¹_il C⁻¹_jk)`,
//!   with `C = I + 2E` and `J = √det C`.
//!
//! Both reduce to linear isotropic elasticity (`S = λ tr(E) I + 2μ E`) at `E = 0`.

use super::material::{Material, MaterialError};
use nalgebra::{Matrix3, Matrix6, Vector6};

/// The tensor index pairs of the Voigt components `[11, 22, 33, 12, 23, 13]` (zero-based).
pub const VOIGT_PAIRS: [(usize, usize); 6] = [(0, 0), (1, 1), (2, 2), (0, 1), (1, 2), (0, 2)];

/// `D = ∂S/∂E` of St. Venant–Kirchhoff (Voigt, engineering shear): the isotropic linear
/// elasticity matrix.
pub fn isotropic_tangent_3d(lambda: f64, mu: f64) -> Matrix6<f64> {
    let mut d = Matrix6::zeros();
    for a in 0..3 {
        for b in 0..3 {
            d[(a, b)] = lambda;
        }
        d[(a, a)] += 2.0 * mu;
        d[(a + 3, a + 3)] = mu;
    }
    d
}

/// The symmetric tensor of a Voigt strain vector (engineering shears halved).
pub fn strain_tensor(e: &Vector6<f64>) -> Matrix3<f64> {
    let mut t = Matrix3::zeros();
    for (a, &(i, j)) in VOIGT_PAIRS.iter().enumerate() {
        let v = if i == j { e[a] } else { 0.5 * e[a] };
        t[(i, j)] = v;
        t[(j, i)] = v;
    }
    t
}

/// The Voigt vector of a symmetric stress tensor (tensor shears).
pub fn stress_voigt(s: &Matrix3<f64>) -> Vector6<f64> {
    Vector6::from_fn(|a, _| {
        let (i, j) = VOIGT_PAIRS[a];
        s[(i, j)]
    })
}

/// `C = I + 2E`, `det C`, `C⁻¹` and `ln J = ½ ln det C`; an error unless `det C > 0`.
fn right_cauchy_green(e: &Vector6<f64>) -> Result<(Matrix3<f64>, f64, Matrix3<f64>, f64), MaterialError> {
    let c = Matrix3::identity() + 2.0 * strain_tensor(e);
    let det_c = c.determinant();
    if det_c <= 0.0 || !det_c.is_finite() {
        return Err(MaterialError::InvertedJacobian(det_c));
    }
    let ci = c.try_inverse().ok_or(MaterialError::InvertedJacobian(det_c))?;
    Ok((c, det_c, ci, 0.5 * det_c.ln()))
}

impl Material {
    /// `D = ∂S/∂E` in 3D when it does not depend on `E` (St. Venant–Kirchhoff), else `None`.
    pub fn constant_tangent_3d(&self) -> Option<Matrix6<f64>> {
        match *self {
            Material::SaintVenantKirchhoff { lambda, mu } => Some(isotropic_tangent_3d(lambda, mu)),
            Material::NeoHookean { .. } => None,
        }
    }

    /// Second Piola–Kirchhoff stress `S` and tangent `D = ∂S/∂E` (6×6, symmetric) for a 3D
    /// Green–Lagrange strain `e = [E11, E22, E33, 2E12, 2E23, 2E13]` (module documentation
    /// for the formulas). Neo-Hooke fails with [`MaterialError::InvertedJacobian`] unless
    /// `det C > 0` (a strain of no deformation); St. Venant–Kirchhoff is defined for every `E`
    /// (a folded element is the kernel's check, `det F`).
    pub fn stress_tangent_3d(&self, e: &Vector6<f64>) -> Result<(Vector6<f64>, Matrix6<f64>), MaterialError> {
        match *self {
            Material::SaintVenantKirchhoff { lambda, mu } => {
                let d = isotropic_tangent_3d(lambda, mu);
                Ok((d * e, d))
            }
            Material::NeoHookean { lambda, mu } => {
                let (_, _, ci, ln_j) = right_cauchy_green(e)?;
                let s = mu * (Matrix3::identity() - ci) + lambda * ln_j * ci;
                let f = mu - lambda * ln_j;
                let d = Matrix6::from_fn(|a, b| {
                    let ((i, j), (k, l)) = (VOIGT_PAIRS[a], VOIGT_PAIRS[b]);
                    lambda * ci[(i, j)] * ci[(k, l)] + f * (ci[(i, k)] * ci[(j, l)] + ci[(i, l)] * ci[(j, k)])
                });
                Ok((stress_voigt(&s), d))
            }
        }
    }

    /// Strain energy density `W(E)` per unit reference volume, 3D.
    pub fn energy_3d(&self, e: &Vector6<f64>) -> Result<f64, MaterialError> {
        match *self {
            Material::SaintVenantKirchhoff { lambda, mu } => {
                let t = strain_tensor(e);
                let tr = t.trace();
                Ok(0.5 * lambda * tr * tr + mu * t.norm_squared())
            }
            Material::NeoHookean { lambda, mu } => {
                let (c, _, _, ln_j) = right_cauchy_green(e)?;
                Ok(0.5 * mu * (c.trace() - 3.0) - mu * ln_j + 0.5 * lambda * ln_j * ln_j)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::element::material::lame;

    fn materials() -> [Material; 2] {
        let (l, m) = lame(2.1e4, 0.3);
        [
            Material::SaintVenantKirchhoff { lambda: l, mu: m },
            Material::NeoHookean { lambda: l, mu: m },
        ]
    }

    /// A sizeable strain with every component non-zero (principal stretches ≈ 0.8 … 1.3).
    const E: [f64; 6] = [0.12, -0.09, 0.05, 0.08, -0.06, 0.04];

    /// Largest relative error of `S` against central differences of `W` and of `D` against
    /// central differences of `S` (`h = 1e-6`, truncation `O(h²)`), both relative to the
    /// largest entry.
    fn fd_errors(m: &Material, e: &Vector6<f64>) -> (f64, f64) {
        let (s, d) = m.stress_tangent_3d(e).unwrap();
        let h = 1e-6;
        let (mut es, mut ed) = (0.0f64, 0.0f64);
        for b in 0..6 {
            let (mut ep, mut em) = (*e, *e);
            ep[b] += h;
            em[b] -= h;
            let dw = (m.energy_3d(&ep).unwrap() - m.energy_3d(&em).unwrap()) / (2.0 * h);
            es = es.max((dw - s[b]).abs() / s.amax());
            let ds = (m.stress_tangent_3d(&ep).unwrap().0 - m.stress_tangent_3d(&em).unwrap().0) / (2.0 * h);
            for a in 0..6 {
                ed = ed.max((ds[a] - d[(a, b)]).abs() / d.amax());
            }
        }
        (es, ed)
    }

    /// `S = ∂W/∂E` and `D = ∂S/∂E` against central differences at a sizeable strain with
    /// every component non-zero, both materials. Reference: the energies of the module
    /// documentation. Tolerance 1e-8 of the largest entry (measured: `S` 8e-12 St. Venant–
    /// Kirchhoff, 5e-10 Neo-Hooke; `D` ≤ 4e-11). `D` symmetric to 1e-14.
    #[test]
    fn stress_and_tangent_match_finite_differences_of_energy_and_stress() {
        for m in materials() {
            let e = Vector6::from_column_slice(&E);
            let (es, ed) = fd_errors(&m, &e);
            println!("{m:?}: |S − FD(W)|/|S| = {es:.2e}, |D − FD(S)|/|D| = {ed:.2e}");
            assert!(es < 1e-8 && ed < 1e-8, "{m:?}: {es:.2e} {ed:.2e}");
            let d = m.stress_tangent_3d(&e).unwrap().1;
            assert!((d - d.transpose()).amax() <= 1e-14 * d.amax());
        }
    }

    /// At `E = 0` both materials are stress-free with the isotropic linear-elastic tangent
    /// (`λ + 2μ` on the normal diagonal, `λ` off it, `μ` on the shears; exact to round-off,
    /// 1e-12 relative), and Neo-Hooke agrees with St. Venant–Kirchhoff to first order in `E`
    /// (the difference of the stresses at `1e-6 E` is `O(|E|²)`: ≤ 1e-5 of the stress).
    #[test]
    fn both_materials_reduce_to_linear_isotropic_elasticity_at_zero_strain() {
        let (young, nu) = (2.1e4, 0.3);
        let (l, m) = lame(young, nu);
        let svk = Material::SaintVenantKirchhoff { lambda: l, mu: m };
        let nh = Material::NeoHookean { lambda: l, mu: m };
        // the textbook compliance, inverted: uniaxial stress has strains (1, −ν, −ν) σ/E
        let mut compliance = Matrix6::zeros();
        for a in 0..3 {
            for b in 0..3 {
                compliance[(a, b)] = if a == b { 1.0 } else { -nu } / young;
            }
            compliance[(a + 3, a + 3)] = 2.0 * (1.0 + nu) / young;
        }
        let linear = compliance.try_inverse().unwrap();
        for mat in [svk, nh] {
            let (s0, d0) = mat.stress_tangent_3d(&Vector6::zeros()).unwrap();
            assert!(s0.amax() <= 1e-12 * young, "{mat:?}: S(0) = {s0}");
            assert!((d0 - linear).amax() <= 1e-12 * young, "{mat:?}: D(0) = {d0}");
            assert!(mat.energy_3d(&Vector6::zeros()).unwrap().abs() <= 1e-12 * young);
        }
        let small = Vector6::from_column_slice(&E) * 1e-6;
        let (s1, s2) = (
            svk.stress_tangent_3d(&small).unwrap().0,
            nh.stress_tangent_3d(&small).unwrap().0,
        );
        assert!((s1 - s2).amax() <= 1e-5 * s1.amax(), "{s1} vs {s2}");
    }

    /// Neo-Hooke at a strain with `det C ≤ 0` (here `C11 = 1 + 2 E11 = −0.2`) is a typed
    /// error, not a NaN; so is a NaN strain. St. Venant–Kirchhoff stays finite there.
    #[test]
    fn an_inverted_strain_is_a_typed_error_not_a_nan() {
        let [svk, nh] = materials();
        let bad = Vector6::new(-0.6, 0.0, 0.0, 0.0, 0.0, 0.0);
        assert!(matches!(
            nh.stress_tangent_3d(&bad),
            Err(MaterialError::InvertedJacobian(d)) if d <= 0.0
        ));
        assert!(matches!(nh.energy_3d(&bad), Err(MaterialError::InvertedJacobian(_))));
        let nan = Vector6::new(f64::NAN, 0.0, 0.0, 0.0, 0.0, 0.0);
        assert!(matches!(
            nh.stress_tangent_3d(&nan),
            Err(MaterialError::InvertedJacobian(_))
        ));
        assert!(svk.stress_tangent_3d(&bad).unwrap().0.iter().all(|v| v.is_finite()));
    }
}
