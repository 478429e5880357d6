//! Invariance of the contact Newton under placement and units.
//!
//! Reference: a model's answer and the way Newton reaches it may not depend on where the
//! model sits or in what consistent units it is written (the convergence test's reference
//! and floors are in the model's own scale; the contact kernels compute about each slave's
//! own origin).
//!
//! Parameters: the seed's strip-channel (24×1, μ = 0.2, 1 200 increments, continuous
//! transfer) and the built-in ironing (36×12, μ = 0.3, 120 increments)
//! - translated by 10⁶ lengths (mesh origin, rigid outline and arc centre);
//! - in consistent units: lengths ×10³, E and ε ×10⁻⁶ (forces per unit thickness ×10⁻³).
//!
//! Tolerances: the monitored force at every increment equal to 10⁻⁸ of the run's largest
//! (translation; 10⁻⁷ for the ironing, whose die is placed to 8 digits), in the scaled units
//! for the units case; Newton iterations of the whole run within ±2 %. Refined in step: the
//! strip-channel at 1 200 and 2 400 increments.

mod common;

use contrail::record::Memory;

/// The first monitor's force at every increment.
fn forces(m: &Memory) -> Vec<f64> {
    m.increments
        .iter()
        .map(|i| i.monitor.as_ref().expect("a monitor").force)
        .collect()
}

/// Run and return the force history and the Newton iterations of the whole run.
fn run(name: &str, sets: &[String]) -> (Vec<f64>, usize) {
    let sets: Vec<&str> = sets.iter().map(String::as_str).collect();
    let (summary, mem) = common::solve_ok(&common::scene(name, &sets));
    let all: usize = mem.iterations.len();
    assert!(summary.newton_iterations > 0 && all >= summary.newton_iterations);
    (forces(&mem), all)
}

fn assert_same(what: &str, a: &(Vec<f64>, usize), b: &(Vec<f64>, usize), scale_b: f64, tol: f64) {
    assert_eq!(a.0.len(), b.0.len(), "{what}: increments");
    let big = a.0.iter().fold(0.0f64, |m, f| m.max(f.abs()));
    for (k, (fa, fb)) in a.0.iter().zip(&b.0).enumerate() {
        assert!(
            (fa - fb / scale_b).abs() <= tol * big,
            "{what}: increment {}: force {fa} against {}",
            k + 1,
            fb / scale_b
        );
    }
    let (ia, ib) = (a.1 as f64, b.1 as f64);
    assert!(
        (ia - ib).abs() <= 0.02 * ia,
        "{what}: Newton iterations {} against {}",
        a.1,
        b.1
    );
}

fn strip(increments: usize, extra: &[String]) -> Vec<String> {
    let mut s = vec![format!("stepping.increments={increments}")];
    s.extend_from_slice(extra);
    s
}

#[test]
fn strip_channel_converges_the_same_way_wherever_it_sits_and_in_any_units() {
    for increments in [1200, 2400] {
        let base = run("strip-channel", &strip(increments, &[]));
        let (dx, dy) = (1.0e6, -1.0e6);
        let moved = run(
            "strip-channel",
            &strip(
                increments,
                &[
                    format!("body.strip.mesh.origin=[{dx}, {dy}]"),
                    format!(
                        "rigid.block.polyline=[[{}, {}], [{}, {}], [{}, {}]]",
                        20.0 + dx,
                        dy,
                        6.5 + dx,
                        dy,
                        6.5 + dx,
                        -40.0 + dy
                    ),
                ],
            ),
        );
        assert_same("translated by 1e6", &base, &moved, 1.0, 1e-8);
        let units = run(
            "strip-channel",
            &strip(
                increments,
                &[
                    "body.strip.mesh.size=[12000.0, 500.0]".into(),
                    "body.strip.material.young=2.1e-2".into(),
                    "fix.1.value=-12000.0".into(),
                    "rigid.block.polyline=[[20000.0, 0.0], [6500.0, 0.0], [6500.0, -40000.0]]".into(),
                    "contact.eps_n=0.21".into(),
                    "contact.eps_t=0.21".into(),
                ],
            ),
        );
        // forces per unit thickness: stress × length, ×1e-6 × 1e3
        assert_same("lengths x1e3, E x1e-6", &base, &units, 1e-3, 1e-8);
    }
}

#[test]
fn ironing_converges_the_same_way_wherever_it_sits_and_in_any_units() {
    let mu = "contact.mu=0.3".to_string();
    let base = run("ironing", std::slice::from_ref(&mu));
    let (dx, dy) = (1.0e6, 1.0e6);
    let moved = run(
        "ironing",
        &[
            mu.clone(),
            format!("body.block.mesh.origin=[{dx}, {dy}]"),
            format!("rigid.die.arc.centre=[{}, {}]", 2.75 + dx, 6.0 + dy),
        ],
    );
    assert_same("translated by 1e6", &base, &moved, 1.0, 1e-7);
    let units = run(
        "ironing",
        &[
            mu,
            "body.block.mesh.size=[9000.0, 3000.0]".into(),
            "body.block.material.young=1e-6".into(),
            "rigid.die.arc.centre=[2750.0, 6000.0]".into(),
            "rigid.die.arc.radius=3000.0".into(),
            "rigid.die.move.x=[[0.0, 0.0], [1.0, 0.0], [3.0, 3500.0]]".into(),
            "rigid.die.move.y=[[0.0, 0.0], [1.0, -1400.0], [3.0, -1400.0]]".into(),
            "contact.eps_n=1e-4".into(),
            "contact.eps_t=1e-4".into(),
        ],
    );
    assert_same("lengths x1e3, E x1e-6", &base, &units, 1e-3, 1e-7);
}
