//! The rerun stream of a run (`.rrd` or a live viewer): what is logged where, and how it looks.

pub mod curve;
pub mod sink;
pub mod style;
pub mod view;
pub mod view3d;
