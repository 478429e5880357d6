//! Reading a contrail MCAP recording back into the record types (for `inspect`, `diff`,
//! `replay` and the tests). Anything that is not a complete contrail recording is an error
//! with a message that says why, never a panic.

use super::chunks::{expand, split};
use super::validate_records::{check_model, check_records};
use crate::record::interface::InterfaceRecord;
use crate::record::mcap::arrays::{ContactArrays, PressureArrays};
use crate::record::mcap::schemas;
use crate::record::mcap::surface_arrays::SurfaceContactArrays;
use crate::record::messages::{ContactPointMessage, CrossingMessage, ModelRecord, PackedPositions, PositionsMessage};
use crate::record::pressure::PressureRecord;
use crate::record::surface_contact::SurfacePointRecord;
use crate::record::{ContactPointRecord, IncrementRecord, IterationRecord, LogRecord, Outcome};
use mcap::records::Record;
use serde::de::DeserializeOwned;
use std::collections::{BTreeMap, HashMap};
use std::path::Path;

/// A recording that could not be read.
#[derive(Debug, thiserror::Error)]
pub enum RecordingError {
    #[error("{path}: cannot read: {source}")]
    Read { path: String, source: std::io::Error },
    #[error("{path}: not a readable MCAP file (truncated or corrupt): {source}\n  hint: the file of a run that was killed is unfinished; `contrail recover {path} FIXED.mcap` salvages its complete chunks")]
    Corrupt { path: String, source: mcap::McapError },
    #[error("{path}: not a contrail recording ({detail})")]
    NotContrail { path: String, detail: String },
    #[error("{path}: recording format version {found}; this contrail reads versions {expected}")]
    Version {
        path: String,
        found: String,
        expected: String,
    },
    #[error("{path}: message {sequence} on {topic} does not match its schema: {source}")]
    Message {
        path: String,
        topic: String,
        sequence: u32,
        source: serde_json::Error,
    },
    #[error("{path}: {what}")]
    Incomplete { path: String, what: String },
    #[error("{path}: the record on {topic} is inconsistent: {what}")]
    Invalid { path: String, topic: String, what: String },
}

/// Everything in a recording.
#[derive(Debug, Clone)]
pub struct Recording {
    pub path: String,
    pub size_bytes: u64,
    pub library: String,
    /// The `contrail.run` metadata (scene, overrides, transfer, versions, parameters …).
    pub metadata: BTreeMap<String, String>,
    /// The scene file attachment (name, text).
    pub scene_file: Option<(String, String)>,
    pub model: ModelRecord,
    pub increments: Vec<IncrementRecord>,
    pub iterations: Vec<IterationRecord>,
    /// Contact points by increment number.
    pub contact: BTreeMap<usize, Vec<ContactPointRecord>>,
    pub crossings: Vec<CrossingMessage>,
    pub positions: Vec<PositionsMessage>,
    pub logs: Vec<LogRecord>,
    /// How the run ended (None: the recording has no outcome message).
    pub outcome: Option<Outcome>,
    /// Contact pressure profiles (`/pressure`; none in recordings made before the channel).
    pub pressure: Vec<PressureRecord>,
    /// Two-pass interfaces, both passes combined (`/interface`; none in recordings of runs
    /// without a two-pass pair or made before the channel).
    pub interface: Vec<InterfaceRecord>,
    /// 3D (node-to-surface) contact points by increment number, in pair and slave order
    /// (`/surface_contact`; none in 2D).
    pub surface: BTreeMap<usize, Vec<SurfacePointRecord>>,
    /// The rigid masters' offsets of the 3D pairs by increment (one per pair, zero for
    /// facets; `/surface_contact` `master_offset`).
    pub surface_offsets: BTreeMap<usize, Vec<[f64; 3]>>,
    /// Message count per topic.
    pub message_counts: BTreeMap<String, u64>,
    pub chunks: usize,
    /// Log time (ns since the UNIX epoch) of the `/model` message and of each increment's
    /// `/increment` message (what `contrail convert` gives the messages it writes).
    pub start_time: u64,
    pub increment_times: BTreeMap<usize, u64>,
}

impl Recording {
    /// Read a recording file.
    pub fn open(path: &Path) -> Result<Recording, RecordingError> {
        let name = path.display().to_string();
        let bytes = std::fs::read(path).map_err(|source| RecordingError::Read {
            path: name.clone(),
            source,
        })?;
        Recording::from_bytes(&bytes, &name)
    }

    /// The scene name (from the metadata).
    pub fn scene(&self) -> &str {
        self.metadata
            .get("scene")
            .map_or(self.model.name.as_str(), String::as_str)
    }

    /// A JSON list in the metadata (`overrides`, `transfer`).
    pub fn metadata_list(&self, key: &str) -> Vec<String> {
        self.metadata
            .get(key)
            .and_then(|v| serde_json::from_str(v).ok())
            .unwrap_or_default()
    }

    /// Parse a recording held in memory; `name` is used in error messages.
    pub fn from_bytes(bytes: &[u8], name: &str) -> Result<Recording, RecordingError> {
        let (st, mut b, chunks) = read_all_records(bytes, name)?;
        let State {
            profile,
            library,
            metadata,
            scene_file,
            ..
        } = st;
        let metadata = check_header(profile.as_deref(), &library, metadata, name)?;
        let model = b.model.take().ok_or_else(|| RecordingError::Incomplete {
            path: name.to_string(),
            what: format!("no message on {}", schemas::MODEL),
        })?;
        check_model(&model).map_err(|what| RecordingError::Invalid {
            path: name.to_string(),
            topic: schemas::MODEL.to_string(),
            what,
        })?;
        b.expand_arrays(&model)
            .map_err(|(topic, what)| RecordingError::Invalid {
                path: name.to_string(),
                topic,
                what,
            })?;
        super::restore::restore_out_of_reach(&mut b.contact, &b.positions, &b.increments);
        check_records(&model, &b).map_err(|(topic, what)| RecordingError::Invalid {
            path: name.to_string(),
            topic,
            what,
        })?;
        Ok(Recording {
            path: name.to_string(),
            size_bytes: bytes.len() as u64,
            library,
            metadata,
            scene_file,
            model,
            increments: b.increments,
            iterations: b.iterations,
            contact: b.contact,
            crossings: b.crossings,
            positions: b.positions,
            logs: b.logs,
            outcome: b.outcome,
            pressure: b.pressure,
            interface: b.interface,
            surface: b.surface,
            surface_offsets: b.surface_offsets,
            message_counts: b.counts,
            chunks,
            start_time: b.start_time,
            increment_times: b.increment_times,
        })
    }

    /// 3D contact points of an increment (empty if none were recorded).
    pub fn surface_at(&self, increment: usize) -> &[SurfacePointRecord] {
        self.surface.get(&increment).map_or(&[], Vec::as_slice)
    }

    /// Contact points of an increment (empty if none were recorded).
    pub fn contact_at(&self, increment: usize) -> &[ContactPointRecord] {
        self.contact.get(&increment).map_or(&[], Vec::as_slice)
    }
}

/// Every record of the file, chunks opened with bounded work (see `chunks`), CRCs checked:
/// the state of the header and metadata, the messages sorted by channel, and the number of
/// chunks.
fn read_all_records(bytes: &[u8], name: &str) -> Result<(State, Builder, usize), RecordingError> {
    let corrupt = |source| RecordingError::Corrupt {
        path: name.to_string(),
        source,
    };
    let mut st = State::default();
    let mut b = Builder::default();
    let mut reader = mcap::sans_io::LinearReader::new_with_options(
        mcap::sans_io::LinearReaderOptions::default()
            .with_emit_chunks(true)
            .with_validate_data_section_crc(true)
            .with_validate_summary_section_crc(true)
            .with_check_finishes_after_end_magic(true)
            .with_record_length_limit(length_limit(bytes.len())),
    );
    let mut rest = bytes;
    let mut chunks = 0usize;
    while let Some(event) = reader.next_event() {
        let (opcode, data) = match event.map_err(corrupt)? {
            mcap::sans_io::LinearReadEvent::ReadRequest(need) => {
                let n = need.min(rest.len());
                reader.insert(n).copy_from_slice(&rest[..n]);
                reader.notify_read(n);
                rest = &rest[n..];
                continue;
            }
            mcap::sans_io::LinearReadEvent::Record { opcode, data } => (opcode, data),
        };
        let record = mcap::parse_record(opcode, data).map_err(corrupt)?;
        if let Record::Chunk { header, data } = record {
            chunks += 1;
            let content = expand(&header, &data, length_limit(bytes.len()) as u64).map_err(corrupt)?;
            for inner in split(&content) {
                let (opcode, data) = inner.map_err(corrupt)?;
                let record = mcap::parse_record(opcode, data).map_err(corrupt)?;
                st.record(record, &mut b, name)?;
            }
        } else {
            st.record(record, &mut b, name)?;
        }
    }
    Ok((st, b, chunks))
}

/// A contrail recording of a readable format: its profile, its metadata (returned) and the
/// metadata's format version.
fn check_header(
    profile: Option<&str>,
    library: &str,
    metadata: Option<BTreeMap<String, String>>,
    name: &str,
) -> Result<BTreeMap<String, String>, RecordingError> {
    let not_ours = |detail: String| RecordingError::NotContrail {
        path: name.to_string(),
        detail,
    };
    match profile {
        Some(schemas::PROFILE) => {}
        Some(p) => {
            let by = if library.is_empty() {
                String::new()
            } else {
                format!(" written by `{library}`")
            };
            return Err(not_ours(format!(
                "MCAP profile `{p}`{by}, expected `{}`",
                schemas::PROFILE
            )));
        }
        None => return Err(not_ours("no MCAP header".into())),
    }
    let metadata = metadata.ok_or_else(|| not_ours(format!("no `{}` metadata", schemas::METADATA_NAME)))?;
    let version = metadata.get("format_version").cloned().unwrap_or_default();
    if !schemas::READABLE_VERSIONS.contains(&version.as_str()) {
        return Err(RecordingError::Version {
            path: name.to_string(),
            found: version,
            expected: schemas::READABLE_VERSIONS.join(", "),
        });
    }
    Ok(metadata)
}

/// Largest record (a decompressed chunk included) a corrupt length field may announce before
/// it is refused rather than allocated: JSON compresses well, but not 200-fold.
fn length_limit(file_len: usize) -> usize {
    file_len.saturating_mul(200).clamp(64 << 20, 4 << 30)
}

/// What the file-level records said (header, channels, metadata, scene attachment).
#[derive(Default)]
struct State {
    profile: Option<String>,
    library: String,
    metadata: Option<BTreeMap<String, String>>,
    scene_file: Option<(String, String)>,
    topics: HashMap<u16, (String, String)>,
    /// Encoding and name of each schema.
    schemas: HashMap<u16, (String, String)>,
}

impl State {
    fn record(&mut self, record: Record, b: &mut Builder, name: &str) -> Result<(), RecordingError> {
        let not_ours = |detail: String| RecordingError::NotContrail {
            path: name.to_string(),
            detail,
        };
        match record {
            Record::Header(h) => {
                self.profile = Some(h.profile);
                self.library = h.library;
            }
            Record::Schema { header, .. } => {
                self.schemas.insert(header.id, (header.encoding, header.name));
            }
            Record::Channel(c) => {
                let (encoding, schema) = self.schemas.get(&c.schema_id).cloned().unwrap_or_default();
                if schemas::channel(&c.topic).is_some() {
                    if c.message_encoding != "json" {
                        return Err(not_ours(format!(
                            "channel {} has message encoding `{}`, expected json",
                            c.topic, c.message_encoding
                        )));
                    }
                    if encoding != "jsonschema" {
                        return Err(not_ours(format!("channel {} has no jsonschema schema", c.topic)));
                    }
                }
                self.topics.insert(c.id, (c.topic, schema));
            }
            Record::Metadata(m) if m.name == schemas::METADATA_NAME => self.metadata = Some(m.metadata),
            Record::Attachment { header, data, .. } if header.media_type == "application/toml" => {
                self.scene_file = Some((header.name, String::from_utf8_lossy(&data).into_owned()));
            }
            Record::Message { header, data } => {
                let (topic, schema) = self
                    .topics
                    .get(&header.channel_id)
                    .ok_or_else(|| RecordingError::Corrupt {
                        path: name.to_string(),
                        source: mcap::McapError::UnknownChannel(header.sequence, header.channel_id),
                    })?;
                b.message(topic, schema, &header, &data)
                    .map_err(|(topic, sequence, source)| RecordingError::Message {
                        path: name.to_string(),
                        topic,
                        sequence,
                        source,
                    })?;
            }
            _ => {}
        }
        Ok(())
    }
}

/// The records of a recording as they are read.
#[derive(Default)]
pub(crate) struct Builder {
    pub(crate) model: Option<ModelRecord>,
    pub(crate) increments: Vec<IncrementRecord>,
    pub(crate) iterations: Vec<IterationRecord>,
    pub(crate) contact: BTreeMap<usize, Vec<ContactPointRecord>>,
    pub(crate) crossings: Vec<CrossingMessage>,
    pub(crate) positions: Vec<PositionsMessage>,
    pub(crate) logs: Vec<LogRecord>,
    pub(crate) outcome: Option<Outcome>,
    pub(crate) pressure: Vec<PressureRecord>,
    pub(crate) interface: Vec<InterfaceRecord>,
    pub(crate) surface: BTreeMap<usize, Vec<SurfacePointRecord>>,
    pub(crate) surface_offsets: BTreeMap<usize, Vec<[f64; 3]>>,
    pub(crate) counts: BTreeMap<String, u64>,
    /// Format-3 messages, made into records once the model is known.
    contact_arrays: Vec<ContactArrays>,
    pressure_arrays: Vec<PressureArrays>,
    surface_arrays: Vec<SurfaceContactArrays>,
    packed_positions: Vec<PackedPositions>,
    start_time: u64,
    increment_times: BTreeMap<usize, u64>,
}

type MessageError = (String, u32, serde_json::Error);

fn parse<T: DeserializeOwned>(topic: &str, sequence: u32, data: &[u8]) -> Result<T, MessageError> {
    serde_json::from_slice(data).map_err(|e| (topic.to_string(), sequence, e))
}

impl Builder {
    /// Take one message of `topic`, whose schema is named `schema` (the layout of `/contact`
    /// and `/pressure` depends on it: points and profiles of objects in formats 1 and 2,
    /// arrays in format 3).
    fn message(
        &mut self,
        topic: &str,
        schema: &str,
        header: &mcap::records::MessageHeader,
        data: &[u8],
    ) -> Result<(), MessageError> {
        *self.counts.entry(topic.to_string()).or_default() += 1;
        let seq = header.sequence;
        match topic {
            schemas::MODEL => {
                self.model = Some(parse(topic, seq, data)?);
                self.start_time = header.log_time;
            }
            schemas::INCREMENT => {
                let inc: IncrementRecord = parse(topic, seq, data)?;
                self.increment_times.insert(inc.increment, header.log_time);
                self.increments.push(inc);
            }
            schemas::ITERATION => self.iterations.push(parse(topic, seq, data)?),
            schemas::CONTACT if schema == schemas::CONTACT_ARRAYS => {
                self.contact_arrays.push(parse(topic, seq, data)?);
            }
            schemas::CONTACT => {
                let m: ContactPointMessage = parse(topic, seq, data)?;
                self.contact.entry(m.increment).or_default().push(m.point);
            }
            schemas::CROSSING => self.crossings.push(parse(topic, seq, data)?),
            schemas::POSITIONS if schema == schemas::PACKED_POSITIONS => {
                self.packed_positions.push(parse(topic, seq, data)?);
            }
            schemas::POSITIONS => self.positions.push(parse(topic, seq, data)?),
            schemas::LOG => self.logs.push(parse(topic, seq, data)?),
            schemas::OUTCOME => self.outcome = Some(parse(topic, seq, data)?),
            schemas::PRESSURE if schema == schemas::PRESSURE_ARRAYS => {
                self.pressure_arrays.push(parse(topic, seq, data)?);
            }
            schemas::PRESSURE => self.pressure.push(parse(topic, seq, data)?),
            schemas::INTERFACE => self.interface.push(parse(topic, seq, data)?),
            schemas::SURFACE_CONTACT => self.surface_arrays.push(parse(topic, seq, data)?),
            _ => {}
        }
        Ok(())
    }

    /// Make the format-3 messages into records (labels from `model`); an error names the
    /// topic and what is wrong.
    fn expand_arrays(&mut self, model: &ModelRecord) -> Result<(), (String, String)> {
        for a in std::mem::take(&mut self.contact_arrays) {
            let points = a.records(model).map_err(|e| (schemas::CONTACT.to_string(), e))?;
            self.contact.entry(a.increment).or_default().extend(points);
        }
        for p in std::mem::take(&mut self.packed_positions) {
            self.positions
                .push(p.unpack_for(model).map_err(|e| (schemas::POSITIONS.to_string(), e))?);
        }
        let positions: BTreeMap<usize, &PositionsMessage> = self.positions.iter().map(|p| (p.increment, p)).collect();
        for a in std::mem::take(&mut self.surface_arrays) {
            let mut points = a
                .records(model)
                .map_err(|e| (schemas::SURFACE_CONTACT.to_string(), e))?;
            let at = positions.get(&a.increment).copied();
            super::restore::restore_surface_out_of_reach(&mut points, (a.pair, &a.pair_name), model, at);
            self.surface.entry(a.increment).or_default().extend(points);
            self.surface_offsets
                .entry(a.increment)
                .or_default()
                .push(a.master_offset);
        }
        for a in std::mem::take(&mut self.pressure_arrays) {
            self.pressure
                .push(a.record().map_err(|e| (schemas::PRESSURE.to_string(), e))?);
        }
        Ok(())
    }
}
