//! The stabilised EAS element [`ElementKind::Q4EasStab`]: a fixed share of the bilinear
//! element's energy added to the EAS element's.

use super::{quad_residual_tangent_with, ElementError, ElementKind, Material, QuadGeometry};

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
