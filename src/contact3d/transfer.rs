//! History transfer when a contact point moves from facet `A` (of the last converged
//! increment) to facet `B` (seed §3, eqs. 2–4, on surfaces). The transfer maps the stored
//! [`History`] `(ξ_(n), T_α^(n))` of `A` to a history on `B`, which the point kernel then
//! uses as if the point had been on `B` all along (`T_α^tr = T_α^B − ε_T a_αβ Δξ^β`).
//!
//! The transfer runs on the geometry it is given (the current configuration, as in the seed)
//! and its result is data for the kernel: its dependence on the nodes is not in the tangent
//! (the 2D kernel differentiates through `A` during a crossing step; here a crossing step's
//! tangent misses that term).
//!
//! Schemes ([`Scheme`]):
//! - **straightforward** (seed eq. 1 across facets): `ξ_(n)` and `T_α^(n)` kept as numbers.
//!   Both are meaningless in `B`'s parametrisation: `Δξ` jumps (by about 2 across an edge)
//!   and the traction vector `T^α ρ_α` changes wherever `B`'s tangents differ from `A`'s.
//! - **continuous** (parallel translation, seed eqs. 2–4): the old contact point's current
//!   position `ρ_A(ξ_(n))`, unfolded about the edge, is re-projected onto `B`'s (extended)
//!   surface ([`map_point`]), giving `ξ_(n)` on `B`, so `Δξ` on `B` is the continuation of
//!   the slip (exact on coplanar parallelograms:
//!   `a_αβ Δξ^β = ρ_α·Δρ`, seed eq. 3's `Δρ·ρ_B^j` term); the traction vector
//!   `t = T_α a^αβ ρ_β` of `A` (at `ξ_(n)`) is turned by the smallest rotation `R` that takes
//!   `n_A` to `n_B` (about `n_A × n_B`: the common edge of two flat facets) and its covariant
//!   components on `B` are taken, `T_β^B = (R t)·ρ_β^B`. On coplanar facets `R = I` and this is
//!   seed eq. (3) exactly: `T_β^B = T^α_A (ρ^A_α·ρ^B_β)`. On a fold the rotation keeps `|t|`
//!   and `t`'s angle with the edge — the parallel translation of the surface unfolded about
//!   the edge — where seed eq. (3)'s projection ([`Scheme::ContinuousProjected`]) shrinks the
//!   component across the edge by the cosine of the fold angle, so a point at the Coulomb
//!   limit would arrive inside the cone, and a back-and-forth crossing would not return the
//!   traction it started with.
//! - **path length** (after Wriggers, Krstulovic-Opara & Korelc, IJNME 51 (2001), 2D): the
//!   physical components of `t` in each facet's unit frame `e_1 = ρ_1/|ρ_1|`,
//!   `e_2 = n × e_1` are kept, the old point mapped as in continuous (the distance
//!   slid is kept). It depends on how each facet's local axes are drawn.

use super::point::History;
use super::projection::{project, ProjectionError};
use super::surface::{Facet, FacetPoint, GeometryError};
use super::vec3::{add, cross, dot, norm, scale, sub, V3};
use thiserror::Error;

/// How the history reaches `B`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Scheme {
    Straightforward,
    /// Re-projection of the old point, traction turned about the edge (module docs).
    Continuous,
    /// Seed eqs. (2)–(3) literally: `T_β^B = t·ρ_β^B` (the normal part of `t` on `B`
    /// dropped), the old point re-projected without unfolding.
    ContinuousProjected,
    PathLength,
}

/// The scene's name of a scheme (`transfer = "…"`).
pub fn scheme_name(scheme: Scheme) -> &'static str {
    match scheme {
        Scheme::Straightforward => "straightforward",
        Scheme::Continuous => "continuous",
        Scheme::ContinuousProjected => "continuous-projected",
        Scheme::PathLength => "path-length",
    }
}

/// Why a history could not be transferred.
#[derive(Debug, Clone, Copy, PartialEq, Error)]
pub enum TransferError {
    #[error("transfer: old facet: {0}")]
    Old(GeometryError),
    #[error("transfer: re-projecting the old point onto the new facet: {0}")]
    Reprojection(ProjectionError),
    #[error("transfer: the facets' normals are opposite (n_A·n_B = {cos}): no rotation")]
    Folded { cos: f64 },
}

/// Below this `1 + n_A·n_B` the facets are folded flat onto each other.
const MIN_ONE_PLUS_COS: f64 = 1e-8;

/// `R v` for the smallest rotation `R` taking unit vector `a` to unit vector `b`
/// (Rodrigues, axis `a × b`): `R v = c v + k × v + k (k·v)/(1 + c)`, `c = a·b`, `k = a × b`.
pub fn rotate_between(a: V3<f64>, b: V3<f64>, v: V3<f64>) -> Result<V3<f64>, TransferError> {
    let c = dot(a, b);
    if 1.0 + c < MIN_ONE_PLUS_COS {
        return Err(TransferError::Folded { cos: c });
    }
    let k = cross(a, b);
    Ok(add(add(scale(v, c), cross(k, v)), scale(k, dot(k, v) / (1.0 + c))))
}

/// The unit frame `e_1 = ρ_1/|ρ_1|`, `e_2 = n × e_1` of a facet point.
fn unit_frame(p: &FacetPoint<f64>) -> [V3<f64>; 2] {
    let e1 = scale(p.tangents[0], 1.0 / norm(p.tangents[0]));
    [e1, cross(p.normal, e1)]
}

/// The point of `B` (its extended bilinear surface) that stands for the current position
/// of `ξ_A` on `A`: where the old contact point, or the stick anchor (seed eq. 4), lies in
/// `B`'s parametrisation, found by re-projecting `ρ_A(ξ_A)` onto `B`. With `unfold`, the
/// point is first turned into `B`'s tangent plane about the line where the two tangent
/// planes meet (the common edge of two flat facets), by the rotation of
/// [`rotate_between`]`(n_A, n_B)`, so the distance slid across a fold is kept; without it
/// (seed eq. 3's `Δρ·ρ_B^j`) the part on `A` is foreshortened by the fold angle's cosine.
/// Coplanar facets (`|n_A × n_B| < 1e-10`): plain re-projection either way.
pub fn map_point(a: &Facet<f64>, xi_a: [f64; 2], b: &Facet<f64>, unfold: bool) -> Result<[f64; 2], TransferError> {
    let pa = a.point(xi_a).map_err(TransferError::Old)?;
    let first = project(b, pa.rho).map_err(TransferError::Reprojection)?;
    let (na, nb) = (pa.normal, first.point.normal);
    let k = cross(na, nb);
    let k2 = dot(k, k);
    if !unfold || k2 < 1e-20 {
        return Ok(first.point.xi);
    }
    // a point of the planes' intersection: p0 = [d_A (n_B × k) + d_B (k × n_A)] / |k|²
    let (da, db) = (dot(na, pa.rho), dot(nb, first.point.rho));
    let p0 = scale(add(scale(cross(nb, k), da), scale(cross(k, na), db)), 1.0 / k2);
    let turned = add(p0, rotate_between(na, nb, sub(pa.rho, p0))?);
    project(b, turned)
        .map(|p| p.point.xi)
        .map_err(TransferError::Reprojection)
}

/// Transfer `history` of facet `a` onto facet `b` by `scheme` (module docs).
pub fn transfer(scheme: Scheme, a: &Facet<f64>, history: &History, b: &Facet<f64>) -> Result<History, TransferError> {
    if scheme == Scheme::Straightforward {
        return Ok(*history);
    }
    let pa = a.point(history.xi).map_err(TransferError::Old)?;
    let t = pa.vector(history.traction);
    let xi_b = map_point(a, history.xi, b, scheme != Scheme::ContinuousProjected)?;
    let pb = b
        .point(xi_b)
        .map_err(|e| TransferError::Reprojection(ProjectionError::Geometry(e)))?;
    let carried = match scheme {
        Scheme::Continuous => rotate_between(pa.normal, pb.normal, t)?,
        Scheme::ContinuousProjected => t,
        _ => {
            let (fa, fb) = (unit_frame(&pa), unit_frame(&pb));
            add(scale(fb[0], dot(t, fa[0])), scale(fb[1], dot(t, fa[1])))
        }
    };
    Ok(History {
        xi: xi_b,
        traction: pb.covariant(carried),
    })
}

/// The trial tractions a history carried onto `B` by some scheme gives against the parallel
/// translation's: `(‖T^tr_c‖, ‖T^tr_s‖)` in `B`'s metric at the translated point, where
/// `T^tr_s − T^tr_c = (T^s − T^c) + ε_T a_αβ (ξ_s − ξ_c)^β` (`T^tr = T − ε_T a_αβ (ξ − ξ_B)^β`
/// of each). `None` where the parallel translation itself fails. The 3D counterpart of the 2D
/// crossing's trial before and after: a scheme that does not carry the history makes them
/// differ (straightforward: by about `ε_T ℓ`, the jump of `ξ` across an edge).
pub fn trial_against_continuous(
    a: &Facet<f64>,
    history: &History,
    b: &Facet<f64>,
    carried: &History,
    eps_t: f64,
) -> Option<(f64, f64)> {
    let cont = transfer(Scheme::Continuous, a, history, b).ok()?;
    let p = b.point(cont.xi).ok()?;
    let dxi = [carried.xi[0] - cont.xi[0], carried.xi[1] - cont.xi[1]];
    let shift = p.lower(dxi);
    let scheme: [f64; 2] = std::array::from_fn(|k| carried.traction[k] + eps_t * shift[k]);
    Some((p.norm(cont.traction), p.norm(scheme)))
}
