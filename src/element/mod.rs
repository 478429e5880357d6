//! Continuum element kernels: local data in, local residual and tangent out.

pub mod fields;
pub mod material;
pub mod quad;
