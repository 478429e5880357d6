//! 2D ironing (Yang, Laursen & Meng, IJNME 62 (2005) 1183–1225): a rigid circular die pressed
//! into a soft neo-Hookean block, then dragged along it with friction.
//!
//! ```text
//!          ╭───────╮   die R = 3 (rigid), pressed 1.4 (t ≤ 1), dragged 3.5 → (t ≤ 3)
//!   ┌──────╰───────╯────────────────┐
//!   │  block 9 × 3, E = 1, ν = 0.3  │  bottom fixed; ε_N = ε_T = 100 E per node
//!   └───────────────────────────────┘
//! ```
//! Scene `ironing`; meshes 18 × 6 (coarse), 36 × 12 (medium, the scene's), 72 × 24 (fine);
//! 120 increments nominal, 240 and 480 (half and quarter step). The measures over the
//! sliding phase t ∈ [2, 3] (after the last point under the die has begun to slip):
//! * the mean of F_x/F_y. The published curves are figures only (no numbers to compare
//!   with); what is known exactly: frictionless, an elastic body dissipates nothing, so in
//!   steady sliding the drag vanishes — here it is −0.012 F_y (the die nears the block's
//!   free end: not quite steady) on every mesh; with friction the ratio exceeds μ by the
//!   share of the pressure on the die's inclined front (measured 1.18–1.25 μ over the
//!   frictionless offset). Measured (2026-11-26, nominal step): μ = 0.1: 0.1124, 0.1101,
//!   0.1087; μ = 0.3: 0.3626, 0.3570, 0.3567 (coarse, medium, fine);
//! * the oscillation of the forces as block nodes enter and leave the contact: the largest
//!   misfit of a cubic fit of F_x over t ∈ [2, 3], over the mean F_y — measured 4.7e-3,
//!   1.3e-3, 3.6e-4 (μ = 0.3), falling as h²: node-to-segment against a smooth die.
//!
//! Asserted (release tier: coarse and medium at the nominal and half step, μ = 0, 0.1, 0.3;
//! the full study adds the fine mesh and the quarter step, `-- --include-ignored`):
//! * every run completes with default settings (the default element; μ = 0.1 used to stop
//!   at 6 % of the indentation with slip directions flipping every iteration);
//! * frictionless: |F_x/F_y| < 0.02;
//! * with friction: μ < F_x/F_y − (its frictionless value) < 1.3 μ;
//! * the ratio on consecutive meshes within 0.01, and at half the step within 0.005 of the
//!   nominal step's;
//! * the oscillation at least 2.5 times smaller on each finer mesh.

mod common;

use contrail::record::Memory;

/// `(mean F_x/F_y, oscillation)` over the sliding phase.
fn sliding(m: &Memory) -> (f64, f64) {
    let pts: Vec<(f64, f64, f64)> = m
        .increments
        .iter()
        .filter(|i| i.t >= 2.0 - 1e-9)
        .map(|i| (i.t, i.monitors[0].force, i.monitors[1].force))
        .collect();
    assert!(pts.len() >= 10, "too few increments in the sliding phase");
    let n = pts.len() as f64;
    let ratio = pts.iter().map(|p| p.1 / p.2).sum::<f64>() / n;
    let fy = pts.iter().map(|p| p.2).sum::<f64>() / n;
    let drag: Vec<(f64, f64)> = pts.iter().map(|p| (p.0, p.1)).collect();
    (ratio, cubic_misfit(&drag) / fy)
}

/// The largest |y − cubic least-squares fit| over the points.
fn cubic_misfit(pts: &[(f64, f64)]) -> f64 {
    let t0 = pts[0].0;
    let basis = |t: f64| [1.0, t - t0, (t - t0).powi(2), (t - t0).powi(3)];
    let mut a = nalgebra::Matrix4::<f64>::zeros();
    let mut b = nalgebra::Vector4::<f64>::zeros();
    for &(t, y) in pts {
        let phi = basis(t);
        for i in 0..4 {
            b[i] += phi[i] * y;
            for j in 0..4 {
                a[(i, j)] += phi[i] * phi[j];
            }
        }
    }
    let c = a.lu().solve(&b).expect("a cubic fit of the drag");
    pts.iter()
        .map(|&(t, y)| {
            let phi = basis(t);
            (y - (0..4).map(|i| c[i] * phi[i]).sum::<f64>()).abs()
        })
        .fold(0.0, f64::max)
}

fn run(mu: f64, mesh: [usize; 2], increments: usize) -> (f64, f64) {
    let sets = [
        format!("contact.mu={mu}"),
        format!("body.block.mesh.elements=[{}, {}]", mesh[0], mesh[1]),
        format!("stepping.increments={increments}"),
    ];
    let sets: Vec<&str> = sets.iter().map(String::as_str).collect();
    let (s, m) = common::solve_ok(&common::scene("ironing", &sets));
    let (ratio, oscillation) = sliding(&m);
    println!(
        "μ = {mu}, {mesh:?}, {increments} increments: F_x/F_y {ratio:.4}, oscillation {oscillation:.2e} ({} Newton iterations, {} cut-backs, {:.1} s)",
        s.newton_iterations, s.cutbacks, s.wall_time_s
    );
    (ratio, oscillation)
}

fn study(meshes: &[[usize; 2]], steps: &[usize]) {
    let mut frictionless = Vec::new();
    for mu in [0.0, 0.1, 0.3] {
        let mut last: Option<(f64, f64)> = None;
        for (im, &mesh) in meshes.iter().enumerate() {
            let (ratio, oscillation) = run(mu, mesh, steps[0]);
            if mu == 0.0 {
                assert!(ratio.abs() < 0.02, "frictionless drag {ratio}");
                frictionless.push(ratio);
            } else {
                let friction = ratio - frictionless[im];
                assert!(friction > mu && friction < 1.3 * mu, "μ = {mu}, {mesh:?}: {ratio}");
            }
            if let Some((r, o)) = last {
                assert!((ratio - r).abs() < 0.01, "μ = {mu}, {mesh:?}: {ratio} after {r}");
                assert!(oscillation < o / 2.5, "μ = {mu}, {mesh:?}: {oscillation} after {o}");
            }
            last = Some((ratio, oscillation));
            for &finer in &steps[1..] {
                let (r, _) = run(mu, mesh, finer);
                assert!((r - ratio).abs() < 5e-3, "μ = {mu}, {mesh:?}, {finer}: {r} vs {ratio}");
            }
        }
    }
}

#[test]
#[cfg_attr(debug_assertions, ignore = "release tier")]
fn ironing_completes_and_converges_on_coarse_and_medium_meshes_and_half_steps() {
    study(&[[18, 6], [36, 12]], &[120, 240]);
}

#[test]
#[ignore = "full study"]
fn ironing_full_refinement_study() {
    study(&[[18, 6], [36, 12], [72, 24]], &[120, 240, 480]);
}

/// One run of the penalty study: ironing with `ε_N = ε_T = eps · E` (E = 1).
#[derive(Debug)]
struct Cell {
    mu: f64,
    mesh: [usize; 2],
    increments: usize,
    eps: f64,
    outcome: String,
    iterations_per_increment: f64,
    cutbacks: usize,
    ratio: f64,
    /// The run warned that elements lost stability (hourglassing: the element, not the
    /// contact, failing to resolve the deformation).
    elements_unstable: bool,
}

fn cell(mu: f64, mesh: [usize; 2], increments: usize, eps: f64) -> Cell {
    let sets = [
        format!("contact.mu={mu}"),
        format!("body.block.mesh.elements=[{}, {}]", mesh[0], mesh[1]),
        format!("stepping.increments={increments}"),
        format!("contact.eps_n={eps}"),
        format!("contact.eps_t={eps}"),
        "solver.threads=1".to_string(),
    ];
    let sets: Vec<&str> = sets.iter().map(String::as_str).collect();
    let (r, m) = common::solve(&common::scene("ironing", &sets));
    let (outcome, iterations_per_increment, cutbacks, ratio) = match &r {
        Ok(s) => (
            "completed".to_string(),
            s.newton_iterations as f64 / s.increments as f64,
            s.cutbacks,
            sliding(&m).0,
        ),
        Err(e) => (e.to_string(), f64::NAN, usize::MAX, f64::NAN),
    };
    let elements_unstable = m.logs.iter().any(|l| l.message.contains("lost stability"));
    Cell {
        mu,
        mesh,
        increments,
        eps,
        outcome,
        iterations_per_increment,
        cutbacks,
        ratio,
        elements_unstable,
    }
}

/// Every (μ, mesh, step, ε) run on as many threads as the machine has, one thread each.
fn penalty_study(meshes: &[[usize; 2]], steps: &[usize]) -> Vec<Cell> {
    let mut jobs = Vec::new();
    for &mesh in meshes {
        for &increments in steps {
            for mu in [0.1, 0.3] {
                for eps in [1e1, 1e2, 1e3, 1e4, 1e5, 1e6] {
                    jobs.push((mu, mesh, increments, eps));
                }
            }
        }
    }
    // the finest meshes first: the longest runs start first
    jobs.reverse();
    let next = std::sync::atomic::AtomicUsize::new(0);
    let cells = std::sync::Mutex::new(Vec::new());
    let workers = std::thread::available_parallelism().map_or(1, |n| n.get());
    std::thread::scope(|s| {
        for _ in 0..workers {
            s.spawn(|| loop {
                let k = next.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
                let Some(&(mu, mesh, increments, eps)) = jobs.get(k) else {
                    break;
                };
                let c = cell(mu, mesh, increments, eps);
                println!("{c:?}");
                cells.lock().unwrap().push(c);
            });
        }
    });
    let mut cells = cells.into_inner().unwrap();
    cells.sort_by(|a, b| {
        (a.mesh, a.increments, a.mu, a.eps)
            .partial_cmp(&(b.mesh, b.increments, b.mu, b.eps))
            .unwrap()
    });
    println!("| mesh | increments | μ | ε/E | outcome | Newton its / increment | cut-backs | F_x/F_y |");
    println!("|---|---|---|---|---|---|---|---|");
    for c in &cells {
        println!(
            "| {}×{} | {} | {} | {:.0e} | {} | {:.2} | {} | {:.4} |",
            c.mesh[0], c.mesh[1], c.increments, c.mu, c.eps, c.outcome, c.iterations_per_increment, c.cutbacks, c.ratio
        );
    }
    cells
}

/// Issue 31's criteria: every run completes, without a cut-back at the nominal step (at most
/// 2 on the finest mesh), with at most 6 Newton iterations per increment on average, and
/// F_x/F_y within 0.01 of the gallery's penalty (ε = 1e2 E) on the same mesh and step. The
/// one exception allowed is a run stopped by an inverted element after the element
/// stability check warned that elements lost stability: the element's limit, reported.
fn check_penalty_study(cells: &[Cell], finest: [usize; 2], nominal: usize) {
    for c in cells {
        if c.outcome != "completed" && c.elements_unstable && c.outcome.contains("det") {
            println!("element limit, reported: {c:?}");
            continue;
        }
        assert_eq!(c.outcome, "completed", "{c:?}");
        if c.increments == nominal {
            let allowed = if c.mesh == finest { 2 } else { 0 };
            assert!(c.cutbacks <= allowed, "{c:?}");
        }
        assert!(c.iterations_per_increment <= 6.0, "{c:?}");
        let Some(gallery) = (cells.iter()).find(|g| {
            g.eps == 1e2 && g.mu == c.mu && g.mesh == c.mesh && g.increments == c.increments && g.ratio.is_finite()
        }) else {
            continue;
        };
        assert!((c.ratio - gallery.ratio).abs() < 0.01, "{c:?} against {gallery:?}");
    }
}

/// The penalty study on the medium mesh at the nominal step (ε = 1e1 … 1e6 E, μ = 0.1, 0.3).
#[test]
#[cfg_attr(debug_assertions, ignore = "release tier")]
fn ironing_converges_the_same_for_penalties_from_1e1_to_1e6_times_e() {
    let cells = penalty_study(&[[36, 12]], &[120]);
    check_penalty_study(&cells, [36, 12], 120);
}

/// The whole penalty study: three meshes, the nominal and half step (72 runs; 16 cores: 69 s):
/// `cargo test --release --test ironing ironing_penalty_study_on_every_mesh -- --ignored
/// --nocapture`. Measured 2026-11-26 (16-core device): all 72 complete, 2.7–4.3 Newton
/// iterations per increment, cut-backs at the nominal step only on 72×24 with μ = 0.1 (2 for
/// ε ≤ 1e4 E). Table in docs/methods.md.
#[test]
#[ignore = "full penalty study"]
fn ironing_penalty_study_on_every_mesh() {
    let cells = penalty_study(&[[18, 6], [36, 12], [72, 24]], &[120, 240]);
    check_penalty_study(&cells, [72, 24], 120);
}
