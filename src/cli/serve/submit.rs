//! Submissions: a run (a built-in scene or a scene's TOML text, with `--set` overrides) or a
//! sweep plan, checked against the limits and the scene format, given the stable ids the
//! sweeps use (`sweep::expand`), and catalogued once (a resubmission returns the catalogued
//! run unless a re-run is asked for).

use super::catalogue::NewRun;
use super::errors::ApiError;
use super::state::Service;
use contrail::scene::types::MeshSpec;
use contrail::scene::{builtin, SceneFile, SceneSource};
use contrail::sweep::{expand, fnv1a, Plan, PlannedRun};
use serde::Deserialize;
use std::collections::BTreeMap;
use std::path::Path;

/// `POST /api/runs`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RunRequest {
    /// A built-in scene name.
    #[serde(default)]
    pub scene: Option<String>,
    /// Or a scene's TOML text.
    #[serde(default)]
    pub scene_toml: Option<String>,
    /// `key.path=value` overrides.
    #[serde(default)]
    pub set: Vec<String>,
    /// Solve again even if the run is catalogued.
    #[serde(default)]
    pub rerun: bool,
    /// Node positions every N-th increment in the recording.
    #[serde(default)]
    pub positions_every: Option<usize>,
}

/// `POST /api/sweeps`.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SweepRequest {
    /// The plan's TOML text (the format of `contrail sweep`; scenes must be built-in names).
    pub plan: String,
    #[serde(default)]
    pub rerun: bool,
    #[serde(default)]
    pub positions_every: Option<usize>,
}

/// A run ready to catalogue.
#[derive(Debug, Clone)]
pub struct Checked {
    pub id: String,
    pub scene: String,
    pub scene_ref: String,
    pub sets: Vec<String>,
    pub params: BTreeMap<String, String>,
}

/// `key=value` overrides as parameters (string values without their quotes).
pub fn params_of(sets: &[String]) -> BTreeMap<String, String> {
    sets.iter()
        .filter_map(|s| s.split_once('='))
        .map(|(k, v)| {
            let v = v.trim();
            let v = v.strip_prefix('"').and_then(|x| x.strip_suffix('"')).unwrap_or(v);
            (k.trim().to_string(), v.to_string())
        })
        .collect()
}

fn check_sets(svc: &Service, sets: &[String]) -> Result<(), ApiError> {
    if sets.len() > svc.limits.sets {
        return Err(ApiError::bad(
            format!("{} overrides; at most {} are accepted", sets.len(), svc.limits.sets),
            "put the changes into the scene's TOML text instead",
        ));
    }
    for s in sets {
        if s.len() > 4096 || !s.contains('=') {
            return Err(ApiError::bad(
                format!("override `{}` is not KEY=VALUE", s.chars().take(80).collect::<String>()),
                "write overrides as key.path=value, e.g. contact.mu=0.3",
            ));
        }
    }
    Ok(())
}

/// The elements of a scene's generated meshes; a mesh file is refused (the service does not
/// read files on its machine for a client), except a built-in scene's own 2D mesh.
fn scene_elements(file: &SceneFile, sets: &[String], builtin: bool) -> Result<usize, ApiError> {
    let mut elements = 0usize;
    for b in &file.bodies {
        match &b.mesh {
            MeshSpec::Gmsh { .. } if builtin && !sets.iter().any(|s| s.contains("mesh")) => {}
            MeshSpec::Gmsh { file } | MeshSpec::Gmsh3d { file } => {
                return Err(ApiError::bad(
                    format!("body `{}` reads the mesh file `{file}` from the server", b.name),
                    "scenes sent to the service use generated meshes (rectangle, annulus, box, \
                     revolved, hemisphere-shell, sphere-shell); run Gmsh scenes with `contrail run`",
                ))
            }
            generated => elements = elements.saturating_add(generated.element_count() as usize),
        }
    }
    Ok(elements)
}

/// Parse the scene with its overrides (no mesh is built) and check the service's limits.
fn check_scene(svc: &Service, src: &SceneSource, sets: &[String], builtin: bool) -> Result<SceneFile, ApiError> {
    let file = contrail::scene::parse(src, sets)
        .map_err(|e| ApiError::bad(e.to_string(), "check the scene with `contrail check SCENE --set ...`"))?;
    let elements = scene_elements(&file, sets, builtin)?;
    if elements > svc.limits.elements {
        return Err(ApiError::bad(
            format!(
                "the scene has {elements} elements; this service solves at most {}",
                svc.limits.elements
            ),
            "use a coarser mesh, or run it with `contrail run` or on the Slurm backend",
        ));
    }
    Ok(file)
}

fn unknown_scene(name: &str) -> ApiError {
    let names: Vec<&str> = builtin::BUILTINS.iter().map(|b| b.name).collect();
    ApiError::bad(
        format!(
            "`{}` is not a built-in scene",
            name.chars().take(80).collect::<String>()
        ),
        format!(
            "built-in scenes: {}; or send the scene's TOML text as `scene_toml`",
            names.join(", ")
        ),
    )
}

/// A study name usable in ids (letters, digits, `-`, `_`).
fn id_name(name: &str) -> String {
    let s: String = name
        .chars()
        .map(|c| if c.is_ascii_alphanumeric() || c == '_' { c } else { '-' })
        .take(48)
        .collect();
    let s = s.trim_matches('-').to_string();
    if s.is_empty() {
        "scene".into()
    } else {
        s
    }
}

/// The sweep's stable id of one run: a one-study plan of the scene with these overrides.
fn planned(name: &str, scene_ref: &str, sets: &[String]) -> Result<PlannedRun, ApiError> {
    let plan: Plan = serde_json::from_value(serde_json::json!({
        "name": name,
        "study": [{ "name": name, "scene": scene_ref, "set": sets }],
    }))
    .map_err(ApiError::internal)?;
    let mut runs = expand(&plan).map_err(|e| ApiError::bad(e.to_string(), ""))?;
    runs.pop().ok_or_else(|| ApiError::internal("the plan has no run"))
}

/// Check a run request and give it its id.
pub fn check_run(svc: &Service, r: &RunRequest) -> Result<Checked, ApiError> {
    check_sets(svc, &r.set)?;
    let (src, scene_ref, builtin) = match (&r.scene, &r.scene_toml) {
        (Some(name), None) => {
            let b = builtin::find(name).ok_or_else(|| unknown_scene(name))?;
            let src = SceneSource {
                origin: format!("builtin:{}", b.name),
                text: b.text.to_string(),
            };
            (src, b.name.to_string(), true)
        }
        (None, Some(text)) => {
            if text.len() > svc.limits.scene_bytes {
                return Err(ApiError::new(
                    axum::http::StatusCode::PAYLOAD_TOO_LARGE,
                    "too-large",
                    format!(
                        "the scene is {} bytes; at most {} are accepted",
                        text.len(),
                        svc.limits.scene_bytes
                    ),
                    "use a generated mesh rather than listing nodes",
                ));
            }
            let scene_ref = format!("scenes/{:016x}.toml", fnv1a(text));
            let src = SceneSource {
                origin: scene_ref.clone(),
                text: text.clone(),
            };
            (src, scene_ref, false)
        }
        _ => {
            return Err(ApiError::bad(
                "give either `scene` (a built-in name) or `scene_toml` (a scene's text)",
                "e.g. {\"scene\": \"crossing\", \"set\": [\"contact.mu=0.3\"]}",
            ))
        }
    };
    let file = check_scene(svc, &src, &r.set, builtin)?;
    if !builtin {
        store_scene(&svc.data, &scene_ref, &src.text)?;
    }
    let name = if builtin {
        scene_ref.clone()
    } else {
        id_name(&file.name)
    };
    let run = planned(&name, &scene_ref, &r.set)?;
    Ok(Checked {
        id: run.id,
        scene: file.name,
        scene_ref,
        sets: r.set.clone(),
        params: params_of(&r.set),
    })
}

fn store_scene(data: &Path, scene_ref: &str, text: &str) -> Result<(), ApiError> {
    let path = data.join(scene_ref);
    if path.exists() {
        return Ok(());
    }
    contrail::sweep::write_atomic(&path, text.as_bytes()).map_err(ApiError::internal)
}

/// Check a sweep plan; its runs with their ids (those of `contrail sweep`).
pub fn check_sweep(svc: &Service, r: &SweepRequest) -> Result<(String, Vec<Checked>), ApiError> {
    if r.plan.len() > svc.limits.scene_bytes {
        return Err(ApiError::bad("the plan is too large", "split it into several plans"));
    }
    let plan = Plan::parse(&r.plan, "plan", Path::new("")).map_err(|e| ApiError::bad(e.to_string(), ""))?;
    for s in &plan.studies {
        if builtin::find(&s.scene).is_none() {
            return Err(ApiError::bad(
                format!("study `{}`: `{}` is not a built-in scene", s.name, s.scene),
                "plans sent to the service name built-in scenes; send other scenes one by one as `scene_toml`",
            ));
        }
    }
    let runs = expand(&plan).map_err(|e| ApiError::bad(e.to_string(), ""))?;
    if runs.len() > svc.limits.sweep_runs {
        return Err(ApiError::bad(
            format!(
                "the plan has {} runs; at most {} are accepted",
                runs.len(),
                svc.limits.sweep_runs
            ),
            "split the plan",
        ));
    }
    let mut out = Vec::with_capacity(runs.len());
    for run in runs {
        check_sets(svc, &run.sets)?;
        let b = builtin::find(&run.scene).ok_or_else(|| unknown_scene(&run.scene))?;
        let src = SceneSource {
            origin: format!("builtin:{}", b.name),
            text: b.text.to_string(),
        };
        let file = check_scene(svc, &src, &run.sets, true).map_err(|mut e| {
            e.message = format!("run {}: {}", run.id, e.message);
            e
        })?;
        out.push(Checked {
            id: run.id,
            scene: file.name,
            scene_ref: run.scene,
            params: params_of(&run.sets),
            sets: run.sets,
        });
    }
    Ok((plan.name, out))
}

/// Catalogue a checked run (or find it); returns whether it is new (queued now) or re-run.
pub fn catalogue(
    svc: &Service,
    c: &Checked,
    sweep: Option<&str>,
    rerun: bool,
    positions_every: usize,
) -> Result<bool, ApiError> {
    let new = NewRun {
        id: &c.id,
        scene: &c.scene,
        scene_ref: &c.scene_ref,
        sets: &c.sets,
        params: &c.params,
        sweep,
        positions_every: positions_every.max(1),
    };
    let queued = svc.catalogue.insert(&new)? || (rerun && svc.catalogue.requeue(&c.id)?);
    if queued {
        svc.live
            .send("status", &c.id, serde_json::json!({ "status": "queued" }));
        svc.notify_work();
    }
    Ok(queued)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn overrides_become_parameters() {
        let p = params_of(&["contact.mu=0.3".into(), "contact.transfer=\"continuous\"".into()]);
        assert_eq!(p["contact.mu"], "0.3");
        assert_eq!(p["contact.transfer"], "continuous");
        assert_eq!(id_name("my scene/1"), "my-scene-1");
        assert_eq!(id_name("///"), "scene");
    }

    #[test]
    fn generated_meshes_are_counted_and_mesh_files_refused() {
        let count = |name: &str, sets: &[&str]| {
            let b = builtin::find(name).expect("a built-in scene");
            let src = SceneSource {
                origin: format!("builtin:{name}"),
                text: b.text.to_string(),
            };
            let sets: Vec<String> = sets.iter().map(|s| s.to_string()).collect();
            let file = contrail::scene::parse(&src, &sets).expect("the scene parses");
            scene_elements(&file, &sets, true)
        };
        // octants of 3 n²/4 cells per layer: 3·64·2 + 3·36·2
        assert_eq!(count("concentric-spheres", &[]).ok(), Some(600));
        assert_eq!(count("twisting-hemisphere", &[]).ok(), Some(13 * 13 * 6 + 3 * 64 * 2));
        assert_eq!(count("half-disc", &[]).ok(), Some(0), "a built-in's own 2D mesh file");
        let e = count("half-disc", &["body.disc.mesh.file=\"x.msh\""]).expect_err("refused");
        assert!(e.message.contains("from the server"), "{}", e.message);
    }

    #[test]
    fn a_single_run_has_the_id_a_sweep_gives_it() {
        let sets = vec!["stepping.increments=40".to_string()];
        let single = planned("crossing", "crossing", &sets).unwrap();
        let text = "name = \"p\"\n[[study]]\nscene = \"crossing\"\nset = [\"stepping.increments=40\"]\n";
        let plan = Plan::parse(text, "p.toml", Path::new("")).unwrap();
        assert_eq!(expand(&plan).unwrap()[0].id, single.id);
    }
}
