//! Post-processing of results (summaries, plots).

pub mod plot;
