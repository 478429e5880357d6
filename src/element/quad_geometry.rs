//! The reference geometry of a quadrilateral: shape-function derivatives, Jacobians, the
//! Gauss points' gradients and enhanced-strain interpolation, computed once per element
//! ([`QuadGeometry`]), and the element's smallest `det F`.

use super::*;

/// The smallest `det F` of the compatible deformation over the Gauss points of an element
/// (`F = I + Σ u_I ⊗ ∇N_I`). A folded element has `det F < 0` where it folds while
/// `C = FᵀF` stays positive definite, so a law written in `C` or `E` (Neo-Hooke's
/// `ln J = ½ ln det C`, St. Venant–Kirchhoff) cannot see it: the check is the kernel's.
pub fn min_det_f(geo: &QuadGeometry, u: &[[f64; 2]; 4]) -> f64 {
    geo.gp
        .iter()
        .map(|g| {
            let mut f = [[1.0, 0.0], [0.0, 1.0]];
            for (i, ui) in u.iter().enumerate() {
                for (r, fr) in f.iter_mut().enumerate() {
                    fr[0] += ui[r] * g.grad[0][i];
                    fr[1] += ui[r] * g.grad[1][i];
                }
            }
            f[0][0] * f[1][1] - f[0][1] * f[1][0]
        })
        .fold(f64::INFINITY, f64::min)
}

pub(crate) const XI_NODES: [(f64, f64); 4] = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)];
pub(super) const G: f64 = 0.577_350_269_189_625_8; // 1/sqrt(3)
pub(crate) const GAUSS: [(f64, f64); 4] = [(-G, -G), (G, -G), (G, G), (-G, G)];

/// Shape-function derivatives with respect to `(ξ, η)`: `[[∂N_I/∂ξ], [∂N_I/∂η]]`.
pub(crate) fn dn_dxi(xi: f64, eta: f64) -> [[f64; 4]; 2] {
    let mut d = [[0.0; 4]; 2];
    for (i, &(xa, ea)) in XI_NODES.iter().enumerate() {
        d[0][i] = 0.25 * xa * (1.0 + ea * eta);
        d[1][i] = 0.25 * ea * (1.0 + xa * xi);
    }
    d
}

/// Jacobian `J_ab = ∂X_a/∂ξ_b`.
pub(crate) fn jacobian(x: &[[f64; 2]; 4], d: &[[f64; 4]; 2]) -> Matrix2<f64> {
    let mut j = Matrix2::zeros();
    for i in 0..4 {
        for a in 0..2 {
            for b in 0..2 {
                j[(a, b)] += x[i][a] * d[b][i];
            }
        }
    }
    j
}

/// Per-Gauss-point quantities of the reference configuration (independent of `u` and `α`).
#[derive(Debug, Clone, Copy)]
pub(super) struct GaussGeom {
    /// `∂N_I/∂X_a`
    pub(super) grad: [[f64; 4]; 2],
    /// `j · w` (weights are 1 for 2×2 Gauss)
    pub(super) dv: f64,
    /// `Ẽ = G α` (3×4, zero for [`ElementKind::Q4`])
    pub(super) g: [[f64; 4]; 3],
}

/// Reference geometry of one quadrilateral at its four Gauss points: shape-function
/// gradients, volume weights and the EAS interpolation `G = (j₀/j) T₀ M`. It depends on the
/// reference coordinates only, so an assembler computes it once per element.
#[derive(Debug, Clone, Copy)]
pub struct QuadGeometry {
    pub(super) gp: [GaussGeom; 4],
    /// The columns of the centre Jacobian, `∂X/∂ξ` and `∂X/∂η` (the element's two natural
    /// axes, half their side lengths long).
    pub(super) axes: [[f64; 2]; 2],
    /// Penalty `p_m` on each enhanced parameter, `Π += ½ Σ p_m α_m²` (zero but where the
    /// hourglass modes of a [`ElementKind::Q4EasSafe`] element are held: `quad_stab.rs`,
    /// `hourglass_holds`).
    pub(super) penalty: [f64; 4],
    /// Closed-form `α(u)` for one material with a constant tangent (see
    /// [`QuadGeometry::for_material`]).
    pub(super) linear: Option<LinearEas>,
    /// Plane strain, plane stress or axisymmetric (`quad_models.rs`).
    pub(super) model: ModelGeometry,
}

impl QuadGeometry {
    /// Geometry of the element with reference nodes `x` (counter-clockwise); fails on a
    /// non-positive Jacobian at the centre or a Gauss point.
    pub fn new(kind: ElementKind, x: &[[f64; 2]; 4]) -> Result<Self, ElementError> {
        let d0 = dn_dxi(0.0, 0.0);
        let j0 = jacobian(x, &d0);
        let det0 = j0.determinant();
        if det0 <= 0.0 {
            return Err(ElementError::BadGeometry(det0));
        }
        let a = j0.try_inverse().ok_or(ElementError::BadGeometry(det0))?;
        // T0: covariant (ξ,η) Voigt strain -> Cartesian Voigt strain (engineering shear).
        let t0 = Matrix3::new(
            a[(0, 0)] * a[(0, 0)],
            a[(1, 0)] * a[(1, 0)],
            a[(0, 0)] * a[(1, 0)],
            a[(0, 1)] * a[(0, 1)],
            a[(1, 1)] * a[(1, 1)],
            a[(0, 1)] * a[(1, 1)],
            2.0 * a[(0, 0)] * a[(0, 1)],
            2.0 * a[(1, 0)] * a[(1, 1)],
            a[(0, 0)] * a[(1, 1)] + a[(1, 0)] * a[(0, 1)],
        );
        let mk = |&(xi, eta): &(f64, f64)| -> Result<GaussGeom, ElementError> {
            let d = dn_dxi(xi, eta);
            let jm = jacobian(x, &d);
            let det = jm.determinant();
            if det <= 0.0 {
                return Err(ElementError::BadGeometry(det));
            }
            let jinv = jm.try_inverse().ok_or(ElementError::BadGeometry(det))?;
            let mut grad = [[0.0; 4]; 2];
            for i in 0..4 {
                for a2 in 0..2 {
                    // ∂N/∂X_a = Σ_b ∂N/∂ξ_b (J⁻¹)_ba
                    grad[a2][i] = d[0][i] * jinv[(0, a2)] + d[1][i] * jinv[(1, a2)];
                }
            }
            let mut g = [[0.0; 4]; 3];
            if kind != ElementKind::Q4 {
                // (j₀/j) T₀ M with M = [[ξ,0,0,0],[0,η,0,0],[0,0,ξ,η]]
                let m = [[xi, 0.0, 0.0, 0.0], [0.0, eta, 0.0, 0.0], [0.0, 0.0, xi, eta]];
                for (a, row) in g.iter_mut().enumerate() {
                    for (c, v) in row.iter_mut().enumerate() {
                        *v = (det0 / det) * (0..3).map(|b| t0[(a, b)] * m[b][c]).sum::<f64>();
                    }
                }
            }
            Ok(GaussGeom { grad, dv: det, g })
        };
        Ok(QuadGeometry {
            gp: [mk(&GAUSS[0])?, mk(&GAUSS[1])?, mk(&GAUSS[2])?, mk(&GAUSS[3])?],
            axes: [[j0[(0, 0)], j0[(1, 0)]], [j0[(0, 1)], j0[(1, 1)]]],
            penalty: [0.0; 4],
            linear: None,
            model: ModelGeometry::PlaneStrain,
        })
    }

    /// [`QuadGeometry::new`] plus, for an EAS element of a material with a constant tangent
    /// (St. Venant–Kirchhoff), the closed-form enhanced parameters of
    /// `element/eas_linear.rs`: the kernel then needs one pass over the Gauss points instead
    /// of two when called with that material (with any other it takes the general path).
    pub fn for_material(kind: ElementKind, material: &Material, x: &[[f64; 2]; 4]) -> Result<Self, ElementError> {
        let mut geo = Self::new(kind, x)?;
        if kind != ElementKind::Q4 {
            geo.linear = LinearEas::new(material, &geo.gp.map(|q| (q.dv, q.g)), &geo.penalty);
        }
        Ok(geo)
    }

    /// The geometry of an element in the given setting: [`QuadGeometry::for_material`] in
    /// plane strain; in plane stress and the axisymmetric setting the same reference
    /// geometry with the setting's data (`quad_models.rs`; no closed-form `α`: the local
    /// Newton iteration is used). Fails also on a non-positive thickness and on a node at
    /// `r < 0`.
    pub fn with_kinematics(
        kind: ElementKind,
        material: &Material,
        kinematics: Kinematics,
        x: &[[f64; 2]; 4],
    ) -> Result<Self, ElementError> {
        if kinematics == Kinematics::PlaneStrain {
            return Self::for_material(kind, material, x);
        }
        let mut geo = Self::new(kind, x)?;
        geo.model = ModelGeometry::new(kinematics, x)?;
        Ok(geo)
    }

    /// The setting of the element (plane strain unless made by
    /// [`QuadGeometry::with_kinematics`]).
    pub fn kinematics(&self) -> Kinematics {
        self.model.kinematics()
    }
}
