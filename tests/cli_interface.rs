//! A two-pass pair as one interface on the command line: `contrail plot --pressure` draws
//! one curve for both passes (two with `--passes`), `contrail inspect` has an `interface`
//! row and names the second pass as such. Scene `contact-patch` (two-pass, 5/4 elements,
//! frictionless): reference, the press's reaction 1.0972 (E ε/(1 − ν²) = 1.0989 over the
//! unit width, 0.15 % less at finite strain); the row's normal force is asserted to 4 digits.

use std::process::{Command, Output};

fn contrail(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_contrail"))
        .args(args)
        .output()
        .expect("run contrail")
}

#[test]
fn plot_and_inspect_show_a_two_pass_pair_as_one_interface() {
    let d = std::env::temp_dir().join(format!("contrail-cli-interface-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    let p = |n: &str| d.join(n).to_str().unwrap().to_string();
    let o = contrail(&["run", "contact-patch", "--quiet", "--out", &p("patch.mcap")]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let lines = |extra: &[&str], out: &str| {
        let (rec, path) = (p("patch.mcap"), p(out));
        let mut args = vec!["plot", rec.as_str(), "--pressure", "last", "--out", path.as_str()];
        args.extend_from_slice(extra);
        let o = contrail(&args);
        assert!(o.status.success(), "{extra:?}: {}", String::from_utf8_lossy(&o.stderr));
        // series are drawn in colour (and their legend keys beside them), axes and grid in black
        let svg = std::fs::read_to_string(p(out)).unwrap();
        let mut colours: Vec<&str> = (svg.split("<polyline").skip(1))
            .filter_map(|l| l.split("stroke=\"").nth(1)?.split('"').next())
            .filter(|c| *c != "#000000")
            .collect();
        colours.sort_unstable();
        colours.dedup();
        colours.len()
    };
    let (joined, passes) = (lines(&[], "joined.svg"), lines(&["--passes"], "passes.svg"));
    let (named, second) = (
        lines(&["--pair", "interface"], "named.svg"),
        lines(&["--pair", "interface/second-pass"], "second.svg"),
    );
    println!("curves: interface {joined}, --passes {passes}, --pair interface {named}, --pair interface/second-pass {second}");
    assert_eq!(
        (joined, passes),
        (1, 2),
        "one curve for the interface, two with --passes"
    );
    assert_eq!(named, joined, "--pair NAME draws the interface");
    assert_eq!(second, joined, "--pair NAME/second-pass draws that pass");

    let o = contrail(&["inspect", &p("patch.mcap")]);
    let text = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let row = text
        .lines()
        .find(|l| l.starts_with("interface "))
        .expect("an interface row");
    println!("{row}");
    assert!(row.contains("interface at increment 1: normal force 1.097"), "{row}");
    assert!(row.contains("6 of 6 nodes closed"), "{row}");
    assert!(text.contains("the second pass of `interface`"), "{text}");
    assert!(text.contains("/interface"), "the channel is counted: {text}");
    let _ = std::fs::remove_dir_all(&d);
}
