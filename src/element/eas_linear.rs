//! Closed-form enhanced-strain parameters for a material with a constant tangent
//! (St. Venant–Kirchhoff).
//!
//! With the enhancement added to the Green–Lagrange strain, `E = E_c(u) + G α`, and
//! `S = D E` with a constant `D`, the enhanced-strain equation of [`super::quad`],
//!
//! `R_α(u, α) = Σ_q dv_q G_qᵀ D (E_c,q + G_q α) = 0`,
//!
//! is linear in `α` with the constant matrix `K_αα = Σ_q dv_q G_qᵀ D G_q`, so
//!
//! `α(u) = Σ_q P_q E_c,q`, `P_q = −K_αα⁻¹ dv_q (D G_q)ᵀ` (4×3 per Gauss point), with the
//! penalty of held hourglass modes (if any) on `K_αα`'s diagonal.
//!
//! `P_q` and `K_αα⁻¹` depend on the reference geometry and the material only: they are
//! computed once per element, and the kernel evaluates `α` from the compatible strains
//! before its single full pass over the Gauss points, instead of a first pass that only
//! finds `R_α` and `K_αα` at the previous `α` (the local Newton step of the general path,
//! which gives the same `α` up to round-off). The full pass still evaluates `R_α` and the
//! kernel falls back to the local Newton iteration if it is not at round-off.

use super::material::Material;
use nalgebra::Matrix4;

/// The precondensation of one element for one material (see the module documentation).
#[derive(Debug, Clone, Copy)]
pub(crate) struct LinearEas {
    /// The material it was computed for (the kernel uses it for no other).
    pub material: Material,
    /// `P_q` (4×3) at each Gauss point.
    pub p: [[[f64; 3]; 4]; 4],
    /// `K_αα⁻¹`.
    pub kaa_inv: Matrix4<f64>,
}

impl LinearEas {
    /// `None` unless the material's tangent is constant and `K_αα` is invertible.
    /// `gauss`: `(dv_q, G_q)` at the four Gauss points.
    pub fn new(material: &Material, gauss: &[(f64, [[f64; 4]; 3]); 4], penalty: &[f64; 4]) -> Option<Self> {
        let d = material.constant_tangent()?;
        let mut dg = [[[0.0; 4]; 3]; 4];
        let mut kaa = Matrix4::zeros();
        for ((dv, g), dgq) in gauss.iter().zip(dg.iter_mut()) {
            for (a, row) in dgq.iter_mut().enumerate() {
                for (m, v) in row.iter_mut().enumerate() {
                    *v = dv * (d[(a, 0)] * g[0][m] + d[(a, 1)] * g[1][m] + d[(a, 2)] * g[2][m]);
                }
            }
            for m in 0..4 {
                for n in 0..4 {
                    kaa[(m, n)] += g[0][m] * dgq[0][n] + g[1][m] * dgq[1][n] + g[2][m] * dgq[2][n];
                }
            }
        }
        for (m, p) in penalty.iter().enumerate() {
            kaa[(m, m)] += p;
        }
        let kaa_inv: Matrix4<f64> = kaa.try_inverse()?;
        if !kaa_inv.iter().all(|v| v.is_finite()) {
            return None;
        }
        let mut p = [[[0.0; 3]; 4]; 4];
        for (pq, dgq) in p.iter_mut().zip(&dg) {
            for (m, row) in pq.iter_mut().enumerate() {
                for (a, v) in row.iter_mut().enumerate() {
                    *v = -(0..4).map(|n| kaa_inv[(m, n)] * dgq[a][n]).sum::<f64>();
                }
            }
        }
        Some(LinearEas {
            material: *material,
            p,
            kaa_inv,
        })
    }

    /// `α = Σ_q P_q E_c,q` from the compatible strains at the Gauss points.
    #[inline(always)]
    pub fn alpha(&self, ec: [&[f64; 3]; 4]) -> [f64; 4] {
        let mut al = [0.0; 4];
        for (pq, e) in self.p.iter().zip(ec) {
            for (a, row) in al.iter_mut().zip(pq) {
                *a += row[0] * e[0] + row[1] * e[1] + row[2] * e[2];
            }
        }
        al
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::element::material::lame;
    use nalgebra::Vector3;

    #[test]
    fn the_constant_tangent_is_the_materials() {
        let (l, m) = lame(2.1e4, 0.3);
        let mat = Material::SaintVenantKirchhoff { lambda: l, mu: m };
        let d = mat.constant_tangent().unwrap();
        for e in [Vector3::new(0.01, -0.02, 0.03), Vector3::new(-0.3, 0.1, 0.0)] {
            let (_, dm) = mat.stress_tangent(&e).unwrap();
            assert_eq!(d, dm);
        }
        assert!(Material::NeoHookean { lambda: l, mu: m }.constant_tangent().is_none());
    }
}
