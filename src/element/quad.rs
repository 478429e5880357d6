//! Four-node plane-strain quadrilateral, total Lagrangian, with optional enhanced assumed
//! strains (EAS) — the 2D counterpart of the seed's linear solid-shell element.
//!
//! # Formulation
//! Nodes are numbered counter-clockwise; natural coordinates `(ξ, η) ∈ [−1, 1]²` with
//! `N_I = ¼ (1 + ξ_I ξ)(1 + η_I η)`. With `F = I + Σ u_I ⊗ ∇_X N_I` the compatible
//! Green–Lagrange strain is `E_c = ½ (FᵀF − I)` (Voigt, engineering shear, see
//! [`super::material`]).
//!
//! `Q4Eas` enriches the Green–Lagrange strain with four incompatible modes
//! (Andelfinger & Ramm, IJNME 36 (1993) 1311–1337; the EAS-4 space of Simo & Rifai,
//! IJNME 29 (1990) 1595–1638, applied to `E` as in solid-shell elements, e.g.
//! Klinkel & Wagner, IJNME 40 (1997) 4529–4545):
//!
//! `Ẽ = (j₀ / j) T₀ M(ξ, η) α`, `M = [[ξ,0,0,0],[0,η,0,0],[0,0,ξ,η]]`,
//!
//! where `j = det J`, `j₀` its value at the centre and `T₀` maps covariant strain
//! components in `(ξ, η)` to Cartesian ones with `J₀⁻¹` (centre Jacobian). Because
//! `∫ M dξ dη = 0`, the element passes the patch test; the `ξ` and `η` modes in the
//! normal strains remove shear locking in bending and volumetric locking.
//!
//! The enhanced parameters `α` are element-internal: for the given displacements the kernel
//! solves `R_α(u, α) = ∫ Gᵀ S dA = 0` by a local Newton iteration (exact in one step for
//! St. Venant–Kirchhoff) and returns the statically condensed residual and tangent
//! `R* = R_u − K_uα K_αα⁻¹ R_α`, `K* = K_uu − K_uα K_αα⁻¹ K_αu`,
//! so the element is a function of `u` alone and `K* = ∂R*/∂u` exactly (checked by finite
//! differences below). `Q4` is the plain bilinear element (it locks in bending; it is kept
//! as the reference that shows why the enhancement is there).

use super::material::{Material, MaterialError};
use nalgebra::{Matrix2, Matrix3, SMatrix, SVector, Vector3};
use serde::{Deserialize, Serialize};

/// Which quadrilateral formulation an element uses.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "kebab-case")]
pub enum ElementKind {
    /// Bilinear displacement element (locks in bending with one layer).
    Q4,
    /// Bilinear element with four enhanced strain modes (default; does not lock).
    Q4Eas,
    /// `Q4Eas` stabilised against its hourglass instability in compression by a small
    /// share of the displacement-based energy (see [`EAS_STABILISATION`]).
    Q4EasStab,
}

/// Failure of an element evaluation; the solver treats it as a divergent iteration.
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
pub enum ElementError {
    #[error("reference Jacobian det J = {0:.3e} ≤ 0 (nodes not counter-clockwise or degenerate)")]
    BadGeometry(f64),
    #[error(transparent)]
    Material(#[from] MaterialError),
    #[error("enhanced-strain parameters did not converge (|R_α| = {0:.3e})")]
    EasNotConverged(f64),
}

type Mat38 = SMatrix<f64, 3, 8>;
type Mat34 = SMatrix<f64, 3, 4>;
type Mat88 = SMatrix<f64, 8, 8>;
type Mat84 = SMatrix<f64, 8, 4>;
type Mat44 = SMatrix<f64, 4, 4>;

pub(crate) const XI_NODES: [(f64, f64); 4] = [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)];
const G: f64 = 0.577_350_269_189_625_8; // 1/sqrt(3)
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
struct GaussGeom {
    /// `∂N_I/∂X_a`
    grad: [[f64; 4]; 2],
    /// `j · w` (weights are 1 for 2×2 Gauss)
    dv: f64,
    /// `Ẽ = G α`
    g: Mat34,
}

/// Reference geometry of one quadrilateral at its four Gauss points: shape-function
/// gradients, volume weights and the EAS interpolation `G = (j₀/j) T₀ M`. It depends on the
/// reference coordinates only, so an assembler computes it once per element.
#[derive(Debug, Clone, Copy)]
pub struct QuadGeometry {
    gp: [GaussGeom; 4],
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
            let g = match kind {
                ElementKind::Q4 => Mat34::zeros(),
                ElementKind::Q4Eas | ElementKind::Q4EasStab => {
                    let m = Mat34::new(xi, 0.0, 0.0, 0.0, 0.0, eta, 0.0, 0.0, 0.0, 0.0, xi, eta);
                    (det0 / det) * t0 * m
                }
            };
            Ok(GaussGeom { grad, dv: det, g })
        };
        Ok(QuadGeometry {
            gp: [mk(&GAUSS[0])?, mk(&GAUSS[1])?, mk(&GAUSS[2])?, mk(&GAUSS[3])?],
        })
    }
}

/// Deformation gradient and strain–displacement matrix at one Gauss point.
struct GaussKin {
    f: Matrix2<f64>,
    /// `δE_c = B δu`
    b: Mat38,
}

fn kinematics(geo: &GaussGeom, u: &[[f64; 2]; 4]) -> GaussKin {
    let grad = &geo.grad;
    let mut f = Matrix2::identity();
    for i in 0..4 {
        for r in 0..2 {
            for c in 0..2 {
                f[(r, c)] += u[i][r] * grad[c][i];
            }
        }
    }
    let mut b = Mat38::zeros();
    for i in 0..4 {
        let (n1, n2) = (grad[0][i], grad[1][i]);
        for r in 0..2 {
            b[(0, 2 * i + r)] = f[(r, 0)] * n1;
            b[(1, 2 * i + r)] = f[(r, 1)] * n2;
            b[(2, 2 * i + r)] = f[(r, 0)] * n2 + f[(r, 1)] * n1;
        }
    }
    GaussKin { f, b }
}

fn green_lagrange(f: &Matrix2<f64>) -> Vector3<f64> {
    let c = f.transpose() * f;
    Vector3::new(0.5 * (c[(0, 0)] - 1.0), 0.5 * (c[(1, 1)] - 1.0), c[(0, 1)])
}

/// Residual and (optionally) tangent of one quadrilateral, plane strain, unit thickness
/// (builds the [`QuadGeometry`] and calls [`quad_residual_tangent_with`]).
pub fn quad_residual_tangent(
    kind: ElementKind,
    material: &Material,
    x: &[[f64; 2]; 4],
    u: &[[f64; 2]; 4],
    alpha: &mut [f64; 4],
    r: &mut [f64; 8],
    k: Option<&mut [f64; 64]>,
) -> Result<f64, ElementError> {
    let geo = QuadGeometry::new(kind, x)?;
    quad_residual_tangent_with(kind, material, &geo, u, alpha, r, k)
}

/// Residual and (optionally) tangent of one quadrilateral, plane strain, unit thickness,
/// on its precomputed reference geometry.
///
/// * `geo` — [`QuadGeometry`] of the reference nodes (counter-clockwise), `u` — nodal
///   displacements;
/// * `alpha` — enhanced-strain parameters: read as the starting guess, overwritten with the
///   values that satisfy `R_α = 0` for this `u` (ignored for [`ElementKind::Q4`]);
/// * `r` — internal force `R* = ∂Π/∂u` (condensed), local DOF order `[u1x, u1y, u2x, …]`;
/// * `k` — `∂R*/∂u`, row-major 8×8, when requested.
///
/// The local Newton iteration on `α` evaluates only `R_α`, `K_αα` in its first pass; every
/// later pass also evaluates `R_u`, `K_uu`, `K_uα`, so the pass that finds `R_α` converged
/// is the one whose condensed residual and tangent are returned (two passes over the Gauss
/// points for St. Venant–Kirchhoff from any starting `α`).
///
/// Returns the stored strain energy of the element. Sign: `r` is the internal force, the
/// global residual is `r − f_ext`.
pub fn quad_residual_tangent_with(
    kind: ElementKind,
    material: &Material,
    geo: &QuadGeometry,
    u: &[[f64; 2]; 4],
    alpha: &mut [f64; 4],
    r: &mut [f64; 8],
    k: Option<&mut [f64; 64]>,
) -> Result<f64, ElementError> {
    let kin = [
        kinematics(&geo.gp[0], u),
        kinematics(&geo.gp[1], u),
        kinematics(&geo.gp[2], u),
        kinematics(&geo.gp[3], u),
    ];
    let ec: [Vector3<f64>; 4] = [
        green_lagrange(&kin[0].f),
        green_lagrange(&kin[1].f),
        green_lagrange(&kin[2].f),
        green_lagrange(&kin[3].f),
    ];
    if kind == ElementKind::Q4EasStab {
        return stabilised(material, geo, u, alpha, r, k);
    }
    let eas = kind == ElementKind::Q4Eas;
    let mut al = SVector::<f64, 4>::from_column_slice(alpha);
    if !eas {
        al.fill(0.0);
    }
    let want_k = k.is_some();
    let mut ru = SVector::<f64, 8>::zeros();
    let mut kuu = Mat88::zeros();
    let mut kua = Mat84::zeros();
    let mut kaa = Mat44::zeros();
    let mut ra = SVector::<f64, 4>::zeros();
    let mut energy = 0.0;
    let mut last_step = false;
    // Local Newton on α (one step is exact for linear S(E)); the displacement terms are
    // evaluated from the second pass on (a pass at a converged α is the last one).
    for it in 0..=25 {
        let full = !eas || it > 0;
        kaa.fill(0.0);
        ra.fill(0.0);
        if full {
            ru.fill(0.0);
            kuu.fill(0.0);
            kua.fill(0.0);
            energy = 0.0;
        }
        let mut scale = 0.0f64;
        for (q, (g, kq)) in geo.gp.iter().zip(&kin).enumerate() {
            let e = ec[q] + g.g * al;
            let (s, d) = material.stress_tangent(&e)?;
            if eas {
                ra += g.g.transpose() * s * g.dv;
                let dg = d * g.g;
                kaa += g.g.transpose() * dg * g.dv;
                scale = scale.max(d.norm() * g.dv);
                if full {
                    kua += kq.b.transpose() * dg * g.dv;
                }
            }
            if !full {
                continue;
            }
            energy += material.energy(&e)? * g.dv;
            ru += kq.b.transpose() * s * g.dv;
            if want_k {
                kuu += kq.b.transpose() * (d * kq.b) * g.dv;
                // geometric stiffness δ_ab ∇N_I · S ∇N_J
                let sm = Matrix2::new(s[0], s[2], s[2], s[1]);
                for i in 0..4 {
                    let gi = nalgebra::Vector2::new(g.grad[0][i], g.grad[1][i]);
                    let sgi = sm * gi;
                    for j in 0..4 {
                        let v = sgi.dot(&nalgebra::Vector2::new(g.grad[0][j], g.grad[1][j])) * g.dv;
                        kuu[(2 * i, 2 * j)] += v;
                        kuu[(2 * i + 1, 2 * j + 1)] += v;
                    }
                }
            }
        }
        if !eas {
            break;
        }
        let last = ra.norm();
        if full && (last_step || last <= 1e-13 * scale.max(1e-300) * (1.0 + al.norm())) {
            break;
        }
        if it == 25 {
            return Err(ElementError::EasNotConverged(last));
        }
        let da = kaa.lu().solve(&ra).ok_or(ElementError::EasNotConverged(last))?;
        al -= da;
        // a step below round-off: one more pass evaluates everything at this α
        last_step = da.norm() <= 1e-15 * (1.0 + al.norm());
    }
    if eas {
        let inv = kaa.try_inverse().ok_or(ElementError::EasNotConverged(ra.norm()))?;
        ru -= kua * (inv * ra);
        if let Some(kout) = k {
            kuu -= kua * inv * kua.transpose();
            write_k(&kuu, kout);
        }
        alpha.copy_from_slice(al.as_slice());
    } else if let Some(kout) = k {
        write_k(&kuu, kout);
    }
    r.copy_from_slice(ru.as_slice());
    Ok(energy)
}

/// Share `β` of the displacement-based (`Q4`) energy in [`ElementKind::Q4EasStab`].
///
/// Why: the EAS element has a spurious (hourglass) instability under large compressive
/// strain (Wriggers & Reese, CMAME 135 (1996) 201–209; de Souza Neto et al., IJNME 38
/// (1995) 3365–3381). Measured here: a one-layer cantilever of 240×1 elements (tall,
/// narrow: aspect 12) under 4× the k = 4 elastica load zig-zags near the clamp, where the
/// bottom fibre is compressed by ≈ 40 % (tip deflection 9.80 instead of 8.58 with
/// St. Venant–Kirchhoff; no convergence past 39 % of the load with Neo-Hooke; 480×4 the
/// same). `β = 0.05` stabilises these with Neo-Hooke (8.582 on 240×1, 8.584 on 480×4);
/// with St. Venant–Kirchhoff, whose uniaxial stress itself peaks at 42 % compression, the
/// branch followed depends on round-off (8.579 optimised, 9.65 unoptimised). The cost is in
/// bending accuracy on
/// flat elements (24×1, k = 4: −0.53 % against Mattiasson's tip deflection, plain EAS
/// +0.21 %); `β = 0.01` does not stabilise them. `tests/cantilever_hourglass.rs` checks both.
pub const EAS_STABILISATION: f64 = 0.05;

/// `Π = (1 − β) Π_EAS(u) + β Π_Q4(u)` with `β =` [`EAS_STABILISATION`] (a fixed share of the
/// bilinear element's stiffness, the simplest of the hourglass controls): both energies are
/// exact functions of `u`, so are the blended residual and tangent.
fn stabilised(
    material: &Material,
    geo: &QuadGeometry,
    u: &[[f64; 2]; 4],
    alpha: &mut [f64; 4],
    r: &mut [f64; 8],
    k: Option<&mut [f64; 64]>,
) -> Result<f64, ElementError> {
    let beta = EAS_STABILISATION;
    let mut k = k;
    let (mut rq, mut kq, mut a0) = ([0.0; 8], [0.0; 64], [0.0; 4]);
    let want_k = k.is_some();
    let eq = quad_residual_tangent_with(
        ElementKind::Q4,
        material,
        geo,
        u,
        &mut a0,
        &mut rq,
        want_k.then_some(&mut kq),
    )?;
    let ee = quad_residual_tangent_with(ElementKind::Q4Eas, material, geo, u, alpha, r, k.as_deref_mut())?;
    for (a, b) in r.iter_mut().zip(&rq) {
        *a = (1.0 - beta) * *a + beta * b;
    }
    if let Some(k) = k {
        for (a, b) in k.iter_mut().zip(&kq) {
            *a = (1.0 - beta) * *a + beta * b;
        }
    }
    Ok((1.0 - beta) * ee + beta * eq)
}

fn write_k(k: &Mat88, out: &mut [f64; 64]) {
    for i in 0..8 {
        for j in 0..8 {
            out[8 * i + j] = k[(i, j)];
        }
    }
}

/// Green–Lagrange strain and second Piola–Kirchhoff stress at the element centre (for output).
pub fn quad_centre_stress(
    kind: ElementKind,
    material: &Material,
    x: &[[f64; 2]; 4],
    u: &[[f64; 2]; 4],
    alpha: &[f64; 4],
) -> Result<(Vector3<f64>, Vector3<f64>), ElementError> {
    let geo = QuadGeometry::new(kind, x)?;
    let al = SVector::<f64, 4>::from_column_slice(alpha);
    // centre value = Gauss average (the enhanced field averages to zero)
    let mut e = Vector3::zeros();
    for g in &geo.gp {
        e += 0.25 * (green_lagrange(&kinematics(g, u).f) + g.g * al);
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

#[cfg(test)]
#[path = "quad_tests.rs"]
mod tests;
