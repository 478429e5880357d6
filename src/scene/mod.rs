//! Scenes: TOML files (or built-ins) → checked [`SceneFile`] → [`crate::model::Model`].
//!
//! Errors name the file, the line and column, and how to fix it; `--set key.path=value`
//! overrides are applied to the parsed TOML before it is checked.

mod axisymmetry;
mod body_model;
mod build;
pub mod build_pairs;
pub mod build_solid;
pub mod build_surface_pairs;
pub mod builtin;
mod edge_slave;
pub mod extrude;
pub mod fillet;
pub mod initial_contact;
mod mesh;
pub mod mesh_spec;
pub mod model_advice;
pub mod model_advice_axisym;
pub mod monitors;
mod overclosure;
mod overrides;
mod plane_to_3d;
pub mod pressure;
pub mod revolve;
pub mod rigid_spec;
pub mod types;
pub mod validate;

pub use build::{build, build_any, build_model, AnyProblem};
pub use overrides::apply_override;
pub use types::SceneFile;

use std::path::Path;

/// A scene that could not be read, parsed or resolved.
#[derive(Debug, thiserror::Error)]
pub enum SceneError {
    #[error("{origin}: cannot read: {source}\n  hint: give a scene file path or a built-in name (`contrail scenes` lists them)")]
    Read { origin: String, source: std::io::Error },
    #[error("{origin}:{line}:{column}: {message}\n  hint: {hint}")]
    Syntax {
        origin: String,
        line: usize,
        column: usize,
        message: String,
        hint: String,
    },
    #[error("{origin}: --set {set}: {message}\n  hint: use --set table.key=value, e.g. --set stepping.increments=200 or --set contact.mu=0.1")]
    Override {
        origin: String,
        set: String,
        message: String,
    },
    /// A body's mesh file could not be read or used (the error names the file and the fix).
    #[error("{origin}{location}: body `{body}`: {error}")]
    Mesh {
        origin: String,
        location: String,
        body: String,
        error: Box<crate::model::gmsh::GmshError>,
    },
    #[error("{origin}{location}: {message}\n  hint: {hint}")]
    Invalid {
        origin: String,
        location: String,
        message: String,
        hint: String,
    },
}

/// A scene text with where it came from.
#[derive(Debug, Clone)]
pub struct SceneSource {
    /// `builtin:NAME` or the file path.
    pub origin: String,
    pub text: String,
}

impl SceneSource {
    /// A built-in name or a path.
    pub fn resolve(name_or_path: &str) -> Result<Self, SceneError> {
        if let Some(b) = builtin::find(name_or_path) {
            return Ok(SceneSource {
                origin: format!("builtin:{}", b.name),
                text: b.text.to_string(),
            });
        }
        let text = std::fs::read_to_string(Path::new(name_or_path)).map_err(|source| SceneError::Read {
            origin: name_or_path.to_string(),
            source,
        })?;
        Ok(SceneSource {
            origin: name_or_path.to_string(),
            text,
        })
    }
}

/// Line and column (1-based) of a byte offset.
pub fn line_col(text: &str, offset: usize) -> (usize, usize) {
    let before = &text[..offset.min(text.len())];
    let line = before.matches('\n').count() + 1;
    let col = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
    (line, col)
}

/// Solver keys of earlier versions, and why they are gone.
const REMOVED_KEYS: [(&str, &str); 4] = [
    ("line_search", "the line search on the merit function is always on"),
    ("line_search_rule", "the line search is the merit function's, always on"),
    (
        "freeze_after",
        "no point is frozen: the contact states are the complementarity functions' (docs/methods.md)",
    ),
    (
        "max_settling_iterations",
        "no settling budget: a contact front settles within max_iterations (docs/methods.md)",
    ),
];

fn hint_for(message: &str) -> String {
    if let Some((key, why)) = REMOVED_KEYS.iter().find(|(k, _)| message.contains(&format!("`{k}`"))) {
        return format!("remove the key `{key}`: {why}");
    }
    if message.contains("unknown field") {
        "remove or correct the key; the accepted keys are listed above (schemas/scene.schema.json documents them)"
            .into()
    } else if message.contains("missing field") {
        "add the missing key".into()
    } else if message.contains("did not match any variant") {
        "a node selection is a set name (\"left\") or a table like { x = 0.0 }; a value is a number or [[t, v], ...]"
            .into()
    } else {
        "check the TOML syntax and the value's type".into()
    }
}

/// Parse and check a scene text, then apply `--set` overrides and check again.
pub fn parse(source: &SceneSource, sets: &[String]) -> Result<SceneFile, SceneError> {
    let first: SceneFile = toml::from_str(&source.text).map_err(|e| {
        let (line, column) = e.span().map_or((0, 0), |s| line_col(&source.text, s.start));
        let message = e.message().to_string();
        SceneError::Syntax {
            origin: source.origin.clone(),
            line,
            column,
            hint: hint_for(&message),
            message,
        }
    })?;
    if sets.is_empty() {
        return extrude::apply(source, first);
    }
    let mut table: toml::Table = toml::from_str(&source.text).expect("parsed above");
    for set in sets {
        apply_override(&mut table, set).map_err(|message| SceneError::Override {
            origin: source.origin.clone(),
            set: shorten(set),
            message,
        })?;
    }
    let names = table.clone();
    let file = toml::Value::Table(table)
        .try_into()
        .map_err(|e: toml::de::Error| SceneError::Override {
            origin: source.origin.clone(),
            set: sets.join(" --set "),
            message: overrides::unknown_name(&names, sets, e.message()).unwrap_or_else(|| e.message().to_string()),
        })?;
    extrude::apply(source, file)
}

/// A `--set` argument for an error message: at most 120 characters.
fn shorten(set: &str) -> String {
    match set.char_indices().nth(120) {
        Some((cut, _)) => format!("{}… ({} characters)", &set[..cut], set.len()),
        None => set.to_string(),
    }
}

/// Location `:line:col` of the first quoted occurrence of `needle` in the text (for semantic
/// errors about names), or an empty string.
pub(crate) fn locate(text: &str, needle: &str) -> String {
    let quoted = format!("\"{needle}\"");
    text.find(&quoted).map_or(String::new(), |off| {
        let (l, c) = line_col(text, off);
        format!(":{l}:{c}")
    })
}

#[cfg(test)]
mod tests;
