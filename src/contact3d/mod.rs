//! 3D node-to-surface frictional contact: the point kernel only (issue "Three dimensions").
//! Nothing else in the solver uses it yet.
//!
//! - [`surface`]: a 4-node bilinear master facet, `ρ(ξ¹, ξ²)`, `ρ_α`, `a_αβ`, `a^αβ`, `n`,
//!   `h_αβ`;
//! - [`projection`]: closest-point projection by Newton in `(ξ¹, ξ²)`, typed outcomes;
//! - [`point`]: penalty normal force, Coulomb friction by return mapping with the surface
//!   metric, residual and consistent tangent (15 DOFs) by second-order dual numbers;
//! - [`transfer`]: the friction history carried across a facet edge (straightforward,
//!   continuous by parallel translation, path length).
//!
//! Formulas: Konyukhov & Schweizerhof, Comput Mech 35 (2005) 190–213 (covariant description
//! on surfaces), the seed (continuous transfer, eqs. 1–4), notes `contact-3d.md`.

pub mod point;
pub mod projection;
pub mod surface;
pub mod transfer;
pub mod vec3;

#[cfg(test)]
mod point_tests;
#[cfg(test)]
mod projection_tests;
#[cfg(test)]
mod transfer_tests;
