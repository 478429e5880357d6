//! Message types of a recording that are not solver records themselves: the static model,
//! node positions, and the per-increment envelopes of contact points and crossings. Their
//! JSON Schemas sit in `schemas/` next to those of the solver records.

pub use super::packed_positions::{pack_nodes, pack_values, PackedPositions};
use super::real::{Real, Real2, Real2s};
use super::surface_contact::SurfacePairInfo;
use super::{ContactPointRecord, CrossingRecord};
use crate::model::{Master, Model, ModelRef, RigidShape, Solid};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// A deformable body of the mesh.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct BodyInfo {
    pub name: String,
    /// `q4` or `q4-eas`.
    pub element: String,
    /// Its nodes are `first_node .. first_node + node_count`.
    pub first_node: usize,
    pub node_count: usize,
    /// Named boundary faces as node pairs `[a, b]`, counter-clockwise around the body.
    pub faces: Vec<FaceInfo>,
    /// `plane-strain` (forces per unit thickness), `plane-stress` (forces for a plate of
    /// `thickness`) or `axisymmetric` (about `x = 0`; every force of the recording on this
    /// body — reactions, loads, contact forces, monitors — is the total over the full
    /// circle). Absent in older recordings: read as `plane-strain`.
    #[serde(default = "plane_strain")]
    pub model: String,
    /// The plate's thickness of a `plane-stress` body (absent otherwise).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub thickness: Option<f64>,
    /// Named boundary faces of a 3D body as quadrilaterals (absent in 2D).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub quad_faces: Vec<QuadFaceInfo>,
}

/// A named boundary face of a 3D body: quadrilaterals, counter-clockwise seen from outside.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct QuadFaceInfo {
    pub name: String,
    pub quads: Vec<[usize; 4]>,
}

fn plane_strain() -> String {
    "plane-strain".into()
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct FaceInfo {
    pub name: String,
    pub segments: Vec<[usize; 2]>,
}

/// A rigid body in its reference position: each piece drawn as a polyline (a point body
/// has one polyline of one point). Its motion is recorded with the node positions.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct RigidInfo {
    pub name: String,
    /// `point` or `surface`.
    pub kind: String,
    /// One polyline per piece (the segment ids of a rigid master are these piece indices).
    #[schemars(with = "Vec<Vec<Real2>>")]
    #[serde(with = "real_polylines")]
    pub pieces: Vec<Vec<[f64; 2]>>,
}

/// A contact pair: its slaves and master.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct PairInfo {
    pub name: String,
    /// `node N` or `rigid NAME`, in slave order.
    pub slaves: Vec<String>,
    /// `body NAME` or `rigid NAME`.
    pub master: String,
    /// Master segments of a deformable face as node pairs (empty for a rigid master).
    pub master_segments: Vec<[usize; 2]>,
    pub transfer: String,
    #[serde(with = "Real")]
    pub eps_n: f64,
    #[serde(with = "Real")]
    pub eps_t: f64,
    #[serde(with = "Real")]
    pub mu: f64,
}

/// The static model, written once at the start (channel `/model`).
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct ModelRecord {
    pub name: String,
    pub description: String,
    /// Reference coordinates of the nodes.
    #[schemars(with = "Vec<Real2>")]
    #[serde(with = "Real2s")]
    pub nodes: Vec<[f64; 2]>,
    /// Quadrilaterals: four node ids, counter-clockwise.
    pub elements: Vec<[usize; 4]>,
    /// Body index of each element.
    pub element_body: Vec<usize>,
    pub bodies: Vec<BodyInfo>,
    pub rigid: Vec<RigidInfo>,
    pub contacts: Vec<PairInfo>,
    /// Label of the first load–displacement monitor, if the scene has one.
    pub monitor: Option<String>,
    /// Labels of all monitors, in scene order (absent in older recordings: read as empty).
    #[serde(default)]
    pub monitors: Vec<String>,
    /// Final pseudo-time of the stepping.
    #[serde(with = "Real")]
    pub end: f64,
    /// The spatial dimension: 3 for a model of hexahedra (then `nodes` and `elements` are
    /// empty, the mesh is `nodes_3d` and `hexahedra`, `element_body` is per hexahedron, and
    /// the faces are quadrilaterals); absent for a 2D model.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub dim: Option<usize>,
    /// Reference coordinates of the nodes of a 3D model (x, y, z).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub nodes_3d: Vec<[f64; 3]>,
    /// Hexahedra of a 3D model: eight node ids in Gmsh/VTK order (`VTK_HEXAHEDRON`).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub hexahedra: Vec<[usize; 8]>,
    /// The 3D contact pairs (node-to-surface; absent in 2D): `/surface_contact` holds
    /// their points.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub surface_contacts: Vec<SurfacePairInfo>,
    /// The nodes `/positions` holds, in its order, where the recording keeps the boundary
    /// of the mesh only (`--positions-of surface`; absent: every node).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub positions_nodes: Vec<usize>,
}

impl ModelRecord {
    /// The record of a model of either dimension ([`Self::new`], [`Self::solid`]).
    pub fn of(model: ModelRef<'_>, end: f64) -> Self {
        match model {
            ModelRef::Plane(m) => Self::new(m, end),
            ModelRef::Solid(m) => Self::solid(m, end),
        }
    }

    /// The record of a 3D model: its nodes, hexahedra and bodies (faces as quadrilaterals,
    /// `element` the hexahedron's name, `model = "3d"`) and its node-to-surface pairs (rigid
    /// masters among them); no 2D rigid bodies or pairs.
    pub fn solid(model: &Model<Solid>, end: f64) -> Self {
        let bodies = (model.bodies.iter())
            .map(|b| BodyInfo {
                name: b.name.clone(),
                element: b.kind.name().into(),
                first_node: b.first_node,
                node_count: b.node_count,
                faces: Vec::new(),
                model: "3d".into(),
                thickness: None,
                quad_faces: (b.faces.iter())
                    .map(|(name, quads)| QuadFaceInfo {
                        name: name.clone(),
                        quads: quads.clone(),
                    })
                    .collect(),
            })
            .collect();
        ModelRecord {
            name: model.name.clone(),
            description: model.description.clone(),
            nodes: Vec::new(),
            elements: Vec::new(),
            element_body: model.elements.iter().map(|e| e.body).collect(),
            bodies,
            rigid: Vec::new(),
            contacts: Vec::new(),
            monitor: model.monitor().map(|m| m.label.clone()),
            monitors: model.monitors.iter().map(|m| m.label.clone()).collect(),
            end,
            dim: Some(3),
            nodes_3d: model.nodes.clone(),
            hexahedra: model.elements.iter().map(|e| e.nodes).collect(),
            surface_contacts: (model.surface_contacts.iter())
                .map(|p| SurfacePairInfo::of(model, p))
                .collect(),
            positions_nodes: Vec::new(),
        }
    }

    /// The spatial dimension (2 unless the record says 3).
    pub fn dim(&self) -> usize {
        self.dim.unwrap_or(2)
    }

    /// Nodes of the model in either dimension.
    pub fn node_count(&self) -> usize {
        self.nodes.len().max(self.nodes_3d.len())
    }

    /// The record of `model`, run to the pseudo-time `end`.
    pub fn new(model: &Model, end: f64) -> Self {
        let bodies = model
            .bodies
            .iter()
            .map(|b| BodyInfo {
                name: b.name.clone(),
                element: serde_json::to_value(b.kind)
                    .ok()
                    .and_then(|v| v.as_str().map(str::to_string))
                    .unwrap_or_default(),
                first_node: b.first_node,
                node_count: b.node_count,
                faces: b
                    .faces
                    .iter()
                    .map(|(name, segments)| FaceInfo {
                        name: name.clone(),
                        segments: segments.clone(),
                    })
                    .collect(),
                model: b.kinematics.name().into(),
                thickness: match b.kinematics {
                    crate::element::quad::Kinematics::PlaneStress { thickness } => Some(thickness),
                    _ => None,
                },
                quad_faces: Vec::new(),
            })
            .collect();
        let rigid = model
            .rigid
            .iter()
            .map(|r| match &r.shape {
                RigidShape::Point { at } => RigidInfo {
                    name: r.name.clone(),
                    kind: "point".into(),
                    pieces: vec![vec![*at]],
                },
                RigidShape::Surface { pieces } => RigidInfo {
                    name: r.name.clone(),
                    kind: "surface".into(),
                    pieces: pieces.iter().map(|p| p.polyline(24)).collect(),
                },
            })
            .collect();
        let contacts = model
            .contacts
            .iter()
            .map(|c| PairInfo {
                name: c.name.clone(),
                slaves: c.slaves.iter().map(|s| model.slave_label(*s)).collect(),
                master: match &c.master {
                    Master::Face { body, .. } => format!("body {}", model.bodies[*body].name),
                    Master::Rigid { body, .. } => format!("rigid {}", model.rigid[*body].name),
                },
                master_segments: match &c.master {
                    Master::Face { segments, .. } => segments.clone(),
                    Master::Rigid { .. } => Vec::new(),
                },
                transfer: c.transfer.name().to_string(),
                eps_n: c.law.eps_n,
                eps_t: c.law.eps_t,
                mu: c.law.mu,
            })
            .collect();
        ModelRecord {
            name: model.name.clone(),
            description: model.description.clone(),
            nodes: model.nodes.clone(),
            elements: model.elements.iter().map(|e| e.nodes).collect(),
            element_body: model.elements.iter().map(|e| e.body).collect(),
            bodies,
            rigid,
            contacts,
            monitor: model.monitor().map(|m| m.label.clone()),
            monitors: model.monitors.iter().map(|m| m.label.clone()).collect(),
            end,
            dim: None,
            nodes_3d: Vec::new(),
            hexahedra: Vec::new(),
            surface_contacts: Vec::new(),
            positions_nodes: Vec::new(),
        }
    }

    /// Labels of every monitor: `monitors`, or the single `monitor` of an older recording.
    pub fn monitor_labels(&self) -> Vec<String> {
        if self.monitors.is_empty() {
            self.monitor.iter().cloned().collect()
        } else {
            self.monitors.clone()
        }
    }

    /// Unique element edges (node pairs), in first-seen order.
    pub fn edges(&self) -> Vec<[usize; 2]> {
        let mut seen = std::collections::HashSet::new();
        let mut out = Vec::new();
        for e in &self.elements {
            for k in 0..4 {
                let (a, b) = (e[k], e[(k + 1) % 4]);
                if seen.insert((a.min(b), a.max(b))) {
                    out.push([a, b]);
                }
            }
        }
        out
    }

    /// The nodes on the boundary of the mesh, ascending: the ends of element edges met once
    /// (2D), the corners of hexahedron faces met once (3D), and any node of no element.
    pub fn surface_nodes(&self) -> Vec<usize> {
        let total = self.nodes.len().max(self.nodes_3d.len());
        let mut interior = vec![false; total];
        let boundary: Vec<usize> = match self.dim() {
            3 => {
                self.hexahedra.iter().flatten().for_each(|&n| interior[n] = true);
                crate::model::hex_boundary::boundary_quads(&self.hexahedra)
                    .into_iter()
                    .flatten()
                    .collect()
            }
            _ => {
                self.elements.iter().flatten().for_each(|&n| interior[n] = true);
                crate::model::quad_boundary_edges(&self.elements)
                    .into_iter()
                    .flatten()
                    .collect()
            }
        };
        boundary.into_iter().for_each(|n| interior[n] = false);
        (0..total).filter(|&n| !interior[n]).collect()
    }

    /// Same mesh and contact layout (what `diff` needs to align two recordings).
    pub fn same_layout(&self, other: &ModelRecord) -> bool {
        self.nodes.len() == other.nodes.len()
            && self.elements == other.elements
            && self.rigid.len() == other.rigid.len()
            && self.contacts.len() == other.contacts.len()
            && self
                .contacts
                .iter()
                .zip(&other.contacts)
                .all(|(a, b)| a.slaves == b.slaves && a.master == b.master)
            && self.nodes_3d.len() == other.nodes_3d.len()
            && self.hexahedra == other.hexahedra
            && self.surface_contacts.len() == other.surface_contacts.len()
            && (self.surface_contacts.iter().zip(&other.surface_contacts))
                .all(|(a, b)| a.slave_nodes == b.slave_nodes && a.master == b.master)
    }
}

/// A contact slave point at the end of a converged increment (channel `/contact` of formats
/// 1 and 2, read by this build; format 3 writes [`crate::record::mcap::arrays::ContactArrays`]): the
/// increment and load level, then the fields of the solver's contact-point record.
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
pub struct ContactPointMessage {
    pub increment: usize,
    #[serde(with = "Real")]
    pub t: f64,
    #[serde(flatten)]
    pub point: ContactPointRecord,
}

/// A crossing of a master-segment boundary in a converged increment (channel `/crossing`).
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
pub struct CrossingMessage {
    pub increment: usize,
    #[serde(with = "Real")]
    pub t: f64,
    #[serde(flatten)]
    pub crossing: CrossingRecord,
}

/// [`CrossingMessage`] as written: the same JSON, borrowing the solver's record.
#[derive(Serialize)]
pub(crate) struct CrossingMessageRef<'a> {
    pub increment: usize,
    #[serde(with = "Real")]
    pub t: f64,
    #[serde(flatten)]
    pub crossing: &'a CrossingRecord,
}

/// Current positions after a converged increment (channel `/positions` of formats 1 and 2,
/// and the in-memory form of format 3's [`PackedPositions`]; every increment, or every N-th
/// and the last one with `--positions-every N`).
#[derive(Debug, Clone, Serialize, Deserialize, JsonSchema)]
pub struct PositionsMessage {
    pub increment: usize,
    #[serde(with = "Real")]
    pub t: f64,
    /// Current coordinates `X + u` of every node.
    #[schemars(with = "Vec<Real2>")]
    #[serde(with = "Real2s")]
    pub nodes: Vec<[f64; 2]>,
    /// Translation of each rigid body (same order as the model's `rigid`).
    #[schemars(with = "Vec<Real2>")]
    #[serde(with = "Real2s")]
    pub rigid_offsets: Vec<[f64; 2]>,
    /// Current coordinates `X + u` of every node of a 3D model (then `nodes` is empty).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub nodes_3d: Vec<[f64; 3]>,
}

mod real_polylines {
    use serde::ser::SerializeSeq;
    use serde::{Deserialize, Deserializer, Serializer};

    use super::super::real::Real2s;

    struct L<'a>(&'a [[f64; 2]]);
    impl serde::Serialize for L<'_> {
        fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
            Real2s::serialize(self.0, s)
        }
    }
    #[derive(Deserialize)]
    struct D(#[serde(with = "Real2s")] Vec<[f64; 2]>);

    pub fn serialize<S: Serializer>(v: &[Vec<[f64; 2]>], s: S) -> Result<S::Ok, S::Error> {
        let mut seq = s.serialize_seq(Some(v.len()))?;
        for p in v {
            seq.serialize_element(&L(p))?;
        }
        seq.end()
    }
    pub fn deserialize<'de, De: Deserializer<'de>>(d: De) -> Result<Vec<Vec<[f64; 2]>>, De::Error> {
        let v: Vec<D> = Vec::deserialize(d)?;
        Ok(v.into_iter().map(|D(p)| p).collect())
    }
}

impl PositionsMessage {
    /// The positions of a model of either dimension (3D: `nodes_3d`, `nodes` empty).
    pub fn of(increment: usize, t: f64, model: ModelRef<'_>, u: &[f64]) -> Self {
        match model {
            ModelRef::Plane(m) => Self::new(increment, t, m, u),
            ModelRef::Solid(m) => PositionsMessage {
                increment,
                t,
                nodes: Vec::new(),
                rigid_offsets: Vec::new(),
                nodes_3d: (m.nodes.iter().enumerate())
                    .map(|(i, x)| std::array::from_fn(|c| x[c] + u[3 * i + c]))
                    .collect(),
            },
        }
    }

    pub fn new(increment: usize, t: f64, model: &Model, u: &[f64]) -> Self {
        PositionsMessage {
            increment,
            t,
            nodes: model
                .nodes
                .iter()
                .enumerate()
                .map(|(i, x)| [x[0] + u[2 * i], x[1] + u[2 * i + 1]])
                .collect(),
            rigid_offsets: model.rigid.iter().map(|r| r.offset(t)).collect(),
            nodes_3d: Vec::new(),
        }
    }
}
