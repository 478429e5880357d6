//! A steady-state Newton iteration allocates nothing (issue 8: no per-iteration allocation or
//! hashing in the hot path).
//!
//! Setting: the seed's strip-channel on a 48×2 mesh (μ = 0.2), first brought to a converged
//! state with the corner C in contact (the block nodes paired, open) by Newton itself (`solve_increment` at
//! v = 0.01 from rest). Then, with a counting global allocator, 20 repetitions of what one
//! Newton iteration does to the model — full assembly (elements, contact pairing, contact
//! kernels, scatter into the fixed CSC pattern), a residual-only assembly (the line search's
//! trial) and the sparse LU factorisation with its solve — must make **zero** allocations.
//! Tolerance: none (a count). Per-increment work (copying the state, the records) is not
//! part of this claim. The same on the 120×4 mesh (480 elements), whose element kernels are
//! shared with a team of two threads (`assembly/team.rs`; the allocator counts every
//! thread's allocations). And on the frictionless 48×2 strip with the banded LU switched off,
//! whose symmetric tangent is factorised by faer's sparse `LDLᵀ` (`assembly/ldlt.rs`:
//! symmetry check, factorisation, solve and backward-error check).

mod common;

use contrail::assembly::Assembler;
use contrail::contact::law::ContactState;
use contrail::linalg::chooser::LinearSolver;
use contrail::solver::newton::{solve_increment, IncrementTarget, Workspace};
use contrail::solver::state::TrialState;
use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering};

struct Counting;

static ALLOCATIONS: AtomicUsize = AtomicUsize::new(0);

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        ALLOCATIONS.fetch_add(1, Ordering::Relaxed);
        unsafe { System.alloc(layout) }
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        ALLOCATIONS.fetch_add(1, Ordering::Relaxed);
        unsafe { System.realloc(ptr, layout, new_size) }
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

/// Allocations made by 20 steady-state iterations on the strip meshed `mesh` (see above);
/// also whether its assembler evaluated the elements on more than one thread. With
/// `threads > 1` every assembly shares its element kernels with the team.
fn allocations_in_steady_state(
    mesh: &str,
    mu: &str,
    solver: Option<LinearSolver>,
    threads: usize,
) -> (usize, bool, Assembler) {
    let mesh = format!("body.strip.mesh.elements={mesh}");
    let mu = format!("contact.mu={mu}");
    let problem = common::scene("strip-channel", &[mesh.as_str(), mu.as_str()]);
    let model = &problem.model;
    let mut asm = Assembler::new(model);
    asm.set_threads(threads, model.elements.len());
    if threads > 1 {
        asm.pacing.force(contrail::assembly::pacing::Mode::Team);
    }
    if let Some(s) = solver {
        asm.linear.set_solver(s);
    }
    let mut state = TrialState::new(model);
    let mut ws = Workspace::default();
    // the start of a run: the initial configuration as the converged state
    let u0 = state.u.clone();
    let cfg = contrail::contact::system::Config { model, u: &u0, t: 0.0 };
    state.contact.start_from_initial_configuration(&cfg);
    // v = 0.01 of 12 in one increment from rest (the scene's first): the strip bends over C
    let t = 0.01 / 12.0;
    state.contact.reset_current();
    let target = IncrementTarget {
        t,
        reference_floor: 0.0,
        increment: 1,
        attempt: 0,
        predicted: false,
    };
    solve_increment(
        model,
        &problem.settings.newton,
        &mut asm,
        &mut state,
        target,
        &mut |_| true,
        &mut ws,
    )
    .expect("the first increment converges");
    let closed = state
        .contact
        .current
        .iter()
        .flatten()
        .filter(|p| p.eval.is_some_and(|e| e.state != ContactState::Open))
        .count();
    assert!(closed >= 1, "contact is active ({closed} closed points)");

    let mut r = vec![0.0; asm.dofs.n_free];
    let before = ALLOCATIONS.load(Ordering::Relaxed);
    for _ in 0..20 {
        // the line search's residual-only trial, then a full assembly (it clears the values)
        asm.assemble(model, &state.u, t, &mut state.alphas, &mut state.contact, false)
            .unwrap();
        asm.assemble(model, &state.u, t, &mut state.alphas, &mut state.contact, true)
            .unwrap();
        asm.free_residual(&mut r);
        asm.solve(&mut r).unwrap();
    }
    let made = ALLOCATIONS.load(Ordering::Relaxed) - before;
    let parallel = asm.timings().team_assemblies > 0;
    (made, parallel, asm)
}

/// The three settings in one test: the count is process-wide, and a test of this binary that
/// ends while another measures makes the harness allocate (its completion message) inside the
/// other's window. One test, measured one setting after the other, sees only its own work.
#[test]
fn steady_state_newton_iterations_allocate_nothing() {
    // 96 elements on the calling thread
    let (made, parallel, _) = allocations_in_steady_state("[48,2]", "0.2", None, 1);
    assert!(!parallel, "96 elements are assembled on the calling thread");
    assert_eq!(made, 0, "allocations in 20 steady-state iterations");

    // 480 elements shared with a team of two
    let (made, parallel, team) = allocations_in_steady_state("[120,4]", "0.2", None, 2);
    assert!(parallel, "480 elements are shared with the team");
    assert_eq!(made, 0, "allocations in 20 steady-state iterations (team included)");
    drop(team);

    // the symmetric factorisation (frictionless: the tangent is symmetric)
    let (made, _, asm) = allocations_in_steady_state("[48,2]", "0", Some(LinearSolver::General), 1);
    let stats = asm.linear.ldlt_stats();
    assert!(stats.solves >= 20 && stats.fallbacks == 0, "LDLT used: {stats:?}");
    assert_eq!(made, 0, "allocations in 20 steady-state iterations (LDLT)");
}
