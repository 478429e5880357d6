//! Finite-difference checks of the kernel's tangent for the methods the seed compares
//! against: every transfer scheme (the spatial one included) on faceted, Hermite- and
//! Bézier-smoothed faces, in every state (stick, slip, frictionless, first closing, first
//! touch; same segment, forward and backward crossing; a free end), and with augmented-
//! Lagrangian multipliers (a point held closed by `λ_N` at a positive gap).

use super::tests::fd_check;
use super::*;
use crate::contact::transfer::TransferKind::*;

const LAW: ContactLaw = ContactLaw {
    eps_n: 2.1e3,
    eps_t: 1.7e3,
    mu: 0.3,
};

#[derive(Debug, Clone, Copy, PartialEq)]
enum Face {
    Faceted,
    Hermite,
    Bezier,
}

/// Slots 1–6: the nodes of a bent face (body above, running +x: outward normal −y);
/// segment `a` runs from slot `a` to `a + 1`, `a ∈ 1..=5`. Slot 0 is the slave.
fn segment(face: Face, a: usize) -> SegSource {
    let nb = [(a > 1).then(|| a - 1), Some(a), Some(a + 1), (a < 5).then_some(a + 2)];
    match face {
        Face::Faceted => SegSource::Face([a, a + 1]),
        Face::Hermite => SegSource::Hermite(nb),
        Face::Bezier => SegSource::Bezier(nb),
    }
}

/// How the point got to segment 3 (slots 3 → 4) since the last converged increment.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Came {
    /// It was on segment 3 already.
    Same,
    /// From segment 2 (forward crossing).
    Forward,
    /// From segment 4 (backward crossing).
    Backward,
}

fn problem(face: Face, scheme: TransferKind, came: Came, mu: f64) -> PointProblem {
    let mut x = [[0.0; 2]; MAX_NODES];
    x[0] = [0.45, 0.03];
    x[1] = [-0.9, 0.12];
    x[2] = [-0.3, 0.02];
    x[3] = [0.3, 0.0];
    x[4] = [0.85, 0.05];
    x[5] = [1.3, 0.16];
    x[6] = [1.7, 0.3];
    let (seg_a, xi, direction) = match came {
        Came::Same => (3, -0.2, 0),
        Came::Forward => (2, 0.9, 1),
        Came::Backward => (4, -0.9, -1),
    };
    PointProblem {
        law: ContactLaw { mu, ..LAW },
        scheme,
        x,
        n_nodes: 7,
        slave: SlaveSource::Node(0),
        seg_b: segment(face, 3),
        closed: Some(Closed {
            stored: StoredTraction {
                xi,
                t1: 0.02,
                a11: 0.08,
                slave: [0.25, 0.028],
                tangent: [0.998, 0.0632],
            },
            seg_a: segment(face, seg_a),
            path: Path {
                direction,
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

const FACES: [Face; 3] = [Face::Faceted, Face::Hermite, Face::Bezier];
const SCHEMES: [TransferKind; 4] = [Straightforward, Continuous, PathLength, Spatial];
const CAME: [Came; 3] = [Came::Same, Came::Forward, Came::Backward];

#[test]
fn every_scheme_on_every_face_has_consistent_tangents_in_stick_slip_and_frictionless() {
    for face in FACES {
        for scheme in SCHEMES {
            for came in CAME {
                let what = format!("{face:?} {scheme:?} {came:?}");
                let p = problem(face, scheme, came, 1e3);
                assert!(
                    p.evaluate_f64().proj.xi.abs() < 1.0,
                    "{what}: the slave is over segment 3"
                );
                fd_check(&p, ContactState::Stick);
                fd_check(&problem(face, scheme, came, 0.01), ContactState::Slip);
                fd_check(&problem(face, scheme, came, 0.0), ContactState::Slip);
            }
            // first closing increment (no history: frictionless, stick state)
            let mut p = problem(face, scheme, Came::Same, 0.3);
            p.closed = None;
            fd_check(&p, ContactState::Stick);
        }
    }
}

#[test]
fn first_touch_and_free_end_tangents_match_fd_on_smoothed_faces() {
    for face in FACES {
        for scheme in SCHEMES {
            for (mu, state) in [(1e3, ContactState::Stick), (0.01, ContactState::Slip)] {
                for came in CAME {
                    let mut p = problem(face, scheme, came, mu);
                    p.closed.as_mut().unwrap().touch_gap = Some(0.004);
                    p.closed.as_mut().unwrap().stored.t1 = 0.0;
                    fd_check(&p, state);
                }
                // segment 5 ends the face: slave over it, near its free end
                let mut p = problem(face, scheme, Came::Same, mu);
                p.x[0] = [1.62, 0.3];
                p.seg_b = segment(face, 5);
                let c = p.closed.as_mut().unwrap();
                c.seg_a = segment(face, 5);
                c.stored.xi = 0.1;
                let e = p.evaluate_f64();
                assert!(e.proj.xi > 0.5 && e.proj.xi < 1.0, "{face:?}: ξ = {}", e.proj.xi);
                fd_check(&p, state);
            }
        }
    }
}

/// An augmented point: `N = λ_N − ε_N ζ`, the trial traction shifted by `Λ √a11`. A point
/// just outside the face (ζ > 0) is still closed while `λ_N > ε_N ζ`.
#[test]
fn augmented_points_have_consistent_tangents_also_at_a_positive_gap() {
    let m = Multiplier {
        normal: 5.0,
        tangential: 0.3,
    };
    for face in FACES {
        for scheme in SCHEMES {
            for came in CAME {
                for (mu, state) in [
                    (1e3, ContactState::Stick),
                    (0.01, ContactState::Slip),
                    (0.0, ContactState::Slip),
                ] {
                    let mut p = problem(face, scheme, came, mu);
                    p.multiplier = Some(m);
                    fd_check(&p, state);
                    // lift the slave out of the face by 1e-3 along the normal
                    let e = p.evaluate_f64();
                    let n = e.proj.normal();
                    let out = 1e-3 - e.proj.gap;
                    p.x[0] = [p.x[0][0] + out * n[0], p.x[0][1] + out * n[1]];
                    let e = p.evaluate_f64();
                    assert!(e.proj.gap > 0.0 && e.state == state, "{face:?} {scheme:?}: {e:?}");
                    assert!((e.normal_force - (m.normal - LAW.eps_n * e.proj.gap)).abs() < 1e-12);
                    fd_check(&p, state);
                    // without the multiplier it is open
                    p.multiplier = None;
                    assert_eq!(p.evaluate_f64().state, ContactState::Open);
                }
            }
        }
    }
}

/// The carried traction (`ε_T = 0`) plus `Λ √a11` is what the Uzawa update measures against:
/// in stick the returned traction minus it is `−ε_T` times the slip of the increment.
#[test]
fn augmented_carried_traction_is_the_trial_without_this_increments_slip() {
    let m = Multiplier {
        normal: 1.0,
        tangential: 0.3,
    };
    for scheme in SCHEMES {
        let mut p = problem(Face::Faceted, scheme, Came::Same, 1e3);
        p.multiplier = Some(m);
        let e = p.evaluate_f64();
        let mut q = p;
        q.law.eps_t = 0.0;
        q.law.mu = 0.0;
        let carried = q.scheme.trial(&q.transfer_input(
            q.closed.as_ref().unwrap(),
            &q.x[..q.n_nodes],
            &seg_geom(&q.seg_b, &q.x[..q.n_nodes]),
            e.proj,
        ));
        let expect = carried + e.proj.a11.sqrt() * m.tangential;
        assert!(
            (e.t1_carried - expect).abs() < 1e-12,
            "{scheme:?}: {} vs {expect}",
            e.t1_carried
        );
        // penalty points do not work it out
        p.multiplier = None;
        assert_eq!(p.evaluate_f64().t1_carried, 0.0);
    }
}
