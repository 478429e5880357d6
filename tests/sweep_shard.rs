//! `--shard 1/2` and `--shard 2/2` into two folders plus `sweep merge` give the same index
//! as the unsharded sweep (modulo wall times and recording paths), although the finest-run
//! reference of `block-slide` is in only one of the shards.

mod sweep_common;

use contrail::sweep::{merge, Index, Shard};

#[test]
fn shards_and_merge_equal_the_whole() {
    let dir = sweep_common::scratch("sweep-shard");
    let plan = sweep_common::smoke_plan();
    let whole = sweep_common::sweep(&plan, &dir.join("whole"), None);
    let a = sweep_common::sweep(&plan, &dir.join("a"), Some(Shard { index: 1, count: 2 }));
    let b = sweep_common::sweep(&plan, &dir.join("b"), Some(Shard { index: 2, count: 2 }));
    assert_eq!(a.selected + b.selected, whole.selected);
    assert!(a.index_csv.ends_with("index-shard-1-of-2.csv"));
    let (rows, csv, _) = merge(&[dir.join("a"), dir.join("b")], &dir.join("merged")).unwrap();
    let merged: Vec<_> = rows.iter().map(sweep_common::comparable).collect();
    let unsharded: Vec<_> = whole.rows.iter().map(sweep_common::comparable).collect();
    assert_eq!(merged, unsharded);
    assert!(csv.is_file());
    // recordings are referenced where the shards left them
    let index = Index::load(&dir.join("merged")).unwrap();
    assert!(index.runs.iter().all(|r| std::path::Path::new(&r.recording).is_file()));
    // a folder of another plan does not merge
    let mut other = plan.clone();
    other.name = "other".into();
    sweep_common::sweep(&other, &dir.join("c"), Some(Shard { index: 1, count: 8 }));
    assert!(merge(&[dir.join("a"), dir.join("c")], &dir.join("m2")).is_err());
    std::fs::remove_dir_all(&dir).unwrap();
}
