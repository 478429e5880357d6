//! Resolve a checked scene into a [`Model`]: mesh generation, node selections, constraints,
//! rigid geometry and contact pairs, with errors that point at the offending name.

use super::build_pairs;
use super::mesh::{body_mesh, MeshFile};
use super::types::*;
use super::{locate, SceneError, SceneSource};
use crate::element::material::{lame, Material};
use crate::model::ContactLaw;
use crate::model::{
    chain_neighbours, Body, ContactPair, Dim, Element, Enforcement, Master, Model, Monitor, MonitorTarget, NodalLoad,
    Piece, Prescribed, Ramp, RigidBody, RigidShape, SkewPrescribed, Slave, Smoothing, Turn,
};
use crate::problem::Problem;
use crate::settings::SolverSettings;

pub(super) struct Ctx<'a> {
    src: &'a SceneSource,
    /// Per body: its Gmsh file and the physical curves that are not faces (for errors).
    mesh_files: Vec<Option<MeshFile>>,
}

impl<'a> Ctx<'a> {
    /// The context of a scene whose bodies have no mesh files (generated meshes only).
    pub(super) fn new(src: &'a SceneSource) -> Self {
        Ctx {
            src,
            mesh_files: Vec::new(),
        }
    }

    pub(super) fn err(&self, near: &str, message: String, hint: &str) -> SceneError {
        SceneError::Invalid {
            origin: self.src.origin.clone(),
            location: locate(&self.src.text, near),
            message,
            hint: hint.to_string(),
        }
    }
}

pub(super) fn ramp(spec: &RampSpec, end: f64) -> Ramp {
    match spec {
        RampSpec::Final(v) => Ramp::linear(*v, end),
        RampSpec::Path(k) => Ramp {
            knots: k.iter().map(|p| (p[0], p[1])).collect(),
        },
    }
}

/// The history of one component of a rigid body's `move` (none: it stays), in 2D and 3D.
pub(super) fn motion_ramp(spec: &Option<RampSpec>, end: f64) -> Ramp {
    spec.as_ref().map_or(Ramp::constant(0.0), |x| ramp(x, end))
}

fn comp(c: Component) -> usize {
    match c {
        Component::X => 0,
        Component::Y => 1,
        Component::Z => 2,
    }
}

/// The component index of `c` in a model of dimension `S` (`z` refused in 2D).
pub(super) fn comp_of<S: Dim>(cx: &Ctx, c: Component, near: &str) -> Result<usize, SceneError> {
    let k = comp(c);
    if k >= S::D {
        return Err(cx.err(
            near,
            format!("component {c:?} in a {} model", S::NAME),
            "a 2D model has the components x and y; z needs a 3D body (a `box` mesh)",
        ));
    }
    Ok(k)
}

pub(super) fn select<S: Dim>(
    cx: &Ctx,
    model: &Model<S>,
    body: usize,
    sel: &NodeSelection,
) -> Result<Vec<usize>, SceneError> {
    let b = &model.bodies[body];
    let nodes = match sel {
        NodeSelection::Named(name) => b.node_sets.get(name).cloned().ok_or_else(|| {
            let known: Vec<&str> = b.node_sets.keys().map(|s| s.as_str()).collect();
            match cx.mesh_files.get(body).and_then(Option::as_ref) {
                Some((file, _)) => cx.err(
                    name,
                    format!("body `{}`: the mesh {file} has no physical group `{name}`", b.name),
                    &format!(
                        "its node sets are: {}; add `Physical Curve(\"{name}\") = {{…}};` (or Point/Surface) to the .geo and mesh it again",
                        known.join(", ")
                    ),
                ),
                None => cx.err(
                    name,
                    format!("body `{}` has no node set `{name}`", b.name),
                    &format!("known sets: {}", known.join(", ")),
                ),
            }
        })?,
        NodeSelection::Where(w) => (b.first_node..b.first_node + b.node_count)
            .filter(|&n| {
                let p = model.nodes[n].as_ref();
                w.x.is_none_or(|x| (p[0] - x).abs() <= w.tol)
                    && w.y.is_none_or(|y| (p[1] - y).abs() <= w.tol)
                    && w.z.is_none_or(|z| p.get(2).is_some_and(|pz| (pz - z).abs() <= w.tol))
                    && w.bbox.is_none_or(|bb| {
                        p[0] >= bb[0][0] - w.tol
                            && p[0] <= bb[1][0] + w.tol
                            && p[1] >= bb[0][1] - w.tol
                            && p[1] <= bb[1][1] + w.tol
                    })
            })
            .collect(),
    };
    if nodes.is_empty() {
        return Err(cx.err(
            &b.name,
            format!("the node selection {sel} on body `{}` is empty", b.name),
            "check the coordinates and `tol`",
        ));
    }
    Ok(nodes)
}

pub(super) fn body_index<S: Dim>(cx: &Ctx, model: &Model<S>, name: &str) -> Result<usize, SceneError> {
    model.bodies.iter().position(|b| b.name == name).ok_or_else(|| {
        let known: Vec<&str> = model.bodies.iter().map(|b| b.name.as_str()).collect();
        cx.err(
            name,
            format!("no body named `{name}`"),
            &format!("known bodies: {}", known.join(", ")),
        )
    })
}

fn rigid_index<S: Dim>(cx: &Ctx, model: &Model<S>, name: &str) -> Result<usize, SceneError> {
    model.rigid.iter().position(|b| b.name == name).ok_or_else(|| {
        let known: Vec<&str> = model.rigid.iter().map(|b| b.name.as_str()).collect();
        cx.err(
            name,
            format!("no rigid body named `{name}`"),
            &format!("known rigid bodies: {}", known.join(", ")),
        )
    })
}

fn arc_piece(a: &ArcSpec) -> Piece {
    Piece::Arc {
        centre: a.centre,
        radius: a.radius,
        theta0: a.from_deg.to_radians(),
        theta1: a.to_deg.to_radians(),
    }
}

fn line_pieces(pts: &[[f64; 2]]) -> impl Iterator<Item = Piece> + '_ {
    pts.windows(2).map(|w| Piece::Segment { a: w[0], b: w[1] })
}

/// The shape of a rigid body, its straight joints rounded when it has a `fillet`.
fn rigid_shape(cx: &Ctx, r: &RigidSpec) -> Result<RigidShape, SceneError> {
    let shape = sharp_shape(cx, r)?;
    match (r.fillet, shape) {
        (None, shape) => Ok(shape),
        (Some(radius), RigidShape::Surface { pieces }) => super::fillet::fillet(&pieces, radius)
            .map(|pieces| RigidShape::Surface { pieces })
            .map_err(|e| {
                cx.err(
                    &r.name,
                    format!("rigid body `{}`: {e}", r.name),
                    "the radius must fit on the straight pieces next to every vertex",
                )
            }),
        (Some(_), RigidShape::Point { .. }) => Err(cx.err(
            &r.name,
            format!("rigid body `{}` is a point: it has no vertex to round", r.name),
            "remove `fillet`, or make it a polyline, polygon or outline",
        )),
    }
}

fn sharp_shape(cx: &Ctx, r: &RigidSpec) -> Result<RigidShape, SceneError> {
    let hint = "give exactly one of `point`, `polyline`, `arc`, `outline` or `polygon`";
    if let (Some(poly), None, None, None, None) = (&r.polygon, &r.point, &r.polyline, &r.arc, &r.outline) {
        return Ok(RigidShape::Surface {
            pieces: line_pieces(&poly.vertices()).collect(),
        });
    }
    if r.polygon.is_some() {
        return Err(cx.err(
            &r.name,
            format!("rigid body `{}` has a polygon and another shape", r.name),
            hint,
        ));
    }
    match (&r.point, &r.polyline, &r.arc, &r.outline) {
        (Some(p), None, None, None) => Ok(RigidShape::Point { at: *p }),
        (None, Some(pts), None, None) if pts.len() >= 2 => Ok(RigidShape::Surface {
            pieces: line_pieces(pts).collect(),
        }),
        (None, None, Some(a), None) if a.radius > 0.0 && a.from_deg != a.to_deg => Ok(RigidShape::Surface {
            pieces: vec![arc_piece(a)],
        }),
        (None, None, None, Some(parts)) if !parts.is_empty() => {
            let mut pieces = Vec::new();
            for part in parts {
                match (&part.line, &part.arc) {
                    (Some(pts), None) if pts.len() >= 2 => pieces.extend(line_pieces(pts)),
                    (None, Some(a)) if a.radius > 0.0 && a.from_deg != a.to_deg => pieces.push(arc_piece(a)),
                    _ => {
                        return Err(cx.err(
                            &r.name,
                            format!("rigid body `{}`: an outline piece is not a valid line or arc", r.name),
                            hint,
                        ))
                    }
                }
            }
            Ok(RigidShape::Surface { pieces })
        }
        _ => Err(cx.err(
            &r.name,
            format!(
                "rigid body `{}` is not a valid point, polyline (≥ 2 points), arc or outline",
                r.name
            ),
            hint,
        )),
    }
}

/// Build the problem of a scene: its model and its solver settings.
pub fn build(src: &SceneSource, s: &SceneFile) -> Result<Problem, SceneError> {
    if super::build_solid::is_3d(s) {
        return Err(SceneError::Invalid {
            origin: src.origin.clone(),
            location: String::new(),
            message: format!("scene `{}` has 3D bodies (a `box` mesh)", s.name),
            hint: "3D scenes are run by `contrail run`, `contrail check` and `contrail sweep`; the service and the 2D tools take 2D scenes only for now".into(),
        });
    }
    Ok(Problem {
        model: build_model(src, s)?,
        settings: SolverSettings {
            stepping: s.stepping.clone(),
            newton: s.solver.clone(),
        },
    })
}

/// Build the model of a checked scene: its bodies, then what is prescribed and loaded on
/// them, the rigid bodies, the contact pairs (with those they imply) and the monitors.
pub fn build_model(src: &SceneSource, s: &SceneFile) -> Result<Model, SceneError> {
    super::validate::validate(src, s)?;
    let mut cx = Ctx {
        src,
        mesh_files: Vec::new(),
    };
    let end = steps::checked_end(&cx, s)?;
    let mut m = Model {
        name: s.name.clone(),
        description: s.description.clone(),
        ..Model::default()
    };
    super::body_model::check_mixed(&cx, s)?;
    steps::add_bodies(&mut cx, s, &mut m)?;
    steps::add_fixes(&cx, s, &mut m, end)?;
    super::body_model::fix_axis(&cx, &mut m, end)?;
    steps::add_loads(&cx, s, &mut m, end)?;
    steps::add_body_loads(&cx, s, &mut m, end)?;
    super::pressure::add_pressures(&cx, s, &mut m, end)?;
    steps::add_rigid(&cx, s, &mut m, end)?;
    super::axisymmetry::refuse_asymmetry(&cx, s, &m)?;
    steps::add_contacts(&cx, s, &mut m)?;
    super::body_model::contact_weights(&cx, &mut m)?;
    super::overclosure::adjust_overclosures(&mut m, s);
    super::initial_contact::refuse_initial_overlaps(&cx, &m, s)?;
    steps::add_monitors(&cx, s, &mut m)?;
    Ok(m)
}

#[path = "build_steps.rs"]
pub(super) mod steps;

/// A built scene of either dimension.
#[derive(Debug, Clone)]
pub enum AnyProblem {
    Plane(Problem),
    Solid(Problem<crate::model::Solid>),
}

/// Build a scene of either dimension: 3D when one of its bodies has a 3D mesh
/// ([`super::build_solid::build_solid`]), else 2D ([`build`]).
pub fn build_any(src: &SceneSource, s: &SceneFile) -> Result<AnyProblem, SceneError> {
    match super::build_solid::is_3d(s) {
        true => super::build_solid::build_solid(src, s).map(AnyProblem::Solid),
        false => build(src, s).map(AnyProblem::Plane),
    }
}

/// A vertex of a filleted outline is an arc now: it cannot be a slave point.
fn refuse_rounded_vertex(cx: &Ctx, s: &SceneFile, c: &ContactSpec) -> Result<(), SceneError> {
    let (Some(r), Some(v)) = (&c.slave.rigid, c.slave.vertex) else {
        return Ok(());
    };
    match s.rigid.iter().find(|x| x.name == *r).and_then(|x| x.fillet) {
        Some(radius) => Err(cx.err(
            &c.name,
            format!(
                "contact `{}`: vertex {v} of `{r}` is rounded by its fillet (r = {radius}): it is no point",
                c.name
            ),
            "remove the pair (the outline's arc meets the slave nodes itself), or remove the fillet",
        )),
        None => Ok(()),
    }
}

fn max_edge(m: &Model) -> f64 {
    let mut h = 0.0f64;
    for e in &m.elements {
        for i in 0..4 {
            let (a, b) = (m.nodes[e.nodes[i]], m.nodes[e.nodes[(i + 1) % 4]]);
            h = h.max(((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2)).sqrt());
        }
    }
    h
}

fn contact_pair(cx: &Ctx, m: &Model, c: &ContactSpec, h: f64) -> Result<ContactPair, SceneError> {
    let bad = |msg: &str| {
        cx.err(
            &c.name,
            format!("contact `{}`: {msg}", c.name),
            "slave = { body, nodes } or { rigid }; master = { body, face } or { rigid }",
        )
    };
    let slaves = match (&c.slave.body, &c.slave.nodes, &c.slave.rigid) {
        (Some(b), Some(sel), None) => {
            let bi = body_index(cx, m, b)?;
            select(cx, m, bi, sel)?.into_iter().map(Slave::Node).collect()
        }
        (None, None, Some(r)) => {
            let ri = rigid_index(cx, m, r)?;
            match (&m.rigid[ri].shape, c.slave.vertex) {
                (RigidShape::Point { .. }, None) => vec![Slave::RigidPoint(ri)],
                (RigidShape::Surface { pieces }, Some(v)) if v <= pieces.len() => {
                    vec![Slave::RigidVertex(ri, v)]
                }
                (RigidShape::Surface { pieces }, Some(v)) => {
                    return Err(bad(&format!("`{r}` has vertices 0..={}, not {v}", pieces.len())))
                }
                _ => return Err(bad("a rigid slave is a `point`, or a polyline with `vertex = K`")),
            }
        }
        _ => return Err(bad("invalid slave")),
    };
    let master = match (&c.master.body, &c.master.face, &c.master.rigid) {
        (Some(b), Some(face), None) => face_master(cx, m, b, face)?,
        (None, None, Some(r)) => {
            let ri = rigid_index(cx, m, r)?;
            let RigidShape::Surface { pieces } = &m.rigid[ri].shape else {
                return Err(bad("a rigid master must be a polyline or an arc"));
            };
            let n = pieces.len();
            let prev = (0..n).map(|k| k.checked_sub(1)).collect();
            let next = (0..n).map(|k| if k + 1 < n { Some(k + 1) } else { None }).collect();
            Master::Rigid { body: ri, prev, next }
        }
        _ => return Err(bad("invalid master")),
    };
    if c.mu_path.is_some() {
        return Err(bad("`mu_path` is for 3D pairs only for now: give a constant `mu`"));
    }
    let law = contact_law(cx, c)?;
    let smoothing = curve_smoothing(cx, c, &master)?;
    Ok(ContactPair {
        name: c.name.clone(),
        slaves,
        master,
        law,
        transfer: c.transfer,
        search_radius: c.search_radius.unwrap_or(2.0 * h),
        owned_vertices: Vec::new(),
        weights: Vec::new(),
        smoothing,
        enforcement: enforcement(cx, c)?,
    })
}

/// The master face `face` of body `b` (faces joined by `+` are one chain), or why it is not
/// one: no such face, or a Gmsh physical curve not on the boundary.
fn face_master(cx: &Ctx, m: &Model, b: &str, face: &str) -> Result<Master, SceneError> {
    let bi = body_index(cx, m, b)?;
    let segments = super::build_pairs::face_union(&m.bodies[bi].faces, face).ok_or_else(|| {
        let known: Vec<&str> = m.bodies[bi].faces.keys().map(|s| s.as_str()).collect();
        match &cx.mesh_files[bi] {
            Some((file, interior)) => match interior.iter().find(|c| c.0 == *face) {
                Some((_, n)) => cx.err(
                    face,
                    format!("body `{b}`: physical curve `{face}` of {file} is not a face: {n} of its lines are not on the boundary"),
                    &format!("a master face must lie on the body's boundary; its faces are: {}", known.join(", ")),
                ),
                None => cx.err(
                    face,
                    format!("body `{b}`: the mesh {file} has no physical curve `{face}` on its boundary"),
                    &format!(
                        "its faces are: {}; add `Physical Curve(\"{face}\") = {{…}};` to the .geo and mesh it again",
                        known.join(", ")
                    ),
                ),
            },
            None => cx.err(
                face,
                format!("body `{b}` has no face `{face}`"),
                &format!("faces are {}", known.join(", ")),
            ),
        }
    })?;
    let (prev, next) = chain_neighbours(&segments);
    Ok(Master::Face {
        body: bi,
        segments,
        prev,
        next,
    })
}

/// A 2D master's interpolation: the scene's `master_smoothing`, else straight segments for
/// a deformable face and Hermite for a rigid outline's vertex pair; `"nagata"` (a 3D face's
/// patches) refused.
fn curve_smoothing(cx: &Ctx, c: &ContactSpec, master: &Master) -> Result<Smoothing, SceneError> {
    if c.master_smoothing == Some(Smoothing::Nagata) {
        return Err(cx.err(
            &c.name,
            format!(
                "contact `{}`: `master_smoothing = \"nagata\"` smooths a 3D face",
                c.name
            ),
            "a 2D master curve is smoothed by master_smoothing = \"hermite\" or \"bezier\"",
        ));
    }
    Ok(c.master_smoothing.unwrap_or(match master {
        Master::Face { .. } => Smoothing::None,
        Master::Rigid { .. } => Smoothing::Hermite,
    }))
}

/// The law of a pair (2D or 3D): `eps_n > 0`, `mu ≥ 0` (every value of a `mu_path`), and
/// `eps_t > 0` when `mu > 0`. With a `mu_path` the law carries its largest `μ`: what
/// decides whether the pair is frictional.
pub(super) fn contact_law(cx: &Ctx, c: &ContactSpec) -> Result<ContactLaw, SceneError> {
    let (mu, lowest) = match &c.mu_path {
        Some(knots) => knots.iter().fold((0.0, f64::INFINITY), |(hi, lo), k| {
            (f64::max(hi, k[1]), f64::min(lo, k[1]))
        }),
        None => (c.mu, c.mu),
    };
    if c.eps_n <= 0.0 || c.eps_t < 0.0 || lowest < 0.0 || (mu > 0.0 && c.eps_t <= 0.0) {
        return Err(cx.err(
            &c.name,
            format!(
                "contact `{}`: need eps_n > 0, mu ≥ 0, and eps_t > 0 when mu > 0",
                c.name
            ),
            "give e.g. eps_n = 1e4, and eps_t > 0 with mu > 0 (mu = 0: frictionless)",
        ));
    }
    Ok(ContactLaw {
        eps_n: c.eps_n,
        eps_t: c.eps_t,
        mu,
    })
}

/// The pair's enforcement from its scene keys.
fn enforcement(cx: &Ctx, c: &ContactSpec) -> Result<Enforcement, SceneError> {
    match c.enforcement {
        EnforcementKind::Penalty => Ok(Enforcement::Penalty),
        EnforcementKind::Augmented if c.augmented_tol > 0.0 && c.augmented_max > 0 => Ok(Enforcement::Augmented {
            tol: c.augmented_tol,
            max: c.augmented_max,
        }),
        EnforcementKind::Augmented => Err(cx.err(
            &c.name,
            format!(
                "contact `{}`: augmented_tol = {} and augmented_max = {} (both must be positive)",
                c.name, c.augmented_tol, c.augmented_max
            ),
            "e.g. augmented_tol = 1e-3, augmented_max = 30",
        )),
    }
}
