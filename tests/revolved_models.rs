//! One scene, several models: an axisymmetric scene built as written and, with
//! `revolution.build = true`, as the 3D quarter of its revolution (`src/scene/revolve.rs`,
//! `src/model/revolved_mesh.rs`). References and tolerances:
//! - a hollow cylinder (r from 0.5 to 1, height 0.5, E = 1000, ν = 0.3, neo-Hooke) shortened
//!   by 1e-5 of its height between held ends free to slide: a uniform uniaxial state, so the
//!   quarter model's force over the axisymmetric one is the area of its faceted section over
//!   the ring's, `n sin(2π/n) / 2π` for `n` = 4 × `around` facets, within 1e-6 (around = 8
//!   and 16), and the axisymmetric force is `E A ε` within 1e-4 (small strain);
//! - the disc barrelling between rough plates (`tests/data/disc-axisym.toml`: radius 1, height
//!   1, the upper half, compressed 4 %, μ = 0.3): the revolved model's force within 1 % of
//!   the axisymmetric model's on the same section meshes 8 × 4 and 12 × 6 (measured −0.79 %
//!   and −0.36 %: the 3D quarter's facets and elements converging on the section's);
//! - the revolved Hertz scene (`hertz-axisym`, section 8 × 8): the rigid sphere's monitor (in
//!   3D the sum of the forces its points put on the block) equals the reaction on the block's
//!   base within 1e-6 of it (equilibrium), and the axisymmetric force within 2 %;
//! - what has no 3D counterpart is refused with the reason.

use contrail::record::Memory;
use std::sync::atomic::AtomicBool;

/// The named monitor's force at the last increment of a scene (text or path) with overrides.
fn monitor_force(scene: &str, text: Option<&str>, sets: &[String], label: &str) -> f64 {
    let src = match text {
        Some(t) => contrail::scene::SceneSource {
            origin: scene.into(),
            text: t.into(),
        },
        None => contrail::scene::SceneSource::resolve(scene).expect("the scene reads"),
    };
    let file = contrail::scene::parse(&src, sets).unwrap_or_else(|e| panic!("{e}"));
    let problem = contrail::scene::build_any(&src, &file).unwrap_or_else(|e| panic!("{e}"));
    let mut mem = Memory::default();
    match &problem {
        contrail::scene::AnyProblem::Plane(p) => {
            let info = contrail::run_info(&src, sets, p);
            contrail::solver::run(p, &info, &mut mem, &AtomicBool::new(false)).unwrap_or_else(|e| panic!("{e}"));
        }
        contrail::scene::AnyProblem::Solid(p) => {
            let info = contrail::run_info(&src, sets, p);
            contrail::solver::run(p, &info, &mut mem, &AtomicBool::new(false)).unwrap_or_else(|e| panic!("{e}"));
        }
    }
    let last = mem.increments.last().expect("increments");
    last.monitors
        .iter()
        .find(|m| m.label == label)
        .expect("the monitor")
        .force
}

fn sets(list: &[&str]) -> Vec<String> {
    list.iter().map(|s| s.to_string()).collect()
}

const RING: &str = r#"
name = "ring"
[[body]]
name = "ring"
model = "axisymmetric"
material = { model = "neo-hookean", young = 1000.0, poisson = 0.3 }
mesh = { kind = "rectangle", origin = [0.5, 0.0], size = [0.5, 0.5], elements = [4, 3] }
[[fix]]
body = "ring"
nodes = "bottom"
components = ["y"]
[[fix]]
body = "ring"
nodes = "top"
components = ["y"]
value = -5.0e-6
[[monitor]]
label = "base"
body = "ring"
nodes = "bottom"
component = "y"
[stepping]
increments = 1
[revolution]
"#;

#[test]
fn a_revolved_ring_in_uniform_compression_carries_the_force_of_its_faceted_section() {
    let axisymmetric = monitor_force("ring.toml", Some(RING), &[], "base");
    // E A ε with A = π (1 − 0.25), ε = 1e-5: uniaxial and small
    let exact = 1000.0 * std::f64::consts::PI * 0.75 * 1.0e-5;
    assert!(
        (axisymmetric / exact - 1.0).abs() <= 1e-4,
        "{axisymmetric} against E A ε = {exact}"
    );
    for around in [8, 16] {
        let n = format!("revolution.around={around}");
        let quarter = monitor_force("ring.toml", Some(RING), &sets(&["revolution.build=true", &n]), "base");
        let facets = 4.0 * around as f64;
        let area_ratio = facets * (2.0 * std::f64::consts::PI / facets).sin() / (2.0 * std::f64::consts::PI);
        let ratio = quarter / axisymmetric;
        println!("around {around}: axisymmetric {axisymmetric:.9}, quarter ×4 {quarter:.9}, ratio {ratio:.8} (faceted area {area_ratio:.8})");
        assert!((ratio / area_ratio - 1.0).abs() <= 1e-6, "{ratio} against {area_ratio}");
    }
}

#[test]
fn the_revolved_disc_barrels_with_the_axisymmetric_force_within_a_per_cent() {
    let scene = "tests/data/disc-axisym.toml";
    for mesh in ["[8, 4]", "[12, 6]"] {
        let m = format!("body.disc.mesh.elements={mesh}");
        let axisymmetric = monitor_force(scene, None, &sets(&[&m]), "symmetry plane");
        let quarter = monitor_force(scene, None, &sets(&[&m, "revolution.build=true"]), "symmetry plane");
        let diff = quarter / axisymmetric - 1.0;
        println!(
            "{mesh}: axisymmetric {axisymmetric:.4}, revolved quarter ×4 {quarter:.4} ({:+.2} %)",
            100.0 * diff
        );
        assert!(diff.abs() <= 0.01, "{diff}");
    }
}

#[test]
fn the_revolved_spheres_monitor_is_the_reaction_on_the_base() {
    let text = contrail::scene::SceneSource::resolve("hertz-axisym")
        .expect("built in")
        .text
        + "\n[[monitor]]\nlabel = \"base\"\nbody = \"block\"\nnodes = \"bottom\"\ncomponent = \"y\"\n";
    let mesh = sets(&["body.block.mesh.elements=[8, 8]"]);
    let axisymmetric = monitor_force("hertz.toml", Some(&text), &mesh, "sphere");
    let mut revolved = mesh.clone();
    revolved.push("revolution.build=true".into());
    let sphere = monitor_force("hertz.toml", Some(&text), &revolved, "sphere");
    let base = monitor_force("hertz.toml", Some(&text), &revolved, "base");
    println!("axisymmetric {axisymmetric:.6}; revolved: sphere {sphere:.8}, base {base:.8}");
    assert!((sphere / base - 1.0).abs() <= 1e-6, "{sphere} against {base}");
    assert!(
        (sphere / axisymmetric - 1.0).abs() <= 0.02,
        "{sphere} against {axisymmetric}"
    );
}

#[test]
fn what_has_no_3d_revolution_is_refused_with_the_reason() {
    let refused = |extra: &[&str], said: &str| {
        let mut s = sets(&["revolution.build=true"]);
        s.extend(sets(extra));
        let e = contrail::load_any_scene("tests/data/disc-axisym.toml", &s)
            .err()
            .unwrap_or_else(|| panic!("{extra:?} is refused"))
            .to_string();
        assert!(e.contains(said) && e.contains("[revolution]"), "{e}");
    };
    refused(&["body.disc.model=\"plane-strain\""], "not axisymmetric");
    refused(&["rigid.plate.polyline=[[-0.1, 0.5], [1.5, 0.6]]"], "cone");
    refused(&["rigid.plate.move.x=0.1"], "across the axis");
    refused(
        &["fix.0.nodes=\"right\"", "fix.0.components=[\"x\"]"],
        "radial support off the axis",
    );
    refused(&["monitor.0.component=\"x\""], "radial");
}
