//! What a scene becomes: nodes, elements, materials, constraints, rigid geometry and contact
//! pairs, with everything resolved to indices. The model is immutable during a run.

pub mod box_mesh;
pub mod contact;
pub mod dim;
pub mod gmsh;
pub mod hex_boundary;
pub mod mesh;
pub mod ramp;
pub mod revolved_mesh;
pub mod rigid;
pub mod shell_mesh;
pub mod surface_contact;

use crate::element::material::Material;
pub use contact::{
    ContactLaw, ContactPair, Enforcement, Master, OwnedVertex, Slave, Smoothing, TransferKind, SECOND_PASS_SUFFIX,
};
pub use dim::{AnyModel, Dim, ModelRef, Plane, Solid, SolidKind};
pub use ramp::Ramp;
pub use rigid::{Piece, RigidBody, RigidShape};
use std::collections::BTreeMap;
pub use surface_contact::{RigidSurface, RigidSurfaceShape, SlaveMeasure, SurfaceMaster, SurfacePair};

/// One element: a quadrilateral in 2D, a hexahedron in 3D (nodes in the kernel's order).
#[derive(Debug, Clone)]
pub struct Element<S: Dim = Plane> {
    pub nodes: S::Cell,
    pub body: usize,
}

/// A deformable body: its nodes are `first_node .. first_node + node_count`.
#[derive(Debug, Clone)]
pub struct Body<S: Dim = Plane> {
    pub name: String,
    pub material: Material,
    pub kind: S::Kind,
    /// In 2D: plane strain, plane stress (with its thickness) or axisymmetric: the measure of
    /// every force on the body (per unit thickness, for the plate, or the total over the full
    /// circle; see [`crate::element::quad::Kinematics`]). Nothing in 3D.
    pub kinematics: S::Kinematics,
    pub first_node: usize,
    pub node_count: usize,
    /// Named node sets (global node ids).
    pub node_sets: BTreeMap<String, Vec<usize>>,
    /// Named boundary faces (global node ids): in 2D segments counter-clockwise around the
    /// body, in 3D quadrilaterals counter-clockwise seen from outside (outward normal).
    pub faces: BTreeMap<String, Vec<S::Face>>,
}

/// Prescribed value of one degree of freedom (`dof = D node + component`): `ramp(t)`, plus
/// the displacement of a rigid turn where the fix turns its nodes about an axis.
#[derive(Debug, Clone)]
pub struct Prescribed {
    pub dof: usize,
    pub ramp: Ramp,
    pub turn: Option<Turn>,
}

impl Prescribed {
    /// A DOF held at `ramp(t)`.
    pub fn along(dof: usize, ramp: Ramp) -> Self {
        Prescribed { dof, ramp, turn: None }
    }

    /// The prescribed displacement at time `t`.
    pub fn at(&self, t: f64) -> f64 {
        self.ramp.at(t) + self.turn.as_ref().map_or(0.0, |r| r.displacement(t))
    }

    /// Zero at every time (held in place).
    pub fn is_zero(&self) -> bool {
        self.ramp.is_zero() && self.turn.as_ref().is_none_or(|r| r.angle.is_zero())
    }
}

/// The rigid turn of one node about an axis (3D): the component `component` of
/// `R(θ(t)) a − a`, with `a` the node's arm from a point of the axis and `R` the rotation
/// by `θ` (radians, right-handed about the unit `axis`; Rodrigues' formula).
#[derive(Debug, Clone)]
pub struct Turn {
    /// `θ(t)` in radians.
    pub angle: Ramp,
    pub axis: [f64; 3],
    pub arm: [f64; 3],
    pub component: usize,
}

impl Turn {
    /// `[R(θ) a − a]_c = [(cos θ − 1)(a − k (k·a)) + sin θ (k × a)]_c`.
    pub fn displacement(&self, t: f64) -> f64 {
        use crate::contact3d::vec3::{cross, dot};
        let (k, a, c) = (self.axis, self.arm, self.component);
        let theta = self.angle.at(t);
        (theta.cos() - 1.0) * (a[c] - k[c] * dot(k, a)) + theta.sin() * cross(k, a)[c]
    }
}

/// Prescribed displacement of one node along a unit direction only (a skew support):
/// `u · n = v(t)` with `n = direction`, the component along `t = (−n_y, n_x)` free. The
/// assembler holds it by the classical transformation of the node's two DOFs into the frame
/// `(n, t)` ([`crate::assembly::skew`]); its reaction is the node's internal force along `n`.
#[derive(Debug, Clone)]
pub struct SkewPrescribed {
    pub node: usize,
    /// Unit vector `n` along which the displacement is prescribed.
    pub direction: [f64; 2],
    pub ramp: Ramp,
}

/// Dead nodal force on one degree of freedom.
#[derive(Debug, Clone)]
pub struct NodalLoad {
    pub dof: usize,
    pub ramp: Ramp,
}

/// What a monitor watches.
#[derive(Debug, Clone, PartialEq)]
pub enum MonitorTarget {
    /// A node set of a deformable body: the mean displacement of the set and the sum of the
    /// forces on it (reactions where prescribed, applied loads elsewhere).
    Nodes(Vec<usize>),
    /// A rigid body (index into [`Model::rigid`]): its prescribed travel (the motion law at
    /// `t`) and the sum of the contact forces it receives.
    Rigid(usize),
    /// A node set of a 3D body, turned about the axis along the monitor's component through
    /// `point`: the set's turn about it (radians) and the moment of its forces about it.
    Moment { nodes: Vec<usize>, point: [f64; 3] },
    /// A rigid surface of the 3D contact pairs (by name): its prescribed travel and the force
    /// its drive applies, the sum of the forces its contact points put on their slaves.
    RigidSurface(String),
}

/// One load–displacement monitor: a displacement and a force in one direction.
#[derive(Debug, Clone)]
pub struct Monitor {
    pub label: String,
    pub target: MonitorTarget,
    pub component: usize,
    /// `-1` to report displacement and force with flipped sign (e.g. a downward push).
    pub sign: f64,
    /// Multiplies the force only: from the modelled part to what is reported.
    pub force_scale: f64,
}

/// The resolved model, in 2D ([`Plane`], the default) or 3D ([`Solid`]). Rigid bodies,
/// contact pairs and skew supports are 2D only: empty in 3D.
#[derive(Debug, Clone)]
pub struct Model<S: Dim = Plane> {
    pub name: String,
    pub description: String,
    pub nodes: Vec<S::Point>,
    pub elements: Vec<Element<S>>,
    pub bodies: Vec<Body<S>>,
    pub prescribed: Vec<Prescribed>,
    /// Displacements prescribed along a direction (skew supports), at most one per node and
    /// on nodes without a [`Prescribed`] DOF.
    pub skew: Vec<SkewPrescribed>,
    pub loads: Vec<NodalLoad>,
    pub rigid: Vec<RigidBody>,
    pub contacts: Vec<ContactPair>,
    /// 3D contact pairs (node-to-surface; empty in 2D).
    pub surface_contacts: Vec<SurfacePair>,
    /// The load–displacement monitors, in scene order (the first is "the" monitor of
    /// summaries, plots and sweeps).
    pub monitors: Vec<Monitor>,
    /// What building the model changed that the scene did not say (slave nodes moved onto
    /// their master: [`crate::scene`]'s overclosure adjustment), one sentence each; a run
    /// logs them first.
    pub notes: Vec<String>,
}

impl<S: Dim> Default for Model<S> {
    fn default() -> Self {
        Model {
            name: String::new(),
            description: String::new(),
            nodes: Vec::new(),
            elements: Vec::new(),
            bodies: Vec::new(),
            prescribed: Vec::new(),
            skew: Vec::new(),
            loads: Vec::new(),
            rigid: Vec::new(),
            contacts: Vec::new(),
            surface_contacts: Vec::new(),
            monitors: Vec::new(),
            notes: Vec::new(),
        }
    }
}

impl<S: Dim> Model<S> {
    /// The smaller plane-strain modulus of the bodies that own `nodes` and of body `master`
    /// (infinite when none of them is deformable): the stiffness against which the contact
    /// Newton weighs a penalty ([`crate::contact::decision::weights`]).
    pub fn contact_stiffness(&self, nodes: impl IntoIterator<Item = usize>, master: Option<usize>) -> f64 {
        let body_of =
            |node: usize| (self.bodies.iter()).find(|b| (b.first_node..b.first_node + b.node_count).contains(&node));
        let slaves = nodes.into_iter().filter_map(body_of);
        let master = master.map(|b| &self.bodies[b]);
        (slaves.chain(master))
            .map(|b| b.material.plane_strain_modulus())
            .fold(f64::INFINITY, f64::min)
    }

    /// The first monitor, if any.
    pub fn monitor(&self) -> Option<&Monitor> {
        self.monitors.first()
    }

    /// `D` DOFs per node.
    pub fn dof_count(&self) -> usize {
        S::D * self.nodes.len()
    }

    /// The diagonal of the bounding box of the nodes (1 for a model without extent): the
    /// length scale of tolerances on positions.
    pub fn size(&self) -> f64 {
        let (mut lo, mut hi) = ([f64::MAX; 3], [f64::MIN; 3]);
        for x in &self.nodes {
            for c in 0..S::D {
                lo[c] = lo[c].min(x.as_ref()[c]);
                hi[c] = hi[c].max(x.as_ref()[c]);
            }
        }
        let mut l = (hi[0] - lo[0]).hypot(hi[1] - lo[1]);
        if S::D == 3 {
            l = l.hypot(hi[2] - lo[2]);
        }
        if l.is_finite() && l > 0.0 {
            l
        } else {
            1.0
        }
    }

    /// The 2D view the contact layer works on ([`Dim::plane`]).
    pub fn plane(&self) -> &Model<Plane> {
        S::plane(self)
    }

    /// The model as observers take it.
    pub fn view(&self) -> ModelRef<'_> {
        S::model_ref(self)
    }

    /// `node N`, `rigid NAME` or `rigid NAME vertex K`.
    pub fn slave_label(&self, s: Slave) -> String {
        match s {
            Slave::Node(n) => format!("node {n}"),
            Slave::RigidPoint(r) => format!("rigid {}", self.rigid[r].name),
            Slave::RigidVertex(r, v) => format!("rigid {} vertex {v}", self.rigid[r].name),
        }
    }
}

impl Model {
    /// The smallest element edge at each node (infinite at a node of no element).
    pub fn smallest_edge_at_nodes(&self) -> Vec<f64> {
        let mut h = vec![f64::INFINITY; self.nodes.len()];
        for e in &self.elements {
            for i in 0..4 {
                let (a, b) = (e.nodes[i], e.nodes[(i + 1) % 4]);
                let (p, q) = (self.nodes[a], self.nodes[b]);
                let l = (p[0] - q[0]).hypot(p[1] - q[1]);
                h[a] = h[a].min(l);
                h[b] = h[b].min(l);
            }
        }
        h
    }

    /// The boundary edges of body `body` (edges of exactly one of its elements), oriented
    /// as in their element, i.e. with the body on their left like the faces.
    pub fn boundary_segments(&self, body: usize) -> Vec<[usize; 2]> {
        let quads: Vec<[usize; 4]> = (self.elements.iter())
            .filter(|e| e.body == body)
            .map(|e| [e.nodes[0], e.nodes[1], e.nodes[2], e.nodes[3]])
            .collect();
        quad_boundary_edges(&quads)
    }
}

/// The edges of a mesh of 4-node cells that belong to one cell only, each as that cell runs
/// it, in cell order.
pub fn quad_boundary_edges(quads: &[[usize; 4]]) -> Vec<[usize; 2]> {
    let edges = |q: &[usize; 4]| {
        let q = *q;
        (0..4).map(move |i| [q[i], q[(i + 1) % 4]])
    };
    let key = |[a, b]: [usize; 2]| [a.min(b), a.max(b)];
    let mut count = std::collections::HashMap::<[usize; 2], usize>::new();
    for e in quads.iter().flat_map(edges) {
        *count.entry(key(e)).or_default() += 1;
    }
    quads.iter().flat_map(edges).filter(|&e| count[&key(e)] == 1).collect()
}

/// Neighbour lists of a chain of segments (neighbours share an end node).
pub fn chain_neighbours(segments: &[[usize; 2]]) -> (Vec<Option<usize>>, Vec<Option<usize>>) {
    let n = segments.len();
    let starts: std::collections::HashMap<usize, usize> = segments.iter().enumerate().map(|(k, s)| (s[0], k)).collect();
    let mut prev = vec![None; n];
    let mut next = vec![None; n];
    for (k, s) in segments.iter().enumerate() {
        if let Some(&l) = starts.get(&s[1]) {
            if l != k {
                next[k] = Some(l);
                prev[l] = Some(k);
            }
        }
    }
    (prev, next)
}

#[cfg(test)]
mod turn_tests {
    use super::{Ramp, Turn};

    fn turned(axis: [f64; 3], arm: [f64; 3], degrees: f64) -> [f64; 3] {
        std::array::from_fn(|c| {
            let turn = Turn {
                angle: Ramp::linear(degrees.to_radians(), 1.0),
                axis,
                arm,
                component: c,
            };
            arm[c] + turn.displacement(1.0)
        })
    }

    #[test]
    fn a_quarter_turn_about_z_takes_x_to_y() {
        let x = turned([0.0, 0.0, 1.0], [2.0, 0.0, 0.5], 90.0);
        for (got, want) in x.iter().zip([0.0, 2.0, 0.5]) {
            assert!((got - want).abs() < 1e-15, "{x:?}");
        }
    }

    #[test]
    fn a_turn_about_a_skew_axis_keeps_length_and_axial_part() {
        let k = [1.0 / 3f64.sqrt(); 3];
        let a = [0.3, -1.2, 0.7];
        // a third of a turn about the cube diagonal permutes the axes
        let x = turned(k, a, 120.0);
        for (got, want) in x.iter().zip([a[2], a[0], a[1]]) {
            assert!((got - want).abs() < 1e-14, "{x:?}");
        }
        for degrees in [13.0, 97.0, 181.0, -45.0] {
            let x = turned(k, a, degrees);
            let dot = |u: [f64; 3], v: [f64; 3]| u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
            assert!((dot(x, x) - dot(a, a)).abs() < 1e-14);
            assert!((dot(x, k) - dot(a, k)).abs() < 1e-14);
        }
    }
}
