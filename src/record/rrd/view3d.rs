//! The rerun view of a 3D model (z up): the reference mesh's edges (static), the deformed
//! boundary as a shaded mesh with its edges, each rigid master (a plane as a square, a
//! sphere as an ellipsoid) moved by its offset, and per 3D contact pair the slave points
//! coloured by state with the tangential contact force as arrows (as long as
//! [`ARROW_FRACTION`] of the model at the Coulomb limit `μN`), and a text log of the
//! crossings of facet edges with the history carried across. Logged from records alone, so
//! a replay gives the same stream as the run.
//!
//! Entities: `/scene/model/{reference,deformed,edges}`, `/scene/rigid/PAIR`,
//! `/scene/contact/PAIR/{points,friction}`, `/events/crossings`.

use crate::contact::law::ContactState;
use crate::format::sig;
use crate::model::hex_boundary::boundary_quads;
use crate::record::messages::ModelRecord;
use crate::record::rrd::sink::RerunError;
use crate::record::rrd::style::{point_colour, ARROW_FRACTION, MESH, REFERENCE, RETURNED, RIGID};
use crate::record::surface_contact::{RigidShapeInfo, SurfacePairInfo, SurfacePointRecord};
use rerun::RecordingStream;

fn stream_err(e: impl std::fmt::Display) -> RerunError {
    RerunError::Stream(e.to_string())
}

fn f32s(p: [f64; 3]) -> [f32; 3] {
    p.map(|x| x as f32)
}

/// Colour of the deformed boundary's faces (the edges are [`MESH`]).
const FACES: [u8; 4] = [170, 195, 235, 255];

/// The 3D part of a rerun view.
pub struct SolidView {
    /// The edges of the boundary quadrilaterals, each once.
    edges: Vec<[usize; 2]>,
    /// The boundary's nodes (the deformed mesh's vertices; a recording may hold positions
    /// of these only) and its triangles over them.
    shown: Vec<usize>,
    triangles: Vec<[u32; 3]>,
    pairs: Vec<SurfacePairInfo>,
    /// Length of a friction arrow at the Coulomb limit; half-width of a rigid plane's square.
    arrow_len: f64,
    plane_half: f64,
}

impl SolidView {
    /// Log the static data: the reference mesh's edges and the rigid masters in their
    /// reference position.
    pub fn new(rec: &RecordingStream, model: &ModelRecord) -> Result<Self, RerunError> {
        let quads = boundary_quads(&model.hexahedra);
        let mut edges: Vec<[usize; 2]> = (quads.iter())
            .flat_map(|q| (0..4).map(move |k| sorted([q[k], q[(k + 1) % 4]])))
            .collect();
        edges.sort_unstable();
        edges.dedup();
        let size = model_size(&model.nodes_3d);
        let mut shown: Vec<usize> = quads.iter().flatten().copied().collect();
        shown.sort_unstable();
        shown.dedup();
        let local = |n: usize| shown.binary_search(&n).unwrap_or_default() as u32;
        let triangles = (quads.iter())
            .flat_map(|q| {
                let q = q.map(local);
                [[q[0], q[1], q[2]], [q[0], q[2], q[3]]]
            })
            .collect();
        let view = SolidView {
            edges,
            shown,
            triangles,
            pairs: model.surface_contacts.clone(),
            arrow_len: ARROW_FRACTION * size,
            plane_half: 0.75 * size,
        };
        rec.log_static("scene", &rerun::ViewCoordinates::RIGHT_HAND_Z_UP())
            .map_err(stream_err)?;
        rec.log_static(
            "scene/model/reference",
            &rerun::LineStrips3D::new(view.strips(&model.nodes_3d))
                .with_colors([REFERENCE])
                .with_radii([rerun::Radius::new_ui_points(0.5)]),
        )
        .map_err(stream_err)?;
        for p in &view.pairs {
            if let Some(shape) = &p.rigid {
                view.log_rigid_shape(rec, &p.name, shape)?;
            }
        }
        Ok(view)
    }

    fn strips(&self, x: &[[f64; 3]]) -> Vec<Vec<[f32; 3]>> {
        (self.edges.iter())
            .filter_map(|e| Some(vec![f32s(*x.get(e[0])?), f32s(*x.get(e[1])?)]))
            .collect()
    }

    fn log_rigid_shape(&self, rec: &RecordingStream, pair: &str, shape: &RigidShapeInfo) -> Result<(), RerunError> {
        let path = format!("scene/rigid/{pair}");
        match *shape {
            RigidShapeInfo::Sphere { centre, radius } => rec.log_static(
                path,
                &rerun::Ellipsoids3D::from_centers_and_radii([f32s(centre)], [radius as f32])
                    .with_colors([RIGID])
                    .with_fill_mode(rerun::FillMode::MajorWireframe),
            ),
            RigidShapeInfo::Cylinder { point, axis, radius } => {
                // rerun's cylinders stand along +z: turn z onto the axis
                let turn = [-axis[1], axis[0], 0.0];
                let sin = (turn[0] * turn[0] + turn[1] * turn[1]).sqrt();
                let about = if sin > 1e-12 {
                    [turn[0] / sin, turn[1] / sin, 0.0]
                } else {
                    [1.0, 0.0, 0.0]
                };
                let angle = sin.atan2(axis[2]);
                rec.log_static(
                    path,
                    &rerun::Cylinders3D::from_lengths_and_radii([2.0 * self.plane_half as f32], [radius as f32])
                        .with_centers([f32s(point)])
                        .with_rotation_axis_angles([rerun::RotationAxisAngle::new(
                            f32s(about),
                            rerun::Angle::from_radians(angle as f32),
                        )])
                        .with_colors([RIGID])
                        .with_fill_mode(rerun::FillMode::MajorWireframe),
                )
            }
            RigidShapeInfo::Plane { point, normal } => {
                let corners = square(point, normal, self.plane_half);
                rec.log_static(
                    path,
                    &rerun::Mesh3D::new(corners.map(f32s))
                        .with_triangle_indices([[0u32, 1, 2], [0, 2, 3]])
                        .with_albedo_factor(RIGID),
                )
            }
        }
        .map_err(stream_err)
    }

    /// The deformed boundary at node positions `x`.
    pub fn positions(&self, rec: &RecordingStream, x: &[[f64; 3]]) -> Result<(), RerunError> {
        let e = stream_err;
        if x.is_empty() {
            return Ok(());
        }
        let vertices: Vec<[f32; 3]> = self.shown.iter().filter_map(|&n| Some(f32s(*x.get(n)?))).collect();
        if vertices.len() != self.shown.len() {
            return Ok(());
        }
        rec.log(
            "scene/model/deformed",
            &rerun::Mesh3D::new(vertices)
                .with_triangle_indices(self.triangles.iter().copied())
                .with_albedo_factor(FACES),
        )
        .map_err(e)?;
        rec.log(
            "scene/model/edges",
            &rerun::LineStrips3D::new(self.strips(x))
                .with_colors([MESH])
                .with_radii([rerun::Radius::new_ui_points(0.75)]),
        )
        .map_err(e)
    }

    /// The 3D contact points of an increment, the rigid masters moved to `offsets` (one per
    /// pair), and a log line per crossing.
    pub fn contact(
        &self,
        rec: &RecordingStream,
        points: &[SurfacePointRecord],
        offsets: &[[f64; 3]],
    ) -> Result<(), RerunError> {
        let e = stream_err;
        for (ip, pair) in self.pairs.iter().enumerate() {
            if let (Some(_), Some(off)) = (&pair.rigid, offsets.get(ip)) {
                rec.log(
                    format!("scene/rigid/{}", pair.name),
                    &rerun::Transform3D::from_translation(f32s(*off)),
                )
                .map_err(e)?;
            }
            let pts: Vec<&SurfacePointRecord> = (points.iter())
                .filter(|p| p.pair == ip && p.position.iter().all(|x| x.is_finite()))
                .collect();
            let base = format!("scene/contact/{}", pair.name);
            rec.log(
                format!("{base}/points"),
                &rerun::Points3D::new(pts.iter().map(|p| f32s(p.position)))
                    .with_colors(pts.iter().map(|p| point_colour(p.state, pair.mu)))
                    .with_radii([rerun::Radius::new_ui_points(4.0)]),
            )
            .map_err(e)?;
            let arrows: Vec<([f32; 3], [f32; 3])> =
                pts.iter().filter_map(|p| self.friction_arrow(p, pair.mu)).collect();
            rec.log(
                format!("{base}/friction"),
                &rerun::Arrows3D::from_vectors(arrows.iter().map(|a| a.1))
                    .with_origins(arrows.iter().map(|a| a.0))
                    .with_colors([RETURNED])
                    .with_radii([rerun::Radius::new_ui_points(1.5)]),
            )
            .map_err(e)?;
            for p in pts.iter().filter(|p| p.crossing) {
                rec.log(
                    "events/crossings",
                    &rerun::TextLog::new(crossing_text(p)).with_level(rerun::TextLogLevel::INFO),
                )
                .map_err(e)?;
            }
        }
        Ok(())
    }

    /// The tangential part of the force a closed point receives, from its position, scaled
    /// so that the Coulomb limit `μN` is [`Self::arrow_len`] long (`N` itself without
    /// friction: then no arrow).
    fn friction_arrow(&self, p: &SurfacePointRecord, mu: f64) -> Option<([f32; 3], [f32; 3])> {
        let limit = mu * p.normal_force;
        let closed_with_friction = p.state != ContactState::Open && limit > 0.0;
        if !closed_with_friction || !p.normal.iter().all(|x| x.is_finite()) {
            return None;
        }
        let fn_ = (0..3).map(|c| p.force[c] * p.normal[c]).sum::<f64>();
        let ft: [f64; 3] = std::array::from_fn(|c| p.force[c] - fn_ * p.normal[c]);
        let scale = self.arrow_len / limit;
        Some((f32s(p.position), f32s(ft.map(|x| x * scale))))
    }
}

/// One line of the crossing log: the facets, and the history before and after transfer.
fn crossing_text(p: &SurfacePointRecord) -> String {
    let v = |x: [f64; 2]| format!("({}, {})", sig(x[0], 4), sig(x[1], 4));
    let from = p.previous_facet.map_or("?".into(), |f| f.to_string());
    let to = p.facet.map_or("?".into(), |f| f.to_string());
    let carried = match &p.carried {
        Some(c) => format!(
            ", ξ_A = {}, T_A = {} → ξ_B = {}, T_B = {} (carried)",
            v(c.xi_from),
            v(c.traction_from),
            v(c.xi_to),
            v(c.traction_to)
        ),
        None if p.history_lost => ", the friction history could not be carried (lost)".into(),
        None => String::new(),
    };
    format!(
        "crossing {}/node {}: facet {from} → {to}{carried}, returned T = {}",
        p.pair_name,
        p.node,
        v(p.traction)
    )
}

fn sorted(e: [usize; 2]) -> [usize; 2] {
    [e[0].min(e[1]), e[0].max(e[1])]
}

/// The diagonal of the bounding box of `x` (1 for no nodes).
pub fn model_size(x: &[[f64; 3]]) -> f64 {
    let (mut lo, mut hi) = ([f64::INFINITY; 3], [f64::NEG_INFINITY; 3]);
    for p in x {
        for c in 0..3 {
            lo[c] = lo[c].min(p[c]);
            hi[c] = hi[c].max(p[c]);
        }
    }
    let d = (0..3).map(|c| (hi[c] - lo[c]).powi(2)).sum::<f64>().sqrt();
    if d.is_finite() && d > 0.0 {
        d
    } else {
        1.0
    }
}

/// The corners of the square of half-width `half` about `point` in the plane of `normal`,
/// counter-clockwise seen from the side the normal points to.
pub fn square(point: [f64; 3], normal: [f64; 3], half: f64) -> [[f64; 3]; 4] {
    let len = normal.iter().map(|x| x * x).sum::<f64>().sqrt().max(f64::MIN_POSITIVE);
    let n = normal.map(|x| x / len);
    let helper = if n[0].abs() < 0.9 {
        [1.0, 0.0, 0.0]
    } else {
        [0.0, 1.0, 0.0]
    };
    let cross = |a: [f64; 3], b: [f64; 3]| {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    };
    let u = cross(helper, n);
    let ulen = u.iter().map(|x| x * x).sum::<f64>().sqrt();
    let u = u.map(|x| x / ulen);
    let v = cross(n, u);
    [(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
        .map(|(a, b)| std::array::from_fn(|c| point[c] + half * (a * u[c] + b * v[c])))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_plane_square_lies_in_the_plane_and_faces_its_normal() {
        let n = [0.0, 0.6, 0.8];
        let c = square([1.0, 2.0, 3.0], n, 2.0);
        for p in &c {
            let d: f64 = (0..3).map(|k| (p[k] - [1.0, 2.0, 3.0][k]) * n[k]).sum();
            assert!(d.abs() < 1e-12);
        }
        let (a, b) = (
            [0, 1, 2].map(|k| c[1][k] - c[0][k]),
            [0, 1, 2].map(|k| c[3][k] - c[0][k]),
        );
        let along = (a[1] * b[2] - a[2] * b[1]) * n[0]
            + (a[2] * b[0] - a[0] * b[2]) * n[1]
            + (a[0] * b[1] - a[1] * b[0]) * n[2];
        assert!((along - 16.0).abs() < 1e-12, "{along}");
    }
}
