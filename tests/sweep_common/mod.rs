//! Shared helpers of the sweep tests: a scratch folder per test and the smoke plan.
#![allow(dead_code)]

use contrail::sweep::{run_sweep, IndexRow, Plan, Shard, SweepOptions, SweepReport};
use std::path::{Path, PathBuf};
use std::sync::atomic::AtomicBool;

/// A fresh scratch folder under the target directory's temp space.
pub fn scratch(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("contrail-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// The repository's smoke plan.
pub fn smoke_plan() -> Plan {
    Plan::load(&Path::new(env!("CARGO_MANIFEST_DIR")).join("sweeps/smoke.toml")).unwrap_or_else(|e| panic!("{e}"))
}

/// Run `plan` (or a shard) into `out` with two workers.
pub fn sweep(plan: &Plan, out: &Path, shard: Option<Shard>) -> SweepReport {
    let opts = SweepOptions {
        out: out.to_path_buf(),
        jobs: 2,
        shard,
        positions_every: 1,
    };
    run_sweep(plan, &opts, &AtomicBool::new(false), &|l| println!("{l}")).unwrap_or_else(|e| panic!("{e}"))
}

/// A row with the machine-dependent fields (wall time, recording path) blanked.
pub fn comparable(r: &IndexRow) -> IndexRow {
    IndexRow {
        wall_time_s: 0.0,
        recording: String::new(),
        ..r.clone()
    }
}
