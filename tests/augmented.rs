//! Augmented Lagrangian enforcement (`enforcement = "augmented"`): Uzawa updates of the
//! multipliers at converged increments (see `contact::augmented`).
//!
//! ```text
//!        P → → → → → → → → →        rigid point, pressed 1e-4, dragged 1.6 in x (scene `crossing`)
//!   +----+------+---------+------------+   top face: 4 segments
//!   +----------------------------------+
//!
//!   ┌──────┐ ← pressed 0.005, then dragged 0.05  (scene `block-slide`, μ = 0.3)
//!   └──────┘
//!   ━━━━━━━━━━━━ rigid plane
//! ```
//! References: with the penalty a pressed point sinks by `ζ = −N/ε_N` and a stuck one creeps
//! by `Δt/ε_T` per increment; augmented, both constraints are met to the tolerance:
//! `|ζ| ε_N ≤ augmented_tol · N_max` at every closed increment (crossing, frictionless, the
//! transfer still continuous across the three boundaries), and a node stuck at two
//! consecutive increments moves by at most `augmented_tol · N_max / ε_T` (block-slide). The
//! normal multiplier the last solve used is the force it produced within the tolerance. Each
//! update removes about `ε/(k + ε)` of the error for a local stiffness `k`: with a penalty far
//! below the structure's (the crossing's ε_T = 1e3 on E = 1e7) the cap on updates is reached
//! and the increment fails, as it does with an unreachable tolerance, with a message naming
//! the pair.

mod common;

use contrail::contact::law::ContactState;

const EPS: f64 = 1e8;

fn crossing(sets: &[&str]) -> contrail::problem::Problem {
    let mut all = vec![
        "contact.enforcement=augmented",
        "contact.eps_n=1e8",
        "contact.eps_t=1e8",
        "contact.mu=0",
    ];
    all.extend_from_slice(sets);
    common::scene("crossing", &all)
}

#[test]
fn augmented_point_meets_the_normal_constraint_and_records_its_multiplier() {
    let tol = 1e-6;
    let p = crossing(&[&format!("contact.augmented_tol={tol}")]);
    let (s, mem) = common::solve_ok(&p);
    assert!(s.augmentations > 0, "the multipliers were updated");
    assert_eq!(mem.crossings.len(), 3);
    for (_, c) in &mem.crossings {
        assert!((c.trial_after - c.trial_before).abs() < 1e-6 * EPS, "{c:?}");
    }
    let mut closed = 0;
    for pts in &mem.contact {
        let c = &pts[0];
        if c.state == ContactState::Open {
            continue;
        }
        closed += 1;
        let n = c.normal_force;
        assert!(c.gap.abs() * EPS <= tol * n * 1.01 + 1e-9, "ζ = {}, N = {n}", c.gap);
        assert!((c.multiplier[0] - n).abs() <= tol * n * 1.01 + 1e-9, "{c:?}");
    }
    assert!(closed > 100);
    // the penalty alone: the point sinks by N/ε_N, and records no multiplier
    let (_, pen) = common::solve_ok(&common::scene("crossing", &["contact.eps_n=1e8", "contact.mu=0"]));
    let last = pen.contact.last().unwrap()[0].clone();
    assert!(
        (last.gap * EPS + last.normal_force).abs() < 1e-6 * last.normal_force,
        "{last:?}"
    );
    assert!(last.multiplier.iter().all(|m| m.is_nan()));
}

#[test]
fn augmented_stick_does_not_creep_and_carries_its_tangential_multiplier() {
    let tol = 1e-6;
    let slide = |sets: &[&str]| common::solve_ok(&common::scene("block-slide", sets)).1;
    let creep = |mem: &contrail::record::Memory| {
        let n_max = (mem.contact.iter().flatten())
            .map(|c| c.normal_force)
            .fold(0.0, f64::max);
        let mut worst = 0.0f64;
        let mut stuck = 0;
        for w in mem.contact.windows(2) {
            for (a, b) in w[0].iter().zip(&w[1]) {
                if a.state == ContactState::Stick && b.state == ContactState::Stick {
                    stuck += 1;
                    worst = worst.max((b.position[0] - a.position[0]).abs() * 1e3 / n_max);
                }
            }
        }
        (worst, stuck)
    };
    let aug = slide(&["contact.enforcement=augmented", &format!("contact.augmented_tol={tol}")]);
    let pen = slide(&[]);
    let ((a, na), (p, np)) = (creep(&aug), creep(&pen));
    println!("stick creep × ε_T / N_max: augmented {a:.2e} ({na} stuck pairs), penalty {p:.2e} ({np})");
    assert!(na > 10 && np > 10);
    assert!(a <= 1.01 * tol, "augmented stick creeps: {a}");
    assert!(p > 1e3 * tol, "the penalty's stick creeps: {p}");
    // λ_T is the traction carried into the increment plus its correction: the returned
    // traction within the tolerance
    let n_max = aug.contact.iter().flatten().map(|c| c.normal_force).fold(0.0, f64::max);
    let with_history = (aug.contact.iter().flatten())
        .filter(|c| c.state == ContactState::Stick && c.multiplier[1].is_finite())
        .inspect(|c| assert!((c.multiplier[1] - c.traction).abs() <= 1.01 * tol * n_max, "{c:?}"))
        .count();
    assert!(with_history > 10);
}

/// A penalty far below the structure's stiffness: each update removes only a small part of
/// the error, and the cap on updates is reached (the scene's own ε_T = 1e3 on E = 1e7).
#[test]
fn a_soft_penalty_converges_too_slowly_and_the_cap_fails_the_increment() {
    let p = common::scene(
        "crossing",
        &[
            "contact.enforcement=augmented",
            "contact.augmented_max=10",
            "stepping.max_cutbacks=0",
        ],
    );
    let e = common::solve(&p).0.unwrap_err().to_string();
    assert!(e.contains("not converged after 10 multiplier updates"), "{e}");
}

#[test]
fn an_unreachable_tolerance_fails_the_increment_with_a_message_naming_the_pair() {
    let p = crossing(&[
        "contact.augmented_tol=1e-17",
        "contact.augmented_max=1",
        "stepping.max_cutbacks=0",
    ]);
    let (r, _) = common::solve(&p);
    let e = r.unwrap_err().to_string();
    assert!(
        e.contains("augmented Lagrangian of pair `point` not converged after 1 multiplier updates")
            && e.contains("augmented_tol"),
        "{e}"
    );
}

#[test]
fn bad_augmented_settings_are_refused() {
    let e = common::scene_text_err(&format!(
        "{}\naugmented_tol = 0.0\nenforcement = \"augmented\"\n",
        CROSSING_HEAD
    ));
    assert!(e.contains("augmented_tol") && e.contains("must be positive"), "{e}");
}

const CROSSING_HEAD: &str = r#"
name = "x"
[[body]]
name = "block"
material = { model = "saint-venant-kirchhoff", young = 1.0e7, poisson = 0.3 }
mesh = { kind = "rectangle", origin = [0.0, -0.5], size = [2.0, 0.5], elements = [4, 1] }
[[fix]]
body = "block"
nodes = "bottom"
components = ["x", "y"]
[[rigid]]
name = "P"
point = [0.2, 0.0]
[[contact]]
name = "point"
slave = { rigid = "P" }
master = { body = "block", face = "top" }
eps_n = 1.0e6
eps_t = 1.0e3
mu = 100.0"#;
