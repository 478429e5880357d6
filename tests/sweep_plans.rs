//! Every plan under `sweeps/` loads, and every run it plans builds: its scene with the
//! study's overrides and the varied ones (no run is solved). A plan whose scene or keys drift
//! from the scene format fails here rather than at the first run of a long sweep.

use contrail::sweep::{expand, Plan};
use std::path::Path;

#[test]
fn every_shipped_plan_loads_and_every_planned_run_builds() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("sweeps");
    let mut plans: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e == "toml"))
        .collect();
    plans.sort();
    assert!(plans.len() >= 10, "{plans:?}");
    let mut runs = 0;
    for path in &plans {
        let plan = Plan::load(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
        for run in expand(&plan).unwrap_or_else(|e| panic!("{}: {e}", path.display())) {
            if let Err(e) = contrail::load_any_scene(&run.scene, &run.sets) {
                panic!(
                    "{}: run {} ({}) does not build: {e}",
                    path.display(),
                    run.id,
                    run.sets.join(" ")
                );
            }
            runs += 1;
        }
    }
    println!("{} plans, {runs} runs built", plans.len());
}
