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

/// A step of the local iteration that changes no enhanced strain by more than this is close
/// enough for the next pass to converge (Newton's quadratic rate): that pass evaluates the
/// displacement terms too (the 2D element's rule).
const EAS_NEAR: f64 = 1e-6;

/// Sums of one pass over the Gauss points (`kuu` and `kaa` in full: each summed on its upper
/// triangle and mirrored at the end of the pass).
struct Sums {
    ru: Vec24,
    kuu: SMatrix<f64, 24, 24>,
    kua: SMatrix<f64, 24, EAS_COUNT>,
    kaa: MatAA,
    ra: VecA,
    energy: f64,
}

/// What one Gauss pass evaluates.
#[derive(Clone, Copy)]
struct Wanted {
    /// `R_α`, `K_αα` (and with `full` `K_uα`): an EAS element.
    eas: bool,
    /// `R_u`, `K_uα` and the energy (passes of the local iteration far from its solution
    /// need `R_α` and `K_αα` only).
    full: bool,
    /// `K_uu` (with `full`).
    k: bool,
}

/// `out += aᵀ b` on the upper triangle of the square `out` (`a`, `b`: `R × C`).
#[inline]
fn add_upper_tr_mul<const R: usize, const C: usize>(
    out: &mut SMatrix<f64, C, C>,
    a: &SMatrix<f64, R, C>,
    b: &SMatrix<f64, R, C>,
) {
    for j in 0..C {
        let bj = b.column(j);
        for i in 0..=j {
            out[(i, j)] += a.column(i).dot(&bj);
        }
    }
}

/// Copy the upper triangle of a square matrix onto its lower one.
fn mirror_upper<const N: usize>(m: &mut SMatrix<f64, N, N>) {
    for j in 0..N {
        for i in 0..j {
            m[(j, i)] = m[(i, j)];
        }
    }
}

/// One pass over the Gauss points at the enhanced parameters `al`: with `eas`
/// `R_α = Σ Gᵀ S dv`, `K_αα = Σ Gᵀ D G dv` (plus the penalties of held modes,
/// `½ Σ p_m α_m²`); with `full` also `R_u`, the energy and `K_uα = Σ Bᵀ D G dv`, and with `k`
/// `K_uu` (material part `Bᵀ D B` plus geometric part `δ_ab ∇N_I · S ∇N_J`).
fn gauss_pass(
    material: &Material,
    geo: &Hex8Geometry,
    kin: &[GaussKin; 8],
    al: &VecA,
    wanted: Wanted,
) -> Result<Sums, Hex8Error> {
    let Wanted { eas, full, k: want_k } = wanted;
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
        if eas {
            let dg = (d * gq.g) * dv;
            t.ra += gq.g.tr_mul(&s) * dv;
            add_upper_tr_mul(&mut t.kaa, &gq.g, &dg);
            if full {
                t.kua += kq.b.tr_mul(&dg);
            }
        }
        if !full {
            continue;
        }
        t.energy += material.energy_3d(&e)? * dv;
        t.ru += kq.b.tr_mul(&s) * dv;
        if want_k {
            add_upper_tr_mul(&mut t.kuu, &kq.b, &((d * kq.b) * dv));
            let st = Matrix3::new(s[0], s[3], s[5], s[3], s[1], s[4], s[5], s[4], s[2]);
            let gsg = gq.grad.tr_mul(&(st * gq.grad)) * dv;
            for j in 0..8 {
                for i in 0..=j {
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
        mirror_upper(&mut t.kaa);
    }
    if full && want_k {
        mirror_upper(&mut t.kuu);
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
        let (mut t, factor) = solve_enhanced(material, geo, &kin, &mut al, want_k)?;
        condense(&mut t, &factor, want_k);
        alpha.copy_from_slice(al.as_slice());
        t
    } else {
        let wanted = Wanted {
            eas: false,
            full: true,
            k: want_k,
        };
        gauss_pass(material, geo, &kin, &VecA::zeros(), wanted)?
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

/// `K_αα` factorised: by Cholesky (symmetric positive definite, as for a stable material
/// state), else inverted by LU.
enum KaaFactor {
    Cholesky(nalgebra::Cholesky<f64, nalgebra::Const<EAS_COUNT>>),
    Inverse(MatAA),
}

impl KaaFactor {
    fn new(kaa: &MatAA) -> Result<Self, Hex8Error> {
        if let Some(c) = kaa.cholesky().filter(|c| c.l_dirty().iter().all(|v| v.is_finite())) {
            return Ok(KaaFactor::Cholesky(c));
        }
        kaa.try_inverse()
            .filter(|m| m.iter().all(|v| v.is_finite()))
            .map(KaaFactor::Inverse)
            .ok_or(Hex8Error::EasSingular)
    }

    /// `K_αα⁻¹ b`.
    fn solve(&self, b: &VecA) -> VecA {
        match self {
            KaaFactor::Cholesky(c) => c.solve(b),
            KaaFactor::Inverse(inv) => inv * b,
        }
    }
}

/// The local Newton iteration on `α` from `al` (module documentation of
/// [`hex8_residual_tangent_with`]): the converged pass and `K_αα` factorised; `al` is left at
/// the converged `α`. Passes evaluate `R_α` and `K_αα` only until a step is below
/// [`EAS_NEAR`]; from then on they are full, and a pass that finds `α` converged without
/// being full is repeated fully at the same `α` (the same `α` and the same figures as full
/// passes throughout).
fn solve_enhanced(
    material: &Material,
    geo: &Hex8Geometry,
    kin: &[GaussKin; 8],
    al: &mut VecA,
    want_k: bool,
) -> Result<(Sums, KaaFactor), Hex8Error> {
    let mut last = f64::INFINITY;
    let mut near = false;
    for it in 0..EAS_MAX_ITERATIONS {
        let wanted = Wanted {
            eas: true,
            full: near,
            k: want_k && near,
        };
        let t = gauss_pass(material, geo, kin, al, wanted)?;
        let factor = KaaFactor::new(&t.kaa)?;
        let da = factor.solve(&t.ra);
        let step = enhanced_strain_change(geo, &da);
        if !step.is_finite() {
            return Err(Hex8Error::EasSingular);
        }
        if step <= EAS_STRAIN_TOLERANCE || (step <= EAS_ROUNDOFF_FLOOR && step > 0.5 * last) {
            if near {
                return Ok((t, factor));
            }
            near = true;
            continue;
        }
        *al -= da;
        last = step;
        // a local iteration still not near after 12 steps (far from Newton's quadratic
        // rate) evaluates everything from then on, so that the pass that converges is full
        // (the 2D element's rule, `element/quad.rs`)
        near = step <= EAS_NEAR || it >= 12;
    }
    let wanted = Wanted {
        eas: true,
        full: false,
        k: false,
    };
    let t = gauss_pass(material, geo, kin, al, wanted)?;
    Err(Hex8Error::EasNotConverged(t.ra.norm()))
}

/// Static condensation at a converged `α`: `R* = R_u − K_uα K_αα⁻¹ R_α` and, with `want_k`,
/// `K* = K_uu − K_uα K_αα⁻¹ K_αu`. With a Cholesky factor `K_αα = L Lᵀ`: `Y = L⁻¹ K_αu`,
/// `R* = R_u − Yᵀ L⁻¹ R_α`, `K* = K_uu − Yᵀ Y` (symmetric by construction).
fn condense(t: &mut Sums, factor: &KaaFactor, want_k: bool) {
    match factor {
        KaaFactor::Cholesky(c) => {
            let l = c.l_dirty();
            let y = l
                .solve_lower_triangular(&t.kua.transpose())
                .expect("a Cholesky factor has a nonzero diagonal");
            let z = l
                .solve_lower_triangular(&t.ra)
                .expect("a Cholesky factor has a nonzero diagonal");
            t.ru -= y.tr_mul(&z);
            if want_k {
                let mut yty = SMatrix::<f64, 24, 24>::zeros();
                add_upper_tr_mul(&mut yty, &y, &y);
                mirror_upper(&mut yty);
                t.kuu -= yty;
            }
        }
        KaaFactor::Inverse(inv) => {
            let w = t.kua * inv;
            t.ru -= w * t.ra;
            if want_k {
                t.kuu -= w * t.kua.transpose();
            }
        }
    }
}
