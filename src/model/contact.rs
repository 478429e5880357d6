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
    /// How a deformable master face is interpolated between its nodes.
    pub smoothing: Smoothing,
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
}

impl TransferKind {
    pub fn name(self) -> &'static str {
        match self {
            TransferKind::Straightforward => "straightforward",
            TransferKind::Continuous => "continuous",
            TransferKind::PathLength => "path-length",
        }
    }
}
