//! The mesh of one body: generated (`rectangle`) or read from a Gmsh file (`gmsh`, resolved
//! relative to the scene file, or among the files shipped with a built-in scene).

use super::types::{Bias, BodySpec, GridAxes, MeshSpec, Rotation};
use super::{builtin, locate, SceneError, SceneSource};
use crate::model::gmsh::{read_gmsh, read_gmsh_hex, GmshError, GmshSolidMesh};
use crate::model::mesh::{annulus_on, axis_coords, rotate, RectMesh};
use std::borrow::Cow;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// A body's Gmsh file as resolved, and its physical curves that are not faces (name, number
/// of lines off the boundary).
pub(super) type MeshFile = (String, Vec<(String, usize)>);

/// Nodes, counter-clockwise quadrilaterals, named node sets and faces of one body (local
/// node numbers), and the mesh file it came from.
pub(super) struct BodyMesh {
    pub nodes: Vec<[f64; 2]>,
    pub quads: Vec<[usize; 4]>,
    pub node_sets: BTreeMap<String, Vec<usize>>,
    pub faces: BTreeMap<String, Vec<[usize; 2]>>,
    /// The Gmsh file (as resolved), with the physical curves that are not faces.
    pub file: Option<MeshFile>,
}

/// Where a mesh file named in a scene is: beside the scene file, or (built-in scenes) among
/// the shipped files first, then relative to the working directory.
fn resolve(src: &SceneSource, file: &str) -> (String, Option<&'static [u8]>, PathBuf) {
    if src.origin.starts_with("builtin:") {
        if let Some(bytes) = builtin::file(file) {
            return (format!("builtin:{file}"), Some(bytes), PathBuf::from(file));
        }
        return (file.to_string(), None, PathBuf::from(file));
    }
    let dir = Path::new(&src.origin).parent().unwrap_or(Path::new(""));
    let path = dir.join(file);
    (path.display().to_string(), None, path)
}

/// Largest mesh file read (bytes): a regular file of at most this size, so that a scene
/// naming a device or a huge file fails with a message instead of exhausting memory.
const MAX_MESH_BYTES: u64 = 1 << 30;

fn read_limited(path: &Path) -> std::io::Result<Vec<u8>> {
    use std::io::{Error, ErrorKind, Read};
    let meta = std::fs::metadata(path)?;
    if !meta.is_file() {
        return Err(Error::new(ErrorKind::InvalidInput, "not a regular file"));
    }
    if meta.len() > MAX_MESH_BYTES {
        return Err(Error::new(
            ErrorKind::InvalidInput,
            format!("{} bytes, more than the limit of {MAX_MESH_BYTES}", meta.len()),
        ));
    }
    let mut bytes = Vec::with_capacity(meta.len() as usize);
    std::fs::File::open(path)?
        .take(MAX_MESH_BYTES)
        .read_to_end(&mut bytes)?;
    Ok(bytes)
}

/// The error of body `b`'s Gmsh file, located at its `file` key.
fn gmsh_error<'a>(src: &'a SceneSource, b: &'a BodySpec, file: &'a str) -> impl Fn(GmshError) -> SceneError + 'a {
    move |error: GmshError| SceneError::Mesh {
        origin: src.origin.clone(),
        location: locate(&src.text, file),
        body: b.name.clone(),
        error: Box::new(error),
    }
}

/// The bytes of body `b`'s Gmsh file (shipped with a built-in scene, or read from disk) and
/// its label for messages.
fn gmsh_bytes<'s>(src: &'s SceneSource, b: &BodySpec, file: &str) -> Result<(String, Cow<'s, [u8]>), SceneError> {
    let wrap = gmsh_error(src, b, file);
    let (label, shipped, path) = resolve(src, file);
    let bytes: Cow<[u8]> = match shipped {
        Some(b) => Cow::Borrowed(b),
        None => Cow::Owned(read_limited(&path).map_err(|source| {
            let shipped: Vec<&str> = builtin::FILES.iter().map(|f| f.0).collect();
            wrap(GmshError::Read {
                file: label.clone(),
                source,
                hint: format!(
                    "`file` is relative to the scene file's directory; the meshes of the built-in scenes ({}) are in the repository's `scenes/` directory",
                    shipped.join(", ")
                ),
            })
        })?),
    };
    Ok((label, bytes))
}

/// Read and check the Gmsh file of a 3D body (`kind = "gmsh-3d"`: hexahedra).
pub(super) fn gmsh_solid(src: &SceneSource, b: &BodySpec, file: &str) -> Result<GmshSolidMesh, SceneError> {
    let (label, bytes) = gmsh_bytes(src, b, file)?;
    read_gmsh_hex(&label, &bytes).map_err(gmsh_error(src, b, file))
}

/// Read and check the Gmsh file of a body.
fn gmsh(src: &SceneSource, b: &BodySpec, file: &str) -> Result<BodyMesh, SceneError> {
    let wrap = gmsh_error(src, b, file);
    let (label, bytes) = gmsh_bytes(src, b, file)?;
    let m = read_gmsh(&label, &bytes).map_err(wrap)?;
    Ok(BodyMesh {
        nodes: m.nodes,
        quads: m.quads,
        node_sets: m.node_sets,
        faces: m.faces,
        file: Some((label, m.interior_curves)),
    })
}

/// Node coordinates along one axis of a structured mesh: `n` elements on `[0, len]` graded
/// by `ratio` with `bias` (`at`: the focus from the axis' start, used by `"centre"` only).
fn axis(len: f64, n: usize, ratio: f64, bias: Bias, at: Option<f64>) -> Vec<f64> {
    let at = at.filter(|_| bias == Bias::Centre);
    axis_coords(len, n, bias.axis(ratio, at))
}

/// The mesh of a body.
pub(super) fn body_mesh(src: &SceneSource, b: &BodySpec) -> Result<BodyMesh, SceneError> {
    let invalid = |message: String, hint: &str| SceneError::Invalid {
        origin: src.origin.clone(),
        location: locate(&src.text, &b.name),
        message,
        hint: hint.to_string(),
    };
    let mesh = match &b.mesh {
        MeshSpec::Rectangle {
            origin,
            size,
            elements,
            grading,
            bias,
            focus,
            rotate: turn,
        } => rectangle_mesh(
            b,
            (origin, size),
            (elements, grading, bias),
            (*focus, turn.as_ref()),
            &invalid,
        )?,
        MeshSpec::Annulus {
            centre,
            radius,
            angle_deg,
            elements,
            grading,
            bias,
            focus,
        } => annulus_mesh(
            b,
            (centre, radius, angle_deg),
            (elements, grading, bias),
            *focus,
            &invalid,
        )?,
        MeshSpec::Gmsh { file } => gmsh(src, b, file)?,
        MeshSpec::Box { .. }
        | MeshSpec::Gmsh3d { .. }
        | MeshSpec::HemisphereShell { .. }
        | MeshSpec::SphereShell { .. }
        | MeshSpec::Revolved { .. } => {
            return Err(invalid(
                format!(
                "body `{}`: a `box`, `revolved`, `hemisphere-shell`, `sphere-shell` or `gmsh-3d` mesh makes a 3D body",
                b.name
            ),
                "a scene is 2D or 3D in all its bodies",
            ))
        }
    };
    if let Some(x) = mesh.nodes.iter().find(|x| !(x[0].is_finite() && x[1].is_finite())) {
        return Err(invalid(
            format!(
                "body `{}`: the mesh has a node at {x:?} (its coordinates overflow)",
                b.name
            ),
            "give a smaller mesh size or grading",
        ));
    }
    Ok(mesh)
}

/// Why a mesh is invalid, as the scene's error.
type Invalid<'a> = dyn Fn(String, &str) -> SceneError + 'a;

/// The body mesh of a generated (not read) structured mesh.
fn generated(m: RectMesh) -> BodyMesh {
    BodyMesh {
        nodes: m.nodes,
        quads: m.quads,
        node_sets: m.node_sets,
        faces: m.faces,
        file: None,
    }
}

/// A rectangle's structured mesh (graded, biased, focused, rotated).
fn rectangle_mesh(
    b: &BodySpec,
    (origin, size): (&[f64; 2], &[f64; 2]),
    (elements, grading, bias): GridAxes,
    (focus, turn): (Option<[f64; 2]>, Option<&Rotation>),
    invalid: &Invalid,
) -> Result<BodyMesh, SceneError> {
    if elements[0] == 0 || elements[1] == 0 || size[0] <= 0.0 || size[1] <= 0.0 {
        return Err(invalid(
            format!("body `{}`: mesh needs positive size and ≥ 1 element each way", b.name),
            "fix [body.mesh]",
        ));
    }
    let at = |k: usize| focus.map(|f| f[k] - origin[k]);
    let xs = axis(size[0], elements[0], grading[0], bias[0], at(0));
    let ys = axis(size[1], elements[1], grading[1], bias[1], at(1));
    let mut m = RectMesh::on_grid(*origin, &xs, &ys);
    if let Some(r) = turn {
        rotate(&mut m.nodes, r.angle_deg, r.about.unwrap_or(*origin));
    }
    Ok(generated(m))
}

/// An annulus sector's structured mesh (graded, biased, focused).
fn annulus_mesh(
    b: &BodySpec,
    (centre, radius, angle_deg): (&[f64; 2], &[f64; 2], &[f64; 2]),
    (elements, grading, bias): GridAxes,
    focus: Option<[f64; 2]>,
    invalid: &Invalid,
) -> Result<BodyMesh, SceneError> {
    let ok = elements[0] > 0
        && elements[1] > 0
        && radius[0] > 0.0
        && radius[1] > radius[0]
        && angle_deg[0] != angle_deg[1]
        && (angle_deg[1] - angle_deg[0]).abs() <= 360.0;
    if !ok {
        return Err(invalid(
            format!("body `{}`: an annulus needs 0 < radius[0] < radius[1], two different angles less than a turn apart and ≥ 1 element each way", b.name),
            "fix [body.mesh]",
        ));
    }
    // in units of a uniform element: the focus as a fraction of the sweep and thickness
    let [na, nr] = elements.map(|e| e as f64);
    let at = |k: usize, from: f64, to: f64| focus.map(|f| (f[k] - from) / (to - from) * [na, nr][k]);
    let around = axis(na, elements[0], grading[0], bias[0], at(0, angle_deg[0], angle_deg[1]));
    let through = axis(nr, elements[1], grading[1], bias[1], at(1, radius[0], radius[1]));
    let m = annulus_on(*centre, *radius, *angle_deg, &around, &through);
    Ok(generated(m))
}
