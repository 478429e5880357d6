//! Post-processing of results (summaries, plots).

pub mod analytic;
pub mod chunks;
pub mod convert;
pub mod diff;
pub mod diff_surface;
pub mod elastica;
pub mod export;
pub mod hertz_point;
pub mod inspect;
pub mod inspect_surface;
pub mod metrics;
pub mod plot;
pub mod recording;
pub mod recover;
pub mod restore;
pub mod validate_records;
