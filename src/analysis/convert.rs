//! `contrail convert OLD.mcap NEW.mcap`: a recording of any readable format written again in
//! the current one (format 3, with the Foxglove channels), as the MCAP sink would have
//! written the same run: the records read by [`Recording`] (thinned contact points restored)
//! go through the sink's own per-increment writer ([`Format3Writer`]). Every message is
//! logged at the time of its increment's `/increment` message in the old file. The Foxglove
//! scene is drawn at the increments that have `/positions` (the old file has no other node
//! coordinates), in 3D with the 3D pairs' points and rigid masters.

use super::recording::Recording;
use crate::record::mcap::format3::Format3Writer;
use crate::record::mcap::foxglove::{ScenePoint, SceneView};
use crate::record::mcap::foxglove3d::SolidSceneView;
use crate::record::mcap::out::{Clock, Compression, McapOut, OutError};
use crate::record::mcap::schemas;
use crate::record::mcap::sink::SceneEvery;
use crate::record::messages::{CrossingMessageRef, PositionsMessage};
use crate::record::packed_positions::{PositionsContent, Precision};
use crate::record::pressure::PressureRecord;
use crate::record::IncrementRecord;
use std::collections::BTreeMap;
use std::io::{Seek, Write};

/// How the new file is written.
#[derive(Debug, Clone, Copy)]
pub struct ConvertOptions {
    pub compression: Compression,
    pub message_indexes: bool,
    /// Scenes at the increments with `/positions` that are multiples of the stride (and the
    /// last); `Auto` takes the stride from the scene's nominal increments.
    pub scene: SceneEvery,
}

/// What a conversion wrote.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ConvertReport {
    /// Format version of the old file.
    pub from_version: String,
    pub increments: usize,
    pub scenes: usize,
}

/// The metadata (marked as converted, with the scene stride chosen for the run's nominal
/// increments), the scene file attached and the model: returns the stride of the Foxglove
/// scenes and the old file's format version.
fn write_header<W: Write + Seek>(
    r: &Recording,
    out: &mut McapOut<W>,
    opts: &ConvertOptions,
) -> Result<(usize, String), OutError> {
    let nominal: usize = (r.metadata.get("parameters"))
        .and_then(|p| serde_json::from_str::<serde_json::Value>(p).ok())
        .and_then(|p| p["stepping"]["increments"].as_u64())
        .map_or(r.increments.len(), |n| n as usize);
    let stride = opts.scene.stride(nominal);
    let from_version = r.metadata.get("format_version").cloned().unwrap_or_default();
    let mut metadata = r.metadata.clone();
    metadata.insert("format_version".into(), schemas::FORMAT_VERSION.into());
    metadata.insert("converted_from_format".into(), from_version.clone());
    metadata.insert("scene_every".into(), stride.to_string());
    let attachment = r.scene_file.as_ref().map(|(name, text)| mcap::Attachment {
        log_time: r.start_time,
        create_time: r.start_time,
        name: name.clone(),
        media_type: "application/toml".into(),
        data: std::borrow::Cow::Borrowed(text.as_bytes()),
    });
    out.register(metadata, attachment.as_slice())?;
    out.put(schemas::MODEL, &r.model)?;
    Ok((stride, from_version))
}

/// Write `r` in format 3 to `out`.
pub fn convert<W: Write + Seek>(r: &Recording, out: W, opts: &ConvertOptions) -> Result<(W, ConvertReport), OutError> {
    let library = format!("contrail {} (converted from {})", crate::VERSION, r.library);
    let mut out = McapOut::new(
        out,
        library,
        opts.compression,
        opts.message_indexes,
        Clock::Fixed(r.start_time),
    )?;
    let (stride, from_version) = write_header(r, &mut out, opts)?;
    let mut format = Format3Writer::new(&r.model, r.scene(), true).lossless();
    // the positions as the recording kept them (every node or the boundary; the precision)
    let single = r.metadata.get("positions_precision").map(String::as_str) == Some("single");
    let kept = PositionsContent {
        nodes: (!r.model.positions_nodes.is_empty()).then(|| r.model.positions_nodes.clone()),
        precision: if single { Precision::Single } else { Precision::Double },
    };
    format.keep_positions(&r.model, kept);
    let mut scenes = 0;
    if stride > 0 {
        format.reference(&mut out)?;
        let start = PositionsMessage {
            increment: 0,
            t: 0.0,
            nodes: r.model.nodes.clone(),
            nodes_3d: r.model.nodes_3d.clone(),
            rigid_offsets: vec![[0.0; 2]; r.model.rigid.len()],
        };
        let first = IncrementRecord::default();
        scene_at(&mut format, &mut out, r, &first, &start)?;
        scenes += 1;
    }
    let positions: BTreeMap<usize, _> = r.positions.iter().map(|p| (p.increment, p)).collect();
    let mut pressure: BTreeMap<usize, Vec<PressureRecord>> = BTreeMap::new();
    for p in &r.pressure {
        pressure.entry(p.increment).or_default().push(p.clone());
    }
    let (mut its, mut logs) = (r.iterations.iter().peekable(), r.logs.iter().peekable());
    let last = r.increments.last().map(|i| i.increment);
    for inc in &r.increments {
        out.set_time(r.increment_times.get(&inc.increment).copied().unwrap_or(r.start_time));
        while let Some(i) = its.next_if(|i| i.increment <= inc.increment) {
            out.put(schemas::ITERATION, i)?;
        }
        while let Some(l) = logs.next_if(|l| l.increment <= inc.increment) {
            format.log(&mut out, l)?;
        }
        out.put(schemas::INCREMENT, inc)?;
        let contact = r.contact_at(inc.increment);
        let at = positions.get(&inc.increment).copied();
        format.contact(&mut out, inc.increment, inc.t, contact, at.is_some())?;
        if !r.model.surface_contacts.is_empty() {
            let offsets = r.surface_offsets.get(&inc.increment).map_or(&[][..], Vec::as_slice);
            let surface = r.surface_at(inc.increment);
            format.surface_contact(&mut out, (inc.increment, inc.t), offsets, surface, at.is_some())?;
        }
        for c in r.crossings.iter().filter(|c| c.increment == inc.increment) {
            let msg = CrossingMessageRef {
                increment: c.increment,
                t: c.t,
                crossing: &c.crossing,
            };
            out.put(schemas::CROSSING, &msg)?;
        }
        let Some(p) = at else { continue };
        let profiles = pressure.get(&inc.increment).map_or(&[][..], Vec::as_slice);
        format.positions(&mut out, p, profiles)?;
        let joined: Vec<_> = r
            .interface
            .iter()
            .filter(|f| f.increment == inc.increment)
            .cloned()
            .collect();
        format.interfaces(&mut out, &joined)?;
        if stride > 0 && (inc.increment.is_multiple_of(stride) || Some(inc.increment) == last) {
            scene_at(&mut format, &mut out, r, inc, p)?;
            scenes += 1;
        }
    }
    for i in its {
        out.put(schemas::ITERATION, i)?;
    }
    for l in logs {
        format.log(&mut out, l)?;
    }
    if let Some(o) = &r.outcome {
        out.put(schemas::OUTCOME, o)?;
    }
    let report = ConvertReport {
        from_version,
        increments: r.increments.len(),
        scenes,
    };
    out.finish().map(|w| (w, report)).map_err(|(_, e)| e)
}

/// The Foxglove scene of increment `inc` (the reference configuration: a default record) at
/// the positions `p`: the 3D mesh with the 3D pairs' points and rigid masters, or the plane
/// mesh with its contact points and rigid bodies.
fn scene_at<W: Write + Seek>(
    format: &mut Format3Writer,
    out: &mut McapOut<W>,
    r: &Recording,
    inc: &IncrementRecord,
    p: &PositionsMessage,
) -> Result<(), OutError> {
    if !r.model.nodes_3d.is_empty() {
        let contact: Vec<ScenePoint<[f64; 3]>> = (r.surface_at(inc.increment).iter())
            .map(ScenePoint::of_surface)
            .collect();
        // the reference configuration: the rigid masters where they start
        let start = vec![[0.0; 3]; r.model.surface_contacts.len()];
        let offsets = r.surface_offsets.get(&inc.increment).unwrap_or(&start);
        let view = SolidSceneView {
            increment: inc.increment,
            t: inc.t,
            nodes: &p.nodes_3d,
            master_offsets: offsets,
            contact: &contact,
        };
        return format.solid_scene(out, &view);
    }
    let points: Vec<ScenePoint> = r.contact_at(inc.increment).iter().map(ScenePoint::of).collect();
    let view = SceneView {
        increment: inc.increment,
        t: inc.t,
        nodes: &p.nodes,
        rigid_offsets: &p.rigid_offsets,
        contact: &points,
    };
    format.scene(out, &view)
}
