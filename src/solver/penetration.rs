//! Penetration against the size of the elements it happens in: a penalty too soft for the
//! load it carries.
//!
//! A penalty contact lets the bodies overlap by `N/ε_N`. Where that overlap reaches a good
//! part of an element, the contact is no longer the one the scene meant: the forces are
//! those of a softer interface (a cylinder pressed into a block with `ε_N = 0.1 E` carried
//! half the force of the converged answer while its friction ratio was still right), and
//! nothing else in the run says so. At every converged increment the deepest closed point
//! is compared with the smallest element edge at its slave node (for a rigid slave point,
//! with the length of the master segment it presses on; a 3D point with the smallest
//! hexahedron edge at its slave node); beyond
//! [`DEEP_PENETRATION`] the run warns once, naming the pair, the point and the remedy.

use crate::contact::law::ContactState;
use crate::model::dim::HEX8_EDGES;
use crate::model::{Model, Slave, Solid};
use crate::record::surface_contact::SurfacePointRecord;
use crate::record::ContactPointRecord;

/// Penetration, as a share of the local element size, beyond which a run warns.
pub const DEEP_PENETRATION: f64 = 0.1;

/// The smallest element edge at each node (infinite at a node of no element).
pub fn node_sizes(model: &Model) -> Vec<f64> {
    model.smallest_edge_at_nodes()
}

/// The deepest penetration of an increment, relative to the local element size.
#[derive(Debug, Clone, PartialEq)]
pub struct Penetration {
    pub pair: String,
    pub slave: String,
    pub depth: f64,
    /// `depth` over the local element size.
    pub ratio: f64,
}

/// The closed point whose penetration is the largest share of its local element size.
pub fn deepest(model: &Model, sizes: &[f64], points: &[ContactPointRecord]) -> Option<Penetration> {
    let mut worst: Option<Penetration> = None;
    for p in points
        .iter()
        .filter(|p| p.state != crate::contact::law::ContactState::Open)
    {
        let depth = -p.gap;
        if depth.is_nan() || depth <= 0.0 {
            continue;
        }
        let size = match model.contacts[p.pair].slaves[p.slave] {
            Slave::Node(n) => sizes[n],
            _ => segment_length(model, p),
        };
        let ratio = depth / size;
        if ratio.is_finite() && worst.as_ref().is_none_or(|w| ratio > w.ratio) {
            worst = Some(Penetration {
                pair: p.pair_name.to_string(),
                slave: p.slave_label.to_string(),
                depth,
                ratio,
            });
        }
    }
    worst
}

/// The smallest hexahedron edge at each node of a 3D model (infinite at a node of no element).
pub fn solid_node_sizes(model: &Model<Solid>) -> Vec<f64> {
    let mut h = vec![f64::INFINITY; model.nodes.len()];
    for e in &model.elements {
        for [a, b] in HEX8_EDGES.map(|[i, j]| [e.nodes[i], e.nodes[j]]) {
            let (p, q) = (model.nodes[a], model.nodes[b]);
            let l = (0..3).map(|c| (p[c] - q[c]).powi(2)).sum::<f64>().sqrt();
            h[a] = h[a].min(l);
            h[b] = h[b].min(l);
        }
    }
    h
}

/// The closed 3D point whose penetration is the largest share of the smallest element edge
/// at its slave node (`sizes` of [`solid_node_sizes`]).
pub fn deepest_surface(sizes: &[f64], points: &[SurfacePointRecord]) -> Option<Penetration> {
    let mut worst: Option<Penetration> = None;
    for p in points.iter().filter(|p| p.state != ContactState::Open) {
        let depth = -p.gap;
        let ratio = depth / sizes.get(p.node).copied().unwrap_or(f64::INFINITY);
        if depth > 0.0 && ratio.is_finite() && worst.as_ref().is_none_or(|w| ratio > w.ratio) {
            worst = Some(Penetration {
                pair: p.pair_name.clone(),
                slave: format!("node {}", p.node),
                depth,
                ratio,
            });
        }
    }
    worst
}

/// The length of the deformable master segment a rigid slave point presses on (infinite
/// when the master is rigid too).
fn segment_length(model: &Model, p: &ContactPointRecord) -> f64 {
    match (&model.contacts[p.pair].master, p.segment) {
        (crate::model::Master::Face { segments, .. }, Some(s)) => {
            let [a, b] = segments[s];
            let (x, y) = (model.nodes[a], model.nodes[b]);
            (x[0] - y[0]).hypot(x[1] - y[1])
        }
        _ => f64::INFINITY,
    }
}

/// The warning of a penetration beyond [`DEEP_PENETRATION`].
pub fn warning(p: &Penetration) -> String {
    format!(
        "contact `{}`: {} penetrates its master by {:.3e}, {:.0} % of the element size there: the penalty is soft for this load and the contact forces are those of a softer interface (raise eps_n, or set enforcement = \"augmented\")",
        p.pair,
        p.slave,
        p.depth,
        100.0 * p.ratio
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn node_sizes_are_the_smallest_edge_at_each_node() {
        let m = crate::load_scene("block-slide", &[]).unwrap().1.model;
        let h = node_sizes(&m);
        assert!(h.iter().all(|v| v.is_finite() && *v > 0.0));
        let e = &m.elements[0];
        let (p, q) = (m.nodes[e.nodes[0]], m.nodes[e.nodes[1]]);
        assert!(h[e.nodes[0]] <= (p[0] - q[0]).hypot(p[1] - q[1]) + 1e-15);
    }
}
