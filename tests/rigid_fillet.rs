//! A composite rigid outline (line + arc + line: a step with a rounded corner) and a block
//! dragged off its top face over the fillet.
//!
//! ```text
//!            block 1.0 × 0.5 (2×1 EAS), pressed by 1e-3, then dragged −2.5 in x
//!                        ┌──┬──┐ ←
//!   ─ ─ void ─ ─ ─ ─ ─ ╭─┴━━┴━━┴━━━━━━━━━●  top face y = 0 (x from 2.5 to 6, free end at 6)
//!                      │ fillet r = 0.5 about (2.5, −0.5), 90° → 180°
//!                      ┃ wall x = 2 down to y = −2
//! ```
//! The outline is `[{ line = [[6, 0], [2.5, 0]] }, { arc = { centre = [2.5, −0.5],
//! radius = 0.5, from_deg = 90, to_deg = 180 } }, { line = [[2, −0.5], [2, −2]] }]`, the
//! rigid body below and right (on the left of the direction of travel). The joints are
//! tangent, so a node leaving the top over the fillet follows a continuous normal.
//!
//! Reference (frictionless): a node in contact touches the top face or the fillet
//! (`x ≥ 2 − 1e-3`, `|ζ| ≤ 2e-3`, the press `1e-3` plus elastic recovery); a node's contact
//! normal on the fillet points away from the fillet's centre (to 1e-3); the horizontal
//! reaction of the drag is bounded by the geometry of the fillet, `|R_x| ≤ |R_y| + 1e-6 ε_N`
//! (normal forces on a quarter circle); at the end (block at x ∈ [0.5, 1.5]) nothing touches.
//! The outline with a gap between two pieces is refused with the piece named.

mod common;

use contrail::contact::law::ContactState;
use contrail::record::Outcome;

const SCENE: &str = r#"
name = "fillet-pass"
description = "a block dragged off a step over its rounded corner"

[[body]]
name = "block"
material = { model = "neo-hookean", young = 1.0e3, poisson = 0.3 }
mesh = { kind = "rectangle", origin = [3.0, 0.0], size = [1.0, 0.5], elements = [2, 1] }

[[fix]]
body = "block"
nodes = "top"
components = ["x"]
value = [[0.0, 0.0], [0.1, 0.0], [1.0, -2.5]]

[[fix]]
body = "block"
nodes = "top"
components = ["y"]
value = [[0.0, 0.0], [0.1, -1.0e-3], [1.0, -1.0e-3]]

[[rigid]]
name = "step"
outline = [
  { line = [[6.0, 0.0], [2.5, 0.0]] },
  { arc = { centre = [2.5, -0.5], radius = 0.5, from_deg = 90.0, to_deg = 180.0 } },
  { line = [[2.0, -0.5], [2.0, -2.0]] },
]

[[contact]]
name = "step"
slave = { body = "block", nodes = "bottom" }
master = { rigid = "step" }
eps_n = 1.0e5
mu = 0.0

[stepping]
increments = 200
"#;

#[test]
fn rigid_fillet_nodes_leave_the_step_over_the_rounded_corner() {
    // the scene as written, and refined once in mesh and step
    let refined = SCENE
        .replace("elements = [2, 1]", "elements = [4, 2]")
        .replace("increments = 200", "increments = 400");
    for text in [SCENE.to_string(), refined] {
        fillet_pass(&text);
    }
}

fn fillet_pass(text: &str) {
    let model = common::scene_text(text);
    let eps_n = model.model.contacts[0].law.eps_n;
    let (summary, mem) = common::solve_ok(&model);
    assert!(matches!(mem.outcome, Some(Outcome::Completed { .. })));
    let mut on_fillet = 0;
    for (inc, pts) in mem.increments.iter().zip(&mem.contact) {
        for p in pts.iter().filter(|p| p.state != ContactState::Open) {
            let [x, y] = p.position;
            assert!(
                x >= 2.0 - 1e-3,
                "increment {}: {} in contact at x = {x}",
                inc.increment,
                p.slave_label
            );
            assert!(p.gap.abs() <= 2e-3, "increment {}: gap {}", inc.increment, p.gap);
            if x < 2.5 {
                // on the fillet: the normal points away from its centre
                let (dx, dy) = (x - 2.5, y + 0.5);
                let r = dx.hypot(dy);
                let n = p.normal;
                assert!(
                    (n[0] - dx / r).abs() < 1e-3 && (n[1] - dy / r).abs() < 1e-3,
                    "increment {}: normal {n:?} at ({x}, {y})",
                    inc.increment
                );
                on_fillet += 1;
            }
        }
        let [rx, ry] = inc.reaction_total;
        assert!(
            rx.abs() <= ry.abs() + 1e-6 * eps_n,
            "increment {}: R = ({rx}, {ry})",
            inc.increment
        );
    }
    assert!(on_fillet > 0, "no node was in contact on the fillet");
    assert!(mem
        .contact
        .last()
        .unwrap()
        .iter()
        .all(|p| p.state == ContactState::Open));
    println!(
        "{} increments, {} Newton iterations, {} cut-backs, {on_fillet} point-increments on the fillet",
        summary.increments, summary.newton_iterations, summary.cutbacks
    );
}

#[test]
fn rigid_fillet_outline_with_a_gap_is_refused_naming_the_piece() {
    let bad = SCENE.replace(
        "{ line = [[2.0, -0.5], [2.0, -2.0]] }",
        "{ line = [[2.1, -0.5], [2.1, -2.0]] }",
    );
    let err = common::scene_text_err(&bad);
    assert!(err.contains("outline[2]") && err.contains("end to end"), "{err}");
}
