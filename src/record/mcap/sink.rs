//! MCAP sink: every record as a JSON message on its channel (see [`crate::record::mcap::schemas`]; the
//! per-increment layout is format 3, [`crate::record::mcap::format3`]), compressed chunks, the run's facts
//! as MCAP metadata and the scene text as an attachment. `finish` writes the outcome as the
//! last message and closes the file, so a failed or interrupted run still leaves a complete
//! recording.
//!
//! [`McapSink::create`] writes a file under a temporary name and renames it into place at
//! `finish` (see [`crate::record::atomic_file`]). An I/O error (a full disk) is reported with its
//! cause and stops the run; the half-written temporary file is then removed, and the mcap
//! writer — which cannot recover from an error in the middle of a chunk — never sees it.

use crate::model::Model;
use crate::record::atomic_file::AtomicFile;
use crate::record::interface::{interfaces, InterfaceLayout, InterfaceRecord};
pub use crate::record::mcap::format3::node_of_label;
use crate::record::mcap::format3::Format3Writer;
use crate::record::mcap::foxglove::{ScenePoint, SceneView};
use crate::record::mcap::foxglove3d::SolidSceneView;
pub use crate::record::mcap::out::ChunkCompression;
use crate::record::mcap::out::{Clock, Compression, McapOut, OutError};
use crate::record::mcap::schemas;
use crate::record::messages::{CrossingMessageRef, ModelRecord, PositionsMessage};
use crate::record::packed_positions::{PositionsContent, PositionsOf, Precision};
use crate::record::pressure::{profiles, PressureLayout, PressureRecord};
use crate::record::surface_contact::{master_offset, SurfacePointRecord};
use crate::record::{IncrementRecord, IterationRecord, LogRecord, Observer, ObserverError, Outcome, RunInfo, StepView};
use std::collections::BTreeMap;
use std::io::{Seek, Write};
use std::path::Path;

/// Options of the MCAP recorder.
#[derive(Debug, Clone)]
pub struct McapOptions {
    /// Write node positions and contact pressure profiles every N-th increment (and always the
    /// last one); 1 = every one.
    pub positions_every: usize,
    /// Which nodes `/positions` holds (every node, or the boundary of the mesh).
    pub positions_of: PositionsOf,
    /// Precision of the coordinates in `/positions`.
    pub positions_precision: Precision,
    /// Compression of the chunks.
    pub compression: ChunkCompression,
    /// zstd level (1 by default; 19 for small golden files; negative: zstd's fast levels).
    pub compression_level: i32,
    /// Message index records (for seeking by time; readers work without them). Off for the
    /// golden files, where they would be a third of the size.
    pub message_indexes: bool,
    /// Leave out the `/contact` entries of node slaves that stay out of reach (see
    /// [`OutOfReach`]); `false` writes every point of every increment.
    pub thin_out_of_reach: bool,
    /// Which increments get a Foxglove scene (`/foxglove/scene`).
    pub scene: SceneEvery,
    /// Which Newton iterations go on `/iteration`.
    pub iterations: Iterations,
}

/// Which Newton iterations are written on `/iteration`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, clap::ValueEnum)]
pub enum Iterations {
    /// Every iteration, as it happens (default)
    #[default]
    All,
    /// Only the iterations of attempts that failed (cut-backs, retries, the failure), written
    /// at the end of their increment; the residuals of a converged attempt stay on
    /// `/increment`
    Failed,
}

/// Which increments get a Foxglove scene (besides the reference configuration at the start
/// and the last increment, which always do).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum SceneEvery {
    /// About [`SCENES_PER_RUN`] per run, at increments with `/positions` (the MCAP sink
    /// rounds the stride up to a multiple of `positions_every`): every
    /// `increments / SCENES_PER_RUN`-th of the
    /// scene's nominal increments (default).
    #[default]
    Auto,
    /// Every N-th increment.
    Every(usize),
    /// No scene at all.
    Off,
}

/// Scenes of a run with `SceneEvery::Auto`.
pub const SCENES_PER_RUN: usize = 200;

impl SceneEvery {
    /// The stride for a run of `increments` nominal increments (0: no scenes).
    pub fn stride(self, increments: usize) -> usize {
        match self {
            SceneEvery::Auto => increments.div_ceil(SCENES_PER_RUN).max(1),
            SceneEvery::Every(n) => n.max(1),
            SceneEvery::Off => 0,
        }
    }
}

/// How `/contact` and `/surface_contact` treat a slave node with no master within reach
/// (format versions 2 and 3). Such a point is open and carries nothing but its position:
/// every other field is null, NaN or zero, and the same from one increment to the next. Its
/// entry is written at the first increment it is out of reach (and whenever it comes back
/// within reach), and left out while it stays out of reach: at the increments whose
/// `/positions` hold its position bit for bit, and at the increments without `/positions`
/// (`--positions-every N`: its position is not kept there, as no node's is). Readers
/// ([`crate::analysis::recording::Recording`]) restore those records from the last one
/// written (3D: [`crate::record::surface_contact::SurfacePointRecord::out_of_reach`]) with
/// the node's position in that increment's `/positions`, NaN where it has none: bit for bit
/// where the positions are kept (tested by `tests/recording_roundtrip.rs` and
/// `tests/recording_positions_content.rs`).
pub struct OutOfReach;

impl Default for McapOptions {
    fn default() -> Self {
        McapOptions {
            positions_every: 1,
            positions_of: PositionsOf::All,
            positions_precision: Precision::Double,
            compression: ChunkCompression::default(),
            compression_level: 1,
            message_indexes: true,
            thin_out_of_reach: true,
            scene: SceneEvery::default(),
            iterations: Iterations::default(),
        }
    }
}

/// The last increment's data, kept until `finish` in case its positions or scene were not
/// written (thinned away).
struct Last {
    positions: PositionsMessage,
    pressure: Vec<PressureRecord>,
    interfaces: Vec<InterfaceRecord>,
    positions_written: bool,
    /// Its contact points as the scene draws them.
    contact: Vec<ScenePoint>,
    /// A 3D model's: its pairs' slave points and rigid masters' offsets.
    solid: SolidScene,
    scene_written: bool,
}

/// What the scene of a 3D model draws beside the node positions.
#[derive(Default)]
struct SolidScene {
    contact: Vec<ScenePoint<[f64; 3]>>,
    master_offsets: Vec<[f64; 3]>,
}

impl SolidScene {
    fn of(model: &crate::model::Model<crate::model::Solid>, t: f64, points: &[SurfacePointRecord]) -> Self {
        SolidScene {
            contact: points.iter().map(ScenePoint::of_surface).collect(),
            master_offsets: model.surface_contacts.iter().map(|p| master_offset(p, t)).collect(),
        }
    }

    /// The Foxglove scene of the increment whose positions are `positions`.
    fn write<W: Write + Seek>(
        &self,
        format: &mut Format3Writer,
        out: &mut McapOut<W>,
        positions: &PositionsMessage,
    ) -> Result<(), OutError> {
        let view = SolidSceneView {
            increment: positions.increment,
            t: positions.t,
            nodes: &positions.nodes_3d,
            master_offsets: &self.master_offsets,
            contact: &self.contact,
        };
        format.solid_scene(out, &view)
    }
}

/// Writes a recording to `W` (a file, or a `Cursor<Vec<u8>>` in tests).
pub struct McapSink<W: Write + Seek> {
    out: McapOut<W>,
    done: Option<W>,
    /// What to do with the output at `finish` (commit or discard a temporary file).
    finalise: Option<Finalise<W>>,
    name: String,
    opts: McapOptions,
    /// The per-increment messages (made at `start`, from the model).
    format: Option<Format3Writer>,
    /// Increments between two scenes (0: none), worked out at `start`.
    scene_stride: usize,
    /// The model's pressure layout, worked out at the first increment.
    pressure_layout: Option<PressureLayout>,
    /// The model's two-pass interfaces, worked out at the first increment.
    interface_layout: Option<InterfaceLayout>,
    last: Option<Last>,
    /// Iterations of the increment under way (with `Iterations::Failed`).
    pending_iterations: Vec<IterationRecord>,
}

/// Called at `finish` with the output and whether everything was written.
type Finalise<W> = Box<dyn FnOnce(W, bool) -> std::io::Result<()> + Send>;

impl McapSink<AtomicFile> {
    /// Record to the file `path`: written under a temporary name in the same directory and
    /// renamed to `path` when the recording is finished (removed if it could not be written).
    pub fn create(path: &Path, opts: McapOptions) -> Result<Self, ObserverError> {
        let name = path.display().to_string();
        let file = AtomicFile::create(path).map_err(|e| ObserverError::new(&name, CannotCreate(e)))?;
        let mut sink = McapSink::new(file, &name, opts)?;
        sink.finalise = Some(Box::new(|f: AtomicFile, ok| {
            if ok {
                f.commit().map(|_| ())
            } else {
                f.discard();
                Ok(())
            }
        }));
        Ok(sink)
    }
}

/// The output file could not be created.
#[derive(Debug, thiserror::Error)]
#[error("cannot create: {0}")]
struct CannotCreate(#[source] std::io::Error);

impl<W: Write + Seek> McapSink<W> {
    /// Start a recording on `out`; `name` names the sink in error messages (the file path).
    pub fn new(out: W, name: &str, opts: McapOptions) -> Result<Self, ObserverError> {
        let compression = Compression {
            kind: opts.compression,
            zstd_level: opts.compression_level,
        };
        let library = format!("contrail {}", crate::VERSION);
        let out = McapOut::new(out, library, compression, opts.message_indexes, Clock::wall())
            .map_err(|e| ObserverError::new(name, e))?;
        Ok(McapSink {
            out,
            done: None,
            finalise: None,
            name: name.to_string(),
            opts,
            format: None,
            scene_stride: 0,
            pressure_layout: None,
            interface_layout: None,
            last: None,
            pending_iterations: Vec::new(),
        })
    }

    /// The output after `finish` (tests read recordings from memory this way).
    pub fn into_inner(self) -> Option<W> {
        self.done
    }

    fn err(&self, e: impl Into<Box<dyn std::error::Error + Send + Sync>>) -> ObserverError {
        ObserverError::new(&self.name, e)
    }

    /// Write the last increment's positions and scene if they were thinned away.
    fn flush_last(&mut self) -> Result<(), OutError> {
        let Some(last) = self.last.take() else {
            return Ok(());
        };
        let Some(format) = self.format.as_mut() else {
            return Ok(());
        };
        if !last.positions_written {
            format.positions(&mut self.out, &last.positions, &last.pressure)?;
            format.interfaces(&mut self.out, &last.interfaces)?;
        }
        if !last.scene_written && self.scene_stride > 0 && !last.positions.nodes_3d.is_empty() {
            last.solid.write(format, &mut self.out, &last.positions)?;
        } else if !last.scene_written && self.scene_stride > 0 {
            let view = SceneView {
                increment: last.positions.increment,
                t: last.positions.t,
                nodes: &last.positions.nodes,
                rigid_offsets: &last.positions.rigid_offsets,
                contact: &last.contact,
            };
            format.scene(&mut self.out, &view)?;
        }
        Ok(())
    }
}

/// The `contrail.run` metadata record of a run.
pub fn metadata(info: &RunInfo, model: &Model, opts: &McapOptions, scene_stride: usize) -> BTreeMap<String, String> {
    let json = |v: serde_json::Value| v.to_string();
    let parameters = serde_json::json!({
        "stepping": info.settings.stepping,
        "newton": info.settings.newton,
        "contact": model.contacts.iter().map(|c| serde_json::json!({
            "name": c.name,
            "law": c.law,
            "transfer": c.transfer.name(),
            "search_radius": c.search_radius,
        })).collect::<Vec<_>>(),
    });
    let mut m = BTreeMap::new();
    m.insert("format".into(), "contrail-recording".into());
    m.insert("format_version".into(), schemas::FORMAT_VERSION.into());
    m.insert("scene".into(), info.scene.clone());
    m.insert("scene_origin".into(), info.scene_origin.clone());
    m.insert("overrides".into(), json(serde_json::json!(info.overrides)));
    m.insert("transfer".into(), json(serde_json::json!(info.transfer)));
    m.insert("parameters".into(), json(parameters));
    m.insert("crate_version".into(), info.crate_version.clone());
    m.insert("git_revision".into(), info.git_revision.clone());
    m.insert("dofs".into(), info.dofs.to_string());
    m.insert("free_dofs".into(), info.free_dofs.to_string());
    m.insert("positions_every".into(), opts.positions_every.max(1).to_string());
    m.insert("positions_of".into(), opts.positions_of.name().into());
    m.insert("positions_precision".into(), opts.positions_precision.name().into());
    m.insert("scene_every".into(), scene_stride.to_string());
    m.insert(
        "non_finite".into(),
        "NaN and infinities are the JSON strings \"NaN\", \"Infinity\", \"-Infinity\"".into(),
    );
    m
}

/// The scene text as an attachment, named after the scene file.
pub fn scene_attachment(info: &RunInfo, time_ns: u64) -> mcap::Attachment<'_> {
    let scene_file = std::path::Path::new(&info.scene_origin)
        .file_name()
        .and_then(|f| f.to_str())
        .filter(|f| f.ends_with(".toml"))
        .map_or_else(|| format!("{}.toml", info.scene), str::to_string);
    mcap::Attachment {
        log_time: time_ns,
        create_time: time_ns,
        name: scene_file,
        media_type: "application/toml".into(),
        data: std::borrow::Cow::Borrowed(info.scene_text.as_bytes()),
    }
}

impl<W: Write + Seek> Observer for McapSink<W> {
    fn start(&mut self, model: crate::model::ModelRef<'_>, info: &RunInfo) -> Result<(), ObserverError> {
        self.scene_stride = self.opts.scene.stride(info.settings.stepping.increments);
        if self.opts.scene == SceneEvery::Auto {
            // a scene draws the positions: at increments that keep them
            let every = self.opts.positions_every.max(1);
            self.scene_stride = self.scene_stride.div_ceil(every) * every;
        }
        let mut record = ModelRecord::of(model, info.settings.stepping.end);
        let content = PositionsContent::of(&record, self.opts.positions_of, self.opts.positions_precision);
        record.positions_nodes = content.nodes.clone().unwrap_or_default();
        let model_ref = model;
        let model = model.plane();
        let metadata = metadata(info, model, &self.opts, self.scene_stride);
        let now = self.out.now();
        let mut format = Format3Writer::new(&record, &info.scene, self.opts.thin_out_of_reach);
        format.keep_positions(&record, content);
        let r = (self.out.register(metadata, &[scene_attachment(info, now)]))
            .and_then(|_| self.out.put(schemas::MODEL, &record))
            .and_then(|_| {
                if self.scene_stride == 0 {
                    return Ok(());
                }
                format.reference(&mut self.out)?;
                if let crate::model::ModelRef::Solid(solid) = model_ref {
                    let start = PositionsMessage::of(0, 0.0, model_ref, &vec![0.0; 3 * solid.nodes.len()]);
                    return SolidScene::of(solid, 0.0, &[]).write(&mut format, &mut self.out, &start);
                }
                let offsets: Vec<[f64; 2]> = model.rigid.iter().map(|r| r.offset(0.0)).collect();
                let view = SceneView {
                    increment: 0,
                    t: 0.0,
                    nodes: &record.nodes,
                    rigid_offsets: &offsets,
                    contact: &[],
                };
                format.scene(&mut self.out, &view)
            });
        self.format = Some(format);
        r.map_err(|e| self.err(e))
    }

    fn iteration(&mut self, rec: &IterationRecord) -> Result<(), ObserverError> {
        if self.opts.iterations == Iterations::Failed {
            self.pending_iterations.push(rec.clone());
            return Ok(());
        }
        self.out.put(schemas::ITERATION, rec).map_err(|e| self.err(e))
    }

    fn increment(&mut self, rec: &IncrementRecord, view: &StepView) -> Result<(), ObserverError> {
        // the messages of an increment are logged at one time (when it is written)
        self.out.hold_time();
        let r = self.write_increment(rec, view);
        self.out.release_time();
        r.map_err(|e| self.err(e))
    }

    fn log(&mut self, rec: &LogRecord) -> Result<(), ObserverError> {
        let r = match self.format.as_mut() {
            Some(f) => f.log(&mut self.out, rec),
            None => self.out.put(schemas::LOG, rec),
        };
        r.map_err(|e| self.err(e))
    }

    fn finish(&mut self, outcome: &Outcome) -> Result<(), ObserverError> {
        // the iterations of the increment that did not converge
        let mut last = Ok(());
        for rec in std::mem::take(&mut self.pending_iterations) {
            last = last.and(self.out.put(schemas::ITERATION, &rec));
        }
        let last = last.and(self.flush_last());
        let r = self.out.put(schemas::OUTCOME, outcome);
        let written = last.and(r);
        let (out, result) = match self.out.finish() {
            Ok(out) => (Some(out), written),
            Err((out, e)) => (out, written.and(Err(e))),
        };
        let result = result.map_err(|e| self.err(e));
        let Some(mut out) = out else {
            return result;
        };
        match self.finalise.take() {
            Some(f) => {
                let ok = result.is_ok();
                let committed = f(out, ok).map_err(|e| self.err(OutError::Io(e)));
                result.and(committed)
            }
            None => {
                let flushed = out.flush().map_err(|e| self.err(OutError::Io(e)));
                self.done = Some(out);
                result.and(flushed)
            }
        }
    }
}

impl<W: Write + Seek> McapSink<W> {
    fn write_increment(&mut self, rec: &IncrementRecord, view: &StepView) -> Result<(), OutError> {
        // with `Iterations::Failed`: the attempts before the converged one
        let converged = self.pending_iterations.iter().map(|i| i.attempt).max();
        for it in std::mem::take(&mut self.pending_iterations) {
            if Some(it.attempt) != converged || it.increment != rec.increment {
                self.out.put(schemas::ITERATION, &it)?;
            }
        }
        self.out.put(schemas::INCREMENT, rec)?;
        let every = self.opts.positions_every.max(1);
        let positions_now = rec.increment.is_multiple_of(every);
        let scene_now = self.scene_stride > 0 && rec.increment.is_multiple_of(self.scene_stride);
        let format = self.format.as_mut().ok_or(OutError::NotStarted(schemas::CONTACT))?;
        format.contact(&mut self.out, rec.increment, rec.t, view.contact, positions_now)?;
        for c in view.crossings {
            let msg = CrossingMessageRef {
                increment: rec.increment,
                t: rec.t,
                crossing: c,
            };
            self.out.put(schemas::CROSSING, &msg)?;
        }
        if let crate::model::ModelRef::Solid(solid) = view.model {
            let offsets: Vec<[f64; 3]> = (solid.surface_contacts.iter())
                .map(|pair| master_offset(pair, rec.t))
                .collect();
            let at = (rec.increment, rec.t);
            format.surface_contact(&mut self.out, at, &offsets, view.surface, positions_now)?;
        }
        let positions = PositionsMessage::of(rec.increment, rec.t, view.model, view.u);
        let plane = view.model.plane();
        let layout = self.pressure_layout.get_or_insert_with(|| PressureLayout::new(plane));
        let pressure = profiles(layout, plane, view.u, rec.t, rec.increment, view.contact);
        let layout = (self.interface_layout).get_or_insert_with(|| InterfaceLayout::new(plane));
        let interfaces = interfaces(layout, plane, view.u, rec.t, rec.increment, view.contact);
        if positions_now {
            format.positions(&mut self.out, &positions, &pressure)?;
            format.interfaces(&mut self.out, &interfaces)?;
        }
        // the last increment's positions and scene are written at `finish` if thinned away
        let mut contact = self.last.take().map(|l| l.contact).unwrap_or_default();
        contact.clear();
        if self.scene_stride > 0 {
            contact.extend(view.contact.iter().map(ScenePoint::of));
        }
        let solid = match view.model {
            crate::model::ModelRef::Solid(m) if self.scene_stride > 0 => SolidScene::of(m, rec.t, view.surface),
            _ => SolidScene::default(),
        };
        if scene_now && !positions.nodes_3d.is_empty() {
            solid.write(format, &mut self.out, &positions)?;
        } else if scene_now {
            let scene = SceneView {
                increment: rec.increment,
                t: rec.t,
                nodes: &positions.nodes,
                rigid_offsets: &positions.rigid_offsets,
                contact: &contact,
            };
            format.scene(&mut self.out, &scene)?;
        }
        self.last = Some(Last {
            positions,
            pressure,
            interfaces,
            positions_written: positions_now,
            contact,
            solid,
            scene_written: scene_now,
        });
        Ok(())
    }
}
