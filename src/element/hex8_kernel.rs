//! The hexahedron's residual and tangent: Gauss passes, the local Newton iteration on the
//! enhanced parameters and their static condensation (formulation in [`super`]).

use super::{hex8_min_det_f, kinematics, GaussKin, Hex8Error, Hex8Geometry, Hex8Kind, Material, EAS_COUNT};
use nalgebra::{Matrix3, SMatrix, SVector};

type Vec24 = SVector<f64, 24>;
type VecA = SVector<f64, EAS_COUNT>;
type MatAA = SMatrix<f64, EAS_COUNT, EAS_COUNT>;

/// The local iteration on `α` has converged when its next step would change no enhanced
/// strain by more than this (strains are O(1) at most; the 2D element's tolerance).
pub const EAS_STRAIN_TOLERANCE: f64 = 1e-14;

/// Below this size a step that does not shrink by half is round-off (nearly incompressible
/// materials have `K_αα` conditioned like `λ/μ`): the iteration stops there.
const EAS_ROUNDOFF_FLOOR: f64 = 1e-11;

/// Local Newton steps on `α` before [`Hex8Error::EasNotConverged`].
const EAS_MAX_ITERATIONS: usize = 25;

/// Sums of one pass over the Gauss points.
struct Sums {
    ru: Vec24,
    kuu: SMatrix<f64, 24, 24>,
    kua: SMatrix<f64, 24, EAS_COUNT>,
    kaa: MatAA,
    ra: VecA,
    energy: f64,
}

/// One pass over the Gauss points at the enhanced parameters `al`: `R_u`, the energy, with
/// `want_k` `K_uu` (material part `Bᵀ D B` plus geometric part `δ_ab ∇N_I · S ∇N_J`), and with
/// `eas` `R_α = Σ Gᵀ S dv`, `K_αα = Σ Gᵀ D G dv`, `K_uα = Σ Bᵀ D G dv` (plus the penalties of
/// held modes, `½ Σ p_m α_m²`).
fn gauss_pass(
    material: &Material,
    geo: &Hex8Geometry,
    kin: &[GaussKin; 8],
    al: &VecA,
    eas: bool,
    want_k: bool,
) -> Result<Sums, Hex8Error> {
    let mut t = Sums {
        ru: Vec24::zeros(),
        kuu: SMatrix::zeros(),
        kua: SMatrix::zeros(),
        kaa: MatAA::zeros(),
        ra: VecA::zeros(),
        energy: 0.0,
    };
    for (gq, kq) in geo.gp.iter().zip(kin) {
        let dv = gq.dv;
        let e = if eas { kq.ec + gq.g * al } else { kq.ec };
        let (s, d) = material.stress_tangent_3d(&e)?;
        t.energy += material.energy_3d(&e)? * dv;
        t.ru += kq.b.tr_mul(&s) * dv;
        if eas {
            let dg = d * gq.g;
            t.ra += gq.g.tr_mul(&s) * dv;
            t.kaa += gq.g.tr_mul(&dg) * dv;
            t.kua += kq.b.tr_mul(&dg) * dv;
        }
        if want_k {
            t.kuu += kq.b.tr_mul(&(d * kq.b)) * dv;
            let st = Matrix3::new(s[0], s[3], s[5], s[3], s[1], s[4], s[5], s[4], s[2]);
            let gsg = gq.grad.tr_mul(&(st * gq.grad)) * dv;
            for i in 0..8 {
                for j in 0..8 {
                    for a in 0..3 {
                        t.kuu[(3 * i + a, 3 * j + a)] += gsg[(i, j)];
                    }
                }
            }
        }
    }
    if eas {
        for (m, &pm) in geo.penalty.iter().enumerate().filter(|(_, p)| **p != 0.0) {
            t.ra[m] += pm * al[m];
            t.kaa[(m, m)] += pm;
            t.energy += 0.5 * pm * al[m] * al[m];
        }
    }
    Ok(t)
}

/// Largest change of an enhanced strain component, `max_q ‖G_q δα‖∞`, that the step `δα`
/// makes at the Gauss points.
fn enhanced_strain_change(geo: &Hex8Geometry, da: &VecA) -> f64 {
    geo.gp.iter().map(|q| (q.g * da).amax()).fold(0.0, f64::max)
}

/// Residual and (optionally) tangent of one hexahedron (builds its [`Hex8Geometry`] and
/// calls [`hex8_residual_tangent_with`]).
pub fn hex8_residual_tangent(
    kind: Hex8Kind,
    material: &Material,
    x: &[[f64; 3]; 8],
    u: &[[f64; 3]; 8],
    alpha: &mut [f64; EAS_COUNT],
    r: &mut [f64; 24],
    k: Option<&mut [f64; 576]>,
) -> Result<f64, Hex8Error> {
    let geo = Hex8Geometry::new(kind, x)?;
    hex8_residual_tangent_with(kind, material, &geo, u, alpha, r, k)
}

/// Residual and (optionally) tangent of one hexahedron on its precomputed reference geometry.
///
/// * `geo` — [`Hex8Geometry`] of the reference nodes (Gmsh/VTK order), made for the same
///   `kind`; `u` — nodal displacements;
/// * `alpha` — enhanced parameters: read as the starting guess of the local Newton
///   iteration, overwritten with the `α` that solves `R_α(u, α) = 0` (left alone for
///   [`Hex8Kind::Hex8`]);
/// * `r` — internal force `R* = ∂Π/∂u` (condensed), local DOF order `[u0x, u0y, u0z, u1x, …]`;
/// * `k` — `K* = ∂R*/∂u`, row-major 24×24, when requested.
///
/// The local iteration (`α ← α − K_αα⁻¹ R_α`, exact in one step for St. Venant–Kirchhoff)
/// stops when the next step would change no enhanced strain `G_q δα` by more than
/// [`EAS_STRAIN_TOLERANCE`] (or, below `1e-11`, stops shrinking: round-off); the pass that
/// finds it converged is condensed, `R* = R_u − K_uα K_αα⁻¹ R_α`,
/// `K* = K_uu − K_uα K_αα⁻¹ K_αu`.
///
/// Errors (never a panic or a NaN): [`Hex8Error::Inverted`] when `det F ≤ 0` or is not finite
/// at a Gauss point, [`Hex8Error::Material`] for a strain the material rejects (Neo-Hooke:
/// `det C ≤ 0`), [`Hex8Error::EasSingular`], [`Hex8Error::EasNotConverged`].
///
/// Returns the stored energy `Π = Σ_q W(E_q) dv_q (+ ½ Σ p_m α_m²)`. Sign: `r` is the internal
/// force, the global residual is `r − f_ext`.
pub fn hex8_residual_tangent_with(
    kind: Hex8Kind,
    material: &Material,
    geo: &Hex8Geometry,
    u: &[[f64; 3]; 8],
    alpha: &mut [f64; EAS_COUNT],
    r: &mut [f64; 24],
    k: Option<&mut [f64; 576]>,
) -> Result<f64, Hex8Error> {
    let det_f = hex8_min_det_f(geo, u);
    if det_f <= 0.0 || !det_f.is_finite() {
        return Err(Hex8Error::Inverted(det_f));
    }
    let kin = geo.gp.map(|q| kinematics(&q, u));
    let eas = kind == Hex8Kind::Hex8Eas;
    let want_k = k.is_some();
    let t = if eas {
        let mut al = VecA::from(*alpha);
        let (mut t, inv) = solve_enhanced(material, geo, &kin, &mut al, want_k)?;
        condense(&mut t, &inv, want_k);
        alpha.copy_from_slice(al.as_slice());
        t
    } else {
        gauss_pass(material, geo, &kin, &VecA::zeros(), false, want_k)?
    };
    if let Some(kout) = k {
        for (i, row) in kout.chunks_exact_mut(24).enumerate() {
            for (j, v) in row.iter_mut().enumerate() {
                *v = t.kuu[(i, j)];
            }
        }
    }
    r.copy_from_slice(t.ru.as_slice());
    Ok(t.energy)
}

/// The local Newton iteration on `α` from `al` (module documentation of
/// [`hex8_residual_tangent_with`]): the converged pass and `K_αα⁻¹`; `al` is left at the
/// converged `α`.
fn solve_enhanced(
    material: &Material,
    geo: &Hex8Geometry,
    kin: &[GaussKin; 8],
    al: &mut VecA,
    want_k: bool,
) -> Result<(Sums, MatAA), Hex8Error> {
    let mut last = f64::INFINITY;
    for _ in 0..EAS_MAX_ITERATIONS {
        let t = gauss_pass(material, geo, kin, al, true, want_k)?;
        let inv = t
            .kaa
            .try_inverse()
            .filter(|m| m.iter().all(|v| v.is_finite()))
            .ok_or(Hex8Error::EasSingular)?;
        let da = inv * t.ra;
        let step = enhanced_strain_change(geo, &da);
        if !step.is_finite() {
            return Err(Hex8Error::EasSingular);
        }
        if step <= EAS_STRAIN_TOLERANCE || (step <= EAS_ROUNDOFF_FLOOR && step > 0.5 * last) {
            return Ok((t, inv));
        }
        *al -= da;
        last = step;
    }
    let t = gauss_pass(material, geo, kin, al, true, false)?;
    Err(Hex8Error::EasNotConverged(t.ra.norm()))
}

/// Static condensation at a converged `α` (`inv = K_αα⁻¹`): `R* = R_u − W R_α` and, with
/// `want_k`, `K* = K_uu − W K_αu`, `W = K_uα K_αα⁻¹`.
fn condense(t: &mut Sums, inv: &MatAA, want_k: bool) {
    let w = t.kua * inv;
    t.ru -= w * t.ra;
    if want_k {
        t.kuu -= w * t.kua.transpose();
    }
}
