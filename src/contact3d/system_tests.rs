//! Tests of the 3D contact state: pairing, history transfer and its failure, commit.

use super::*;
use crate::contact3d::locate::locate;
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
            friction: None,
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
            smoothing: Default::default(),
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

/// A block's top, narrow across (`[0, 10] × [0, 0.05]` at `z = 0`, normal `+z`), and its
/// wall (`x = 0`, `z ∈ [−40, 0]`, normal `−x`), meeting at a convex edge; node 6 the slave.
fn top_and_wall() -> Model<Solid> {
    let mut model = two_facets(false);
    model.nodes = vec![
        [0.0, 0.0, 0.0],
        [10.0, 0.0, 0.0],
        [10.0, 0.05, 0.0],
        [0.0, 0.05, 0.0],
        [0.0, 0.0, -40.0],
        [0.0, 0.05, -40.0],
        [4.0, 0.025, 0.0],
    ];
    let pair = &mut model.surface_contacts[0];
    // the wall first: the search meets it first
    pair.master = SurfaceMaster::Facets {
        body: 0,
        facets: vec![[0, 3, 5, 4], [0, 1, 2, 3]],
    };
    pair.search_radius = 50.0;
    model
}

#[test]
fn a_point_a_hair_past_a_narrow_facets_border_stays_with_it_not_with_a_far_wall() {
    // The refined plate over an edge: a slave on the top, 1e-12 past its free border
    // across (ξ² = 1 + 4e-11) and 1e-9 into it, lies as far outside the wall's corner in
    // ξ (the wall is as wide) and 4 behind the wall's plane. The nearest facet is the top;
    // before the rule ranked by distance, the wall could win the tie in ξ and the point
    // was paired with a gap of −4.
    let model = top_and_wall();
    let SurfaceMaster::Facets { facets, .. } = &model.surface_contacts[0].master else {
        unreachable!()
    };
    let boxes: Vec<_> = facets.iter().map(|f| bounding_box(f.map(|n| model.nodes[n]))).collect();
    let grid = FacetGrid::new(&boxes, 50.0);
    for (x, inside) in [([4.0, 0.05 + 1e-12, -1e-9], false), ([4.0, 0.04, -1e-9], true)] {
        let u = slave_at(&model, x);
        let cfg = SurfaceConfig {
            model: &model,
            u: &u,
            t: 0.0,
        };
        let origin = model.nodes[6];
        assert_eq!(
            locate(&cfg, (facets, None), &grid, (6, origin), None, 50.0),
            Some(1),
            "inside: {inside}"
        );
        // from the wall as the facet of the last iterate, too
        assert_eq!(
            locate(&cfg, (facets, None), &grid, (6, origin), Some(0), 50.0),
            Some(1),
            "inside: {inside}"
        );
    }
}

/// Four unit facets around a vertex pressed 0.2 down (a dimple: `[0, 2]²`, the vertex at
/// `(1, 1, −0.2)`, normals up); node 6 the slave.
fn dimple() -> Model<Solid> {
    let mut model = two_facets(false);
    let mut nodes: Vec<[f64; 3]> = (0..9).map(|k| [(k % 3) as f64, (k / 3) as f64, 0.0]).collect();
    nodes[4][2] = -0.2;
    // node 6 is the slave: the grid's node 6 (0, 2) goes to index 9
    nodes.push(nodes[6]);
    nodes[6] = [1.0, 1.0, -0.3];
    let g = |k: usize| if k == 6 { 9 } else { k };
    let pair = &mut model.surface_contacts[0];
    pair.master = SurfaceMaster::Facets {
        body: 0,
        facets: vec![
            [0, 1, 4, 3].map(g),
            [1, 2, 5, 4].map(g),
            [3, 4, 7, 6].map(g),
            [4, 5, 8, 7].map(g),
        ],
    };
    pair.search_radius = 5.0;
    model.nodes = nodes;
    model
}

#[test]
fn a_point_below_a_pressed_vertex_keeps_its_facet() {
    // Below the vertex of a dimple every facet around it is as near (its nearest point is
    // the vertex); the pairing keeps the facet of the last iterate there. It used to look
    // on at how far outside each facet the projection lies, and a Newton iterate a hair
    // aside switched facets: the pole of the twisting hemisphere cycled between two
    // diagonal facets at the block's centre vertex.
    let model = dimple();
    let SurfaceMaster::Facets { facets, .. } = &model.surface_contacts[0].master else {
        unreachable!()
    };
    let boxes: Vec<_> = facets.iter().map(|f| bounding_box(f.map(|n| model.nodes[n]))).collect();
    let grid = FacetGrid::new(&boxes, 5.0);
    let origin = model.nodes[6];
    for x in [[1.0, 1.0, -0.3], [1.0 + 1e-7, 1.0 - 1e-7, -0.3]] {
        let u = slave_at(&model, x);
        let cfg = SurfaceConfig {
            model: &model,
            u: &u,
            t: 0.0,
        };
        for start in 0..4 {
            let got = locate(&cfg, (facets, None), &grid, (6, origin), Some(start), 5.0);
            assert_eq!(got, Some(start), "at {x:?}");
        }
    }
    // a point nearer to one facet goes to it, whatever the last iterate's
    let u = slave_at(&model, [0.4, 0.5, -0.05]);
    let cfg = SurfaceConfig {
        model: &model,
        u: &u,
        t: 0.0,
    };
    assert_eq!(locate(&cfg, (facets, None), &grid, (6, origin), Some(3), 5.0), Some(0));
}

/// A curved master of 2 × 2 facets (a cap of `z = −0.3 (x² + y²)` over `[−1, 1]²`), slave
/// node 9 pressed into it near the edge `x = 0`.
fn cap(smoothing: crate::model::Smoothing) -> Model<Solid> {
    let mut nodes = vec![];
    for j in 0..3 {
        for i in 0..3 {
            let (x, y) = (i as f64 - 1.0, j as f64 - 1.0);
            nodes.push([x, y, -0.3 * (x * x + y * y)]);
        }
    }
    nodes.push([0.05, 0.3, -0.1]);
    let f = |i: usize, j: usize| [3 * j + i, 3 * j + i + 1, 3 * (j + 1) + i + 1, 3 * (j + 1) + i];
    Model {
        nodes,
        surface_contacts: vec![SurfacePair {
            friction: None,
            name: "pair".into(),
            slaves: vec![9],
            areas: vec![1.0],
            measure: Default::default(),
            master: SurfaceMaster::Facets {
                body: 0,
                facets: vec![f(0, 0), f(1, 0), f(0, 1), f(1, 1)],
            },
            law: ContactLaw {
                eps_n: 1e3,
                eps_t: 1e3,
                mu: 0.0,
            },
            transfer: Scheme::Continuous,
            smoothing,
            search_radius: 0.5,
        }],
        ..Model::default()
    }
}

/// The point's residual against central differences over every DOF of the model, with the
/// pairing and the bends as the system makes them (bends of the start, held).
#[test]
fn a_point_on_nagata_patches_has_the_tangent_of_its_residual() {
    use crate::contact3d::decision::SurfaceRule;
    use crate::contact3d::evaluate::{evaluate_point, SearchStart};
    use crate::contact3d::nagata::FacetBends;
    let model = cap(crate::model::Smoothing::Nagata);
    let pair = &model.surface_contacts[0];
    let SurfaceMaster::Facets { facets, .. } = &pair.master else {
        unreachable!()
    };
    let u0 = vec![0.0; 3 * model.nodes.len()];
    let cfg = SurfaceConfig {
        model: &model,
        u: &u0,
        t: 0.0,
    };
    let mut bends = FacetBends::new(facets);
    bends.update(facets, |n| cfg.node(n));
    let boxes: Vec<_> = facets.iter().map(|f| bounding_box(f.map(|n| cfg.node(n)))).collect();
    let grid = FacetGrid::new(&boxes, pair.search_radius);
    let borders = free_borders(facets);
    let residual = |u: &[f64]| {
        let cfg = SurfaceConfig {
            model: &model,
            u,
            t: 0.0,
        };
        let search = SearchStart {
            grid: Some(&grid),
            facet: None,
            closed_at_last_iterate: false,
            borders: &borders,
            bends: Some(&bends),
        };
        let mut local = PointLocal::default();
        let hist = SurfaceHistory::default();
        let ev = evaluate_point(
            &cfg,
            (pair, 0, &hist),
            search,
            1.0,
            (SurfaceRule::Penalty, false),
            &mut local,
        );
        let mut r = vec![0.0; u.len()];
        let mut k = vec![vec![0.0; u.len()]; u.len()];
        for (i, &di) in ev.dofs.iter().enumerate().take(local.len) {
            r[di] += local.r[i];
            for (j, &dj) in ev.dofs.iter().enumerate().take(local.len) {
                k[di][dj] += local.k[local.len * i + j];
            }
        }
        (
            r,
            k,
            (
                ev.now.facet,
                ev.now.eval.map(|e| (e.state, e.projection.gap, e.projection.point.xi)),
            ),
        )
    };
    let (_, k, facet) = residual(&u0);
    eprintln!("facet {facet:?}");
    let h = 1e-6;
    let mut worst: f64 = 0.0;
    for j in 0..u0.len() {
        let (mut up, mut um) = (u0.clone(), u0.clone());
        up[j] += h;
        um[j] -= h;
        let (rp, _, _) = residual(&up);
        let (rm, _, _) = residual(&um);
        for i in 0..u0.len() {
            worst = worst.max(((rp[i] - rm[i]) / (2.0 * h) - k[i][j]).abs());
        }
    }
    let kmax = k.iter().flatten().fold(0.0f64, |a, b| a.max(b.abs()));
    assert!(
        worst < 1e-5 * kmax,
        "tangent against differences: {worst:e} of {kmax:e}"
    );
}
