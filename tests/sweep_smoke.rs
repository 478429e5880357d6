//! `contrail sweep sweeps/smoke.toml --out DIR` writes DIR/index.csv and DIR/index.json with
//! one row per run, a recording per run, and the expected outcomes: on `crossing` the
//! continuous transfer passes and the straightforward one is flagged as a wrong answer by
//! the crossing-jump check; on `block-slide` every run completes and has errors against the
//! finest continuous run (exactly zero for that run itself). Charts render from the index.

mod sweep_common;

use contrail::study::FailureKind;
use contrail::sweep::{expand, Index};
use std::process::Command;

#[test]
fn smoke_plan_from_the_command_line() {
    let dir = sweep_common::scratch("sweep-smoke");
    let out = dir.join("out");
    let bin = env!("CARGO_BIN_EXE_contrail");
    let root = env!("CARGO_MANIFEST_DIR");
    let st = Command::new(bin)
        .current_dir(root)
        .args(["sweep", "sweeps/smoke.toml", "--jobs", "2", "--out"])
        .arg(&out)
        .status()
        .unwrap();
    assert!(st.success());
    let n = expand(&sweep_common::smoke_plan()).unwrap().len();
    assert_eq!(n, 10);
    let csv = std::fs::read_to_string(out.join("index.csv")).unwrap();
    assert_eq!(csv.lines().count(), n + 1, "{csv}");
    let index = Index::load(&out.join("index.json")).unwrap();
    assert_eq!(index.runs.len(), n);
    assert_eq!(index.plan, "smoke");
    for r in &index.runs {
        assert!(out.join(&r.recording).is_file(), "{}", r.recording);
        assert_eq!(r.status, "completed", "{}: {}", r.id, r.message);
        assert!(r.increments > 0 && r.newton_iterations > 0);
        match (
            r.study.as_str(),
            r.params.get("contact.transfer").map_or("", |v| v.as_str()),
        ) {
            ("crossing", "continuous") => {
                assert!(r.passed(), "{}: {}", r.id, r.message);
                assert!(r.metrics.jump_rel_max.unwrap() < 1e-3);
            }
            ("crossing", _) => {
                assert_eq!(r.failure_kind, Some(FailureKind::WrongAnswer));
                assert!(r.failure_increment.is_some());
            }
            ("block-slide", t) => {
                assert!(r.passed(), "{}: {}", r.id, r.message);
                assert!(!r.reference.is_empty());
                let e = r.metrics.err_max.unwrap();
                if r.id == r.reference {
                    assert_eq!(e, 0.0);
                    assert_eq!(t, "continuous");
                }
            }
            ("hertz", _) => {
                assert!(r.passed(), "{}: {}", r.id, r.message);
                assert!(r.metrics.analytic_err.unwrap() < 0.5, "{}", r.metrics.analytic_detail);
            }
            _ => unreachable!(),
        }
    }
    // the recordings are complete contrail recordings
    let rec = contrail::analysis::recording::Recording::open(&out.join(&index.runs[0].recording)).unwrap();
    assert!(rec.outcome.is_some());
    // the charts render from the index
    for args in [
        vec!["chart", "pareto"],
        vec![
            "chart",
            "stability",
            "--study",
            "crossing",
            "--x",
            "stepping.increments",
            "--y",
            "contact.transfer",
        ],
    ] {
        let st = Command::new(bin)
            .args(&args)
            .arg(out.join("index.json"))
            .status()
            .unwrap();
        assert!(st.success(), "{args:?}");
    }
    for f in ["pareto.svg", "pareto.png", "stability.svg", "stability.png"] {
        assert!(std::fs::metadata(out.join(f)).unwrap().len() > 1000, "{f}");
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn bad_plans_are_errors_with_a_location() {
    let bin = env!("CARGO_BIN_EXE_contrail");
    let dir = sweep_common::scratch("sweep-bad");
    let plan = dir.join("p.toml");
    std::fs::write(&plan, "name = \"p\"\n[[study]]\nscene = \"crossing\"\ngird = {}\n").unwrap();
    let o = Command::new(bin)
        .arg("sweep")
        .arg(&plan)
        .arg("--out")
        .arg(dir.join("o"))
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("p.toml:") && err.contains("gird"), "{err}");
    std::fs::write(
        &plan,
        "name = \"p\"\n[[study]]\nscene = \"crossing\"\ngrid = { \"contact.mu\" = [0.1, \"x\"] }\n",
    )
    .unwrap();
    let o = Command::new(bin)
        .arg("sweep")
        .arg(&plan)
        .arg("--out")
        .arg(dir.join("o"))
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("contact.mu"), "{err}");
    std::fs::remove_dir_all(&dir).unwrap();
}
