//! `contrail export FILE.mcap --vtu DIR`: a recording as a ParaView VTU series.

use super::out::outln;
use super::BadInput;
use contrail::analysis::export::{export_vtu, matches, matches_solid};
use contrail::analysis::recording::Recording;
use contrail::model::AnyModel;
use contrail::scene::{build_any, parse, AnyProblem, SceneSource};
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(clap::Args, Debug)]
pub struct ExportArgs {
    /// A recording made with `contrail run --out FILE.mcap`.
    pub file: PathBuf,
    /// Write `DIR/NAME.pvd` and the `.vtu` files in `DIR/NAME/` (NAME: the recording's file
    /// name without `.mcap`): the mesh with displacement, stress and strain, and the contact
    /// points, for every increment the recording has positions of.
    #[arg(long, value_name = "DIR")]
    pub vtu: PathBuf,
}

/// The model of the run, rebuilt from the scene attached to the recording and its
/// overrides (for the materials, which the recording does not hold).
fn rebuild(r: &Recording) -> Result<AnyModel, String> {
    let (name, text) = r.scene_file.clone().ok_or("the recording has no scene attachment")?;
    let origin = r.metadata.get("scene_origin").cloned().unwrap_or(name);
    let src = SceneSource { origin, text };
    let scene = parse(&src, &r.metadata_list("overrides")).map_err(|e| e.to_string())?;
    let same = match build_any(&src, &scene).map_err(|e| e.to_string())? {
        AnyProblem::Plane(p) => matches(&p.model, r).then_some(AnyModel::Plane(p.model)),
        AnyProblem::Solid(p) => matches_solid(&p.model, r).then_some(AnyModel::Solid(p.model)),
    };
    same.ok_or_else(|| "the scene attached to the recording no longer gives the recorded mesh".into())
}

pub fn export(a: ExportArgs) -> anyhow::Result<ExitCode> {
    let r = Recording::open(&a.file).map_err(|e| BadInput(e.to_string()))?;
    let stem = a
        .file
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_else(|| "run".into());
    let pvd = a.vtu.join(format!("{stem}.pvd"));
    let model = rebuild(&r);
    if let Err(why) = &model {
        eprintln!("warning: stress and strain are not exported: {why}");
    }
    let s = export_vtu(&r, model.as_ref().ok().map(AnyModel::view), &pvd)
        .map_err(|e| BadInput(format!("{}: cannot write the VTU series: {e}", pvd.display())))?;
    outln!(
        "written      {} ({} increments{})",
        pvd.display(),
        s.steps,
        if s.fields {
            ""
        } else {
            "; displacement and contact points only"
        }
    )?;
    Ok(ExitCode::SUCCESS)
}
