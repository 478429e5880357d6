//! A finished run is skipped on resume also when a contact point has no position at its
//! last increment (the strip-channel's corner C, open once the strip's end has passed it:
//! its contact point is NaN). Such a point is left out of the run's `final_contact`, so the
//! run record holds only finite numbers and reads back; a record that did not read back was
//! taken as unfinished and the run made again at every resume.
//!
//! ```text
//!   strip (24×1) drawn over C to v = 12: C is open at the end (the end passed it at v ≈ 9.1)
//! ```

mod sweep_common;

use contrail::sweep::{read_records, Plan};
use std::path::Path;

#[test]
fn a_run_ending_with_an_open_vertex_point_is_finished_on_resume() {
    let plan = Plan::parse(
        "name = \"open-corner\"\n[[study]]\nscene = \"strip-channel\"\nset = [\"stepping.increments=300\"]\n",
        "open-corner.toml",
        Path::new(""),
    )
    .unwrap();
    let dir = sweep_common::scratch("sweep-open-corner");
    let first = sweep_common::sweep(&plan, &dir, None);
    assert_eq!((first.ran, first.skipped), (1, 0));
    assert_eq!(first.rows[0].status, "completed", "{:?}", first.rows[0]);
    let recs = read_records(&dir);
    assert_eq!(recs.len(), 1, "the run record reads back");
    let fc = &recs[0].outcome.data.final_contact;
    assert!(!fc.is_empty() && fc.iter().flatten().all(|v| v.is_finite()), "{fc:?}");
    let again = sweep_common::sweep(&plan, &dir, None);
    assert_eq!((again.ran, again.skipped), (0, 1));
    std::fs::remove_dir_all(&dir).unwrap();
}
