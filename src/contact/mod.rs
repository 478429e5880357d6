//! Node-to-segment frictional contact in the covariant description.

pub mod augmented;
pub mod config;
pub mod decision;
pub mod events;
pub mod geometry;
pub mod history;
pub mod law;
pub mod pairing;
pub mod point;
pub mod scalar;
pub mod search;
pub mod surface;
pub mod system;
pub mod transfer;
pub mod vertex;
