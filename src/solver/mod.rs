//! Newton–Raphson with load stepping, automatic cut-backs and step growth.

pub mod active_set;
pub mod augmented;
mod continuation;
pub mod element_check;
pub mod equilibrium;
pub mod faceted_node;
pub mod friction_limit;
mod line_search;
pub mod monitor;
pub mod newton;
mod newton_failure;
mod newton_types;
pub mod penetration;
pub mod run;
mod search_reach;
pub mod stability;
pub mod state;
mod stepping;
pub mod tangent_check;

pub use run::{run, RunSummary, SolveError};
