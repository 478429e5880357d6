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

use super::eas_linear::LinearEas;
use super::material::{Material, MaterialError};
use nalgebra::{Matrix2, Matrix3, Matrix4, Vector3};
use serde::{Deserialize, Serialize};

/// Which quadrilateral formulation an element uses.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, schemars::JsonSchema)]
#[serde(rename_all = "kebab-case")]
pub enum ElementKind {
    /// Bilinear displacement element (locks in bending with one layer).
    Q4,
    /// Bilinear element with four enhanced strain modes (does not lock; can hourglass in
    /// large compression, see [`Q4EasSafe`](Self::Q4EasSafe)).
    Q4Eas,
    /// `Q4Eas` stabilised against its hourglass instability in compression by a small
    /// share of the displacement-based energy (see [`EAS_STABILISATION`]).
    Q4EasStab,
    /// `Q4Eas` made safe against its hourglass instabilities (the default): the enhanced
    /// shear mode that frees an element's hourglass pattern across its short side is held
    /// once the element has been compressed across that side (see [`hourglass_holds`]), and
    /// the element turns into the bilinear one when compressed as a whole beyond ≈ 15 %
    /// (`quad_stab.rs`, `compression_share`). Plain EAS in bending and at moderate strain.
    Q4EasSafe,
    /// The 3D solid-shell for thin bodies (`element/solid_shell.rs`; 3D meshes only, a 2D
    /// scene refuses it).
    SolidShell,
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
    /// The enhanced-strain stiffness `K_αα` is singular: the element is degenerate (flattened
    /// or distorted beyond what its enhanced modes can take).
    #[error("degenerate element: its enhanced-strain stiffness K_αα is singular")]
    EasSingular,
    /// The element is folded: `det F ≤ 0` at a Gauss point of the compatible deformation.
    #[error("inverted element: det F = {0:.3e} ≤ 0 at a Gauss point")]
    Inverted(f64),
    /// A plane-stress thickness that is not positive and finite.
    #[error("plane-stress thickness {0:.3e} is not positive")]
    BadThickness(f64),
    /// An axisymmetric element with a node at `x = r < 0` (the axis is `x = 0`).
    #[error("axisymmetric element with a node at radius r = {0:.3e} < 0")]
    NegativeRadius(f64),
    /// A hexahedron's failure (3D models).
    #[error(transparent)]
    Hex8(#[from] super::hex8::Hex8Error),
}

#[path = "quad_geometry.rs"]
mod geometry;
pub use geometry::*;

/// Strain–displacement matrix and compatible Green–Lagrange strain at one Gauss point, from
/// `F_ab = δ_ab + Σ_I u_Ia ∂N_I/∂X_b`.
#[derive(Clone, Copy)]
struct GaussKin {
    /// `δE_c = B δu` (rows: `E11, E22, 2E12`; columns: local DOFs `[u1x, u1y, u2x, …]`)
    b: [[f64; 8]; 3],
    /// `E_c = ½ (FᵀF − I)` in Voigt form with engineering shear
    ec: [f64; 3],
    /// `det F`
    det_f: f64,
}

#[inline(always)]
fn kinematics(geo: &GaussGeom, u: &[[f64; 2]; 4]) -> GaussKin {
    let grad = &geo.grad;
    let mut f = [[1.0, 0.0], [0.0, 1.0]];
    for (i, ui) in u.iter().enumerate() {
        for (r, fr) in f.iter_mut().enumerate() {
            fr[0] += ui[r] * grad[0][i];
            fr[1] += ui[r] * grad[1][i];
        }
    }
    let mut b = [[0.0; 8]; 3];
    for i in 0..4 {
        let (n1, n2) = (grad[0][i], grad[1][i]);
        for r in 0..2 {
            b[0][2 * i + r] = f[r][0] * n1;
            b[1][2 * i + r] = f[r][1] * n2;
            b[2][2 * i + r] = f[r][0] * n2 + f[r][1] * n1;
        }
    }
    let c11 = f[0][0] * f[0][0] + f[1][0] * f[1][0];
    let c22 = f[0][1] * f[0][1] + f[1][1] * f[1][1];
    let c12 = f[0][0] * f[0][1] + f[1][0] * f[1][1];
    GaussKin {
        b,
        ec: [0.5 * (c11 - 1.0), 0.5 * (c22 - 1.0), c12],
        det_f: f[0][0] * f[1][1] - f[0][1] * f[1][0],
    }
}

/// `Ẽ = G α` at one Gauss point.
#[inline(always)]
fn enhanced(g: &[[f64; 4]; 3], al: &[f64; 4]) -> [f64; 3] {
    let row = |r: &[f64; 4]| r[0] * al[0] + r[1] * al[1] + r[2] * al[2] + r[3] * al[3];
    [row(&g[0]), row(&g[1]), row(&g[2])]
}

/// Residual and (optionally) tangent of one quadrilateral, plane strain, unit thickness
/// (builds the [`QuadGeometry`] for the material and calls [`quad_residual_tangent_with`]).
pub fn quad_residual_tangent(
    kind: ElementKind,
    material: &Material,
    x: &[[f64; 2]; 4],
    u: &[[f64; 2]; 4],
    alpha: &mut [f64; 4],
    r: &mut [f64; 8],
    k: Option<&mut [f64; 64]>,
) -> Result<f64, ElementError> {
    let geo = QuadGeometry::for_material(kind, material, x)?;
    quad_residual_tangent_with(kind, material, &geo, u, alpha, r, k)
}

/// Sums of one pass over the Gauss points (upper triangles of the symmetric blocks).
struct Sums {
    ru: [f64; 8],
    kuu: [[f64; 8]; 8],
    kua: [[f64; 4]; 8],
    kaa: [[f64; 4]; 4],
    ra: [f64; 4],
    energy: f64,
}

impl Sums {
    fn new() -> Self {
        Sums {
            ru: [0.0; 8],
            kuu: [[0.0; 8]; 8],
            kua: [[0.0; 4]; 8],
            kaa: [[0.0; 4]; 4],
            ra: [0.0; 4],
            energy: 0.0,
        }
    }
}

/// What one Gauss pass evaluates.
#[derive(Clone, Copy)]
struct Wanted {
    /// `R_α` (and `K_αα` with `kaa`): an EAS element.
    eas: bool,
    /// `K_αα` (not needed when it is known in closed form, [`LinearEas`]).
    kaa: bool,
    /// `R_u`, `K_uα` and the energy.
    full: bool,
    /// `K_uu`.
    k: bool,
}

/// One pass over the Gauss points at the enhanced parameters `al`: `R_α`, `K_αα` (when
/// `eas`; `K_αα` unless it is known), and with `full` also `R_u`, `K_uα`, the energy and
/// (with `k`) `K_uu` (material part `Bᵀ D B` plus geometric part `δ_ab ∇N_I · S ∇N_J`).
// index loops: several arrays are walked by the same (triangular) index ranges
#[allow(clippy::needless_range_loop)]
#[inline(always)]
fn gauss_pass(
    material: &Material,
    geo: &QuadGeometry,
    kin: &[GaussKin; 4],
    al: &[f64; 4],
    wanted: Wanted,
) -> Result<Sums, ElementError> {
    let Wanted {
        eas,
        kaa,
        full,
        k: want_k,
    } = wanted;
    let mut t = Sums::new();
    // a constant tangent (St. Venant–Kirchhoff) once, not per Gauss point: S = D E, the
    // same product `stress_tangent` forms
    let constant = material.constant_tangent();
    for (gq, kq) in geo.gp.iter().zip(kin) {
        let dv = gq.dv;
        let en = enhanced(&gq.g, al);
        let e = Vector3::new(kq.ec[0] + en[0], kq.ec[1] + en[1], kq.ec[2] + en[2]);
        let (s, d) = match &constant {
            // `D e` written out (nalgebra's generic product is not inlined here)
            Some(d) => (
                Vector3::from_fn(|a, _| d[(a, 0)] * e[0] + d[(a, 1)] * e[1] + d[(a, 2)] * e[2]),
                *d,
            ),
            None => material.stress_tangent(&e)?,
        };
        let b = &kq.b;
        if eas {
            add_enhanced_terms(&mut t, &gq.g, b, &s, &d, dv, kaa, full);
        }
        if !full {
            continue;
        }
        t.energy += material.energy(&e)? * dv;
        for (i, v) in t.ru.iter_mut().enumerate() {
            *v += dv * (b[0][i] * s[0] + b[1][i] * s[1] + b[2][i] * s[2]);
        }
        if want_k {
            add_displacement_stiffness(&mut t.kuu, b, &s, &d, &gq.grad, dv);
        }
    }
    if eas {
        // the hold ½ Σ p_m α_m² of the hourglass modes (zero but in held elements)
        for (m, &pm) in geo.penalty.iter().enumerate().filter(|(_, p)| **p != 0.0) {
            t.ra[m] += pm * al[m];
            if kaa {
                t.kaa[m][m] += pm;
            }
            if full {
                t.energy += 0.5 * pm * al[m] * al[m];
            }
        }
    }
    Ok(t)
}

/// One Gauss point's share of the enhanced-strain blocks: `R_α += dv Gᵀ S`, with `kaa` the
/// upper triangle of `K_αα += dv Gᵀ D G`, with `full` `K_uα += dv Bᵀ D G`.
#[allow(clippy::too_many_arguments, clippy::needless_range_loop)]
#[inline(always)]
fn add_enhanced_terms(
    t: &mut Sums,
    g: &[[f64; 4]; 3],
    b: &[[f64; 8]; 3],
    s: &Vector3<f64>,
    d: &Matrix3<f64>,
    dv: f64,
    kaa: bool,
    full: bool,
) {
    // D G (3×4)
    let mut dg = [[0.0; 4]; 3];
    for (a, row) in dg.iter_mut().enumerate() {
        for (m, v) in row.iter_mut().enumerate() {
            *v = d[(a, 0)] * g[0][m] + d[(a, 1)] * g[1][m] + d[(a, 2)] * g[2][m];
        }
    }
    for m in 0..4 {
        t.ra[m] += dv * (g[0][m] * s[0] + g[1][m] * s[1] + g[2][m] * s[2]);
        if kaa {
            for n in m..4 {
                t.kaa[m][n] += dv * (g[0][m] * dg[0][n] + g[1][m] * dg[1][n] + g[2][m] * dg[2][n]);
            }
        }
    }
    if full {
        for (i, row) in t.kua.iter_mut().enumerate() {
            for (m, v) in row.iter_mut().enumerate() {
                *v += dv * (b[0][i] * dg[0][m] + b[1][i] * dg[1][m] + b[2][i] * dg[2][m]);
            }
        }
    }
}

/// One Gauss point's share of the upper triangle of `K_uu`: the material part `dv Bᵀ D B`
/// and the geometric part `dv δ_ab ∇N_I · S ∇N_J` (`gr` = the shape gradients `∇N`).
#[allow(clippy::needless_range_loop)]
#[inline(always)]
fn add_displacement_stiffness(
    kuu: &mut [[f64; 8]; 8],
    b: &[[f64; 8]; 3],
    s: &Vector3<f64>,
    d: &Matrix3<f64>,
    gr: &[[f64; 4]; 2],
    dv: f64,
) {
    let mut db = [[0.0; 8]; 3];
    for (a, row) in db.iter_mut().enumerate() {
        for (i, v) in row.iter_mut().enumerate() {
            *v = d[(a, 0)] * b[0][i] + d[(a, 1)] * b[1][i] + d[(a, 2)] * b[2][i];
        }
    }
    for i in 0..8 {
        for j in i..8 {
            kuu[i][j] += dv * (b[0][i] * db[0][j] + b[1][i] * db[1][j] + b[2][i] * db[2][j]);
        }
    }
    // geometric stiffness on the node pairs I ≤ J
    for ni in 0..4 {
        let sgx = dv * (s[0] * gr[0][ni] + s[2] * gr[1][ni]);
        let sgy = dv * (s[2] * gr[0][ni] + s[1] * gr[1][ni]);
        for nj in ni..4 {
            let v = sgx * gr[0][nj] + sgy * gr[1][nj];
            kuu[2 * ni][2 * nj] += v;
            kuu[2 * ni + 1][2 * nj + 1] += v;
        }
    }
}

/// Largest change of an enhanced strain component, `max_q ‖G_q δα‖∞`, that the step `δα`
/// makes at the Gauss points.
#[inline(always)]
fn enhanced_strain_change(geo: &QuadGeometry, da: &[f64; 4]) -> f64 {
    geo.gp
        .iter()
        .map(|gq| enhanced(&gq.g, da).iter().fold(0.0f64, |m, v| m.max(v.abs())))
        .fold(0.0, f64::max)
}

/// The local iteration on `α` has converged when its next step would change no enhanced
/// strain by more than this (strains are O(1) at most; round-off is ~1e-16 of them).
pub const EAS_STRAIN_TOLERANCE: f64 = 1e-14;

/// A local step changing no enhanced strain by more than this is close enough for the next
/// pass to converge (Newton's quadratic rate): that pass evaluates the displacement terms
/// too. Larger steps are followed by passes that evaluate `R_α` and `K_αα` only.
const EAS_NEAR: f64 = 1e-6;

/// `K_αα⁻¹` from its upper triangle.
#[inline(always)]
fn kaa_inverse(kaa: &[[f64; 4]; 4]) -> Option<Matrix4<f64>> {
    let mut m = Matrix4::zeros();
    for i in 0..4 {
        for j in i..4 {
            m[(i, j)] = kaa[i][j];
            m[(j, i)] = kaa[i][j];
        }
    }
    m.try_inverse()
}

/// Residual and (optionally) tangent of one quadrilateral, plane strain, unit thickness,
/// on its precomputed reference geometry.
///
/// * `geo` — [`QuadGeometry`] of the reference nodes (counter-clockwise), `u` — nodal
///   displacements;
/// * `alpha` — enhanced-strain parameters: read as the starting guess (by the local Newton
///   iteration), overwritten with the values that satisfy `R_α = 0` for this `u` (ignored
///   for [`ElementKind::Q4`]);
/// * `r` — internal force `R* = ∂Π/∂u` (condensed), local DOF order `[u1x, u1y, u2x, …]`;
/// * `k` — `∂R*/∂u`, row-major 8×8, when requested.
///
/// With a geometry made by [`QuadGeometry::for_material`] for this material and a constant
/// tangent (St. Venant–Kirchhoff), `α` is computed in closed form from the compatible
/// strains (`element/eas_linear.rs`; the incoming `alpha` is not needed) and one full pass
/// over the Gauss points follows (`K_αα⁻¹` is stored, `K_αα` not summed). Otherwise the
/// local Newton iteration on `α` starts from `alpha` and its passes evaluate only `R_α`,
/// `K_αα` while the steps are large; once a step changes no enhanced strain by more than
/// [`EAS_NEAR`] the next pass also evaluates `R_u`, `K_uu`, `K_uα`, so that the pass that
/// finds `α` converged is the one whose condensed residual and tangent are returned.
/// Converged means: the next step `δα = K_αα⁻¹ R_α` would change no enhanced strain
/// `G_q δα` by more than [`EAS_STRAIN_TOLERANCE`] (a test in strain units; a test on `|R_α|`
/// against `‖D‖ dv` mixed the scales of `G` and `Gᵀ G`, sat near round-off on fine meshes
/// and cost 0.78 extra full passes per call on the 1e4-DOF punch). In both cases a full
/// pass that is not converged is followed by another local Newton step (counted on the
/// strip-channel runs with the closed form and the earlier residual test: no extra pass in
/// 296 000 calls on 24×1, 34 in 2.17 million on 120×4; on the punch with Neo-Hooke and this
/// test: 7 in 350 760 calls, with 1.33 `R_α`-only passes per call). The symmetric blocks
/// (`K_uu`, `K_αα`, and the condensed `K*`) are summed on their upper triangles and
/// mirrored.
///
/// Returns the stored strain energy of the element. Sign: `r` is the internal force, the
/// global residual is `r − f_ext`.
///
/// Where the processor has AVX2 the kernel runs as compiled for it ([`crate::cpu`]; the same
/// operations in the same order, so the same figures to the last bit).
pub fn quad_residual_tangent_with(
    kind: ElementKind,
    material: &Material,
    geo: &QuadGeometry,
    u: &[[f64; 2]; 4],
    alpha: &mut [f64; 4],
    r: &mut [f64; 8],
    k: Option<&mut [f64; 64]>,
) -> Result<f64, ElementError> {
    #[cfg(target_arch = "x86_64")]
    if crate::cpu::wide_vectors() {
        // SAFETY: the processor has AVX2 (detected at run time).
        return unsafe { residual_tangent_avx2(kind, material, geo, u, alpha, r, k) };
    }
    residual_tangent(kind, material, geo, u, alpha, r, k)
}

#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
fn residual_tangent_avx2(
    kind: ElementKind,
    material: &Material,
    geo: &QuadGeometry,
    u: &[[f64; 2]; 4],
    alpha: &mut [f64; 4],
    r: &mut [f64; 8],
    k: Option<&mut [f64; 64]>,
) -> Result<f64, ElementError> {
    residual_tangent(kind, material, geo, u, alpha, r, k)
}

/// The body of [`quad_residual_tangent_with`], inlined into each of its compilations.
#[inline(always)]
fn residual_tangent(
    kind: ElementKind,
    material: &Material,
    geo: &QuadGeometry,
    u: &[[f64; 2]; 4],
    alpha: &mut [f64; 4],
    r: &mut [f64; 8],
    k: Option<&mut [f64; 64]>,
) -> Result<f64, ElementError> {
    let plane_strain = matches!(geo.model, ModelGeometry::PlaneStrain);
    // in plane strain the kernel below checks `det F` on the deformation gradients it forms
    // (the stabilised and safe kinds evaluate it first: the same values); the other models
    // are checked here
    if !plane_strain {
        let det_f = min_det_f(geo, u);
        if det_f <= 0.0 || !det_f.is_finite() {
            return Err(ElementError::Inverted(det_f));
        }
    }
    if kind == ElementKind::Q4EasStab {
        return stabilised(material, geo, u, alpha, r, k);
    }
    if kind == ElementKind::Q4EasSafe {
        return stab::compression_blend(material, geo, u, alpha, r, k);
    }
    if !plane_strain {
        return models::residual_tangent(kind == ElementKind::Q4Eas, material, geo, u, alpha, r, k);
    }
    let kin = [
        kinematics(&geo.gp[0], u),
        kinematics(&geo.gp[1], u),
        kinematics(&geo.gp[2], u),
        kinematics(&geo.gp[3], u),
    ];
    // the check of `min_det_f`, on the deformation gradients just formed (same values)
    let det_f = kin.iter().map(|q| q.det_f).fold(f64::INFINITY, f64::min);
    if det_f <= 0.0 || !det_f.is_finite() {
        return Err(ElementError::Inverted(det_f));
    }
    let eas = kind == ElementKind::Q4Eas;
    // a constant-tangent material: α(u) in closed form, the first pass is already full
    let linear = geo.linear.as_ref().filter(|l| eas && l.material == *material);
    let mut al = match linear {
        Some(l) => l.alpha([&kin[0].ec, &kin[1].ec, &kin[2].ec, &kin[3].ec]),
        None if eas => *alpha,
        None => [0.0; 4],
    };
    let want_k = k.is_some();
    let (mut t, inv) = local_alpha_iteration(material, geo, &kin, &mut al, eas, linear, want_k)?;
    if eas {
        condense(&mut t, &inv, want_k);
        alpha.copy_from_slice(&al);
    }
    if let Some(kout) = k {
        for i in 0..8 {
            for j in i..8 {
                kout[8 * i + j] = t.kuu[i][j];
                kout[8 * j + i] = t.kuu[i][j];
            }
        }
    }
    r.copy_from_slice(&t.ru);
    Ok(t.energy)
}

/// The local Newton iteration on `α` for displacements whose kinematics are `kin` (one
/// step is exact for a linear `S(E)`; none for `Q4`): passes over the Gauss points that
/// evaluate `R_α`, `K_αα` while the steps are large and, once a step changes no enhanced
/// strain by more than [`EAS_NEAR`], the displacement terms too, until a full pass finds
/// `α` converged ([`EAS_STRAIN_TOLERANCE`]). Returns that pass's sums and `K_αα⁻¹`; `al` is
/// the converged `α`.
#[inline(always)]
fn local_alpha_iteration(
    material: &Material,
    geo: &QuadGeometry,
    kin: &[GaussKin; 4],
    al: &mut [f64; 4],
    eas: bool,
    linear: Option<&LinearEas>,
    want_k: bool,
) -> Result<(Sums, Matrix4<f64>), ElementError> {
    let norm4 = |v: &[f64; 4]| v.iter().map(|x| x * x).sum::<f64>().sqrt();
    let mut last_step = false;
    // Local Newton on α (one step is exact for linear S(E)); the displacement terms are
    // evaluated from the second pass on (a pass at a converged α is the last one).
    let mut it = usize::from(linear.is_some());
    let mut near = linear.is_some();
    let out = loop {
        let full = !eas || near;
        let wanted = Wanted {
            eas,
            kaa: linear.is_none(),
            full,
            k: want_k,
        };
        let t = gauss_pass(material, geo, kin, al, wanted)?;
        if !eas {
            break (t, Matrix4::zeros());
        }
        let res = norm4(&t.ra);
        let inv = match linear {
            Some(l) => l.kaa_inv,
            None => kaa_inverse(&t.kaa).ok_or(ElementError::EasSingular)?,
        };
        let mut da = [0.0; 4];
        for (m, v) in da.iter_mut().enumerate() {
            *v = (0..4).map(|n| inv[(m, n)] * t.ra[n]).sum();
        }
        // the change of the enhanced strains the next step would make
        let step = enhanced_strain_change(geo, &da);
        if full && (last_step || step <= EAS_STRAIN_TOLERANCE) {
            break (t, inv);
        }
        if it == 25 {
            return Err(ElementError::EasNotConverged(res));
        }
        for (a, d) in al.iter_mut().zip(&da) {
            *a -= d;
        }
        // a step below round-off: one more pass evaluates everything at this α
        last_step = step <= 1e-3 * EAS_STRAIN_TOLERANCE;
        // close enough for the next pass to be the last: evaluate the displacement terms
        near = step <= EAS_NEAR || it >= 12;
        it += 1;
    };
    Ok(out)
}

/// Static condensation of the enhanced-strain parameters at a converged `α`:
/// `R* = R_u − K_uα (K_αα⁻¹ R_α)` into `t.ru` and, with `want_k`, `K* = K_uu − W K_αu` with
/// `W = K_uα K_αα⁻¹` into the upper triangle of `t.kuu` (`inv = K_αα⁻¹`). With `α` in closed
/// form ([`LinearEas`]) `R_α` is round-off, and its correction compensates that round-off
/// of `α`: left out, the residual's floor rose and the 120×4 strip took 1.9 % more Newton
/// iterations (measured 2026-11-27), so it stays.
#[inline(always)]
fn condense(t: &mut Sums, inv: &Matrix4<f64>, want_k: bool) {
    // plain arrays (row-major `inv[m][n]`): the sums below in the same order as before
    let mut rows = [[0.0; 4]; 4];
    for (m, row) in rows.iter_mut().enumerate() {
        for (n, v) in row.iter_mut().enumerate() {
            *v = inv[(m, n)];
        }
    }
    let inv = rows;
    let dot = |a: &[f64; 4], b: &[f64; 4]| ((a[0] * b[0] + a[1] * b[1]) + a[2] * b[2]) + a[3] * b[3];
    let mut y = [0.0; 4];
    for (v, row) in y.iter_mut().zip(&inv) {
        *v = dot(row, &t.ra);
    }
    for (ri, ki) in t.ru.iter_mut().zip(&t.kua) {
        *ri -= dot(ki, &y);
    }
    if want_k {
        // K_αα⁻¹ is symmetric up to round-off; its columns are taken as stored (plain loops:
        // `array::from_fn` is not inlined into the kernel's AVX2 compilation)
        let mut col = [[0.0; 4]; 4];
        for m in 0..4 {
            for n in 0..4 {
                col[m][n] = inv[n][m];
            }
        }
        let mut w = [[0.0; 4]; 8];
        for (wi, ki) in w.iter_mut().zip(&t.kua) {
            for (v, cm) in wi.iter_mut().zip(&col) {
                *v = dot(ki, cm);
            }
        }
        for (i, wi) in w.iter().enumerate() {
            for j in i..8 {
                t.kuu[i][j] -= dot(wi, &t.kua[j]);
            }
        }
    }
}

#[path = "quad_stab.rs"]
mod stab;
use stab::stabilised;
pub use stab::{hourglass_holds, EAS_STABILISATION};

#[path = "quad_models.rs"]
mod models;
pub use models::Kinematics;
use models::ModelGeometry;

#[path = "quad_output.rs"]
mod output;
pub use output::{quad_centre_deformation_gradient, quad_centre_stress};

#[cfg(test)]
#[path = "quad_tests.rs"]
mod tests;

#[cfg(test)]
#[path = "quad_model_mesh.rs"]
mod model_mesh;

#[cfg(test)]
#[path = "quad_axisym_tests.rs"]
mod axisym_tests;

#[cfg(test)]
#[path = "quad_plane_stress_tests.rs"]
mod plane_stress_tests;
