//! The hold of the hexahedron's enhanced shear modes against their hourglass instability in
//! compression: the 2D element's `hourglass_holds` (`quad_stab.rs`) in three dimensions.

use super::{deformation_gradient, Hex8Geometry, Material, EAS_COUNT, EAS_MODES, PAIRS};
use nalgebra::{Matrix6, Vector3};

/// Compression (relative to the critical one) from which an enhanced shear mode is held,
/// and the growth of the hold: `p = K⁰_mm · HOLD_GROWTH · ⟨x − HOLD_FROM⟩²` (the 2D values).
pub const HOLD_FROM: f64 = 0.05;
pub const HOLD_GROWTH: f64 = 40.0;

/// For an enhanced shear mode, the natural axis whose compression frees its hourglass
/// pattern, and the axis the mode varies along; `None` for the normal modes and the
/// bilinear ones (no hourglass pattern of the trilinear element is theirs alone).
///
/// The shear mode `ξ_l` in the `kl` component cancels the shear of the pattern
/// `u_k ∝ ξ_k ξ_l` (the 2D zig-zag, in the `kl` plane); compression along `k` softens it.
fn held_by(mode: usize) -> Option<(usize, usize)> {
    let (row, &[l]) = EAS_MODES[mode] else {
        return None;
    };
    let (i, j) = PAIRS[row];
    (i != j).then_some((if i == l { j } else { i }, l))
}

/// The penalties that hold the hourglass modes of an EAS hexahedron at a converged state `u`,
/// for the next increment (set them with [`Hex8Geometry::set_alpha_penalty`]).
///
/// The 2D rule per plane: for each natural axis `k` (`e_k = ∂X/∂ξ_k` at the centre, half
/// extent `L_k`) the largest compression along it over the Gauss points,
/// `c_k = max_q (1 − |F_q e_k|/|e_k|)`, is measured for each shear mode varying along `l`
/// ([`held_by`]) against the compression at which plain EAS loses stability in that plane,
/// `(L_k/L_l)²`: `x = c_k (L_l/L_k)²`, and `p = K⁰_mm · 40 ⟨x − 0.05⟩²` (`K⁰_mm` the mode's
/// stiffness at rest). The normal modes are never held.
///
/// Why (Wriggers & Reese, CMAME 135 (1996) 201–209; measured in 2D, `quad_stab.rs`): the
/// mode frees the zig-zag of an element short along `k`, whose remaining stiffness `∝ E/L_l²`
/// a compression along `k` softens as `σ/L_k²`. Held per increment the element's energy is
/// fixed within an increment, its tangent exact; it still passes the patch test (`α = 0` in a
/// homogeneous state) and stays frame-indifferent (`|F e_k|` is an invariant of `C`).
/// Not carried over from 2D: the blend into the plain element in large compression
/// (`compression_share`) and the fixed-share stabilisation (`EAS_STABILISATION`).
pub fn hex8_hourglass_holds(geo: &Hex8Geometry, material: &Material, u: &[[f64; 3]; 8]) -> [f64; EAS_COUNT] {
    let axes: [Vector3<f64>; 3] = std::array::from_fn(|k| geo.axes.column(k).into_owned());
    let len = axes.map(|a| a.norm());
    let mut compression = [0.0f64; 3];
    for q in &geo.gp {
        let f = deformation_gradient(&q.grad, u);
        for (c, (a, l)) in compression.iter_mut().zip(axes.iter().zip(&len)) {
            *c = c.max(1.0 - (f * a).norm() / l);
        }
    }
    std::array::from_fn(|m| {
        let Some((k, l)) = held_by(m) else {
            return 0.0;
        };
        let over = (compression[k] * (len[l] / len[k]).powi(2) - HOLD_FROM).max(0.0);
        if over == 0.0 {
            0.0
        } else {
            geo.mode_stiffness(material, m) * HOLD_GROWTH * over * over
        }
    })
}

impl Hex8Geometry {
    /// The penalties on the enhanced parameters.
    pub fn alpha_penalty(&self) -> [f64; EAS_COUNT] {
        self.penalty
    }

    /// Set the penalties on the enhanced parameters (from [`hex8_hourglass_holds`]).
    pub fn set_alpha_penalty(&mut self, penalty: [f64; EAS_COUNT]) {
        self.penalty = penalty;
    }

    /// `K⁰_mm = Σ_q G_qmᵀ D₀ G_qm dv_q`: the stiffness of enhanced mode `m` with the
    /// material's tangent at rest (zero if the material cannot be evaluated there).
    pub(crate) fn mode_stiffness(&self, material: &Material, m: usize) -> f64 {
        let Ok((_, d0)) = material.stress_tangent_3d(&Default::default()) else {
            return 0.0;
        };
        let d0: Matrix6<f64> = d0;
        (0..8)
            .map(|q| {
                let g = self.enhanced(q);
                let gm = g.column(m);
                self.gp[q].dv * gm.dot(&(d0 * gm))
            })
            .sum()
    }
}
