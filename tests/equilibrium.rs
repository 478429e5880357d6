//! Global equilibrium of each body at every converged increment (`crate::solver::equilibrium`)
//! and the contact force each point records.
//!
//! Reference: a state in equilibrium — for each body, its applied loads, reactions and the
//! contact forces it receives sum to zero. Measured (2026-11-27) on the built-in scenes:
//! 3.2e-15 … 2.0e-9 of the force scale; asserted ≤ 1e-8 at every increment of the scenes
//! below (the run stops above 1e-6).
//! The recorded force of a closed point on a straight master is `N n + T τ` (asserted to
//! 1e-9 relative); on the ironing's circular die (R = 3) its tangential part is
//! `T / (1 − ζ κ)`, `κ = −1/R` seen from the block (the curvature factor of `∇ξ`), asserted
//! to 1e-9 relative — the factor the load–displacement monitor neglected before it read
//! this force.
mod common;

use contrail::contact::law::ContactState;
use contrail::record::Memory;

fn closed(m: &Memory) -> impl Iterator<Item = &contrail::record::ContactPointRecord> {
    m.contact.iter().flatten().filter(|p| p.state != ContactState::Open)
}

#[test]
fn every_converged_increment_is_in_equilibrium() {
    for (scene, sets) in [
        ("contact-patch", vec![]),
        ("block-slide", vec![]),
        ("crossing", vec![]),
        ("hertz", vec![]),
        ("capstan-polygon", vec![]),
    ] {
        let p = common::scene(scene, &sets);
        let (s, m) = common::solve_ok(&p);
        let worst = m.increments.iter().map(|i| i.equilibrium).fold(0.0, f64::max);
        println!(
            "{scene}: worst imbalance {worst:.2e} over {} increments",
            m.increments.len()
        );
        assert!(worst <= 1e-8, "{scene}: {worst:e}");
        assert_eq!(s.equilibrium, Some(worst), "{scene}: the summary keeps the worst");
    }
}

#[test]
fn a_point_on_a_straight_master_records_its_tractions_as_its_force() {
    let p = common::scene("block-slide", &[]);
    let (_, m) = common::solve_ok(&p);
    let mut n = 0;
    for c in closed(&m) {
        let f = [
            c.normal_force * c.normal[0] + c.traction * c.tangent[0],
            c.normal_force * c.normal[1] + c.traction * c.tangent[1],
        ];
        let err = (f[0] - c.force[0]).hypot(f[1] - c.force[1]);
        assert!(err <= 1e-9 * c.force[0].hypot(c.force[1]), "{c:?}");
        n += 1;
    }
    assert!(n > 0);
}

/// On the ironing's die (a rigid circle of radius R = 3 over a deformable block) the
/// tangential part of the force is the traction times the curvature factor of `∇ξ`: the
/// slave sits at `R + ζ` from the centre, so `f·τ = T R / (R + ζ)`; the normal part is `N`.
#[test]
fn a_point_on_a_curved_master_records_the_curvature_factor() {
    const R: f64 = 3.0;
    let p = common::scene("ironing", &["stepping.increments=40"]);
    let (_, m) = common::solve_ok(&p);
    let mut n = 0;
    for c in closed(&m).filter(|c| c.traction.abs() > 1e-3 * c.normal_force.abs()) {
        let along = |d: [f64; 2]| c.force[0] * d[0] + c.force[1] * d[1];
        let factor = along(c.tangent) / c.traction;
        assert!((factor - R / (R + c.gap)).abs() <= 1e-9, "{c:?}");
        assert!(
            (along(c.normal) - c.normal_force).abs() <= 1e-9 * c.normal_force.abs(),
            "{c:?}"
        );
        n += 1;
    }
    assert!(n > 100, "{n} sliding points");
}
