//! The MCAP recording: the writer and its channels, the schemas, format 3's arrays and the
//! Foxglove-native channels.

pub mod arrays;
pub mod format3;
pub mod foxglove;
pub mod foxglove3d;
pub mod json_text;
pub mod out;
pub mod schemas;
pub mod sink;
pub mod surface_arrays;
