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

/// `contrail plot RUN.mcap --pressure INC`: the `/pressure` profile at an increment (or the
/// last), and errors that say which increments and pairs there are.
#[test]
fn plot_draws_the_contact_pressure_of_an_increment() {
    let d = std::env::temp_dir().join(format!("contrail-cli-pressure-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    let p = |n: &str| d.join(n).to_str().unwrap().to_string();
    let o = contrail(&[
        "run",
        "hertz",
        "--quiet",
        "--set",
        "body.block.mesh.elements=[10, 8]",
        "--positions-every",
        "2",
        "--out",
        &p("h.mcap"),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    for (inc, out) in [("last", "p.svg"), ("2", "p.png"), ("5", "p5.svg")] {
        let o = contrail(&["plot", &p("h.mcap"), "--pressure", inc, "--out", &p(out)]);
        assert!(o.status.success(), "{inc}: {}", String::from_utf8_lossy(&o.stderr));
        assert!(std::fs::metadata(p(out)).unwrap().len() > 1000);
    }
    let svg = std::fs::read_to_string(p("p.svg")).unwrap();
    assert!(svg.contains("<polyline"), "the profile is drawn");
    // increment 3 has no /positions, hence no profile
    let o = contrail(&["plot", &p("h.mcap"), "--pressure", "3", "--out", &p("x.svg")]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(
        err.contains("no pressure profile at increment 3") && err.contains("2, 4, 5"),
        "{err}"
    );
    let o = contrail(&[
        "plot",
        &p("h.mcap"),
        "--pressure",
        "last",
        "--pair",
        "nope",
        "--out",
        &p("x.svg"),
    ]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(err.contains("pairs: indenter"), "{err}");
    let o = contrail(&["plot", &p("h.mcap"), "--pressure", "soon", "--out", &p("x.svg")]);
    assert_eq!(o.status.code(), Some(2));
    let _ = std::fs::remove_dir_all(&d);
}
