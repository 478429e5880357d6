//! Consistent nodal forces of a dead body load on one quadrilateral.
//!
//! `f_I = ∫_Ω₀ N_I b dA`, integrated exactly for a bilinear element by 2×2 Gauss points on
//! the reference configuration (`b`: force per unit reference volume, e.g. `ρ₀ g`; unit
//! thickness in plane strain). A dead load in the total Lagrangian description does not
//! depend on the deformation, so these are constant nodal forces.

use super::quad::{dn_dxi, jacobian, GAUSS, XI_NODES};

/// Nodal forces `[f1x, f1y, f2x, …]` of the body force `b` on the quad with reference nodes
/// `x` (counter-clockwise), with the element kernel's shape functions and Gauss points.
pub fn quad_body_force(x: &[[f64; 2]; 4], b: [f64; 2], out: &mut [f64; 8]) {
    out.fill(0.0);
    for &(gx, gy) in &GAUSS {
        let det = jacobian(x, &dn_dxi(gx, gy)).determinant();
        for (i, &(xa, ea)) in XI_NODES.iter().enumerate() {
            let n = 0.25 * (1.0 + xa * gx) * (1.0 + ea * gy);
            out[2 * i] += n * b[0] * det;
            out[2 * i + 1] += n * b[1] * det;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn total_force_is_body_force_times_area_and_bilinear_moments_are_exact() {
        // a distorted quad: area by the shoelace formula
        let x = [[0.0, 0.0], [2.0, 0.3], [2.4, 1.9], [-0.2, 1.2]];
        let area = 0.5
            * (0..4)
                .map(|i| x[i][0] * x[(i + 1) % 4][1] - x[(i + 1) % 4][0] * x[i][1])
                .sum::<f64>();
        let mut f = [0.0; 8];
        quad_body_force(&x, [0.3, -2.0], &mut f);
        let fx: f64 = (0..4).map(|i| f[2 * i]).sum();
        let fy: f64 = (0..4).map(|i| f[2 * i + 1]).sum();
        assert!((fx - 0.3 * area).abs() < 1e-12 && (fy + 2.0 * area).abs() < 1e-12);
        // a unit square: each node carries a quarter
        let mut f = [0.0; 8];
        quad_body_force(&[[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]], [0.0, 1.0], &mut f);
        assert!((0..4).all(|i| (f[2 * i + 1] - 0.25).abs() < 1e-15 && f[2 * i] == 0.0));
    }
}
