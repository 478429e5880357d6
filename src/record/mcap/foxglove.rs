//! Foxglove-native channels of a recording, beside contrail's own, so that a recording opened
//! in Foxglove (or Lichtblick) shows the log and the model without hand work:
//!
//! - `/foxglove/log` (`foxglove.Log`): every `/log` message, with its level;
//! - `/foxglove/reference` (`foxglove.SceneUpdate`, once, at the start): the reference mesh
//!   (element edges as a line list). Foxglove shows the last message of each topic before the
//!   time it seeks to, so a static entity needs only one message;
//! - `/foxglove/scene` (`foxglove.SceneUpdate`): the deformed mesh, the rigid surfaces (line
//!   segments, moved by their prescribed translation), the contact slave points within reach
//!   (spheres coloured by state: the colours of the rerun view) and a label with the increment
//!   and load level. The model lies in the plane z = 0, x right and y up as in the scene;
//!   coordinates are written in single precision (display data: the exact values are on
//!   `/positions` and `/contact`).
//!
//! The messages are JSON against the JSON Schemas of the `@foxglove/schemas` package
//! (`.ci/interop.sh` validates them); those schemas are embedded in the recording as they are
//! published ([`FOXGLOVE_LOG_SCHEMA`], [`FOXGLOVE_SCENE_SCHEMA`]).

use crate::contact::law::ContactState;
use crate::record::mcap::json_text::{colour, point3, raw, real32, string, time, uint, Xyz};
use crate::record::messages::ModelRecord;
use crate::record::rrd::style::{point_colour, MESH, REFERENCE, RIGID};
use crate::record::rrd::view::{bbox, clip};
use crate::record::{ContactPointRecord, LogLevel, LogRecord};

/// JSON Schema of `foxglove.Log` (from `@foxglove/schemas` 2.1.0, descriptions left out).
pub const FOXGLOVE_LOG_SCHEMA: &str = include_str!("../../../schemas/foxglove/foxglove.Log.json");
/// JSON Schema of `foxglove.SceneUpdate` (likewise).
pub const FOXGLOVE_SCENE_SCHEMA: &str = include_str!("../../../schemas/foxglove/foxglove.SceneUpdate.json");

/// Frame of every scene entity (Foxglove's 3D panel displays it when no other frame exists).
pub const FRAME: &str = "contrail";

/// Append a `foxglove.Log` message for `rec`, logged at `time_ns`.
pub fn log(out: &mut Vec<u8>, rec: &LogRecord, scene: &str, time_ns: u64) {
    let level = match rec.level {
        LogLevel::Info => 2,
        LogLevel::Warning => 3,
        LogLevel::Error => 4,
    };
    raw(out, "{\"timestamp\":");
    time(out, time_ns);
    raw(out, ",\"level\":");
    uint(out, level);
    raw(out, ",\"message\":");
    let text = format!("increment {} (t = {}): {}", rec.increment, rec.t, rec.message);
    string(out, &text);
    raw(out, ",\"name\":");
    string(out, &format!("contrail {scene}"));
    raw(out, ",\"file\":\"\",\"line\":0}");
}

/// A rigid body as drawn: its segments in the reference position (clipped to a window
/// around the mesh, as in the rerun view), or its points.
struct RigidShape {
    segments: Vec<[[f64; 2]; 2]>,
    points: Vec<[f64; 2]>,
}

/// Writes `foxglove.SceneUpdate` messages of one model (what does not change from one
/// increment to the next is worked out once).
pub struct SceneEncoder {
    /// The reference mesh entity's line primitive, as text.
    reference: Vec<u8>,
    /// `"indices":[…]` of the element edges (the deformed mesh's line list).
    indices: Vec<u8>,
    rigid: Vec<RigidShape>,
    /// Friction coefficient of each pair (teal points on frictionless pairs).
    mu: Vec<f64>,
    /// Diameter of a contact point's sphere and a rigid point's sphere.
    point_size: f64,
    /// Where the label goes (above the mesh's top left corner).
    label_at: [f64; 2],
}

pub(super) const POSE: &str =
    "{\"position\":{\"x\":0,\"y\":0,\"z\":0},\"orientation\":{\"x\":0,\"y\":0,\"z\":0,\"w\":1}}";

impl SceneEncoder {
    pub fn new(model: &ModelRecord) -> Self {
        let (lo, hi) = bbox(&model.nodes);
        let size = (hi[0] - lo[0]).max(hi[1] - lo[1]).max(1e-9);
        let edges = model.edges();
        let mut indices = Vec::new();
        raw(&mut indices, "\"indices\":[");
        for (k, e) in edges.iter().enumerate() {
            if k > 0 {
                raw(&mut indices, ",");
            }
            uint(&mut indices, e[0] as u64);
            raw(&mut indices, ",");
            uint(&mut indices, e[1] as u64);
        }
        raw(&mut indices, "]");
        let mut reference = Vec::new();
        line_list(&mut reference, &model.nodes, &indices, REFERENCE, 1.0);
        let window = [[lo[0] - size, lo[1] - size], [hi[0] + size, hi[1] + size]];
        let rigid = (model.rigid.iter())
            .map(|r| {
                if r.kind == "point" {
                    RigidShape {
                        segments: Vec::new(),
                        points: r.pieces.iter().flatten().copied().collect(),
                    }
                } else {
                    RigidShape {
                        segments: (r.pieces.iter())
                            .flat_map(|pl| pl.windows(2).filter_map(|w| clip(w[0], w[1], window)))
                            .map(|(a, b)| [a, b])
                            .collect(),
                        points: Vec::new(),
                    }
                }
            })
            .collect();
        SceneEncoder {
            reference,
            indices,
            rigid,
            mu: model.contacts.iter().map(|c| c.mu).collect(),
            point_size: 0.02 * size,
            label_at: [lo[0], hi[1] + 0.1 * size],
        }
    }

    /// Append the reference mesh (`/foxglove/reference`), logged at `time_ns`.
    pub fn write_reference(&self, out: &mut Vec<u8>, time_ns: u64) {
        raw(out, "{\"deletions\":[],\"entities\":[");
        entity(out, "reference mesh", time_ns, "[]");
        primitives(out, &[("lines", &self.reference)]);
        raw(out, "]}");
    }

    /// Append the scene at `increment` (load level `t`, logged at `time_ns`): current node
    /// coordinates `nodes`, rigid offsets, and the contact points of the increment.
    pub fn write(&self, out: &mut Vec<u8>, view: &SceneView, time_ns: u64) {
        raw(out, "{\"deletions\":[],\"entities\":[");
        let meta = format!(
            "[{{\"key\":\"increment\",\"value\":\"{}\"}},{{\"key\":\"t\",\"value\":\"{}\"}}]",
            view.increment, view.t
        );
        let entity = |out: &mut Vec<u8>, id: &str| entity(out, id, time_ns, &meta);
        // deformed mesh
        entity(out, "mesh");
        let mut lines = Vec::new();
        line_list(&mut lines, view.nodes, &self.indices, MESH, 1.5);
        primitives(out, &[("lines", &lines)]);
        // rigid bodies
        raw(out, ",");
        entity(out, "rigid");
        let (lines, spheres) = self.rigid_primitives(view.rigid_offsets);
        primitives(out, &[("lines", &lines), ("spheres", &spheres)]);
        // contact points within reach
        raw(out, ",");
        entity(out, "contact points");
        let spheres = self.contact_spheres(view.contact);
        primitives(out, &[("spheres", &spheres)]);
        // a label: increment and load level
        raw(out, ",");
        entity(out, "label");
        label(out, self.label_at, view.increment, view.t);
        raw(out, "]}");
    }

    fn rigid_primitives(&self, offsets: &[[f64; 2]]) -> (Vec<u8>, Vec<u8>) {
        let (mut lines, mut spheres) = (Vec::new(), Vec::new());
        for (r, off) in self.rigid.iter().zip(offsets) {
            let at = |p: [f64; 2]| [p[0] + off[0], p[1] + off[1]];
            if !r.segments.is_empty() {
                if !lines.is_empty() {
                    raw(&mut lines, ",");
                }
                raw(&mut lines, "{\"type\":2,\"pose\":");
                raw(&mut lines, POSE);
                raw(&mut lines, ",\"thickness\":3,\"scale_invariant\":true,\"points\":[");
                for (k, s) in r.segments.iter().enumerate() {
                    if k > 0 {
                        raw(&mut lines, ",");
                    }
                    point3(&mut lines, at(s[0]));
                    raw(&mut lines, ",");
                    point3(&mut lines, at(s[1]));
                }
                raw(&mut lines, "],\"color\":");
                colour(&mut lines, RIGID);
                raw(&mut lines, ",\"colors\":[],\"indices\":[]}");
            }
            for p in &r.points {
                sphere(&mut spheres, at(*p), 2.0 * self.point_size, RIGID);
            }
        }
        (lines, spheres)
    }

    fn contact_spheres(&self, contact: &[ScenePoint]) -> Vec<u8> {
        let mut out = Vec::new();
        // a point paired with a segment but without a projection has a NaN position
        for p in (contact.iter()).filter(|p| p.in_reach && p.position.iter().all(|x| x.is_finite())) {
            let mu = self.mu.get(p.pair).copied().unwrap_or(0.0);
            sphere(&mut out, p.position, self.point_size, point_colour(p.state, mu));
        }
        out
    }
}

/// A contact point as the scene draws it.
#[derive(Debug, Clone, Copy)]
pub struct ScenePoint<P = [f64; 2]> {
    pub pair: usize,
    pub position: P,
    pub state: ContactState,
    /// It has a master segment within reach (points out of reach are not drawn, nor points
    /// without a finite position).
    pub in_reach: bool,
}

impl ScenePoint {
    /// A point of a plane pair.
    pub fn of(p: &ContactPointRecord) -> Self {
        ScenePoint {
            pair: p.pair,
            position: p.position,
            state: p.state,
            in_reach: p.segment.is_some(),
        }
    }
}

impl ScenePoint<[f64; 3]> {
    /// A slave point of a 3D pair.
    pub fn of_surface(p: &crate::record::surface_contact::SurfacePointRecord) -> Self {
        ScenePoint {
            pair: p.pair,
            position: p.position,
            state: p.state,
            in_reach: p.facet.is_some(),
        }
    }
}

/// What one scene shows.
pub struct SceneView<'a> {
    pub increment: usize,
    pub t: f64,
    /// Current coordinates of every node.
    pub nodes: &'a [[f64; 2]],
    /// Translation of each rigid body.
    pub rigid_offsets: &'a [[f64; 2]],
    pub contact: &'a [ScenePoint],
}

/// Append the start of a scene entity (up to its primitives).
pub(super) fn entity(out: &mut Vec<u8>, id: &str, time_ns: u64, metadata: &str) {
    raw(out, "{\"timestamp\":");
    time(out, time_ns);
    raw(out, ",\"frame_id\":\"");
    raw(out, FRAME);
    raw(out, "\",\"id\":\"");
    raw(out, id);
    raw(
        out,
        "\",\"lifetime\":{\"sec\":0,\"nsec\":0},\"frame_locked\":false,\"metadata\":",
    );
    raw(out, metadata);
}

/// Close the label entity: a text "increment N, t = …" at `at` (the entity is started).
pub(super) fn label(out: &mut Vec<u8>, at: impl Xyz, increment: usize, t: f64) {
    let mut text = Vec::new();
    raw(&mut text, "{\"pose\":{\"position\":");
    point3(&mut text, at);
    raw(
        &mut text,
        ",\"orientation\":{\"x\":0,\"y\":0,\"z\":0,\"w\":1}},\"billboard\":true,\"font_size\":14,\"scale_invariant\":true,\"color\":",
    );
    colour(&mut text, [230, 230, 230, 255]);
    raw(&mut text, ",\"text\":");
    string(&mut text, &format!("increment {increment}, t = {t}"));
    raw(&mut text, "}");
    primitives(out, &[("texts", &text)]);
}

/// Append a line list primitive through `nodes` with the given `"indices":[…]` text.
pub(super) fn line_list<P: Xyz>(out: &mut Vec<u8>, nodes: &[P], indices: &[u8], c: [u8; 4], thickness: f64) {
    raw(out, "{\"type\":2,\"pose\":");
    raw(out, POSE);
    raw(out, ",\"thickness\":");
    real32(out, thickness);
    raw(out, ",\"scale_invariant\":true,\"points\":[");
    for (k, p) in nodes.iter().enumerate() {
        if k > 0 {
            raw(out, ",");
        }
        point3(out, *p);
    }
    raw(out, "],\"color\":");
    colour(out, c);
    raw(out, ",\"colors\":[],");
    out.extend_from_slice(indices);
    raw(out, "}");
}

/// Append a sphere (after a comma if `out` already holds one).
pub(super) fn sphere(out: &mut Vec<u8>, at: impl Xyz, size: f64, c: [u8; 4]) {
    if !out.is_empty() {
        raw(out, ",");
    }
    raw(out, "{\"pose\":{\"position\":");
    point3(out, at);
    raw(
        out,
        ",\"orientation\":{\"x\":0,\"y\":0,\"z\":0,\"w\":1}},\"size\":{\"x\":",
    );
    real32(out, size);
    raw(out, ",\"y\":");
    real32(out, size);
    raw(out, ",\"z\":");
    real32(out, size);
    raw(out, "},\"color\":");
    colour(out, c);
    raw(out, "}");
}

/// Close an entity: every primitive list (`lists` given, the others empty), `}`.
pub(super) fn primitives(out: &mut Vec<u8>, lists: &[(&str, &[u8])]) {
    for name in [
        "arrows",
        "cubes",
        "spheres",
        "cylinders",
        "lines",
        "triangles",
        "texts",
        "models",
    ] {
        raw(out, ",\"");
        raw(out, name);
        raw(out, "\":[");
        if let Some((_, items)) = lists.iter().find(|(n, _)| *n == name) {
            out.extend_from_slice(items);
        }
        raw(out, "]");
    }
    raw(out, "}");
}

#[cfg(test)]
mod tests {
    use super::*;

    fn model() -> ModelRecord {
        let (_, problem) = crate::load_scene("strip-channel", &[]).unwrap();
        ModelRecord::new(&problem.model, 1.0)
    }

    fn point(pair: usize, position: [f64; 2], state: ContactState, in_reach: bool) -> ScenePoint {
        ScenePoint {
            pair,
            position,
            state,
            in_reach,
        }
    }

    #[test]
    fn a_scene_has_the_mesh_the_rigid_surfaces_and_the_points_within_reach() {
        let m = model();
        let enc = SceneEncoder::new(&m);
        let contact = [
            point(0, [f64::NAN, f64::NAN], ContactState::Open, true),
            point(1, [1.0, -0.5], ContactState::Slip, true),
            point(1, [2.0, 0.0], ContactState::Open, false),
            point(1, [3.0, 0.0], ContactState::Stick, true),
        ];
        let view = SceneView {
            increment: 7,
            t: 0.25,
            nodes: &m.nodes,
            rigid_offsets: &[[0.0, 0.0]],
            contact: &contact,
        };
        let mut out = Vec::new();
        enc.write(&mut out, &view, 1_700_000_000_000_000_123);
        let v: serde_json::Value = serde_json::from_slice(&out).unwrap();
        let entities = v["entities"].as_array().unwrap();
        let ids: Vec<&str> = entities.iter().map(|e| e["id"].as_str().unwrap()).collect();
        assert_eq!(ids, ["mesh", "rigid", "contact points", "label"]);
        let mesh = &entities[0]["lines"][0];
        assert_eq!(mesh["points"].as_array().unwrap().len(), m.nodes.len());
        assert_eq!(mesh["indices"].as_array().unwrap().len(), 2 * m.edges().len());
        assert_eq!(mesh["points"][1]["y"], m.nodes[1][1] as f32 as f64);
        let spheres = entities[2]["spheres"].as_array().unwrap();
        assert_eq!(
            spheres.len(),
            2,
            "not the point without a position, nor the one out of reach"
        );
        assert_eq!(spheres[0]["color"]["r"], 0.882, "slip is orange");
        assert_eq!(entities[0]["timestamp"]["nsec"], 123);
        assert_eq!(entities[3]["texts"][0]["text"], "increment 7, t = 0.25");
        for e in entities {
            for list in [
                "arrows",
                "cubes",
                "spheres",
                "cylinders",
                "lines",
                "triangles",
                "texts",
                "models",
            ] {
                assert!(e[list].is_array(), "{list}");
            }
        }
        let mut reference = Vec::new();
        enc.write_reference(&mut reference, 0);
        let r: serde_json::Value = serde_json::from_slice(&reference).unwrap();
        assert_eq!(r["entities"][0]["id"], "reference mesh");
    }

    #[test]
    fn a_log_message_has_foxglove_levels() {
        let rec = LogRecord {
            level: LogLevel::Warning,
            increment: 3,
            t: 0.5,
            message: "cut back \"twice\"".into(),
        };
        let mut out = Vec::new();
        log(&mut out, &rec, "crossing", 2_000_000_001);
        let v: serde_json::Value = serde_json::from_slice(&out).unwrap();
        assert_eq!(v["level"], 3);
        assert_eq!(v["timestamp"]["sec"], 2);
        assert_eq!(v["message"], "increment 3 (t = 0.5): cut back \"twice\"");
        assert_eq!(v["name"], "contrail crossing");
    }
}
