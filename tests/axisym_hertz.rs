//! Hertz point contact, axisymmetric: a rigid sphere pressed into an elastic block (the
//! built-in scene `hertz-axisym`).
//!
//! ```text
//!   z ↑   ( R = 1 )  rigid sphere (an arc revolved about the axis), moved down by δ
//!     +---\__/----------+
//!     | block: cylinder |   r ≤ 0.5, −0.5 ≤ z ≤ 0, E = 1000, ν = 0.3, Neo-Hooke,
//!     | of revolution   |   u_z = 0 at the bottom, u_r = 0 on the axis (automatic)
//!     +-----------------+--→ r
//! ```
//! Reference (Hertz 1882; Johnson, Contact Mechanics (1985) §4.2): with `E* = E/(1 − ν²)`
//! (rigid partner) and `F` the total force over the full circle, `a = (3 F R / (4 E*))^(1/3)`
//! and `p0 = 3 F / (2π a²)`, `p(r) = p0 √(1 − r²/a²)`.
//! Parameters: `δ = 0.001` (`a ≈ 0.032 = R/32`, `a` ≈ 1/16 of the block), frictionless, ε_N = 1e6
//! per unit circumferential length (the ring's forces are `2π r̄` times the plane point's).
//! Measured: `F` the sphere's contact force (the monitor), `a` from the second moment of the
//! nodal normal forces (`∫ r² p dA / ∫ p dA = 2a²/5` for the Hertz distribution), `p0` the
//! recorded pressure of the node on the axis (`/pressure`: its force over its ring area
//! `2π r̄ l = π h²/3`).
//! Tolerances: on the finest of three meshes (graded, 24², 48², 96²), `a` within 2 % and
//! `p0` within 5 % of Hertz for the measured `F`; the coarser two within 5 % each.
//! Increments 4 and 8 on the middle mesh give the same `F` to 1e-6.
//! Measured (`cargo test --test axisym_hertz -- --nocapture`, 2026): `a` −1.92 %, +0.02 %,
//! −0.24 %; `p0` −1.33 %, −1.16 %, −0.52 % (8, 14, 27 nodes in contact); all three meshes
//! ≈ 3 s in the test profile (optimised).

mod common;

use contrail::record::pressure::{profiles, PressureLayout};

struct Hertz {
    force: f64,
    a_err: f64,
    p0_err: f64,
}

fn run(mesh: usize, increments: usize) -> Hertz {
    let el = format!("body.block.mesh.elements=[{mesh}, {mesh}]");
    let inc = format!("stepping.increments={increments}");
    let problem = common::scene("hertz-axisym", &[&el, &inc]);
    let (_, mem) = common::solve_ok(&problem);
    let model = &problem.model;
    let last = mem.increments.last().unwrap();
    let force = last.all_monitors()[0].force;
    let pts = mem.contact.last().unwrap();
    let n_sum: f64 = pts.iter().map(|p| p.normal_force).sum();
    let m2: f64 = pts.iter().map(|p| p.position[0].powi(2) * p.normal_force).sum();
    let a = (2.5 * m2 / n_sum).sqrt();
    let e_star = 1000.0 / (1.0 - 0.09);
    let a_ref = (3.0 * force * 1.0 / (4.0 * e_star)).cbrt();
    let p0_ref = 3.0 * force / (2.0 * std::f64::consts::PI * a_ref * a_ref);
    let layout = PressureLayout::new(model);
    let prof = profiles(&layout, model, &mem.final_u, last.t, last.increment, pts);
    let axis = prof[0]
        .points
        .iter()
        .find(|p| model.nodes[p.node][0] == 0.0)
        .expect("the node on the axis is in contact");
    let p0 = axis.pressure;
    let closed = pts.iter().filter(|p| p.normal_force > 0.0).count();
    println!(
        "mesh {mesh}², {increments} increments: F = {force:.6} (Σ N = {n_sum:.6}), a = {a:.5} (Hertz {a_ref:.5}, {:+.2} %), p0 = {p0:.3} (Hertz {p0_ref:.3}, {:+.2} %), {closed} nodes in contact",
        100.0 * (a / a_ref - 1.0),
        100.0 * (p0 / p0_ref - 1.0)
    );
    // F is the sphere's axial force, Σ N the normal forces' sum: they differ by the slope of
    // the sphere at the contact (1 − cos θ ≤ a²/(2R²) ≈ 5e-4)
    assert!((n_sum - force).abs() < 1e-3 * force, "Σ N = {n_sum} vs F = {force}");
    Hertz {
        force,
        a_err: (a / a_ref - 1.0).abs(),
        p0_err: (p0 / p0_ref - 1.0).abs(),
    }
}

#[test]
fn axisym_hertz_contact_radius_and_peak_pressure() {
    let coarse = run(24, 4);
    let mid = run(48, 4);
    assert!(coarse.a_err < 0.05 && coarse.p0_err < 0.05, "24²");
    assert!(mid.a_err < 0.05 && mid.p0_err < 0.05, "48²");
    let mid8 = run(48, 8);
    assert!(
        (mid8.force - mid.force).abs() < 1e-6 * mid.force,
        "{} vs {}",
        mid8.force,
        mid.force
    );
    let fine = run(96, 4);
    assert!(fine.a_err < 0.02, "a off by {:.2} %", 100.0 * fine.a_err);
    assert!(fine.p0_err < 0.05, "p0 off by {:.2} %", 100.0 * fine.p0_err);
}
