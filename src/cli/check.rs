//! `contrail check SCENE`: validate a scene (and build its model) without running it.

use super::out::outln;
use contrail::scene::types::ArcSide;
use contrail::scene::{build, parse, SceneSource};
use std::process::ExitCode;

#[derive(clap::Args, Debug)]
pub struct CheckArgs {
    /// Built-in scene name or path to a scene TOML file.
    pub scene: String,
    /// Override a scene value, e.g. --set contact.mu=0.1 (repeatable).
    #[arg(long = "set", value_name = "KEY=VALUE")]
    pub sets: Vec<String>,
}

pub fn check(a: CheckArgs) -> anyhow::Result<ExitCode> {
    let src = SceneSource::resolve(&a.scene)?;
    let scene = parse(&src, &a.sets)?;
    if contrail::scene::build_solid::is_3d(&scene) {
        let problem = contrail::scene::build_solid::build_solid(&src, &scene)?;
        report_solid(&src.origin, &problem)?;
    } else {
        let problem = build(&src, &scene)?;
        report_plane(&src.origin, &problem)?;
        report_rigid_and_contacts(&scene, &problem.model)?;
    }
    Ok(ExitCode::SUCCESS)
}

/// A 3D scene: its size, its bodies and the smaller model that would do, if any.
fn report_solid(origin: &str, problem: &contrail::problem::Problem<contrail::model::Solid>) -> anyhow::Result<()> {
    let m = &problem.model;
    outln!(
        "{}: ok — 3D, {} bodies, {} nodes, {} hexahedra, {} DOFs ({} prescribed), {} increments to t = {}",
        origin,
        m.bodies.len(),
        m.nodes.len(),
        m.elements.len(),
        m.dof_count(),
        m.prescribed.len(),
        problem.settings.stepping.increments,
        problem.settings.stepping.end
    )?;
    for b in &m.bodies {
        outln!("  body {}: 3d, {}", b.name, b.kind.name())?;
    }
    if let Some(advice) = contrail::scene::model_advice::plane_advice(m) {
        outln!("  {}", advice.line())?;
    }
    if let Some(advice) = contrail::scene::model_advice_axisym::axisymmetric_advice(m) {
        outln!("  {}", advice.line())?;
    }
    Ok(())
}

/// A 2D scene: its size, its bodies' models and the builder's notes.
fn report_plane(origin: &str, problem: &contrail::problem::Problem) -> anyhow::Result<()> {
    let m = &problem.model;
    let slaves: usize = m.contacts.iter().map(|c| c.slaves.len()).sum();
    outln!(
        "{}: ok — {} bodies, {} nodes, {} elements, {} DOFs ({} prescribed), {} rigid bodies, {} contact pairs ({} slave points), {} increments to t = {}",
        origin,
        m.bodies.len(),
        m.nodes.len(),
        m.elements.len(),
        m.dof_count(),
        m.prescribed.len(),
        m.rigid.len(),
        m.contacts.len(),
        slaves,
        problem.settings.stepping.increments,
        problem.settings.stepping.end
    )?;
    for b in &m.bodies {
        outln!("  body {}: {}", b.name, b.kinematics.label())?;
    }
    for note in &m.notes {
        outln!("  note: {note}")?;
    }
    Ok(())
}

/// A 2D scene's rigid arcs and outlines (which side is solid) and its contact pairs.
fn report_rigid_and_contacts(
    scene: &contrail::scene::types::SceneFile,
    m: &contrail::model::Model,
) -> anyhow::Result<()> {
    for r in &scene.rigid {
        if let Some(arc) = &r.arc {
            let side = ArcSide::of(arc.from_deg, arc.to_deg);
            outln!(
                "  rigid {}: arc about [{}, {}], r = {}, {} from {}° to {}°: the rigid body is {} the circle ({}){}",
                r.name,
                arc.centre[0],
                arc.centre[1],
                arc.radius,
                if side == ArcSide::Inside {
                    "counter-clockwise"
                } else {
                    "clockwise"
                },
                arc.from_deg,
                arc.to_deg,
                side.name(),
                if side == ArcSide::Inside { "a disc" } else { "a cavity" },
                if arc.side.is_none() {
                    format!("; state it with side = \"{}\"", side.name())
                } else {
                    String::new()
                }
            )?;
        }
    }
    for (ib, body) in m.rigid.iter().enumerate() {
        if let contrail::model::RigidShape::Surface { pieces } = &body.shape {
            outln!(
                "  {}",
                outline_side(
                    &body.name,
                    pieces,
                    &contrail::scene::build_pairs::convex_vertices(m, ib)
                )
            )?;
        }
    }
    for c in &m.contacts {
        outln!(
            "  contact {}: {} slaves, ε_N = {:e}, ε_T = {:e}, μ = {}, transfer = {}",
            c.name,
            c.slaves.len(),
            c.law.eps_n,
            c.law.eps_t,
            c.law.mu,
            c.transfer.name()
        )?;
    }
    Ok(())
}

/// Where a rigid outline's solid is: the inward normal (the tangent turned +90°) in the
/// middle of its first piece, and its convex vertices.
fn outline_side(name: &str, pieces: &[contrail::model::Piece], convex: &[usize]) -> String {
    let (p, t) = pieces[0].eval(0.0);
    let len = t[0].hypot(t[1]);
    let inward = [-t[1] / len + 0.0, t[0] / len + 0.0];
    let (a, _) = pieces[0].eval(-1.0);
    let (b, _) = pieces[0].eval(1.0);
    let vertices = if convex.is_empty() {
        "no convex vertex".to_string()
    } else {
        format!("convex vertices {convex:?} (contact points where a pair's slave nodes face them)")
    };
    format!(
        "rigid {name}: outline of {} pieces, the rigid body on the left of travel: its first piece runs from [{:.4}, {:.4}] to [{:.4}, {:.4}], solid towards [{:.3}, {:.3}] from [{:.4}, {:.4}]; {vertices}",
        pieces.len(),
        a[0],
        a[1],
        b[0],
        b[1],
        inward[0],
        inward[1],
        p[0],
        p[1]
    )
}
