//! The file side of a recording: an mcap writer with contrail's channels registered, messages
//! written as JSON into one reused buffer that goes to the writer's chunk as it is, the first
//! I/O error kept (see [`crate::record::atomic_file::Guarded`]) and reported instead of whatever the
//! mcap writer made of it. Shared by the MCAP sink and `contrail convert`.

use crate::record::atomic_file::{FirstError, Guarded};
use crate::record::mcap::schemas::{self, CHANNELS};
use serde::Serialize;
use std::collections::BTreeMap;
use std::io::{Seek, Write};

/// How the chunks of a recording are compressed. The doc comments of the variants are the
/// help text of `contrail run --compression`: they say what a choice does; what each costs
/// and saves on a run is measured in `docs/recording.md` (Size and cost).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, clap::ValueEnum)]
pub enum ChunkCompression {
    /// zstd (default; its level is an option of its own)
    #[default]
    Zstd,
    /// LZ4 frames (larger files than zstd)
    Lz4,
    /// No compression (the largest files)
    None,
}

/// Compression of the chunks and its level.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Compression {
    pub kind: ChunkCompression,
    /// zstd level: 1 to 22, or negative for zstd's fast levels (−1 to −7: faster, larger).
    pub zstd_level: i32,
}

/// The first I/O error of the output, or what the mcap writer said.
#[derive(Debug, thiserror::Error)]
pub enum OutError {
    #[error("cannot write: {0}")]
    Io(#[source] std::io::Error),
    #[error(transparent)]
    Mcap(#[from] mcap::McapError),
    #[error("{0}")]
    Json(#[from] serde_json::Error),
    #[error("the recording is already finished")]
    Finished,
    #[error("a message on {0} before the channels were registered")]
    NotStarted(&'static str),
}

/// When a message is logged.
#[derive(Debug, Clone, Copy)]
pub enum Clock {
    /// Wall clock: `epoch_ns` (ns since the UNIX epoch) at `started`, plus the time since.
    Wall { epoch_ns: u64, started: std::time::Instant },
    /// A fixed time, set by the caller ([`McapOut::set_time`]).
    Fixed(u64),
}

impl Clock {
    /// The wall clock from now.
    pub fn wall() -> Self {
        Clock::Wall {
            epoch_ns: std::time::SystemTime::now()
                .duration_since(std::time::UNIX_EPOCH)
                .map_or(0, |d| d.as_nanos() as u64),
            started: std::time::Instant::now(),
        }
    }
}

/// An mcap writer with contrail's channels (see the module documentation).
pub struct McapOut<W: Write + Seek> {
    writer: Option<mcap::Writer<Guarded<W>>>,
    io_error: FirstError,
    /// Channel id of each of [`CHANNELS`] (empty until [`McapOut::register`]).
    channel_ids: Vec<u16>,
    sequence: Vec<u32>,
    clock: Clock,
    /// A time every message gets until [`McapOut::release_time`] (the messages of one
    /// increment share their time: cheaper, and they compress better).
    held: Option<u64>,
    buf: Vec<u8>,
}

impl<W: Write + Seek> McapOut<W> {
    /// Start a file on `out` (header written) with the given compression and library name.
    pub fn new(
        out: W,
        library: String,
        compression: Compression,
        message_indexes: bool,
        clock: Clock,
    ) -> Result<Self, OutError> {
        let (kind, level) = match compression.kind {
            ChunkCompression::Zstd => (Some(mcap::Compression::Zstd), compression.zstd_level as u32),
            ChunkCompression::Lz4 => (Some(mcap::Compression::Lz4), 0),
            ChunkCompression::None => (None, 0),
        };
        let options = mcap::WriteOptions::new()
            .profile(schemas::PROFILE)
            .library(library)
            .compression(kind)
            // the mcap crate passes the level on to zstd as an i32 (`level as i32`): a
            // negative level goes through as its two's complement
            .compression_level(level)
            // zstd's worker threads are created per chunk and compete with the solver for
            // the cores: the writer thread compresses on its own
            .compression_threads(0)
            .emit_message_indexes(message_indexes);
        let io_error = FirstError::default();
        let writer = options.create(Guarded::new(out, io_error.clone()));
        let out = McapOut {
            writer: None,
            io_error,
            channel_ids: Vec::new(),
            sequence: vec![0; CHANNELS.len()],
            clock,
            held: None,
            buf: Vec::with_capacity(1 << 16),
        };
        let writer = out.checked(writer)?;
        Ok(McapOut {
            writer: Some(writer),
            ..out
        })
    }

    /// `r`, unless the output failed first (that error is the cause).
    pub fn checked<T>(&self, r: Result<T, impl Into<OutError>>) -> Result<T, OutError> {
        match self.io_error.get() {
            Some(e) => Err(OutError::Io(e)),
            None => r.map_err(Into::into),
        }
    }

    fn writer(&mut self) -> Result<&mut mcap::Writer<Guarded<W>>, OutError> {
        self.writer.as_mut().ok_or(OutError::Finished)
    }

    /// Register every channel of [`CHANNELS`] with its schema, then write the metadata
    /// record `contrail.run` and the attachments.
    pub fn register(
        &mut self,
        metadata: BTreeMap<String, String>,
        attachments: &[mcap::Attachment],
    ) -> Result<(), OutError> {
        let w = self.writer()?;
        let mut ids = Vec::with_capacity(CHANNELS.len());
        let add = || -> Result<(), mcap::McapError> {
            for c in CHANNELS {
                let schema = w.add_schema(c.schema_name, "jsonschema", c.schema_text().as_bytes())?;
                let mut meta = BTreeMap::new();
                meta.insert("description".to_string(), c.description.to_string());
                ids.push(w.add_channel(schema, c.topic, "json", &meta)?);
            }
            w.write_metadata(&mcap::records::Metadata {
                name: schemas::METADATA_NAME.into(),
                metadata,
            })?;
            for a in attachments {
                w.attach(a)?;
            }
            Ok(())
        };
        let r = add();
        self.channel_ids = ids;
        self.checked(r)
    }

    /// The time a message written now gets.
    pub fn now(&self) -> u64 {
        if let Some(t) = self.held {
            return t;
        }
        match self.clock {
            Clock::Wall { epoch_ns, started } => epoch_ns + started.elapsed().as_nanos() as u64,
            Clock::Fixed(t) => t,
        }
    }

    /// Log every message at the current time until [`McapOut::release_time`].
    pub fn hold_time(&mut self) {
        self.held = None;
        self.held = Some(self.now());
    }

    /// Log messages at their own time again.
    pub fn release_time(&mut self) {
        self.held = None;
    }

    /// Log the next messages at `time_ns` (a [`Clock::Fixed`] output).
    pub fn set_time(&mut self, time_ns: u64) {
        if let Clock::Fixed(t) = &mut self.clock {
            *t = time_ns;
        }
    }

    /// Write `msg` as JSON on `topic`.
    pub fn put<T: Serialize + ?Sized>(&mut self, topic: &'static str, msg: &T) -> Result<(), OutError> {
        self.put_with(topic, |buf, _| serde_json::to_writer(buf, msg).map_err(OutError::from))
    }

    /// Write a message on `topic` whose bytes `fill` appends to the (empty) buffer it gets,
    /// with the message's log time.
    pub fn put_with(
        &mut self,
        topic: &'static str,
        fill: impl FnOnce(&mut Vec<u8>, u64) -> Result<(), OutError>,
    ) -> Result<(), OutError> {
        let idx = CHANNELS
            .iter()
            .position(|c| std::ptr::eq(c.topic, topic) || c.topic == topic)
            .ok_or(OutError::NotStarted(topic))?;
        let channel_id = *self.channel_ids.get(idx).ok_or(OutError::NotStarted(topic))?;
        let now = self.now();
        let mut buf = std::mem::take(&mut self.buf);
        buf.clear();
        let filled = fill(&mut buf, now);
        let header = mcap::records::MessageHeader {
            channel_id,
            sequence: self.sequence[idx],
            log_time: now,
            publish_time: now,
        };
        self.sequence[idx] = self.sequence[idx].wrapping_add(1);
        let r = match filled {
            Ok(()) => self.writer().and_then(|w| Ok(w.write_to_known_channel(&header, &buf)?)),
            Err(e) => Err(e),
        };
        self.buf = buf;
        self.checked(r)
    }

    /// Close the file (summary, footer): the output, and whether everything was written.
    pub fn finish(&mut self) -> Result<W, (Option<W>, OutError)> {
        let Some(mut writer) = self.writer.take() else {
            return Err((None, OutError::Finished));
        };
        let closed = writer.finish();
        let mut out = writer.into_inner();
        let _ = out.flush();
        let r = self.checked(closed.map(|_| ()));
        let out = out.into_inner();
        match r {
            Ok(()) => Ok(out),
            Err(e) => Err((Some(out), e)),
        }
    }
}
