//! Continuum element kernels: local data in, local residual and tangent out.

pub mod body_force;
mod eas_linear;
pub mod fields;
pub mod hex8;
pub mod material;
pub mod material3d;
pub mod material_models;
pub mod quad;
