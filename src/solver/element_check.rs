//! Element stability at a converged increment: the elements whose own tangent has lost
//! positive definiteness in a deformation mode other than a rigid motion.
//!
//! For each element the condensed tangent `K_e` (8×8 for a quadrilateral, 24×24 for a
//! hexahedron; symmetric for the hyperelastic elements) is evaluated at the converged
//! displacements, the rigid-body modes of its current position — `D` translations and the
//! rotations in each coordinate plane `(i, j)`, `v_i = −(x_j − c_j)`, `v_j = x_i − c_i` (one
//! in 2D, three in 3D), orthonormalised — are shifted out of the way (`K_e + s Σ r rᵀ`, `s` =
//! the trace), and the smallest eigenvalue is compared with the largest:
//! `λ_min < −10⁻⁸ λ_max` means the element alone can deform without resistance — an
//! hourglass pattern of an enhanced-strain element in compression (Wriggers & Reese 1996), or
//! an element inverted in all but name. A mesh of such elements may still converge, to a
//! wrong answer; the run says so instead.
//!
//! Only elements compressed enough for the instability to be possible are checked (see
//! `worth_checking`): an element's tangent at small strain is positive definite. The shift of
//! the rigid modes is written once over the element's size (`D` coordinates, `N = D · nodes`
//! DOFs); the eigenvalues and the Cholesky screen are taken of the concrete 8×8 (quadrilateral)
//! and 24×24 (hexahedron) matrices.

use crate::assembly::{Assembler, AssemblyError};
use crate::element::hex8::{hex8_dn_dxi, hex8_jacobian};
use crate::model::{Dim, Model, Plane, Solid};
use nalgebra::{Matrix3, SMatrix, SVector, SymmetricEigen};

/// Relative size of a negative eigenvalue that counts as a loss of stability.
pub const UNSTABLE_RATIO: f64 = 1e-8;

/// An element that lost stability, with `λ_min/λ_max` of its tangent (rigid modes aside).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct UnstableElement {
    pub element: usize,
    pub ratio: f64,
}

/// The unstable elements at displacements `u` with enhanced parameters `alphas` (flat,
/// [`Dim::ALPHAS`] per element), worst first: quadrilaterals in 2D, hexahedra in 3D.
pub fn unstable_elements<S: Dim>(
    model: &Model<S>,
    asm: &Assembler<S>,
    u: &[f64],
    alphas: &[f64],
) -> Result<Vec<UnstableElement>, AssemblyError> {
    let any: (&dyn std::any::Any, &dyn std::any::Any) = (model, asm);
    if let (Some(model), Some(asm)) = (
        any.0.downcast_ref::<Model<Plane>>(),
        any.1.downcast_ref::<Assembler<Plane>>(),
    ) {
        return unstable_quads(model, asm, u, Plane::alphas(alphas));
    }
    match (
        any.0.downcast_ref::<Model<Solid>>(),
        any.1.downcast_ref::<Assembler<Solid>>(),
    ) {
        (Some(model), Some(asm)) => unstable_hexes(model, asm, u, Solid::alphas(alphas)),
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

/// The hexahedra's check, as [`unstable_quads`] (the same screen, then the eigenvalues).
fn unstable_hexes(
    model: &Model<Solid>,
    asm: &Assembler<Solid>,
    u: &[f64],
    alphas: &[[f64; crate::element::hex8::EAS_COUNT]],
) -> Result<Vec<UnstableElement>, AssemblyError> {
    let mut out = Vec::new();
    let mut k = [0.0; 576];
    for (ie, el) in model.elements.iter().enumerate() {
        let ue: [[f64; 3]; 8] = el.nodes.map(|n| [u[3 * n], u[3 * n + 1], u[3 * n + 2]]);
        if ue.iter().flatten().all(|v| v.abs() < 1e-12) {
            continue;
        }
        let x0: [[f64; 3]; 8] = el.nodes.map(|n| model.nodes[n]);
        if !hex8_worth_checking(&x0, &ue) {
            continue;
        }
        let x: [[f64; 3]; 8] = std::array::from_fn(|i| std::array::from_fn(|c| x0[i][c] + ue[i][c]));
        asm.element_tangent(model, ie, u, &alphas[ie], &mut k)?;
        if hex8_certainly_stable(&k, &x) {
            continue;
        }
        if let Some(ratio) = hex8_smallest_deformation_eigenvalue(&k, &x).filter(|r| *r < -UNSTABLE_RATIO) {
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

/// The hexahedron's [`worth_checking`]: its centre compression `1 − λ_min` (`λ_min` the
/// smallest principal stretch of `F = I + (∂u/∂ξ) J₀⁻¹` at the centre, `√` of the smallest
/// eigenvalue of `FᵀF`) exceeds `0.05 r²`, `r ≤ 1` the shortest over the longest of its
/// natural axes at the centre (the columns of `J₀`). Plain EAS loses stability in the plane
/// `(k, l)` at a compression along `k` of about `(L_k/L_l)²` (`hex8_stab.rs`), so the
/// threshold sits well below the first plane to go, as in 2D.
fn hex8_worth_checking(x: &[[f64; 3]; 8], ue: &[[f64; 3]; 8]) -> bool {
    let d = hex8_dn_dxi(&[0.0; 3]);
    let j = hex8_jacobian(x, &d);
    let du = hex8_jacobian(ue, &d); // ∂u_a/∂ξ_b
    let Some(inv) = j.try_inverse().filter(|_| j.determinant() > 0.0) else {
        return true;
    };
    let f = Matrix3::identity() + du * inv;
    let c = f.transpose() * f;
    let lambda = c.symmetric_eigenvalues().min().max(0.0).sqrt();
    let len: [f64; 3] = std::array::from_fn(|k| j.column(k).norm());
    let (lo, hi) = len.iter().fold((f64::MAX, 0.0f64), |(a, b), v| (a.min(*v), b.max(*v)));
    let r = lo / hi;
    1.0 - lambda > 0.05 * r * r
}

/// `λ_min / λ_max` of `K` (row-major 8×8) with the rigid-body modes of the current nodes `x`
/// shifted to the top of the spectrum; `None` for a non-finite tangent.
pub fn smallest_deformation_eigenvalue(k: &[f64; 64], x: &[[f64; 2]; 4]) -> Option<f64> {
    let shifted = shifted_tangent::<2, 8>(k, x)?;
    Some(extreme_ratio(SymmetricEigen::new(shifted).eigenvalues.as_slice()))
}

/// The hexahedron's [`smallest_deformation_eigenvalue`]: `K` row-major 24×24, six rigid modes.
pub fn hex8_smallest_deformation_eigenvalue(k: &[f64; 576], x: &[[f64; 3]; 8]) -> Option<f64> {
    let shifted = shifted_tangent::<3, 24>(k, x)?;
    Some(extreme_ratio(SymmetricEigen::new(shifted).eigenvalues.as_slice()))
}

/// `λ_min / |λ_max|` of a spectrum.
fn extreme_ratio(eig: &[f64]) -> f64 {
    let (lo, hi) = eig
        .iter()
        .fold((f64::MAX, f64::MIN), |(a, b), v| (a.min(*v), b.max(*v)));
    lo / hi.abs().max(f64::MIN_POSITIVE)
}

/// Whether the element is certainly not unstable, at the cost of one 8×8 Cholesky
/// factorisation instead of an eigenvalue problem: `K̂ + ρ d I` positive definite (`K̂` the
/// shifted tangent of [`smallest_deformation_eigenvalue`], `ρ` = [`UNSTABLE_RATIO`],
/// `d = max_i K̂_ii ≤ λ_max` by Rayleigh's quotient) means `λ_min > −ρ d ≥ −ρ λ_max`, so the
/// ratio is above `−ρ`. A failed factorisation proves nothing: the eigenvalues decide.
pub fn certainly_stable(k: &[f64; 64], x: &[[f64; 2]; 4]) -> bool {
    shifted_tangent::<2, 8>(k, x).is_some_and(screen)
}

/// The hexahedron's [`certainly_stable`] (one 24×24 Cholesky factorisation).
pub fn hex8_certainly_stable(k: &[f64; 576], x: &[[f64; 3]; 8]) -> bool {
    shifted_tangent::<3, 24>(k, x).is_some_and(screen)
}

/// The Cholesky screen of [`certainly_stable`] on a shifted tangent.
fn screen<const N: usize>(mut shifted: SMatrix<f64, N, N>) -> bool {
    let d = shifted.diagonal().max();
    if d <= 0.0 {
        return false;
    }
    for i in 0..N {
        shifted[(i, i)] += UNSTABLE_RATIO * d;
    }
    shifted.cholesky().is_some()
}

/// The symmetric part of `K` (row-major `N × N`, `N = D · nodes`) with the rigid-body modes
/// of the current nodes `x` shifted by its trace (to the top of the spectrum); `None` for a
/// non-finite tangent.
fn shifted_tangent<const D: usize, const N: usize>(k: &[f64], x: &[[f64; D]]) -> Option<SMatrix<f64, N, N>> {
    let km = SMatrix::<f64, N, N>::from_row_slice(k);
    if !km.iter().all(|v| v.is_finite()) {
        return None;
    }
    let sym = (km + km.transpose()) * 0.5;
    let shift = sym.trace().abs().max(f64::MIN_POSITIVE);
    let mut shifted = sym;
    for q in &rigid_modes::<D, N>(x) {
        shifted += q * q.transpose() * shift;
    }
    Some(shifted)
}

/// The orthonormalised rigid-body modes of nodes `x`: the `D` translations, then the
/// rotations about the centroid `c` in the planes `(i, j)`, `i < j`.
fn rigid_modes<const D: usize, const N: usize>(x: &[[f64; D]]) -> Vec<SVector<f64, N>> {
    let w = 1.0 / x.len() as f64;
    let c = x.iter().fold([0.0; D], |mut s, p| {
        for (sa, pa) in s.iter_mut().zip(p) {
            *sa += w * pa;
        }
        s
    });
    let planes = (0..D).flat_map(|i| (i + 1..D).map(move |j| (i, j)));
    let fields: Vec<(usize, usize, bool)> = (0..D)
        .map(|a| (a, a, false))
        .chain(planes.map(|(i, j)| (i, j, true)))
        .collect();
    let mut modes: Vec<SVector<f64, N>> = Vec::with_capacity(fields.len());
    for (i, j, rotation) in fields {
        let mut v = SVector::<f64, N>::zeros();
        for (n, p) in x.iter().enumerate() {
            if rotation {
                v[D * n + i] = -(p[j] - c[j]);
                v[D * n + j] = p[i] - c[i];
            } else {
                v[D * n + i] = 1.0;
            }
        }
        for q in &modes {
            v -= q * q.dot(&v);
        }
        modes.push(v.normalize());
    }
    modes
}

#[cfg(test)]
#[path = "element_check_tests.rs"]
mod tests;
