//! # contrail
//!
//! A finite-element solver (plane, axisymmetric and 3D) for frictional contact in the covariant description
//! (Konyukhov & Schweizerhof) with continuous transfer of history variables across master
//! segments, that reports everything it does to observers (MCAP, rerun, CSV, JSON lines).
//!
//! Data flow: [`scene`] (TOML) → [`model`] → kernels ([`element`], [`contact`]) →
//! [`assembly`] → [`solver`] (Newton, load stepping) → [`record`] (observers).

pub mod analysis;
pub mod assembly;
pub mod chart;
pub mod contact;
pub mod contact3d;
pub mod cpu;
pub mod element;
pub mod format;
pub mod linalg;
pub mod model;
pub mod problem;
pub mod record;
pub mod scene;
pub mod settings;
pub mod solver;
pub mod study;
pub mod sweep;
pub mod team;
pub mod threads;

/// Version of the crate (recorded in every run).
pub const VERSION: &str = env!("CARGO_PKG_VERSION");

/// Git revision the crate was built from (`unknown` outside a checkout).
pub const GIT_REVISION: &str = env!("CONTRAIL_GIT_REV");

/// Load a scene (built-in name or path), apply overrides and build its model.
pub fn load_scene(
    name_or_path: &str,
    sets: &[String],
) -> Result<(scene::SceneSource, problem::Problem), scene::SceneError> {
    let src = scene::SceneSource::resolve(name_or_path)?;
    let file = scene::parse(&src, sets)?;
    let problem = scene::build(&src, &file)?;
    Ok((src, problem))
}

/// Load a scene of either dimension (built-in name or path), apply overrides and build it.
pub fn load_any_scene(
    name_or_path: &str,
    sets: &[String],
) -> Result<(scene::SceneSource, scene::AnyProblem), scene::SceneError> {
    let src = scene::SceneSource::resolve(name_or_path)?;
    let file = scene::parse(&src, sets)?;
    let problem = scene::build_any(&src, &file)?;
    Ok((src, problem))
}

/// Run metadata for a model.
pub fn run_info<S: model::Dim>(
    src: &scene::SceneSource,
    sets: &[String],
    problem: &problem::Problem<S>,
) -> record::RunInfo {
    let model = &problem.model;
    let asm_free = assembly::DofMap::new(model).n_free;
    record::RunInfo {
        scene: model.name.clone(),
        scene_origin: src.origin.clone(),
        scene_text: src.text.clone(),
        overrides: sets.to_vec(),
        crate_version: VERSION.to_string(),
        git_revision: GIT_REVISION.to_string(),
        transfer: (model.contacts.iter().map(|c| c.transfer.name().to_string()))
            .chain(S::solid(model).into_iter().flat_map(|m| {
                (m.surface_contacts.iter()).map(|c| contact3d::transfer::scheme_name(c.transfer).to_string())
            }))
            .collect(),
        dofs: model.dof_count(),
        free_dofs: asm_free,
        settings: problem.settings.clone(),
    }
}
