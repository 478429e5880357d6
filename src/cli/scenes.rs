use super::out::outln;
use contrail::scene::builtin::{description, BUILTINS};
use std::process::ExitCode;

pub fn list() -> anyhow::Result<ExitCode> {
    for b in BUILTINS {
        outln!("{:<14} {}", b.name, description(b))?;
    }
    Ok(ExitCode::SUCCESS)
}
