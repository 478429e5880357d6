//! One scene, several models: a plane scene built as its 3D extrusion (`[extrusion]`,
//! `build = true`), so that `contrail sweep` varies the model as one key.
//!
//! The plane `(x, y)` of the scene becomes the plane `(x, z)` in 3D and the extrusion runs
//! along `y`, over `[0, ℓ]`:
//! - a **plane-strain** body of `length` `L`: `ends = "held"` (default) is the slice
//!   `ℓ = L` with `u_y = 0` at every node (plane strain exactly, at any `L`); `ends = "free"`
//!   is the half body `ℓ = L/2`, held at `u_y = 0` on its mid-plane `y = 0` and free at
//!   `y = L/2` (a block whose ends may lengthen: not plane strain);
//! - a **plane-stress** plate of `thickness` `t`: the half plate `ℓ = t/2`, held at `u_y = 0`
//!   on its mid-plane, its face free;
//! - an axisymmetric body is refused (its 3D model is revolved, not extruded).
//!
//! What a 2D scene states per unit thickness (plane strain) or for the plate (plane stress),
//! the 3D model states for its part `ℓ`: nodal loads are multiplied by `ℓ / w` and monitors'
//! forces by `w / ℓ` (`force_scale`), with `w = 1` in plane strain and `t` in plane stress, so
//! the two models report the same quantity. A 2D penalty is per slave node (force per unit
//! thickness per unit penetration), a 3D one per unit area: the 3D `ε = ε₂ᴅ / h`, `h` the
//! smallest element edge along the slave side (at least as stiff as in 2D at every node), and
//! unchanged for a slave that is one corner node (a 3D edge slave's penalty is per unit
//! length already). Rectangles graded end to end become boxes graded alike; rigid straight
//! lines become planes, arcs around a disc its cylinder along `y` (the whole cylinder: a slave
//! past the arc's ends in 2D meets the cylinder in 3D). What has no 3D counterpart here is
//! refused with the reason.

use super::mesh_spec::{Bias, MeshSpec};
use super::plane_to_3d::{contact_pairs, scaled, start, table_err};
use super::rigid_spec::{CylinderSpec, MotionSpec, PlaneSpec};
use super::types::{BodyModel, Component, FixSpec, NodeSelection, RampSpec, RigidSpec, SceneFile, WhereSpec};
use super::{SceneError, SceneSource};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// The `[extrusion]` table: how a plane scene is built in 3D.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
#[serde(deny_unknown_fields)]
pub struct ExtrusionSpec {
    /// Build the scene as its 3D extrusion (default false: as written, in 2D).
    #[serde(default)]
    pub build: bool,
    /// Length of plane-strain bodies along the extrusion (`y` in 3D); a plane-stress plate's
    /// is its `thickness` (this key is then not used).
    pub length: Option<f64>,
    /// Hexahedra along the modelled length (default 1).
    #[serde(default = "one")]
    pub elements: usize,
    /// Grading along the extrusion, last element over first (default 1; `< 1` refines
    /// towards a free end).
    #[serde(default = "unit")]
    pub grading: f64,
    /// Plane-strain bodies: `"held"` (u_y = 0 everywhere: the slice) or `"free"` (the half
    /// body, free at its end).
    pub ends: Option<ExtrusionEnds>,
}

fn one() -> usize {
    1
}

fn unit() -> f64 {
    1.0
}

/// The ends of an extruded plane-strain body.
#[derive(Debug, Clone, Copy, Serialize, Deserialize, JsonSchema, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum ExtrusionEnds {
    /// Every node held at `u_y = 0`: plane strain exactly.
    Held,
    /// The half body, symmetric about `y = 0`, its end free.
    Free,
}

/// How the plane quantities map onto the 3D part: `ℓ` modelled, `w` the 2D measure.
struct Part {
    modelled: f64,
    measure: f64,
    held_everywhere: bool,
}

/// The scene as it is to be built: itself, or its 3D extrusion or revolution when
/// `[extrusion]` or `[revolution]` says so.
pub fn apply(src: &SceneSource, s: SceneFile) -> Result<SceneFile, SceneError> {
    match (&s.extrusion, &s.revolution) {
        (Some(e), Some(r)) if e.build && r.build => Err(err(
            src,
            "and [revolution] build = true".into(),
            "build the scene one way",
        )),
        (Some(e), _) if e.build => {
            super::validate::validate(src, &s)?;
            extrude(src, &s, e)
        }
        (_, Some(r)) if r.build => {
            super::validate::validate(src, &s)?;
            super::revolve::revolve(src, &s, r)
        }
        _ => Ok(s),
    }
}

fn err(src: &SceneSource, message: String, hint: &str) -> SceneError {
    table_err(src, "extrusion", message, hint)
}

fn extrude(src: &SceneSource, s: &SceneFile, e: &ExtrusionSpec) -> Result<SceneFile, SceneError> {
    let part = part(src, s, e)?;
    let what = format!(
        "its extrusion ({} of length {} along y)",
        if part.held_everywhere { "a slice" } else { "half" },
        part.modelled
    );
    let mut out = start(src, "extrusion", s, &what)?;
    for b in &mut out.bodies {
        b.mesh = boxed(src, &b.name, &b.mesh, e, part.modelled)?;
        b.model = BodyModel::PlaneStrain;
        b.thickness = None;
    }
    for f in &mut out.fixes {
        if f.direction.is_some() || f.turn.is_some() {
            return Err(err(
                src,
                format!("fix on `{}`: a skew support has no 3D extrusion yet", f.body),
                "give the fix by components",
            ));
        }
        f.nodes = selection(src, s, &f.body, &f.nodes)?;
        f.components = f.components.iter().map(|&c| component(c)).collect();
    }
    for b in &s.bodies {
        let nodes = if part.held_everywhere || held_still(s, &b.name) {
            "all"
        } else {
            "ymin"
        };
        out.fixes.push(FixSpec {
            name: Some(format!("extrusion-{}", b.name)),
            body: b.name.clone(),
            nodes: NodeSelection::Named(nodes.into()),
            components: vec![Component::Y],
            direction: None,
            value: RampSpec::Final(0.0),
            turn: None,
        });
    }
    for l in &mut out.loads {
        l.nodes = selection(src, s, &l.body, &l.nodes)?;
        l.component = component(l.component);
        l.total = scaled(&l.total, part.modelled / part.measure);
    }
    for r in &mut out.rigid {
        rigid(src, r)?;
    }
    let nodes = |body: &str, n: &NodeSelection| selection(src, s, body, n);
    contact_pairs(src, "extrusion", s, &mut out, &nodes, &|_, f: &str| Ok(face(f)))?;
    for m in &mut out.monitors.0 {
        let body = m.body.clone().unwrap_or_default();
        m.nodes = m.nodes.as_ref().map(|n| selection(src, s, &body, n)).transpose()?;
        m.component = component(m.component);
        m.force_scale *= part.measure / part.modelled;
    }
    Ok(out)
}

/// Whether every node of `body` is held still in the plane (fixes of `all` its nodes at zero
/// in `x` and `y`): a body standing for a rigid one, which its extrusion holds still along
/// `y` too — not a plate whose faces may move across its thickness.
fn held_still(s: &SceneFile, body: &str) -> bool {
    let still = |c: Component| {
        s.fixes.iter().any(|f| {
            f.body == body
                && matches!(&f.nodes, NodeSelection::Named(n) if n == "all")
                && matches!(f.value, RampSpec::Final(v) if v == 0.0)
                && f.components.contains(&c)
        })
    };
    still(Component::X) && still(Component::Y)
}

/// The modelled length and the 2D measure of the scene's bodies (all plane strain or all
/// plane stress of one thickness).
fn part(src: &SceneSource, s: &SceneFile, e: &ExtrusionSpec) -> Result<Part, SceneError> {
    let models: Vec<(BodyModel, Option<f64>)> = s.bodies.iter().map(|b| (b.model, b.thickness)).collect();
    if models.iter().any(|(m, _)| *m == BodyModel::Axisymmetric) {
        return Err(err(
            src,
            "an axisymmetric body is revolved, not extruded".into(),
            "model its 3D quarter as a scene of its own",
        ));
    }
    if !(e.elements >= 1 && e.grading > 0.0 && e.grading.is_finite()) {
        return Err(err(
            src,
            format!("elements = {}, grading = {}", e.elements, e.grading),
            "give elements ≥ 1 and a positive grading",
        ));
    }
    let stress: Vec<f64> = models
        .iter()
        .filter_map(|(m, t)| (*m == BodyModel::PlaneStress).then_some(t.unwrap_or(0.0)))
        .collect();
    if stress.is_empty() {
        let length = e.length.filter(|l| *l > 0.0 && l.is_finite()).ok_or_else(|| {
            err(
                src,
                format!("plane-strain bodies need a positive `length` (got {:?})", e.length),
                "add length = 1.0 to [extrusion]",
            )
        })?;
        let held = e.ends != Some(ExtrusionEnds::Free);
        return Ok(Part {
            modelled: if held { length } else { length / 2.0 },
            measure: 1.0,
            held_everywhere: held,
        });
    }
    let t = stress[0];
    if stress.len() < models.len() || stress.iter().any(|x| *x != t) || e.ends == Some(ExtrusionEnds::Held) {
        return Err(err(
            src,
            "plane-stress plates are extruded by their own thickness, all alike, free on their faces, and with no plane-strain body".into(),
            "give every body the same model and thickness, and no `ends = \"held\"` (a plate held at u_y = 0 is in plane strain)",
        ));
    }
    Ok(Part {
        modelled: t / 2.0,
        measure: t,
        held_everywhere: false,
    })
}

/// A rectangle graded end to end as the box of its extrusion.
fn boxed(
    src: &SceneSource,
    body: &str,
    m: &MeshSpec,
    e: &ExtrusionSpec,
    modelled: f64,
) -> Result<MeshSpec, SceneError> {
    match m {
        MeshSpec::Rectangle {
            origin,
            size,
            elements,
            grading,
            bias,
            focus: None,
            rotate: None,
        } if bias.iter().all(|b| *b == Bias::End) => Ok(MeshSpec::Box {
            origin: [origin[0], 0.0, origin[1]],
            size: [size[0], modelled, size[1]],
            elements: [elements[0], e.elements, elements[1]],
            grading: [grading[0], e.grading, grading[1]],
        }),
        _ => Err(err(
            src,
            format!("body `{body}`: only a rectangle graded from end to end (no bias, focus or rotation) is extruded"),
            "mesh the body as such a rectangle, or build the scene in 2D",
        )),
    }
}

/// A 2D component in 3D: `y` (up in the plane) is `z`.
fn component(c: Component) -> Component {
    match c {
        Component::Y => Component::Z,
        other => other,
    }
}

/// A rectangle's side as the box's face.
fn face(name: &str) -> String {
    match name {
        "left" => "xmin",
        "right" => "xmax",
        "bottom" => "zmin",
        "top" => "zmax",
        other => other,
    }
    .to_string()
}

/// A 2D node selection as the 3D one: sides are faces, corners the edge lines along `y`.
fn selection(src: &SceneSource, s: &SceneFile, body: &str, n: &NodeSelection) -> Result<NodeSelection, SceneError> {
    let line = |x: Option<f64>, z: Option<f64>, tol: f64| {
        NodeSelection::Where(WhereSpec {
            x,
            y: None,
            z,
            bbox: None,
            tol,
        })
    };
    let corner = |v: &str, h: &str| {
        if !["bottom", "top"].contains(&v) || !["left", "right"].contains(&h) {
            return None;
        }
        let Some(MeshSpec::Rectangle { origin, size, .. }) = s.bodies.iter().find(|b| b.name == body).map(|b| &b.mesh)
        else {
            return None;
        };
        let x = origin[0] + if h == "right" { size[0] } else { 0.0 };
        let z = origin[1] + if v == "top" { size[1] } else { 0.0 };
        Some(line(Some(x), Some(z), 1e-9 * size[0].max(size[1])))
    };
    Ok(match n {
        NodeSelection::Named(name) => match name.split_once('-').and_then(|(v, h)| corner(v, h)) {
            Some(edge) => edge,
            None => NodeSelection::Named(face(name)),
        },
        NodeSelection::Where(w) if w.bbox.is_none() && w.z.is_none() => line(w.x, w.y, w.tol),
        NodeSelection::Where(_) => {
            return Err(err(
                src,
                format!("the node selection {n} has no 3D extrusion"),
                "select by a set name or by x and y",
            ))
        }
    })
}

/// A rigid line or disc as its extrusion along `y`; motions in the plane move alike.
fn rigid(src: &SceneSource, r: &mut RigidSpec) -> Result<(), SceneError> {
    let name = r.name.clone();
    let refuse = |what: &str| {
        err(
            src,
            format!("rigid `{name}`: {what} has no 3D extrusion yet"),
            "use a straight polyline or an arc around a disc, or build the scene in 2D",
        )
    };
    if let Some(p) = r.polyline.take() {
        let (a, b) = (p[0], p[p.len() - 1]);
        let d = [b[0] - a[0], b[1] - a[1]];
        let len = d[0].hypot(d[1]);
        let straight = len > 0.0
            && p.iter()
                .all(|q| ((q[0] - a[0]) * d[1] - (q[1] - a[1]) * d[0]).abs() <= 1e-12 * len * len);
        if !straight {
            return Err(refuse("a bent polyline"));
        }
        // the rigid body on the left: the outward normal is the direction turned clockwise
        r.plane = Some(PlaneSpec {
            point: [a[0], 0.0, a[1]],
            normal: [d[1] / len, 0.0, -d[0] / len],
        });
    } else if let Some(a) = r.arc.take() {
        if a.to_deg <= a.from_deg {
            return Err(refuse("an arc around a cavity"));
        }
        r.cylinder = Some(CylinderSpec {
            point: [a.centre[0], 0.0, a.centre[1]],
            axis: [0.0, 1.0, 0.0],
            radius: a.radius,
        });
    } else if r.point.is_some() || r.outline.is_some() || r.polygon.is_some() {
        return Err(refuse("a point, an outline or a polygon"));
    }
    r.fillet = None;
    let m = std::mem::take(&mut r.motion);
    r.motion = MotionSpec {
        x: m.x,
        y: None,
        z: m.y,
    };
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn src() -> SceneSource {
        SceneSource {
            origin: "t.toml".into(),
            text: "[extrusion]\nbuild = true\n".into(),
        }
    }

    #[test]
    fn a_straight_polyline_becomes_the_plane_facing_away_from_the_body_on_its_left() {
        // travelling towards −x with the body on the left (below): the outside is +y, i.e. +z
        let mut r: RigidSpec = toml::from_str(
            "name = \"floor\"\npolyline = [[1.0, 0.5], [0.0, 0.5], [-2.0, 0.5]]\nmove = { x = 0.1, y = -0.2 }",
        )
        .unwrap();
        rigid(&src(), &mut r).unwrap();
        let p = r.plane.as_ref().expect("a plane");
        assert_eq!((p.point, p.normal), ([1.0, 0.0, 0.5], [0.0, 0.0, 1.0]));
        assert!(r.polyline.is_none() && r.motion.y.is_none());
        assert!(matches!(r.motion.z, Some(RampSpec::Final(v)) if v == -0.2));
        let mut bent: RigidSpec =
            toml::from_str("name = \"v\"\npolyline = [[0.0, 0.0], [1.0, 0.1], [2.0, 0.0]]").unwrap();
        assert!(rigid(&src(), &mut bent)
            .unwrap_err()
            .to_string()
            .contains("bent polyline"));
    }

    #[test]
    fn sides_become_faces_corners_edge_lines_and_y_becomes_z() {
        let s: SceneFile = toml::from_str(
            "name = \"s\"\n[[body]]\nname = \"b\"\nmaterial = { model = \"neo-hookean\", young = 1.0, poisson = 0.3 }\nmesh = { kind = \"rectangle\", origin = [1.0, -2.0], size = [2.0, 3.0], elements = [2, 2] }",
        )
        .unwrap();
        let named = |n: &str| {
            selection(&src(), &s, "b", &NodeSelection::Named(n.into()))
                .unwrap()
                .to_string()
        };
        assert_eq!(named("top"), "\"zmax\"");
        assert_eq!(named("left"), "\"xmin\"");
        assert_eq!(named("all"), "\"all\"");
        assert!(
            named("top-right").starts_with("{ x = 3, z = 1"),
            "{}",
            named("top-right")
        );
        let w = NodeSelection::Where(WhereSpec {
            x: None,
            y: Some(0.5),
            z: None,
            bbox: None,
            tol: 1e-9,
        });
        assert!(selection(&src(), &s, "b", &w)
            .unwrap()
            .to_string()
            .starts_with("{ z = 0.5"));
        assert_eq!(component(Component::Y), Component::Z);
        assert_eq!(face("bottom"), "zmin");
        assert!(
            matches!(scaled(&RampSpec::Path(vec![[0.0, 1.0], [1.0, 2.0]]), 0.5), RampSpec::Path(p) if p == vec![[0.0, 0.5], [1.0, 1.0]])
        );
    }

    #[test]
    fn a_body_held_still_in_the_plane_is_held_still_in_3d_and_a_plate_is_not() {
        let scene = |fixes: &str| -> SceneFile {
            toml::from_str(&format!(
                "name = \"s\"\n[[body]]\nname = \"b\"\nmaterial = {{ model = \"neo-hookean\", young = 1.0, poisson = 0.3 }}\nmesh = {{ kind = \"rectangle\", origin = [0.0, 0.0], size = [1.0, 1.0], elements = [1, 1] }}\n{fixes}"
            ))
            .unwrap()
        };
        let fix = |nodes: &str, comps: &str, value: f64| {
            format!("[[fix]]\nbody = \"b\"\nnodes = \"{nodes}\"\ncomponents = {comps}\nvalue = {value}\n")
        };
        let still = fix("all", "[\"x\", \"y\"]", 0.0);
        assert!(held_still(&scene(&still), "b"));
        let split = fix("all", "[\"x\"]", 0.0) + &fix("all", "[\"y\"]", 0.0);
        assert!(held_still(&scene(&split), "b"));
        for not in [
            fix("bottom", "[\"x\", \"y\"]", 0.0),
            fix("all", "[\"x\"]", 0.0),
            fix("all", "[\"x\", \"y\"]", 0.1),
        ] {
            assert!(!held_still(&scene(&not), "b"), "{not}");
        }
    }
}
