//! The models sweep (`sweeps/models.toml`): one scene as an axisymmetric and as a 3D model,
//! each run scored against Hertz point contact, so that `chart pareto` shows which model is
//! enough.
//!
//! Reference: Hertz (Johnson, Contact Mechanics (1985) §4.2) for a rigid sphere (R = 1) on
//! a neo-Hookean block, E = 1000, ν = 0.3: contact radius `a` and peak pressure `p0` for the
//! run's total force (`src/analysis/hertz_point.rs`).
//! Parameters: the plan's coarse rungs — axisymmetric 8×6, 12×8, 20×12; the 3D quarter
//! model 8×8×6 (four copies make the whole); the axisymmetric scene revolved in 3D on the
//! section 8×6; δ = 0.005 in 4 increments.
//! Tolerances: the plan's check (max(|a|, |p0|) error ≤ 5 %) flags 8×6 (measured 7.7 %,
//! 2026-11-27) and passes 12×8 (5.0 %), 20×12 (3.1 %), the 3D 8×8×6 (2.1 %) and the revolved
//! 8×6 (2.1 %, 2026-11-28; below 3 % asserted for both 3D runs); the error
//! falls at each refinement of the axisymmetric ladder (the refinement this test asserts;
//! the finer rungs are in docs/models.md). The 3D run goes through the sweep like a 2D one:
//! recorded, scored, resumable.

mod sweep_common;

use contrail::study::FailureKind;
use contrail::sweep::{Index, Plan};
use std::path::Path;

fn plan() -> Plan {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("sweeps/models.toml");
    let mut plan = Plan::load(&path).unwrap_or_else(|e| panic!("{e}"));
    let key = "body.block.mesh.elements".to_string();
    let meshes = |m: &[&[i64]]| {
        m.iter()
            .map(|e| toml::Value::Array(e.iter().map(|n| toml::Value::Integer(*n)).collect()))
            .collect::<Vec<_>>()
    };
    for s in &mut plan.studies {
        let ladder = match s.name.as_str() {
            "axisymmetric" => meshes(&[&[8, 6], &[12, 8], &[20, 12]]),
            "3d-quarter" => meshes(&[&[8, 8, 6]]),
            "3d-revolved" => meshes(&[&[8, 6]]),
            other => panic!("a study the test does not know: {other}"),
        };
        s.grid.insert(key.clone(), ladder);
    }
    plan
}

#[test]
fn axisymmetric_and_3d_models_of_hertz_scored_alike() {
    let dir = sweep_common::scratch("sweep-models");
    let report = sweep_common::sweep(&plan(), &dir, None);
    let rows = &report.rows;
    assert_eq!(rows.len(), 5);
    for r in rows {
        assert_eq!(r.status, "completed", "{}: {}", r.id, r.message);
        assert_eq!(r.reference, "hertz-point");
        let e = r
            .metrics
            .analytic_err
            .unwrap_or_else(|| panic!("{}: no analytic error", r.id));
        println!("{} {:?}: {:.4} ({})", r.study, r.params, e, r.metrics.analytic_detail);
        let flagged = r.failure_kind == Some(FailureKind::WrongAnswer);
        assert_eq!(flagged, e > 0.05, "{}: flagged {flagged} at error {e}", r.id);
    }
    let axi: Vec<f64> = (rows.iter().filter(|r| r.study == "axisymmetric"))
        .map(|r| r.metrics.analytic_err.unwrap())
        .collect();
    assert!(axi[0] > 0.05, "the coarsest axisymmetric mesh is flagged: {axi:?}");
    assert!(
        axi.windows(2).all(|w| w[1] < w[0]),
        "the error falls with the mesh: {axi:?}"
    );
    let solid = rows.iter().find(|r| r.study == "3d-quarter").unwrap();
    assert!(
        solid.metrics.analytic_err.unwrap() < 0.03,
        "{}",
        solid.metrics.analytic_detail
    );
    assert!(solid.dofs > 1000 && dir.join(&solid.recording).is_file());
    // the axisymmetric scene revolved in 3D: the same body, below 3 % on its coarsest section
    let revolved = rows.iter().find(|r| r.study == "3d-revolved").unwrap();
    assert!(
        revolved.metrics.analytic_err.unwrap() < 0.03,
        "{}",
        revolved.metrics.analytic_detail
    );
    // the same command resumes: nothing is run again
    let again = sweep_common::sweep(&plan(), &dir, None);
    assert_eq!(again.rows.len(), 5);
    assert_eq!(Index::load(&dir).unwrap().runs.len(), 5);
    std::fs::remove_dir_all(&dir).unwrap();
}
