//! Eight-node hexahedron, total Lagrangian, finite deformation, with optional enhanced
//! assumed strains (EAS) — the 3D counterpart of [`super::quad`] (kernel only: nothing in
//! the solver uses it yet).
//!
//! # Formulation
//! Node ordering of Gmsh and VTK (`VTK_HEXAHEDRON`, Gmsh element type 5): natural
//! coordinates `(ξ, η, ζ) ∈ [−1, 1]³`, nodes 0–3 the bottom face `ζ = −1` counter-clockwise
//! seen from `+ζ` (from above), nodes 4–7 the top face `ζ = +1` in the same order, node
//! `I + 4` above node `I`:
//! `0 (−,−,−)`, `1 (+,−,−)`, `2 (+,+,−)`, `3 (−,+,−)`, `4 (−,−,+)`, `5 (+,−,+)`, `6 (+,+,+)`,
//! `7 (−,+,+)` ([`HEX8_NODES`]); a well-ordered element has `det J > 0` (the bottom face seen
//! from inside the element turns clockwise). `N_I = ⅛ (1 + ξ_I ξ)(1 + η_I η)(1 + ζ_I ζ)`.
//! With `F = I + Σ u_I ⊗ ∇_X N_I`, the compatible Green–Lagrange strain is
//! `E_c = ½ (FᵀF − I)` (Voigt `[11, 22, 33, 12, 23, 13]`, engineering shears, see
//! [`super::material3d`]). Integration: 2×2×2 Gauss.
//!
//! [`Hex8Kind::Hex8Eas`] enriches the Green–Lagrange strain with 21 incompatible modes, the
//! EAS-21 hexahedron of Andelfinger & Ramm (IJNME 36 (1993) 1311–1337), whose first nine
//! modes are the 3D form of the 2D element's EAS-4 (Simo & Rifai, IJNME 29 (1990)
//! 1595–1638); applied to `E` as in the 2D element and in solid shells (Klinkel & Wagner,
//! IJNME 40 (1997) 4529–4545); for finite strain see also Simo & Armero, IJNME 33 (1992)
//! 1413–1449 (their Q1/E9 enhances `F` with the nine linear gradients):
//!
//! `Ẽ = (j₀ / j) T₀ M(ξ, η, ζ) α`, `M` in natural Voigt rows `ξξ, ηη, ζζ, 2ξη, 2ηζ, 2ξζ`
//! ([`EAS_MODES`]):
//! - nine linear modes: `ξ` in `ξξ`, `η` in `ηη`, `ζ` in `ζζ`, `ξ, η` in `2ξη`, `η, ζ` in
//!   `2ηζ`, `ξ, ζ` in `2ξζ` — the symmetric gradients of Wilson's bubbles `(1 − ξ_k²) e_l`, so
//!   in the linear limit on parallelepipeds they make the incompatible-mode hexahedron
//!   (Wilson et al. 1973; Taylor, Beresford & Wilson, IJNME 10 (1976) 1211–1219), exact in
//!   pure bending at any `ν`;
//! - twelve bilinear modes: `ξη, ξζ` in `ξξ`, `ξη, ηζ` in `ηη`, `ξζ, ηζ` in `ζζ` and, in each
//!   shear, the two products containing the coordinate missing from it (`ξζ, ηζ` in `2ξη`,
//!   …). Why 21 and not 9: under a moment varying along the element the volumetric strain
//!   has a bilinear part (`ξζ` in a beam along `ξ` bent in `ξζ`) that the nine linear modes
//!   cannot release: measured on a 10×1×1 cantilever at `ν = 0.4999`, 0.939 of Timoshenko's
//!   deflection with nine modes, 0.9955 with 21 (`hex8_mesh_tests.rs`);
//!
//! where `j = det J`, `j₀` its value at the centre and `T₀` maps covariant strain components
//! in `(ξ, η, ζ)` to Cartesian ones with the centre Jacobian,
//! `E_ij = Σ_ab (J₀⁻¹)_ai (J₀⁻¹)_bj Ê_ab` (the `T₀⁻ᵀ` of Andelfinger & Ramm). Because every
//! mode has `∫ M dξ dη dζ = 0` and `j dξ dη dζ` is the volume element, `∫ Ẽ dV = 0` and a
//! homogeneous state has `α = 0`: the element passes the patch test, on distorted meshes too.
//!
//! The enhanced parameters are element-internal and condensed as in the 2D element: a local
//! Newton iteration solves `R_α(u, α) = ∫ Gᵀ S dV = 0` and the kernel returns
//! `R* = R_u − K_uα K_αα⁻¹ R_α`, `K* = K_uu − K_uα K_αα⁻¹ K_αu`, so the element is a function
//! of `u` alone and `K* = ∂R*/∂u` (checked by finite differences in `hex8_tests.rs`).
//! [`Hex8Kind::Hex8`] is the plain trilinear element, kept as the reference that locks.
//!
//! Hourglassing of EAS in compression (Wriggers & Reese, CMAME 135 (1996) 201–209): the 2D
//! element's hold of its enhanced shear modes carries over, [`hex8_hourglass_holds`]
//! (`hex8_stab.rs`); its blend into the plain element in large compression does not (yet).

use super::material::{Material, MaterialError};
use nalgebra::{Matrix3, Matrix6, SMatrix, SVector, Vector6};

/// Natural coordinates of the nodes, Gmsh/VTK order (module documentation).
pub const HEX8_NODES: [[f64; 3]; 8] = [
    [-1.0, -1.0, -1.0],
    [1.0, -1.0, -1.0],
    [1.0, 1.0, -1.0],
    [-1.0, 1.0, -1.0],
    [-1.0, -1.0, 1.0],
    [1.0, -1.0, 1.0],
    [1.0, 1.0, 1.0],
    [-1.0, 1.0, 1.0],
];

/// 2×2×2 Gauss points `±1/√3` (weights 1), in the order of the nodes they are nearest to.
pub const HEX8_GAUSS: [[f64; 3]; 8] = {
    const G: f64 = 0.577_350_269_189_625_8; // 1/sqrt(3)
    let mut p = [[0.0; 3]; 8];
    let mut i = 0;
    while i < 8 {
        p[i] = [G * HEX8_NODES[i][0], G * HEX8_NODES[i][1], G * HEX8_NODES[i][2]];
        i += 1;
    }
    p
};

/// Number of enhanced parameters of [`Hex8Kind::Hex8Eas`].
pub const EAS_COUNT: usize = 21;

/// The enhanced modes: `(natural Voigt row, the natural coordinates whose product it is)`;
/// rows `0..3` are `ξξ, ηη, ζζ`, `3 = 2ξη`, `4 = 2ηζ`, `5 = 2ξζ`.
pub const EAS_MODES: [(usize, &[usize]); EAS_COUNT] = [
    // the nine linear modes (the 3D EAS-4: Wilson's bubbles)
    (0, &[0]),
    (1, &[1]),
    (2, &[2]),
    (3, &[0]),
    (3, &[1]),
    (4, &[1]),
    (4, &[2]),
    (5, &[0]),
    (5, &[2]),
    // the twelve bilinear ones of EAS-21
    (0, &[0, 1]),
    (0, &[0, 2]),
    (1, &[0, 1]),
    (1, &[1, 2]),
    (2, &[0, 2]),
    (2, &[1, 2]),
    (3, &[0, 2]),
    (3, &[1, 2]),
    (4, &[0, 1]),
    (4, &[0, 2]),
    (5, &[0, 1]),
    (5, &[1, 2]),
];

/// Tensor index pairs of the Voigt rows (the same order in natural and Cartesian components).
const PAIRS: [(usize, usize); 6] = super::material3d::VOIGT_PAIRS;

/// Which hexahedron formulation an element uses.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Hex8Kind {
    /// Trilinear displacement element (locks in bending and near incompressibility).
    Hex8,
    /// Trilinear element with the enhanced strain modes (module documentation).
    Hex8Eas,
    /// The solid-shell for thin bodies: assumed transverse shear and thickness strains and
    /// five enhanced modes, `ζ` through the thickness (`solid_shell.rs`).
    SolidShell,
}

/// Failure of a hexahedron evaluation; a solver treats it as a divergent iteration.
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
pub enum Hex8Error {
    /// `det J ≤ 0` (or not finite) at the centre or a Gauss point of the reference element.
    #[error("reference Jacobian det J = {0:.3e} ≤ 0 (nodes not in Gmsh/VTK order, or degenerate)")]
    BadGeometry(f64),
    #[error(transparent)]
    Material(#[from] MaterialError),
    #[error("enhanced-strain parameters did not converge (|R_α| = {0:.3e})")]
    EasNotConverged(f64),
    /// `K_αα` is singular: the element is degenerate (flattened, or distorted beyond what its
    /// enhanced modes can take).
    #[error("degenerate element: its enhanced-strain stiffness K_αα is singular")]
    EasSingular,
    /// The element is folded: `det F ≤ 0` (or not finite) at a Gauss point of the compatible
    /// deformation.
    #[error("inverted element: det F = {0:.3e} ≤ 0 at a Gauss point")]
    Inverted(f64),
}

/// Shape-function derivatives with respect to the natural coordinates, `d[(b, I)] = ∂N_I/∂ξ_b`.
pub fn hex8_dn_dxi(p: &[f64; 3]) -> SMatrix<f64, 3, 8> {
    SMatrix::from_fn(|b, i| {
        let n = HEX8_NODES[i];
        // ⅛ ξ_Ib Π_{c≠b} (1 + ξ_Ic ξ_c)
        let f = |c: usize| if c == b { 0.125 * n[c] } else { 1.0 + n[c] * p[c] };
        f(0) * f(1) * f(2)
    })
}

/// Jacobian `J_ab = ∂X_a/∂ξ_b` of reference nodes `x` for the derivatives `d` of [`hex8_dn_dxi`].
pub fn hex8_jacobian(x: &[[f64; 3]; 8], d: &SMatrix<f64, 3, 8>) -> Matrix3<f64> {
    Matrix3::from_fn(|a, b| (0..8).map(|i| x[i][a] * d[(b, i)]).sum())
}

/// `T`: covariant natural Voigt strain → Cartesian Voigt strain (engineering shears), with
/// `A = J⁻¹`: `E_ij = Σ_ab A_ai A_bj Ê_ab` (`T₀` with the centre Jacobian).
fn strain_transformation(a: &Matrix3<f64>) -> Matrix6<f64> {
    Matrix6::from_fn(|p, q| {
        let ((i, j), (k, l)) = (PAIRS[p], PAIRS[q]);
        let fp = if i == j { 1.0 } else { 2.0 };
        if k == l {
            fp * a[(k, i)] * a[(k, j)]
        } else {
            fp * 0.5 * (a[(k, i)] * a[(l, j)] + a[(l, i)] * a[(k, j)])
        }
    })
}

/// `M(ξ, η, ζ)`: the enhanced `modes` ([`EAS_MODES`] or the solid-shell's) in natural Voigt
/// components, in the first columns.
fn eas_interpolation(modes: &[(usize, &[usize])], p: &[f64; 3]) -> SMatrix<f64, 6, EAS_COUNT> {
    let mut m = SMatrix::zeros();
    for (c, &(row, axes)) in modes.iter().enumerate() {
        m[(row, c)] = axes.iter().map(|&a| p[a]).product::<f64>();
    }
    m
}

/// Per-Gauss-point quantities of the reference configuration (independent of `u` and `α`).
#[derive(Debug, Clone, Copy)]
pub(crate) struct GaussGeom {
    /// `grad[(a, I)] = ∂N_I/∂X_a`
    pub grad: SMatrix<f64, 3, 8>,
    /// `j · w` (weights are 1 for 2×2×2 Gauss)
    pub dv: f64,
    /// `j₀ / j`: the enhanced interpolation here is `G = (j₀/j) T₀ M(ξ_q)`
    /// ([`Hex8Geometry::enhanced`]).
    pub scale: f64,
}

/// Reference geometry of one hexahedron at its eight Gauss points: shape-function gradients,
/// volume weights and the factors of the EAS interpolation `G = (j₀/j) T₀ M`; computed once
/// per element. `G` is kept factored (`T₀` per element, `j₀/j` per point, `M` a constant of
/// the Gauss point with one entry per mode): a dense `G` would be 1 kB per point, and the
/// kernel's products with it cost three times those with the factors.
#[derive(Debug, Clone, Copy)]
pub struct Hex8Geometry {
    pub(crate) gp: [GaussGeom; 8],
    /// `T₀`: covariant natural Voigt strain → Cartesian Voigt strain at the centre.
    pub(crate) t0: Matrix6<f64>,
    /// Columns: the natural axes at the centre, `∂X/∂ξ`, `∂X/∂η`, `∂X/∂ζ` (half the element's
    /// extents along them).
    pub(crate) axes: Matrix3<f64>,
    /// Penalty `p_m` on each enhanced parameter, `Π += ½ Σ p_m α_m²` (zero unless set from
    /// [`hex8_hourglass_holds`]).
    pub(crate) penalty: [f64; EAS_COUNT],
    /// The reference nodes (the solid-shell samples its assumed strains from them).
    pub(crate) x: [[f64; 3]; 8],
    pub(crate) kind: Hex8Kind,
}

/// The enhanced modes of an element kind ([`EAS_MODES`], [`SHELL_EAS_MODES`], none).
pub(crate) fn modes_of(kind: Hex8Kind) -> &'static [(usize, &'static [usize])] {
    match kind {
        Hex8Kind::Hex8 => &[],
        Hex8Kind::Hex8Eas => &EAS_MODES,
        Hex8Kind::SolidShell => &SHELL_EAS_MODES,
    }
}

/// The first `N` of `modes` as the kernel takes them: each mode's natural Voigt row, and
/// its value `M_m(ξ_q)` at each Gauss point.
pub(crate) fn factored_modes<const N: usize>(modes: &[(usize, &[usize])]) -> ([usize; N], [[f64; N]; 8]) {
    let rows = std::array::from_fn(|m| modes[m].0);
    let values =
        std::array::from_fn(|q| std::array::from_fn(|m| modes[m].1.iter().map(|&a| HEX8_GAUSS[q][a]).product::<f64>()));
    (rows, values)
}

/// `det J` if it is positive and finite, else [`Hex8Error::BadGeometry`].
fn positive_det(j: &Matrix3<f64>) -> Result<f64, Hex8Error> {
    let det = j.determinant();
    if det <= 0.0 || !det.is_finite() {
        return Err(Hex8Error::BadGeometry(det));
    }
    Ok(det)
}

impl Hex8Geometry {
    /// Geometry of the element with reference nodes `x` (Gmsh/VTK order); fails on a
    /// non-positive or non-finite `det J` at the centre or a Gauss point.
    pub fn new(kind: Hex8Kind, x: &[[f64; 3]; 8]) -> Result<Self, Hex8Error> {
        let j0 = hex8_jacobian(x, &hex8_dn_dxi(&[0.0; 3]));
        let det0 = positive_det(&j0)?;
        let t0 = strain_transformation(&j0.try_inverse().ok_or(Hex8Error::BadGeometry(det0))?);
        let mk = |p: &[f64; 3]| -> Result<GaussGeom, Hex8Error> {
            let d = hex8_dn_dxi(p);
            let jm = hex8_jacobian(x, &d);
            let det = positive_det(&jm)?;
            let jinv = jm.try_inverse().ok_or(Hex8Error::BadGeometry(det))?;
            // ∂N/∂X_a = Σ_b ∂N/∂ξ_b (J⁻¹)_ba
            let grad = jinv.transpose() * d;
            Ok(GaussGeom {
                grad,
                dv: det,
                scale: det0 / det,
            })
        };
        let mut gp = [GaussGeom {
            grad: SMatrix::zeros(),
            dv: 0.0,
            scale: 0.0,
        }; 8];
        for (q, p) in gp.iter_mut().zip(&HEX8_GAUSS) {
            *q = mk(p)?;
        }
        Ok(Hex8Geometry {
            gp,
            t0,
            axes: j0,
            penalty: [0.0; EAS_COUNT],
            x: *x,
            kind,
        })
    }

    /// `G_q = (j₀/j_q) T₀ M(ξ_q)`: the enhanced interpolation `Ẽ = G α` at Gauss point `q`,
    /// dense (6×21; zero for [`Hex8Kind::Hex8`], the first five columns for
    /// [`Hex8Kind::SolidShell`]).
    pub(crate) fn enhanced(&self, q: usize) -> SMatrix<f64, 6, EAS_COUNT> {
        self.gp[q].scale * self.t0 * eas_interpolation(modes_of(self.kind), &HEX8_GAUSS[q])
    }

    /// Reference volume `Σ_q j_q` (exact for the trilinear map).
    pub fn volume(&self) -> f64 {
        self.gp.iter().map(|q| q.dv).sum()
    }
}

/// `F = I + Σ_I u_I ⊗ ∇N_I` at one Gauss point.
fn deformation_gradient(grad: &SMatrix<f64, 3, 8>, u: &[[f64; 3]; 8]) -> Matrix3<f64> {
    Matrix3::from_fn(|r, c| {
        let delta = if r == c { 1.0 } else { 0.0 };
        delta + (0..8).map(|i| u[i][r] * grad[(c, i)]).sum::<f64>()
    })
}

/// The smallest `det F` of the compatible deformation over the Gauss points (a folded
/// element has `det F < 0` where `C = FᵀF`, hence `E`, is admissible: the kernel's check).
pub fn hex8_min_det_f(geo: &Hex8Geometry, u: &[[f64; 3]; 8]) -> f64 {
    geo.gp
        .iter()
        .map(|q| deformation_gradient(&q.grad, u).determinant())
        .fold(f64::INFINITY, |m, d| {
            if m.is_nan() || d.is_nan() {
                f64::NAN
            } else {
                m.min(d)
            }
        })
}

/// Strain–displacement matrix `δE_c = B δu` (local DOFs `[u0x, u0y, u0z, u1x, …]`) and the
/// compatible strain `E_c` at one Gauss point.
#[derive(Clone, Copy)]
struct GaussKin {
    b: SMatrix<f64, 6, 24>,
    ec: Vector6<f64>,
}

fn kinematics(gq: &GaussGeom, u: &[[f64; 3]; 8]) -> GaussKin {
    let f = deformation_gradient(&gq.grad, u);
    let mut b = SMatrix::<f64, 6, 24>::zeros();
    // δE_ij = ½ (Fᵀ δF + δFᵀ F)_ij, δF = δu_I ⊗ ∇N_I: rows in [`PAIRS`] order
    for (node, g) in gq.grad.column_iter().enumerate() {
        for r in 0..3 {
            let mut col = b.column_mut(3 * node + r);
            let fr = f.row(r);
            col[0] = fr[0] * g[0];
            col[1] = fr[1] * g[1];
            col[2] = fr[2] * g[2];
            col[3] = fr[0] * g[1] + fr[1] * g[0];
            col[4] = fr[1] * g[2] + fr[2] * g[1];
            col[5] = fr[0] * g[2] + fr[2] * g[0];
        }
    }
    let c = f.transpose() * f;
    let ec = Vector6::from_fn(|a, _| {
        let (i, j) = PAIRS[a];
        if i == j {
            0.5 * (c[(i, i)] - 1.0)
        } else {
            c[(i, j)]
        }
    });
    GaussKin { b, ec }
}

/// The Green–Lagrange strain `E = E_c + G α` at the eight Gauss points (for output and tests;
/// `α` as returned by the kernel for this `u`; the solid-shell's assumed `E`).
pub fn hex8_gauss_strains(
    geo: &Hex8Geometry,
    u: &[[f64; 3]; 8],
    alpha: &[f64; EAS_COUNT],
) -> Result<[Vector6<f64>; 8], Hex8Error> {
    if geo.kind == Hex8Kind::SolidShell {
        return solid_shell::shell_gauss_strains(geo, u, alpha);
    }
    let al = SVector::from(*alpha);
    Ok(std::array::from_fn(|q| {
        kinematics(&geo.gp[q], u).ec + geo.enhanced(q) * al
    }))
}

#[path = "hex8_kernel.rs"]
mod kernel;
pub use kernel::{hex8_residual_tangent, hex8_residual_tangent_with, EAS_STRAIN_TOLERANCE};

#[path = "solid_shell.rs"]
mod solid_shell;
pub use solid_shell::{SHELL_EAS_COUNT, SHELL_EAS_MODES};

#[path = "hex8_stab.rs"]
mod stab;
pub use stab::{hex8_hourglass_holds, HOLD_FROM, HOLD_GROWTH};

#[cfg(test)]
#[path = "hex8_tests.rs"]
mod tests;

#[cfg(test)]
#[path = "hex8_mesh_tests.rs"]
mod mesh_tests;

#[cfg(test)]
#[path = "solid_shell_tests.rs"]
mod shell_tests;
