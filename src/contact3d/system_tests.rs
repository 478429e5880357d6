//! Tests of the 3D contact state: pairing, history transfer and its failure, commit.

use super::*;
use crate::contact3d::search::{free_borders, past_free_border};
use crate::contact3d::transfer::Scheme;
use crate::model::{ContactLaw, SurfaceMaster, SurfacePair};

/// Two unit squares side by side in `z = 0`: facet 0 on `[0, 1] × [0, 1]` with its normal
/// `+z`, facet 1 on `[1, 2] × [0, 1]`, its normal `+z` or (`folded`) `−z`; node 6 the slave.
fn two_facets(folded: bool) -> Model<Solid> {
    let nodes = vec![
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [2.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [1.0, 1.0, 0.0],
        [2.0, 1.0, 0.0],
        [0.5, 0.5, 0.0],
    ];
    let second = if folded { [1, 4, 5, 2] } else { [1, 2, 5, 4] };
    Model {
        nodes,
        surface_contacts: vec![SurfacePair {
            name: "pair".into(),
            slaves: vec![6],
            areas: vec![1.0],
            measure: Default::default(),
            master: SurfaceMaster::Facets {
                body: 0,
                facets: vec![[0, 1, 4, 3], second],
            },
            law: ContactLaw {
                eps_n: 1e3,
                eps_t: 1e3,
                mu: 0.5,
            },
            transfer: Scheme::Continuous,
            search_radius: 0.5,
        }],
        ..Model::default()
    }
}

/// The slave node at `x`: the displacement vector that puts it there.
fn slave_at(model: &Model<Solid>, x: [f64; 3]) -> Vec<f64> {
    let mut u = vec![0.0; 3 * model.nodes.len()];
    for c in 0..3 {
        u[18 + c] = x[c] - model.nodes[6][c];
    }
    u
}

/// Press the slave at `(0.5, 0.5)` by 1e-3 into the facets' `+z` side (the first facet's
/// outside), hold it there for a second increment (the first closing one is frictionless;
/// the second gives it a stick anchor), then move it to `to`: its state there.
fn press_then_move(model: &Model<Solid>, to: [f64; 3]) -> (SurfaceSystem, SurfaceNow) {
    let mut system = SurfaceSystem::new(Some(model));
    let pressed = slave_at(model, [0.5, 0.5, -1e-3]);
    let cfg = SurfaceConfig {
        model,
        u: &pressed,
        t: 0.0,
    };
    for _ in 0..2 {
        system.evaluate(&cfg, &mut |_, _, _, _, _| {});
        system.commit();
        system.reset_current();
    }
    assert!(system.committed[0][0].closed && system.committed[0][0].history.is_some());
    let moved = slave_at(model, to);
    let cfg = SurfaceConfig {
        model,
        u: &moved,
        t: 0.0,
    };
    system.evaluate(&cfg, &mut |_, _, _, _, _| {});
    let now = system.current[0][0];
    (system, now)
}

#[test]
fn a_point_slides_onto_the_next_facet_with_its_history_carried() {
    let model = two_facets(false);
    let (_, now) = press_then_move(&model, [1.5, 0.5, -1e-3]);
    assert_eq!(now.facet, Some(1), "the point is on the second facet");
    assert!(!now.history_lost);
    let e = now.eval.expect("paired");
    assert_ne!(e.state, ContactState::Open);
    // it slid 1 against a stick anchor: it slips, at the Coulomb limit
    assert_eq!(e.state, ContactState::Slip);
    let t = e.projection.point.norm(e.traction);
    assert!(
        (t - 0.5 * e.normal_force).abs() < 1e-9 * e.normal_force,
        "|T| {t} vs μN"
    );
}

#[test]
fn a_history_that_cannot_be_carried_onto_a_folded_facet_is_reported_lost() {
    let model = two_facets(true);
    // the folded facet's normal is −z: from above, the point is pressed into it
    let (system, now) = press_then_move(&model, [1.5, 0.5, 1e-3]);
    assert_eq!(now.facet, Some(1));
    assert!(
        now.history_lost,
        "a transfer across a fold of 180° cannot keep the history"
    );
    let u = slave_at(&model, [1.5, 0.5, 1e-3]);
    let cfg = SurfaceConfig {
        model: &model,
        u: &u,
        t: 0.0,
    };
    let snapshot = system.snapshots(&cfg)[0];
    assert!(snapshot.history_lost && snapshot.crossing);
}

#[test]
fn the_free_border_of_two_facets_side_by_side_is_every_edge_but_the_shared_one() {
    let model = two_facets(false);
    let SurfaceMaster::Facets { facets, .. } = &model.surface_contacts[0].master else {
        unreachable!()
    };
    // facet 0's edge 1 (ξ¹ = 1) and facet 1's edge 3 (ξ¹ = −1) are the shared edge 1–4
    assert_eq!(
        free_borders(facets),
        vec![[true, false, true, true], [true, true, true, false]]
    );
    assert_eq!(past_free_border([1.5, 0.0], [true, false, true, true]), 0.0);
    assert_eq!(past_free_border([-1.5, 0.25], [true, false, true, true]), 0.5);
    assert_eq!(past_free_border([0.0, 1.25], [true, true, false, true]), 0.0);
}

#[test]
fn a_point_that_slides_past_the_faces_free_border_opens() {
    // before the rule, it stayed paired with the extension of facet 1 (ξ¹ = 1.6) and was
    // pushed by a surface that is not there
    let model = two_facets(false);
    let (_, now) = press_then_move(&model, [2.3, 0.5, -1e-3]);
    assert_eq!(now.facet, None);
    assert!(now.eval.is_none() && now.force == [0.0; 3]);
}

#[test]
fn a_closed_point_just_past_the_free_border_is_held_and_a_fresh_one_is_not() {
    let model = two_facets(false);
    // first onto facet 1, where it is committed closed …
    let (mut system, now) = press_then_move(&model, [1.9, 0.5, -1e-3]);
    assert_eq!(now.facet, Some(1));
    system.commit();
    system.reset_current();
    // … then 2e-4 of the facet's width past its free end (ξ¹ = 1.0004): held
    let u = slave_at(&model, [2.0002, 0.5, -1e-3]);
    let cfg = SurfaceConfig {
        model: &model,
        u: &u,
        t: 0.0,
    };
    system.evaluate(&cfg, &mut |_, _, _, _, _| {});
    let held = system.current[0][0];
    assert_eq!(held.facet, Some(1));
    assert!(held.eval.is_some_and(|e| e.state != ContactState::Open));
    // a point there without that history is beyond the face
    let mut fresh = SurfaceSystem::new(Some(&model));
    fresh.evaluate(&cfg, &mut |_, _, _, _, _| {});
    assert_eq!(fresh.current[0][0].facet, None);
}
