use super::*;
use crate::contact::transfer::TransferKind::*;

const LAW: ContactLaw = ContactLaw {
    eps_n: 2.1e3,
    eps_t: 1.7e3,
    mu: 0.3,
};

/// Slots: 0 slave, 1–2 segment B, 3 the far node of A (A = [3, 1]).
fn base(scheme: TransferKind, law: ContactLaw, stored_t1: f64) -> PointProblem {
    let mut x = [[0.0; 2]; MAX_NODES];
    x[0] = [0.31, 0.02]; // slave, slightly above the bottom face -> penetrated
    x[1] = [0.0, 0.001];
    x[2] = [0.8, -0.01];
    x[3] = [-0.5, 0.004];
    PointProblem {
        law,
        scheme,
        x,
        n_nodes: 4,
        slave: SlaveSource::Node(0),
        seg_b: SegSource::Face([1, 2]),
        closed: Some(Closed {
            stored: StoredTraction {
                xi: 0.93,
                t1: stored_t1,
                a11: 0.0626,
                slave: [f64::NAN; 2],
                tangent: [f64::NAN; 2],
            },
            seg_a: SegSource::Face([3, 1]),
            path: Path {
                direction: 1,
                between: 0.0,
            },
            touch_gap: None,
        }),
        rule: crate::contact::decision::Rule::Penalty,
        kink: crate::contact::decision::Kink::Open,
        warm: false,
        at_vertex: None,
        multiplier: None,
    }
}

pub(super) fn fd_check(p: &PointProblem, expect: ContactState) {
    fd_check_at(p, expect, 1e-5);
}

/// [`fd_check`] with a relative tolerance `tol` on the tangent's entries.
pub(super) fn fd_check_at(p: &PointProblem, expect: ContactState, tol: f64) {
    let n = 2 * p.n_nodes;
    let mut r = vec![0.0; n];
    let mut k = vec![0.0; n * n];
    let e = p.residual_tangent(&mut r, &mut k);
    assert_eq!(e.state, expect, "state");
    let h = 1e-7;
    let kmax = k.iter().fold(1e-30f64, |a, b| a.max(b.abs()));
    for j in 0..n {
        let mut pp = *p;
        let mut pm = *p;
        pp.x[j / 2][j % 2] += h;
        pm.x[j / 2][j % 2] -= h;
        let mut rp = vec![0.0; n];
        let mut rm = vec![0.0; n];
        let mut kk = vec![0.0; n * n];
        assert_eq!(pp.residual_tangent(&mut rp, &mut kk).state, expect);
        assert_eq!(pm.residual_tangent(&mut rm, &mut kk).state, expect);
        for i in 0..n {
            let fd = (rp[i] - rm[i]) / (2.0 * h);
            assert!(
                (fd - k[n * i + j]).abs() < tol * kmax,
                "{:?} {expect:?}: K[{i},{j}] = {} vs FD {fd}",
                p.scheme,
                k[n * i + j]
            );
        }
    }
}

#[test]
fn crossing_step_tangent_matches_fd_for_every_scheme_stick_and_slip() {
    for scheme in [Straightforward, Continuous, PathLength] {
        // big friction coefficient: stays in stick
        fd_check(&base(scheme, ContactLaw { mu: 1e3, ..LAW }, 0.8), ContactState::Stick);
        // small friction coefficient: slips
        fd_check(&base(scheme, ContactLaw { mu: 0.05, ..LAW }, 0.8), ContactState::Slip);
    }
}

#[test]
fn same_segment_stick_slip_frictionless_and_first_closing_tangents_match_fd() {
    for scheme in [Straightforward, Continuous, PathLength] {
        let mut p = base(scheme, ContactLaw { mu: 1e3, ..LAW }, 0.3);
        let c = p.closed.as_mut().unwrap();
        c.seg_a = SegSource::Face([1, 2]);
        c.stored.xi = -0.1;
        c.path = Path {
            direction: 0,
            between: 0.0,
        };
        fd_check(&p, ContactState::Stick);
        p.law.mu = 0.01;
        fd_check(&p, ContactState::Slip);
        p.law.mu = 0.0;
        fd_check(&p, ContactState::Slip);
        p.law.mu = 0.3;
        p.closed = None;
        fd_check(&p, ContactState::Stick);
    }
}

#[test]
fn first_touch_tangents_match_fd_and_anchor_at_the_touch_point() {
    for scheme in [Straightforward, Continuous, PathLength] {
        for (mu, state) in [(1e3, ContactState::Stick), (0.01, ContactState::Slip)] {
            let mut p = base(scheme, ContactLaw { mu, ..LAW }, 0.0);
            let c = p.closed.as_mut().unwrap();
            c.touch_gap = Some(0.004);
            fd_check(&p, state);
            // forward crossing too (A = [3, 1], B = [1, 2]): same kernel, other path
            let c = p.closed.as_mut().unwrap();
            c.seg_a = SegSource::Face([1, 2]);
            c.stored.xi = -0.1;
            c.path = Path {
                direction: 0,
                between: 0.0,
            };
            fd_check(&p, state);
        }
    }
    // on one segment the stick trial is exactly −ε_T a11 (ξ − ξ_touch)
    let mut p = base(Continuous, ContactLaw { mu: 1e3, ..LAW }, 0.0);
    let c = p.closed.as_mut().unwrap();
    c.seg_a = SegSource::Face([1, 2]);
    c.stored.xi = -0.1;
    c.path = Path {
        direction: 0,
        between: 0.0,
    };
    let g0 = 0.004;
    c.touch_gap = Some(g0);
    let e = p.evaluate_f64();
    let s = g0 / (g0 - e.proj.gap);
    let xi_touch = -0.1 + s * (e.proj.xi + 0.1);
    let expect = -LAW.eps_t * e.proj.a11 * (e.proj.xi - xi_touch);
    assert!(
        (e.t1_trial - expect).abs() < 1e-10 * expect.abs(),
        "{} vs {expect}",
        e.t1_trial
    );
}

#[test]
fn backward_crossing_and_rigid_slave_tangents_match_fd() {
    for scheme in [Straightforward, Continuous, PathLength] {
        let mut p = base(scheme, ContactLaw { mu: 1e3, ..LAW }, -0.5);
        // A = [2, 3] lies after B: the point moved backwards; make slot 3 the far end
        p.x[3] = [1.6, -0.02];
        let c = p.closed.as_mut().unwrap();
        c.seg_a = SegSource::Face([2, 3]);
        c.stored.xi = -0.9;
        c.path = Path {
            direction: -1,
            between: 0.0,
        };
        fd_check(&p, ContactState::Stick);
        // rigid slave point: slots shift down by one
        let mut q = p;
        q.x = [[0.0; 2]; MAX_NODES];
        q.x[..3].copy_from_slice(&p.x[1..4]);
        q.n_nodes = 3;
        q.slave = SlaveSource::Fixed(p.x[0]);
        q.seg_b = SegSource::Face([0, 1]);
        q.closed.as_mut().unwrap().seg_a = SegSource::Face([1, 2]);
        fd_check(&q, ContactState::Stick);
    }
}

#[test]
fn rigid_arc_master_tangent_matches_fd() {
    let arc = Piece::Arc {
        centre: [0.0, 1.0],
        radius: 1.0,
        theta0: -2.5,
        theta1: -0.6,
    };
    let mut x = [[0.0; 2]; MAX_NODES];
    x[0] = [0.2, 0.03];
    let mut p = PointProblem {
        law: ContactLaw { mu: 1e3, ..LAW },
        scheme: Continuous,
        x,
        n_nodes: 1,
        slave: SlaveSource::Node(0),
        seg_b: SegSource::Rigid(arc, [0.0, 0.0]),
        closed: Some(Closed {
            stored: StoredTraction {
                xi: 0.1,
                t1: 0.01,
                a11: 0.9,
                slave: [f64::NAN; 2],
                tangent: [f64::NAN; 2],
            },
            seg_a: SegSource::Rigid(arc, [0.0, 0.0]),
            path: Path {
                direction: 0,
                between: 0.0,
            },
            touch_gap: None,
        }),
        rule: crate::contact::decision::Rule::Penalty,
        kink: crate::contact::decision::Kink::Open,
        warm: false,
        at_vertex: None,
        multiplier: None,
    };
    fd_check(&p, ContactState::Stick);
    p.law.mu = 0.01;
    fd_check(&p, ContactState::Slip);
}

#[test]
fn open_point_has_no_contribution() {
    let mut p = base(Continuous, LAW, 0.0);
    p.x[0] = [0.31, -0.2];
    let mut r = vec![1.0; 8];
    let mut k = vec![1.0; 64];
    let e = p.residual_tangent(&mut r, &mut k);
    assert_eq!(e.state, ContactState::Open);
    assert!(r.iter().chain(k.iter()).all(|v| *v == 0.0));
}

#[test]
fn slave_force_is_normal_push_plus_traction() {
    // rigid flat master (bottom face of a rigid body above), deformable slave below it
    let seg = Piece::Segment {
        a: [0.0, 0.0],
        b: [2.0, 0.0],
    };
    let mut x = [[0.0; 2]; MAX_NODES];
    x[0] = [1.5, 0.01];
    let p = PointProblem {
        law: ContactLaw {
            eps_n: 100.0,
            eps_t: 50.0,
            mu: 10.0,
        },
        scheme: Continuous,
        x,
        n_nodes: 1,
        slave: SlaveSource::Node(0),
        seg_b: SegSource::Rigid(seg, [0.0, 0.0]),
        closed: Some(Closed {
            stored: StoredTraction {
                xi: 0.4,
                t1: 0.0,
                a11: 1.0,
                slave: [f64::NAN; 2],
                tangent: [f64::NAN; 2],
            },
            seg_a: SegSource::Rigid(seg, [0.0, 0.0]),
            path: Path {
                direction: 0,
                between: 0.0,
            },
            touch_gap: None,
        }),
        rule: crate::contact::decision::Rule::Penalty,
        kink: crate::contact::decision::Kink::Open,
        warm: false,
        at_vertex: None,
        multiplier: None,
    };
    let mut r = [0.0; 2];
    let mut k = [0.0; 4];
    let e = p.residual_tangent(&mut r, &mut k);
    // penetration 0.01 along −n = +y: force on slave (−r) pushes out along n = −y by ε_N·0.01
    assert!((-r[1] + 1.0).abs() < 1e-12);
    // slid +0.1 in x from the anchor: friction on the slave is −ε_T·0.1 in x
    assert!((-r[0] + 5.0).abs() < 1e-12, "{r:?}");
    assert!((e.t1 + 5.0).abs() < 1e-12);
}

/// Under the augmented rule with the force unknowns at the penalty's own forces the point
/// is the penalty's: same state, and the condensed tangent is the derivative of the
/// residual (its Hessian terms are weighted by the unknowns, equal to the penalty forces).
#[test]
fn augmented_rule_at_the_penalty_forces_has_the_penalty_tangent() {
    use crate::contact::decision::{Forces, Rule};
    for (mu, state) in [(1e3, ContactState::Stick), (0.3, ContactState::Slip)] {
        let mut p = base(Continuous, ContactLaw { mu, ..LAW }, 0.8);
        let e = p.evaluate_f64();
        assert_eq!(e.state, state);
        p.rule = Rule::AlartCurnier {
            forces: Forces {
                normal: e.normal_force,
                tangential: e.t1 / e.proj.a11.sqrt(),
            },
            rho_n: 1e-3,
            rho_t: 1e-3,
        };
        // the unknowns are held while the positions move: only the points' own state
        assert_eq!(p.evaluate_f64().state, state);
        assert!(p.evaluate_f64().complementarity.iter().all(|c| c.abs() < 1e-12));
        fd_check_at(&p, state, 1e-6);
    }
}

/// A point whose force unknown carries load stays closed under the augmented rule though
/// its gap has opened a little (the penalty would open it), and says by how much its
/// unknown and the penalty force differ.
#[test]
fn a_force_unknown_that_carries_load_keeps_its_point_closed() {
    use crate::contact::decision::{Forces, Rule};
    let mut p = base(Continuous, ContactLaw { mu: 1e3, ..LAW }, 0.8);
    p.x[0][1] -= 0.03; // the slave on the other side of the face: open by the penalty rule
    assert_eq!(p.evaluate_f64().state, ContactState::Open);
    let rho = 1e-4;
    p.rule = Rule::AlartCurnier {
        forces: Forces {
            normal: 1.0,
            tangential: 0.0,
        },
        rho_n: rho,
        rho_t: rho,
    };
    let e = p.evaluate_f64();
    assert_ne!(e.state, ContactState::Open);
    // C_N = ρ (N − N_ε), N_ε = −ε ζ < 0 here
    assert!((e.complementarity[0] - rho * (1.0 - e.normal_force)).abs() < 1e-12 && e.normal_force < 0.0);
}

/// Wedge of a concave vertex: A = [3, 1] rises to the vertex (slot 1), B = [1, 2] falls from
/// it, the body is above; the slave sits just above the vertex, past the end of A and
/// before the start of B. Tracked on A, pinned to A's end (`ξ = +1`).
fn wedge(mu: f64, slave: [f64; 2]) -> PointProblem {
    let mut p = base(Continuous, ContactLaw { mu, ..LAW }, 0.0);
    p.x[1] = [0.0, 0.01];
    p.x[2] = [0.8, 0.0];
    p.x[3] = [-0.5, 0.0];
    p.x[0] = slave;
    p.seg_b = SegSource::Face([3, 1]);
    let c = p.closed.as_mut().unwrap();
    c.seg_a = SegSource::Face([3, 1]);
    c.stored = StoredTraction {
        xi: 0.7,
        t1: 0.6,
        a11: 0.0626,
        slave: [f64::NAN; 2],
        tangent: [f64::NAN; 2],
    };
    c.path = Path {
        direction: 0,
        between: 0.0,
    };
    p.at_vertex = Some(1.0);
    p
}

#[test]
fn point_pinned_to_a_concave_vertex_has_fd_consistent_tangents() {
    let inside = [0.00002, 0.015];
    let unpinned = PointProblem {
        at_vertex: None,
        multiplier: None,
        ..wedge(0.3, inside)
    };
    let e = unpinned.evaluate_f64();
    assert!(e.proj.xi > 1.0 && e.proj.gap < 0.0, "past the end of A: {:?}", e.proj);
    fd_check(&wedge(1e3, inside), ContactState::Stick);
    fd_check(&wedge(0.01, inside), ContactState::Slip);
    fd_check(&wedge(0.0, inside), ContactState::Slip);
    // rigid slave (the corner C) pinned to a node of the face
    let mut q = wedge(1e3, inside);
    let moved = [q.x[1], q.x[2], q.x[3]];
    q.x = [[0.0; 2]; MAX_NODES];
    q.x[..3].copy_from_slice(&moved);
    q.n_nodes = 3;
    q.slave = SlaveSource::Fixed(inside);
    q.seg_b = SegSource::Face([2, 0]);
    q.closed.as_mut().unwrap().seg_a = SegSource::Face([2, 0]);
    fd_check(&q, ContactState::Stick);
    // the pinned gap is the distance to the vertex, the normal force a spring to it
    let e = wedge(0.0, inside).evaluate_f64();
    let d = (inside[0] * inside[0] + (inside[1] - 0.01) * (inside[1] - 0.01f64)).sqrt();
    assert!((e.proj.gap + d).abs() < 1e-15 && e.proj.xi == 1.0);
}

/// At the boundary of the wedge (slave on A's normal through the vertex) the pinned and the
/// node-to-segment forms give the same residual on the slave for every friction coefficient,
/// and on the master nodes without friction; with friction the share of A's two nodes
/// differs by `O(t ζ / l)` (A's rotation moves the projected point, not the vertex).
#[test]
fn pinned_and_segment_forms_agree_at_the_boundary_of_the_wedge() {
    // A's unit normal into the body (left of the direction 3 → 1)
    let (a, b): ([f64; 2], [f64; 2]) = ([-0.5, 0.0], [0.0, 0.01]);
    let l = ((b[0] - a[0]) * (b[0] - a[0]) + (b[1] - a[1]) * (b[1] - a[1])).sqrt();
    let inward = [-(b[1] - a[1]) / l, (b[0] - a[0]) / l];
    let depth = 0.004;
    let on_normal = [b[0] + depth * inward[0], b[1] + depth * inward[1]];
    for mu in [0.0, 0.01, 1e3] {
        let pinned = wedge(mu, on_normal);
        let segment = PointProblem {
            at_vertex: None,
            multiplier: None,
            ..pinned
        };
        assert!((segment.evaluate_f64().proj.xi - 1.0).abs() < 1e-12);
        let (mut rp, mut rs) = ([0.0; 8], [0.0; 8]);
        let mut k = [0.0; 64];
        let ep = pinned.residual_tangent(&mut rp, &mut k);
        let es = segment.residual_tangent(&mut rs, &mut k);
        assert_eq!(ep.state, es.state);
        let scale = rs.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let t = es.t1.abs() / es.proj.a11.sqrt();
        for i in 0..8 {
            let exact = i < 2 || mu == 0.0;
            let bound = if exact {
                1e-9 * scale
            } else {
                2.0 * t * depth / l + 1e-9 * scale
            };
            assert!(
                (rp[i] - rs[i]).abs() <= bound,
                "mu {mu} dof {i}: {} vs {}",
                rp[i],
                rs[i]
            );
        }
    }
}

/// A rigid vertex (slave) on a C1-smoothed face: slots 1–5 are five face nodes on a bent
/// face, `A` = Hermite([1, 2] with neighbours 0→slot 1's predecessor), `B` the next segment.
fn hermite_base(law: ContactLaw, crossing: bool) -> PointProblem {
    let mut x = [[0.0; 2]; MAX_NODES];
    // a face bent downwards (body above, face running +x: outward normal −y)
    x[1] = [-0.9, 0.12];
    x[2] = [-0.3, 0.02];
    x[3] = [0.3, 0.0];
    x[4] = [0.85, 0.05];
    x[5] = [1.3, 0.16];
    let seg_a = SegSource::Hermite([Some(1), Some(2), Some(3), Some(4)]);
    let seg_b = SegSource::Hermite([Some(2), Some(3), Some(4), Some(5)]);
    PointProblem {
        law,
        scheme: TransferKind::Continuous,
        x,
        n_nodes: 6,
        slave: SlaveSource::Node(0),
        seg_b,
        closed: Some(Closed {
            stored: StoredTraction {
                xi: if crossing { 0.9 } else { -0.4 },
                t1: 0.02,
                a11: 0.09,
                slave: [f64::NAN; 2],
                tangent: [f64::NAN; 2],
            },
            seg_a: if crossing { seg_a } else { seg_b },
            path: Path {
                direction: i8::from(crossing),
                between: 0.0,
            },
            touch_gap: None,
        }),
        rule: crate::contact::decision::Rule::Penalty,
        kink: crate::contact::decision::Kink::Open,
        warm: false,
        at_vertex: None,
        multiplier: None,
    }
}

#[test]
fn hermite_face_tangents_match_fd_in_every_state() {
    for crossing in [false, true] {
        let mut p = hermite_base(ContactLaw { mu: 1e3, ..LAW }, crossing);
        p.x[0] = [0.45, 0.008]; // slave just inside the face near x = 0.45
        fd_check(&p, ContactState::Stick);
        p.law.mu = 0.01;
        fd_check(&p, ContactState::Slip);
        p.law.mu = 0.0;
        fd_check(&p, ContactState::Slip);
        p.law.mu = 0.3;
        p.closed = None;
        fd_check(&p, ContactState::Stick);
    }
    // a rigid slave (a vertex of a rigid outline) on the smoothed face: the face's nodes only
    let mut p = hermite_base(ContactLaw { mu: 0.01, ..LAW }, true);
    let slave = [0.45, 0.008];
    p.x.copy_within(1..6, 0);
    p.x[5] = [0.0; 2];
    p.n_nodes = 5;
    p.slave = SlaveSource::Fixed(slave);
    p.seg_b = SegSource::Hermite([Some(1), Some(2), Some(3), Some(4)]);
    p.closed.as_mut().unwrap().seg_a = SegSource::Hermite([Some(0), Some(1), Some(2), Some(3)]);
    fd_check(&p, ContactState::Slip);
}

#[test]
fn fixed_coordinate_scale_is_the_rigid_geometry_entering_the_gap() {
    // every coordinate a node: nothing fixed
    assert_eq!(base(Continuous, LAW, 0.0).fixed_coordinate_scale(), 0.0);
    // an arc of radius 1 centred 1 above, offset by (3, 4): |c + o| + R = 5 + 1
    let arc = Piece::Arc {
        centre: [0.0, 1.0],
        radius: 1.0,
        theta0: -2.5,
        theta1: -0.6,
    };
    let mut p = base(Continuous, LAW, 0.0);
    p.seg_b = SegSource::Rigid(arc, [3.0, 3.0]);
    assert!((p.fixed_coordinate_scale() - 6.0).abs() < 1e-12);
    // a straight piece: its farther end; a rigid slave point: its distance from the origin
    p.seg_b = SegSource::Rigid(
        Piece::Segment {
            a: [-1.0, 0.0],
            b: [7.0, 0.0],
        },
        [1.0, 0.0],
    );
    assert_eq!(p.fixed_coordinate_scale(), 8.0);
    p.slave = SlaveSource::Fixed([0.0, -9.0]);
    assert_eq!(p.fixed_coordinate_scale(), 9.0);
}
