//! Consistent nodal forces of a dead body load on one quadrilateral.
//!
//! `f_I = ∫_Ω₀ N_I b dA`, integrated exactly for a bilinear element by 2×2 Gauss points on
//! the reference configuration (`b`: force per unit reference volume, e.g. `ρ₀ g`; unit
//! thickness in plane strain). A dead load in the total Lagrangian description does not
//! depend on the deformation, so these are constant nodal forces.

use super::quad::Kinematics;
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

/// Nodal forces of the body force `b` in a setting: `f_I = ∫ N_I b dV` with `dV = det J dξ dη`
/// in plane strain (per unit thickness: [`quad_body_force`] itself), `dV = t det J dξ dη` in
/// plane stress (the plate's force) and `dV = 2π R det J dξ dη`, `R = Σ N_I X_I` (the
/// reference radius at the Gauss point), in the axisymmetric setting: the total over the full
/// circle, like the element's residual (`quad_models.rs`). 2×2 Gauss points integrate
/// `N_I R det J` exactly (bilinear times a polynomial of degree ≤ 1 in each of `ξ`, `η` on a
/// parallelogram; on a general quad to the element's own accuracy).
pub fn quad_body_force_with(x: &[[f64; 2]; 4], b: [f64; 2], kinematics: Kinematics, out: &mut [f64; 8]) {
    let weight = |n: &[f64; 4]| match kinematics {
        Kinematics::PlaneStrain => 1.0,
        Kinematics::PlaneStress { thickness } => thickness,
        Kinematics::Axisymmetric => 2.0 * std::f64::consts::PI * n.iter().zip(x).map(|(n, p)| n * p[0]).sum::<f64>(),
    };
    if kinematics == Kinematics::PlaneStrain {
        return quad_body_force(x, b, out);
    }
    out.fill(0.0);
    for &(gx, gy) in &GAUSS {
        let det = jacobian(x, &dn_dxi(gx, gy)).determinant();
        let n = XI_NODES.map(|(xa, ea)| 0.25 * (1.0 + xa * gx) * (1.0 + ea * gy));
        let w = weight(&n) * det;
        for (i, ni) in n.iter().enumerate() {
            out[2 * i] += ni * b[0] * w;
            out[2 * i + 1] += ni * b[1] * w;
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

    #[test]
    fn settings_weigh_by_thickness_and_by_the_ring() {
        // the ring 1 ≤ r ≤ 3, 0 ≤ z ≤ 2: volume π (3² − 1²) 2 = 16π; the plate: area 4 times t
        let x = [[1.0, 0.0], [3.0, 0.0], [3.0, 2.0], [1.0, 2.0]];
        let mut f = [0.0; 8];
        quad_body_force_with(&x, [0.0, -1.5], Kinematics::Axisymmetric, &mut f);
        let fy: f64 = (0..4).map(|i| f[2 * i + 1]).sum();
        assert!((fy + 1.5 * 16.0 * std::f64::consts::PI).abs() < 1e-12, "{fy}");
        // the outer nodes carry more: ∫ N r dV with N linear in r
        assert!(f[3] < f[1]);
        quad_body_force_with(&x, [0.5, 0.0], Kinematics::PlaneStress { thickness: 0.2 }, &mut f);
        let fx: f64 = (0..4).map(|i| f[2 * i]).sum();
        assert!((fx - 0.5 * 4.0 * 0.2).abs() < 1e-14);
        let mut g = [0.0; 8];
        quad_body_force_with(&x, [0.5, 0.0], Kinematics::PlaneStrain, &mut f);
        quad_body_force(&x, [0.5, 0.0], &mut g);
        assert_eq!(f, g);
    }
}
