//! Shared helpers of the verification tests.
#![allow(dead_code)]

use contrail::model::Model;
use contrail::record::Memory;
use contrail::solver::{run, RunSummary, SolveError};
use std::sync::atomic::AtomicBool;

/// Load a built-in scene with overrides.
pub fn scene(name: &str, sets: &[&str]) -> Model {
    let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
    contrail::load_scene(name, &sets).unwrap_or_else(|e| panic!("{e}")).1
}

/// Load a scene from TOML text.
pub fn scene_text(text: &str) -> Model {
    let src = contrail::scene::SceneSource {
        origin: "test.toml".into(),
        text: text.into(),
    };
    let file = contrail::scene::parse(&src, &[]).unwrap_or_else(|e| panic!("{e}"));
    contrail::scene::build_model(&src, &file).unwrap_or_else(|e| panic!("{e}"))
}

/// Run a model, keeping every record in memory.
pub fn solve(model: &Model) -> (Result<RunSummary, SolveError>, Memory) {
    let src = contrail::scene::SceneSource {
        origin: "test".into(),
        text: String::new(),
    };
    let info = contrail::run_info(&src, &[], model);
    let mut mem = Memory::default();
    let r = run(model, &info, &mut mem, &AtomicBool::new(false));
    (r, mem)
}

/// Run and require completion.
pub fn solve_ok(model: &Model) -> (RunSummary, Memory) {
    let (r, m) = solve(model);
    (r.unwrap_or_else(|e| panic!("{}: {e}", model.name)), m)
}
