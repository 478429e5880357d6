//! `contrail scenes`: the built-in scenes, one of them as a template (`--show NAME`), and the
//! "did you mean" for a scene argument that is neither a built-in nor a file.

use super::out::{out, outln};
use super::BadInput;
use contrail::scene::builtin::{description, find, BUILTINS};
use std::path::Path;
use std::process::ExitCode;

#[derive(clap::Args, Debug)]
pub struct ScenesArgs {
    /// Print the TOML of a built-in scene, to start a scene file from:
    /// `contrail scenes --show hertz > my-hertz.toml`.
    #[arg(long, value_name = "NAME")]
    pub show: Option<String>,
}

pub fn scenes(a: ScenesArgs) -> anyhow::Result<ExitCode> {
    match a.show {
        Some(name) => {
            let b = find(&name).ok_or_else(|| BadInput(unknown_scene(&name)))?;
            out!("{}", b.text)?;
            Ok(ExitCode::SUCCESS)
        }
        None => {
            for b in BUILTINS {
                outln!("{:<14} {}", b.name, description(b))?;
            }
            outln!("\n(`contrail scenes --show NAME` prints one as a template)")?;
            Ok(ExitCode::SUCCESS)
        }
    }
}

/// The built-in scene closest to `name`, if it is close (a few typos, or a prefix).
pub fn closest(name: &str) -> Option<&'static str> {
    super::suggest::closest(name.trim_end_matches(".toml"), BUILTINS.iter().map(|b| b.name))
}

fn unknown_scene(name: &str) -> String {
    let names: Vec<&str> = BUILTINS.iter().map(|b| b.name).collect();
    let mut m = format!("`{name}` is neither a built-in scene nor a scene file");
    match closest(name) {
        Some(s) => m.push_str(&format!("\n  hint: did you mean `{s}`?")),
        None => m.push_str(&format!("\n  hint: built-in scenes are {}", names.join(", "))),
    }
    m
}

/// Check a scene argument before it is loaded: a built-in name, or a file that exists.
/// Anything else is bad input with a "did you mean" when a built-in name is close.
pub fn check_scene_arg(arg: &str) -> Result<(), BadInput> {
    if find(arg).is_some() || Path::new(arg).exists() {
        return Ok(());
    }
    let looks_like_path = arg.contains('/') || arg.contains('\\') || arg.ends_with(".toml");
    if looks_like_path {
        let stem = Path::new(arg).file_stem().and_then(|s| s.to_str()).unwrap_or(arg);
        let hint = match closest(stem) {
            Some(s) => format!("did you mean the built-in scene `{s}`?"),
            None => "give a scene file path or a built-in name (`contrail scenes` lists them)".into(),
        };
        return Err(BadInput(format!("{arg}: no such scene file\n  hint: {hint}")));
    }
    Err(BadInput(unknown_scene(arg)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn typos_of_scene_names_are_recognised() {
        assert_eq!(closest("strip-chanel"), Some("strip-channel"));
        assert_eq!(closest("herz"), Some("hertz"));
        assert_eq!(closest("block"), Some("block-slide"));
        assert_eq!(closest("cantilevr"), Some("cantilever"));
        assert_eq!(closest("something-else-entirely"), None);
    }

    #[test]
    fn unknown_scenes_get_a_hint() {
        let e = check_scene_arg("strip-chanel").unwrap_err().0;
        assert!(e.contains("did you mean `strip-channel`?"), "{e}");
        let e = check_scene_arg("nothing/here.toml").unwrap_err().0;
        assert!(e.contains("no such scene file"), "{e}");
        assert!(check_scene_arg("hertz").is_ok());
    }
}
