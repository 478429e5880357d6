//! A run that fails where the method fails says why: the polygon capstan with the belt's
//! inner face left faceted (`contact.master_smoothing = "none"`), 16 drum vertices pressing
//! on it as contact points, stops in the pull when a vertex slides onto a node of the face,
//! where the face's normal jumps and the node-to-segment residual has no root (measured
//! 2026-11-27: increment 40, t = 0.775, drum vertex 4 at ξ = 1.0003 of belt segment 38).
//! Asserted: the run fails, its reason names a point at a node of a faceted master and the
//! remedy; the same scene with the default Hermite face completes (`tests/capstan.rs`).

mod common;

#[test]
fn faceted_node_failure_names_the_point_at_the_node_and_the_remedy() {
    let problem = common::scene(
        "capstan-polygon",
        &[
            "rigid.drum.polygon.sides=16",
            "stepping.increments=100",
            "contact.master_smoothing=\"none\"",
        ],
    );
    let (result, _) = common::solve(&problem);
    let message = result
        .expect_err("the faceted face has no equilibrium at the node")
        .to_string();
    println!("{message}");
    assert!(message.contains("sits at a node of its faceted master"), "{message}");
    assert!(message.contains("master_smoothing = \"hermite\""), "{message}");
}
