//! The stabilised EAS elements: [`ElementKind::Q4EasStab`] (a fixed share of the bilinear
//! element's energy added to the EAS element's) and [`ElementKind::Q4EasSafe`] (EAS with its
//! hourglass modes held where compression frees them, bilinear in large compression).

use super::{quad_residual_tangent_with, ElementError, ElementKind, LinearEas, Material, QuadGeometry};
use nalgebra::Vector3;

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
pub(super) fn stabilised(
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

/// Smallest principal stretches (of the mean deformation gradient) between which
/// [`ElementKind::Q4EasSafe`] turns from EAS into the bilinear element (see
/// [`compression_share`]).
pub const COMPRESSION_STRETCH: [f64; 2] = [0.85, 0.6];

/// `β(u)` of [`ElementKind::Q4EasSafe`] in scalar type `S` (dual numbers give its gradient
/// and Hessian): with `λ` the smallest principal stretch of the mean deformation gradient
/// `F̄ = I + Σ_I u_I ⊗ ∇N_I` (the Gauss-point average), `x = (λ₀ − λ)/(λ₀ − λ₁)`
/// ([`COMPRESSION_STRETCH`] = `[λ₀, λ₁]`), `β = 6x⁵ − 15x⁴ + 10x³` on `[0, 1]`: zero (EAS)
/// until the element as a whole is compressed to λ₀, one (the bilinear element) from λ₁ on,
/// twice continuously differentiable; `λ` is an invariant of `C̄ = F̄ᵀF̄`, so `β` — and the
/// blended energy — is frame-indifferent.
///
/// Why: a square EAS element hourglasses too when compressed far enough (Wriggers & Reese
/// 1996): under a die pressed 1.4 into a 3-thick soft block (the ironing benchmark, 40–50 %
/// compression under the die) EAS elements invert at every mesh and step, bilinear ones do
/// not; in such compression the bilinear element's locking in bending does not matter. (A
/// one-layer beam in bending has no mean compression: its elements are held by
/// [`hourglass_holds`] instead.)
pub(super) fn compression_share<S: num_dual::DualNum<f64> + Copy>(geo: &QuadGeometry, u: &[[S; 2]; 4]) -> S {
    let mut f = [[S::from(1.0), S::from(0.0)], [S::from(0.0), S::from(1.0)]];
    for (i, ui) in u.iter().enumerate() {
        let mut g = [0.0; 2];
        for q in 0..4 {
            let gq = geo.gauss_gradient(q, i);
            g = [g[0] + 0.25 * gq[0], g[1] + 0.25 * gq[1]];
        }
        for (r, fr) in f.iter_mut().enumerate() {
            fr[0] += ui[r] * g[0];
            fr[1] += ui[r] * g[1];
        }
    }
    let c11 = f[0][0] * f[0][0] + f[1][0] * f[1][0];
    let c22 = f[0][1] * f[0][1] + f[1][1] * f[1][1];
    let c12 = f[0][0] * f[0][1] + f[1][0] * f[1][1];
    let dev = ((c11 - c22) * (c11 - c22) * 0.25 + c12 * c12).sqrt();
    let lambda = ((c11 + c22) * 0.5 - dev).sqrt();
    let [l0, l1] = COMPRESSION_STRETCH;
    let x = (-lambda + l0) / (l0 - l1);
    if x.re() <= 0.0 {
        return S::from(0.0);
    }
    if x.re() >= 1.0 {
        return S::from(1.0);
    }
    x * x * x * (x * (x * 6.0 - 15.0) + 10.0)
}

/// Compression (relative to the critical one) from which an enhanced shear mode is held,
/// and the growth of the hold: `p = K⁰_mm · HOLD_GROWTH · ⟨x − HOLD_FROM⟩²`.
pub const HOLD_FROM: f64 = 0.05;
pub const HOLD_GROWTH: f64 = 40.0;

/// The penalties that hold the hourglass modes of a [`ElementKind::Q4EasSafe`] element at a
/// converged state `u`, for the next increment (`α₃`, `α₄`: the enhanced shear modes).
///
/// For each natural axis `k` (`e_k` = `∂X/∂ξ`, `∂X/∂η`, sides `L_k`), the largest compression
/// along it over the Gauss points, `c_k = max_q (1 − |F_q e_k|/|e_k|)`, is measured against
/// the compression at which plain EAS loses stability across that axis, `(L_k/L_other)²`:
/// `x_k = c_k (L_other/L_k)²`. Compression along `ξ` holds the `η` shear mode (`α₄`), along
/// `η` the `ξ` one (`α₃`), with `p = K⁰_mm · 40 ⟨x − 0.05⟩²` (`K⁰_mm` the mode's stiffness
/// at rest): nothing below 5 % of the critical compression, 8 times the mode's stiffness at
/// half of it, the mode practically removed beyond.
///
/// Why: the enhanced shear mode `η` cancels the shear of the pattern `u_y ∝ ξη` — in an
/// element short along `ξ` and long along `η` (a one-layer beam refined along its length:
/// 240 × 1 elements are 12 times taller than long) a zig-zag of its short sides whose
/// remaining stiffness is `∝ E/L_η²`, which a compression `σ` along `ξ` softens as `σ/L_ξ²`:
/// unstable from `|σ|/E ~ (L_ξ/L_η)²`, 0.7 % strain at aspect 12 (Wriggers & Reese 1996;
/// measured: a tip deflection 14 % too large). Held, the pattern keeps the bilinear element's
/// shear stiffness, and the bilinear element's locking in it costs `(L_ξ/L_η)²` — nothing in
/// a tall element. The same mode is the bending of a *column* of such elements along `η`: a
/// rule by shape alone would lock it, so the hold follows the compression across the short
/// side, which a bent column or belt (compressed along its long side) does not have. Held per
/// increment (from the last converged state), the element's energy is fixed within an
/// increment and its tangent exact; the element passes the patch test (`α = 0` in a
/// homogeneous state) and stays frame-indifferent (`|F e_k|` is an invariant of `C`).
pub fn hourglass_holds(geo: &QuadGeometry, material: &Material, u: &[[f64; 2]; 4]) -> [f64; 4] {
    let axes = geo.axes();
    let len = axes.map(|a| a[0].hypot(a[1]));
    let mut x = [0.0f64; 2];
    for q in 0..4 {
        let mut f = [[1.0, 0.0], [0.0, 1.0]];
        for (i, ui) in u.iter().enumerate() {
            let g = geo.gauss_gradient(q, i);
            for (r, fr) in f.iter_mut().enumerate() {
                fr[0] += ui[r] * g[0];
                fr[1] += ui[r] * g[1];
            }
        }
        for k in 0..2 {
            let e = [axes[k][0] / len[k], axes[k][1] / len[k]];
            let fe = [f[0][0] * e[0] + f[0][1] * e[1], f[1][0] * e[0] + f[1][1] * e[1]];
            let c = 1.0 - fe[0].hypot(fe[1]);
            x[k] = x[k].max(c * (len[1 - k] / len[k]).powi(2));
        }
    }
    let hold = |x: f64, m: usize| {
        let over = (x - HOLD_FROM).max(0.0);
        if over == 0.0 {
            0.0
        } else {
            geo.mode_stiffness(material, m) * HOLD_GROWTH * over * over
        }
    };
    [0.0, 0.0, hold(x[1], 2), hold(x[0], 3)]
}

/// `Π = Π_EAS(u) + β(u) (Π_Q4(u) − Π_EAS(u))` with the compression share `β(u)` of
/// [`compression_share`]; the residual and tangent are the exact derivatives:
/// `R = R_E + β (R_Q − R_E) + (Π_Q − Π_E) ∇β`,
/// `K = K_E + β (K_Q − K_E) + (R_Q − R_E) ⊗ ∇β + ∇β ⊗ (R_Q − R_E) + (Π_Q − Π_E) ∇²β`
/// (`Π_E`, `R_E`, `K_E` of the statically condensed EAS element, a function of `u` alone).
pub(super) fn compression_blend(
    material: &Material,
    geo: &QuadGeometry,
    u: &[[f64; 2]; 4],
    alpha: &mut [f64; 4],
    r: &mut [f64; 8],
    k: Option<&mut [f64; 64]>,
) -> Result<f64, ElementError> {
    use nalgebra::{Const, U1};
    use num_dual::Dual2SVec64;
    let mut k = k;
    let ee = quad_residual_tangent_with(ElementKind::Q4Eas, material, geo, u, alpha, r, k.as_deref_mut())?;
    // most elements are not compressed to λ₀: β = 0 there, and its derivatives (second-order
    // dual numbers in 8 unknowns, the costliest part of the element) are not needed
    if compression_share(geo, u) == 0.0 {
        return Ok(ee);
    }
    let ud: [[Dual2SVec64<8>; 2]; 4] =
        std::array::from_fn(|i| std::array::from_fn(|c| Dual2SVec64::<8>::from_re(u[i][c]).derivative(2 * i + c)));
    let beta = compression_share(geo, &ud);
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
    let b = beta.re;
    let gb = beta.v1.unwrap_generic(U1, Const::<8>);
    let hb = beta.v2.unwrap_generic(Const::<8>, Const::<8>);
    let dpi = eq - ee;
    let dr: [f64; 8] = std::array::from_fn(|i| rq[i] - r[i]);
    if let Some(k) = k {
        for i in 0..8 {
            for j in 0..8 {
                k[8 * i + j] += b * (kq[8 * i + j] - k[8 * i + j]) + dr[i] * gb[j] + gb[i] * dr[j] + dpi * hb[(i, j)];
            }
        }
    }
    for i in 0..8 {
        r[i] += b * dr[i] + dpi * gb[i];
    }
    Ok(ee + b * dpi)
}

/// What the hourglass holds of [`ElementKind::Q4EasSafe`] need of an element's geometry.
impl QuadGeometry {
    /// The element's natural axes at its centre, `∂X/∂ξ` and `∂X/∂η`.
    pub(crate) fn axes(&self) -> [[f64; 2]; 2] {
        self.axes
    }

    /// The penalties on the enhanced parameters.
    pub fn alpha_penalty(&self) -> [f64; 4] {
        self.penalty
    }

    /// Set the penalties on the enhanced parameters (and the closed form of `α` for
    /// `material`, when the geometry has one).
    pub fn set_alpha_penalty(&mut self, penalty: [f64; 4], material: &Material) {
        if penalty == self.penalty {
            return;
        }
        self.penalty = penalty;
        if self.linear.is_some() {
            self.linear = LinearEas::new(material, &self.gp.map(|q| (q.dv, q.g)), &self.penalty);
        }
    }

    /// `K⁰_mm`: the stiffness of enhanced mode `m` with the material's initial tangent.
    pub(crate) fn mode_stiffness(&self, material: &Material, m: usize) -> f64 {
        if !matches!(self.model, super::ModelGeometry::PlaneStrain) {
            return super::models::mode_stiffness(self, material, m);
        }
        let Ok((_, d0)) = material.stress_tangent(&Vector3::zeros()) else {
            return 0.0;
        };
        self.gp
            .iter()
            .map(|q| {
                let gm = Vector3::new(q.g[0][m], q.g[1][m], q.g[2][m]);
                q.dv * gm.dot(&(d0 * gm))
            })
            .sum()
    }

    /// `∂N_I/∂X` at Gauss point `q`.
    pub(crate) fn gauss_gradient(&self, q: usize, i: usize) -> [f64; 2] {
        [self.gp[q].grad[0][i], self.gp[q].grad[1][i]]
    }
}
