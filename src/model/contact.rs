//! How the model describes contact: pairs of slave points and master surfaces, the contact
//! law and the history-transfer scheme of each pair. Plain data; the kernels that act on it
//! are in [`crate::contact`].

use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// A contact slave: a node of a deformable body, a rigid point, or a vertex of a rigid
/// outline (`(body, vertex)`, the vertex being the polyline's point index).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Slave {
    Node(usize),
    RigidPoint(usize),
    RigidVertex(usize, usize),
}

/// A vertex of a rigid master outline that is itself the slave point of another pair (the
/// corner of a block against a deformable face): that pair owns the vertex region (see
/// [`crate::contact::pairing`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct OwnedVertex {
    /// Point index of the vertex in the outline (between pieces `vertex − 1` and `vertex`).
    pub vertex: usize,
    /// Index of the owning pair in [`Model::contacts`] …
    pub owner: usize,
    /// … and of the vertex among that pair's slaves.
    pub slave: usize,
}

/// A contact master surface.
#[derive(Debug, Clone)]
pub enum Master {
    /// A face of a deformable body: linear segments `[a, b]` with their neighbours.
    Face {
        body: usize,
        segments: Vec<[usize; 2]>,
        prev: Vec<Option<usize>>,
        next: Vec<Option<usize>>,
    },
    /// A rigid surface (index into [`Model::rigid`]); piece `k` neighbours `k ± 1`.
    Rigid {
        body: usize,
        prev: Vec<Option<usize>>,
        next: Vec<Option<usize>>,
    },
}

impl Master {
    pub fn segment_count(&self) -> usize {
        match self {
            Master::Face { segments, .. } => segments.len(),
            Master::Rigid { prev, .. } => prev.len(),
        }
    }
    pub fn neighbours(&self, seg: usize) -> (Option<usize>, Option<usize>) {
        match self {
            Master::Face { prev, next, .. } | Master::Rigid { prev, next, .. } => (prev[seg], next[seg]),
        }
    }
}

/// The name of a two-pass pair's second pass is its first pass's name followed by this
/// (`NAME/second-pass`): the nodes of the first pass's master face against the face of its
/// slave nodes (`scene::build_pairs::second_pass`; combined with the first pass into one
/// interface by `record::interface`).
pub const SECOND_PASS_SUFFIX: &str = "/second-pass";

/// A node-to-segment contact pair.
#[derive(Debug, Clone)]
pub struct ContactPair {
    pub name: String,
    pub slaves: Vec<Slave>,
    pub master: Master,
    pub law: ContactLaw,
    pub transfer: TransferKind,
    /// Slaves farther than this from a segment are not searched against it.
    pub search_radius: f64,
    /// Vertices of a rigid master outline owned by another pair's slave.
    pub owned_vertices: Vec<OwnedVertex>,
    /// How a deformable master face is interpolated between its nodes. For a rigid master
    /// (whose pieces are exact curves) it is the smoothing of the face its implied vertex
    /// pair presses on (see [`ContactPair::face_smoothing`]).
    pub smoothing: Smoothing,
    /// Penalty, or augmented Lagrangian (Uzawa updates at converged increments).
    pub enforcement: Enforcement,
    /// Per slave: the weight `w` of its contact forces, the measure of the point in the
    /// body's model (`t` in plane stress, `2π r̄` in the axisymmetric setting: see
    /// `scene::body_model::contact_weights`); the point's law is `law` with `ε_N`, `ε_T`
    /// times `w` ([`ContactPair::law_of`]). Empty: 1 for every slave (plane strain).
    pub weights: Vec<f64>,
}

impl ContactPair {
    /// The weight of slave `is`'s contact forces (1 where [`ContactPair::weights`] is empty).
    pub fn weight(&self, is: usize) -> f64 {
        self.weights.get(is).copied().unwrap_or(1.0)
    }

    /// The law of slave `is`: the penalties times its weight (its forces are those of a
    /// plane-strain point times `w`; the friction coefficient is the pair's). The pair's own
    /// law where the weights are all 1 (bit for bit).
    pub fn law_of(&self, is: usize) -> ContactLaw {
        match self.weights.get(is) {
            None => self.law,
            Some(w) => ContactLaw {
                eps_n: self.law.eps_n * w,
                eps_t: self.law.eps_t * w,
                mu: self.law.mu,
            },
        }
    }

    /// The interpolation of this pair's own master: its smoothing for a deformable face,
    /// [`Smoothing::None`] for a rigid outline (its kinks are real vertices).
    pub fn face_smoothing(&self) -> Smoothing {
        match self.master {
            Master::Face { .. } => self.smoothing,
            Master::Rigid { .. } => Smoothing::None,
        }
    }
}

/// How a pair enforces its contact constraints.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum Enforcement {
    /// Penalty regularisation: forces `ε_N ⟨−ζ⟩` and the penalised stick, errors of order
    /// force / ε.
    #[default]
    Penalty,
    /// Augmented Lagrangian by Uzawa updates at converged increments (Wriggers 2006, §6.4;
    /// Laursen & Simo 1993 for friction): the increment is solved again with the updated
    /// multipliers until their largest change, relative to the pair's largest normal force,
    /// is at most `tol`, at most `max` times (`contact::augmented`).
    Augmented { tol: f64, max: usize },
}

impl Enforcement {
    pub fn name(self) -> &'static str {
        match self {
            Enforcement::Penalty => "penalty",
            Enforcement::Augmented { .. } => "augmented",
        }
    }
}

/// Interpolation of a deformable master face (rigid masters are exact curves).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "kebab-case")]
pub enum Smoothing {
    /// Straight segments between the nodes (faceted; the normal jumps at each node).
    #[default]
    None,
    /// C1 cubic Hermite segments through the nodes, tangents from the neighbours
    /// (`contact::surface::hermite`; Wriggers, Krstulovic-Opara & Korelc 2001).
    Hermite,
    /// C1 quadratic Bézier arcs between the midpoints of neighbouring segments with the node
    /// as middle control point (`contact::surface::bezier`; the uniform quadratic B-spline of
    /// the nodes): it cuts the face's corners instead of passing through the nodes.
    Bezier,
    /// 3D faces only: each facet bent into a quadratic (Nagata) patch through its nodes,
    /// its edges curved by the area-weighted nodal normals (`contact3d::nagata`; Nagata 2005).
    Nagata,
}

impl Smoothing {
    pub fn name(self) -> &'static str {
        match self {
            Smoothing::None => "none",
            Smoothing::Hermite => "hermite",
            Smoothing::Bezier => "bezier",
            Smoothing::Nagata => "nagata",
        }
    }
}

/// Penalty and friction parameters of a contact pair.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct ContactLaw {
    /// Normal penalty `ε_N` (force per unit penetration at a point).
    pub eps_n: f64,
    /// Tangential (stick) penalty `ε_T` (force per unit tangential displacement).
    pub eps_t: f64,
    /// Coulomb coefficient `μ` (0 = frictionless).
    pub mu: f64,
}

/// The transfer scheme of a contact pair.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize, JsonSchema)]
#[serde(rename_all = "kebab-case")]
pub enum TransferKind {
    /// Seed eq. (1) with `Δξ = ξ_B − ξ_A` taken across segments as is.
    Straightforward,
    /// Seed eqs. (2)–(4): parallel translation in the current configuration.
    Continuous,
    /// Wriggers, Krstulovic-Opara & Korelc, IJNME 51 (2001): slip as arc length.
    PathLength,
    /// Puso & Laursen, IJNME 54 (2002): the convective increment from the stored spatial
    /// position of the slave point projected on the current segment (no segment history).
    Spatial,
}

impl TransferKind {
    pub fn name(self) -> &'static str {
        match self {
            TransferKind::Straightforward => "straightforward",
            TransferKind::Continuous => "continuous",
            TransferKind::PathLength => "path-length",
            TransferKind::Spatial => "spatial",
        }
    }
}
