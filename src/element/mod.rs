//! Continuum element kernels: local data in, local residual and tangent out.

pub mod body_force;
pub mod fields;
pub mod material;
pub mod quad;
