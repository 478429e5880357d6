//! Format 3's `/positions`: node coordinates packed as byte-shuffled hexadecimal — of every
//! node or of the boundary nodes only, in double or single precision. The choice is the
//! user's ([`PositionsContent`]); it is recorded in `/model` (`positions_nodes`), in the
//! metadata (`positions_of`, `positions_precision`) and in each message (`of`, `precision`).

use super::messages::{ModelRecord, PositionsMessage};
use super::real::{Real, Real2s};
use schemars::JsonSchema;
use serde::{Deserialize, Serialize};

/// Which nodes `/positions` holds.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, JsonSchema, clap::ValueEnum)]
#[serde(rename_all = "kebab-case")]
pub enum PositionsOf {
    /// Every node (default)
    #[default]
    All,
    /// The nodes on the boundary of the mesh (edges of one element in 2D, faces of one
    /// hexahedron in 3D): what a view of the deformed body draws; interior nodes read as NaN
    Surface,
}

/// Precision of the coordinates in `/positions`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize, JsonSchema, clap::ValueEnum)]
#[serde(rename_all = "kebab-case")]
pub enum Precision {
    /// IEEE 754 doubles, bit for bit (default)
    #[default]
    Double,
    /// IEEE 754 singles: each coordinate rounded to the nearest single, a relative error of at
    /// most 2⁻²⁴ ≈ 6.0e-8 of its magnitude
    Single,
}

impl PositionsOf {
    pub fn name(self) -> &'static str {
        match self {
            PositionsOf::All => "all",
            PositionsOf::Surface => "surface",
        }
    }
}

impl Precision {
    pub fn name(self) -> &'static str {
        match self {
            Precision::Double => "double",
            Precision::Single => "single",
        }
    }

    /// Bytes (shuffled planes) per value.
    fn bytes(self) -> usize {
        match self {
            Precision::Double => 8,
            Precision::Single => 4,
        }
    }
}

/// What the writer keeps of the node positions.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct PositionsContent {
    /// The nodes written, in order (`None`: every node).
    pub nodes: Option<Vec<usize>>,
    pub precision: Precision,
}

impl PositionsContent {
    /// The content a choice gives for the model `record` (its boundary nodes for `surface`).
    pub fn of(record: &ModelRecord, of: PositionsOf, precision: Precision) -> Self {
        let nodes = (of == PositionsOf::Surface).then(|| record.surface_nodes());
        PositionsContent { nodes, precision }
    }

    /// Whether the positions of node `n` are written bit for bit (readers can restore what
    /// was left out from them).
    pub fn exact_for(&self, n: usize) -> bool {
        self.precision == Precision::Double && self.nodes.as_ref().is_none_or(|s| s.binary_search(&n).is_ok())
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
    /// Current coordinates `X + u` of the nodes written, bit for bit (NaN included): the
    /// values x₀ y₀ x₁ y₁ … (`dim` per node) as IEEE 754 doubles (singles where `precision`
    /// is `single`), byte-shuffled — 8 planes (4 for singles), plane k holding byte k
    /// (little-endian: k = 0 is the least significant) of every value — written as lowercase
    /// hexadecimal (base16). In Python:
    /// `numpy.frombuffer(bytes.fromhex(msg["nodes"]), numpy.uint8).reshape(8, -1).T.copy().view("<f8").reshape(-1, 2)`
    /// (`reshape(4, -1)` and `"<f4"` for singles).
    #[schemars(extend("contentEncoding" = "base16", "pattern" = "^([0-9a-f]{8})*$"))]
    pub nodes: String,
    /// Translation of each rigid body (same order as the model's `rigid`).
    #[schemars(with = "Vec<super::real::Real2>")]
    #[serde(with = "Real2s")]
    pub rigid_offsets: Vec<[f64; 2]>,
    /// Values per node in `nodes`: 3 for a 3D model (x₀ y₀ z₀ x₁ …; reshape to `(-1, 3)`);
    /// absent for 2.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub dim: Option<usize>,
    /// `surface`: `nodes` holds the nodes listed in `/model`'s `positions_nodes`, in that
    /// order (the boundary of the mesh); absent: every node.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub of: Option<PositionsOf>,
    /// `single`: the values are IEEE 754 singles (4 planes); absent: doubles (8 planes).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub precision: Option<Precision>,
}

const HEX: &[u8; 16] = b"0123456789abcdef";

/// Append the shuffled hexadecimal text of the coordinates `nodes` (see [`PackedPositions`]).
pub fn pack_nodes(out: &mut Vec<u8>, nodes: &[[f64; 2]]) {
    pack_values(out, nodes.as_flattened());
}

/// Append the shuffled hexadecimal text of the values `values` (see [`PackedPositions`]).
pub fn pack_values(out: &mut Vec<u8>, values: &[f64]) {
    pack_bits(out, values.len(), 8, |i| values[i].to_bits());
}

/// Append the shuffled hexadecimal text of `n` values of `bytes` bytes each, value `i` of
/// bits `bits(i)` (the low `bytes` bytes are written).
fn pack_bits(out: &mut Vec<u8>, n: usize, bytes: usize, bits: impl Fn(usize) -> u64) {
    let start = out.len();
    out.resize(start + 2 * bytes * n, 0);
    let rows = out[start..].chunks_exact_mut(2 * n.max(1));
    // one row per byte of the values, least significant first, written in place (no
    // capacity check per byte: the writer thread's cost, docs/performance.md)
    for (k, row) in rows.enumerate() {
        for (i, digits) in row.chunks_exact_mut(2).enumerate() {
            let b = (bits(i) >> (8 * k)) as u8;
            digits[0] = HEX[(b >> 4) as usize];
            digits[1] = HEX[(b & 15) as usize];
        }
    }
}

/// The flat coordinates of `p` and their dimension.
fn flat(p: &PositionsMessage) -> (&[f64], usize) {
    match p.nodes_3d.is_empty() {
        true => (p.nodes.as_flattened(), 2),
        false => (p.nodes_3d.as_flattened(), 3),
    }
}

/// Append the text of `p`'s coordinates kept by `content`.
fn pack_content(out: &mut Vec<u8>, p: &PositionsMessage, content: &PositionsContent) {
    let (values, dim) = flat(p);
    let value = |i: usize| match &content.nodes {
        Some(nodes) => values[dim * nodes[i / dim] + i % dim],
        None => values[i],
    };
    let n = content.nodes.as_ref().map_or(values.len(), |s| dim * s.len());
    match content.precision {
        Precision::Double => pack_bits(out, n, 8, |i| value(i).to_bits()),
        Precision::Single => pack_bits(out, n, 4, |i| u64::from((value(i) as f32).to_bits())),
    }
}

impl PackedPositions {
    /// `p` packed, every node in double precision.
    pub fn pack(p: &PositionsMessage) -> Self {
        let mut text = Vec::new();
        pack_content(&mut text, p, &PositionsContent::default());
        PackedPositions {
            increment: p.increment,
            t: p.t,
            nodes: String::from_utf8(text).unwrap_or_default(),
            rigid_offsets: p.rigid_offsets.clone(),
            dim: (!p.nodes_3d.is_empty()).then_some(3),
            of: None,
            precision: None,
        }
    }

    /// Append the JSON of `p` packed with `content` (for every node in double precision, the
    /// text of `serde_json::to_vec(&PackedPositions::pack(p))`, without the intermediate
    /// string).
    pub fn write_json(out: &mut Vec<u8>, p: &PositionsMessage, content: &PositionsContent) -> serde_json::Result<()> {
        use super::real::Item;
        out.extend_from_slice(b"{\"increment\":");
        serde_json::to_writer(&mut *out, &p.increment)?;
        out.extend_from_slice(b",\"t\":");
        serde_json::to_writer(&mut *out, &Item(p.t))?;
        out.extend_from_slice(b",\"nodes\":\"");
        pack_content(out, p, content);
        out.extend_from_slice(b"\",\"rigid_offsets\":");
        let mut ser = serde_json::Serializer::new(&mut *out);
        Real2s::serialize(&p.rigid_offsets, &mut ser)?;
        if !p.nodes_3d.is_empty() {
            out.extend_from_slice(b",\"dim\":3");
        }
        if content.nodes.is_some() {
            out.extend_from_slice(b",\"of\":\"surface\"");
        }
        if content.precision == Precision::Single {
            out.extend_from_slice(b",\"precision\":\"single\"");
        }
        out.push(b'}');
        Ok(())
    }

    /// The values of `nodes` (refused when the text is not the hexadecimal of whole nodes).
    fn values(&self) -> Result<Vec<f64>, String> {
        let err = |what: &str| format!("positions of increment {}: {what}", self.increment);
        let text = self.nodes.as_bytes();
        let dim = self.dim.unwrap_or(2);
        if dim != 2 && dim != 3 {
            return Err(err(&format!("dimension {dim}: neither 2 nor 3")));
        }
        let bytes = self.precision.unwrap_or_default().bytes();
        if !text.len().is_multiple_of(2 * bytes * dim) {
            return Err(err(&format!(
                "{} hexadecimal digits, not a whole number of nodes ({} each)",
                text.len(),
                2 * bytes * dim
            )));
        }
        let digit = |c: u8| match c {
            b'0'..=b'9' => Ok(c - b'0'),
            b'a'..=b'f' => Ok(c - b'a' + 10),
            _ => Err(err("not lowercase hexadecimal")),
        };
        let n = text.len() / (2 * bytes);
        let mut bits = vec![0u64; n];
        for (i, pair) in text.chunks_exact(2).enumerate() {
            let b = (digit(pair[0])? << 4) | digit(pair[1])?;
            bits[i % n] |= (b as u64) << (8 * (i / n));
        }
        Ok(match bytes {
            8 => bits.iter().map(|b| f64::from_bits(*b)).collect(),
            _ => bits.iter().map(|b| f64::from(f32::from_bits(*b as u32))).collect(),
        })
    }

    /// The positions of every node, unpacked (a message of every node).
    pub fn unpack(&self) -> Result<PositionsMessage, String> {
        self.unpack_onto(None)
    }

    /// The positions of every node of `model`: a message of the boundary nodes only
    /// (`of: surface`) puts its values at `model.positions_nodes` and NaN at the other nodes.
    pub fn unpack_for(&self, model: &ModelRecord) -> Result<PositionsMessage, String> {
        match self.of {
            Some(PositionsOf::Surface) => {
                let total = model.nodes.len().max(model.nodes_3d.len());
                self.unpack_onto(Some((&model.positions_nodes, total)))
            }
            _ => self.unpack(),
        }
    }

    /// Unpacked; with `subset` (the nodes written, the model's node count) spread over every node.
    fn unpack_onto(&self, subset: Option<(&[usize], usize)>) -> Result<PositionsMessage, String> {
        let mut values = self.values()?;
        let dim = self.dim.unwrap_or(2);
        if let Some((nodes, total)) = subset {
            if values.len() != dim * nodes.len() || nodes.iter().any(|&n| n >= total) {
                return Err(format!(
                    "positions of increment {}: {} nodes of the surface, but /model lists {} of its {total} nodes",
                    self.increment,
                    values.len() / dim,
                    nodes.len()
                ));
            }
            let mut all = vec![f64::NAN; dim * total];
            for (k, &n) in nodes.iter().enumerate() {
                all[dim * n..dim * n + dim].copy_from_slice(&values[dim * k..dim * k + dim]);
            }
            values = all;
        }
        let (nodes, nodes_3d) = match dim {
            3 => (Vec::new(), values.as_chunks::<3>().0.to_vec()),
            _ => (values.as_chunks::<2>().0.to_vec(), Vec::new()),
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

#[cfg(test)]
#[path = "packed_positions_tests.rs"]
mod tests;
