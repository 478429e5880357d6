//! The `model` key of a body (plane strain, plane stress, axisymmetric) and what it implies
//! beyond the elements: the checks of a scene's models, the radial support of the nodes on
//! the axis, and the weights of the contact forces (per slave point).
//!
//! The elements (`element::quad_models`) compute, in each setting, the force of the 3D body
//! the mesh stands for: per unit thickness in plane strain, for a plate of thickness `t` in
//! plane stress, and the total over the full circle in the axisymmetric setting (volume
//! weight `2π R det J`). Every other force of the model is in the same measure: nodal loads
//! are totals as given, body loads and pressures are integrated with the setting's volume or
//! area measure, and contact forces are weighted per slave point ([`contact_weights`]).

use super::build::Ctx;
use super::types::{BodySpec, SceneFile};
use super::SceneError;
use crate::element::quad::Kinematics;
use crate::model::{Master, Model, Prescribed, Ramp, Slave};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// How a body's 2D mesh stands for the 3D body (the scene key `model`).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "kebab-case")]
pub enum BodyModel {
    /// `E33 = 0`: a long body; forces per unit thickness.
    #[default]
    PlaneStrain,
    /// `S33 = 0`: a thin plate of `thickness`; forces for the plate.
    PlaneStress,
    /// A body of revolution about `x = 0` (`x = r ≥ 0`, `y = z`); forces are totals over the
    /// full circle.
    Axisymmetric,
}

impl BodyModel {
    /// As the scene writes it.
    pub fn name(self) -> &'static str {
        match self {
            BodyModel::PlaneStrain => "plane-strain",
            BodyModel::PlaneStress => "plane-stress",
            BodyModel::Axisymmetric => "axisymmetric",
        }
    }
}

/// Nodes within this share of the body's size from `x = 0` are on the axis.
pub const AXIS_TOLERANCE: f64 = 1e-12;

/// The element setting of a body from its `model` and `thickness` keys: plane stress needs a
/// positive, finite thickness, and only plane stress takes one.
pub(super) fn kinematics(cx: &Ctx, b: &BodySpec) -> Result<Kinematics, SceneError> {
    let name = &b.name;
    match (b.model, b.thickness) {
        (BodyModel::PlaneStress, Some(t)) if t > 0.0 && t.is_finite() => Ok(Kinematics::PlaneStress { thickness: t }),
        (BodyModel::PlaneStress, Some(t)) => Err(cx.err(
            name,
            format!("body `{name}`: model = \"plane-stress\" with thickness = {t}: the thickness must be positive"),
            "give the plate's thickness, e.g. thickness = 0.01",
        )),
        (BodyModel::PlaneStress, None) => Err(cx.err(
            name,
            format!("body `{name}`: model = \"plane-stress\" needs the key `thickness`"),
            "add the plate's thickness to [[body]], e.g. thickness = 0.01",
        )),
        (model, Some(_)) => Err(cx.err(
            name,
            format!("body `{name}`: `thickness` is given, but the model is \"{}\"", model.name()),
            "remove `thickness` (plane strain is per unit thickness; an axisymmetric body is the full circle), or set model = \"plane-stress\"",
        )),
        (BodyModel::PlaneStrain, None) => Ok(Kinematics::PlaneStrain),
        (BodyModel::Axisymmetric, None) => Ok(Kinematics::Axisymmetric),
    }
}

/// The largest extent of a set of points (the body's size for the axis tolerance).
fn size(nodes: &[[f64; 2]]) -> f64 {
    let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
    for p in nodes {
        for c in 0..2 {
            lo[c] = lo[c].min(p[c]);
            hi[c] = hi[c].max(p[c]);
        }
    }
    (hi[0] - lo[0]).max(hi[1] - lo[1]).max(0.0)
}

/// An axisymmetric body's nodes must lie in `x = r ≥ 0` (within the axis tolerance; those
/// within it are put on the axis, `x = 0`, so that no element sees a negative radius).
pub(super) fn check_radii(cx: &Ctx, name: &str, nodes: &mut [[f64; 2]]) -> Result<(), SceneError> {
    let tol = AXIS_TOLERANCE * size(nodes);
    if let Some((n, p)) = nodes.iter().enumerate().find(|(_, p)| p[0] < -tol || p[0].is_nan()) {
        return Err(cx.err(
            name,
            format!(
                "body `{name}`: model = \"axisymmetric\" needs every node at x = r ≥ 0 (the axis of revolution is x = 0), but node {n} is at x = {}",
                p[0]
            ),
            "move the mesh (its `origin`) to x ≥ 0, or use model = \"plane-strain\"",
        ));
    }
    nodes.iter_mut().filter(|p| p[0] < 0.0).for_each(|p| p[0] = 0.0);
    Ok(())
}

/// A scene is axisymmetric in all its bodies or in none (a body of revolution and a planar
/// body cannot share a model).
pub(super) fn check_mixed(cx: &Ctx, s: &SceneFile) -> Result<(), SceneError> {
    let axi = |b: &&BodySpec| b.model == BodyModel::Axisymmetric;
    if let (Some(a), Some(p)) = (s.bodies.iter().find(axi), s.bodies.iter().find(|b| !axi(b))) {
        return Err(cx.err(
            &p.name,
            format!(
                "body `{}` is axisymmetric but body `{}` is {}: a scene is axisymmetric in all its bodies or in none",
                a.name,
                p.name,
                p.model.name()
            ),
            "give every [[body]] model = \"axisymmetric\", or none",
        ));
    }
    Ok(())
}

/// Hold `u_r = 0` at the nodes of axisymmetric bodies on the axis (`|x| ≤` [`AXIS_TOLERANCE`]
/// of the body's size): a point of the axis stays on it. Nodes whose `x` is already held at
/// zero keep their fix; one held elsewhere, or on a skew support, is refused. Adds one note
/// per body.
pub(super) fn fix_axis(cx: &Ctx, m: &mut Model, end: f64) -> Result<(), SceneError> {
    for bi in 0..m.bodies.len() {
        let b = &m.bodies[bi];
        if b.kinematics != Kinematics::Axisymmetric {
            continue;
        }
        let range = b.first_node..b.first_node + b.node_count;
        let tol = AXIS_TOLERANCE * size(&m.nodes[range.clone()]);
        let on_axis: Vec<usize> = range.filter(|&n| m.nodes[n][0].abs() <= tol).collect();
        let (mut added, mut kept) = (0, 0);
        for n in on_axis {
            let refuse = |what: &str| {
                cx.err(
                    &m.bodies[bi].name,
                    format!(
                        "body `{}`: node {n} is on the axis (r = 0) but {what}",
                        m.bodies[bi].name
                    ),
                    "a node on the axis of an axisymmetric body has u_r = 0, held automatically: remove its x fix",
                )
            };
            if m.skew.iter().any(|s| s.node == n) {
                return Err(refuse("has a skew support"));
            }
            match m.prescribed.iter().find(|p| p.dof == 2 * n) {
                Some(p) if p.is_zero() => kept += 1,
                Some(_) => return Err(refuse("its x displacement is prescribed to a non-zero value")),
                None => {
                    m.prescribed.push(Prescribed::along(2 * n, Ramp::linear(0.0, end)));
                    added += 1;
                }
            }
        }
        if added + kept > 0 {
            m.notes.push(format!(
                "body `{}` is axisymmetric: u_r = 0 held at its {} nodes on the axis (r = 0){}",
                m.bodies[bi].name,
                added + kept,
                if kept > 0 {
                    format!(", {kept} of them fixed in x by the scene already")
                } else {
                    String::new()
                }
            ));
        }
    }
    Ok(())
}

/// The body whose nodes include `node`.
fn body_of(m: &Model, node: usize) -> Option<usize> {
    (m.bodies.iter()).position(|b| (b.first_node..b.first_node + b.node_count).contains(&node))
}

/// Mean radius `r̄ = ∫ N r ds / ∫ N ds` of a slave node's tributary along the slave face:
/// over the boundary segments of its body that join it to another slave node of the pair
/// (reference configuration, `N` the segment's linear shape function of the node, `r` linear
/// along it: `∫ N_a r ds = L (r_a/3 + r_b/6)`, `∫ N_a ds = L/2`); the node's own radius
/// where no such segment exists (a lone slave node).
fn tributary_radius(m: &Model, node: usize, segments: &[[usize; 2]], slaves: &std::collections::HashSet<usize>) -> f64 {
    let (mut num, mut den) = (0.0, 0.0);
    for s in segments.iter().filter(|s| s.contains(&node)) {
        let other = if s[0] == node { s[1] } else { s[0] };
        if !slaves.contains(&other) {
            continue;
        }
        let (p, q) = (m.nodes[node], m.nodes[other]);
        let l = (p[0] - q[0]).hypot(p[1] - q[1]);
        num += l * (p[0] / 3.0 + q[0] / 6.0);
        den += l / 2.0;
    }
    if den > 0.0 {
        num / den
    } else {
        m.nodes[node][0]
    }
}

/// The weight `w` of each slave point's contact forces ([`crate::model::ContactPair::weights`]),
/// in the model of the body the point belongs to (a rigid point: of the master face's body).
///
/// The penalty `ε_N` of a pair is the force per unit penetration of one slave point per unit
/// thickness (plane strain). A point of a plate of thickness `t` carries `t` times that
/// (`w = t`). In the axisymmetric setting a slave node is a ring: a penalty traction
/// `ε_N g / l` per unit area on the ring's tributary area `A = 2π ∫ N r ds` gives the total
/// force `ε_N g · A / l` with `l = ∫ N ds` the tributary length, i.e. `w = 2π r̄`
/// ([`tributary_radius`]; `r̄ = r` at an interior node of a uniform face, `r̄ = h/3` at the
/// node on the axis with its neighbour at `h`). The weight is of the reference
/// configuration: the penalty potential `Σ w ½ ε_N ⟨−g⟩²` keeps a constant weight, so the
/// tangent stays the plane point's times `w` (no term from a changing radius; the current
/// ring area differs by the hoop strain `u_r/r`, a higher-order term in the penalty's own
/// error). A rigid vertex is a circle of its reference radius (`w = 2π x`).
///
/// Also refuses a pair between two deformable bodies of different models.
pub(super) fn contact_weights(cx: &Ctx, m: &mut Model) -> Result<(), SceneError> {
    for ip in 0..m.contacts.len() {
        let pair = &m.contacts[ip];
        let master_body = match pair.master {
            Master::Face { body, .. } => Some(body),
            Master::Rigid { .. } => None,
        };
        let slave_body = pair.slaves.iter().find_map(|s| match s {
            Slave::Node(n) => body_of(m, *n),
            _ => None,
        });
        if let (Some(a), Some(b)) = (slave_body, master_body) {
            let (ka, kb) = (m.bodies[a].kinematics, m.bodies[b].kinematics);
            if ka != kb {
                return Err(cx.err(
                    &pair.name,
                    format!(
                        "contact `{}`: its slave body `{}` is {} and its master body `{}` is {}",
                        pair.name,
                        m.bodies[a].name,
                        ka.label(),
                        m.bodies[b].name,
                        kb.label()
                    ),
                    "give both bodies the same model (and thickness)",
                ));
            }
        }
        let Some(body) = slave_body.or(master_body) else {
            continue;
        };
        let weights = match m.bodies[body].kinematics {
            Kinematics::PlaneStrain => continue,
            Kinematics::PlaneStress { thickness } => vec![thickness; pair.slaves.len()],
            Kinematics::Axisymmetric => {
                let segments = m.boundary_segments(body);
                // a rigid point on the axis is no ring: a vanishing weight (not zero, which
                // would leave its penalty zero and its force undefined)
                let tiny = 1e-9 * size(&m.nodes);
                let ring = |p: Option<[f64; 2]>| 2.0 * PI * p.map_or(0.0, |p| p[0].abs()).max(tiny);
                let nodes: std::collections::HashSet<usize> = (pair.slaves.iter())
                    .filter_map(|s| if let Slave::Node(n) = s { Some(*n) } else { None })
                    .collect();
                (pair.slaves.iter())
                    .map(|s| match *s {
                        Slave::Node(n) => 2.0 * PI * tributary_radius(m, n, &segments, &nodes).max(tiny),
                        Slave::RigidPoint(r) => ring(m.rigid[r].vertex(0)),
                        Slave::RigidVertex(r, v) => ring(m.rigid[r].vertex(v)),
                    })
                    .collect()
            }
        };
        m.contacts[ip].weights = weights;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tributary_radius_is_the_ring_centroid_of_the_shape_function() {
        let m = Model {
            nodes: vec![[0.0, 0.0], [1.0, 0.0], [2.0, 0.0], [3.5, 0.0]],
            ..Model::default()
        };
        let segs = [[0, 1], [1, 2], [2, 3]];
        let all: std::collections::HashSet<usize> = (0..4).collect();
        // the axis node: ∫ N r ds / ∫ N ds = (h²/6)/(h/2) = h/3
        assert!((tributary_radius(&m, 0, &segs, &all) - 1.0 / 3.0).abs() < 1e-15);
        // an interior node of a uniform face: its own radius
        assert!((tributary_radius(&m, 1, &segs, &all) - 1.0).abs() < 1e-15);
        // non-uniform: (1 (1/6 + 2/3) + 1.5 (2/3 + 3.5/6)) / 1.25
        let want = (1.0 * (1.0 / 6.0 + 2.0 / 3.0) + 1.5 * (2.0 / 3.0 + 3.5 / 6.0)) / 1.25;
        assert!((tributary_radius(&m, 2, &segs, &all) - want).abs() < 1e-14);
        // a node whose neighbours are no slaves keeps its own radius
        let one: std::collections::HashSet<usize> = [2].into_iter().collect();
        assert_eq!(tributary_radius(&m, 2, &segs, &one), 2.0);
    }
}
