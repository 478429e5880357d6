//! The Foxglove scene of a 3D model (`/foxglove/reference`, `/foxglove/scene`, as
//! [`super::foxglove`] writes them for a plane model): the edges of the mesh's boundary
//! quadrilaterals (reference and deformed; the line list holds the boundary nodes only), each rigid master of a 3D pair moved by its
//! offset — a plane as a translucent square of 1.5 model sizes, a sphere as a sphere, a
//! cylinder as a cylinder of that length — the contact slave points within reach as spheres
//! coloured by state (the colours of the rerun view), and a label. z is up, as in the
//! model; coordinates in single precision (display data: the exact values are on
//! `/positions` and `/surface_contact`).

use super::foxglove::{entity, label, line_list, primitives, sphere, ScenePoint, POSE};
use super::json_text::{colour, point3, raw, real32};
use crate::model::hex_boundary::boundary_quads;
use crate::record::messages::ModelRecord;
use crate::record::rrd::style::{point_colour, MESH, REFERENCE, RIGID};
use crate::record::surface_contact::RigidShapeInfo;

/// A rigid master drawn see-through, so that the points it presses stay visible.
const RIGID_FILL: [u8; 4] = [RIGID[0], RIGID[1], RIGID[2], 90];

/// What one 3D scene shows.
pub struct SolidSceneView<'a> {
    pub increment: usize,
    pub t: f64,
    /// Current coordinates of every node.
    pub nodes: &'a [[f64; 3]],
    /// The displacement of each 3D pair's rigid master (zero for a deformable master).
    pub master_offsets: &'a [[f64; 3]],
    /// The slave points of every 3D pair (`pair` indexes the model's `surface_contacts`).
    pub contact: &'a [ScenePoint<[f64; 3]>],
}

/// Writes the `foxglove.SceneUpdate` messages of a 3D model.
pub struct SolidSceneEncoder {
    reference: Vec<u8>,
    /// The nodes drawn: those of the boundary (an interior node is on no drawn edge), in
    /// node order; the line list's points are these nodes' positions.
    shown: Vec<usize>,
    /// `"indices":[…]` of the boundary edges, into `shown`.
    indices: Vec<u8>,
    /// Per 3D pair: its rigid master's shape (none for facets) and friction coefficient.
    pairs: Vec<(Option<RigidShapeInfo>, f64)>,
    point_size: f64,
    /// Half-width of a plane's square, half-length of a cylinder.
    half: f64,
    label_at: [f64; 3],
}

impl SolidSceneEncoder {
    pub fn new(model: &ModelRecord) -> Self {
        let mut edges: Vec<[usize; 2]> = (boundary_quads(&model.hexahedra).iter())
            .flat_map(|q| (0..4).map(move |k| [q[k].min(q[(k + 1) % 4]), q[k].max(q[(k + 1) % 4])]))
            .collect();
        edges.sort_unstable();
        edges.dedup();
        let mut shown: Vec<usize> = edges.iter().flatten().copied().collect();
        shown.sort_unstable();
        shown.dedup();
        let mut indices = Vec::new();
        raw(&mut indices, "\"indices\":[");
        let list: Vec<String> = (edges.iter().flatten())
            .map(|n| shown.binary_search(n).expect("an edge's node is shown").to_string())
            .collect();
        raw(&mut indices, &list.join(","));
        raw(&mut indices, "]");
        let mut reference = Vec::new();
        let at_rest: Vec<[f64; 3]> = shown.iter().map(|&n| model.nodes_3d[n]).collect();
        line_list(&mut reference, &at_rest, &indices, REFERENCE, 1.0);
        let (lo, hi) = bounds(&model.nodes_3d);
        let size = (0..3).map(|c| (hi[c] - lo[c]).powi(2)).sum::<f64>().sqrt().max(1e-9);
        SolidSceneEncoder {
            reference,
            shown,
            indices,
            pairs: (model.surface_contacts.iter())
                .map(|p| (p.rigid.clone(), p.mu))
                .collect(),
            point_size: 0.01 * size,
            half: 0.75 * size,
            label_at: [lo[0], lo[1], hi[2] + 0.1 * size],
        }
    }

    /// Append the reference mesh (`/foxglove/reference`), logged at `time_ns`.
    pub fn write_reference(&self, out: &mut Vec<u8>, time_ns: u64) {
        raw(out, "{\"deletions\":[],\"entities\":[");
        entity(out, "reference mesh", time_ns, "[]");
        primitives(out, &[("lines", &self.reference)]);
        raw(out, "]}");
    }

    /// Append the scene of one increment (`/foxglove/scene`), logged at `time_ns`.
    pub fn write(&self, out: &mut Vec<u8>, view: &SolidSceneView, time_ns: u64) {
        raw(out, "{\"deletions\":[],\"entities\":[");
        let meta = format!(
            "[{{\"key\":\"increment\",\"value\":\"{}\"}},{{\"key\":\"t\",\"value\":\"{}\"}}]",
            view.increment, view.t
        );
        entity(out, "mesh", time_ns, &meta);
        let mut lines = Vec::new();
        let now: Vec<[f64; 3]> = (self.shown.iter())
            .map(|&n| view.nodes.get(n).copied().unwrap_or([f64::NAN; 3]))
            .collect();
        line_list(&mut lines, &now, &self.indices, MESH, 1.5);
        primitives(out, &[("lines", &lines)]);
        raw(out, ",");
        entity(out, "rigid", time_ns, &meta);
        let (spheres, cylinders, triangles) = self.rigid_primitives(view.master_offsets);
        primitives(
            out,
            &[
                ("spheres", &spheres),
                ("cylinders", &cylinders),
                ("triangles", &triangles),
            ],
        );
        raw(out, ",");
        entity(out, "contact points", time_ns, &meta);
        let mut points = Vec::new();
        for p in (view.contact.iter()).filter(|p| p.in_reach && p.position.iter().all(|x| x.is_finite())) {
            let mu = self.pairs.get(p.pair).map_or(0.0, |(_, mu)| *mu);
            sphere(&mut points, p.position, self.point_size, point_colour(p.state, mu));
        }
        primitives(out, &[("spheres", &points)]);
        raw(out, ",");
        entity(out, "label", time_ns, &meta);
        label(out, self.label_at, view.increment, view.t);
        raw(out, "]}");
    }

    /// The rigid masters moved by their offsets: spheres, cylinders and the planes'
    /// squares (two triangles each).
    fn rigid_primitives(&self, offsets: &[[f64; 3]]) -> (Vec<u8>, Vec<u8>, Vec<u8>) {
        let (mut spheres, mut cylinders, mut triangles) = (Vec::new(), Vec::new(), Vec::new());
        for ((shape, _), off) in self.pairs.iter().zip(offsets) {
            let moved = |p: [f64; 3]| -> [f64; 3] { std::array::from_fn(|c| p[c] + off[c]) };
            match shape {
                Some(RigidShapeInfo::Sphere { centre, radius }) => {
                    sphere(&mut spheres, moved(*centre), 2.0 * radius, RIGID_FILL)
                }
                Some(RigidShapeInfo::Cylinder { point, axis, radius }) => {
                    cylinder(&mut cylinders, moved(*point), *axis, [2.0 * radius, 2.0 * self.half]);
                }
                Some(RigidShapeInfo::Plane { point, normal }) => {
                    square(&mut triangles, moved(*point), *normal, self.half)
                }
                None => {}
            }
        }
        (spheres, cylinders, triangles)
    }
}

/// Append a cylinder about `axis` through `centre` (`size`: diameter, length).
fn cylinder(out: &mut Vec<u8>, centre: [f64; 3], axis: [f64; 3], size: [f64; 2]) {
    if !out.is_empty() {
        raw(out, ",");
    }
    raw(out, "{\"pose\":{\"position\":");
    point3(out, centre);
    raw(out, ",\"orientation\":");
    quaternion(out, z_onto(axis));
    raw(out, "},\"size\":{\"x\":");
    real32(out, size[0]);
    raw(out, ",\"y\":");
    real32(out, size[0]);
    raw(out, ",\"z\":");
    real32(out, size[1]);
    raw(out, "},\"bottom_scale\":1,\"top_scale\":1,\"color\":");
    colour(out, RIGID_FILL);
    raw(out, "}");
}

/// Append the square of half-width `half` about `point` in the plane of `normal`.
fn square(out: &mut Vec<u8>, point: [f64; 3], normal: [f64; 3], half: f64) {
    if !out.is_empty() {
        raw(out, ",");
    }
    raw(out, "{\"pose\":");
    raw(out, POSE);
    raw(out, ",\"points\":[");
    for (k, c) in crate::record::rrd::view3d::square(point, normal, half)
        .iter()
        .enumerate()
    {
        if k > 0 {
            raw(out, ",");
        }
        point3(out, *c);
    }
    raw(out, "],\"color\":");
    colour(out, RIGID_FILL);
    raw(out, ",\"colors\":[],\"indices\":[0,1,2,0,2,3]}");
}

/// The rotation `(x, y, z, w)` that turns `+z` onto the unit vector `axis` (about
/// `z × axis`).
fn z_onto(axis: [f64; 3]) -> [f64; 4] {
    let len = axis.iter().map(|x| x * x).sum::<f64>().sqrt().max(f64::MIN_POSITIVE);
    let a = axis.map(|x| x / len);
    let sin = a[0].hypot(a[1]);
    let about = if sin > 1e-12 {
        [-a[1] / sin, a[0] / sin, 0.0]
    } else {
        [1.0, 0.0, 0.0]
    };
    let half = 0.5 * sin.atan2(a[2]);
    [about[0] * half.sin(), about[1] * half.sin(), 0.0, half.cos()]
}

fn quaternion(out: &mut Vec<u8>, q: [f64; 4]) {
    raw(out, "{\"x\":");
    real32(out, q[0]);
    raw(out, ",\"y\":");
    real32(out, q[1]);
    raw(out, ",\"z\":");
    real32(out, q[2]);
    raw(out, ",\"w\":");
    real32(out, q[3]);
    raw(out, "}");
}

/// The corners of the bounding box of `x` (the origin for no nodes).
fn bounds(x: &[[f64; 3]]) -> ([f64; 3], [f64; 3]) {
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    for p in x {
        for c in 0..3 {
            lo[c] = lo[c].min(p[c]);
            hi[c] = hi[c].max(p[c]);
        }
    }
    if lo[0].is_finite() {
        (lo, hi)
    } else {
        ([0.0; 3], [0.0; 3])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rotate(q: [f64; 4], v: [f64; 3]) -> [f64; 3] {
        // v + 2 w (u × v) + 2 u × (u × v), u the vector part
        let u = [q[0], q[1], q[2]];
        let cross = |a: [f64; 3], b: [f64; 3]| {
            [
                a[1] * b[2] - a[2] * b[1],
                a[2] * b[0] - a[0] * b[2],
                a[0] * b[1] - a[1] * b[0],
            ]
        };
        let uv = cross(u, v);
        let uuv = cross(u, uv);
        std::array::from_fn(|c| v[c] + 2.0 * q[3] * uv[c] + 2.0 * uuv[c])
    }

    #[test]
    fn the_cylinder_rotation_turns_z_onto_the_axis() {
        for axis in [
            [0.0, 1.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 0.0, 1.0],
            [0.0, 0.0, -1.0],
            [0.3, -0.4, 0.5f64],
        ] {
            let len = (axis[0] * axis[0] + axis[1] * axis[1] + axis[2] * axis[2]).sqrt();
            let q = z_onto(axis);
            let turned = rotate(q, [0.0, 0.0, 1.0]);
            for c in 0..3 {
                assert!((turned[c] - axis[c] / len).abs() < 1e-12, "{axis:?}: {turned:?}");
            }
            let norm: f64 = q.iter().map(|x| x * x).sum();
            assert!((norm - 1.0).abs() < 1e-12);
        }
    }
}
