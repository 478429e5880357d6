//! ParaView output: VTK XML files and the sink that writes a series of them.

pub mod file;
pub mod sink;
