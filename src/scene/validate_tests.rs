//! Regression tests of the scene rules (issue 10: every case a hostile user found).

use crate::scene::{build_model, parse, SceneSource};

/// Build a built-in scene with overrides; the error text, or "ok".
fn outcome(scene: &str, sets: &[&str]) -> String {
    let src = SceneSource::resolve(scene).unwrap();
    let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
    match parse(&src, &sets) {
        Ok(s) => crate::scene::build_any(&src, &s).map_or_else(|e| e.to_string(), |_| "ok".into()),
        Err(e) => e.to_string(),
    }
}

fn refused(scene: &str, set: &str, expect: &[&str]) {
    let e = outcome(scene, &[set]);
    assert!(e != "ok", "{set}: accepted");
    for x in expect {
        assert!(e.contains(x), "{set}: expected `{x}` in:\n{e}");
    }
    assert!(e.contains("hint:"), "{set}: no hint in:\n{e}");
}

fn build_text(text: &str) -> String {
    let src = SceneSource {
        origin: "t.toml".into(),
        text: text.into(),
    };
    match parse(&src, &[]) {
        Ok(s) => build_model(&src, &s).map_or_else(|e| e.to_string(), |_| "ok".into()),
        Err(e) => e.to_string(),
    }
}

#[test]
fn builtins_pass() {
    for b in crate::scene::builtin::BUILTINS {
        assert_eq!(outcome(b.name, &[]), "ok", "{}", b.name);
    }
}

#[test]
fn huge_meshes_are_refused_before_allocation() {
    // capacity overflow (panic) in the issue
    refused(
        "crossing",
        "body.block.mesh.elements=[9223372036854775807, 1]",
        &["DOFs", "limits.max_dofs"],
    );
    // allocated until killed
    refused("crossing", "body.block.mesh.elements=[65536, 65536]", &["DOFs"]);
    refused("crossing", "body.block.mesh.elements=[10000, 10000]", &["DOFs"]);
    // ended in `sparse LU failed: OutOfMemory` after 29 s
    refused(
        "crossing",
        "body.block.mesh.elements=[1000, 1000]",
        &["body.block.mesh.elements", "[1000, 1000]"],
    );
    // not even a TOML integer: refused by the override
    refused(
        "crossing",
        "body.block.mesh.elements=[18446744073709551615, 1]",
        &["--set"],
    );
    // the memory estimate has its own limit
    let e = outcome(
        "crossing",
        &["body.block.mesh.elements=[400, 400]", "limits.max_memory_gib=0.1"],
    );
    assert!(e.contains("GiB") && e.contains("limits.max_memory_gib"), "{e}");
}

#[test]
fn the_size_limit_can_be_raised() {
    let src = SceneSource::resolve("crossing").unwrap();
    let sets = [
        "body.block.mesh.elements=[1000, 1000]".to_string(),
        "limits.max_dofs=3000000".into(),
    ];
    let s = parse(&src, &sets).unwrap();
    super::validate(&src, &s).unwrap();
}

#[test]
fn non_finite_numbers_are_refused() {
    let cases: &[(&str, &str)] = &[
        ("body.block.material.young=nan", "body.block.material.young"),
        ("body.block.material.young=inf", "body.block.material.young"),
        ("body.block.material.poisson=nan", "body.block.material.poisson"),
        ("body.block.mesh.size=[nan, 0.5]", "body.block.mesh.size[0]"),
        ("body.block.mesh.origin=[inf, 0.5]", "body.block.mesh.origin[0]"),
        ("body.block.mesh.grading=[1.0, nan]", "body.block.mesh.grading[1]"),
        ("contact.point.eps_n=nan", "contact.point.eps_n"),
        ("contact.point.eps_t=nan", "contact.point.eps_t"),
        ("contact.point.mu=inf", "contact.point.mu"),
        ("contact.point.search_radius=inf", "contact.point.search_radius"),
        ("fix.0.value=nan", "fix.0.value"),
        ("rigid.P.point=[nan, 0.0]", "rigid.P.point[0]"),
        ("rigid.P.move.x=[[0.0, 0.0], [1.0, inf]]", "rigid.P.move.x[1].value"),
        ("rigid.P.move.x=[[0.0, 0.0], [nan, 1.0]]", "rigid.P.move.x[1].t"),
        ("stepping.end=nan", "stepping.end"),
        ("stepping.end=inf", "stepping.end"),
        ("stepping.growth=nan", "stepping.growth"),
        ("solver.residual_tol=nan", "solver.residual_tol"),
        ("solver.divergence_factor=inf", "solver.divergence_factor"),
    ];
    for (set, key) in cases {
        refused("crossing", set, &[key, "finite"]);
    }
}

#[test]
fn out_of_range_numbers_are_refused() {
    refused("crossing", "body.block.material.young=-1.0", &["> 0"]);
    refused("crossing", "body.block.material.poisson=0.5", &["0.5"]);
    refused("crossing", "body.block.mesh.grading=[0.0, 1.0]", &["grading[0]", "> 0"]);
    refused("crossing", "contact.point.mu=-0.1", &["≥ 0"]);
    refused("crossing", "contact.point.eps_t=0.0", &["eps_t", "mu"]);
    refused("crossing", "stepping.increments=0", &["≥ 1"]);
    refused("crossing", "stepping.increments=100000000", &["limits.max_increments"]);
    refused("crossing", "solver.max_iterations=0", &["max_iterations"]);
    refused("crossing", "rigid.P.move.x=[[1.0, 0.0], [0.0, 1.0]]", &["sort"]);
}

#[test]
fn geometry_out_of_reach_of_the_contact_grid_is_refused() {
    // both hung in SegmentGrid::new in the issue
    refused(
        "hertz",
        "rigid.cylinder.arc.radius=inf",
        &["rigid.cylinder.arc.radius", "finite"],
    );
    refused(
        "block-slide",
        "rigid.plane.polyline=[[-9.2e18, 0.0], [-2.0, 0.0]]",
        &["search radii"],
    );
    refused("hertz", "rigid.cylinder.arc.radius=0.0", &["> 0"]);
}

#[test]
fn names_must_be_unique_and_polylines_distinct() {
    let base = "name = \"x\"\n[[rigid]]\nname = \"A\"\npoint = [0.0, 0.0]\n";
    let e = build_text(&format!("{base}[[rigid]]\nname = \"A\"\npoint = [1.0, 0.0]\n"));
    assert!(e.starts_with("t.toml:6:8: `rigid.1.name` = \"A\""), "{e}");
    let e = build_text(&format!(
        "{base}[[contact]]\nname = \"c\"\nslave = {{ rigid = \"A\" }}\nmaster = {{ rigid = \"A\" }}\neps_n = 1.0\n[[contact]]\nname = \"c\"\nslave = {{ rigid = \"A\" }}\nmaster = {{ rigid = \"A\" }}\neps_n = 1.0\n"
    ));
    assert!(e.contains("`contact.1.name` = \"c\""), "{e}");
    let e = build_text("name = \"x\"\n[[rigid]]\nname = \"L\"\npolyline = [[0.0, 0.0], [1.0, 0.0], [1.0, 0.0]]\n");
    assert!(
        e.starts_with("t.toml:4:") && e.contains("rigid.L.polyline[2]") && e.contains("repeats"),
        "{e}"
    );
    let e = build_text("name = \"x\"\n[[rigid]]\nname = \"L\"\npolyline = [[0.0, 0.0]]\n");
    assert!(e.contains("at least 2 points"), "{e}");
}

#[test]
fn arcs_state_their_side() {
    // hertz: counter-clockwise, the cylinder (a disc) inside the circle
    assert_eq!(outcome("hertz", &["rigid.cylinder.arc.side=inside"]), "ok");
    refused(
        "hertz",
        "rigid.cylinder.arc.side=outside",
        &["counter-clockwise", "swap from_deg and to_deg"],
    );
    // reversed arc: ran silently with the rigid body on the wrong side
    let e = outcome(
        "hertz",
        &[
            "rigid.cylinder.arc.from_deg=-30.0",
            "rigid.cylinder.arc.to_deg=-150.0",
            "rigid.cylinder.arc.side=inside",
        ],
    );
    assert!(e.contains("clockwise") && e.contains("outside"), "{e}");
    refused("hertz", "rigid.cylinder.arc.to_deg=400.0", &["full turn"]);
}

#[test]
fn errors_point_at_the_value() {
    let text = "name = \"x\"\n\n[[body]]\nname = \"b\"\nmaterial = { model = \"neo-hookean\", young = nan, poisson = 0.3 }\nmesh = { kind = \"rectangle\", origin = [0.0, 0.0], size = [1.0, 1.0], elements = [1, 1] }\n";
    let e = build_text(text);
    assert!(e.starts_with("t.toml:5:"), "{e}");
    assert!(
        e.contains("`body.b.material.young` = NaN: must be a finite number"),
        "{e}"
    );
    let text = "name = \"x\"\n[stepping]\nend = nan\n";
    let e = build_text(text);
    assert!(e.starts_with("t.toml:3:7: `stepping.end` = NaN"), "{e}");
}

#[test]
fn a_mesh_reaching_beyond_the_coordinate_bound_is_refused() {
    // found by the long scene fuzz (CONTRAIL_FUZZ_CASES=20000): each number finite, the
    // graded mesh's nodes overflowed to [inf, −9.2e18]
    refused(
        "cantilever",
        "body.strip.mesh.size=[1e308, 0.5]",
        &["body.strip.mesh", "1e12"],
    );
    refused(
        "cantilever",
        "body.strip.mesh.origin=[-1e13, 0.0]",
        &["body.strip.mesh"],
    );
    assert_eq!(outcome("cantilever", &["body.strip.mesh.size=[1e6, 0.5]"]), "ok");
}

#[test]
fn a_hollow_hemisphere_a_turn_and_a_friction_history_are_checked() {
    let h = "twisting-hemisphere";
    refused(h, "body.hemisphere.mesh.elements=[7, 2]", &["n even", "elements"]);
    refused(h, "body.hemisphere.mesh.elements=[8, 0]", &["layers ≥ 1"]);
    refused(h, "body.hemisphere.mesh.radius=[1.0, 0.5]", &["0 < inner < outer"]);
    refused(
        h,
        "fix.twist.turn.axis=[0.0, 0.0, 0.0]",
        &["no length", "fix.twist.turn.axis"],
    );
    refused(h, "fix.twist.turn.point=[0.0, nan, 1.0]", &["fix.twist.turn.point[1]"]);
    refused(h, "contact.interface.mu=0.3", &["mu_path", "constant or a history"]);
    refused(
        h,
        "contact.interface.mu_path=[[0.0, 0.0], [1.0, -0.1]]",
        &["mu_path[1]"],
    );
    refused(
        h,
        "contact.interface.mu_path=[[1.0, 0.0], [0.0, 0.5]]",
        &["must not decrease"],
    );
    refused(h, "contact.interface.eps_t=0.0", &["eps_t"]);
    // a friction history is 3D only for now
    let e = outcome(
        "crossing",
        &["contact.point.mu=0", "contact.point.mu_path=[[0.0, 0.1]]"],
    );
    assert!(e.contains("3D pairs only") && e.contains("hint:"), "{e}");
}

#[test]
fn a_sphere_shell_is_checked_for_its_counts_and_part() {
    let c = "concentric-spheres";
    assert_eq!(outcome(c, &[]), "ok");
    // a whole sphere has no symmetry faces: the scene's fixes on them are refused by name
    let e = outcome(c, &["body.inner.mesh.part=\"whole\""]);
    assert!(
        e.contains("no node set `xmin`") && e.contains("all, inner, outer"),
        "{e}"
    );
    refused(c, "body.outer.mesh.elements=[15, 2]", &["n even", "elements"]);
    refused(c, "body.inner.mesh.radius=[0.8, 0.65]", &["0 < inner < outer"]);
    let e = outcome(c, &["body.inner.mesh.part=\"half\""]);
    assert!(e.contains("octant") && e.contains("whole"), "{e}");
}

#[test]
fn nagata_patches_are_for_3d_faces_and_the_2d_curves_for_2d() {
    let e = outcome("crossing", &["contact.point.master_smoothing=\"nagata\""]);
    assert!(e.contains("smooths a 3D face") && e.contains("hermite"), "{e}");
    refused(
        "twisting-hemisphere",
        "contact.interface.master_smoothing=\"bezier\"",
        &["a 2D curve's", "nagata"],
    );
    assert_eq!(
        outcome(
            "twisting-hemisphere",
            &["contact.interface.master_smoothing=\"nagata\""]
        ),
        "ok"
    );
}

#[test]
fn a_revolved_mesh_is_checked_for_its_counts_and_its_core() {
    let with = |extra: &[&str]| {
        let mut sets = vec!["revolution.build=true"];
        sets.extend_from_slice(extra);
        outcome("hertz-axisym", &sets)
    };
    assert_eq!(with(&[]), "ok");
    for (set, said) in [
        ("revolution.core=1.5", "0 < core < 1"),
        ("revolution.around=0", "around ≥ 1"),
        ("body.block.mesh.elements=[0, 4]", "must be ≥ 1"),
    ] {
        let e = with(&[set]);
        assert!(e.contains(said) && e.contains("hint:"), "{set}: {e}");
    }
    // a monitor of a rigid surface no pair presses on
    let text = SceneSource::resolve("hertz-axisym").unwrap().text
        + "\n[[rigid]]\nname = \"lid\"\npolyline = [[2.0, 1.0], [0.0, 1.0]]\n";
    let src = SceneSource {
        origin: "t.toml".into(),
        text,
    };
    let sets = [
        "revolution.build=true".to_string(),
        "monitor.0.rigid=\"lid\"".to_string(),
    ];
    let unpaired = parse(&src, &sets)
        .and_then(|s| crate::scene::build_any(&src, &s))
        .map(|_| ())
        .expect_err("refused")
        .to_string();
    assert!(
        unpaired.contains("no contact pair has the rigid surface `lid`"),
        "{unpaired}"
    );
}
