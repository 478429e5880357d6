//! A resumed sweep skips the finished runs; a stopped sweep leaves a consistent index of the
//! runs that finished, and running it again completes it with the same index.

mod sweep_common;

use contrail::sweep::{run_sweep, Plan, SweepOptions};
use std::path::Path;
use std::sync::atomic::AtomicBool;

fn small() -> Plan {
    Plan::parse(
        "name = \"r\"\n[[study]]\nscene = \"crossing\"\nset = [\"stepping.increments=30\"]\n\
         grid = { \"contact.transfer\" = [\"continuous\", \"path-length\", \"straightforward\"] }\n",
        "r.toml",
        Path::new(""),
    )
    .unwrap()
}

#[test]
fn resume_skips_finished_runs() {
    let dir = sweep_common::scratch("sweep-resume");
    let plan = small();
    let first = sweep_common::sweep(&plan, &dir, None);
    assert_eq!((first.ran, first.skipped, first.rows.len()), (3, 0, 3));
    // forget one run: only that one is made again
    std::fs::remove_file(dir.join("runs").join(format!("{}.json", first.rows[1].id))).unwrap();
    let again = sweep_common::sweep(&plan, &dir, None);
    assert_eq!((again.ran, again.skipped), (1, 2));
    let a: Vec<_> = first.rows.iter().map(sweep_common::comparable).collect();
    let b: Vec<_> = again.rows.iter().map(sweep_common::comparable).collect();
    assert_eq!(a, b);
    let third = sweep_common::sweep(&plan, &dir, None);
    assert_eq!((third.ran, third.skipped), (0, 3));
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_stopped_sweep_leaves_a_consistent_index_and_resumes() {
    let dir = sweep_common::scratch("sweep-stop");
    let plan = small();
    let opts = SweepOptions {
        out: dir.clone(),
        jobs: 1,
        shard: None,
        positions_every: 1,
    };
    let stopped = run_sweep(&plan, &opts, &AtomicBool::new(true), &|_| {}).unwrap();
    assert!(stopped.interrupted);
    assert_eq!(stopped.rows.len(), 0);
    let csv = std::fs::read_to_string(dir.join("index.csv")).unwrap();
    assert_eq!(csv.lines().count(), 1, "header only");
    let done = sweep_common::sweep(&plan, &dir, None);
    assert!(!done.interrupted);
    assert_eq!(done.rows.len(), 3);
    std::fs::remove_dir_all(&dir).unwrap();
}
