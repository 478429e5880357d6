//! What `contrail` tells a user: "did you mean" for scene names and subcommands, scenes as
//! templates, several `--out` files, the summary of a completed and of a failed run (plain
//! numbers, plurals, compact residuals, the command to inspect the recording) and iteration
//! counts that agree with `contrail inspect`; the plane or axisymmetric model `contrail check`
//! advises for a 3D scene.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn contrail(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_contrail"))
        .args(args)
        .output()
        .expect("run contrail")
}

fn dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("contrail-cli-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn text(o: &Output) -> (String, String) {
    (
        String::from_utf8_lossy(&o.stdout).into_owned(),
        String::from_utf8_lossy(&o.stderr).into_owned(),
    )
}

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// No float noise such as `1.100000e1` or `0.6413636363636566` in what people read.
fn assert_plain_numbers(out: &str) {
    for word in out.split(|c: char| c.is_whitespace() || c == ',' || c == '(' || c == ')') {
        // significant digits: leading zeros do not count
        let mantissa = word.split(['e', 'E']).next().unwrap_or(word);
        let digits = mantissa
            .trim_start_matches('-')
            .trim_start_matches(['0', '.'])
            .chars()
            .filter(char::is_ascii_digit)
            .count();
        if word.parse::<f64>().is_ok() && word.contains('.') {
            assert!(digits <= 8, "long number `{word}` in:\n{out}");
            assert!(!word.contains("00000e"), "padded exponent `{word}` in:\n{out}");
        }
    }
}

#[test]
fn a_mistyped_scene_name_gets_a_suggestion() {
    let o = contrail(&["run", "strip-chanel"]);
    let (_, err) = text(&o);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(err.contains("did you mean `strip-channel`?"), "{err}");
    assert!(!err.contains("No such file"), "{err}");
    let o = contrail(&["run", "scenes/herz.toml"]);
    let (_, err) = text(&o);
    assert_eq!(o.status.code(), Some(2), "{err}");
    assert!(err.contains("no such scene file") && err.contains("`hertz`"), "{err}");
}

#[test]
fn a_mistyped_subcommand_gets_a_suggestion() {
    for (typed, meant) in [("rn", "run"), ("inspct", "inspect"), ("senes", "scenes")] {
        let o = contrail(&[typed]);
        let (_, err) = text(&o);
        assert_eq!(o.status.code(), Some(2), "{err}");
        assert!(err.contains(&format!("'{meant}'")), "{typed}: {err}");
    }
}

#[test]
fn check_advises_the_plane_or_axisymmetric_model_of_a_3d_scene() {
    let data = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/slice-3d.toml");
    let o = contrail(&["check", s(&data)]);
    assert!(o.status.success(), "{}", text(&o).1);
    let out = text(&o).0;
    assert!(
        out.contains("a plane-strain model of the section would do, with about 90 DOFs instead of 405"),
        "{out}"
    );
    // the same block with one end free along z is told nothing
    let o = contrail(&["check", s(&data), "--set", "fix=[]"]);
    assert!(o.status.success() && !text(&o).0.contains("advice"), "{}", text(&o).0);
    let o = contrail(&["check", "hertz-3d"]);
    assert!(o.status.success() && !text(&o).0.contains("advice"));
    // a rigid cylinder along the extrusion: the plane-strain model; the block with free ends
    // along it, or the cylinder turned off the axis, is told nothing
    let cyl = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/cylinder-slice-3d.toml");
    let out = text(&contrail(&["check", s(&cyl)])).0;
    assert!(
        out.contains("a plane-strain model of the section would do, with about 2542 DOFs instead of 7626"),
        "{out}"
    );
    // (a block 2 long held on its mid-plane is half of a thick block: no plate)
    for sets in [
        &[
            "--set",
            "fix.2.nodes=ymin",
            "--set",
            "body.block.mesh.size=[2.0, 1.0, 2.0]",
        ][..],
        &["--set", "rigid.0.cylinder.axis=[0.1, 1.0, 0.0]"][..],
    ] {
        let out = text(&contrail(&[&["check", s(&cyl)][..], sets].concat())).0;
        assert!(out.contains(": ok —") && !out.contains("advice"), "{sets:?}: {out}");
    }
    // the plate over an edge written in 3D (half the plate, its mid-plane held; the block a
    // held body): plane stress
    let plate = [
        "check",
        "strip-channel-3d",
        "--set",
        "body.strip.mesh.size=[12.0, 0.05, 0.5]",
        "--set",
        "body.block.mesh.size=[13.5, 0.05, 40.0]",
        "--set",
        "fix.1.nodes=ymin",
    ];
    let out = text(&contrail(&plate)).0;
    assert!(out.contains("a plane-stress model of the section would do"), "{out}");
    // the chart's plate scene built in 3D: its own plane-stress model
    let edge = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/plate-edge.toml");
    let out = text(&contrail(&["check", s(&edge), "--set", "extrusion.build=true"])).0;
    assert!(
        out.contains("a plane-stress model of the section would do, with about 108 DOFs instead of 324"),
        "{out}"
    );
    // the axisymmetric Hertz scene built in 3D: the axisymmetric model would do
    let out = text(&contrail(&["check", "hertz-axisym", "--set", "revolution.build=true"])).0;
    assert!(out.contains("the quarter of a body of revolution about z"), "{out}");
    // the quarter of a disc between plates: an axisymmetric model would do
    let disc = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/disc-3d.toml");
    let out = text(&contrail(&["check", s(&disc)])).0;
    assert!(
        out.contains(
            "an axisymmetric model of its section (the half-plane y = 0, x ≥ 0) would do, with about 306 DOFs instead of 5859"
        ),
        "{out}"
    );
}

#[test]
fn a_builtin_scene_prints_as_a_template() {
    let o = contrail(&["scenes", "--show", "hertz"]);
    assert!(o.status.success());
    assert_eq!(text(&o).0, include_str!("../scenes/hertz.toml"));
    let o = contrail(&["scenes", "--show", "herz"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(text(&o).1.contains("did you mean `hertz`?"));
    let o = contrail(&["scenes"]);
    assert!(text(&o).0.contains("--show NAME"));
}

#[test]
fn a_completed_run_writes_every_out_file_and_sums_up_plainly() {
    let d = dir("completed");
    let (mcap, csv) = (d.join("slide.mcap"), d.join("slide.csv"));
    let o = contrail(&["run", "block-slide", "--quiet", "--out", s(&mcap), "--out", s(&csv)]);
    let (out, err) = text(&o);
    assert!(o.status.success(), "{out}{err}");
    assert!(mcap.exists() && csv.exists());
    assert_eq!(out.matches("written").count(), 2, "{out}");
    assert!(out.contains("ended        completed"), "{out}");
    assert!(out.contains("reached      t = 3 of 3 in 60 increments"), "{out}");
    assert!(
        out.contains(&format!("inspect      contrail inspect {}", s(&mcap))),
        "{out}"
    );
    assert!(out.contains("last point   drag = "), "{out}");
    assert_plain_numbers(&out);
    let o = contrail(&["run", "block-slide", "--quiet", "--out", s(&csv), "--out", s(&csv)]);
    assert_eq!(o.status.code(), Some(2));
    assert!(text(&o).1.contains("given twice"));
}

#[test]
fn a_failed_run_says_how_far_it_got_where_it_stopped_and_how_to_look() {
    let d = dir("failed");
    let mcap = d.join("fail.mcap");
    let o = contrail(&[
        "run",
        "crossing",
        "--quiet",
        "--set",
        "solver.max_iterations=1",
        "--set",
        "stepping.max_cutbacks=1",
        "--out",
        s(&mcap),
    ]);
    let (out, err) = text(&o);
    assert_eq!(o.status.code(), Some(1), "{out}{err}");
    for words in [
        "ended        FAILED",
        "stopped      increment ",
        "residuals    ",
        "reached      t = ",
        "crossings    ",
        &format!("inspect      contrail inspect {}", s(&mcap)),
    ] {
        assert!(out.contains(words), "`{words}` missing in:\n{out}");
    }
    let residuals = out.lines().find(|l| l.starts_with("residuals")).unwrap();
    assert!(residuals.split(", ").count() <= 9, "{residuals}");
    assert!(err.contains("failed at t = "), "{err}");
    assert_plain_numbers(&out);
    assert_plain_numbers(&err);
}

fn iterations_in_all(out: &str) -> usize {
    let line = out
        .lines()
        .find(|l| l.contains(" in all"))
        .unwrap_or_else(|| panic!("no iteration count in:\n{out}"));
    let words: Vec<&str> = line.split_whitespace().collect();
    let k = words.iter().position(|w| w.starts_with("iteration")).unwrap();
    words[k - 1].parse().unwrap()
}

#[test]
fn run_and_inspect_count_newton_iterations_alike() {
    let d = dir("count");
    let mcap = d.join("count.mcap");
    // two iterations are too few for some increments: cut-backs and failed attempts
    let o = contrail(&[
        "run",
        "crossing",
        "--quiet",
        "--set",
        "solver.max_iterations=2",
        "--out",
        s(&mcap),
    ]);
    let (out, err) = text(&o);
    assert!(matches!(o.status.code(), Some(0 | 1)), "{out}{err}");
    let i = contrail(&["inspect", s(&mcap)]);
    let (ins, err) = text(&i);
    assert!(i.status.success(), "{err}");
    assert_eq!(
        iterations_in_all(&out),
        iterations_in_all(&ins),
        "run:\n{out}\ninspect:\n{ins}"
    );
    assert!(ins.contains("in converged increments"), "{ins}");
    assert!(
        !ins.contains("1 slaves") && ins.contains("point: 1 slave against the master body block"),
        "{ins}"
    );
}
