//! The hexahedron's centre fields on a homogeneous state: `x = F X` on a distorted element
//! is reproduced by both kinds (patch test), so the centre Cauchy stress must be the
//! material's `J⁻¹ F S(E) Fᵀ` at `E = ½(FᵀF − I)`, to 1e-10 relative; the strain is `E`
//! (1e-14) and von Mises is that of `σ`.

use super::*;
use crate::element::material::lame;
use crate::element::material3d::stress_voigt;

/// A distorted hexahedron (no two faces parallel), Gmsh/VTK order.
const X: [[f64; 3]; 8] = [
    [0.0, 0.0, 0.0],
    [1.3, 0.1, -0.05],
    [1.2, 1.0, 0.1],
    [-0.1, 0.8, 0.0],
    [0.1, -0.05, 0.9],
    [1.1, 0.05, 1.2],
    [1.25, 1.1, 1.0],
    [0.05, 0.9, 1.1],
];

#[test]
fn a_homogeneous_state_gives_the_materials_cauchy_stress_at_the_centre() {
    let fm = Matrix3::new(1.05, 0.02, -0.03, -0.01, 0.97, 0.04, 0.02, 0.01, 1.03);
    let u = X.map(|p| {
        let q = fm * nalgebra::Vector3::new(p[0], p[1], p[2]);
        [q[0] - p[0], q[1] - p[1], q[2] - p[2]]
    });
    let (lambda, mu) = lame(200.0, 0.3);
    let e_tensor = 0.5 * (fm.transpose() * fm - Matrix3::identity());
    let mut e = stress_voigt(&e_tensor);
    for a in 3..6 {
        e[a] *= 2.0; // engineering shears
    }
    for material in [
        Material::SaintVenantKirchhoff { lambda, mu },
        Material::NeoHookean { lambda, mu },
    ] {
        let (s, _) = material.stress_tangent_3d(&e).unwrap();
        let sig = fm * stress_tensor(&s) * fm.transpose() / fm.determinant();
        let vm = (0.5
            * ((sig[(0, 0)] - sig[(1, 1)]).powi(2)
                + (sig[(1, 1)] - sig[(2, 2)]).powi(2)
                + (sig[(2, 2)] - sig[(0, 0)]).powi(2))
            + 3.0 * (sig[(0, 1)].powi(2) + sig[(1, 2)].powi(2) + sig[(0, 2)].powi(2)))
        .sqrt();
        for kind in [Hex8Kind::Hex8, Hex8Kind::Hex8Eas] {
            let c = hex8_centre_fields(kind, &material, &X, &u).unwrap();
            let tol = 1e-10 * sig.norm();
            for r in 0..3 {
                for k in 0..3 {
                    assert!(
                        (c.cauchy[r][k] - sig[(r, k)]).abs() < tol,
                        "{kind:?} {material:?} σ{r}{k}: {} vs {}",
                        c.cauchy[r][k],
                        sig[(r, k)]
                    );
                    assert!((c.green_lagrange[r][k] - e_tensor[(r, k)]).abs() < 1e-14);
                }
            }
            assert!((c.von_mises - vm).abs() < tol && vm > 0.0);
        }
    }
}
