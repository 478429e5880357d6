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
            },
            seg_a: SegSource::Face([3, 1]),
            path: Path {
                direction: 1,
                between: 0.0,
            },
            touch_gap: None,
        }),
        forced: None,
    }
}

fn fd_check(p: &PointProblem, expect: ContactState) {
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
                (fd - k[n * i + j]).abs() < 1e-5 * kmax,
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
        q.x = [p.x[1], p.x[2], p.x[3], [0.0; 2], [0.0; 2]];
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
            },
            seg_a: SegSource::Rigid(arc, [0.0, 0.0]),
            path: Path {
                direction: 0,
                between: 0.0,
            },
            touch_gap: None,
        }),
        forced: None,
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
            },
            seg_a: SegSource::Rigid(seg, [0.0, 0.0]),
            path: Path {
                direction: 0,
                between: 0.0,
            },
            touch_gap: None,
        }),
        forced: None,
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
