//! Message types of a recording that are not solver records themselves: the static model,
//! node positions, and the per-increment envelopes of contact points and crossings. Their
//! JSON Schemas sit in `schemas/` next to those of the solver records.

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
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
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

/// Current positions after a converged increment (channel `/positions`, format 3): the node
/// coordinates packed as binary. They are the bulk of a recording of a large mesh; packed,
/// they cost the writer about half the CPU of JSON numbers (formatting and compressing) and
/// compress to fewer bytes (measured in `docs/recording.md`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, JsonSchema)]
pub struct PackedPositions {
    pub increment: usize,
    #[serde(with = "Real")]
    pub t: f64,
    /// Current coordinates `X + u` of every node, bit for bit (NaN included): the values
    /// x₀ y₀ x₁ y₁ … (2 per node) as IEEE 754 doubles, byte-shuffled — 8 planes, plane k
    /// holding byte k (little-endian: k = 0 is the least significant) of every value — written
    /// as lowercase hexadecimal (base16). In Python:
    /// `numpy.frombuffer(bytes.fromhex(msg["nodes"]), numpy.uint8).reshape(8, -1).T.copy().view("<f8").reshape(-1, 2)`.
    #[schemars(extend("contentEncoding" = "base16", "pattern" = "^([0-9a-f]{16})*$"))]
    pub nodes: String,
    /// Translation of each rigid body (same order as the model's `rigid`).
    #[schemars(with = "Vec<Real2>")]
    #[serde(with = "Real2s")]
    pub rigid_offsets: Vec<[f64; 2]>,
    /// Values per node in `nodes`: 3 for a 3D model (x₀ y₀ z₀ x₁ …; reshape to `(-1, 3)`);
    /// absent for 2.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub dim: Option<usize>,
}

const HEX: &[u8; 16] = b"0123456789abcdef";

/// Append the shuffled hexadecimal text of the coordinates `nodes` (see [`PackedPositions`]).
pub fn pack_nodes(out: &mut Vec<u8>, nodes: &[[f64; 2]]) {
    pack_values(out, nodes.as_flattened());
}

/// Append the shuffled hexadecimal text of the values `values` (see [`PackedPositions`]).
pub fn pack_values(out: &mut Vec<u8>, values: &[f64]) {
    let start = out.len();
    out.resize(start + 16 * values.len(), 0);
    let rows = out[start..].chunks_exact_mut(2 * values.len().max(1));
    // one row per byte of the doubles, least significant first, written in place (no
    // capacity check per byte: the writer thread's cost, docs/performance.md)
    for (k, row) in rows.enumerate() {
        for (digits, v) in row.chunks_exact_mut(2).zip(values) {
            let b = (v.to_bits() >> (8 * k)) as u8;
            digits[0] = HEX[(b >> 4) as usize];
            digits[1] = HEX[(b & 15) as usize];
        }
    }
}

impl PackedPositions {
    /// `p` packed.
    pub fn pack(p: &PositionsMessage) -> Self {
        let mut text = Vec::new();
        let dim = (!p.nodes_3d.is_empty()).then_some(3);
        match dim {
            Some(_) => pack_values(&mut text, p.nodes_3d.as_flattened()),
            None => pack_nodes(&mut text, &p.nodes),
        }
        PackedPositions {
            increment: p.increment,
            t: p.t,
            nodes: String::from_utf8(text).unwrap_or_default(),
            rigid_offsets: p.rigid_offsets.clone(),
            dim,
        }
    }

    /// Append the JSON of `p` packed (the text of `serde_json::to_vec(&PackedPositions::pack(p))`,
    /// without the intermediate string).
    pub fn write_json(out: &mut Vec<u8>, p: &PositionsMessage) -> serde_json::Result<()> {
        use super::real::Item;
        out.extend_from_slice(b"{\"increment\":");
        serde_json::to_writer(&mut *out, &p.increment)?;
        out.extend_from_slice(b",\"t\":");
        serde_json::to_writer(&mut *out, &Item(p.t))?;
        out.extend_from_slice(b",\"nodes\":\"");
        match p.nodes_3d.is_empty() {
            true => pack_nodes(out, &p.nodes),
            false => pack_values(out, p.nodes_3d.as_flattened()),
        }
        out.extend_from_slice(b"\",\"rigid_offsets\":");
        let mut ser = serde_json::Serializer::new(&mut *out);
        Real2s::serialize(&p.rigid_offsets, &mut ser)?;
        if !p.nodes_3d.is_empty() {
            out.extend_from_slice(b",\"dim\":3");
        }
        out.push(b'}');
        Ok(())
    }

    /// The positions unpacked (refused when the text is not the hexadecimal of whole nodes).
    pub fn unpack(&self) -> Result<PositionsMessage, String> {
        let err = |what: &str| format!("positions of increment {}: {what}", self.increment);
        let text = self.nodes.as_bytes();
        let dim = self.dim.unwrap_or(2);
        if dim != 2 && dim != 3 {
            return Err(err(&format!("dimension {dim}: neither 2 nor 3")));
        }
        if !text.len().is_multiple_of(16 * dim) {
            return Err(err(&format!(
                "{} hexadecimal digits, not a whole number of nodes ({} each)",
                text.len(),
                16 * dim
            )));
        }
        let digit = |c: u8| match c {
            b'0'..=b'9' => Ok(c - b'0'),
            b'a'..=b'f' => Ok(c - b'a' + 10),
            _ => Err(err("not lowercase hexadecimal")),
        };
        let n = text.len() / 16;
        let mut bits = vec![0u64; n];
        for (i, pair) in text.chunks_exact(2).enumerate() {
            let b = (digit(pair[0])? << 4) | digit(pair[1])?;
            bits[i % n] |= (b as u64) << (8 * (i / n));
        }
        let values = bits.iter().map(|b| f64::from_bits(*b));
        let (nodes, nodes_3d) = match dim {
            3 => (Vec::new(), values.collect::<Vec<f64>>().as_chunks::<3>().0.to_vec()),
            _ => (values.collect::<Vec<f64>>().as_chunks::<2>().0.to_vec(), Vec::new()),
        };
        Ok(PositionsMessage {
            increment: self.increment,
            t: self.t,
            nodes,
            rigid_offsets: self.rigid_offsets.clone(),
            nodes_3d,
        })
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn packed_positions_unpack_bit_for_bit() {
        let p = PositionsMessage {
            increment: 4,
            t: 0.5,
            nodes: vec![[1.0 / 3.0, -0.0], [f64::NAN, f64::INFINITY], [5e-324, -1e308]],
            rigid_offsets: vec![[0.0, -0.25]],
            nodes_3d: Vec::new(),
        };
        let text = serde_json::to_string(&PackedPositions::pack(&p)).unwrap();
        let mut direct = Vec::new();
        PackedPositions::write_json(&mut direct, &p).unwrap();
        assert_eq!(String::from_utf8(direct).unwrap(), text);
        let back: PackedPositions = serde_json::from_str(&text).unwrap();
        let q = back.unpack().unwrap();
        let bits = |m: &PositionsMessage| -> Vec<u64> { m.nodes.iter().flatten().map(|x| x.to_bits()).collect() };
        assert_eq!(bits(&p), bits(&q));
        assert_eq!((q.increment, q.t, q.rigid_offsets), (4, 0.5, vec![[0.0, -0.25]]));
        let mut bad = back.clone();
        bad.nodes.truncate(bad.nodes.len() - 4);
        assert!(bad.unpack().unwrap_err().contains("whole number of nodes"));
        bad.nodes = "0123456789ABCDEF0123456789abcdef".into();
        assert!(bad.unpack().unwrap_err().contains("hexadecimal"));
        // plane 7 (the most significant bytes) comes last: 1.0 is 3ff0000000000000
        let one = PackedPositions::pack(&PositionsMessage {
            nodes: vec![[1.0, 0.0]],
            ..p.clone()
        });
        assert_eq!(one.nodes, format!("{}f000{}3f00", "00".repeat(12), ""));
    }
}
