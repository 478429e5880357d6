//! The solid-shell: an eight-node hexahedron for thin bodies, with assumed natural strains
//! (ANS) for the transverse shears and the thickness strain and five enhanced modes — the
//! linear solid-shell of Harnau & Schweizerhof (Comput Struct 80 (2002) 805–817), the element
//! of the seed's strip (Harnau, Konyukhov & Schweizerhof, Comput Struct 83 (2005) 1804–1823).
//!
//! # Formulation
//! Node order and `N_I` as [`super::Hex8Kind::Hex8`]; `ζ` (nodes 0–3 to 4–7) runs through
//! the thickness. With the covariant base vectors `G_a = ∂X/∂ξ_a`, `g_a = G_a + ∂u/∂ξ_a`, the
//! natural Green–Lagrange strains are `Ê_ab = ½ (g_a·g_b − G_a·G_b)` (Voigt rows `ξξ, ηη,
//! ζζ, 2ξη, 2ηζ, 2ξζ`). Three of them are assumed, sampled on the mid-surface `ζ = 0`:
//! - transverse shear (Bathe & Dvorkin, IJNME 22 (1986) 697–722): `2Ê_ξζ` from the points
//!   `A = (0, −1, 0)` and `C = (0, 1, 0)`, linear in `η`; `2Ê_ηζ` from `B = (−1, 0, 0)` and
//!   `D = (1, 0, 0)`, linear in `ξ` — free of transverse shear locking;
//! - thickness strain (Betsch & Stein, Comm Numer Meth Eng 11 (1995) 899–909): `Ê_ζζ` from
//!   the four corners `(±1, ±1, 0)`, bilinear in `ξ, η` — free of the trapezoidal (curvature)
//!   thickness locking.
//!
//! The Cartesian strain at a Gauss point is `E = T_q Ê` (`T_q` the covariant-to-Cartesian map
//! with the Jacobian at that point, so the components not assumed are the compatible ones),
//! and five enhanced modes are added as in the hexahedron, `Ẽ = (j₀/j) T₀ M α`
//! ([`SHELL_EAS_MODES`]): `ζ` in `ζζ` (the linear thickness strain that bending with Poisson's
//! ratio needs: without it the element locks, Büchter, Ramm & Roehl, IJNME 37 (1994)
//! 2551–2568) and the four membrane modes of the 2D element's EAS-4 (`ξ` in `ξξ`, `η` in `ηη`,
//! `ξ, η` in `2ξη`: in-plane bending). Condensation and the local iteration are the
//! hexahedron's (`hex8_kernel.rs`).
//!
//! Linearisation: `δE = T_q δÊ`, `δÊ_ab = ½ (g_a·δg_b + δg_a·g_b)`, assumed rows interpolated
//! from the sampling points; the geometric stiffness is
//! `Σ_points d_pᵀ Σ_p d_p` (`d_p = ∂N/∂ξ` at the point, `Σ_p` the natural stress `Ŝ = T_qᵀ S`
//! of the rows the point carries, times their interpolation weight).
//!
//! The patch test holds to round-off where the thickness direction `G_ζ` is constant (meshes
//! straight through the thickness, any in-plane distortion): there the assumed components of
//! a homogeneous strain are linear in the in-plane coordinates and interpolated exactly.

use super::kernel::{add_node_pairs_upper, enhanced_residual_tangent, EnhancedElement, PassPoint};
use super::{
    factored_modes, hex8_dn_dxi, hex8_jacobian, strain_transformation, Hex8Error, Hex8Geometry, Material, EAS_COUNT,
    HEX8_GAUSS, PAIRS,
};
use nalgebra::{Matrix3, Matrix6, SMatrix, Vector6};

/// Number of enhanced parameters of the solid-shell (the first entries of the element's `α`).
pub const SHELL_EAS_COUNT: usize = 5;

/// The solid-shell's enhanced modes, `(natural Voigt row, natural coordinates)` as
/// [`super::EAS_MODES`].
pub const SHELL_EAS_MODES: [(usize, &[usize]); SHELL_EAS_COUNT] =
    [(0, &[0]), (1, &[1]), (3, &[0]), (3, &[1]), (2, &[2])];

/// Sampling points of the assumed strains: `A, C` (`2Ê_ξζ`), `B, D` (`2Ê_ηζ`), then the four
/// mid-surface corners (`Ê_ζζ`).
const SAMPLES: [[f64; 3]; 8] = [
    [0.0, -1.0, 0.0],
    [0.0, 1.0, 0.0],
    [-1.0, 0.0, 0.0],
    [1.0, 0.0, 0.0],
    [-1.0, -1.0, 0.0],
    [1.0, -1.0, 0.0],
    [1.0, 1.0, 0.0],
    [-1.0, 1.0, 0.0],
];

/// The assumed rows and the samples each interpolates: `(row, sample indices)`.
const ASSUMED: [(usize, &[usize]); 3] = [(5, &[0, 1]), (4, &[2, 3]), (2, &[4, 5, 6, 7])];

/// Interpolation weights of the samples at natural point `p` (indices of [`SAMPLES`]).
fn sample_weights(p: &[f64; 3]) -> [f64; 8] {
    let [xi, eta, _] = *p;
    let corner = |k: usize| 0.25 * (1.0 + SAMPLES[k][0] * xi) * (1.0 + SAMPLES[k][1] * eta);
    [
        0.5 * (1.0 - eta),
        0.5 * (1.0 + eta),
        0.5 * (1.0 - xi),
        0.5 * (1.0 + xi),
        corner(4),
        corner(5),
        corner(6),
        corner(7),
    ]
}

/// Natural strains and their variations at one point: `d = ∂N/∂ξ` (3×8), the reference
/// and current base vectors as columns of `big_g` and `small_g`.
struct NaturalPoint {
    d: SMatrix<f64, 3, 8>,
    big_g: Matrix3<f64>,
    small_g: Matrix3<f64>,
}

impl NaturalPoint {
    fn new(x: &[[f64; 3]; 8], u: &[[f64; 3]; 8], p: &[f64; 3]) -> Self {
        let d = hex8_dn_dxi(p);
        let big_g = hex8_jacobian(x, &d);
        let small_g = big_g + hex8_jacobian(u, &d);
        NaturalPoint { d, big_g, small_g }
    }

    /// `Ê_aa = ½ (g_a·g_a − G_a·G_a)`, `2Ê_ab = g_a·g_b − G_a·G_b` of Voigt row `row`.
    fn strain(&self, row: usize) -> f64 {
        let (a, b) = PAIRS[row];
        let (g, gr) = (&self.small_g, &self.big_g);
        let v = g.column(a).dot(&g.column(b)) - gr.column(a).dot(&gr.column(b));
        if a == b {
            0.5 * v
        } else {
            v
        }
    }

    /// `∂Ê_row/∂u` (local DOFs `[u0x, u0y, u0z, u1x, …]`).
    fn variation(&self, row: usize) -> [f64; 24] {
        let (a, b) = PAIRS[row];
        std::array::from_fn(|col| {
            let (node, r) = (col / 3, col % 3);
            if a == b {
                self.d[(a, node)] * self.small_g[(r, a)]
            } else {
                self.d[(b, node)] * self.small_g[(r, a)] + self.d[(a, node)] * self.small_g[(r, b)]
            }
        })
    }
}

/// The per-evaluation state: assumed strains at the Gauss points and what the geometric
/// stiffness needs.
struct Assumed {
    points: [(f64, SMatrix<f64, 6, 24>, Vector6<f64>); 8],
    /// `T_q` (natural covariant → Cartesian Voigt) at each Gauss point.
    t: [Matrix6<f64>; 8],
    /// `∂N/∂ξ` at the Gauss points and at the samples.
    d_gauss: [SMatrix<f64, 3, 8>; 8],
    d_samples: [SMatrix<f64, 3, 8>; 8],
}

/// The assumed strains `E = T_q Ê` and `B = T_q B̂` at the eight Gauss points.
fn assumed(geo: &Hex8Geometry, u: &[[f64; 3]; 8]) -> Result<Assumed, Hex8Error> {
    let x = &geo.x;
    let samples = SAMPLES.map(|p| NaturalPoint::new(x, u, &p));
    let mut out = Assumed {
        points: [(0.0, SMatrix::zeros(), Vector6::zeros()); 8],
        t: [Matrix6::zeros(); 8],
        d_gauss: [SMatrix::zeros(); 8],
        d_samples: samples.each_ref().map(|s| s.d),
    };
    for (q, p) in HEX8_GAUSS.iter().enumerate() {
        let at = NaturalPoint::new(x, u, p);
        let jinv = at.big_g.try_inverse().ok_or(Hex8Error::BadGeometry(0.0))?;
        let w = sample_weights(p);
        let mut e_nat = Vector6::zeros();
        let mut b_nat = SMatrix::<f64, 6, 24>::zeros();
        for row in [0, 1, 3] {
            e_nat[row] = at.strain(row);
            b_nat.row_mut(row).copy_from_slice(&at.variation(row));
        }
        for (row, from) in ASSUMED {
            for &s in from {
                e_nat[row] += w[s] * samples[s].strain(row);
                let v = samples[s].variation(row);
                for (c, vc) in v.iter().enumerate() {
                    b_nat[(row, c)] += w[s] * vc;
                }
            }
        }
        let t = strain_transformation(&jinv);
        out.points[q] = (geo.gp[q].dv, t * b_nat, t * e_nat);
        out.t[q] = t;
        out.d_gauss[q] = at.d;
    }
    Ok(out)
}

/// `K_uu += Σ_p d_pᵀ Σ_p d_p dv` at Gauss point `q` (module documentation), `s` the Cartesian
/// second Piola–Kirchhoff stress.
fn geometric_stiffness(a: &Assumed, q: usize, s: &Vector6<f64>, dv: f64, kuu: &mut SMatrix<f64, 24, 24>) {
    let sn = a.t[q].tr_mul(s);
    let at_gauss = Matrix3::new(sn[0], sn[3], 0.0, sn[3], sn[1], 0.0, 0.0, 0.0, 0.0);
    let mut gsg = a.d_gauss[q].tr_mul(&(at_gauss * a.d_gauss[q]));
    let w = sample_weights(&HEX8_GAUSS[q]);
    for (row, from) in ASSUMED {
        let (i, j) = PAIRS[row];
        for &k in from {
            let mut sigma = Matrix3::zeros();
            sigma[(i, j)] = w[k] * sn[row];
            sigma[(j, i)] = w[k] * sn[row];
            let d = &a.d_samples[k];
            gsg += d.tr_mul(&(sigma * d));
        }
    }
    add_node_pairs_upper(kuu, &(gsg * dv));
}

/// The solid-shell's residual, tangent and energy (called by
/// [`super::hex8_residual_tangent_with`] for [`super::Hex8Kind::SolidShell`]; arguments and
/// errors as there, `α` in the first [`SHELL_EAS_COUNT`] entries of `alpha`).
pub(super) fn residual_tangent(
    material: &Material,
    geo: &Hex8Geometry,
    u: &[[f64; 3]; 8],
    alpha: &mut [f64; EAS_COUNT],
    r: &mut [f64; 24],
    k: Option<&mut [f64; 576]>,
) -> Result<f64, Hex8Error> {
    let a = assumed(geo, u)?;
    let (rows, values) = factored_modes::<SHELL_EAS_COUNT>(&SHELL_EAS_MODES);
    let penalty: [f64; SHELL_EAS_COUNT] = std::array::from_fn(|m| geo.penalty[m]);
    let geometric =
        |q: usize, s: &Vector6<f64>, dv: f64, kuu: &mut SMatrix<f64, 24, 24>| geometric_stiffness(&a, q, s, dv, kuu);
    let el = EnhancedElement {
        points: std::array::from_fn(|q| PassPoint {
            dv: a.points[q].0,
            b: &a.points[q].1,
            e: &a.points[q].2,
            scale: geo.gp[q].scale,
            m: &values[q],
        }),
        t0: &geo.t0,
        rows: &rows,
        penalty: &penalty,
        geometric: &geometric,
    };
    let mut al: [f64; SHELL_EAS_COUNT] = std::array::from_fn(|m| alpha[m]);
    let energy = enhanced_residual_tangent(material, &el, true, &mut al, r, k)?;
    alpha[..SHELL_EAS_COUNT].copy_from_slice(&al);
    Ok(energy)
}

/// The strains `E = T_q Ê + G_q α` at the eight Gauss points (for output and tests).
pub(super) fn shell_gauss_strains(
    geo: &Hex8Geometry,
    u: &[[f64; 3]; 8],
    alpha: &[f64; EAS_COUNT],
) -> Result<[Vector6<f64>; 8], Hex8Error> {
    let a = assumed(geo, u)?;
    Ok(std::array::from_fn(|q| {
        let g = geo.enhanced(q);
        let enhanced: Vector6<f64> = (0..SHELL_EAS_COUNT).map(|m| g.column(m) * alpha[m]).sum();
        a.points[q].2 + enhanced
    }))
}
