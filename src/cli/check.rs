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
    let problem = build(&src, &scene)?;
    let m = &problem.model;
    let slaves: usize = m.contacts.iter().map(|c| c.slaves.len()).sum();
    outln!(
        "{}: ok — {} bodies, {} nodes, {} elements, {} DOFs ({} prescribed), {} rigid bodies, {} contact pairs ({} slave points), {} increments to t = {}",
        src.origin,
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
    Ok(ExitCode::SUCCESS)
}
