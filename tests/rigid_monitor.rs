//! Several monitors per scene, and monitors of rigid bodies.
//!
//! A rigid monitor reports the body's prescribed travel and the force its drive applies (the
//! reaction of the prescribed motion), the negative of the contact forces it receives. By
//! equilibrium of the deformable body (its only other forces are the reactions of its
//! prescribed nodes), the contact force it receives equals the total reaction `R` of the
//! deformable body's prescribed DOFs, so the drive's force is `−R`. Checked at every converged increment to `1e-6 · max |R|` over the run (the runs
//! converge to `‖R_free‖ ≤ 1e-9 F_ref` or tighter), for
//! - `block-slide` (rigid plane as master, friction, stick then slip),
//! - `hertz` (rigid arc as master, frictionless, x and y),
//! - `crossing` (a rigid point as slave, dragged in stick across segments).
//!
//! The first monitor stays `IncrementRecord::monitor` and the run summary's monitor.

mod common;

use contrail::record::{IncrementRecord, Memory, MonitorRecord};

fn by_label<'a>(inc: &'a IncrementRecord, label: &str) -> &'a MonitorRecord {
    inc.monitors
        .iter()
        .find(|m| m.label == label)
        .unwrap_or_else(|| panic!("no monitor {label} at increment {}", inc.increment))
}

/// Largest `|F + R|` over the run, relative to the largest `|R|`, for monitor `label` against
/// the reaction component `c`, with the sign `sign` of the monitor.
fn equilibrium_error(mem: &Memory, label: &str, c: usize, sign: f64) -> f64 {
    let scale = (mem.increments.iter())
        .map(|i| i.reaction_total[c].abs())
        .fold(0.0, f64::max);
    assert!(scale > 0.0, "no reaction in component {c}");
    (mem.increments.iter())
        .map(|i| (sign * by_label(i, label).force + i.reaction_total[c]).abs() / scale)
        .fold(0.0, f64::max)
}

fn with_monitors(builtin: &str, old_monitor: Option<&str>, monitors: &str) -> String {
    let text = contrail::scene::builtin::find(builtin).unwrap().text.to_string();
    let text = match old_monitor {
        Some(old) => text.replace(old, ""),
        None => text,
    };
    format!("{text}\n{monitors}")
}

#[test]
fn block_slide_plane_receives_the_reaction_and_the_first_monitor_is_kept() {
    let old = "[monitor]\nlabel = \"drag\"\nbody = \"block\"\nnodes = \"top\"\ncomponent = \"x\"\n";
    let text = with_monitors(
        "block-slide",
        Some(old),
        r#"
[[monitor]]
label = "drag"
body = "block"
nodes = "top"
component = "x"

[[monitor]]
label = "plane-x"
rigid = "plane"
component = "x"

[[monitor]]
label = "plane-y"
rigid = "plane"
component = "y"
sign = -1.0
"#,
    );
    assert!(text.contains("[[monitor]]") && !text.contains("\n[monitor]"));
    let (summary, mem) = common::solve_ok(&common::scene_text(&text));
    // the same run with the built-in single [monitor]
    let (single, single_mem) = common::solve_ok(&common::scene("block-slide", &[]));
    assert_eq!(mem.increments.len(), single_mem.increments.len());
    for (a, b) in mem.increments.iter().zip(&single_mem.increments) {
        let (ma, mb) = (a.monitor.as_ref().unwrap(), b.monitor.as_ref().unwrap());
        assert_eq!(ma.label, "drag");
        assert_eq!((ma.displacement, ma.force), (mb.displacement, mb.force));
        assert_eq!(a.monitors.len(), 3);
        assert_eq!(b.monitors.len(), 1);
        assert_eq!(by_label(a, "plane-x").displacement, 0.0, "the plane does not move");
    }
    assert_eq!(summary.monitor.unwrap().force, single.monitor.unwrap().force);
    assert_eq!(summary.monitors.len(), 3);
    let ex = equilibrium_error(&mem, "plane-x", 0, 1.0);
    let ey = equilibrium_error(&mem, "plane-y", 1, -1.0);
    println!("block-slide: plane force against the reactions: x {ex:.2e}, y {ey:.2e} (relative)");
    assert!(ex < 1e-6 && ey < 1e-6, "x {ex:e}, y {ey:e}");
    // the drag is resisted by friction: the plane is pulled along +x and pressed down, so
    // its drive holds it with a force along −x and (with sign = −1) up
    let last = mem.increments.last().unwrap();
    assert!(by_label(last, "plane-x").force < 0.0);
    assert!(
        by_label(last, "plane-y").force < 0.0,
        "the drive pushes the plane up; sign = −1 reports that as negative"
    );
}

#[test]
fn hertz_cylinder_reports_its_travel_and_the_contact_force() {
    let text = with_monitors(
        "hertz",
        None,
        r#"
[[monitor]]
label = "punch"
rigid = "cylinder"
component = "y"

[[monitor]]
label = "punch-x"
rigid = "cylinder"
component = "x"

[[monitor]]
label = "base"
body = "block"
nodes = "bottom"
component = "y"
"#,
    );
    let (_, mem) = common::solve_ok(&common::scene_text(&text));
    for inc in &mem.increments {
        let punch = by_label(inc, "punch");
        assert!(
            (punch.displacement + 0.01 * inc.t).abs() < 1e-15,
            "travel {}",
            punch.displacement
        );
        let base = by_label(inc, "base").force;
        assert!(
            (punch.force + base).abs() <= 1e-6 * base.abs(),
            "increment {}: punch {} base {base}",
            inc.increment,
            punch.force
        );
    }
    let ey = equilibrium_error(&mem, "punch", 1, 1.0);
    let ex = equilibrium_error(&mem, "punch-x", 0, 1.0);
    println!("hertz: cylinder force against the reactions: x {ex:.2e}, y {ey:.2e} (relative)");
    assert!(ex < 1e-6 && ey < 1e-6, "x {ex:e}, y {ey:e}");
    assert!(
        by_label(mem.increments.last().unwrap(), "punch").force < 0.0,
        "the drive pushes the cylinder down (travel and force both negative)"
    );
}

#[test]
fn a_rigid_slave_point_receives_the_reaction() {
    let text = with_monitors(
        "crossing",
        None,
        r#"
[[monitor]]
label = "P-x"
rigid = "P"
component = "x"

[[monitor]]
label = "P-y"
rigid = "P"
component = "y"
"#,
    );
    let (_, mem) = common::solve_ok(&common::scene_text(&text));
    let last = mem.increments.last().unwrap();
    assert!((by_label(last, "P-x").displacement - 1.6).abs() < 1e-12);
    let ex = equilibrium_error(&mem, "P-x", 0, 1.0);
    let ey = equilibrium_error(&mem, "P-y", 1, 1.0);
    println!("crossing: rigid point force against the reactions: x {ex:.2e}, y {ey:.2e} (relative)");
    assert!(ex < 1e-6 && ey < 1e-6, "x {ex:e}, y {ey:e}");
}

#[test]
fn monitor_errors_name_the_key() {
    let base = contrail::scene::builtin::find("hertz").unwrap().text;
    let cases = [
        ("[monitor]\nlabel = \"a\"\ncomponent = \"y\"\n", "monitor.body"),
        (
            "[monitor]\nlabel = \"a\"\nrigid = \"cylinder\"\nbody = \"block\"\nnodes = \"top\"\ncomponent = \"y\"\n",
            "not both",
        ),
        ("[monitor]\nlabel = \"a\"\nrigid = \"cylindre\"\ncomponent = \"y\"\n", "known rigid bodies: cylinder"),
        (
            "[[monitor]]\nlabel = \"a\"\nrigid = \"cylinder\"\ncomponent = \"y\"\n[[monitor]]\nlabel = \"a\"\nrigid = \"cylinder\"\ncomponent = \"x\"\n",
            "monitor.1.label",
        ),
    ];
    for (extra, expect) in cases {
        let src = contrail::scene::SceneSource {
            origin: "t.toml".into(),
            text: format!("{base}\n{extra}"),
        };
        let err = contrail::scene::parse(&src, &[])
            .and_then(|f| contrail::scene::build(&src, &f).map(|_| ()))
            .expect_err(extra)
            .to_string();
        assert!(err.contains(expect), "{extra}: {err}");
        assert!(err.contains("t.toml:"), "{err}");
    }
}

/// The command line: every monitor is a named CSV column, `plot --monitor` picks one from a
/// CSV or an MCAP recording, and a rerun file is written with a curve per monitor.
#[test]
fn every_monitor_is_a_csv_column_and_plot_picks_one() {
    use std::process::Command;
    let d = std::env::temp_dir().join(format!("contrail-monitors-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    let p = |n: &str| d.join(n).to_str().unwrap().to_string();
    let text = with_monitors(
        "hertz",
        None,
        "[[monitor]]\nlabel = \"punch\"\nrigid = \"cylinder\"\ncomponent = \"y\"\nsign = -1.0\n\n\
         [[monitor]]\nlabel = \"base, y\"\nbody = \"block\"\nnodes = \"bottom\"\ncomponent = \"y\"\n",
    );
    let scene = p("two.toml");
    std::fs::write(&scene, text).unwrap();
    let contrail = |args: &[&str]| {
        Command::new(env!("CARGO_BIN_EXE_contrail"))
            .args(args)
            .output()
            .unwrap()
    };
    let o = contrail(&[
        "run",
        &scene,
        "--quiet",
        "--set",
        "body.block.mesh.elements=[10, 8]",
        "--out",
        &p("r.csv"),
        "--out",
        &p("r.mcap"),
        "--rerun-save",
        &p("r.rrd"),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let csv = std::fs::read_to_string(p("r.csv")).unwrap();
    let header: Vec<&str> = csv.lines().next().unwrap().split(',').collect();
    assert!(header.ends_with(&[
        "punch.displacement",
        "punch.force",
        "\"base",
        " y.displacement\"",
        "\"base",
        " y.force\""
    ]));
    // the first monitor's columns equal the plain displacement/force columns
    let last: Vec<f64> = csv
        .lines()
        .last()
        .unwrap()
        .split(',')
        .map(|v| v.parse().unwrap())
        .collect();
    assert_eq!(last[2], last[10]);
    assert_eq!(last[3], last[11]);
    assert!(
        (last[3] - last[13]).abs() <= 1e-6 * last[13].abs() && last[3] > 0.0,
        "punch pressed down with sign = −1 = base reaction, both positive: {last:?}"
    );
    assert!(std::fs::metadata(p("r.rrd")).unwrap().len() > 1000);
    for (input, monitor) in [("r.csv", "punch"), ("r.mcap", "punch"), ("r.mcap", "base, y")] {
        let o = contrail(&["plot", &p(input), "--monitor", monitor, "--out", &p("f.svg")]);
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    }
    let o = contrail(&["plot", &p("r.mcap"), "--monitor", "nope", "--out", &p("f.svg")]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(2), "{err}");
    // (the labels, sorted: "base, y" and "punch")
    assert!(
        err.contains("no monitor `nope`") && err.contains("are base, y, punch"),
        "{err}"
    );
    let _ = std::fs::remove_dir_all(&d);
}
