//! Pairing rules on a rigid block outline `(20, 0) → (6.5, 0) → (6.5, −40)` (body below the
//! top face and right of the wall), as in the strip-channel scene.

use super::*;
use crate::contact::law::ContactLaw;
use crate::contact::transfer::TransferKind;
use crate::model::{Master, Model, Piece, Ramp, RigidBody, RigidShape};

fn block_model(slaves: &[[f64; 2]]) -> Model {
    outline_model([[20.0, 0.0], [6.5, 0.0], [6.5, -40.0]], slaves)
}

/// A rigid outline of two pieces `p0 → p1 → p2`, body on the left of the travel.
fn outline_model(p: [[f64; 2]; 3], slaves: &[[f64; 2]]) -> Model {
    let pieces = vec![Piece::Segment { a: p[0], b: p[1] }, Piece::Segment { a: p[1], b: p[2] }];
    let mut m = Model {
        nodes: slaves.to_vec(),
        ..Model::default()
    };
    m.rigid.push(RigidBody {
        name: "block".into(),
        shape: RigidShape::Surface { pieces },
        motion: [Ramp::constant(0.0), Ramp::constant(0.0)],
    });
    m.contacts.push(ContactPair {
        name: "block".into(),
        slaves: (0..slaves.len()).map(Slave::Node).collect(),
        master: Master::Rigid {
            body: 0,
            prev: vec![None, Some(0)],
            next: vec![Some(1), None],
        },
        law: ContactLaw {
            eps_n: 1.0,
            eps_t: 1.0,
            mu: 0.0,
        },
        transfer: TransferKind::Continuous,
        search_radius: 1.0,
        owned_vertices: Vec::new(),
        weights: Vec::new(),
        smoothing: crate::model::Smoothing::None,
        enforcement: crate::model::Enforcement::Penalty,
    });
    m
}

fn locate_all(m: &Model, start: Option<usize>) -> Vec<Pairing> {
    let u = vec![0.0; m.dof_count()];
    let cfg = Config {
        model: m,
        u: &u,
        t: 0.0,
    };
    let pair = &m.contacts[0];
    let mut grid = None;
    pair.slaves
        .iter()
        .map(|&s| locate(&cfg, pair, s, start, false, &mut grid, 0.0))
        .collect()
}

#[test]
fn a_node_on_the_top_face_right_of_the_corner_is_not_a_wall_contact() {
    // x = 6.75 on the top: its projection on the wall's line lands on the wall's end at
    // ξ = −1 with ζ = −0.25; it belongs to the top face (ζ = 0), tracked or searched
    let m = block_model(&[[6.75, 0.0], [6.75, -1e-4], [7.5, -1e-3]]);
    for start in [None, Some(1), Some(0)] {
        let p = locate_all(&m, start);
        for (i, p) in p.iter().enumerate() {
            let l = p.located.expect("paired");
            assert_eq!(l.segment, 0, "node {i} from {start:?}: {l:?}");
            assert!(l.gap.abs() <= 1e-3 + 1e-15);
        }
    }
}

#[test]
fn a_penetrating_node_near_the_corner_takes_the_nearer_face() {
    let m = block_model(&[[6.52, -0.3], [6.9, -0.01]]);
    for start in [None, Some(0), Some(1)] {
        let p = locate_all(&m, start);
        assert_eq!(p[0].located.unwrap().segment, 1, "near the wall, from {start:?}");
        assert_eq!(p[1].located.unwrap().segment, 0, "near the top, from {start:?}");
    }
}

#[test]
fn the_vertex_region_and_free_ends_pair_nothing() {
    // up-left of the corner (convex vertex region), beyond the top's free end, below the
    // wall's free end
    let m = block_model(&[[6.3, 0.2], [20.3, -0.1], [6.6, -40.2]]);
    for start in [None, Some(0), Some(1)] {
        for (i, p) in locate_all(&m, start).iter().enumerate() {
            assert!(p.located.is_none(), "point {i} from {start:?}: {p:?}");
        }
    }
}

#[test]
fn a_point_beyond_the_search_radius_is_not_paired() {
    let m = block_model(&[[3.0, -5.0], [10.0, 2.0]]);
    for p in locate_all(&m, None) {
        assert_eq!(p, Pairing::default());
    }
}

#[test]
fn a_tracked_point_deeper_inside_than_the_reach_is_flagged_not_paired() {
    // 3 below the top face (search radius 1), projecting onto it: inside the block
    let m = block_model(&[[10.0, -3.0], [10.0, 3.0], [10.0, -0.5]]);
    let tracked = locate_all(&m, Some(0));
    assert!(
        tracked[0].located.is_none() && tracked[0].beyond_reach_inside,
        "{:?}",
        tracked[0]
    );
    // as far outside: out of reach, nothing to flag
    assert_eq!(tracked[1], Pairing::default());
    // within reach inside: paired
    assert!(tracked[2].located.is_some() && !tracked[2].beyond_reach_inside);
    // never tracked, the search asks no such question
    assert!(!locate_all(&m, None)[0].beyond_reach_inside);
}

#[test]
fn a_penetrating_point_in_the_wedge_of_a_concave_vertex_stays_in_contact() {
    // outline (10, 0) → (0, 0) → (−10, 2): body below, the vertex is concave (the outline
    // turns right). (−0.001, −0.05) is inside, between the two inward normals: it projects
    // past the end of both segments. Tracked, it keeps its segment (extended); never
    // tracked, the grid search finds no valid projection.
    let m = outline_model([[10.0, 0.0], [0.0, 0.0], [-10.0, 2.0]], &[[-0.001, -0.05]]);
    for (start, seg) in [(Some(0), 0), (Some(1), 1)] {
        let p = locate_all(&m, start)[0];
        let l = p.located.unwrap_or_else(|| panic!("from {start:?}: released ({p:?})"));
        assert_eq!(l.segment, seg, "from {start:?}: {l:?}");
        assert!(l.gap < 0.0 && l.xi.abs() > 1.0 && l.xi.abs() < 1.01, "{l:?}");
    }
    // the same point outside a convex vertex (mirror: body above) is in its vertex region
    let m = outline_model([[-10.0, 2.0], [0.0, 0.0], [10.0, 0.0]], &[[-0.001, -0.05]]);
    for start in [Some(0), Some(1)] {
        assert!(locate_all(&m, start)[0].located.is_none(), "from {start:?}");
    }
}
