//! The hexahedron's residual and tangent: Gauss passes, the local Newton iteration on the
//! enhanced parameters and their static condensation (formulation in [`super`]). The passes,
//! the local iteration and the condensation take the element as eight [`PassPoint`]s with
//! `N` enhanced modes, so the solid-shell (`solid_shell.rs`), whose strains are assumed
//! rather than compatible, shares them.

use super::{
    factored_modes, hex8_min_det_f, kinematics, GaussKin, Hex8Error, Hex8Geometry, Hex8Kind, Material, EAS_COUNT,
    EAS_MODES,
};
use nalgebra::{Matrix3, Matrix6, SMatrix, SVector, Vector6};

type Vec24 = SVector<f64, 24>;
type Mat24 = SMatrix<f64, 24, 24>;

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

/// One Gauss point as a pass sees it: the volume weight, the strain–displacement matrix
/// `δE = B δu` (Cartesian Voigt, local DOFs `[u0x, u0y, u0z, u1x, …]`), the strain `E` of the
/// displacements (compatible for the hexahedron, assumed for the solid-shell) and the
/// enhanced interpolation `Ẽ = G α` in factored form, `G = c T₀ M` (`c = j₀/j` here, `M`
/// the mode values here, one per mode in its natural Voigt row; [`EnhancedElement`]).
pub(crate) struct PassPoint<'a, const N: usize> {
    pub dv: f64,
    pub b: &'a SMatrix<f64, 6, 24>,
    pub e: &'a Vector6<f64>,
    pub scale: f64,
    pub m: &'a [f64; N],
}

/// `K_uu += ∂²E/∂u∂u : S dv` at Gauss point `q` (the geometric stiffness), on the upper
/// triangle of the 24×24 matrix.
pub(crate) type GeometricStiffness<'a> = &'a dyn Fn(usize, &Vector6<f64>, f64, &mut Mat24);

/// An element as the kernel evaluates it: eight Gauss points, the transformation `T₀` and
/// each mode's natural Voigt row (the factors of `G` common to the points), the penalties on
/// the enhanced parameters (`Π += ½ Σ p_m α_m²`) and its geometric stiffness.
pub(crate) struct EnhancedElement<'a, const N: usize> {
    pub points: [PassPoint<'a, N>; 8],
    pub t0: &'a Matrix6<f64>,
    pub rows: &'a [usize; N],
    pub penalty: &'a [f64; N],
    pub geometric: GeometricStiffness<'a>,
}

impl<const N: usize> EnhancedElement<'_, N> {
    /// `G_q a = c_q T₀ (M_q a)`: an enhanced strain at Gauss point `q`.
    fn enhanced_strain(&self, q: usize, a: &SVector<f64, N>) -> Vector6<f64> {
        let p = &self.points[q];
        let mut natural = Vector6::zeros();
        for (m, (&row, &v)) in self.rows.iter().zip(p.m).enumerate() {
            natural[row] += v * a[m];
        }
        self.t0 * (natural * p.scale)
    }
}

/// Sums of one pass over the Gauss points (`kuu` and `kaa` in full: each summed on its upper
/// triangle and mirrored at the end of the pass).
struct Sums<const N: usize> {
    ru: Vec24,
    kuu: Mat24,
    kua: SMatrix<f64, 24, N>,
    kaa: SMatrix<f64, N, N>,
    ra: SVector<f64, N>,
    energy: f64,
}

impl<const N: usize> Sums<N> {
    fn zeros() -> Self {
        Sums {
            ru: Vec24::zeros(),
            kuu: SMatrix::zeros(),
            kua: SMatrix::zeros(),
            kaa: SMatrix::zeros(),
            ra: SVector::zeros(),
            energy: 0.0,
        }
    }

    /// Zero what a pass with `wanted` sums into.
    fn clear(&mut self, wanted: Wanted) {
        if wanted.eas {
            self.kaa.fill(0.0);
            self.ra.fill(0.0);
            if wanted.full {
                self.kua.fill(0.0);
            }
        }
        if wanted.full {
            self.ru.fill(0.0);
            self.energy = 0.0;
            if wanted.k {
                self.kuu.fill(0.0);
            }
        }
    }
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

/// `K_uu += δ_ab (gᵀ Σ g)_IJ` on the upper triangle: the geometric stiffness of strains
/// quadratic in the displacement gradients, `gsg` the 8×8 node-pair weights.
pub(crate) fn add_node_pairs_upper(kuu: &mut Mat24, gsg: &SMatrix<f64, 8, 8>) {
    for j in 0..8 {
        for i in 0..=j {
            for a in 0..3 {
                kuu[(3 * i + a, 3 * j + a)] += gsg[(i, j)];
            }
        }
    }
}

/// One pass over the Gauss points at the enhanced parameters `al`, into `t`: with `eas`
/// `R_α = Σ Gᵀ S dv`, `K_αα = Σ Gᵀ D G dv` (plus the penalties of held modes,
/// `½ Σ p_m α_m²`); with `full` also `R_u`, the energy and `K_uα = Σ Bᵀ D G dv`, and with `k`
/// `K_uu` (material part `Bᵀ D B` plus the element's geometric part).
///
/// With `G = c T₀ M` and `M` one entry `M_m` per mode in row `r_m`:
/// `R_α,m = Σ c M_m (T₀ᵀ S)_{r_m} dv`, `K_αα,mn = Σ c² M_m M_n (T₀ᵀ D T₀)_{r_m r_n} dv`,
/// `K_uα,·m = Σ c M_m (Bᵀ D T₀)_{·r_m} dv`.
fn gauss_pass<const N: usize>(
    material: &Material,
    el: &EnhancedElement<'_, N>,
    al: &SVector<f64, N>,
    wanted: Wanted,
    t: &mut Sums<N>,
) -> Result<(), Hex8Error> {
    let Wanted { eas, full, k: want_k } = wanted;
    t.clear(wanted);
    for (q, p) in el.points.iter().enumerate() {
        let dv = p.dv;
        let e = if eas { p.e + el.enhanced_strain(q, al) } else { *p.e };
        let (s, d) = material.stress_tangent_3d(&e)?;
        if eas {
            add_enhanced_terms(t, el, p, &s, &d, full);
        }
        if !full {
            continue;
        }
        t.energy += material.energy_3d(&e)? * dv;
        t.ru += p.b.tr_mul(&s) * dv;
        if want_k {
            add_upper_tr_mul(&mut t.kuu, p.b, &((d * p.b) * dv));
            (el.geometric)(q, &s, dv, &mut t.kuu);
        }
    }
    if eas {
        for (m, &pm) in el.penalty.iter().enumerate().filter(|(_, p)| **p != 0.0) {
            t.ra[m] += pm * al[m];
            t.kaa[(m, m)] += pm;
            t.energy += 0.5 * pm * al[m] * al[m];
        }
        mirror_upper(&mut t.kaa);
    }
    if full && want_k {
        mirror_upper(&mut t.kuu);
    }
    Ok(())
}

/// One Gauss point's `R_α`, `K_αα` (upper triangle) and, with `full`, `K_uα`, from its
/// stress `s` and tangent `d` ([`gauss_pass`] for the factored formulas).
fn add_enhanced_terms<const N: usize>(
    t: &mut Sums<N>,
    el: &EnhancedElement<'_, N>,
    p: &PassPoint<'_, N>,
    s: &Vector6<f64>,
    d: &Matrix6<f64>,
    full: bool,
) {
    let w = p.dv * p.scale;
    let dt = d * el.t0;
    let s_nat = el.t0.tr_mul(s);
    let d_nat = el.t0.tr_mul(&dt);
    for (n, (&rn, &mn)) in el.rows.iter().zip(p.m).enumerate() {
        let wn = w * mn;
        t.ra[n] += wn * s_nat[rn];
        let wnc = wn * p.scale;
        for (m, (&rm, &mm)) in el.rows.iter().zip(p.m).enumerate().take(n + 1) {
            t.kaa[(m, n)] += wnc * mm * d_nat[(rm, rn)];
        }
    }
    if full {
        let bdt = p.b.tr_mul(&dt);
        for (n, (&rn, &mn)) in el.rows.iter().zip(p.m).enumerate() {
            t.kua.column_mut(n).axpy(w * mn, &bdt.column(rn), 1.0);
        }
    }
}

/// Largest change of an enhanced strain component, `max_q ‖G_q δα‖∞`, that the step `δα`
/// makes at the Gauss points.
fn enhanced_strain_change<const N: usize>(el: &EnhancedElement<'_, N>, da: &SVector<f64, N>) -> f64 {
    (0..8).map(|q| el.enhanced_strain(q, da).amax()).fold(0.0, f64::max)
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
///   [`Hex8Kind::Hex8`]; the solid-shell uses its first [`super::SHELL_EAS_COUNT`]);
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
    if kind == Hex8Kind::SolidShell {
        return super::solid_shell::residual_tangent(material, geo, u, alpha, r, k);
    }
    let kin: [GaussKin; 8] = std::array::from_fn(|q| kinematics(&geo.gp[q], u));
    let geometric = |q: usize, s: &Vector6<f64>, dv: f64, kuu: &mut Mat24| {
        let grad = &geo.gp[q].grad;
        let st = Matrix3::new(s[0], s[3], s[5], s[3], s[1], s[4], s[5], s[4], s[2]);
        add_node_pairs_upper(kuu, &(grad.tr_mul(&(st * grad)) * dv));
    };
    let (rows, values) = factored_modes::<EAS_COUNT>(&EAS_MODES);
    let el = EnhancedElement {
        points: std::array::from_fn(|q| PassPoint {
            dv: geo.gp[q].dv,
            b: &kin[q].b,
            e: &kin[q].ec,
            scale: geo.gp[q].scale,
            m: &values[q],
        }),
        t0: &geo.t0,
        rows: &rows,
        penalty: &geo.penalty,
        geometric: &geometric,
    };
    enhanced_residual_tangent(material, &el, kind == Hex8Kind::Hex8Eas, alpha, r, k)
}

/// Residual, tangent and energy of an element given as [`EnhancedElement`]: with `eas` the
/// local iteration on `α` (read as the start, left at the solution) and the condensation,
/// else one pass at `α = 0`.
pub(crate) fn enhanced_residual_tangent<const N: usize>(
    material: &Material,
    el: &EnhancedElement<'_, N>,
    eas: bool,
    alpha: &mut [f64; N],
    r: &mut [f64; 24],
    k: Option<&mut [f64; 576]>,
) -> Result<f64, Hex8Error> {
    let want_k = k.is_some();
    let mut t = Sums::zeros();
    if eas {
        let mut al = SVector::from(*alpha);
        let factor = solve_enhanced(material, el, &mut al, want_k, &mut t)?;
        condense(&mut t, &factor, want_k);
        alpha.copy_from_slice(al.as_slice());
    } else {
        let wanted = Wanted {
            eas: false,
            full: true,
            k: want_k,
        };
        gauss_pass(material, el, &SVector::zeros(), wanted, &mut t)?;
    }
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
enum KaaFactor<const N: usize> {
    Cholesky(nalgebra::Cholesky<f64, nalgebra::Const<N>>),
    Inverse(SMatrix<f64, N, N>),
}

impl<const N: usize> KaaFactor<N> {
    fn new(kaa: &SMatrix<f64, N, N>) -> Result<Self, Hex8Error> {
        if let Some(c) = kaa.cholesky().filter(|c| c.l_dirty().iter().all(|v| v.is_finite())) {
            return Ok(KaaFactor::Cholesky(c));
        }
        kaa.try_inverse()
            .filter(|m| m.iter().all(|v| v.is_finite()))
            .map(KaaFactor::Inverse)
            .ok_or(Hex8Error::EasSingular)
    }

    /// `K_αα⁻¹ b`.
    fn solve(&self, b: &SVector<f64, N>) -> SVector<f64, N> {
        match self {
            KaaFactor::Cholesky(c) => c.solve(b),
            KaaFactor::Inverse(inv) => inv * b,
        }
    }
}

/// The local Newton iteration on `α` from `al` (module documentation of
/// [`hex8_residual_tangent_with`]): `K_αα` factorised, the converged pass left in `t` and
/// `al` at the converged `α`. Passes evaluate `R_α` and `K_αα` only until a step is below
/// [`EAS_NEAR`]; from then on they are full, and a pass that finds `α` converged without
/// being full is repeated fully at the same `α` (the same `α` and the same figures as full
/// passes throughout).
fn solve_enhanced<const N: usize>(
    material: &Material,
    el: &EnhancedElement<'_, N>,
    al: &mut SVector<f64, N>,
    want_k: bool,
    t: &mut Sums<N>,
) -> Result<KaaFactor<N>, Hex8Error> {
    let mut last = f64::INFINITY;
    let mut near = false;
    for it in 0..EAS_MAX_ITERATIONS {
        let wanted = Wanted {
            eas: true,
            full: near,
            k: want_k && near,
        };
        gauss_pass(material, el, al, wanted, t)?;
        let factor = KaaFactor::new(&t.kaa)?;
        let da = factor.solve(&t.ra);
        let step = enhanced_strain_change(el, &da);
        if !step.is_finite() {
            return Err(Hex8Error::EasSingular);
        }
        if step <= EAS_STRAIN_TOLERANCE || (step <= EAS_ROUNDOFF_FLOOR && step > 0.5 * last) {
            if near {
                return Ok(factor);
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
    gauss_pass(material, el, al, wanted, t)?;
    Err(Hex8Error::EasNotConverged(t.ra.norm()))
}

/// Static condensation at a converged `α`: `R* = R_u − K_uα K_αα⁻¹ R_α` and, with `want_k`,
/// `K* = K_uu − K_uα K_αα⁻¹ K_αu`. With a Cholesky factor `K_αα = L Lᵀ`: `Y = L⁻¹ K_αu`,
/// `R* = R_u − Yᵀ L⁻¹ R_α`, `K* = K_uu − Yᵀ Y` (symmetric by construction).
fn condense<const N: usize>(t: &mut Sums<N>, factor: &KaaFactor<N>, want_k: bool) {
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
                let mut yty = Mat24::zeros();
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
