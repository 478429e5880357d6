//! Probe of the factorisation grain (docs/performance.md, "Threads"): on the `punch-large`
//! scene (or `SCENE`) at the meshes given (`NXxNY`), the tangent is assembled once and factorised and
//! solved `REPS` times with 1, 2, 4, … threads (up to the cores this process may use), by
//! the solver `auto` picks (`LDLᵀ` on these square blocks; the band on thin ones).
//! Prints one line per mesh and thread count: unknowns, best factorise + solve time, and
//! the speed-up against one thread. Every solve factorises (the `general` setting: no
//! lagged solve with an earlier factor, no band).
//!
//! Run: `cargo run --release --example factor_grain -- 100x20 316x30 1000x50`; in 3D
//! `SCENE=scenes/hertz-3d.toml cargo run --release --example factor_grain -- 24x24x18`
//! (`NXxNYxNZ`; the scene's body `block` is the one meshed).

use contrail::assembly::Assembler;
use contrail::model::{Dim, Model};
use contrail::scene::AnyProblem;
use contrail::settings::LinearSolver;
use contrail::solver::state::TrialState;
use std::time::Instant;

fn main() {
    let scene = std::env::var("SCENE").unwrap_or_else(|_| "scenes/punch-large.toml".into());
    for arg in std::env::args().skip(1) {
        let dims: Vec<&str> = arg.split('x').collect();
        let sets = vec![format!("body.block.mesh.elements=[{}]", dims.join(","))];
        match contrail::load_any_scene(&scene, &sets).expect("scene").1 {
            AnyProblem::Plane(p) => probe(&arg, &p.model),
            AnyProblem::Solid(p) => probe(&arg, &p.model),
        }
    }
}

/// Factorise and solve the tangent of `model` with 1, 2, 4, … threads; print the times.
fn probe<S: Dim>(arg: &str, model: &Model<S>) {
    let reps: usize = std::env::var("REPS").ok().and_then(|v| v.parse().ok()).unwrap_or(3);
    let cores = contrail::threads::available_cores();
    let mut asm = Assembler::new(model);
    asm.linear.set_solver(LinearSolver::General);
    let mut st = TrialState::new(model);
    for (i, u) in st.u.iter_mut().enumerate() {
        *u = 1e-7 * (i as f64 * 0.37).sin();
    }
    for p in &model.prescribed {
        st.u[p.dof] = 0.0;
    }
    asm.assemble(model, &st.u, 0.5, &mut st.alphas, &mut st.contact, true)
        .unwrap();
    let n = asm.dofs.n_free;
    let mut base = None;
    let mut threads = 1;
    while threads <= cores {
        asm.linear.set_threads(threads);
        asm.linear.set_parallel_thresholds(0, 0.0);
        let mut best = f64::INFINITY;
        for _ in 0..reps {
            let mut b = vec![1.0; n];
            let t0 = Instant::now();
            asm.solve(&mut b).unwrap();
            best = best.min(t0.elapsed().as_secs_f64());
        }
        let one = *base.get_or_insert(best);
        println!(
            "{arg}: {n} unknowns, {:.2e} flops, {threads} threads: {:.2} ms (x{:.2} against one thread)",
            asm.linear.ldlt_stats().flops.0,
            best * 1e3,
            one / best
        );
        threads *= 2;
    }
}
