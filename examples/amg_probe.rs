//! Probe for the iterative solver (docs/large-models.md): assembles the tangent of a scene
//! at its initial state (or after a few converged increments of the direct solver) and
//! reports the multigrid hierarchy and the Krylov iterations of one solve.
//!
//! Run: `cargo run --release --example amg_probe -- scenes/punch-large.toml 316x15 [--set k=v]…`

use contrail::assembly::Assembler;
use contrail::linalg::chooser::LinearSolver;
use contrail::solver::state::TrialState;
use std::time::Instant;

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let scene = &args[0];
    let (nx, ny) = args[1].split_once('x').expect("NXxNY");
    let mut sets = vec![format!("body.block.mesh.elements=[{nx},{ny}]")];
    let mut it = args[2..].iter();
    while let Some(a) = it.next() {
        if a == "--set" {
            sets.push(it.next().expect("k=v").clone());
        }
    }
    let t: f64 = std::env::var("T").ok().and_then(|v| v.parse().ok()).unwrap_or(0.5);
    let (_, problem) = contrail::load_scene(scene, &sets).expect("scene");
    let model = &problem.model;
    let mut asm = Assembler::new(model);
    let mut st = TrialState::new(model);
    for p in &model.prescribed {
        st.u[p.dof] = p.ramp.at(t);
    }
    asm.assemble(model, &st.u, t, &mut st.alphas, &mut st.contact, true)
        .unwrap();
    let n = asm.dofs.n_free;
    let b: Vec<f64> = (0..n).map(|i| (0.37 * i as f64).sin()).collect();
    let mut x_lu = b.clone();
    asm.linear.set_solver(LinearSolver::SparseLu);
    let t0 = Instant::now();
    asm.solve(&mut x_lu).unwrap();
    let t_lu = t0.elapsed();
    asm.linear.set_solver(LinearSolver::Iterative);
    let mut x = b.clone();
    let t0 = Instant::now();
    let r = asm.solve(&mut x);
    let t_it = t0.elapsed();
    let (setup, krylov) = (asm.linear.times.factor_time, asm.linear.times.solve_time);
    println!(
        "setup+LU {:.1} ms, krylov+LUsolve {:.1} ms",
        setup.as_secs_f64() * 1e3,
        krylov.as_secs_f64() * 1e3
    );
    let s = asm.linear.iterative_stats();
    let err = x.iter().zip(&x_lu).map(|(a, b)| (a - b).abs()).fold(0.0, f64::max)
        / x_lu.iter().map(|v| v.abs()).fold(0.0, f64::max);
    println!(
        "{}: n {n}, LU {:.1} ms, iterative {:.1} ms ({r:?}): {} Krylov its (CG {}), levels {:?}, complexity {:.2}, {} held nodes, max rel. difference {err:.1e}",
        args[1],
        t_lu.as_secs_f64() * 1e3,
        t_it.as_secs_f64() * 1e3,
        s.krylov_iterations,
        s.cg_solves,
        s.levels,
        s.complexity,
        s.constrained_nodes
    );
}
