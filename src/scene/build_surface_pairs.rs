//! The contact layer of a 3D scene: `[[rigid]]` planes and spheres resolved into
//! [`RigidSurface`]s, `[[contact]]` tables into [`SurfacePair`]s (`Model::surface_contacts`).
//!
//! - A slave side is a named face of a deformable body: its distinct nodes, each weighted by
//!   its tributary area `A_s` in the reference configuration (a quarter of the area of each
//!   face quadrilateral it is a corner of), since 3D penalties are per unit area
//!   (`N = ε_N A_s ⟨−ζ⟩`); or a node set or coordinate selection on one straight line, an
//!   edge, each node weighted by its tributary length (penalties per unit length,
//!   `edge_slave.rs`). Other selections are refused: they have neither areas nor lengths.
//! - A face name may join several faces with `+` (`"zmax+xmin"`): one surface.
//! - A master side is a face of a deformable body (its quadrilaterals as stored, outward) or a
//!   rigid plane or sphere. `two_pass` adds the pair the other way round (`NAME/second-pass`,
//!   the master face's nodes on the slave face), both passes with half the penalties, as in 2D.
//! - Refused in 3D, naming the key: the augmented Lagrangian, `master_smoothing`,
//!   `allow_initial_penetration`, rigid point and vertex slaves, the `spatial` transfer, and
//!   friction against a rigid sphere. `vertices` and `adjust_overclosure` are 2D rules (the
//!   convex vertices of a rigid outline; slave nodes moved onto a deformable master): their
//!   values are not used in 3D.
//! - A slave node that starts inside a rigid plane or sphere is refused
//!   (`refuse_rigid_overclosures`); against a deformable face the initial overclosure is
//!   not checked yet.

use super::build::{body_index, contact_law, motion_ramp, Ctx};
use super::types::{ContactSpec, EnforcementKind, NodeSelection, RigidSpec, SceneFile};
use super::SceneError;
use crate::contact3d::transfer::Scheme;
use crate::model::{
    ContactLaw, Dim, Model, Ramp, RigidSurface, RigidSurfaceShape, SlaveMeasure, Smoothing, Solid, SurfaceMaster,
    SurfacePair, TransferKind, SECOND_PASS_SUFFIX,
};
use std::collections::BTreeMap;

/// Depth (relative to the model's size) beyond which a slave node starts inside a rigid
/// surface: far above the round-off of coordinates that touch.
pub const RIGID_OVERCLOSURE_TOL: f64 = 1e-9;

/// What a 3D slave side is.
const SLAVE_HINT: &str = "a 3D slave is a face of a deformable body: slave = { body = \"B\", nodes = \"zmin\" }";

/// The rigid surfaces of a 3D scene, in scene order.
pub(super) fn rigid_surfaces(cx: &Ctx, s: &SceneFile, end: f64) -> Result<Vec<RigidSurface>, SceneError> {
    s.rigid.iter().map(|r| rigid_surface(cx, r, end)).collect()
}

/// One rigid surface: exactly one of `plane`, `sphere` and `cylinder` (the 2D shape keys
/// refused), its normal or axis made unit, its translation in x, y and z.
fn rigid_surface(cx: &Ctx, r: &RigidSpec, end: f64) -> Result<RigidSurface, SceneError> {
    let hint = "a 3D rigid body is `plane = { point = [x, y, z], normal = [nx, ny, nz] }`, `sphere = { centre = [x, y, z], radius = R }` or `cylinder = { point = [x, y, z], axis = [ax, ay, az], radius = R }`";
    let two_d = [
        ("point", r.point.is_some()),
        ("polyline", r.polyline.is_some()),
        ("arc", r.arc.is_some()),
        ("outline", r.outline.is_some()),
        ("polygon", r.polygon.is_some()),
        ("fillet", r.fillet.is_some()),
    ];
    if let Some((key, _)) = two_d.iter().find(|(_, given)| *given) {
        return Err(cx.err(
            &r.name,
            format!(
                "rigid body `{}`: `{key}` is a 2D rigid outline key in a 3D scene",
                r.name
            ),
            hint,
        ));
    }
    let given: Vec<&str> = [
        ("`plane`", r.plane.is_some()),
        ("`sphere`", r.sphere.is_some()),
        ("`cylinder`", r.cylinder.is_some()),
    ]
    .into_iter()
    .filter_map(|(k, g)| g.then_some(k))
    .collect();
    if given.len() != 1 {
        let msg = match given.len() {
            0 => format!(
                "rigid body `{}` has no shape: give `plane`, `sphere` or `cylinder`",
                r.name
            ),
            _ => format!(
                "rigid body `{}` has {}: one shape per rigid body",
                r.name,
                given.join(" and ")
            ),
        };
        return Err(cx.err(&r.name, msg, hint));
    }
    let zero_vector = |key: &str| cx.err(&r.name, format!("rigid body `{}`: `{key}` is zero", r.name), hint);
    let positive = |key: &str, v: f64| -> Result<f64, SceneError> {
        if v > 0.0 {
            return Ok(v);
        }
        let msg = format!("rigid body `{}`: `{key}` = {v} must be > 0", r.name);
        Err(cx.err(&r.name, msg, hint))
    };
    let shape = if let Some(p) = &r.plane {
        RigidSurfaceShape::Plane {
            point: p.point,
            normal: unit(p.normal).ok_or_else(|| zero_vector("plane.normal"))?,
        }
    } else if let Some(sp) = &r.sphere {
        RigidSurfaceShape::Sphere {
            centre: sp.centre,
            radius: positive("sphere.radius", sp.radius)?,
        }
    } else {
        let cy = r.cylinder.as_ref().expect("one shape given");
        RigidSurfaceShape::Cylinder {
            point: cy.point,
            axis: unit(cy.axis).ok_or_else(|| zero_vector("cylinder.axis"))?,
            radius: positive("cylinder.radius", cy.radius)?,
        }
    };
    let m = &r.motion;
    Ok(RigidSurface {
        name: r.name.clone(),
        shape,
        motion: [&m.x, &m.y, &m.z].map(|c| motion_ramp(c, end)),
    })
}

/// `v` made unit (scaled by its largest component first: no overflow); `None` when zero.
fn unit(v: [f64; 3]) -> Option<[f64; 3]> {
    let big = v.iter().fold(0.0f64, |a, x| a.max(x.abs()));
    if !(big > 0.0 && big.is_finite()) {
        return None;
    }
    let w = v.map(|x| x / big);
    let len = w.iter().map(|x| x * x).sum::<f64>().sqrt();
    Some(w.map(|x| x / len))
}

/// The 3D contact pairs of the scene, then the second passes of its two-pass pairs.
pub(super) fn add_surface_contacts(
    cx: &Ctx,
    s: &SceneFile,
    m: &mut Model<Solid>,
    rigid: &[RigidSurface],
) -> Result<(), SceneError> {
    let h = (m.elements.iter())
        .map(|e| Solid::longest_edge(&e.nodes.map(|n| m.nodes[n])))
        .fold(0.0, f64::max);
    let mut second = Vec::new();
    for c in &s.contacts {
        refuse_2d_keys(cx, c)?;
        let (slave_body, slave_side) = slave_side(cx, m, c)?;
        let master = surface_master(cx, m, c, rigid)?;
        let law = contact_law(cx, c)?;
        let (slaves, areas, measure) = match &slave_side {
            SlaveSide::Face(face) => {
                let (slaves, areas) = tributary_areas(&m.nodes, face);
                (slaves, areas, SlaveMeasure::Area)
            }
            SlaveSide::Edge(slaves, lengths) => (slaves.clone(), lengths.clone(), SlaveMeasure::Length),
        };
        let mut pair = SurfacePair {
            name: c.name.clone(),
            slaves,
            areas,
            measure,
            master,
            law,
            friction: c.mu_path.as_ref().map(|k| Ramp {
                knots: k.iter().map(|p| (p[0], p[1])).collect(),
            }),
            transfer: scheme(cx, c)?,
            smoothing: face_smoothing(cx, c)?,
            search_radius: c.search_radius.unwrap_or(2.0 * h),
        };
        if c.two_pass {
            let SlaveSide::Face(slave_face) = slave_side else {
                return Err(cx.err(
                    &c.name,
                    format!("contact `{}`: `two_pass` with an edge slave: an edge has no face to be the second pass's master", c.name),
                    "remove two_pass (an edge presses on the master face from one side only)",
                ));
            };
            second.push(second_pass(cx, m, c, &mut pair, slave_body, slave_face)?);
        }
        m.surface_contacts.push(pair);
    }
    m.surface_contacts.extend(second);
    Ok(())
}

/// The keys of a `[[contact]]` that 3D does not have, refused naming the key.
fn refuse_2d_keys(cx: &Ctx, c: &ContactSpec) -> Result<(), SceneError> {
    let refused = [
        (
            c.enforcement == EnforcementKind::Augmented,
            "enforcement = \"augmented\"",
            "the augmented Lagrangian's multiplier updates are 2D only; use the penalty (remove `enforcement`)",
        ),
        (
            c.allow_initial_penetration,
            "allow_initial_penetration = true",
            "a slave node inside a rigid surface at the start is refused in 3D; move the body or the rigid surface",
        ),
        (c.slave.rigid.is_some(), "slave.rigid", SLAVE_HINT),
        (c.slave.vertex.is_some(), "slave.vertex", SLAVE_HINT),
    ];
    match refused.iter().find(|(given, _, _)| *given) {
        Some((_, key, hint)) => Err(cx.err(
            &c.name,
            format!("contact `{}`: `{key}` is not available in a 3D scene", c.name),
            hint,
        )),
        None => Ok(()),
    }
}

/// The transfer scheme of a 3D pair (`spatial` refused: it has no 3D kernel).
fn scheme(cx: &Ctx, c: &ContactSpec) -> Result<Scheme, SceneError> {
    match c.transfer {
        TransferKind::Continuous => Ok(Scheme::Continuous),
        TransferKind::Straightforward => Ok(Scheme::Straightforward),
        TransferKind::PathLength => Ok(Scheme::PathLength),
        TransferKind::Spatial => Err(cx.err(
            &c.name,
            format!("contact `{}`: `transfer = \"spatial\"` has no 3D scheme", c.name),
            "use transfer = \"continuous\" (the default), \"straightforward\" or \"path-length\"",
        )),
    }
}

/// A 3D master face's interpolation: `master_smoothing = "none"` (the default: bilinear
/// facets) or `"nagata"` (smooth patches through the nodes); the 2D curves are refused.
fn face_smoothing(cx: &Ctx, c: &ContactSpec) -> Result<Smoothing, SceneError> {
    match c.master_smoothing.unwrap_or_default() {
        s @ (Smoothing::None | Smoothing::Nagata) => Ok(s),
        other => Err(cx.err(
            &c.name,
            format!("contact `{}`: `master_smoothing = \"{}\"` is a 2D curve's", c.name, other.name()),
            "a 3D master face is smoothed by Nagata patches: master_smoothing = \"nagata\" (or \"none\" for bilinear facets)",
        )),
    }
}

/// A 3D slave side: a face's quadrilaterals, or an edge's nodes with their tributary lengths.
enum SlaveSide {
    Face(Vec<[usize; 4]>),
    Edge(Vec<usize>, Vec<f64>),
}

/// The slave body and side of a pair: `slave = { body, nodes = "FACE" }`, or a node set or
/// coordinate selection whose nodes lie on one straight line (an edge, weighted by lengths:
/// `edge_slave.rs`).
fn slave_side(cx: &Ctx, m: &Model<Solid>, c: &ContactSpec) -> Result<(usize, SlaveSide), SceneError> {
    let (Some(b), Some(sel)) = (&c.slave.body, &c.slave.nodes) else {
        return Err(cx.err(&c.name, format!("contact `{}`: invalid slave", c.name), SLAVE_HINT));
    };
    let bi = body_index(cx, m, b)?;
    if let NodeSelection::Named(name) = sel {
        if m.bodies[bi].faces.contains_key(name) || !m.bodies[bi].node_sets.contains_key(name) {
            return Ok((bi, SlaveSide::Face(named_face(cx, m, bi, name, "slave.nodes")?)));
        }
    }
    let nodes = super::build::select(cx, m, bi, sel)?;
    match super::edge_slave::edge_lengths(&m.nodes, &nodes) {
        Ok((slaves, lengths)) => Ok((bi, SlaveSide::Edge(slaves, lengths))),
        Err(why) => Err(cx.err(
            &c.name,
            format!("contact `{}`: `slave.nodes` = {sel} is neither a face nor a straight edge: {why}", c.name),
            &format!("name a face of body `{b}` (penalties per unit area), e.g. nodes = \"zmin\", or select nodes on one straight line, e.g. nodes = {{ x = 6.5, z = 0.0 }} (penalties per unit length)"),
        )),
    }
}

/// The face `name` of body `bi` (`key`: the scene key that names it, for the error); names
/// joined by `+` (`"zmax+xmin"`) give the union of those faces, as one surface whose facets
/// meet at their shared edges.
fn named_face(cx: &Ctx, m: &Model<Solid>, bi: usize, name: &str, key: &str) -> Result<Vec<[usize; 4]>, SceneError> {
    if name.contains('+') {
        let mut union: Vec<[usize; 4]> = Vec::new();
        for part in name.split('+').map(str::trim) {
            for q in named_face(cx, m, bi, part, key)? {
                if !union.contains(&q) {
                    union.push(q);
                }
            }
        }
        return Ok(union);
    }
    let b = &m.bodies[bi];
    if let Some(face) = b.faces.get(name) {
        return Ok(face.clone());
    }
    let known: Vec<&str> = b.faces.keys().map(|s| s.as_str()).collect();
    let hint = format!("the faces of body `{}` are: {}", b.name, known.join(", "));
    let message = match b.node_sets.contains_key(name) {
        true => format!(
            "`{key}` = \"{name}\": body `{}` has a node set `{name}` but no face of that name: 3D slaves and masters are named by a face (areas weigh the penalty)",
            b.name
        ),
        false => format!("`{key}` = \"{name}\": body `{}` has no face `{name}`", b.name),
    };
    Err(cx.err(name, message, &hint))
}

/// The master of a pair: a face of a deformable body, or a rigid surface (cloned).
fn surface_master(
    cx: &Ctx,
    m: &Model<Solid>,
    c: &ContactSpec,
    rigid: &[RigidSurface],
) -> Result<SurfaceMaster, SceneError> {
    match (&c.master.body, &c.master.face, &c.master.rigid) {
        (Some(b), Some(face), None) => {
            let body = body_index(cx, m, b)?;
            let facets = named_face(cx, m, body, face, "master.face")?;
            Ok(SurfaceMaster::Facets { body, facets })
        }
        (None, None, Some(r)) => match rigid.iter().find(|x| x.name == *r) {
            Some(x) => Ok(SurfaceMaster::Rigid(x.clone())),
            None => {
                let known: Vec<&str> = rigid.iter().map(|x| x.name.as_str()).collect();
                let msg = format!("contact `{}`: no rigid body named `{r}`", c.name);
                let hint = match known.is_empty() {
                    true => "add a [[rigid]] with `plane` or `sphere`".to_string(),
                    false => format!("known rigid bodies: {}", known.join(", ")),
                };
                Err(cx.err(r, msg, &hint))
            }
        },
        _ => Err(cx.err(
            &c.name,
            format!("contact `{}`: invalid master", c.name),
            "master = { body = \"B\", face = \"zmax\" } or { rigid = \"R\" }",
        )),
    }
}

/// Make `pair` the first pass of a two-pass pair (half its penalties) and return the second:
/// the master face's nodes (their areas from its quadrilaterals) on the slave face.
fn second_pass(
    cx: &Ctx,
    m: &Model<Solid>,
    c: &ContactSpec,
    pair: &mut SurfacePair,
    slave_body: usize,
    slave_face: Vec<[usize; 4]>,
) -> Result<SurfacePair, SceneError> {
    let SurfaceMaster::Facets { facets, .. } = &pair.master else {
        return Err(cx.err(
            &c.name,
            format!(
                "contact `{}`: `two_pass` is for slave nodes on the face of another deformable body",
                c.name
            ),
            "use master = { body, face }, or remove two_pass",
        ));
    };
    let (slaves, areas) = tributary_areas(&m.nodes, facets);
    pair.law = ContactLaw {
        eps_n: 0.5 * pair.law.eps_n,
        eps_t: 0.5 * pair.law.eps_t,
        mu: pair.law.mu,
    };
    Ok(SurfacePair {
        name: format!("{}{SECOND_PASS_SUFFIX}", pair.name),
        slaves,
        areas,
        measure: SlaveMeasure::Area,
        master: SurfaceMaster::Facets {
            body: slave_body,
            facets: slave_face,
        },
        law: pair.law,
        friction: pair.friction.clone(),
        transfer: pair.transfer,
        smoothing: pair.smoothing,
        search_radius: pair.search_radius,
    })
}

/// The distinct nodes of a face (sorted) and each one's tributary area: a quarter of the
/// reference area of every quadrilateral it is a corner of.
pub fn tributary_areas(nodes: &[[f64; 3]], quads: &[[usize; 4]]) -> (Vec<usize>, Vec<f64>) {
    let mut area = BTreeMap::<usize, f64>::new();
    for q in quads {
        let a = quad_area(&q.map(|n| nodes[n]));
        for n in q {
            *area.entry(*n).or_default() += 0.25 * a;
        }
    }
    area.into_iter().unzip()
}

/// Area of the bilinear quadrilateral through `x` (corners in order): `∫ |x,ξ × x,η| dξ dη`
/// by 2×2 Gauss (exact when the quadrilateral is plane; a warped one is curved).
pub fn quad_area(x: &[[f64; 3]; 4]) -> f64 {
    const XI: [f64; 4] = [-1.0, 1.0, 1.0, -1.0];
    const ETA: [f64; 4] = [-1.0, -1.0, 1.0, 1.0];
    let g = 1.0 / 3f64.sqrt();
    let mut total = 0.0;
    for (xi, eta) in [(-g, -g), (g, -g), (g, g), (-g, g)] {
        let (mut a, mut b) = ([0.0; 3], [0.0; 3]);
        for k in 0..4 {
            for c in 0..3 {
                a[c] += 0.25 * XI[k] * (1.0 + ETA[k] * eta) * x[k][c];
                b[c] += 0.25 * ETA[k] * (1.0 + XI[k] * xi) * x[k][c];
            }
        }
        let n = [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ];
        total += (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
    }
    total
}

/// Signed distance of `x` from a rigid surface in its reference position (negative inside).
pub fn rigid_gap(shape: &RigidSurfaceShape, x: [f64; 3]) -> f64 {
    match *shape {
        RigidSurfaceShape::Plane { point, normal } => (0..3).map(|c| (x[c] - point[c]) * normal[c]).sum(),
        RigidSurfaceShape::Sphere { centre, radius } => {
            let d: f64 = (0..3).map(|c| (x[c] - centre[c]).powi(2)).sum();
            d.sqrt() - radius
        }
        RigidSurfaceShape::Cylinder { point, axis, radius } => {
            let d: [f64; 3] = std::array::from_fn(|c| x[c] - point[c]);
            let along: f64 = (0..3).map(|c| d[c] * axis[c]).sum();
            let r2: f64 = (0..3).map(|c| (d[c] - along * axis[c]).powi(2)).sum();
            r2.sqrt() - radius
        }
    }
}

/// Refuse a pair with a rigid master whose slave nodes start inside it (at `t = 0`) deeper
/// than [`RIGID_OVERCLOSURE_TOL`] × the model's size, naming the deepest node: the first
/// residual would push the face out through the surface and the run would answer wrong.
/// Pairs against a deformable face are not checked (not built yet).
pub(super) fn refuse_rigid_overclosures(cx: &Ctx, m: &Model<Solid>) -> Result<(), SceneError> {
    let tol = RIGID_OVERCLOSURE_TOL * m.size();
    for p in &m.surface_contacts {
        let SurfaceMaster::Rigid(r) = &p.master else {
            continue;
        };
        let off = r.offset(0.0);
        let gap = |n: usize| rigid_gap(&r.shape, std::array::from_fn(|c| m.nodes[n][c] - off[c]));
        let inside = p.slaves.iter().filter(|&&n| gap(n) < -tol).count();
        let Some(&deepest) = p.slaves.iter().min_by(|&&a, &&b| gap(a).total_cmp(&gap(b))) else {
            continue;
        };
        if inside == 0 {
            continue;
        }
        let x = m.nodes[deepest];
        return Err(cx.err(
            &p.name,
            format!(
                "contact `{}`: {inside} of its {} slave nodes start inside rigid body `{}` — node {deepest} at [{:.6}, {:.6}, {:.6}] by {:.4e}",
                p.name,
                p.slaves.len(),
                r.name,
                x[0],
                x[1],
                x[2],
                -gap(deepest)
            ),
            &format!("move the body or the rigid surface `{}` (its `plane.point`, `sphere.centre` or its `move` at t = 0) so that they start apart or touching; a plane's normal points out of the rigid body, towards the slaves", r.name),
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_plane_quadrilaterals_area_is_exact_and_a_warped_ones_larger_than_its_shadow() {
        let trapezoid = [[0.0, 0.0, 1.0], [3.0, 0.0, 1.0], [2.0, 1.0, 1.0], [1.0, 1.0, 1.0]];
        assert!((quad_area(&trapezoid) - 2.0).abs() < 1e-14);
        let warped = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.5], [0.0, 1.0, 0.0]];
        let a = quad_area(&warped);
        assert!(a > 1.0 && a < 1.1, "{a}");
    }

    #[test]
    fn a_planes_normal_is_made_unit() {
        assert_eq!(unit([0.0, 0.0, -3.0]), Some([0.0, 0.0, -1.0]));
        assert_eq!(unit([0.0; 3]), None);
        let n = unit([1e300, 1e300, 0.0]).unwrap();
        assert!((n[0] - 0.5f64.sqrt()).abs() < 1e-15);
    }
}
