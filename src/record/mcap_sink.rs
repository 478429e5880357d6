//! MCAP sink: every record as a JSON message on its channel (see [`super::schemas`]),
//! LZ4- or zstd-compressed chunks, the run's facts as MCAP metadata and the scene text as an
//! attachment. `finish` writes the outcome as the last message and closes the file, so a
//! failed or interrupted run still leaves a complete recording.
//!
//! [`McapSink::create`] writes a file under a temporary name and renames it into place at
//! `finish` (see [`super::atomic_file`]). An I/O error (a full disk) is reported with its
//! cause and stops the run; the half-written temporary file is then removed, and the mcap
//! writer — which cannot recover from an error in the middle of a chunk — never sees it.

use super::atomic_file::{AtomicFile, FirstError, Guarded};
use super::messages::{ContactPointMessageRef, CrossingMessage, ModelRecord, PositionsMessage};
use super::pressure::{profiles, PressureLayout, PressureRecord};
use super::schemas::{self, CHANNELS};
use super::{IncrementRecord, IterationRecord, LogRecord, Observer, ObserverError, Outcome, RunInfo, StepView};
use crate::model::Model;
use serde::Serialize;
use std::collections::BTreeMap;
use std::io::{Seek, Write};
use std::path::Path;
use std::time::{Instant, SystemTime, UNIX_EPOCH};

/// How the chunks of a recording are compressed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, clap::ValueEnum)]
pub enum ChunkCompression {
    /// zstd at [`McapOptions::compression_level`] (default): the smallest files.
    #[default]
    Zstd,
    /// LZ4 frames: files 1.6× larger than zstd level 1 (24×1 strip-channel, 4 800
    /// increments: 19.8 against 12.4 MB; 78 MB uncompressed), and measured no faster to
    /// write there (the JSON encoding, not the compression, is most of the writer's time).
    Lz4,
    /// No compression.
    None,
}

/// Options of the MCAP recorder.
#[derive(Debug, Clone)]
pub struct McapOptions {
    /// Write node positions and contact pressure profiles every N-th increment (and always the
    /// last one); 1 = every one.
    pub positions_every: usize,
    /// Compression of the chunks.
    pub compression: ChunkCompression,
    /// zstd level (default 1, the fastest of the regular levels; on the strip-channel
    /// recording it even writes 5 % less than level 3; 19 for small golden files; 0 means
    /// the library's default, 3).
    pub compression_level: u32,
    /// Message index records (for seeking by time; readers work without them). Off for the
    /// golden files, where they would be a third of the size.
    pub message_indexes: bool,
    /// Leave out the `/contact` messages of node slaves that stay out of reach (see
    /// [`OutOfReach`]); `false` writes every point of every increment.
    pub thin_out_of_reach: bool,
}

/// How `/contact` treats a slave node with no master segment within reach (format version
/// 2). Such a point is open and carries nothing but its position: every other field is null,
/// NaN or zero, and the same from one increment to the next. Its message is written at the
/// first increment it is out of reach (and whenever it comes back within reach), and left
/// out while it stays out of reach in increments whose `/positions` message is written;
/// readers ([`crate::analysis::recording::Recording`]) restore those records from the last
/// one written and the node's position in `/positions`, bit for bit (tested by
/// `tests/recording_roundtrip.rs`). On the 24×1 strip-channel run (4 800 increments) that is
/// 79 800 of the 124 800 `/contact` messages, 37 % of the recording's JSON.
pub struct OutOfReach;

impl Default for McapOptions {
    fn default() -> Self {
        McapOptions {
            positions_every: 1,
            compression: ChunkCompression::default(),
            compression_level: 1,
            message_indexes: true,
            thin_out_of_reach: true,
        }
    }
}

/// Writes a recording to `W` (a file, or a `Cursor<Vec<u8>>` in tests).
pub struct McapSink<W: Write + Seek> {
    writer: Option<mcap::Writer<Guarded<W>>>,
    done: Option<W>,
    /// The first I/O error of the output.
    io_error: FirstError,
    /// What to do with the output at `finish` (commit or discard a temporary file).
    finalise: Option<Finalise<W>>,
    name: String,
    opts: McapOptions,
    channel_ids: Vec<u16>,
    sequence: Vec<u32>,
    epoch_ns: u64,
    started: Instant,
    buf: Vec<u8>,
    /// Positions of the last increment when they were thinned away (written at `finish`).
    pending_positions: Option<PositionsMessage>,
    /// Pressure profiles of the last increment when they were thinned away (likewise).
    pending_pressure: Vec<PressureRecord>,
    /// The model's pressure layout, worked out at the first increment.
    pressure_layout: Option<PressureLayout>,
    /// Per pair and slave: the last `/contact` message written was out of reach.
    out_of_reach: Vec<Vec<bool>>,
}

/// The node of a slave labelled `node N` (see [`crate::model::Model::slave_label`]).
pub fn node_of_label(label: &str) -> Option<usize> {
    label.strip_prefix("node ")?.parse().ok()
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

/// The output could not be written.
#[derive(Debug, thiserror::Error)]
#[error("cannot write: {0}")]
struct CannotWrite(#[source] std::io::Error);

impl<W: Write + Seek> McapSink<W> {
    /// Start a recording on `out`; `name` names the sink in error messages (the file path).
    pub fn new(out: W, name: &str, opts: McapOptions) -> Result<Self, ObserverError> {
        let compression = match opts.compression {
            ChunkCompression::Lz4 => Some(mcap::Compression::Lz4),
            ChunkCompression::Zstd => Some(mcap::Compression::Zstd),
            ChunkCompression::None => None,
        };
        let writer = mcap::WriteOptions::new()
            .profile(schemas::PROFILE)
            .library(format!("contrail {}", crate::VERSION))
            .compression(compression)
            .compression_level(opts.compression_level)
            // zstd's worker threads are created per chunk and compete with the solver for
            // the cores: the writer thread compresses on its own
            .compression_threads(0)
            .emit_message_indexes(opts.message_indexes);
        let io_error = FirstError::default();
        let writer = writer
            .create(Guarded::new(out, io_error.clone()))
            .map_err(|e| ObserverError::new(name, e))?;
        if let Some(e) = io_error.get() {
            return Err(ObserverError::new(name, CannotWrite(e)));
        }
        Ok(McapSink {
            writer: Some(writer),
            done: None,
            io_error,
            finalise: None,
            name: name.to_string(),
            opts,
            channel_ids: Vec::new(),
            sequence: vec![0; CHANNELS.len()],
            epoch_ns: SystemTime::now()
                .duration_since(UNIX_EPOCH)
                .map_or(0, |d| d.as_nanos() as u64),
            started: Instant::now(),
            buf: Vec::with_capacity(4096),
            pending_positions: None,
            pending_pressure: Vec::new(),
            pressure_layout: None,
            out_of_reach: Vec::new(),
        })
    }

    /// The output after `finish` (tests read recordings from memory this way).
    pub fn into_inner(self) -> Option<W> {
        self.done
    }

    fn err(&self, e: impl Into<Box<dyn std::error::Error + Send + Sync>>) -> ObserverError {
        ObserverError::new(&self.name, e)
    }

    /// The first I/O error of the output, if one happened (it wins over what the mcap writer
    /// said, which is only a consequence).
    fn io_check<T>(&self, r: Result<T, ObserverError>) -> Result<T, ObserverError> {
        match self.io_error.get() {
            Some(e) => Err(self.err(CannotWrite(e))),
            None => r,
        }
    }

    fn writer(&mut self) -> Result<&mut mcap::Writer<Guarded<W>>, ObserverError> {
        let name = self.name.clone();
        self.writer
            .as_mut()
            .ok_or_else(|| ObserverError::new(&name, "the recording is already finished"))
    }

    fn put<T: Serialize>(&mut self, topic: &str, msg: &T) -> Result<(), ObserverError> {
        let idx = CHANNELS
            .iter()
            .position(|c| c.topic == topic)
            .ok_or_else(|| self.err(format!("unknown channel {topic}")))?;
        let channel_id = *self
            .channel_ids
            .get(idx)
            .ok_or_else(|| self.err("message before the recording was started"))?;
        self.buf.clear();
        serde_json::to_writer(&mut self.buf, msg).map_err(|e| self.err(e))?;
        let now = self.epoch_ns + self.started.elapsed().as_nanos() as u64;
        let header = mcap::records::MessageHeader {
            channel_id,
            sequence: self.sequence[idx],
            log_time: now,
            publish_time: now,
        };
        self.sequence[idx] += 1;
        let buf = std::mem::take(&mut self.buf);
        let r = self.writer()?.write_to_known_channel(&header, &buf);
        self.buf = buf;
        let r = r.map_err(|e| self.err(e));
        self.io_check(r)
    }

    fn metadata(info: &RunInfo, model: &Model, opts: &McapOptions) -> BTreeMap<String, String> {
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
        m.insert(
            "non_finite".into(),
            "NaN and infinities are the JSON strings \"NaN\", \"Infinity\", \"-Infinity\"".into(),
        );
        m
    }
}

impl<W: Write + Seek> Observer for McapSink<W> {
    fn start(&mut self, model: &Model, info: &RunInfo) -> Result<(), ObserverError> {
        let metadata = Self::metadata(info, model, &self.opts);
        let now = self.epoch_ns;
        let name = self.name.clone();
        let e = |e: mcap::McapError| ObserverError::new(&name, e);
        let w = self.writer()?;
        let mut ids = Vec::with_capacity(CHANNELS.len());
        for c in CHANNELS {
            let schema = w
                .add_schema(c.schema_name, "jsonschema", c.schema_text().as_bytes())
                .map_err(e)?;
            let mut meta = BTreeMap::new();
            meta.insert("description".to_string(), c.description.to_string());
            ids.push(w.add_channel(schema, c.topic, "json", &meta).map_err(e)?);
        }
        w.write_metadata(&mcap::records::Metadata {
            name: schemas::METADATA_NAME.into(),
            metadata,
        })
        .map_err(e)?;
        let scene_file = std::path::Path::new(&info.scene_origin)
            .file_name()
            .and_then(|f| f.to_str())
            .filter(|f| f.ends_with(".toml"))
            .map_or_else(|| format!("{}.toml", info.scene), str::to_string);
        w.attach(&mcap::Attachment {
            log_time: now,
            create_time: now,
            name: scene_file,
            media_type: "application/toml".into(),
            data: std::borrow::Cow::Borrowed(info.scene_text.as_bytes()),
        })
        .map_err(e)?;
        self.channel_ids = ids;
        let r = self.put(schemas::MODEL, &ModelRecord::new(model, info.settings.stepping.end));
        self.io_check(r)
    }

    fn iteration(&mut self, rec: &IterationRecord) -> Result<(), ObserverError> {
        self.put(schemas::ITERATION, rec)
    }

    fn increment(&mut self, rec: &IncrementRecord, view: &StepView) -> Result<(), ObserverError> {
        self.put(schemas::INCREMENT, rec)?;
        let positions_now = rec.increment.is_multiple_of(self.opts.positions_every.max(1));
        for p in view.contact {
            let out = p.segment.is_none();
            if self.out_of_reach.len() <= p.pair {
                self.out_of_reach.resize(p.pair + 1, Vec::new());
            }
            let flags = &mut self.out_of_reach[p.pair];
            if flags.len() <= p.slave {
                flags.resize(p.slave + 1, false);
            }
            let was_out = std::mem::replace(&mut flags[p.slave], out);
            if self.opts.thin_out_of_reach && positions_now && out && was_out && node_of_label(&p.slave_label).is_some()
            {
                continue;
            }
            let msg = ContactPointMessageRef {
                increment: rec.increment,
                t: rec.t,
                point: p,
            };
            self.put(schemas::CONTACT, &msg)?;
        }
        for c in view.crossings {
            let msg = CrossingMessage {
                increment: rec.increment,
                t: rec.t,
                crossing: c.clone(),
            };
            self.put(schemas::CROSSING, &msg)?;
        }
        let positions = PositionsMessage::new(rec.increment, rec.t, view.model, view.u);
        let layout = self
            .pressure_layout
            .get_or_insert_with(|| PressureLayout::new(view.model));
        let pressure = profiles(layout, view.model, view.u, rec.t, rec.increment, view.contact);
        if rec.increment.is_multiple_of(self.opts.positions_every.max(1)) {
            self.pending_positions = None;
            self.pending_pressure.clear();
            for p in &pressure {
                self.put(schemas::PRESSURE, p)?;
            }
            self.put(schemas::POSITIONS, &positions)
        } else {
            self.pending_positions = Some(positions);
            self.pending_pressure = pressure;
            Ok(())
        }
    }

    fn log(&mut self, rec: &LogRecord) -> Result<(), ObserverError> {
        self.put(schemas::LOG, rec)
    }

    fn finish(&mut self, outcome: &Outcome) -> Result<(), ObserverError> {
        let mut first = Ok(());
        for p in std::mem::take(&mut self.pending_pressure) {
            first = first.and(self.put(schemas::PRESSURE, &p));
        }
        if let Some(p) = self.pending_positions.take() {
            first = first.and(self.put(schemas::POSITIONS, &p));
        }
        let r = self.put(schemas::OUTCOME, outcome);
        first = first.and(r);
        let mut writer = self.writer.take().ok_or_else(|| self.err("finish called twice"))?;
        let closed = writer.finish().map_err(|e| self.err(e));
        let mut out = writer.into_inner();
        let _ = out.flush();
        let result = self.io_check(first.and(closed.map(|_| ())));
        let mut out = out.into_inner();
        match self.finalise.take() {
            Some(f) => {
                let ok = result.is_ok();
                let committed = f(out, ok).map_err(|e| self.err(CannotWrite(e)));
                result.and(committed)
            }
            None => {
                let flushed = out.flush().map_err(|e| self.err(CannotWrite(e)));
                self.done = Some(out);
                result.and(flushed)
            }
        }
    }
}
