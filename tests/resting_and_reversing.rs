//! Bodies held by nothing but the contact they rest on, and friction reversing under a
//! slider: two scenes that failed, or finished wrong with exit 0, before the initial state
//! was the committed state of increment 0 and reversing slip was held in stick.
//!
//! ```text
//!   gravity-drag                          block-on-block
//!   ← x held, then pulled 0.05            slider 1 × 0.5 (7 × 4), pressed 0.005, slid 1.0
//!   ┌──────────┐ block 1 × 0.25, W = 5    ┌──────┐
//!   └──────────┘ ↓ body load              └──────┘ μ = 0.3, ε = 1e5
//!   ════════════ rigid floor, μ = 0.4     ┌─────────────────────┐ base 3 × 0.5 (30 × 5)
//! ```
//! Scenes `tests/data/gravity-drag.toml` (E = 1e3, 20 × 5 elements, ε = 1e4, 60 increments:
//! the weight ramps on over t ≤ 1 with the block at zero gap, then its left face is pulled
//! sideways until it slides) and `tests/data/block-on-block.toml` (neo-Hooke E = 1e3 both,
//! non-matching meshes, deformable master face).
//!
//! References: Coulomb's law in gross sliding. On the floor the drag is μW = 2 exactly
//! (a rigid flat master, so the sum of the normal forces is W and every point slides);
//! between the blocks the slider's horizontal reaction over its vertical one is μ = 0.3,
//! and the two bodies' reactions balance.
//!
//! Failures they guard: the block on the floor could not start (its tangent singular with
//! every touching point open: "no convergence" at the first increment, at every cut-back);
//! the block-on-block run accepted a folded base element at its last increment after a
//! long Newton wander (points flipping slip direction), reporting drag 3.294 and press
//! 5.088 (ratio 0.647) with exit 0.
//!
//! Asserted: both complete at the nominal and the half step (gravity drag also on a mesh
//! twice as fine); the gravity drag in sliding (t ≥ 2.5) is μW to 1e-3; the blocks' ratio in
//! sliding (t ≥ 2) is μ to 2 % and their reactions balance to 1e-6 of the press.

mod common;

fn solve(origin: &str, text: &str, sets: &[&str]) -> (contrail::solver::RunSummary, contrail::record::Memory) {
    common::solve_ok(&common::scene_file(origin, text, sets))
}

#[test]
fn gravity_drag_on_a_floor_starts_at_zero_gap_and_slides_at_mu_w() {
    let text = include_str!("data/gravity-drag.toml");
    let cases: [&[&str]; 3] = [
        &[],
        &["stepping.increments=120"],
        &["body.block.mesh.elements=[40, 10]"],
    ];
    for sets in cases {
        let (summary, m) = solve("tests/data/gravity-drag.toml", text, sets);
        let sliding: Vec<f64> = m
            .increments
            .iter()
            .filter(|i| i.t >= 2.5 - 1e-12)
            .map(|i| i.monitors[0].force.abs())
            .collect();
        assert!(!sliding.is_empty());
        for d in &sliding {
            assert!((d - 2.0).abs() <= 2e-3, "{sets:?}: drag {d}, μW = 2");
        }
        println!(
            "{sets:?}: drag {:.6}, cut-backs {}",
            sliding[sliding.len() - 1],
            summary.cutbacks
        );
    }
}

#[test]
fn block_on_block_slides_at_mu_with_balanced_reactions() {
    let text = include_str!("data/block-on-block.toml");
    let cases: [&[&str]; 2] = [&[], &["stepping.increments=120"]];
    for sets in cases {
        let (summary, m) = solve("tests/data/block-on-block.toml", text, sets);
        let last = &m.increments.last().unwrap().monitors;
        println!(
            "{sets:?}: drag {:.4}, press {:.4}, cut-backs {}",
            last[0].force, last[1].force, summary.cutbacks
        );
        for inc in m.increments.iter().filter(|i| i.t >= 2.0 - 1e-12) {
            let f = &inc.monitors;
            let (fx, fy) = (f[0].force, f[1].force);
            let ratio = (fx / fy).abs();
            assert!(
                (ratio - 0.3).abs() <= 0.02 * 0.3,
                "{sets:?} t = {}: F_x/F_y = {ratio}",
                inc.t
            );
            let (bx, by) = (f[2].force, f[3].force);
            assert!(
                (fx + bx).abs() <= 1e-6 * fy.abs(),
                "{sets:?} t = {}: x reactions {fx} {bx}",
                inc.t
            );
            assert!(
                (fy - by).abs() <= 1e-6 * fy.abs() || (fy + by).abs() <= 1e-6 * fy.abs(),
                "{sets:?} t = {}: y reactions {fy} {by}",
                inc.t
            );
        }
    }
}
