//! The quadrilaterals of [`super`] in plane stress and in the axisymmetric setting.
//!
//! [`Kinematics`] is a field of the element's [`QuadGeometry`] (made by
//! [`QuadGeometry::with_kinematics`]); [`super::quad_residual_tangent_with`] branches on it
//! once per element, after the stabilised kinds have split themselves into their `Q4` and
//! `Q4Eas` parts, so every [`super::ElementKind`] exists in every setting and plane strain
//! runs the code it ran before. The formulation is the plane-strain one (total Lagrangian,
//! 2×2 Gauss points, EAS-4 statically condensed, local Newton iteration on `α`) with:
//!
//! * **Plane stress** (`thickness t`): the law with `S33 = 0` condensed per Gauss point
//!   (`material_models.rs`), volume weight `t · det J`; forces are totals for the plate
//!   (force per unit thickness times `t`).
//! * **Axisymmetric** (`x = r ≥ 0`, `y = z`, the axis `r = 0`): `F = [[F_rr, F_rz, 0],
//!   [F_zr, F_zz, 0], [0, 0, r/R]]`, strain `[E_rr, E_zz, 2E_rz, E_θθ]` with the hoop strain
//!   `E_θθ = u_r/R + ½ (u_r/R)²` (`R = Σ N_I R_I` the reference radius at the Gauss point,
//!   `u_r = Σ N_I u_rI`), `δE_θθ = (1 + u_r/R) Σ N_I δu_rI / R`, and the geometric
//!   stiffness gains `S_θθ N_I N_J / R²` on the radial DOFs; volume weight `2π R det J`:
//!   **residuals, tangents, energies and hence reactions are totals over the full circle**
//!   (per radian: divide by 2π). The enhanced strains enrich the in-plane components only,
//!   `Ẽ = (j₀ R₀)/(j R) T₀ M α` (hoop row zero; `R₀` the radius at the centre): the factor
//!   `R₀/R` makes `∫ Gᵀ S dV = 0` for a constant stress, the axisymmetric form of the
//!   condition `∫ M dξ dη = 0` by which EAS passes the patch test (Simo & Rifai 1990, §3,
//!   with `j R` the volume Jacobian of the axisymmetric element). Without it the linear
//!   radial field `u_r = a r, u_z = b z` (constant stress, `S_rr = S_θθ`) is not
//!   reproduced (measured with the factor taken out: the interior displacements of the
//!   MacNeal–Harder patch touching the axis off by 9.9e-6 at `a = 1e-3`, ≈ 4 % of `u`; the
//!   axial force of a stretched hollow cylinder 0.023 % low; with it both to round-off).
//!
//! A node on the axis (`R_I = 0`) is admissible (the Gauss points have `R > 0`); its radial
//! displacement must be zero, which the kernel does not impose: the model is to fix
//! `u_r = 0` at nodes with `r = 0` (proposed: automatically, when a body is axisymmetric).

use super::{kinematics, ElementError, GaussGeom, Material, QuadGeometry, EAS_STRAIN_TOLERANCE, GAUSS, XI_NODES};
use nalgebra::{Matrix4, SMatrix, SVector, Vector3, Vector4};
use serde::{Deserialize, Serialize};

/// How the 2D model stands for the 3D body (per body).
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "kebab-case", tag = "model")]
pub enum Kinematics {
    /// `E33 = 0`; forces per unit thickness (the default, and the only setting before).
    #[default]
    PlaneStrain,
    /// `S33 = 0`; forces for a plate of this (reference) thickness.
    PlaneStress { thickness: f64 },
    /// A body of revolution about `x = 0` (`x = r ≥ 0`, `y = z`); forces are totals over
    /// the full circle.
    Axisymmetric,
}

impl Kinematics {
    /// The setting as a scene writes it, with the measure of its forces: `plane-strain
    /// (per unit thickness)`, `plane-stress, thickness 0.01 (forces for the plate)`,
    /// `axisymmetric (forces are totals over the full circle)`.
    pub fn label(self) -> String {
        match self {
            Kinematics::PlaneStrain => "plane-strain (forces per unit thickness)".into(),
            Kinematics::PlaneStress { thickness } => {
                format!("plane-stress, thickness {thickness} (forces for the plate)")
            }
            Kinematics::Axisymmetric => "axisymmetric (forces are totals over the full circle)".into(),
        }
    }

    /// `plane-strain`, `plane-stress` or `axisymmetric`.
    pub fn name(self) -> &'static str {
        match self {
            Kinematics::PlaneStrain => "plane-strain",
            Kinematics::PlaneStress { .. } => "plane-stress",
            Kinematics::Axisymmetric => "axisymmetric",
        }
    }
}

/// What the kernel needs of the setting beyond the plane-strain geometry.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum ModelGeometry {
    PlaneStrain,
    PlaneStress {
        thickness: f64,
    },
    /// `radius`: `R` at the four Gauss points; `centre`: `R₀`.
    Axisymmetric {
        radius: [f64; 4],
        centre: f64,
    },
}

/// Shape-function values at Gauss point `q`.
fn shape(q: usize) -> [f64; 4] {
    let (xi, eta) = GAUSS[q];
    XI_NODES.map(|(xa, ea)| 0.25 * (1.0 + xa * xi) * (1.0 + ea * eta))
}

impl ModelGeometry {
    /// The setting's data for reference nodes `x`: a thickness must be positive and finite,
    /// an axisymmetric element must lie in `r ≥ 0`.
    pub(super) fn new(kinematics: Kinematics, x: &[[f64; 2]; 4]) -> Result<Self, ElementError> {
        Ok(match kinematics {
            Kinematics::PlaneStrain => ModelGeometry::PlaneStrain,
            Kinematics::PlaneStress { thickness } => {
                if !(thickness > 0.0 && thickness.is_finite()) {
                    return Err(ElementError::BadThickness(thickness));
                }
                ModelGeometry::PlaneStress { thickness }
            }
            Kinematics::Axisymmetric => {
                if let Some(r) = x.iter().map(|p| p[0]).find(|r| r.is_nan() || *r < 0.0) {
                    return Err(ElementError::NegativeRadius(r));
                }
                let radius = std::array::from_fn(|q| shape(q).iter().zip(x).map(|(n, p)| n * p[0]).sum());
                let centre = 0.25 * x.iter().map(|p| p[0]).sum::<f64>();
                ModelGeometry::Axisymmetric { radius, centre }
            }
        })
    }

    pub(super) fn kinematics(&self) -> Kinematics {
        match *self {
            ModelGeometry::PlaneStrain => Kinematics::PlaneStrain,
            ModelGeometry::PlaneStress { thickness } => Kinematics::PlaneStress { thickness },
            ModelGeometry::Axisymmetric { .. } => Kinematics::Axisymmetric,
        }
    }

    /// `(w_q / det J_q, s_q)`: the volume weight per unit `det J` and the scale of the EAS
    /// interpolation at Gauss point `q` (`G_q = s_q (j₀/j) T₀ M`).
    fn weights(&self, q: usize) -> (f64, f64) {
        match *self {
            ModelGeometry::PlaneStrain => (1.0, 1.0),
            ModelGeometry::PlaneStress { thickness } => (thickness, 1.0),
            ModelGeometry::Axisymmetric { radius, centre } => {
                (2.0 * std::f64::consts::PI * radius[q], centre / radius[q])
            }
        }
    }
}

/// One Gauss point of the element in a setting with `NS` strain components.
struct Point<const NS: usize> {
    /// `δE_c = B δu`.
    b: SMatrix<f64, NS, 8>,
    /// `E_c`.
    ec: SVector<f64, NS>,
    /// `Ẽ = G α`.
    g: SMatrix<f64, NS, 4>,
    /// volume weight
    w: f64,
    /// `∂N_I/∂X`, for the in-plane geometric stiffness.
    grad: [[f64; 4]; 2],
    /// `N_I / R` (axisymmetric; zero in plane stress), for the hoop geometric stiffness.
    n_r: [f64; 4],
}

/// The in-plane part of a Gauss point: `B`, `E_c` and `G` in their first three rows.
fn in_plane<const NS: usize>(gq: &GaussGeom, u: &[[f64; 2]; 4], w: f64, scale: f64) -> Point<NS> {
    let k = kinematics(gq, u);
    let mut p = Point {
        b: SMatrix::zeros(),
        ec: SVector::zeros(),
        g: SMatrix::zeros(),
        w: w * gq.dv,
        grad: gq.grad,
        n_r: [0.0; 4],
    };
    for a in 0..3 {
        p.ec[a] = k.ec[a];
        for i in 0..8 {
            p.b[(a, i)] = k.b[a][i];
        }
        for m in 0..4 {
            p.g[(a, m)] = scale * gq.g[a][m];
        }
    }
    p
}

/// The Gauss points of a plane-stress element (strain `[E11, E22, 2E12]`).
fn plane_stress_points(geo: &QuadGeometry, u: &[[f64; 2]; 4]) -> [Point<3>; 4] {
    std::array::from_fn(|q| {
        let (w, s) = geo.model.weights(q);
        in_plane(&geo.gp[q], u, w, s)
    })
}

/// The Gauss points of an axisymmetric element (strain `[E_rr, E_zz, 2E_rz, E_θθ]`); fails
/// where the hoop stretch `1 + u_r/R` is not positive.
fn axisymmetric_points(
    geo: &QuadGeometry,
    u: &[[f64; 2]; 4],
    radius: &[f64; 4],
) -> Result<[Point<4>; 4], ElementError> {
    let mut pts: [Point<4>; 4] = std::array::from_fn(|q| {
        let (w, s) = geo.model.weights(q);
        in_plane(&geo.gp[q], u, w, s)
    });
    for (q, p) in pts.iter_mut().enumerate() {
        let n = shape(q);
        let rq = radius[q];
        let ur_r = n.iter().zip(u).map(|(n, ui)| n * ui[0]).sum::<f64>() / rq;
        let stretch = 1.0 + ur_r;
        if stretch <= 0.0 || !stretch.is_finite() {
            return Err(ElementError::Inverted(stretch));
        }
        p.ec[3] = ur_r + 0.5 * ur_r * ur_r;
        for (i, ni) in n.iter().enumerate() {
            p.n_r[i] = ni / rq;
            p.b[(3, 2 * i)] = stretch * p.n_r[i];
        }
    }
    Ok(pts)
}

/// Sums of one pass over the Gauss points.
struct Sums {
    ru: SVector<f64, 8>,
    kuu: SMatrix<f64, 8, 8>,
    kua: SMatrix<f64, 8, 4>,
    kaa: Matrix4<f64>,
    ra: Vector4<f64>,
    energy: f64,
}

/// The law of a setting: `(S, D, W)` of the strain `e`.
type Law<'a, const NS: usize> =
    &'a dyn Fn(&SVector<f64, NS>) -> Result<(SVector<f64, NS>, SMatrix<f64, NS, NS>, f64), ElementError>;

/// One pass at the enhanced parameters `al` (all terms; `penalty` on `α` as in plane strain):
/// `R_u = Σ w Bᵀ S`, `K_uu = Σ w (Bᵀ D B + δ_ab ∇N_I·S ∇N_J [+ δ_ar δ_br S_θθ N_I N_J/R²])`,
/// `K_uα = Σ w Bᵀ D G`, `K_αα = Σ w Gᵀ D G`, `R_α = Σ w Gᵀ S`, `Π = Σ w W`.
// index loops: node pairs walk the gradients, the hoop factors and the DOFs together
#[allow(clippy::needless_range_loop)]
fn pass<const NS: usize>(
    law: Law<NS>,
    pts: &[Point<NS>; 4],
    al: &Vector4<f64>,
    penalty: &[f64; 4],
) -> Result<Sums, ElementError> {
    let mut t = Sums {
        ru: SVector::zeros(),
        kuu: SMatrix::zeros(),
        kua: SMatrix::zeros(),
        kaa: Matrix4::zeros(),
        ra: Vector4::zeros(),
        energy: 0.0,
    };
    for p in pts {
        let e = p.ec + p.g * al;
        let (s, d, w) = law(&e)?;
        let w_ = p.w;
        t.energy += w_ * w;
        t.ru += w_ * p.b.transpose() * s;
        t.ra += w_ * p.g.transpose() * s;
        let db = d * p.b;
        let dg = d * p.g;
        t.kuu += w_ * p.b.transpose() * db;
        t.kua += w_ * p.b.transpose() * dg;
        t.kaa += w_ * p.g.transpose() * dg;
        let gr = &p.grad;
        for ni in 0..4 {
            let sgx = w_ * (s[0] * gr[0][ni] + s[2] * gr[1][ni]);
            let sgy = w_ * (s[2] * gr[0][ni] + s[1] * gr[1][ni]);
            for nj in 0..4 {
                let v = sgx * gr[0][nj] + sgy * gr[1][nj];
                t.kuu[(2 * ni, 2 * nj)] += v;
                t.kuu[(2 * ni + 1, 2 * nj + 1)] += v;
                if NS == 4 {
                    t.kuu[(2 * ni, 2 * nj)] += w_ * s[3] * p.n_r[ni] * p.n_r[nj];
                }
            }
        }
    }
    for (m, &pm) in penalty.iter().enumerate().filter(|(_, p)| **p != 0.0) {
        t.ra[m] += pm * al[m];
        t.kaa[(m, m)] += pm;
        t.energy += 0.5 * pm * al[m] * al[m];
    }
    Ok(t)
}

/// The element of a setting with `NS` strain components: local Newton iteration on `α`
/// (EAS) to `max_q ‖G_q δα‖∞ ≤` [`EAS_STRAIN_TOLERANCE`] (or stagnation below 1e-12),
/// then `R* = R_u − K_uα K_αα⁻¹ R_α`, `K* = K_uu − K_uα K_αα⁻¹ K_αu`.
fn condensed<const NS: usize>(
    law: Law<NS>,
    pts: &[Point<NS>; 4],
    eas: bool,
    penalty: &[f64; 4],
    alpha: &mut [f64; 4],
) -> Result<(SVector<f64, 8>, SMatrix<f64, 8, 8>, f64), ElementError> {
    if !eas {
        let t = pass(law, pts, &Vector4::zeros(), &[0.0; 4])?;
        return Ok((t.ru, t.kuu, t.energy));
    }
    let mut al = Vector4::from(*alpha);
    let mut last = f64::INFINITY;
    for _ in 0..25 {
        let t = pass(law, pts, &al, penalty)?;
        let inv = t.kaa.try_inverse().ok_or(ElementError::EasSingular)?;
        let da = inv * t.ra;
        let step = pts.iter().map(|p| (p.g * da).amax()).fold(0.0, f64::max);
        if step <= EAS_STRAIN_TOLERANCE || (step >= last && step <= 1e-12) {
            alpha.copy_from_slice(al.as_slice());
            let w = t.kua * inv;
            let k = t.kuu - w * t.kua.transpose();
            return Ok((t.ru - w * t.ra, 0.5 * (k + k.transpose()), t.energy));
        }
        al -= da;
        last = step;
    }
    Err(ElementError::EasNotConverged(last))
}

/// Residual, tangent and energy of an element whose geometry is not plane strain (the
/// branch of [`super::quad_residual_tangent_with`]); `eas`: `Q4Eas`, else `Q4`.
pub(super) fn residual_tangent(
    eas: bool,
    material: &Material,
    geo: &QuadGeometry,
    u: &[[f64; 2]; 4],
    alpha: &mut [f64; 4],
    r: &mut [f64; 8],
    k: Option<&mut [f64; 64]>,
) -> Result<f64, ElementError> {
    let (ru, kuu, energy) = match geo.model {
        ModelGeometry::PlaneStrain => unreachable!("plane strain runs the plane-strain kernel"),
        ModelGeometry::PlaneStress { .. } => {
            let law = |e: &Vector3<f64>| {
                let st = material.plane_stress_state(e)?;
                Ok((st.stress, st.tangent, st.energy))
            };
            condensed(&law, &plane_stress_points(geo, u), eas, &geo.penalty, alpha)?
        }
        ModelGeometry::Axisymmetric { radius, .. } => {
            let law = |e: &Vector4<f64>| Ok(material.stress_tangent_4(e)?);
            condensed(&law, &axisymmetric_points(geo, u, &radius)?, eas, &geo.penalty, alpha)?
        }
    };
    r.copy_from_slice(ru.as_slice());
    if let Some(k) = k {
        // row-major (the matrix is symmetric: the column-major slice is the same)
        k.copy_from_slice(kuu.as_slice());
    }
    Ok(energy)
}

/// `K⁰_mm` of enhanced mode `m` (for the hourglass holds) in a setting other than plane
/// strain: `Σ w_q G_qᵀ D⁰ G_q` with the setting's weights and initial tangent.
pub(super) fn mode_stiffness(geo: &QuadGeometry, material: &Material, m: usize) -> f64 {
    let d0 = match geo.model {
        ModelGeometry::PlaneStress { .. } => material.plane_stress_state(&Vector3::zeros()).map(|s| s.tangent),
        _ => material
            .stress_tangent_4(&Vector4::zeros())
            .map(|(_, d, _)| d.fixed_view::<3, 3>(0, 0).into_owned()),
    };
    let Ok(d0) = d0 else { return 0.0 };
    (0..4)
        .map(|q| {
            let (w, s) = geo.model.weights(q);
            let gq = &geo.gp[q];
            let gm = s * Vector3::new(gq.g[0][m], gq.g[1][m], gq.g[2][m]);
            w * gq.dv * gm.dot(&(d0 * gm))
        })
        .sum()
}
