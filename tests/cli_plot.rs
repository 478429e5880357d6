//! `contrail plot` reads MCAP recordings directly (the load–displacement pairs of the
//! `/increment` monitor records) next to CSV files, and says why it cannot plot a recording
//! without a monitor.

use std::process::{Command, Output};

fn contrail(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_contrail"))
        .args(args)
        .output()
        .expect("run contrail")
}

#[test]
fn plot_reads_mcap_and_csv() {
    let d = std::env::temp_dir().join(format!("contrail-cli-plot-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    let p = |n: &str| d.join(n).to_str().unwrap().to_string();
    let o = contrail(&[
        "run",
        "block-slide",
        "--quiet",
        "--out",
        &p("a.mcap"),
        "--out",
        &p("a.csv"),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    for out in ["fig.svg", "fig.png"] {
        let o = contrail(&[
            "plot",
            &format!("{}=mcap", p("a.mcap")),
            &format!("{}=csv", p("a.csv")),
            "--out",
            &p(out),
        ]);
        let err = String::from_utf8_lossy(&o.stderr);
        assert!(o.status.success(), "{err}");
        assert!(std::fs::metadata(p(out)).unwrap().len() > 1000);
    }
    // (the SVG draws its text as glyph outlines, so the legend labels cannot be read back)
    let svg = std::fs::read_to_string(p("fig.svg")).unwrap();
    assert!(svg.matches("<polyline").count() >= 2, "both series are drawn");

    // a recording without a monitor
    let o = contrail(&["run", "crossing", "--quiet", "--out", &p("c.mcap")]);
    assert!(o.status.success());
    let o = contrail(&["plot", &p("c.mcap"), "--out", &p("c.svg")]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(err.contains("has no [monitor]"), "{err}");
    assert!(!err.contains("UTF-8"), "{err}");
}
