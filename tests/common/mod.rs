//! Shared helpers of the verification tests.
#![allow(dead_code)]

use contrail::problem::Problem;
use contrail::record::Memory;
use contrail::solver::{run, RunSummary, SolveError};
use std::sync::atomic::AtomicBool;

/// Load a built-in scene with overrides.
pub fn scene(name: &str, sets: &[&str]) -> Problem {
    let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
    contrail::load_scene(name, &sets).unwrap_or_else(|e| panic!("{e}")).1
}

/// Load a scene from TOML text.
pub fn scene_text(text: &str) -> Problem {
    let src = contrail::scene::SceneSource {
        origin: "test.toml".into(),
        text: text.into(),
    };
    let file = contrail::scene::parse(&src, &[]).unwrap_or_else(|e| panic!("{e}"));
    contrail::scene::build(&src, &file).unwrap_or_else(|e| panic!("{e}"))
}

/// Load a scene file's text (`origin`: its path, named in errors) with `--set` overrides.
pub fn scene_file(origin: &str, text: &str, sets: &[&str]) -> Problem {
    let src = contrail::scene::SceneSource {
        origin: origin.into(),
        text: text.into(),
    };
    let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
    let file = contrail::scene::parse(&src, &sets).unwrap_or_else(|e| panic!("{e}"));
    contrail::scene::build(&src, &file).unwrap_or_else(|e| panic!("{e}"))
}

/// The error message of a scene in TOML text that does not load.
pub fn scene_text_err(text: &str) -> String {
    let src = contrail::scene::SceneSource {
        origin: "test.toml".into(),
        text: text.into(),
    };
    match contrail::scene::parse(&src, &[]).and_then(|f| contrail::scene::build(&src, &f)) {
        Ok(_) => panic!("the scene loaded"),
        Err(e) => e.to_string(),
    }
}

/// Run a model, keeping every record in memory.
pub fn solve(problem: &Problem) -> (Result<RunSummary, SolveError>, Memory) {
    let src = contrail::scene::SceneSource {
        origin: "test".into(),
        text: String::new(),
    };
    let info = contrail::run_info(&src, &[], problem);
    let mut mem = Memory::default();
    let r = run(problem, &info, &mut mem, &AtomicBool::new(false));
    (r, mem)
}

/// Load a 3D scene (a built-in name or a path) with `--set` overrides, run it to completion
/// and keep every record.
pub fn solve_solid(scene: &str, sets: &[&str]) -> Memory {
    let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
    let (src, problem) = contrail::load_any_scene(scene, &sets).unwrap_or_else(|e| panic!("{e}"));
    let contrail::scene::AnyProblem::Solid(problem) = problem else {
        panic!("{scene}: a 3D scene")
    };
    let mut mem = Memory::default();
    let info = contrail::run_info(&src, &sets, &problem);
    run(&problem, &info, &mut mem, &AtomicBool::new(false)).unwrap_or_else(|e| panic!("{scene} {sets:?}: {e}"));
    mem
}

/// Run and require completion.
pub fn solve_ok(problem: &Problem) -> (RunSummary, Memory) {
    let (r, m) = solve(problem);
    (r.unwrap_or_else(|e| panic!("{}: {e}", problem.model.name)), m)
}

/// The normal force of every contact point at the last increment of `b` equals that of `a`
/// to `tol` times the largest (`what` names the two runs in the message).
pub fn assert_same_normal_forces(a: &Memory, b: &Memory, tol: f64, what: (&str, &str)) {
    let forces = |m: &Memory| -> Vec<(String, f64)> {
        let last = m.contact.last().unwrap();
        last.iter()
            .map(|p| (format!("x = {}", p.position[0]), p.normal_force))
            .collect()
    };
    assert_same_forces(&forces(a), &forces(b), tol, what);
}

/// The normal force of every 3D contact point at the last increment of `b` equals that of
/// `a` to `tol` times the largest (`what` names the two runs in the message).
pub fn assert_same_surface_normal_forces(a: &Memory, b: &Memory, tol: f64, what: (&str, &str)) {
    let forces = |m: &Memory| -> Vec<(String, f64)> {
        let last = m.surface.last().unwrap();
        last.iter()
            .map(|p| (format!("node {}", p.node), p.normal_force))
            .collect()
    };
    assert_same_forces(&forces(a), &forces(b), tol, what);
}

/// Labelled forces of `b` equal those of `a`, one by one, to `tol` times the largest of `a`.
fn assert_same_forces(a: &[(String, f64)], b: &[(String, f64)], tol: f64, what: (&str, &str)) {
    assert_eq!(a.len(), b.len());
    let scale = a.iter().map(|p| p.1.abs()).fold(0.0, f64::max);
    assert!(scale > 0.0);
    for ((at, p), (_, q)) in a.iter().zip(b) {
        assert!(
            (p - q).abs() <= tol * scale,
            "normal force at {at}: {p} ({}) vs {q} ({})",
            what.0,
            what.1
        );
    }
}

/// Load a 3D scene from TOML text (`origin`: its name in errors) and run it to completion,
/// keeping every record in memory.
pub fn solve_solid_text(origin: &str, text: &str) -> (Problem<contrail::model::Solid>, RunSummary, Memory) {
    let (problem, info) = solid_problem(origin, text);
    let mut mem = Memory::default();
    let summary = run(&problem, &info, &mut mem, &AtomicBool::new(false))
        .unwrap_or_else(|e| panic!("{}: {e}", problem.model.name));
    (problem, summary, mem)
}

/// The 3D problem of a scene text (`origin` names it) and its run facts.
pub fn solid_problem(origin: &str, text: &str) -> (Problem<contrail::model::Solid>, contrail::record::RunInfo) {
    let src = contrail::scene::SceneSource {
        origin: origin.into(),
        text: text.into(),
    };
    let file = contrail::scene::parse(&src, &[]).unwrap_or_else(|e| panic!("{e}"));
    let built = contrail::scene::build_any(&src, &file).unwrap_or_else(|e| panic!("{e}"));
    let contrail::scene::AnyProblem::Solid(problem) = built else {
        panic!("{origin}: not a 3D scene")
    };
    let info = contrail::run_info(&src, &[], &problem);
    (problem, info)
}
