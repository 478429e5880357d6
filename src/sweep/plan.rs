//! Sweep plans: TOML files naming scenes, the `--set` keys to vary (a grid, a list, or a
//! list crossed with a grid), the reference the errors are measured against, and the checks
//! that flag a completed run as a wrong answer.
//!
//! ```toml
//! name = "smoke"
//! [[study]]
//! name = "crossing"                 # default: the scene name
//! scene = "crossing"                # built-in name, or a path relative to the plan file
//! set = ["stepping.increments=40"]  # fixed overrides
//! family = ["contact.transfer"]     # keys naming a run's series in the Pareto chart
//! grid = { "contact.transfer" = ["continuous", "straightforward"], "contact.eps_t" = [1e3, 1e4] }
//! list = [{ "contact.mu" = 0.1 }, { "contact.mu" = 0.3 }]   # each entry crossed with the grid
//! reference = { kind = "finest", where = { "contact.transfer" = "continuous" } }
//! checks = { max_crossing_jump_rel = 1e-3, keep_contact = ["corner"], max_error_rel = 0.05, max_peak_error = 0.05 }
//! ```

use super::SweepError;
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;
use std::path::Path;

/// A sweep plan.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Plan {
    /// Name of the sweep (charts' titles).
    pub name: String,
    #[serde(default)]
    pub description: String,
    /// The scenes and what to vary in each.
    #[serde(rename = "study")]
    pub studies: Vec<StudyPlan>,
}

/// One scene and its runs.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StudyPlan {
    /// Name of this part of the plan (default: the scene).
    #[serde(default)]
    pub name: String,
    pub scene: String,
    /// Overrides applied to every run, before the varied ones.
    #[serde(default)]
    pub set: Vec<String>,
    /// Keys whose values name a run's family (series of the Pareto chart); default: the
    /// study name.
    #[serde(default)]
    pub family: Vec<String>,
    /// Every combination of these values (`--set` key → values).
    #[serde(default)]
    pub grid: BTreeMap<String, Vec<toml::Value>>,
    /// Explicit parameter sets, each crossed with the grid.
    #[serde(default)]
    pub list: Vec<BTreeMap<String, toml::Value>>,
    #[serde(default)]
    pub reference: Reference,
    #[serde(default)]
    pub checks: Checks,
    /// Curve points with `x ≥ plateau_from` make the plateau (default: none measured).
    #[serde(default)]
    pub plateau_from: Option<f64>,
    /// Points on either side of a crossing in the roughness fit.
    #[serde(default = "default_window")]
    pub roughness_window: usize,
    /// `[x0, x1]`: measure the crossing spikes as the largest |F − cubic fit| over the curve
    /// points with `x ∈ [x0, x1]`, over the curve's peak |F| (the metric `spike_rel`).
    #[serde(default)]
    pub spike_window: Option<[f64; 2]>,
}

fn default_window() -> usize {
    6
}

/// What the errors of a run are measured against.
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "kebab-case", deny_unknown_fields)]
pub enum Reference {
    /// No curve reference (crossing jumps and roughness are still measured).
    #[default]
    None,
    /// The completed run of this study (or of the study named `study`, so that the
    /// reference is none of the runs charted) matching `where` with the most DOFs, then the
    /// most increments.
    Finest {
        #[serde(default, rename = "where")]
        filter: BTreeMap<String, toml::Value>,
        #[serde(default)]
        study: Option<String>,
    },
    /// An external curve: a CSV file with a header (columns `x` and `y`, or the named ones).
    Csv {
        path: String,
        #[serde(default = "col_x")]
        x: String,
        #[serde(default = "col_y")]
        y: String,
    },
    /// Hertz line contact (half model): half-width and peak pressure.
    Hertz { young: f64, poisson: f64, radius: f64 },
    /// Hertz point contact of a rigid sphere, axisymmetric or 3D: contact radius and peak
    /// pressure ([`crate::analysis::hertz_point`]); a 3D model is `1/copies` of the whole (4: a
    /// quarter model), an axisymmetric model's forces are totals.
    HertzPoint {
        young: f64,
        poisson: f64,
        radius: f64,
        #[serde(default = "unit")]
        copies: f64,
    },
    /// Coulomb sliding: total tangential over normal reaction equals μ at the end
    /// (`mu` default: the run's `contact.mu`).
    Coulomb {
        #[serde(default)]
        mu: Option<f64>,
    },
    /// A known value of the first monitor: its `quantity` (`"force"` or `"displacement"`)
    /// times `scale`, averaged over the increments with `t ∈ [from, to]` (default: the last
    /// increment alone), against `value` (Euler–Eytelwein's `T2/T1` over a plateau of the
    /// capstan, the elastica's tip deflection over `L`, a patch test's force).
    Value {
        value: f64,
        #[serde(default = "quantity_force")]
        quantity: MonitorQuantity,
        #[serde(default = "unit")]
        scale: f64,
        #[serde(default)]
        from: Option<f64>,
        #[serde(default)]
        to: Option<f64>,
    },
}

/// Which column of a monitor a [`Reference::Value`] reads.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum MonitorQuantity {
    Force,
    Displacement,
}

fn quantity_force() -> MonitorQuantity {
    MonitorQuantity::Force
}
fn unit() -> f64 {
    1.0
}

fn col_x() -> String {
    "x".into()
}
fn col_y() -> String {
    "y".into()
}

/// Bounds that flag a completed run as a wrong answer (or lost contact).
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Checks {
    /// Contact pairs that must stay closed once closed (else `lost-contact`).
    #[serde(default)]
    pub keep_contact: Vec<String>,
    /// Largest allowed relative max curve error (else `wrong-answer`).
    #[serde(default)]
    pub max_error_rel: Option<f64>,
    /// Largest allowed relative error of the peak force against the reference's (else
    /// `wrong-answer`): for curves whose pointwise error is dominated by a steep drop that a
    /// small shift in `x` turns into a large error (the strip's end passing the corner).
    #[serde(default)]
    pub max_peak_error: Option<f64>,
    /// Largest allowed relative jump of the trial traction at a crossing (else `wrong-answer`).
    #[serde(default)]
    pub max_crossing_jump_rel: Option<f64>,
    /// Largest allowed relative error against the analytic reference (else `wrong-answer`).
    #[serde(default)]
    pub max_analytic_error: Option<f64>,
}

fn line_col(text: &str, offset: usize) -> (usize, usize) {
    crate::scene::line_col(text, offset)
}

impl Plan {
    /// Parse a plan; `origin` names it in errors, `dir` resolves relative scene and CSV paths.
    pub fn parse(text: &str, origin: &str, dir: &Path) -> Result<Plan, SweepError> {
        let mut plan: Plan = toml::from_str(text).map_err(|e| {
            let (line, column) = e.span().map_or((0, 0), |s| line_col(text, s.start));
            SweepError::Plan {
                origin: origin.to_string(),
                line,
                column,
                message: e.message().to_string(),
                hint: "see sweeps/smoke.toml for the plan format; keys are name, description and [[study]] tables \
                       (name, scene, set, family, grid, list, reference, checks, plateau_from, roughness_window, \
                       spike_window)"
                    .into(),
            }
        })?;
        let invalid = |message: String, needle: &str, hint: &str| {
            let location = text.find(needle).map_or((0, 0), |o| line_col(text, o));
            SweepError::Plan {
                origin: origin.to_string(),
                line: location.0,
                column: location.1,
                message,
                hint: hint.to_string(),
            }
        };
        if plan.studies.is_empty() {
            return Err(invalid(
                "the plan has no [[study]]".into(),
                "name",
                "add a [[study]] table with at least `scene`",
            ));
        }
        let mut names = std::collections::BTreeSet::new();
        for s in &mut plan.studies {
            if s.name.is_empty() {
                s.name = Path::new(&s.scene)
                    .file_stem()
                    .map_or(s.scene.clone(), |f| f.to_string_lossy().into_owned());
            }
            if !names.insert(s.name.clone()) {
                return Err(invalid(
                    format!("two studies are named `{}`", s.name),
                    &s.scene,
                    "give each [[study]] its own `name`",
                ));
            }
            for (k, v) in &s.grid {
                if v.is_empty() {
                    return Err(invalid(
                        format!("grid key `{k}` has no values"),
                        k,
                        "list at least one value, or remove the key",
                    ));
                }
            }
            if crate::scene::builtin::find(&s.scene).is_none() && Path::new(&s.scene).is_relative() {
                s.scene = dir.join(&s.scene).display().to_string();
            }
            if let Reference::Csv { path, .. } = &mut s.reference {
                if Path::new(path.as_str()).is_relative() {
                    *path = dir.join(path.as_str()).display().to_string();
                }
            }
        }
        Ok(plan)
    }

    /// Read and parse a plan file.
    pub fn load(path: &Path) -> Result<Plan, SweepError> {
        let text = std::fs::read_to_string(path).map_err(|source| SweepError::Io {
            path: path.display().to_string(),
            source,
        })?;
        let dir = path.parent().unwrap_or(Path::new(""));
        Plan::parse(&text, &path.display().to_string(), dir)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const PLAN: &str = r#"
name = "t"
[[study]]
scene = "crossing"
set = ["stepping.increments=20"]
grid = { "contact.transfer" = ["continuous", "straightforward"], "contact.eps_t" = [1e3, 1e4] }
reference = { kind = "finest", where = { "contact.transfer" = "continuous" } }
checks = { max_crossing_jump_rel = 1e-3 }
"#;

    #[test]
    fn parses_and_names_the_study() {
        let p = Plan::parse(PLAN, "t.toml", Path::new("")).unwrap();
        assert_eq!(p.studies[0].name, "crossing");
        assert_eq!(p.studies[0].grid.len(), 2);
        assert!(matches!(p.studies[0].reference, Reference::Finest { .. }));
        assert_eq!(p.studies[0].roughness_window, 6);
    }

    #[test]
    fn unknown_keys_are_errors_with_a_line() {
        let bad = PLAN.replace("set = ", "sets = ");
        let e = Plan::parse(&bad, "t.toml", Path::new("")).unwrap_err().to_string();
        assert!(e.contains("t.toml:") && e.contains("sets"), "{e}");
        let bad = PLAN.replace("kind = \"finest\"", "kind = \"best\"");
        assert!(Plan::parse(&bad, "t.toml", Path::new("")).is_err());
        let bad = PLAN.replace("max_crossing_jump_rel", "max_jump");
        assert!(Plan::parse(&bad, "t.toml", Path::new("")).is_err());
        let bad = PLAN.replace("[1e3, 1e4]", "[]");
        let e = Plan::parse(&bad, "t.toml", Path::new("")).unwrap_err().to_string();
        assert!(e.contains("no values"), "{e}");
        assert!(Plan::parse("name = \"x\"\nstudy = []", "t.toml", Path::new("")).is_err());
    }

    #[test]
    fn relative_scene_paths_follow_the_plan() {
        let p = Plan::parse(
            "name = \"x\"\n[[study]]\nscene = \"my.toml\"\n",
            "d/p.toml",
            Path::new("d"),
        )
        .unwrap();
        assert_eq!(p.studies[0].scene, Path::new("d").join("my.toml").display().to_string());
        assert_eq!(p.studies[0].name, "my");
    }
}
