//! Block on a rigid plane, pressed then dragged: penalty stick and Coulomb sliding.
//!
//! ```text
//!        u_y(t), u_x(t) prescribed on the top
//!      +-----------+
//!      |   block   |   E = 1000, ν = 0.3, 1 × 0.5, 4 × 2 Neo-Hookean EAS elements
//!      +-----------+
//!  ====================  rigid plane y = 0: ε_N = 1e4, ε_T = 1e3, μ = 0.3
//! ```
//! t ∈ [0, 1]: press by 0.005; t ∈ [1, 3]: drag by 0.05.
//! References: in stick, the friction force on each slave node grows by −ε_T times its
//! tangential displacement of the increment from where the last increment left it (rigid
//! flat master: a11 is constant; the block starts resting on the plane without force), to
//! 1e-8 of the largest friction force of the run (the contact forces are Newton's force
//! unknowns, within the convergence tolerance of the penalty law); in
//! sliding, the drag force on the top equals μ times the normal force, to 1e-8 relative.

mod common;

use contrail::contact::law::ContactState;

const EPS_T: f64 = 1.0e3;
const MU: f64 = 0.3;

#[test]
fn block_slide_stick_force_is_penalty_times_slip() {
    let m = common::scene("block-slide", &[]);
    let (_, mem) = common::solve_ok(&m);
    // per point, its position and friction force at the last increment: the bottom nodes
    // rest on the plane at t = 0, where they start without force
    let mut last: Vec<Option<(f64, f64)>> = (m.model.contacts[0].slaves.iter())
        .map(|s| match s {
            contrail::model::Slave::Node(n) => Some((m.model.nodes[*n][0], 0.0)),
            _ => None,
        })
        .collect();
    let largest = (mem.contact.iter().flatten())
        .map(|p| (p.traction * p.tangent[0]).abs())
        .fold(0.0, f64::max);
    assert!(largest > 0.0);
    let mut checked = 0;
    for points in &mem.contact {
        for (i, p) in points.iter().enumerate() {
            if p.state == ContactState::Open {
                last[i] = None;
                continue;
            }
            let fx = p.traction * p.tangent[0];
            if let (Some((x0, f0)), ContactState::Stick) = (last[i], p.state) {
                // in stick the force grows by −ε_T times the slip of the increment, from
                // where the last increment left it (in stick or on the cone)
                let expect = f0 - EPS_T * (p.position[0] - x0);
                assert!(
                    (fx - expect).abs() <= 1e-8 * largest,
                    "node {}: friction {fx:e} vs {expect:e}",
                    p.slave_label
                );
                checked += 1;
            }
            last[i] = Some((p.position[0], fx));
        }
    }
    println!("checked {checked} stick states");
    assert!(checked > 10);
}

#[test]
fn block_slide_sliding_force_is_mu_times_normal_force() {
    let m = common::scene("block-slide", &[]);
    let (_, mem) = common::solve_ok(&m);
    let mut sliding = 0;
    for (inc, points) in mem.increments.iter().zip(&mem.contact) {
        if points.iter().all(|p| p.state == ContactState::Slip) {
            let [rx, ry] = inc.reaction_total;
            let ratio = rx.abs() / ry.abs();
            assert!((ratio / MU - 1.0).abs() < 1e-8, "t = {}: |R_x|/|R_y| = {ratio}", inc.t);
            let n: f64 = points.iter().map(|p| p.normal_force).sum();
            let t: f64 = points.iter().map(|p| p.traction.abs()).sum();
            assert!((t / (MU * n) - 1.0).abs() < 1e-12);
            sliding += 1;
        }
    }
    println!("{sliding} fully sliding increments");
    assert!(sliding >= 10, "the block must slide");
    // it stuck first
    assert!(mem
        .contact
        .iter()
        .any(|ps| ps.iter().any(|p| p.state == ContactState::Stick)));
}
