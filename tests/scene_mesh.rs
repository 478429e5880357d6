//! Scene meshing and constraint keys: rectangle grading (`bias = "end" | "both" | "centre"`,
//! `focus`), `rotate`, annulus grading, named `[[fix]]`/`[[load]]` entries in `--set`, and
//! the refusals of bad values.
//!
//! References and tolerances, per test: element size ratios equal `grading` to 1e-12
//! (geometric series by construction); a turned mesh's nodes are `p + Q(θ)(x − p)` of the
//! unturned ones to 1e-12; a homogeneous stretch of a graded mesh (the patch test: Q4 with
//! enhanced strains reproduces any homogeneous deformation on any mesh) gives
//! `u_x = ε x` at every node to 1e-9 of the stretch; named overrides give the same model as
//! index overrides, bit for bit.

mod common;

const BLOCK: &str = r#"
name = "graded"
[[body]]
name = "block"
material = { model = "saint-venant-kirchhoff", young = 1.0e3, poisson = 0.3 }
mesh = { kind = "rectangle", origin = [1.0, 2.0], size = [2.0, 1.0], elements = [8, 6], grading = [4.0, 3.0], bias = ["centre", "both"] }

[[fix]]
name = "hold-x"
body = "block"
nodes = "left"
components = ["x"]

[[fix]]
name = "hold-y"
body = "block"
nodes = "bottom-left"
components = ["y"]

[[fix]]
name = "stretch"
body = "block"
nodes = "right"
components = ["x"]
value = 0.0

[[load]]
name = "pull"
body = "block"
nodes = "right"
component = "x"
total = 0.0

[stepping]
end = 1.0
increments = 1
"#;

/// Distinct sorted coordinates of the nodes along axis `k`.
fn lines(nodes: &[[f64; 2]], k: usize) -> Vec<f64> {
    let mut v: Vec<f64> = nodes.iter().map(|x| x[k]).collect();
    v.sort_by(f64::total_cmp);
    v.dedup_by(|a, b| (*a - *b).abs() < 1e-12);
    v
}

fn steps(c: &[f64]) -> Vec<f64> {
    c.windows(2).map(|w| w[1] - w[0]).collect()
}

#[test]
fn a_rectangle_graded_towards_its_centre_and_towards_both_ends() {
    let p = common::scene_text(BLOCK);
    let xs = steps(&lines(&p.model.nodes, 0));
    let ys = steps(&lines(&p.model.nodes, 1));
    assert_eq!((xs.len(), ys.len()), (8, 6));
    // x: "centre", grading 4 = end / centre element, symmetric
    assert!((xs[0] / xs[3] - 4.0).abs() < 1e-12, "{xs:?}");
    assert!((xs[0] - xs[7]).abs() < 1e-12 && (xs[3] - xs[4]).abs() < 1e-12);
    assert!(
        xs.windows(2).take(4).all(|w| w[1] < w[0]),
        "refined towards the middle: {xs:?}"
    );
    // y: "both", grading 3 = middle / end element
    assert!(
        (ys[2] / ys[0] - 3.0).abs() < 1e-12 && (ys[5] - ys[0]).abs() < 1e-12,
        "{ys:?}"
    );
    assert!((xs.iter().sum::<f64>() - 2.0).abs() < 1e-12 && (ys.iter().sum::<f64>() - 1.0).abs() < 1e-12);
}

#[test]
fn a_focus_puts_a_node_line_at_an_interior_point_and_refines_towards_it() {
    let set = [
        "body.block.mesh.bias=[\"centre\", \"end\"]",
        "body.block.mesh.focus=[1.5, 2.5]",
        "body.block.mesh.grading=[5.0, 1.0]",
    ];
    let p = common::scene_file("test.toml", BLOCK, &set);
    let x = lines(&p.model.nodes, 0);
    let at = x
        .iter()
        .position(|v| (v - 1.5).abs() < 1e-12)
        .expect("a node line at x = 1.5");
    // 8 elements split by length 0.5 : 1.5 → 2 : 6; the elements next to the focus smallest
    assert_eq!(at, 2);
    let h = steps(&x);
    assert!(
        (h[0] / h[1] - 5.0).abs() < 1e-12 && (h[7] / h[2] - 5.0).abs() < 1e-12,
        "{h:?}"
    );
}

#[test]
fn a_graded_rectangle_passes_the_patch_test() {
    // the right face pulled by 0.02 (named fix), free laterally: a homogeneous stretch
    let p = common::scene_file("test.toml", BLOCK, &["fix.stretch.value=0.02"]);
    let (_, mem) = common::solve_ok(&p);
    let u = &mem.final_u;
    let eps = 0.02 / 2.0;
    let lateral = u[2 * p.model.bodies[0].node_sets["top-left"][0] + 1] / 1.0;
    assert!(lateral < 0.0, "Poisson contraction: {lateral}");
    for (n, x) in p.model.nodes.iter().enumerate() {
        assert!(
            (u[2 * n] - eps * (x[0] - 1.0)).abs() <= 1e-9 * eps,
            "node {n}: u_x {}",
            u[2 * n]
        );
        assert!(
            (u[2 * n + 1] - lateral * (x[1] - 2.0)).abs() <= 1e-9 * eps,
            "node {n}: u_y {}",
            u[2 * n + 1]
        );
    }
}

#[test]
fn a_rotated_rectangle_is_the_rectangle_turned_about_its_point() {
    let plain = common::scene_text(BLOCK);
    let set = ["body.block.mesh.rotate={ angle_deg = 30.0, about = [2.0, 2.5] }"];
    let turned = common::scene_file("test.toml", BLOCK, &set);
    let (s, c) = 30f64.to_radians().sin_cos();
    for (a, b) in plain.model.nodes.iter().zip(&turned.model.nodes) {
        let (dx, dy) = (a[0] - 2.0, a[1] - 2.5);
        let expect = [2.0 + c * dx - s * dy, 2.5 + s * dx + c * dy];
        assert!((b[0] - expect[0]).abs() < 1e-12 && (b[1] - expect[1]).abs() < 1e-12);
    }
    // the same quads, still counter-clockwise, the same sets and faces
    assert_eq!(plain.model.bodies[0].faces, turned.model.bodies[0].faces);
    for e in &turned.model.elements {
        let p = e.nodes.map(|n| turned.model.nodes[n]);
        let area: f64 = (0..4)
            .map(|i| p[i][0] * p[(i + 1) % 4][1] - p[(i + 1) % 4][0] * p[i][1])
            .sum();
        assert!(area > 0.0);
    }
    // default point: the origin (bottom-left corner) stays
    let about_origin = common::scene_file("test.toml", BLOCK, &["body.block.mesh.rotate={ angle_deg = 30.0 }"]);
    assert_eq!(about_origin.model.nodes[0], [1.0, 2.0]);
}

const RING: &str = r#"
name = "ring"
[[body]]
name = "belt"
material = { model = "neo-hookean", young = 1.0e3, poisson = 0.3 }
mesh = { kind = "annulus", centre = [0.0, 0.0], radius = [1.0, 1.1], angle_deg = [0.0, 90.0], elements = [10, 4], grading = [2.0, 0.5], bias = ["centre", "end"] }
[stepping]
end = 1.0
increments = 1
"#;

#[test]
fn an_annulus_graded_around_and_through() {
    let p = common::scene_text(RING);
    let m = &p.model;
    let inner = &m.bodies[0].node_sets["inner"];
    let angle: Vec<f64> = inner.iter().map(|&n| m.nodes[n][1].atan2(m.nodes[n][0])).collect();
    let da = steps(&angle);
    assert!(
        (da[0] / da[4] - 2.0).abs() < 1e-9 && (da[0] - da[9]).abs() < 1e-12,
        "{da:?}"
    );
    let start = &m.bodies[0].node_sets["start"];
    let r: Vec<f64> = start.iter().map(|&n| m.nodes[n][0].hypot(m.nodes[n][1])).collect();
    let dr = steps(&r);
    assert!((dr[3] / dr[0] - 0.5).abs() < 1e-9, "{dr:?}");
    // the uniform annulus is what it always was
    let uniform = common::scene_file("test.toml", RING, &["body.belt.mesh.grading=[1.0, 1.0]"]);
    let old = contrail::model::mesh::annulus([0.0, 0.0], [1.0, 1.1], [0.0, 90.0], [10, 4]);
    assert_eq!(uniform.model.nodes, old.nodes);
}

#[test]
fn named_fixes_and_loads_are_addressed_by_name_whatever_their_order() {
    let by_name = common::scene_file("test.toml", BLOCK, &["fix.stretch.value=0.03", "load.pull.total=2.0"]);
    let by_index = common::scene_file("test.toml", BLOCK, &["fix.2.value=0.03", "load.0.total=2.0"]);
    // the same file with the fixes listed the other way round
    let i = BLOCK.find("[[fix]]\nname = \"stretch\"").unwrap();
    let j = BLOCK.find("[[load]]").unwrap();
    let reordered = format!(
        "{}{}{}",
        &BLOCK[..BLOCK.find("[[fix]]").unwrap()],
        &BLOCK[i..j],
        &BLOCK[BLOCK.find("[[fix]]").unwrap()..i]
    ) + &BLOCK[j..];
    let moved = common::scene_file("test.toml", &reordered, &["fix.stretch.value=0.03"]);
    let value = |p: &contrail::problem::Problem| {
        let mut v: Vec<(usize, f64)> = p.model.prescribed.iter().map(|q| (q.dof, q.ramp.at(1.0))).collect();
        v.sort_by_key(|x| x.0);
        v
    };
    assert_eq!(value(&by_name), value(&by_index));
    assert_eq!(value(&by_name), value(&moved));
    assert!(value(&by_name).iter().any(|x| x.1 == 0.03));
    let load: f64 = by_name.model.loads.iter().map(|l| l.ramp.at(1.0)).sum();
    assert!((load - 2.0).abs() < 1e-12);
}

/// The message of a scene that does not load, with overrides.
fn refused(text: &str, sets: &[&str]) -> String {
    let src = contrail::scene::SceneSource {
        origin: "test.toml".into(),
        text: text.into(),
    };
    let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
    match contrail::scene::parse(&src, &sets).and_then(|f| contrail::scene::build(&src, &f)) {
        Ok(_) => panic!("the scene loaded"),
        Err(e) => e.to_string(),
    }
}

#[test]
fn bad_names_and_keys_are_refused_with_the_key_and_the_fix() {
    let dup = BLOCK.replace("name = \"hold-y\"", "name = \"hold-x\"");
    let e = common::scene_text_err(&dup);
    assert!(
        e.contains("fix.1.name") && e.contains("[[fix]] 0 has the same name"),
        "{e}"
    );
    let e = refused(BLOCK, &["fix.nope.value=1.0"]);
    assert!(
        e.contains("no [[fix]] is named `nope`") && e.contains("hold-x, hold-y, stretch"),
        "{e}"
    );
    let e = refused(BLOCK, &["body.block.mesh.bias=[\"middle\", \"end\"]"]);
    assert!(e.contains("middle") && e.contains("centre"), "{e}");
    let e = refused(BLOCK, &["body.block.mesh.focus=[3.5, 2.5]"]);
    assert!(
        e.contains("body.block.mesh.focus[0]") && e.contains("strictly inside"),
        "{e}"
    );
    let e = refused(
        BLOCK,
        &[
            "body.block.mesh.bias=[\"end\", \"end\"]",
            "body.block.mesh.focus=[1.5, 2.5]",
        ],
    );
    assert!(
        e.contains("body.block.mesh.focus") && e.contains("bias = \"centre\""),
        "{e}"
    );
    let e = refused(BLOCK, &["fix.stretch.direction=[1.0, 0.0]"]);
    assert!(
        e.contains("fix.stretch.direction") && e.contains("remove `components`"),
        "{e}"
    );
    let e = refused(
        BLOCK,
        &["fix.stretch.components=[]", "fix.stretch.direction=[0.0, 0.0]"],
    );
    assert!(e.contains("fix.stretch.direction") && e.contains("no length"), "{e}");
    let e = refused(
        BLOCK,
        &[
            "fix.stretch.components=[]",
            "fix.stretch.nodes=\"all\"",
            "fix.stretch.direction=[1.0, 1.0]",
        ],
    );
    assert!(
        e.contains("fix `stretch`") && e.contains("already has a prescribed component"),
        "{e}"
    );
}
