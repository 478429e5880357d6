//! History transfer across a facet edge: the 3D version of the seed's Fig. 4 argument.

use super::point::{History, PointProblem};
use super::surface::Facet;
use super::transfer::{map_point, transfer, Scheme};
use super::vec3::{dot, norm, sub};
use crate::contact::law::ContactState;
use crate::model::ContactLaw;

/// `A`: the unit square in `z = 0`, node 1 at the origin, `ξ¹` along `x`.
fn facet_a() -> Facet<f64> {
    Facet {
        x: [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]],
        bend: None,
    }
}

/// `B`: the rectangle `[1, 3] × [0, 1]` in `z = 0` beside `A` (shared edge `x = 1`), twice
/// as long, its node 1 at `(3, 0)` so that `ξ¹` runs along `+y` and `ξ²` along `−x`
/// (`ρ_1 = (0, ½, 0)`, `ρ_2 = (−1, 0, 0)`); still counter-clockwise from `+z`.
fn facet_b_turned() -> Facet<f64> {
    Facet {
        x: [[3.0, 0.0, 0.0], [3.0, 1.0, 0.0], [1.0, 1.0, 0.0], [1.0, 0.0, 0.0]],
        bend: None,
    }
}

/// `B` as above with the same axes as `A` (node 1 at `(1, 0)`), only larger.
fn facet_b_aligned() -> Facet<f64> {
    Facet {
        x: [[1.0, 0.0, 0.0], [3.0, 0.0, 0.0], [3.0, 1.0, 0.0], [1.0, 1.0, 0.0]],
        bend: None,
    }
}

const HIST: History = History {
    xi: [0.9, 0.2],
    traction: [0.7, -0.4],
};

fn vector(f: &Facet<f64>, h: &History) -> [f64; 3] {
    f.point(h.xi).unwrap().vector(h.traction)
}

/// Coplanar facets, different parametrisation: the continuous transfer keeps the spatial
/// traction vector `t = T_α ρ^α` and the old point's position `ρ(ξ_(n))` (1e-14 relative;
/// seed eq. 3 with `ρ^A_i·ρ^j_B` as the change of basis), and so does the literal seed
/// eq. (3) (`ContinuousProjected`: identical on coplanar facets). Straightforward keeps the
/// numbers `T_α` and `ξ`, which in `B`'s basis are another vector (relative change ≥ 0.3: 1.5
/// on the turned `B`, 0.43 on the aligned one, twice as long) at another place (≥ 0.5 away).
/// Path length keeps `t` where the unit frames agree (aligned `B`) and turns it with the
/// local axes (turned `B`). Figures printed.
#[test]
fn coplanar_transfer_keeps_the_traction_vector() {
    let a = facet_a();
    let t_a = vector(&a, &HIST);
    let x_a = a.position(HIST.xi);
    for (name, b) in [("turned", facet_b_turned()), ("aligned", facet_b_aligned())] {
        for scheme in [
            Scheme::Continuous,
            Scheme::ContinuousProjected,
            Scheme::Straightforward,
            Scheme::PathLength,
        ] {
            let h = transfer(scheme, &a, &HIST, &b).unwrap();
            let dt = norm(sub(vector(&b, &h), t_a)) / norm(t_a);
            let dx = norm(sub(b.position(h.xi), x_a));
            eprintln!("coplanar B {name}, {scheme:?}: |dt|/|t| = {dt:.2e}, old point moved {dx:.2e}");
            match scheme {
                Scheme::Continuous | Scheme::ContinuousProjected => assert!(dt < 1e-14 && dx < 1e-14),
                Scheme::Straightforward => assert!(dt > 0.3 && dx > 0.5),
                Scheme::PathLength if name == "aligned" => assert!(dt < 1e-14 && dx < 1e-14),
                Scheme::PathLength => assert!(dt > 0.5 && dx < 1e-14),
            }
        }
    }
}

/// A slave point pressed 0.01 into `A` at `ξ_(n) = (0.9, 0.2)` (sticking, history `T^(n)`)
/// slides by `Δ = (0.1, 0.02, 0)` onto the turned `B`. On two coplanar rectangles the
/// one-facet answer is exact: `t^tr = t^(n) − ε_T Δ` (the trial traction of a point sliding
/// on one plane). The kernel on `B` with the continuous transfer's history gives it to
/// 1e-12 relative; with the straightforward history the trial is off by O(ε_T) (printed;
/// asserted > 10 %), the seed's jump.
#[test]
fn sliding_across_a_shared_edge_keeps_the_trial_traction() {
    let law = ContactLaw {
        eps_n: 1e3,
        eps_t: 1e2,
        mu: 1e3,
    };
    let (a, b) = (facet_a(), facet_b_turned());
    let t_old = vector(&a, &HIST);
    let x_old = a.position(HIST.xi);
    let delta = [0.1, 0.02, 0.0];
    let slave = [x_old[0] + delta[0], x_old[1] + delta[1], -0.01];
    let want: [f64; 3] = std::array::from_fn(|c| t_old[c] - law.eps_t * delta[c]);
    for scheme in [Scheme::Continuous, Scheme::Straightforward] {
        let h = transfer(scheme, &a, &HIST, &b).unwrap();
        let p = PointProblem {
            history: Some(h),
            ..PointProblem::new(law, [slave, b.x[0], b.x[1], b.x[2], b.x[3]])
        };
        let e = p.evaluate_f64().unwrap();
        assert_eq!(e.state, ContactState::Stick);
        let got = e.projection.point.vector(e.trial);
        let err = norm(sub(got, want)) / norm(want);
        eprintln!("slide across the edge, {scheme:?}: trial {got:?} vs one-plane {want:?}: {err:.2e}");
        if scheme == Scheme::Continuous {
            assert!(err < 1e-12, "{err:e}");
        } else {
            assert!(err > 0.1, "{err:e}");
        }
    }
}

/// `B'`: `B` aligned, hinged down about the edge `x = 1` by `θ` (a convex fold).
fn facet_b_folded(theta: f64) -> Facet<f64> {
    let (c, s) = (2.0 * theta.cos(), 2.0 * theta.sin());
    Facet {
        x: [[1.0, 0.0, 0.0], [1.0 + c, 0.0, -s], [1.0 + c, 1.0, -s], [1.0, 1.0, 0.0]],
        bend: None,
    }
}

/// Across a 30° fold the continuous transfer (rotation about the edge) keeps `|t|` and the
/// component along the edge (1e-14), puts `t` in `B`'s tangent plane, and keeps the
/// distance of the old point from the edge (unfolded: 0.05, 1e-14); a return `B → A` gives
/// back `t` (1e-14). The literal seed eq. (3) (`ContinuousProjected`) shrinks the component
/// across the edge by `cos θ` (checked to 1e-14) and the old point's distance likewise.
#[test]
fn fold_transfer_rotates_about_the_edge() {
    let theta = 30f64.to_radians();
    let (a, b) = (facet_a(), facet_b_folded(theta));
    let t_a = vector(&a, &HIST);
    let across_b = [theta.cos(), 0.0, -theta.sin()];
    for scheme in [Scheme::Continuous, Scheme::ContinuousProjected] {
        let h = transfer(scheme, &a, &HIST, &b).unwrap();
        let pb = b.point(h.xi).unwrap();
        let t_b = pb.vector(h.traction);
        let x_b = b.position(h.xi);
        // the old point lies beyond the edge, on B's extension: ξ¹ < −1
        let dist = -dot(sub(x_b, [1.0, 0.0, 0.0]), across_b);
        let along = (t_b[1] - t_a[1]).abs();
        let across = dot(t_b, across_b);
        eprintln!(
            "fold 30 deg, {scheme:?}: |t_B|/|t_A| = {:.15}, across {across:.15} (A: {}), edge distance {dist:.15}",
            norm(t_b) / norm(t_a),
            t_a[0]
        );
        assert!(along < 1e-14 && dot(t_b, pb.normal).abs() < 1e-14);
        if scheme == Scheme::Continuous {
            assert!((norm(t_b) - norm(t_a)).abs() < 1e-14 && (across - t_a[0]).abs() < 1e-14);
            assert!((dist - 0.05).abs() < 1e-14);
            let back = transfer(scheme, &b, &h, &a).unwrap();
            assert!(norm(sub(vector(&a, &back), t_a)) < 1e-14);
        } else {
            assert!((across - t_a[0] * theta.cos()).abs() < 1e-14);
            assert!((dist - 0.05 * theta.cos()).abs() < 1e-14);
        }
    }
}

/// Normals opposite (a facet folded flat back onto its neighbour): the rotation is
/// undefined and the transfer says so (`Folded`), without panicking; `map_point` without
/// unfolding still answers.
#[test]
fn folded_flat_is_a_typed_error() {
    let a = facet_a();
    // B over A, facing down: counter-clockwise seen from −z
    let b = Facet {
        x: [
            [1.0, 0.0, 0.001],
            [1.0, 1.0, 0.001],
            [3.0, 1.0, 0.001],
            [3.0, 0.0, 0.001],
        ],
        bend: None,
    };
    let r = transfer(Scheme::Continuous, &a, &HIST, &b);
    assert!(matches!(r, Err(super::transfer::TransferError::Folded { .. })), "{r:?}");
    assert!(map_point(&a, HIST.xi, &b, false).is_ok());
}
