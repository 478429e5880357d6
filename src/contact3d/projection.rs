//! Closest-point projection of a slave point onto a facet (bilinear or bent) (Konyukhov &
//! Schweizerhof, Comput Mech 35 (2005) §2; on its solvability near edges and vertices:
//! Konyukhov & Schweizerhof, CMAME 197 (2008); notes `contact-3d.md` §"Surfaces").
//!
//! The closest point solves `f_α(ξ) = (r_s − ρ(ξ))·ρ_α(ξ) = 0` with Jacobian
//! `∂f_α/∂ξ^β = −a_αβ + (r_s − ρ)·ρ_αβ` (`= −a_αβ + ζ h_αβ` at the solution). Newton runs on
//! the real parts from `ξ = 0` (or a given start), each step limited to a length of 1 in
//! `ξ` and kept in the box `|ξ^α| ≤ `[`XI_BOX`] of the facet's bilinear extension; then two
//! more Newton steps in the scalar type `S`. From a converged real root these give the
//! exact first and second derivatives of `ξ` with respect to every node (the
//! implicit-function derivatives, as in the 2D `surface::smooth_closest_xi`), so the
//! kernel's tangent stays consistent.
//!
//! Outcomes are typed: a converged projection is [`Location::Inside`] the facet
//! (`|ξ^α| ≤ 1` up to [`INSIDE_TOLERANCE`]) or [`Location::Outside`] with the `ξ` found (the
//! point belongs to a neighbour, an edge or a vertex: the caller decides); otherwise a
//! [`ProjectionError`].

use super::surface::{Facet, FacetPoint, GeometryError};
use super::vec3::{dot, re, sub, Scalar, V3};
use thiserror::Error;

/// Half-width of the box of the facet's bilinear extension that Newton may search.
pub const XI_BOX: f64 = 4.0;

/// A Newton step below this that does not halve the one before is round-off: the projection
/// has converged as far as the arithmetic allows (the two steps in the scalar type follow).
pub const ROUNDOFF_STEP: f64 = 1e-9;

/// `|ξ^α| ≤ 1 + INSIDE_TOLERANCE` counts as inside.
pub const INSIDE_TOLERANCE: f64 = 1e-12;

/// Where a converged projection lies.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Location {
    /// `|ξ^α| ≤ 1`: on the facet.
    Inside,
    /// On the facet's bilinear extension, outside `[−1, 1]²`.
    Outside,
}

/// Why no closest point was found.
#[derive(Debug, Clone, Copy, PartialEq, Error)]
pub enum ProjectionError {
    #[error("projection: {0}")]
    Geometry(#[from] GeometryError),
    /// Newton did not reach the tolerance (or left the box, or met a singular Jacobian).
    #[error("projection did not converge: xi = {xi:?} after {iterations} iterations, last step {step:e}")]
    NotConverged { xi: [f64; 2], iterations: usize, step: f64 },
}

/// Newton's settings.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ProjectionOptions {
    pub max_iterations: usize,
    /// Converged when the largest component of a step is at most this.
    pub tolerance: f64,
    /// Starting point.
    pub start: [f64; 2],
}

impl Default for ProjectionOptions {
    fn default() -> Self {
        ProjectionOptions {
            max_iterations: 30,
            tolerance: 1e-14,
            start: [0.0, 0.0],
        }
    }
}

/// A converged closest-point projection.
#[derive(Debug, Clone, Copy)]
pub struct Projection<S: Scalar> {
    /// The facet's geometry at the closest point `ξ` (not clamped to `[−1, 1]²`).
    pub point: FacetPoint<S>,
    /// Signed normal gap `ζ = (r_s − ρ)·n` (negative = penetration).
    pub gap: S,
    pub location: Location,
    /// Newton iterations on the real parts.
    pub iterations: usize,
}

impl<S: Scalar> Projection<S> {
    /// The projection onto an analytic surface whose closest point is closed-form (a rigid
    /// sphere's or cylinder's chart): inside its chart, no Newton iteration.
    pub fn closed_form(point: FacetPoint<S>, gap: S) -> Self {
        Projection {
            point,
            gap,
            location: Location::Inside,
            iterations: 0,
        }
    }
}

/// Newton step `Δξ = −J⁻¹ f` at `ξ` for slave `rs`, or `None` where `J` is singular.
fn newton_step<S: Scalar>(facet: &Facet<S>, rs: V3<S>, xi: [S; 2]) -> Option<[S; 2]> {
    let d = sub(rs, facet.position(xi));
    let [t1, t2] = facet.tangents(xi);
    let [[r11, r12], [_, r22]] = facet.second_derivatives(xi);
    let d12 = dot(d, r12);
    let f = [dot(d, t1), dot(d, t2)];
    // J = −a + d·ρ_αβ
    let j = [
        [dot(d, r11) - dot(t1, t1), d12 - dot(t1, t2)],
        [d12 - dot(t1, t2), dot(d, r22) - dot(t2, t2)],
    ];
    let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
    let scale = j[0][0].re().abs() * j[1][1].re().abs() + j[0][1].re().powi(2);
    // NaN fails the comparison: singular
    if det.re().abs().partial_cmp(&(1e-14 * scale)) != Some(std::cmp::Ordering::Greater) {
        return None;
    }
    let inv = det.recip();
    Some([
        -(j[1][1] * f[0] - j[0][1] * f[1]) * inv,
        -(j[0][0] * f[1] - j[1][0] * f[0]) * inv,
    ])
}

/// [`project_with`] with the default options.
pub fn project<S: Scalar>(facet: &Facet<S>, rs: V3<S>) -> Result<Projection<S>, ProjectionError> {
    project_with(facet, rs, &ProjectionOptions::default())
}

/// Closest point of `rs` on `facet` (see the module docs).
pub fn project_with<S: Scalar>(
    facet: &Facet<S>,
    rs: V3<S>,
    opts: &ProjectionOptions,
) -> Result<Projection<S>, ProjectionError> {
    let (xi, iterations) = real_newton(facet, rs, opts)?;
    let mut x: [S; 2] = [S::from(xi[0]), S::from(xi[1])];
    for _ in 0..2 {
        let step = newton_step(facet, rs, x).ok_or(ProjectionError::NotConverged {
            xi,
            iterations,
            step: f64::NAN,
        })?;
        x = [x[0] + step[0], x[1] + step[1]];
    }
    let point = facet.point(x)?;
    let gap = dot(sub(rs, point.rho), point.normal);
    let inside = xi.iter().all(|v| v.abs() <= 1.0 + INSIDE_TOLERANCE);
    Ok(Projection {
        point,
        gap,
        location: if inside { Location::Inside } else { Location::Outside },
        iterations,
    })
}

/// Newton on the real parts: the converged `ξ` and the number of iterations.
fn real_newton<S: Scalar>(
    facet: &Facet<S>,
    rs: V3<S>,
    opts: &ProjectionOptions,
) -> Result<([f64; 2], usize), ProjectionError> {
    let real = facet.real();
    let rs = re(rs);
    // the facet must be usable where Newton starts (a collapsed facet fails here, typed)
    real.point(opts.start)?;
    let mut xi = opts.start;
    let mut last = f64::INFINITY;
    let mut previous = f64::INFINITY;
    for it in 1..=opts.max_iterations {
        let not_converged = ProjectionError::NotConverged {
            xi,
            iterations: it,
            step: last,
        };
        let step = newton_step(&real, rs, xi).ok_or(not_converged)?;
        let len = step[0].abs().max(step[1].abs());
        if !len.is_finite() {
            return Err(not_converged);
        }
        let damp = if len > 1.0 { 1.0 / len } else { 1.0 };
        xi = [xi[0] + damp * step[0], xi[1] + damp * step[1]];
        last = len;
        if xi.iter().any(|v| v.abs() > XI_BOX) {
            return Err(ProjectionError::NotConverged {
                xi,
                iterations: it,
                step: len,
            });
        }
        // at the tolerance, or at round-off: a small step that no longer halves (on a long,
        // narrow facet the narrow direction's `ξ` is resolved only to `ε |r_s − ρ| / |ρ_α|`)
        if len <= opts.tolerance || (len <= ROUNDOFF_STEP && len > 0.5 * previous) {
            return Ok((xi, it));
        }
        previous = len;
    }
    Err(ProjectionError::NotConverged {
        xi,
        iterations: opts.max_iterations,
        step: last,
    })
}
