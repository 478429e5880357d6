//! Post-processing of results (summaries, plots).

pub mod diff;
pub mod inspect;
pub mod plot;
pub mod recording;
