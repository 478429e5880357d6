//! One scene, several models, continued: an axisymmetric scene built as the quarter of its
//! revolution about the axis (`[revolution]`, `build = true`).
//!
//! The section `(x = r, y = z)` becomes the quarter `0 ≤ θ ≤ 90°` of the body of revolution
//! about the 3D `z` axis (`model::revolved_mesh`), held at `u_x = 0` on the plane `x = 0` and
//! `u_y = 0` on the plane `y = 0` (its symmetry planes). An axisymmetric scene states totals
//! over the full circle; the quarter model states its own: nodal loads are divided by 4 and
//! monitors' forces multiplied by 4 (`force_scale`), so the two models report the same
//! quantity. Penalties map as in the extrusion (`super::extrude`: per slave node in 2D, per
//! unit area in 3D). Rigid arcs about a centre on the axis become spheres, horizontal lines
//! planes normal to `z`; both move along the axis only. Sides map to faces: `left` is the
//! `axis` node set (a full section) or the `inner` face, `right` the `outer` face, `bottom`
//! and `top` the faces `zmin` and `zmax`. What has no 3D counterpart here — a radial support
//! or load off the axis, a cone or a torus, a rigid body moved sideways — is refused with the
//! reason.

use super::mesh_spec::{Bias, MeshSpec};
use super::plane_to_3d::{contact_pairs, scaled, start, table_err};
use super::rigid_spec::{MotionSpec, PlaneSpec, SphereSpec};
use super::types::{BodyModel, Component, FixSpec, NodeSelection, RampSpec, RigidSpec, SceneFile, WhereSpec};
use super::{SceneError, SceneSource};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// The `[revolution]` table: how an axisymmetric scene is built in 3D.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct RevolutionSpec {
    /// Build the scene as the quarter of its revolution (default false: as written, in 2D).
    #[serde(default)]
    pub build: bool,
    /// Cells around the quarter of a hollow section (default 8).
    #[serde(default = "super::mesh_spec::eight")]
    pub around: usize,
    /// The share of the radius a full section's core square takes (default 0.5).
    #[serde(default = "super::mesh_spec::half")]
    pub core: f64,
}

fn err(src: &SceneSource, message: String, hint: &str) -> SceneError {
    table_err(src, "revolution", message, hint)
}

/// The 3D quarter model of an axisymmetric scene (see the module).
pub fn revolve(src: &SceneSource, s: &SceneFile, r: &RevolutionSpec) -> Result<SceneFile, SceneError> {
    if let Some(b) = s.bodies.iter().find(|b| b.model != BodyModel::Axisymmetric) {
        return Err(err(
            src,
            format!("body `{}` is not axisymmetric", b.name),
            "revolve axisymmetric scenes; extrude plane ones ([extrusion])",
        ));
    }
    let mut out = start(src, "revolution", s, "the quarter of its revolution")?;
    for b in &mut out.bodies {
        b.mesh = revolved(src, &b.name, &b.mesh, r)?;
        b.model = BodyModel::PlaneStrain;
        b.thickness = None;
    }
    let mut fixes = Vec::new();
    for f in &s.fixes {
        if let Some(f) = fix(src, s, f)? {
            fixes.push(f);
        }
    }
    for b in &s.bodies {
        for (plane, c) in [("xmin", Component::X), ("ymin", Component::Y)] {
            fixes.push(FixSpec {
                name: Some(format!("symmetry-{plane}-{}", b.name)),
                body: b.name.clone(),
                nodes: NodeSelection::Named(plane.into()),
                components: vec![c],
                direction: None,
                value: RampSpec::Final(0.0),
                turn: None,
            });
        }
    }
    out.fixes = fixes;
    for l in &mut out.loads {
        l.nodes = selection(src, s, &l.body, &l.nodes)?;
        l.component = axial(src, l.component, "a radial load")?;
        l.total = scaled(&l.total, 0.25);
    }
    for rb in &mut out.rigid {
        rigid(src, rb)?;
    }
    let nodes = |body: &str, n: &NodeSelection| selection(src, s, body, n);
    let faces = |body: &str, f: &str| match selection(src, s, body, &NodeSelection::Named(f.into()))? {
        NodeSelection::Named(n) if n != "axis" => Ok(n),
        _ => Err(err(
            src,
            format!("the face `{f}` of `{body}` lies on the axis"),
            "name a face off the axis",
        )),
    };
    contact_pairs(src, "revolution", s, &mut out, &nodes, &faces)?;
    for m in &mut out.monitors.0 {
        let body = m.body.clone().unwrap_or_default();
        m.nodes = m.nodes.as_ref().map(|n| selection(src, s, &body, n)).transpose()?;
        m.component = axial(src, m.component, "a radial monitor")?;
        m.force_scale *= 4.0;
    }
    Ok(out)
}

/// The section's rectangle as the revolved mesh.
fn revolved(src: &SceneSource, body: &str, m: &MeshSpec, r: &RevolutionSpec) -> Result<MeshSpec, SceneError> {
    match m {
        MeshSpec::Rectangle {
            origin,
            size,
            elements,
            grading,
            bias,
            focus: None,
            rotate: None,
        } if bias.iter().all(|b| *b == Bias::End) => Ok(MeshSpec::Revolved {
            origin: *origin,
            size: *size,
            elements: *elements,
            grading: *grading,
            around: r.around,
            core: r.core,
            turn_deg: 90.0,
        }),
        _ => Err(err(
            src,
            format!("body `{body}`: only a rectangle graded from end to end (no bias, focus or rotation) is revolved"),
            "mesh the section as such a rectangle, or build the scene in 2D",
        )),
    }
}

/// The axial component (`y` in the section, `z` in 3D); a radial one is refused.
fn axial(src: &SceneSource, c: Component, what: &str) -> Result<Component, SceneError> {
    match c {
        Component::Y => Ok(Component::Z),
        _ => Err(err(
            src,
            format!("{what} has no 3D counterpart here (it is radial)"),
            "build the scene in 2D",
        )),
    }
}

/// A fix in 3D: axial components along `z`; a radial one is kept only on the axis, where the
/// symmetry planes hold it (`None` when nothing else is left).
fn fix(src: &SceneSource, s: &SceneFile, f: &FixSpec) -> Result<Option<FixSpec>, SceneError> {
    if f.direction.is_some() || f.turn.is_some() {
        return Err(err(
            src,
            format!("fix on `{}`: a skew support is not revolved", f.body),
            "give the fix by components",
        ));
    }
    let nodes = selection(src, s, &f.body, &f.nodes)?;
    let on_axis = matches!(&nodes, NodeSelection::Named(n) if n == "axis")
        || matches!(&nodes, NodeSelection::Where(w) if w.x == Some(0.0) && w.y == Some(0.0));
    let zero = matches!(f.value, RampSpec::Final(v) if v == 0.0);
    if f.components.contains(&Component::X) && !(on_axis && zero) {
        return Err(err(
            src,
            format!(
                "fix on `{}` {}: a radial support off the axis (a skew support in 3D) is not built",
                f.body, f.nodes
            ),
            "hold the section along y only, or build the scene in 2D",
        ));
    }
    let components: Vec<Component> = f
        .components
        .iter()
        .filter(|c| **c == Component::Y)
        .map(|_| Component::Z)
        .collect();
    Ok((!components.is_empty()).then(|| FixSpec {
        nodes,
        components,
        ..f.clone()
    }))
}

/// A section's node selection in 3D (see the module); a ring off the axis that no 3D
/// selection names is refused.
fn selection(src: &SceneSource, s: &SceneFile, body: &str, n: &NodeSelection) -> Result<NodeSelection, SceneError> {
    let Some(MeshSpec::Rectangle { origin, size, .. }) = s.bodies.iter().find(|b| b.name == body).map(|b| &b.mesh)
    else {
        return Ok(n.clone());
    };
    let full = origin[0] == 0.0;
    let tol = 1e-9 * size[0].max(size[1]);
    let axis_at = |z: Option<f64>| {
        NodeSelection::Where(WhereSpec {
            x: Some(0.0),
            y: Some(0.0),
            z,
            bbox: None,
            tol,
        })
    };
    let ring = || {
        err(
            src,
            format!("the node selection {n} of `{body}` is a ring off the axis, which no 3D node selection names"),
            "select a side, the axis or a level y",
        )
    };
    Ok(match n {
        NodeSelection::Named(name) => match name.as_str() {
            "left" if full => NodeSelection::Named("axis".into()),
            "left" => NodeSelection::Named("inner".into()),
            "right" => NodeSelection::Named("outer".into()),
            "bottom" => NodeSelection::Named("zmin".into()),
            "top" => NodeSelection::Named("zmax".into()),
            "bottom-left" if full => axis_at(Some(origin[1])),
            "top-left" if full => axis_at(Some(origin[1] + size[1])),
            "bottom-left" | "top-left" | "bottom-right" | "top-right" => return Err(ring()),
            other => NodeSelection::Named(other.into()),
        },
        NodeSelection::Where(w) if w.bbox.is_some() || w.z.is_some() => return Err(ring()),
        NodeSelection::Where(w) => match w.x {
            None => NodeSelection::Where(WhereSpec {
                x: None,
                y: None,
                z: w.y,
                bbox: None,
                tol: w.tol,
            }),
            Some(x) if x.abs() <= w.tol => axis_at(w.y),
            Some(_) => return Err(ring()),
        },
    })
}

/// A rigid arc about a centre on the axis as its sphere, a horizontal line as its plane;
/// moved along the axis only.
fn rigid(src: &SceneSource, r: &mut RigidSpec) -> Result<(), SceneError> {
    let name = r.name.clone();
    let refuse = |what: &str| {
        err(
            src,
            format!("rigid `{name}`: {what} is not revolved"),
            "use an arc about a centre on the axis or a horizontal line, or build the scene in 2D",
        )
    };
    if let Some(p) = r.polyline.take() {
        let (a, b) = (p[0], p[p.len() - 1]);
        if p.iter().any(|q| q[1] != a[1]) || a[0] == b[0] {
            return Err(refuse("a line that is not horizontal (a cone)"));
        }
        // the rigid body on the left of the direction of travel: the outside is turned clockwise
        r.plane = Some(PlaneSpec {
            point: [0.0, 0.0, a[1]],
            normal: [0.0, 0.0, -(b[0] - a[0]).signum()],
        });
    } else if let Some(a) = r.arc.take() {
        if a.centre[0] != 0.0 || a.to_deg <= a.from_deg {
            return Err(refuse(
                "an arc about a centre off the axis (a torus) or around a cavity",
            ));
        }
        r.sphere = Some(SphereSpec {
            centre: [0.0, 0.0, a.centre[1]],
            radius: a.radius,
        });
    } else if r.point.is_some() || r.outline.is_some() || r.polygon.is_some() {
        return Err(refuse("a point, an outline or a polygon"));
    }
    r.fillet = None;
    let m = std::mem::take(&mut r.motion);
    if m.x.is_some() {
        return Err(refuse("a body moved across the axis"));
    }
    r.motion = MotionSpec {
        x: None,
        y: None,
        z: m.y,
    };
    Ok(())
}
