//! 3D node-to-surface frictional contact (issue "Three dimensions").
//!
//! - [`surface`]: a 4-node bilinear master facet, `ρ(ξ¹, ξ²)`, `ρ_α`, `a_αβ`, `a^αβ`, `n`,
//!   `h_αβ`;
//! - [`projection`]: closest-point projection by Newton in `(ξ¹, ξ²)`, typed outcomes;
//! - [`point`]: penalty normal force, Coulomb friction by return mapping with the surface
//!   metric, residual and consistent tangent (15 DOFs) by second-order dual numbers;
//! - [`transfer`]: the friction history carried across a facet edge (straightforward,
//!   continuous by parallel translation, path length);
//! - [`master`]: a point against a facet, a rigid plane or a rigid sphere, as assembled;
//! - [`search`]: the facet grid of a pair;
//! - [`system`]: the state of every 3D pair and point, evaluated into the assembly.
//!
//! Formulas: Konyukhov & Schweizerhof, Comput Mech 35 (2005) 190–213 (covariant description
//! on surfaces), the seed (continuous transfer, eqs. 1–4), notes `contact-3d.md`.

pub mod master;
pub mod point;
pub mod projection;
pub mod search;
pub mod surface;
pub mod system;
pub mod transfer;
pub mod vec3;

#[cfg(test)]
mod point_tests;
#[cfg(test)]
mod projection_tests;
#[cfg(test)]
mod transfer_tests;
