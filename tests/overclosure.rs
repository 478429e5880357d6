//! Initial overclosure: slave nodes that start inside their master by at most 1 % of the
//! element at the interface are moved onto it, strain-free, and the run says so; deeper
//! overlaps are refused as before (`src/scene/overclosure.rs`).
//!
//! Scene `tests/data/block-overlapping-floor.toml`: a block 1 × 0.5 (8 × 4 elements, edge
//! 0.125) meshed 1e-5 below a rigid floor at y = 0 (8e-5 of its element), pressed down 0.01.
//! The block is held still for the first of two increments: strain-free, it carries no force
//! there (asserted ≤ 1e-12 of the pressed force; left inside the floor with
//! `allow_initial_penetration`, it carries the penalty force of the overlap). Reference for the
//! pressed force: the block as adjusted, meshed on the floor (height 0.49999, its bottom row
//! 8e-5 thicker): within 1e-6 relative. Asserted: the overlapping block builds with
//! one note naming the pair, its bottom nodes at y = 0 exactly, the note first in its log; with
//! `adjust_overclosure = false`, and with an overlap of 1e-2 (8 % of the element), the scene
//! is refused naming the pair; two deformable blocks overlapping by 1e-5 are adjusted too.
mod common;

const SCENE: &str = include_str!("data/block-overlapping-floor.toml");

fn forces(sets: &[&str], text: &str) -> (Vec<f64>, contrail::record::Memory) {
    let p = common::scene_file("tests/data/block-overlapping-floor.toml", text, sets);
    let (_, m) = common::solve_ok(&p);
    let f = m.increments.iter().map(|i| i.reaction_total[1]).collect();
    (f, m)
}

#[test]
fn a_round_off_overlap_is_adjusted_strain_free_and_reported() {
    let p = common::scene_file("tests/data/block-overlapping-floor.toml", SCENE, &[]);
    assert_eq!(p.model.notes.len(), 1, "{:?}", p.model.notes);
    assert!(p.model.notes[0].contains("contact `floor`: 9 slave nodes") && p.model.notes[0].contains("moved onto it"));
    let bottom = &p.model.bodies[0].node_sets["bottom"];
    assert!(bottom.iter().all(|&n| p.model.nodes[n][1] == 0.0));

    let (adjusted, m) = forces(&[], SCENE);
    // the block as adjusted: its bottom on the floor, its top where it was
    let on_floor = SCENE
        .replace("origin = [0.0, -1.0e-5]", "origin = [0.0, 0.0]")
        .replace("size = [1.0, 0.5]", "size = [1.0, 0.49999]");
    let (reference, _) = forces(&[], &on_floor);
    let pressed = reference[1];
    assert!(
        adjusted[0].abs() <= 1e-12 * pressed.abs(),
        "held still: {}",
        adjusted[0]
    );
    assert!(
        (adjusted[1] - pressed).abs() <= 1e-6 * pressed.abs(),
        "{} vs {pressed}",
        adjusted[1]
    );
    let (kept, _) = forces(&["contact.allow_initial_penetration=true"], SCENE);
    assert!(kept[0].abs() > 1e-3 * pressed.abs(), "left inside: {}", kept[0]);
    assert!(
        m.logs.first().is_some_and(|l| l.message.contains("moved onto it")),
        "{:?}",
        m.logs.first()
    );
}

#[test]
fn a_gross_overlap_or_no_adjustment_is_refused() {
    let deep = SCENE.replace("origin = [0.0, -1.0e-5]", "origin = [0.0, -1.0e-2]");
    for (text, sets) in [
        (deep.as_str(), vec![]),
        (SCENE, vec!["contact.adjust_overclosure=false"]),
    ] {
        let src = contrail::scene::SceneSource {
            origin: "overlap.toml".into(),
            text: text.into(),
        };
        let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
        let Err(err) = contrail::scene::parse(&src, &sets).and_then(|f| contrail::scene::build(&src, &f)) else {
            panic!("the overlap was not refused")
        };
        assert!(err.to_string().contains("start inside rigid body `floor`"), "{err}");
    }
}

#[test]
fn two_deformable_bodies_overlapping_by_round_off_are_adjusted() {
    let text = r#"
name = "two-blocks"
description = "two blocks meshed 1e-5 into each other"
[[body]]
name = "base"
material = { model = "saint-venant-kirchhoff", young = 1.0e3, poisson = 0.3 }
mesh = { kind = "rectangle", origin = [0.0, 0.0], size = [1.0, 0.5], elements = [5, 2] }
[[body]]
name = "top"
material = { model = "saint-venant-kirchhoff", young = 1.0e3, poisson = 0.3 }
mesh = { kind = "rectangle", origin = [0.0, 0.49999], size = [1.0, 0.5], elements = [4, 2] }
[[fix]]
body = "base"
nodes = "bottom"
components = ["x", "y"]
[[fix]]
body = "top"
nodes = "top"
components = ["x", "y"]
[[contact]]
name = "interface"
slave = { body = "top", nodes = "bottom" }
master = { body = "base", face = "top" }
eps_n = 1.0e6
"#;
    let p = common::scene_text(text);
    assert!(
        p.model
            .notes
            .iter()
            .any(|n| n.contains("contact `interface`") && n.contains("moved onto it")),
        "{:?}",
        p.model.notes
    );
    let top = &p.model.bodies[1].node_sets["bottom"];
    assert!(top.iter().all(|&n| (p.model.nodes[n][1] - 0.5).abs() < 1e-15));
}
