//! Element stability at a converged increment: the elements whose own tangent has lost
//! positive definiteness in a deformation mode other than a rigid motion.
//!
//! For each element the condensed tangent `K_e` (8×8, symmetric for the hyperelastic
//! elements) is evaluated at the converged displacements, the three rigid-body modes of its
//! current position (two translations and the rotation `(−y, x)`, orthonormalised) are
//! shifted out of the way (`K_e + s Σ r rᵀ`, `s` = the trace), and the smallest eigenvalue is
//! compared with the largest: `λ_min < −10⁻⁸ λ_max` means the element alone can deform
//! without resistance — an hourglass pattern of an enhanced-strain element in compression
//! (Wriggers & Reese 1996), or an element inverted in all but name. A mesh of such elements
//! may still converge, to a wrong answer; the run says so instead.
//!
//! Only elements compressed enough for the instability to be possible are checked (see
//! `worth_checking`): an element's tangent at small strain is positive definite.

use crate::assembly::{Assembler, AssemblyError};
use crate::model::{Dim, Model, Plane};
use nalgebra::{SMatrix, SVector, SymmetricEigen};

/// Relative size of a negative eigenvalue that counts as a loss of stability.
pub const UNSTABLE_RATIO: f64 = 1e-8;

/// An element that lost stability, with `λ_min/λ_max` of its tangent (rigid modes aside).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct UnstableElement {
    pub element: usize,
    pub ratio: f64,
}

/// The unstable elements at displacements `u` with enhanced parameters `alphas` (flat,
/// [`Dim::ALPHAS`] per element), worst first. Quadrilaterals only: a 3D model reports none
/// (the hexahedron's check is not written yet).
pub fn unstable_elements<S: Dim>(
    model: &Model<S>,
    asm: &Assembler<S>,
    u: &[f64],
    alphas: &[f64],
) -> Result<Vec<UnstableElement>, AssemblyError> {
    let any: (&dyn std::any::Any, &dyn std::any::Any) = (model, asm);
    match (
        any.0.downcast_ref::<Model<Plane>>(),
        any.1.downcast_ref::<Assembler<Plane>>(),
    ) {
        (Some(model), Some(asm)) => unstable_quads(model, asm, u, Plane::alphas(alphas)),
        _ => Ok(Vec::new()),
    }
}

fn unstable_quads(
    model: &Model,
    asm: &Assembler,
    u: &[f64],
    alphas: &[[f64; 4]],
) -> Result<Vec<UnstableElement>, AssemblyError> {
    let mut out = Vec::new();
    let mut k = [0.0; 64];
    for (ie, el) in model.elements.iter().enumerate() {
        let ue: [[f64; 2]; 4] = el.nodes.map(|n| [u[2 * n], u[2 * n + 1]]);
        if ue.iter().flatten().all(|v| v.abs() < 1e-12) {
            continue;
        }
        let x: [[f64; 2]; 4] = std::array::from_fn(|i| {
            let p = model.nodes[el.nodes[i]];
            [p[0] + ue[i][0], p[1] + ue[i][1]]
        });
        if !worth_checking(model, el, &ue) {
            continue;
        }
        asm.element_tangent(model, ie, u, &alphas[ie], &mut k)?;
        if certainly_stable(&k, &x) {
            continue;
        }
        if let Some(ratio) = smallest_deformation_eigenvalue(&k, &x).filter(|r| *r < -UNSTABLE_RATIO) {
            out.push(UnstableElement { element: ie, ratio });
        }
    }
    out.sort_by(|a, b| a.ratio.total_cmp(&b.ratio));
    Ok(out)
}

/// Whether an element is compressed enough to be worth an eigenvalue check: its centre
/// compression `1 − λ_min` (λ_min the smallest principal stretch of `F` at the centre)
/// exceeds `0.05 r²`, `r ≤ 1` its aspect ratio (short over long side at the centre). The
/// hourglass instability of an enhanced-strain element sets in at a compression of the order
/// of `r²` (`quad::shear_mode_penalty`), so a check well below it finds it from its start,
/// while the elements of a bent beam at a few per cent of strain are not checked at every
/// increment (an eigenvalue problem per element costs about one element evaluation).
fn worth_checking(model: &Model, el: &crate::model::Element, ue: &[[f64; 2]; 4]) -> bool {
    let x = el.nodes.map(|n| model.nodes[n]);
    // centre: ∂N_I/∂ξ = ξ_I/4, ∂N_I/∂η = η_I/4 with (ξ_I, η_I) = (∓1, ∓1) counter-clockwise
    const S: [[f64; 2]; 4] = [[-0.25, -0.25], [0.25, -0.25], [0.25, 0.25], [-0.25, 0.25]];
    let mut j = [[0.0; 2]; 2]; // J_ab = ∂X_a/∂ξ_b
    let mut du = [[0.0; 2]; 2]; // ∂u_a/∂ξ_b
    for i in 0..4 {
        for a in 0..2 {
            for b in 0..2 {
                j[a][b] += x[i][a] * S[i][b];
                du[a][b] += ue[i][a] * S[i][b];
            }
        }
    }
    let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
    if det <= 0.0 {
        return true;
    }
    let inv = [[j[1][1] / det, -j[0][1] / det], [-j[1][0] / det, j[0][0] / det]];
    // F = I + (∂u/∂ξ) J⁻¹
    let f = |a: usize, b: usize| f64::from(u8::from(a == b)) + du[a][0] * inv[0][b] + du[a][1] * inv[1][b];
    let (c11, c22) = (f(0, 0).powi(2) + f(1, 0).powi(2), f(0, 1).powi(2) + f(1, 1).powi(2));
    let c12 = f(0, 0) * f(0, 1) + f(1, 0) * f(1, 1);
    let lambda = (0.5 * (c11 + c22) - (0.25 * (c11 - c22).powi(2) + c12 * c12).sqrt())
        .max(0.0)
        .sqrt();
    let (a, b) = (j[0][0].hypot(j[1][0]), j[0][1].hypot(j[1][1]));
    let r = a.min(b) / a.max(b);
    1.0 - lambda > 0.05 * r * r
}

/// `λ_min / λ_max` of `K` (row-major 8×8) with the rigid-body modes of the current nodes `x`
/// shifted to the top of the spectrum; `None` for a non-finite tangent.
pub fn smallest_deformation_eigenvalue(k: &[f64; 64], x: &[[f64; 2]; 4]) -> Option<f64> {
    let shifted = shifted_tangent(k, x)?;
    let eig = SymmetricEigen::new(shifted).eigenvalues;
    let (lo, hi) = eig
        .iter()
        .fold((f64::MAX, f64::MIN), |(a, b), v| (a.min(*v), b.max(*v)));
    Some(lo / hi.abs().max(f64::MIN_POSITIVE))
}

/// Whether the element is certainly not unstable, at the cost of one 8×8 Cholesky
/// factorisation instead of an eigenvalue problem: `K̂ + ρ d I` positive definite (`K̂` the
/// shifted tangent of [`smallest_deformation_eigenvalue`], `ρ` = [`UNSTABLE_RATIO`],
/// `d = max_i K̂_ii ≤ λ_max` by Rayleigh's quotient) means `λ_min > −ρ d ≥ −ρ λ_max`, so the
/// ratio is above `−ρ`. A failed factorisation proves nothing: the eigenvalues decide.
pub fn certainly_stable(k: &[f64; 64], x: &[[f64; 2]; 4]) -> bool {
    let Some(mut shifted) = shifted_tangent(k, x) else {
        return false;
    };
    let d = shifted.diagonal().max();
    if d <= 0.0 {
        return false;
    }
    for i in 0..8 {
        shifted[(i, i)] += UNSTABLE_RATIO * d;
    }
    shifted.cholesky().is_some()
}

/// The symmetric part of `K` with the rigid-body modes of the current nodes `x` shifted by
/// its trace (to the top of the spectrum); `None` for a non-finite tangent.
fn shifted_tangent(k: &[f64; 64], x: &[[f64; 2]; 4]) -> Option<SMatrix<f64, 8, 8>> {
    let km = SMatrix::<f64, 8, 8>::from_row_slice(k);
    if !km.iter().all(|v| v.is_finite()) {
        return None;
    }
    let sym = (km + km.transpose()) * 0.5;
    let shift = sym.trace().abs().max(f64::MIN_POSITIVE);
    let c = x
        .iter()
        .fold([0.0, 0.0], |s, p| [s[0] + 0.25 * p[0], s[1] + 0.25 * p[1]]);
    let mut modes: Vec<SVector<f64, 8>> = Vec::with_capacity(3);
    for m in 0..3 {
        let mut v = SVector::<f64, 8>::zeros();
        for (i, p) in x.iter().enumerate() {
            let (vx, vy) = match m {
                0 => (1.0, 0.0),
                1 => (0.0, 1.0),
                _ => (-(p[1] - c[1]), p[0] - c[0]),
            };
            v[2 * i] = vx;
            v[2 * i + 1] = vy;
        }
        for q in &modes {
            v -= q * q.dot(&v);
        }
        modes.push(v.normalize());
    }
    let mut shifted = sym;
    for q in &modes {
        shifted += q * q.transpose() * shift;
    }
    Some(shifted)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::element::material::{lame, Material};
    use crate::element::quad::{
        hourglass_holds, quad_residual_tangent, quad_residual_tangent_with, ElementKind, QuadGeometry,
    };

    #[test]
    fn an_element_at_rest_and_a_stretched_one_are_stable() {
        let (l, m) = lame(1e3, 0.3);
        let mat = Material::NeoHookean { lambda: l, mu: m };
        let x = [[0.0, 0.0], [1.0, 0.0], [1.0, 0.5], [0.0, 0.5]];
        for u in [[[0.0; 2]; 4], [[0.0, 0.0], [0.1, 0.0], [0.1, 0.01], [0.0, 0.01]]] {
            let (mut a, mut r, mut k) = ([0.0; 4], [0.0; 8], [0.0; 64]);
            quad_residual_tangent(ElementKind::Q4Eas, &mat, &x, &u, &mut a, &mut r, Some(&mut k)).unwrap();
            let cur: [[f64; 2]; 4] = std::array::from_fn(|i| [x[i][0] + u[i][0], x[i][1] + u[i][1]]);
            let ratio = smallest_deformation_eigenvalue(&k, &cur).unwrap();
            assert!(ratio > 0.0, "{ratio}");
        }
    }

    #[test]
    fn a_tall_eas_element_compressed_across_its_short_side_is_unstable_and_the_safe_one_is_not() {
        // 12 times taller than long, compressed by 5 % along x: beyond (a/b)² ≈ 0.7 %
        let (l, m) = lame(2.1e4, 0.3);
        let mat = Material::NeoHookean { lambda: l, mu: m };
        let x = [[0.0, 0.0], [0.1, 0.0], [0.1, 1.2], [0.0, 1.2]];
        let u: [[f64; 2]; 4] = std::array::from_fn(|i| [-0.05 * x[i][0], 0.0]);
        let cur: [[f64; 2]; 4] = std::array::from_fn(|i| [x[i][0] + u[i][0], x[i][1]]);
        let ratio = |kind| {
            let (mut a, mut r, mut k) = ([0.0; 4], [0.0; 8], [0.0; 64]);
            let mut geo = QuadGeometry::for_material(kind, &mat, &x).unwrap();
            if kind == ElementKind::Q4EasSafe {
                // held from the converged state (as the assembler does after each increment)
                geo.set_alpha_penalty(hourglass_holds(&geo, &mat, &u), &mat);
            }
            quad_residual_tangent_with(kind, &mat, &geo, &u, &mut a, &mut r, Some(&mut k)).unwrap();
            smallest_deformation_eigenvalue(&k, &cur).unwrap()
        };
        assert!(
            ratio(ElementKind::Q4Eas) < -UNSTABLE_RATIO,
            "{}",
            ratio(ElementKind::Q4Eas)
        );
        assert!(ratio(ElementKind::Q4EasSafe) > 0.0, "{}", ratio(ElementKind::Q4EasSafe));
    }

    /// The Cholesky screen never calls an element stable that the eigenvalues call unstable,
    /// and passes the stable ones that are not near the threshold: tall and square elements
    /// of both kinds compressed from 0 to 30 % across and sheared.
    #[test]
    fn the_cholesky_screen_agrees_with_the_eigenvalues() {
        let (l, m) = lame(2.1e4, 0.3);
        let mat = Material::NeoHookean { lambda: l, mu: m };
        let (mut passed, mut unstable) = (0, 0);
        for height in [0.1, 0.5, 1.2] {
            let x = [[0.0, 0.0], [0.1, 0.0], [0.1, height], [0.0, height]];
            for step in 0..=30 {
                let (c, g) = (0.01 * f64::from(step), 0.002 * f64::from(step));
                let u: [[f64; 2]; 4] = std::array::from_fn(|i| [-c * x[i][0] + g * x[i][1], 0.0]);
                let cur: [[f64; 2]; 4] = std::array::from_fn(|i| [x[i][0] + u[i][0], x[i][1] + u[i][1]]);
                for kind in [ElementKind::Q4Eas, ElementKind::Q4] {
                    let (mut a, mut r, mut k) = ([0.0; 4], [0.0; 8], [0.0; 64]);
                    quad_residual_tangent(kind, &mat, &x, &u, &mut a, &mut r, Some(&mut k)).unwrap();
                    let ratio = smallest_deformation_eigenvalue(&k, &cur).unwrap();
                    let screened = certainly_stable(&k, &cur);
                    assert!(
                        !(screened && ratio < -UNSTABLE_RATIO),
                        "{height} {step} {kind:?}: {ratio}"
                    );
                    if ratio > 1e-6 {
                        assert!(screened, "{height} {step} {kind:?}: {ratio} not screened");
                    }
                    passed += usize::from(screened);
                    unstable += usize::from(ratio < -UNSTABLE_RATIO);
                }
            }
        }
        assert!(passed > 50 && unstable > 5, "{passed} screened, {unstable} unstable");
    }
}
