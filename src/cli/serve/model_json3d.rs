//! The model view's JSON of a 3D run (`dim: 3`; [`super::model_json`] answers 2D runs and
//! asks this module for a 3D one): the reference nodes, the boundary quadrilaterals of the
//! hexahedra (the faces the page draws the edges of), the rigid masters of the 3D pairs,
//! and per increment the node positions, the masters' offsets and the `/surface_contact`
//! points. Coordinates are flat arrays of 3 numbers per point in single precision (NaN:
//! null — a recording may hold positions of only some nodes).

use contrail::analysis::recording::Recording;
use contrail::model::hex_boundary::boundary_quads;
use contrail::record::rrd::view3d::{model_size, square};
use contrail::record::surface_contact::{RigidShapeInfo, SurfacePointRecord};
use serde_json::{json, Value};

/// Half-width of a rigid plane's square and half-length of a cylinder's drawn axis, in model
/// sizes (the reference nodes' diagonal), as the Foxglove and rerun views draw them.
const HALF: f64 = 0.75;

/// Points as a flat `[x0, y0, z0, x1, …]` list in single precision (NaN: null).
pub fn flat3(points: impl IntoIterator<Item = [f64; 3]>) -> Vec<f32> {
    points.into_iter().flat_map(|p| p.map(|x| x as f32)).collect()
}

/// Whether the recording is of a 3D model.
pub fn is_3d(rec: &Recording) -> bool {
    rec.model.dim == Some(3)
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// The part of a contact force across the master's normal (a point without a normal, open,
/// has none).
fn tangential(p: &SurfacePointRecord) -> [f64; 3] {
    if !p.normal.iter().all(|x| x.is_finite()) {
        return [0.0; 3];
    }
    let along = dot(p.force, p.normal);
    std::array::from_fn(|c| p.force[c] - along * p.normal[c])
}

/// Largest contact force (magnitude), normal force and tangential force of the run: the
/// page scales its arrows by them, the same at every increment.
fn largest_forces(rec: &Recording) -> Value {
    let (mut total, mut normal, mut across) = (0.0f64, 0.0f64, 0.0f64);
    for p in rec.surface.values().flatten() {
        let t = tangential(p);
        total = total.max(dot(p.force, p.force).sqrt());
        normal = normal.max(p.normal_force.abs());
        across = across.max(dot(t, t).sqrt());
    }
    // NaN never wins a max: these are finite or zero
    json!({ "force": total, "normal_force": normal, "traction": across })
}

/// Grows a box `[xmin, ymin, zmin, xmax, ymax, zmax]` to hold a point (non-finite points are
/// skipped).
fn grow(b: &mut [f64; 6], p: [f64; 3]) {
    if p.iter().all(|x| x.is_finite()) {
        for c in 0..3 {
            b[c] = b[c].min(p[c]);
            b[c + 3] = b[c + 3].max(p[c]);
        }
    }
}

/// `[xmin, ymin, zmin, xmax, ymax, zmax]` of the nodes at every recorded increment (the
/// page fits the sphere about this box; a rigid master is drawn cut off at the frame).
fn bounds(rec: &Recording) -> [f64; 6] {
    let mut b = [
        f64::INFINITY,
        f64::INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::NEG_INFINITY,
        f64::NEG_INFINITY,
    ];
    rec.model.nodes_3d.iter().for_each(|&p| grow(&mut b, p));
    rec.positions
        .iter()
        .flat_map(|p| &p.nodes_3d)
        .for_each(|&p| grow(&mut b, p));
    if b[0] > b[3] {
        return [0.0, 0.0, 0.0, 1.0, 1.0, 1.0];
    }
    b
}

/// The rigid masters of the 3D pairs in their reference position: `pair` indexes the
/// frames' `rigid_offsets`; a plane with the corners of its drawn square, a cylinder with
/// the ends of its drawn axis.
fn rigid(rec: &Recording) -> Vec<Value> {
    let half = HALF * model_size(&rec.model.nodes_3d);
    let pairs = rec.model.surface_contacts.iter().enumerate();
    pairs
        .filter_map(|(k, p)| {
            let name = p.master.strip_prefix("rigid ").unwrap_or(&p.master);
            let v = match *p.rigid.as_ref()? {
                RigidShapeInfo::Plane { point, normal } => json!({
                    "kind": "plane", "point": flat3([point]), "normal": flat3([normal]),
                    "corners": flat3(square(point, normal, half)),
                }),
                RigidShapeInfo::Sphere { centre, radius } => {
                    json!({ "kind": "sphere", "centre": flat3([centre]), "radius": radius as f32 })
                }
                RigidShapeInfo::Cylinder { point, axis, radius } => {
                    let end = |s: f64| std::array::from_fn(|c| point[c] + s * half * axis[c]);
                    json!({
                        "kind": "cylinder", "point": flat3([point]), "axis": flat3([axis]),
                        "radius": radius as f32, "ends": flat3([end(-1.0), end(1.0)]),
                    })
                }
            };
            let mut v = v;
            v["name"] = json!(name);
            v["pair"] = json!(k);
            Some(v)
        })
        .collect()
}

/// The boundary quadrilaterals of the hexahedra (outward) and the body of each (the body
/// whose node range holds the first node).
fn faces(rec: &Recording) -> (Vec<[usize; 4]>, Vec<Option<usize>>) {
    let m = &rec.model;
    let quads = boundary_quads(&m.hexahedra);
    let body = quads
        .iter()
        .map(|q| (m.bodies.iter()).position(|b| (b.first_node..b.first_node + b.node_count).contains(&q[0])))
        .collect();
    (quads, body)
}

/// `GET /api/runs/{id}/model` of a 3D run: `v` is the answer's common part (made by
/// [`super::model_json::model`]), to which the 3D mesh, bounds and forces are added.
pub fn model(rec: &Recording, mesh: bool, mut v: Value) -> Value {
    let m = &rec.model;
    let (quads, face_body) = faces(rec);
    v["dim"] = json!(3);
    v["node_count"] = json!(m.nodes_3d.len());
    v["element_count"] = json!(m.hexahedra.len());
    v["nodes_per_element"] = json!(8);
    v["face_count"] = json!(quads.len());
    v["positions_at"] = json!(rec
        .positions
        .iter()
        .filter(|p| !p.nodes_3d.is_empty())
        .map(|p| p.increment)
        .collect::<Vec<_>>());
    v["bounds"] = json!(bounds(rec));
    v["largest"] = largest_forces(rec);
    if mesh {
        v["nodes"] = json!(flat3(m.nodes_3d.iter().copied()));
        v["faces"] = json!(quads.iter().flatten().collect::<Vec<_>>());
        v["face_body"] = json!(face_body);
        v["rigid"] = json!(rigid(rec));
        v["pairs"] = json!(m
            .surface_contacts
            .iter()
            .map(|c| json!({ "name": c.name, "master": c.master, "mu": c.mu, "slaves": c.slave_nodes.len() }))
            .collect::<Vec<_>>());
    }
    v
}

/// The positions shown at `increment` (its own, else the nearest earlier recorded ones, else
/// the reference configuration) and whose they are.
pub fn positions_at(rec: &Recording, increment: usize) -> (usize, Vec<f32>) {
    let before = rec
        .positions
        .iter()
        .filter(|p| p.increment <= increment && !p.nodes_3d.is_empty())
        .max_by_key(|p| p.increment);
    match before {
        Some(p) => (p.increment, flat3(p.nodes_3d.iter().copied())),
        None => (0, flat3(rec.model.nodes_3d.iter().copied())),
    }
}

/// The 3D pairs' rigid master offsets at `increment` (zero for facets and at increment 0).
pub fn offsets_at(rec: &Recording, increment: usize) -> Vec<f32> {
    let zero = vec![[0.0; 3]; rec.model.surface_contacts.len()];
    let off = rec.surface_offsets.get(&increment).unwrap_or(&zero);
    flat3(off.iter().copied())
}

/// The 3D contact points of an increment as parallel arrays (vectors flat, 3 per point):
/// pair, slave node, state, facet (null: nothing within reach), the slave node's position,
/// the master's normal, the force the slave receives, its normal part and tangential
/// magnitude, the gap.
pub fn contact_arrays(points: &[SurfacePointRecord]) -> Value {
    json!({
        "count": points.len(),
        "pair": points.iter().map(|p| p.pair).collect::<Vec<_>>(),
        "node": points.iter().map(|p| p.node).collect::<Vec<_>>(),
        "state": points.iter().map(|p| p.state).collect::<Vec<_>>(),
        "facet": points.iter().map(|p| p.facet).collect::<Vec<_>>(),
        "crossing": points.iter().map(|p| p.crossing).collect::<Vec<_>>(),
        "position": flat3(points.iter().map(|p| p.position)),
        "normal": flat3(points.iter().map(|p| p.normal)),
        "force": flat3(points.iter().map(|p| p.force)),
        "normal_force": points.iter().map(|p| p.normal_force as f32).collect::<Vec<_>>(),
        "traction": points.iter().map(|p| { let t = tangential(p); dot(t, t).sqrt() as f32 }).collect::<Vec<_>>(),
        "gap": points.iter().map(|p| p.gap as f32).collect::<Vec<_>>(),
    })
}
