//! Sweeps: a plan (TOML) of scenes × `--set` grids → runs in parallel, each recorded to MCAP
//! under one output folder → an index (CSV and JSON) with parameters, outcome, failure kind,
//! figures and error metrics. Resumable (finished runs are skipped), splittable across
//! machines (`--shard i/n`) and mergeable (`merge`).
//!
//! Output folder layout: `plan.json` (the resolved plan), `runs/ID.mcap` (recordings),
//! `runs/ID.json` (what each finished run returned; the index is recomputed from these),
//! `index.csv` / `index.json` (or `index-shard-I-of-N.*` for a shard).

mod execute;
mod expand;
mod index;
mod plan;
mod score;

pub use execute::{merge, run_sweep, SweepOptions, SweepReport};
pub use expand::{expand, fnv1a, PlannedRun, Shard};
pub use index::{read_records, to_csv, write_atomic, Index, IndexRow, Metrics, RunRecord};
pub use plan::{Checks, Plan, Reference, StudyPlan};
pub use score::{read_csv_curve, score};

/// A sweep that could not be planned, run or merged.
#[derive(Debug, thiserror::Error)]
pub enum SweepError {
    #[error("{origin}:{line}:{column}: {message}\n  hint: {hint}")]
    Plan {
        origin: String,
        line: usize,
        column: usize,
        message: String,
        hint: String,
    },
    #[error(
        "two runs have the same parameters (run {id}: {sets})\n  hint: remove the repeated value from the grid or list"
    )]
    Duplicate { id: String, sets: String },
    #[error("run {id} ({sets}): {source}")]
    BadRun {
        id: String,
        sets: String,
        #[source]
        source: Box<crate::scene::SceneError>,
    },
    #[error("{path}: {source}")]
    Io {
        path: String,
        #[source]
        source: std::io::Error,
    },
    #[error("{path}: {message}")]
    Index { path: String, message: String },
    #[error(
        "{path}:{line}: {message}\n  hint: a reference curve is a CSV file with a header and numeric x, y columns"
    )]
    Reference { path: String, line: usize, message: String },
    #[error("{message}\n  hint: {hint}")]
    Merge { message: String, hint: String },
    #[error(transparent)]
    Study(#[from] crate::study::StudyError),
}
