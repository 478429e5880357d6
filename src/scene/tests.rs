use super::*;

#[test]
fn every_builtin_parses_and_builds() {
    for b in builtin::BUILTINS {
        let src = SceneSource::resolve(b.name).unwrap();
        let scene = parse(&src, &[]).unwrap_or_else(|e| panic!("{}: {e}", b.name));
        assert_eq!(scene.name, b.name);
        let elements = match build_any(&src, &scene).unwrap_or_else(|e| panic!("{}: {e}", b.name)) {
            AnyProblem::Plane(p) => p.model.elements.len(),
            AnyProblem::Solid(p) => p.model.elements.len(),
        };
        assert!(elements > 0);
        assert!(!builtin::description(b).is_empty());
    }
}

#[test]
fn typo_in_a_key_reports_file_line_and_column() {
    let text = "name = \"x\"\n[stepping]\nincremnts = 4\n";
    let src = SceneSource {
        origin: "typo.toml".into(),
        text: text.into(),
    };
    let e = parse(&src, &[]).unwrap_err();
    let msg = e.to_string();
    assert!(msg.starts_with("typo.toml:3:1:"), "{msg}");
    assert!(msg.contains("incremnts") && msg.contains("hint"), "{msg}");
}

#[test]
fn unknown_names_point_at_their_line() {
    let text = "name = \"x\"\n[[fix]]\nbody = \"nobody\"\nnodes = \"left\"\ncomponents = [\"x\"]\n";
    let src = SceneSource {
        origin: "names.toml".into(),
        text: text.into(),
    };
    let scene = parse(&src, &[]).unwrap();
    let msg = build_model(&src, &scene).unwrap_err().to_string();
    assert!(msg.starts_with("names.toml:3:8: no body named `nobody`"), "{msg}");
}

#[test]
fn overrides_are_checked_too() {
    let src = SceneSource::resolve("strip-channel").unwrap();
    let s = parse(
        &src,
        &["contact.mu=0.1".into(), "contact.transfer=straightforward".into()],
    )
    .unwrap();
    assert!(s.contacts.iter().all(|c| c.mu == 0.1));
    let e = parse(&src, &["contact.transfer=sideways".into()])
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("--set contact.transfer=sideways") && e.contains("sideways"),
        "{e}"
    );
    let e = parse(&src, &["stepping.incremnts=3".into()]).unwrap_err().to_string();
    assert!(e.contains("incremnts"), "{e}");
}

#[test]
fn missing_file_is_a_clear_error() {
    let e = SceneSource::resolve("/no/such/scene.toml").unwrap_err().to_string();
    assert!(e.starts_with("/no/such/scene.toml: cannot read"), "{e}");
}

/// `schemas/scene.schema.json` is generated from the scene types; refresh it on purpose with
/// `CONTRAIL_BLESS=1 cargo test --lib scene_schema` (or `contrail schema > schemas/scene.schema.json`).
#[test]
fn scene_schema_file_matches_the_types() {
    let generated = serde_json::to_string_pretty(&schemars::schema_for!(SceneFile)).unwrap() + "\n";
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/schemas/scene.schema.json");
    if std::env::var_os("CONTRAIL_BLESS").is_some() {
        std::fs::write(path, &generated).unwrap();
    }
    let on_disk = std::fs::read_to_string(path).unwrap_or_default();
    assert!(
        on_disk == generated,
        "schemas/scene.schema.json is stale: run CONTRAIL_BLESS=1 cargo test --lib scene_schema"
    );
}

/// A scene beside `scenes/half-disc.msh` with the given extra text.
fn gmsh_scene(file: &str, extra: &str) -> Result<crate::model::Model, SceneError> {
    let text = format!(
        "name = \"g\"\n[[body]]\nname = \"disc\"\nmaterial = {{ model = \"neo-hookean\", young = 1.0, poisson = 0.3 }}\nmesh = {{ kind = \"gmsh\", file = \"{file}\" }}\n{extra}"
    );
    let src = SceneSource {
        origin: concat!(env!("CARGO_MANIFEST_DIR"), "/scenes/g.toml").into(),
        text,
    };
    let scene = parse(&src, &[])?;
    build_model(&src, &scene)
}

#[test]
fn gmsh_mesh_resolves_beside_the_scene_and_names_its_groups() {
    let m = gmsh_scene("half-disc.msh", "").unwrap();
    let b = &m.bodies[0];
    for set in ["arc", "top", "tip", "disc", "all"] {
        assert!(b.node_sets.contains_key(set), "{set}");
    }
    assert_eq!(b.faces.keys().collect::<Vec<_>>(), ["arc", "top"]);
    assert_eq!(b.node_sets["tip"].len(), 1);
    // the arc face runs counter-clockwise: outward normals point away from the centre (0, 1)
    for &[a, c] in &b.faces["arc"] {
        let (pa, pc) = (m.nodes[a], m.nodes[c]);
        let n = [pc[1] - pa[1], -(pc[0] - pa[0])];
        let mid = [0.5 * (pa[0] + pc[0]), 0.5 * (pa[1] + pc[1]) - 1.0];
        assert!(n[0] * mid[0] + n[1] * mid[1] > 0.0, "segment {a}→{c} points inward");
    }
}

#[test]
fn gmsh_errors_name_the_file_the_group_and_the_fix() {
    let missing = gmsh_scene("nope.msh", "").unwrap_err().to_string();
    assert!(
        missing.contains("nope.msh") && missing.contains("cannot read") && missing.contains("relative to the scene"),
        "{missing}"
    );
    let fix = "[[fix]]\nbody = \"disc\"\nnodes = \"bottom\"\ncomponents = [\"x\"]\n";
    let group = gmsh_scene("half-disc.msh", fix).unwrap_err().to_string();
    assert!(
        group.contains("half-disc.msh")
            && group.contains("no physical group `bottom`")
            && group.contains("Physical Curve"),
        "{group}"
    );
    let contact = "[[rigid]]\nname = \"p\"\npoint = [0.0, -1.0]\n[[contact]]\nname = \"c\"\nslave = { rigid = \"p\" }\nmaster = { body = \"disc\", face = \"disc\" }\neps_n = 1.0\n";
    let face = gmsh_scene("half-disc.msh", contact).unwrap_err().to_string();
    assert!(
        face.contains("no physical curve `disc`") && face.contains("arc, top"),
        "{face}"
    );
    let not_msh = gmsh_scene("half-disc.toml", "").unwrap_err().to_string();
    assert!(
        not_msh.contains("half-disc.toml") && not_msh.contains("$MeshFormat"),
        "{not_msh}"
    );
}

#[test]
fn gmsh_file_must_be_a_regular_file() {
    for file in ["/dev/zero", "/tmp"] {
        let e = gmsh_scene(file, "").unwrap_err().to_string();
        assert!(e.contains(file) && e.contains("cannot read"), "{e}");
    }
}
