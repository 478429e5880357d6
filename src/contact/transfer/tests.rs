//! Unit behaviour of the schemes on two collinear segments of unequal length:
//! `A` from (−1, 0) to (0, 0) (ℓ = 1), `B` from (0, 0) to (2, 0) (ℓ = 2); the slave was at
//! x = −0.1 on `A` (ξ_A = 0.8) with physical traction τ and is now at x = 0.2 on `B`
//! (ξ_B = −0.8): the true slip is 0.3, so the exact trial traction is τ − 0.3 ε_T.

use crate::contact::law::ContactLaw;
use crate::contact::point::{Closed, Path, PointProblem, SegSource, SlaveSource, MAX_NODES};
use crate::contact::transfer::{StoredTraction, TransferKind};

const EPS_T: f64 = 1.0e3;
const TAU: f64 = 7.0;

fn problem(scheme: TransferKind, slave_x: f64, same_segment: bool) -> PointProblem {
    let mut x = [[0.0; 2]; MAX_NODES];
    x[0] = [-1.0, 0.0];
    x[1] = [0.0, 0.0];
    x[2] = [2.0, 0.0];
    let a11_a: f64 = 0.25;
    PointProblem {
        law: ContactLaw {
            eps_n: 1e4,
            eps_t: EPS_T,
            mu: 1e6,
        },
        scheme,
        x,
        n_nodes: 3,
        slave: SlaveSource::Fixed([slave_x, 1e-3]),
        seg_b: if same_segment {
            SegSource::Face([0, 1])
        } else {
            SegSource::Face([1, 2])
        },
        closed: Some(Closed {
            stored: StoredTraction {
                xi: 0.8,
                t1: TAU * a11_a.sqrt(),
                a11: a11_a,
                // the old slave position (x = −0.1, on A) for the spatial scheme
                slave: [-0.1, 1e-3],
                tangent: [1.0, 0.0],
            },
            seg_a: SegSource::Face([0, 1]),
            path: Path {
                direction: if same_segment { 0 } else { 1 },
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

fn physical_trial(p: &PointProblem) -> f64 {
    let e = p.evaluate_f64();
    e.t1_trial / e.proj.a11.sqrt()
}

#[test]
fn continuous_path_length_and_spatial_give_the_exact_trial_across_the_boundary() {
    for s in [
        TransferKind::Continuous,
        TransferKind::PathLength,
        TransferKind::Spatial,
    ] {
        let t = physical_trial(&problem(s, 0.2, false));
        assert!((t - (TAU - 0.3 * EPS_T)).abs() < 1e-9 * EPS_T, "{s:?}: {t}");
    }
}

#[test]
fn straightforward_jumps_by_the_predicted_amount() {
    let t = physical_trial(&problem(TransferKind::Straightforward, 0.2, false));
    // T_1^(n)/√a11^B − ε_T √a11^B (ξ_B − ξ_A) with a11^B = 1, ξ_B − ξ_A = −1.6
    let predicted = TAU * 0.5 + 1.6 * EPS_T;
    assert!((t - predicted).abs() < 1e-9 * EPS_T, "{t} vs {predicted}");
    let exact = TAU - 0.3 * EPS_T;
    assert!((t - exact).abs() > 1.8 * EPS_T, "the jump is about 2 ε_T in ξ-units");
}

#[test]
fn every_scheme_reduces_to_seed_eq_1_on_one_segment() {
    // slave stays on A: x = −0.3 (ξ = 0.4), slip −0.2 → trial τ + 0.2 ε_T
    for s in [
        TransferKind::Straightforward,
        TransferKind::Continuous,
        TransferKind::PathLength,
        TransferKind::Spatial,
    ] {
        let t = physical_trial(&problem(s, -0.3, true));
        assert!((t - (TAU + 0.2 * EPS_T)).abs() < 1e-9 * EPS_T, "{s:?}: {t}");
    }
}

#[test]
fn continuous_anchor_follows_seed_eq_4() {
    // The anchor derived from the transferred traction, ξ_sl^B = ξ_B + T_1/(ε_T a11^B), is the
    // old anchor ξ_sl^A = ξ_A + T_1^(n)/(ε_T a11^A) translated onto B (same point in space).
    let p = problem(TransferKind::Continuous, 0.2, false);
    let e = p.evaluate_f64();
    let anchor_b = e.proj.xi + e.t1_trial / (EPS_T * e.proj.a11);
    let st = p.closed.unwrap().stored;
    let anchor_a = st.xi + st.t1 / (EPS_T * st.a11);
    let xa = -0.5 + 0.5 * anchor_a; // position on A
    let xb = 1.0 + anchor_b; // position on B
    assert!((xa - xb).abs() < 1e-12, "{xa} vs {xb}");
}

/// The spatial scheme measures the slave's motion over the *current* master: a slave that
/// stays put while the master slides under it sees no slip, where every segment-based
/// scheme sees the master's motion (here 0.3 to the left: the slave slid +0.3 over it).
#[test]
fn spatial_does_not_see_a_master_sliding_under_a_fixed_slave() {
    let moved = |scheme| {
        let mut p = problem(scheme, -0.1, true);
        for x in &mut p.x[..3] {
            x[0] -= 0.3;
        }
        // the slave stays at x = −0.1, now at ξ = 0.2 + 0.6 − 1 … of the moved A
        physical_trial(&p)
    };
    for s in [
        TransferKind::Straightforward,
        TransferKind::Continuous,
        TransferKind::PathLength,
    ] {
        let t = moved(s);
        assert!((t - (TAU - 0.3 * EPS_T)).abs() < 1e-9 * EPS_T, "{s:?}: {t}");
    }
    let t = moved(TransferKind::Spatial);
    assert!((t - TAU).abs() < 1e-9 * EPS_T, "spatial: {t}");
}
