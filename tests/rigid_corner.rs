//! Node-to-segment special cases at a rigid outline's convex vertex and free end (Zavarise &
//! De Lorenzis, CMAME 198 (2009) 3428–3451; the pairing rules of `contact::pairing`).
//!
//! ```text
//!        block 1.0 × 0.5 (2×1 EAS), top dragged by +6 in x, pressed by 1e-3 once on the step
//!   ┌──┬──┐ →
//!   └──┴──┘ y = 0    V (2, 0)                     free end (6, 0)
//!   ─ ─ void ─ ─ ─ ─ ●━━━━━━━━━━━━━━━━━━━━━━━━━━━━━●   rigid step: body below the top, right
//!                    ┃ wall (2, 0) → (2, −2)           of the wall
//! ```
//! The block starts in the void left of the step, its bottom at the height of the top face:
//! its bottom nodes are tracked on the wall (gap 2 − x > 0). Dragged right, each node passes
//! over the convex corner V onto the top face, slides along it, and leaves it past the free
//! end at x = 6.
//!
//! Reference (frictionless, rigid outline): a node on the top carries a penalty force
//! `ε_N · 1e-3` or less (the press); a node left of V or right of the free end carries none;
//! (a node leaving the free end may be held on it for the increment it chattered in, to
//! 1e-3 past it); the horizontal reaction of the drag is a few percent of the vertical one at most (no
//! spurious wall force `ε_N (x − 2)` on nodes past V, which a node tracked on the wall would
//! get). Tolerances: every paired point has `|ζ| ≤ 2e-3`; `|R_x| ≤ 0.05 |R_y| + 1e-6 ε_N`.

mod common;

use contrail::contact::law::ContactState;
use contrail::record::Outcome;

const SCENE: &str = r#"
name = "corner-pass"
description = "a block dragged from a void over a convex rigid corner onto a step, and off its free end"

[[body]]
name = "block"
material = { model = "neo-hookean", young = 1.0e3, poisson = 0.3 }
mesh = { kind = "rectangle", origin = [0.5, 0.0], size = [1.0, 0.5], elements = [2, 1] }

[[fix]]
body = "block"
nodes = "top"
components = ["x"]
value = [[0.0, 0.0], [1.0, 6.0]]

[[fix]]
body = "block"
nodes = "top"
components = ["y"]
value = [[0.0, 0.0], [0.3, 0.0], [0.4, -1.0e-3], [1.0, -1.0e-3]]

[[rigid]]
name = "step"
polyline = [[6.0, 0.0], [2.0, 0.0], [2.0, -2.0]]

[[contact]]
name = "step"
slave = { body = "block", nodes = "bottom" }
master = { rigid = "step" }
eps_n = 1.0e5
mu = 0.0

[stepping]
increments = 240
"#;

#[test]
fn nodes_pass_a_convex_corner_and_leave_a_free_end_without_spurious_contact() {
    let model = common::scene_text(SCENE);
    let eps_n = model.model.contacts[0].law.eps_n;
    let (summary, mem) = common::solve_ok(&model);
    assert!(matches!(mem.outcome, Some(Outcome::Completed { .. })));
    let mut on_top = 0;
    for (inc, pts) in mem.increments.iter().zip(&mem.contact) {
        for p in pts {
            let x = p.position[0];
            if p.state != ContactState::Open {
                assert!(
                    p.gap.abs() <= 2e-3,
                    "increment {}: {} gap {}",
                    inc.increment,
                    p.slave_label,
                    p.gap
                );
                assert!(
                    (2.0 - 1e-3..=6.0 + 1e-3).contains(&x),
                    "increment {}: {} in contact at x = {x}",
                    inc.increment,
                    p.slave_label
                );
                on_top += 1;
            }
        }
        let [rx, ry] = inc.reaction_total;
        assert!(
            rx.abs() <= 0.05 * ry.abs() + 1e-6 * eps_n,
            "increment {}: spurious horizontal force {rx} (vertical {ry})",
            inc.increment
        );
    }
    assert!(on_top > 100, "nodes rode on the top face ({on_top} point-increments)");
    // at the end every node is past the free end: nothing in contact
    assert!(mem
        .contact
        .last()
        .unwrap()
        .iter()
        .all(|p| p.state == ContactState::Open));
    println!(
        "{} increments, {} Newton iterations, {} cut-backs, {on_top} closed point-increments",
        summary.increments, summary.newton_iterations, summary.cutbacks
    );
}
