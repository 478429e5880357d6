//! The scene layer of 3D contact: `[[rigid]]` planes and spheres and `[[contact]]` tables of a
//! 3D scene built into `Model<Solid>::surface_contacts` (slave faces with tributary areas,
//! deformable or rigid masters, two-pass pairs with half the penalties), and every refusal
//! naming its key. Build only: no 3D contact scene is run here.
//!
//! Two boxes stacked: `base` 0..1 × 0..1 × 0..0.5 (4×4×2 elements) and `top`
//! 0..1 × 0..1 × 0.5..1 (3×3×2). Reference: the tributary areas of a face of `n × n` equal
//! squares of side `h` are `h²/4` at its corners, `h²/2` on its edges, `h²` inside, and sum
//! to the face's area (1 here) to round-off (1e-12).

use contrail::contact3d::transfer::Scheme;
use contrail::model::{Model, RigidSurfaceShape, Solid, SurfaceMaster, SECOND_PASS_SUFFIX};
use contrail::scene::{build_any, parse, AnyProblem, SceneSource};

const BODIES: &str = r#"
name = "stack"
[[body]]
name = "base"
material = { model = "neo-hookean", young = 100.0, poisson = 0.3 }
mesh = { kind = "box", origin = [0.0, 0.0, 0.0], size = [1.0, 1.0, 0.5], elements = [4, 4, 2] }
[[body]]
name = "top"
material = { model = "neo-hookean", young = 100.0, poisson = 0.3 }
mesh = { kind = "box", origin = [0.0, 0.0, 0.5], size = [1.0, 1.0, 0.5], elements = [3, 3, 2] }
[[fix]]
body = "base"
nodes = "zmin"
components = ["x", "y", "z"]
"#;

const GLUE: &str = r#"
[[contact]]
name = "glue"
slave = { body = "top", nodes = "zmin" }
master = { body = "base", face = "zmax" }
eps_n = 1000.0
eps_t = 400.0
mu = 0.3
two_pass = true
"#;

const PRESS: &str = r#"
[[contact]]
name = "press"
slave = { body = "top", nodes = "zmax" }
master = { rigid = "tool" }
eps_n = 1000.0
"#;

/// The scene's build: its 3D model, or the error text.
fn build(text: &str) -> Result<Model<Solid>, String> {
    let src = SceneSource {
        origin: "t.toml".into(),
        text: text.into(),
    };
    let file = parse(&src, &[]).map_err(|e| e.to_string())?;
    match build_any(&src, &file).map_err(|e| e.to_string())? {
        AnyProblem::Solid(p) => Ok(p.model),
        AnyProblem::Plane(_) => panic!("a 2D scene"),
    }
}

/// The error of a scene that must not build: it names every one of `expect`, the file and a
/// fix.
fn refused(text: &str, expect: &[&str]) -> String {
    let src = SceneSource {
        origin: "t.toml".into(),
        text: text.into(),
    };
    let e = match parse(&src, &[]) {
        Ok(f) => build_any(&src, &f).map_or_else(|e| e.to_string(), |_| panic!("accepted:\n{text}")),
        Err(e) => e.to_string(),
    };
    for x in expect {
        assert!(e.contains(x), "expected `{x}` in:\n{e}");
    }
    assert!(
        e.starts_with("t.toml:") && e.contains("hint:"),
        "no location or hint:\n{e}"
    );
    e
}

#[test]
fn two_boxes_glued_two_pass_have_two_pairs_with_tributary_areas_and_half_the_penalties() {
    let m = build(&format!("{BODIES}{GLUE}")).unwrap();
    assert_eq!(m.surface_contacts.len(), 2);
    let (first, second) = (&m.surface_contacts[0], &m.surface_contacts[1]);
    assert_eq!(first.name, "glue");
    assert_eq!(second.name, format!("glue{SECOND_PASS_SUFFIX}"));
    assert_eq!((first.slaves.len(), second.slaves.len()), (16, 25));
    for p in [first, second] {
        assert_eq!(p.slaves.len(), p.areas.len());
        assert!(p.slaves.windows(2).all(|w| w[0] < w[1]), "sorted, distinct");
        assert!((p.areas.iter().sum::<f64>() - 1.0).abs() < 1e-12, "{}", p.name);
        assert_eq!((p.law.eps_n, p.law.eps_t, p.law.mu), (500.0, 200.0, 0.3));
        assert_eq!(p.transfer, Scheme::Continuous);
        // twice the longest element edge (the top's 1/3)
        assert!((p.search_radius - 2.0 / 3.0).abs() < 1e-12);
    }
    let (base, top) = (&m.bodies[0], &m.bodies[1]);
    assert!(first.slaves.iter().all(|n| top.node_sets["zmin"].contains(n)));
    assert!(second.slaves.iter().all(|n| base.node_sets["zmax"].contains(n)));
    match (&first.master, &second.master) {
        (SurfaceMaster::Facets { body: 0, facets: a }, SurfaceMaster::Facets { body: 1, facets: b }) => {
            assert_eq!(a, &base.faces["zmax"]);
            assert_eq!(b, &top.faces["zmin"]);
        }
        other => panic!("{other:?}"),
    }
    // the base's 4×4 face: corners 1/64, edges 1/32, inside 1/16
    for (&n, &a) in second.slaves.iter().zip(&second.areas) {
        let x = m.nodes[n];
        let on_edge = |c: f64| c.abs() < 1e-12 || (c - 1.0).abs() < 1e-12;
        let expected = match (on_edge(x[0]), on_edge(x[1])) {
            (true, true) => 1.0 / 64.0,
            (true, false) | (false, true) => 1.0 / 32.0,
            (false, false) => 1.0 / 16.0,
        };
        assert!((a - expected).abs() < 1e-15, "node {n} at {x:?}: {a}");
    }
}

#[test]
fn one_pass_keeps_the_penalties_and_takes_the_scenes_transfer_and_radius() {
    let text = format!(
        "{BODIES}{}",
        GLUE.replace("two_pass = true", "transfer = \"path-length\"\nsearch_radius = 0.1")
    );
    let m = build(&text).unwrap();
    assert_eq!(m.surface_contacts.len(), 1);
    let p = &m.surface_contacts[0];
    assert_eq!((p.law.eps_n, p.law.eps_t), (1000.0, 400.0));
    assert_eq!((p.transfer, p.search_radius), (Scheme::PathLength, 0.1));
    // `straightforward` too
    let text = format!(
        "{BODIES}{}",
        GLUE.replace("two_pass = true", "transfer = \"straightforward\"")
    );
    assert_eq!(
        build(&text).unwrap().surface_contacts[0].transfer,
        Scheme::Straightforward
    );
}

#[test]
fn a_rigid_plane_and_a_rigid_sphere_move_as_prescribed() {
    let plane = r#"
[[rigid]]
name = "tool"
plane = { point = [0.0, 0.0, 1.0], normal = [0.0, 0.0, -2.0] }
move = { x = 0.05, z = -0.1 }
"#;
    let m = build(&format!("{BODIES}{plane}{PRESS}")).unwrap();
    let SurfaceMaster::Rigid(r) = &m.surface_contacts[0].master else {
        panic!("not rigid")
    };
    assert_eq!(r.name, "tool");
    assert_eq!(
        r.shape,
        RigidSurfaceShape::Plane {
            point: [0.0, 0.0, 1.0],
            normal: [0.0, 0.0, -1.0]
        }
    );
    assert_eq!(r.offset(0.0), [0.0; 3]);
    assert_eq!(r.offset(1.0), [0.05, 0.0, -0.1]);
    assert!((m.surface_contacts[0].areas.iter().sum::<f64>() - 1.0).abs() < 1e-12);
    let sphere = r#"
[[rigid]]
name = "tool"
sphere = { centre = [0.5, 0.5, 1.5], radius = 0.5 }
move = { z = [[0.0, 0.0], [0.5, -0.1], [1.0, -0.3]] }
"#;
    let m = build(&format!("{BODIES}{sphere}{PRESS}")).unwrap();
    let SurfaceMaster::Rigid(r) = &m.surface_contacts[0].master else {
        panic!("not rigid")
    };
    let want = RigidSurfaceShape::Sphere {
        centre: [0.5, 0.5, 1.5],
        radius: 0.5,
    };
    assert_eq!(r.shape, want);
    assert_eq!(r.offset(1.0), [0.0, 0.0, -0.3]);
    assert_eq!(r.offset(0.5), [0.0, 0.0, -0.1]);
}

#[test]
fn rigid_shapes_of_the_wrong_dimension_are_refused_naming_the_key() {
    let with = |rigid: &str| format!("{BODIES}[[rigid]]\nname = \"tool\"\n{rigid}\n{PRESS}");
    refused(&with("point = [0.0, 0.0]"), &["`point`", "3D scene"]);
    refused(&with("polyline = [[0.0, 0.0], [1.0, 0.0]]"), &["`polyline`"]);
    let both = "plane = { point = [0.0, 0.0, 1.0], normal = [0.0, 0.0, -1.0] }\nsphere = { centre = [0.0, 0.0, 2.0], radius = 1.0 }";
    refused(&with(both), &["`plane`", "`sphere`"]);
    refused(&with("move = { z = 1.0 }"), &["no shape", "`plane`"]);
    refused(
        &with("plane = { point = [0.0, 0.0, 1.0], normal = [0.0, 0.0, 0.0] }"),
        &["rigid.tool.plane.normal", "zero"],
    );
    refused(
        &with("sphere = { centre = [0.0, 0.0, 2.0], radius = 0.0 }"),
        &["rigid.tool.sphere.radius", "> 0"],
    );
    refused(
        &with("cylinder = { point = [0.0, 0.0, 2.0], axis = [0.0, 0.0, 0.0], radius = 1.0 }"),
        &["rigid.tool.cylinder.axis", "zero"],
    );
    refused(
        &with("cylinder = { point = [0.0, 0.0, 2.0], axis = [0.0, 1.0, 0.0], radius = -1.0 }"),
        &["rigid.tool.cylinder.radius", "> 0"],
    );
    let two = "sphere = { centre = [0.0, 0.0, 2.0], radius = 1.0 }\ncylinder = { point = [0.0, 0.0, 2.0], axis = [0.0, 1.0, 0.0], radius = 1.0 }";
    refused(&with(two), &["`sphere`", "`cylinder`", "one shape"]);
    // 3D keys in a 2D scene
    let flat = r#"
name = "flat"
[[body]]
name = "block"
material = { model = "neo-hookean", young = 100.0, poisson = 0.3 }
mesh = { kind = "rectangle", origin = [0.0, 0.0], size = [1.0, 1.0], elements = [2, 2] }
[[rigid]]
name = "floor"
"#;
    let msg = "3D rigid surface in a 2D scene";
    refused(
        &format!("{flat}plane = {{ point = [0.0, 0.0, 0.0], normal = [0.0, 0.0, 1.0] }}"),
        &["`plane`", msg],
    );
    refused(
        &format!("{flat}sphere = {{ centre = [0.0, 0.0, 0.0], radius = 1.0 }}"),
        &["`sphere`", msg],
    );
    refused(
        &format!("{flat}cylinder = {{ point = [0.0, 0.0, 0.0], axis = [0.0, 1.0, 0.0], radius = 1.0 }}"),
        &["`cylinder`", msg, "`arc`"],
    );
    refused(
        &format!("{flat}polyline = [[1.0, -0.1], [0.0, -0.1]]\nmove = {{ z = 1.0 }}"),
        &["`move.z`", msg],
    );
}

#[test]
fn slaves_are_a_face_or_a_straight_edge_and_masters_must_exist() {
    let glue = |from: &str, to: &str| format!("{BODIES}{}", GLUE.replace(from, to));
    let e = refused(
        &glue("nodes = \"zmin\"", "nodes = { z = 0.5 }"),
        &[
            "slave.nodes",
            "neither a face nor a straight edge",
            "not on one straight edge",
        ],
    );
    assert!(e.contains("z = 0.5"), "{e}");
    refused(
        &glue("nodes = \"zmin\"", "nodes = \"all\""),
        &["slave.nodes", "neither a face nor a straight edge"],
    );
    let edge = glue("nodes = \"zmin\"", "nodes = { x = 0.0, z = 0.5 }").replace("two_pass = true", "");
    refused(&format!("{edge}two_pass = true\n"), &["`two_pass` with an edge slave"]);
    refused(
        &glue("nodes = \"zmin\"", "nodes = \"bottom\""),
        &["no face `bottom`", "zmin"],
    );
    refused(
        &glue("face = \"zmax\"", "face = \"top\""),
        &["master.face", "no face `top`"],
    );
    refused(&glue("body = \"base\"", "body = \"floor\""), &["no body named `floor`"]);
    refused(&format!("{BODIES}{PRESS}"), &["no rigid body named `tool`"]);
}

#[test]
fn what_3d_contact_does_not_have_is_refused_naming_the_key() {
    let glue = |extra: &str| format!("{BODIES}{GLUE}{extra}\n");
    refused(
        &glue("enforcement = \"augmented\""),
        &["enforcement = \"augmented\"", "3D"],
    );
    refused(
        &glue("master_smoothing = \"hermite\""),
        &["`master_smoothing = \"hermite\"`", "nagata"],
    );
    // a 3D face is smoothed by Nagata patches
    assert!(build(&glue("master_smoothing = \"nagata\"")).is_ok());
    refused(&glue("transfer = \"spatial\""), &["transfer = \"spatial\"", "3D"]);
    let plane = r#"
[[rigid]]
name = "tool"
plane = { point = [0.0, 0.0, 1.0], normal = [0.0, 0.0, -1.0] }
"#;
    let press = |extra: &str| format!("{BODIES}{plane}{PRESS}{extra}\n");
    refused(
        &press("allow_initial_penetration = true"),
        &["`allow_initial_penetration = true`"],
    );
    refused(&press("two_pass = true"), &["`two_pass`", "deformable"]);
    // friction on a plane, a sphere and a cylinder builds (each has convective coordinates)
    assert!(build(&press("mu = 0.2\neps_t = 100.0")).is_ok());
    let sphere = r#"
[[rigid]]
name = "tool"
sphere = { centre = [0.5, 0.5, 1.5], radius = 0.5 }
"#;
    let on_sphere = format!("{BODIES}{sphere}{PRESS}mu = 0.2\neps_t = 100.0\n");
    assert!(build(&on_sphere).is_ok());
    let on_cylinder = on_sphere.replace(
        "sphere = { centre = [0.5, 0.5, 1.5], radius = 0.5 }",
        "cylinder = { point = [0.5, 0.5, 1.5], axis = [1.0, 0.0, 0.0], radius = 0.5 }",
    );
    assert!(build(&on_cylinder).is_ok());
    assert!(build(&on_cylinder.replace("mu = 0.2", "mu = 0.0")).is_ok());
    // a rigid point as a slave
    let point_slave = format!(
        "{BODIES}{plane}{}",
        PRESS.replace(
            "slave = { body = \"top\", nodes = \"zmax\" }",
            "slave = { rigid = \"tool\" }"
        )
    );
    refused(&point_slave, &["`slave.rigid`"]);
    // a rigid surface's monitor builds (it was refused before 3D had one)
    let monitor = "[monitor]\nlabel = \"force\"\nrigid = \"tool\"\ncomponent = \"z\"\n";
    let m = build(&format!("{BODIES}{plane}{PRESS}{monitor}")).expect("a rigid surface's monitor");
    assert!(matches!(&m.monitors[0].target, contrail::model::MonitorTarget::RigidSurface(n) if n == "tool"));
}

#[test]
fn slave_nodes_inside_a_rigid_surface_at_the_start_are_refused() {
    // the plane 0.01 below the top face, its normal down: the top face's 16 nodes are inside
    let plane = r#"
[[rigid]]
name = "tool"
plane = { point = [0.0, 0.0, 0.99], normal = [0.0, 0.0, -1.0] }
"#;
    refused(
        &format!("{BODIES}{plane}{PRESS}"),
        &[
            "contact `press`",
            "16 of its 16",
            "`tool`",
            "by 1.0000e-2",
            "move the body or the rigid surface",
        ],
    );
    // a path starting with the tool already moved into the body
    let moved = plane.replace("0.99", "1.0") + "move = { z = [[0.0, -0.01], [1.0, -0.1]] }\n";
    refused(&format!("{BODIES}{moved}{PRESS}"), &["contact `press`", "by 1.0000e-2"]);
    // a sphere pressed 0.1 into the middle of the top face (3×3 elements: no node there;
    // the four nodes around it are inside, by 0.5 − √(1/18 + 0.16) = 0.0357)
    let sphere = r#"
[[rigid]]
name = "tool"
sphere = { centre = [0.5, 0.5, 1.4], radius = 0.5 }
"#;
    refused(
        &format!("{BODIES}{sphere}{PRESS}"),
        &["contact `press`", "4 of its 16", "node", "by 3.57"],
    );
    // touching (gap 0) is fine
    assert!(build(&format!("{BODIES}{}{PRESS}", sphere.replace("1.4]", "1.5]"))).is_ok());
}

/// An edge slave: the top block's nodes on the line `x = 0, z = 0.5` (4 nodes, spacing 1/3)
/// weighted by their tributary lengths (1/6, 1/3, 1/3, 1/6: the edge's length 1 in all),
/// penalties per unit length; a master named `"zmax+xmax"` is the union of the two faces'
/// facets (16 + 8).
#[test]
fn a_straight_edge_is_a_slave_weighted_by_lengths_and_faces_join_with_a_plus() {
    let text = format!(
        "{BODIES}{}",
        GLUE.replace("nodes = \"zmin\"", "nodes = { x = 0.0, z = 0.5 }")
    )
    .replace("two_pass = true", "")
    .replace("face = \"zmax\"", "face = \"zmax+xmax\"");
    let m = build(&text).unwrap_or_else(|e| panic!("{e}"));
    let pair = &m.surface_contacts[0];
    assert_eq!(pair.measure, contrail::model::SlaveMeasure::Length);
    assert_eq!(pair.slaves.len(), 4);
    let expected = [1.0 / 6.0, 1.0 / 3.0, 1.0 / 3.0, 1.0 / 6.0];
    for (l, e) in pair.areas.iter().zip(expected) {
        assert!((l - e).abs() < 1e-12, "{:?}", pair.areas);
    }
    let ys: Vec<f64> = pair.slaves.iter().map(|&n| m.nodes[n][1]).collect();
    let monotone = ys.windows(2).all(|w| w[0] < w[1]) || ys.windows(2).all(|w| w[0] > w[1]);
    assert!(monotone, "sorted along the edge: {ys:?}");
    let SurfaceMaster::Facets { facets, .. } = &pair.master else {
        panic!("a face master")
    };
    assert_eq!(facets.len(), 16 + 8);
}
