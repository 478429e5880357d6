//! The materials of [`super::material`] outside plane strain: the 3D law restricted to a
//! deformation without out-of-plane shear (axisymmetric bodies), and the same law with the
//! out-of-plane stress condensed to zero (plane stress).
//!
//! Conventions: the four-component Voigt vectors are ordered `[11, 22, 12, 33]`, with
//! `(1, 2, 3) = (r, z, θ)` in the axisymmetric setting and `(x, y, thickness)` in plane
//! stress; the strain carries the engineering shear `2E12`, the stress the tensor shear
//! `S12` (as in plane strain), so `δE · S` is the work density and `D = ∂S/∂E` symmetric.
//! The deformation gradient is `F = [[F11, F12, 0], [F21, F22, 0], [0, 0, F33]]`, hence
//! `C = [[C11, C12, 0], [C12, C22, 0], [0, 0, C33]]` and `E13 = E23 = 0`.
//!
//! * St. Venant–Kirchhoff: `S = λ tr(E) I + 2μE`, `W = ½ λ tr(E)² + μ E:E`.
//! * Neo-Hooke (Simo–Pister/Ciarlet, as in plane strain): `W = μ/2 (I₁ − 3) − μ ln J +
//!   λ/2 (ln J)²`, `S = μ (I − C⁻¹) + λ ln J C⁻¹`,
//!   `ℂ_ijkl = λ C⁻¹_ij C⁻¹_kl + (μ − λ ln J)(C⁻¹_ik C⁻¹_jl + C⁻¹_il C⁻¹_jk)`
//!   (e.g. Holzapfel, *Nonlinear Solid Mechanics*, 2000, §6.5; Bonet & Wood, 2008, §6.4.3).
//!
//! Plane stress (`S33 = 0`): `E33` is the solution of `S33(E11, E22, E12, E33) = 0`, and the
//! condensed law is `S_ab(E_in, E33(E_in))` with the tangent
//! `D̄_ab = D_ab − D_a3 D_3b / D_33` (a, b in-plane; exact, since `S33 ≡ 0` along the
//! solution) and the energy `W(E_in, E33(E_in))`, whose gradient is `S_in` because
//! `∂W/∂E33 = S33 = 0`. St. Venant–Kirchhoff: `E33 = −λ (E11 + E22)/(λ + 2μ)` in closed
//! form, which gives the plane-stress law `S = λ̄ tr E I + 2μE`, `λ̄ = 2λμ/(λ + 2μ)`, for any
//! strain. Neo-Hooke: `C33 = e^t` with `t` the root of
//! `h(t) = μ (e^t − 1) + λ/2 (ln det C₂ + t)` (`S33 C33 = h`), increasing and convex in `t`,
//! so Newton's method from `t₀ = max(0, −ln det C₂)`, where `h(t₀) ≥ 0`, converges
//! monotonically (a local Newton per Gauss point; the thickness stretch is `√C33`).

use super::material::{Material, MaterialError};
use nalgebra::{Matrix3, Matrix4, Vector3, Vector4};

/// A plane-stress state: the in-plane stress, the condensed tangent, the energy density and
/// the out-of-plane strain that makes `S33 = 0`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PlaneStressState {
    /// `[S11, S22, S12]`.
    pub stress: Vector3<f64>,
    /// `D̄ = ∂S/∂E` of the condensed law (3×3, engineering shear).
    pub tangent: Matrix3<f64>,
    /// `W(E_in, E33(E_in))`.
    pub energy: f64,
    /// `E33`; the thickness stretch is `√(1 + 2 E33)`.
    pub e33: f64,
}

/// `ℂ` of Neo-Hooke on the index pairs `(11, 22, 12, 33)` for `C⁻¹` (3×3, block form).
fn neo_hooke_tangent(lambda: f64, mu: f64, ln_j: f64, ci: &[[f64; 3]; 3]) -> Matrix4<f64> {
    let f = mu - lambda * ln_j;
    let idx = [(0usize, 0usize), (1, 1), (0, 1), (2, 2)];
    let mut d = Matrix4::zeros();
    for (a, &(i, j)) in idx.iter().enumerate() {
        for (b, &(k, l)) in idx.iter().enumerate() {
            d[(a, b)] = lambda * ci[i][j] * ci[k][l] + f * (ci[i][k] * ci[j][l] + ci[i][l] * ci[j][k]);
        }
    }
    d
}

impl Material {
    /// `(S, D, W)` of the 3D law for a strain without out-of-plane shear,
    /// `e = [E11, E22, 2E12, E33]` (the axisymmetric `[E_rr, E_zz, 2E_rz, E_θθ]`); see the
    /// module documentation for the formulas.
    pub fn stress_tangent_4(&self, e: &Vector4<f64>) -> Result<(Vector4<f64>, Matrix4<f64>, f64), MaterialError> {
        match *self {
            Material::SaintVenantKirchhoff { lambda, mu } => {
                let tr = e[0] + e[1] + e[3];
                let s = Vector4::new(
                    lambda * tr + 2.0 * mu * e[0],
                    lambda * tr + 2.0 * mu * e[1],
                    mu * e[2],
                    lambda * tr + 2.0 * mu * e[3],
                );
                let (a, l) = (lambda + 2.0 * mu, lambda);
                #[rustfmt::skip]
                let d = Matrix4::new(
                    a, l, 0.0, l,
                    l, a, 0.0, l,
                    0.0, 0.0, mu, 0.0,
                    l, l, 0.0, a,
                );
                let ee = e[0] * e[0] + e[1] * e[1] + 0.5 * e[2] * e[2] + e[3] * e[3];
                Ok((s, d, 0.5 * lambda * tr * tr + mu * ee))
            }
            Material::NeoHookean { lambda, mu } => {
                let (c11, c22, c12, c33) = (2.0 * e[0] + 1.0, 2.0 * e[1] + 1.0, e[2], 2.0 * e[3] + 1.0);
                let det2 = c11 * c22 - c12 * c12;
                let det_c = det2 * c33;
                if det2 <= 0.0 || c33 <= 0.0 || !det_c.is_finite() {
                    return Err(MaterialError::InvertedJacobian(det_c));
                }
                let ln_j = 0.5 * det_c.ln();
                let (i11, i22, i12, i33) = (c22 / det2, c11 / det2, -c12 / det2, 1.0 / c33);
                let g = lambda * ln_j;
                let s = Vector4::new(
                    mu * (1.0 - i11) + g * i11,
                    mu * (1.0 - i22) + g * i22,
                    -mu * i12 + g * i12,
                    mu * (1.0 - i33) + g * i33,
                );
                let ci = [[i11, i12, 0.0], [i12, i22, 0.0], [0.0, 0.0, i33]];
                let w = 0.5 * mu * (c11 + c22 + c33 - 3.0) - mu * ln_j + 0.5 * lambda * ln_j * ln_j;
                Ok((s, neo_hooke_tangent(lambda, mu, ln_j, &ci), w))
            }
        }
    }

    /// The plane-stress law (`S33 = 0`) for the in-plane strain `e = [E11, E22, 2E12]`: the
    /// 3D law with `E33` condensed (module documentation).
    pub fn plane_stress_state(&self, e: &Vector3<f64>) -> Result<PlaneStressState, MaterialError> {
        let e33 = match *self {
            Material::SaintVenantKirchhoff { lambda, mu } => -lambda * (e[0] + e[1]) / (lambda + 2.0 * mu),
            Material::NeoHookean { lambda, mu } => {
                let det2 = (2.0 * e[0] + 1.0) * (2.0 * e[1] + 1.0) - e[2] * e[2];
                if det2 <= 0.0 || !det2.is_finite() {
                    return Err(MaterialError::InvertedJacobian(det2));
                }
                let ln2 = det2.ln();
                let mut t = (-ln2).max(0.0);
                for _ in 0..100 {
                    let et = t.exp();
                    let dt = (mu * (et - 1.0) + 0.5 * lambda * (ln2 + t)) / (mu * et + 0.5 * lambda);
                    t -= dt;
                    if dt.abs() <= 4.0 * f64::EPSILON * (1.0 + t.abs()) {
                        break;
                    }
                }
                0.5 * (t.exp() - 1.0)
            }
        };
        let (s, d, w) = self.stress_tangent_4(&Vector4::new(e[0], e[1], e[2], e33))?;
        let mut tangent = Matrix3::zeros();
        for a in 0..3 {
            for b in 0..3 {
                tangent[(a, b)] = d[(a, b)] - d[(a, 3)] * d[(3, b)] / d[(3, 3)];
            }
        }
        Ok(PlaneStressState {
            stress: Vector3::new(s[0], s[1], s[2]),
            tangent,
            energy: w,
            e33,
        })
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

    /// `S = ∂W/∂E` and `D = ∂S/∂E` by central differences (h = 1e-6) at a finite strain,
    /// to 1e-6 of `|S|` and 1e-5 of `|D|`; `D` symmetric.
    #[test]
    fn the_3d_law_matches_finite_differences() {
        let e = Vector4::new(0.03, -0.02, 0.05, 0.04);
        for m in materials() {
            let (s, d, _) = m.stress_tangent_4(&e).unwrap();
            let h = 1e-6;
            for b in 0..4 {
                let (mut ep, mut em) = (e, e);
                ep[b] += h;
                em[b] -= h;
                let (sp, _, wp) = m.stress_tangent_4(&ep).unwrap();
                let (sm, _, wm) = m.stress_tangent_4(&em).unwrap();
                assert!(((wp - wm) / (2.0 * h) - s[b]).abs() < 1e-6 * s.norm(), "{m:?} S[{b}]");
                let ds = (sp - sm) / (2.0 * h);
                for a in 0..4 {
                    assert!((ds[a] - d[(a, b)]).abs() < 1e-5 * d.norm(), "{m:?} D[{a},{b}]");
                }
            }
            assert!((d - d.transpose()).norm() < 1e-12 * d.norm());
        }
    }

    /// With `E33 = 0` the 3D law is the plane-strain law of `material.rs` (to round-off).
    #[test]
    fn the_3d_law_with_no_out_of_plane_strain_is_plane_strain() {
        let e = Vector3::new(0.03, -0.02, 0.05);
        for m in materials() {
            let (s, d, w) = m.stress_tangent_4(&Vector4::new(e[0], e[1], e[2], 0.0)).unwrap();
            let (s2, d2) = m.stress_tangent(&e).unwrap();
            assert!((Vector3::new(s[0], s[1], s[2]) - s2).norm() < 1e-12 * s2.norm());
            assert!((d.fixed_view::<3, 3>(0, 0) - d2).norm() < 1e-12 * d2.norm());
            assert!((s[3] - m.out_of_plane_stress(&e).unwrap()).abs() < 1e-12 * s2.norm());
            assert!((w - m.energy(&e).unwrap()).abs() < 1e-12 * w.abs());
        }
    }

    /// Plane stress: `S33 = 0` to round-off, `S = ∂W/∂E` and `D̄ = ∂S/∂E` by central
    /// differences (1e-6 of `|S|`, 1e-5 of `|D̄|`), at a finite strain and in compression;
    /// St. Venant–Kirchhoff's `D̄` is the closed-form plane-stress matrix with
    /// `λ̄ = 2λμ/(λ + 2μ)` (1e-12).
    #[test]
    fn plane_stress_condensation_matches_finite_differences() {
        for e in [Vector3::new(0.03, -0.02, 0.05), Vector3::new(-0.2, 0.1, -0.15)] {
            for m in materials() {
                let st = m.plane_stress_state(&e).unwrap();
                let (s4, _, _) = m.stress_tangent_4(&Vector4::new(e[0], e[1], e[2], st.e33)).unwrap();
                assert!(s4[3].abs() < 1e-12 * st.stress.norm(), "{m:?}: S33 = {}", s4[3]);
                let h = 1e-6;
                for b in 0..3 {
                    let (mut ep, mut em) = (e, e);
                    ep[b] += h;
                    em[b] -= h;
                    let (p, q) = (m.plane_stress_state(&ep).unwrap(), m.plane_stress_state(&em).unwrap());
                    let dw = (p.energy - q.energy) / (2.0 * h);
                    assert!((dw - st.stress[b]).abs() < 1e-6 * st.stress.norm(), "{m:?} S[{b}]");
                    let ds = (p.stress - q.stress) / (2.0 * h);
                    for a in 0..3 {
                        let err = (ds[a] - st.tangent[(a, b)]).abs();
                        assert!(err < 1e-5 * st.tangent.norm(), "{m:?} D[{a},{b}]");
                    }
                }
                if let Material::SaintVenantKirchhoff { lambda, mu } = m {
                    let lb = 2.0 * lambda * mu / (lambda + 2.0 * mu);
                    let mut dps = Matrix3::new(lb + 2.0 * mu, lb, 0.0, lb, lb + 2.0 * mu, 0.0, 0.0, 0.0, mu);
                    dps -= st.tangent;
                    assert!(dps.norm() < 1e-12 * st.tangent.norm());
                }
            }
        }
    }

    /// Neo-Hooke in plane stress, uniaxial stretch `λ₁ = 1.3` with `S22 = 0` found by
    /// bisection on the 3D law (`λ₂ = λ₃` by symmetry): the condensed law gives the same
    /// `C33` and `S11` (1e-10).
    #[test]
    fn neo_hooke_plane_stress_agrees_with_an_independent_uniaxial_solution() {
        let m = materials()[1];
        let l1: f64 = 1.3;
        let s22 = |l2: f64| {
            let e = Vector4::new(0.5 * (l1 * l1 - 1.0), 0.5 * (l2 * l2 - 1.0), 0.0, 0.5 * (l2 * l2 - 1.0));
            m.stress_tangent_4(&e).unwrap().0
        };
        let (mut lo, mut hi) = (0.5, 1.0);
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if s22(mid)[1] > 0.0 {
                hi = mid;
            } else {
                lo = mid;
            }
        }
        let l2 = 0.5 * (lo + hi);
        let st = m
            .plane_stress_state(&Vector3::new(0.5 * (l1 * l1 - 1.0), 0.5 * (l2 * l2 - 1.0), 0.0))
            .unwrap();
        assert!(((1.0 + 2.0 * st.e33) - l2 * l2).abs() < 1e-10);
        assert!((st.stress[0] - s22(l2)[0]).abs() < 1e-10 * st.stress[0].abs());
        assert!(st.stress[1].abs() < 1e-8 * st.stress[0].abs());
    }
}
