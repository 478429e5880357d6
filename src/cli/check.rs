use contrail::scene::{build_model, parse, SceneSource};
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
    let m = build_model(&src, &scene)?;
    let slaves: usize = m.contacts.iter().map(|c| c.slaves.len()).sum();
    println!(
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
        m.stepping.increments,
        m.stepping.end
    );
    for c in &m.contacts {
        println!(
            "  contact {}: {} slaves, ε_N = {:e}, ε_T = {:e}, μ = {}, transfer = {}",
            c.name,
            c.slaves.len(),
            c.law.eps_n,
            c.law.eps_t,
            c.law.mu,
            c.transfer.name()
        );
    }
    Ok(ExitCode::SUCCESS)
}
