//! 3D node-to-surface frictional contact (issue "Three dimensions").
//!
//! - [`surface`]: a 4-node master facet, bilinear or bent ([`nagata`]: smooth patches from
//!   nodal normals), `ρ(ξ¹, ξ²)`, `ρ_α`, `a_αβ`, `a^αβ`, `n`,
//!   `h_αβ`;
//! - [`projection`]: closest-point projection by Newton in `(ξ¹, ξ²)`, typed outcomes;
//! - [`point`]: penalty normal force, Coulomb friction by return mapping with the surface
//!   metric, residual and consistent tangent (15 DOFs) by second-order dual numbers, the state
//!   decided by [`decision`];
//! - [`decision`]: the contact Newton's rule on a surface — the Alart–Curnier functions of a
//!   point's force unknowns, and the slip force of its condensed step;
//! - [`transfer`]: the friction history carried across a facet edge (straightforward,
//!   continuous by parallel translation, path length);
//! - [`cylinder`], [`sphere`]: convective coordinates on a rigid cylinder and a rigid sphere
//!   (friction on them);
//! - [`master`]: a point against a facet, a rigid plane, cylinder or sphere, its local arrays;
//! - [`evaluate`]: one slave paired, its history carried, its kernel evaluated;
//! - [`search`]: the facet grid of a pair;
//! - [`system`]: the state of every 3D pair and point, evaluated into the assembly;
//! - [`unknowns`]: the points' force unknowns in Newton's iterate.
//!
//! Formulas: Konyukhov & Schweizerhof, Comput Mech 35 (2005) 190–213 (covariant description
//! on surfaces), the seed (continuous transfer, eqs. 1–4), notes `contact-3d.md`.

pub mod cylinder;
pub mod decision;
pub mod evaluate;
pub mod locate;
pub mod master;
pub mod nagata;
pub mod point;
pub mod projection;
pub mod search;
pub mod sphere;
pub mod surface;
pub mod system;
pub mod transfer;
pub mod unknowns;
pub mod variations;
pub mod vec3;

#[cfg(test)]
mod point_tests;
#[cfg(test)]
mod point_unknowns_tests;
#[cfg(test)]
mod projection_tests;
#[cfg(test)]
mod transfer_tests;
