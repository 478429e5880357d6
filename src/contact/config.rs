//! The deformed configuration the contact evaluation works on: node positions (reference
//! plus displacement), rigid bodies at time `t`, and the geometry of master segments in it
//! (straight, smoothed, rigid pieces).

use super::geometry::SegmentGeom;
use crate::model::{ContactPair, Master, Model, RigidShape, Slave, Smoothing};

/// Node positions and time the contact evaluation works on.
pub struct Config<'a> {
    pub model: &'a Model,
    /// Full displacement vector (2 per node).
    pub u: &'a [f64],
    pub t: f64,
}

impl Config<'_> {
    pub(super) fn node(&self, n: usize) -> [f64; 2] {
        let x = self.model.nodes[n];
        [x[0] + self.u[2 * n], x[1] + self.u[2 * n + 1]]
    }

    /// Current position of node `n` about `origin`: `(X − origin) + u`, the difference of
    /// the reference positions first (exact for nearby points), then the displacement.
    pub(super) fn node_about(&self, n: usize, origin: [f64; 2]) -> [f64; 2] {
        let x = self.model.nodes[n];
        [
            (x[0] - origin[0]) + self.u[2 * n],
            (x[1] - origin[1]) + self.u[2 * n + 1],
        ]
    }

    /// The reference position of a slave point: the origin its contact kernel computes
    /// about (see [`super::system`]'s `local_problem`).
    pub(super) fn slave_origin(&self, s: Slave) -> [f64; 2] {
        match s {
            Slave::Node(n) => self.model.nodes[n],
            Slave::RigidPoint(r) => self.model.rigid[r].vertex(0).expect("validated by the scene builder"),
            Slave::RigidVertex(r, v) => self.model.rigid[r].vertex(v).expect("validated by the scene builder"),
        }
    }

    /// Current position of a rigid slave point about `origin` (its reference position
    /// minus the origin first, then the rigid body's travel).
    pub(super) fn slave_pos_about(&self, s: Slave, origin: [f64; 2]) -> [f64; 2] {
        let (r, v) = match s {
            Slave::Node(n) => return self.node_about(n, origin),
            Slave::RigidPoint(r) => (r, 0),
            Slave::RigidVertex(r, v) => (r, v),
        };
        let body = &self.model.rigid[r];
        let at = body.vertex(v).expect("validated by the scene builder");
        let o = body.offset(self.t);
        [(at[0] - origin[0]) + o[0], (at[1] - origin[1]) + o[1]]
    }

    /// Current position of a slave point.
    pub fn slave_pos(&self, s: Slave) -> [f64; 2] {
        let (r, v) = match s {
            Slave::Node(n) => return self.node(n),
            Slave::RigidPoint(r) => (r, 0),
            Slave::RigidVertex(r, v) => (r, v),
        };
        let body = &self.model.rigid[r];
        let at = body.vertex(v).expect("validated by the scene builder");
        let o = body.offset(self.t);
        [at[0] + o[0], at[1] + o[1]]
    }

    /// The global nodes (or the rigid piece) of segment `k` of a pair's master.
    pub(super) fn seg_nodes(&self, pair: &ContactPair, k: usize) -> SegNodes {
        match &pair.master {
            Master::Face {
                segments, prev, next, ..
            } => {
                let smooth = [
                    prev[k].map(|p| segments[p][0]),
                    Some(segments[k][0]),
                    Some(segments[k][1]),
                    next[k].map(|n| segments[n][1]),
                ];
                match pair.smoothing {
                    // (a 2D scene refuses `nagata`: a 3D face's patches)
                    Smoothing::None | Smoothing::Nagata => SegNodes::Linear(segments[k]),
                    Smoothing::Hermite => SegNodes::Smooth(Smoothing::Hermite, smooth),
                    Smoothing::Bezier => SegNodes::Smooth(Smoothing::Bezier, smooth),
                }
            }
            Master::Rigid { body, .. } => {
                let b = &self.model.rigid[*body];
                let RigidShape::Surface { pieces } = &b.shape else {
                    unreachable!("validated")
                };
                SegNodes::Rigid(pieces[k], b.offset(self.t))
            }
        }
    }

    /// Current geometry of segment `k` of a pair's master.
    pub fn segment(&self, pair: &ContactPair, k: usize) -> SegmentGeom<f64> {
        match self.seg_nodes(pair, k) {
            SegNodes::Linear([a, b]) => SegmentGeom::linear(self.node(a), self.node(b)),
            SegNodes::Smooth(kind, [p, a, b, n]) => {
                let (p, n) = (p.map(|p| self.node(p)), n.map(|n| self.node(n)));
                let (a, b) = (self.node(a.expect("segment end")), self.node(b.expect("segment end")));
                match kind {
                    Smoothing::Bezier => SegmentGeom::bezier(p, a, b, n),
                    _ => SegmentGeom::hermite(p, a, b, n),
                }
            }
            SegNodes::Rigid(p, o) => SegmentGeom::from_piece(&p, o),
        }
    }
}

/// Where a master segment's geometry comes from.
pub(super) enum SegNodes {
    Linear([usize; 2]),
    /// A smoothed segment: the neighbour before, the two ends, the neighbour after (global
    /// nodes).
    Smooth(Smoothing, [Option<usize>; 4]),
    Rigid(crate::model::Piece, [f64; 2]),
}
