//! Salvage the complete chunks of an unfinished or damaged recording (a run killed by
//! SIGKILL, a power loss, a full disk) into a new, finalised recording.
//!
//! The file is walked record by record with every length checked; each chunk is
//! decompressed with bounded work and kept only if its CRC matches (a damaged chunk whose
//! length is intact is skipped, and the walk goes on); the walk stops at the first record
//! that runs past the end of the file. Metadata and the scene attachment are copied, the
//! messages of the contrail channels are written again in their order, on channels with the
//! schemas the file had (a recording of an older format stays one), and — unless the
//! salvaged part already ends with one — an `/outcome` is appended that says the run was cut
//! off and the file recovered (a `failed` outcome whose reason starts with [`RECOVERED`]).

use super::chunks::{expand, split};
use crate::record::atomic_file::{FirstError, Guarded};
use crate::record::mcap::schemas::{self, CHANNELS};
use crate::record::{IncrementRecord, Outcome};
use mcap::records::{op, MessageHeader, Metadata, Record};
use std::collections::{BTreeMap, HashMap};
use std::io::{Seek, Write};

/// How the reason of an appended outcome begins.
pub const RECOVERED: &str = "recovered by `contrail recover`";

/// A file that could not be salvaged at all.
#[derive(Debug, thiserror::Error)]
pub enum RecoverError {
    #[error("{path}: not an MCAP file (it does not start with the MCAP magic bytes)")]
    NotMcap { path: String },
    #[error("{path}: nothing to salvage: {what}")]
    Nothing { path: String, what: String },
    #[error("{path}: cannot write the recovered recording: {source}")]
    Write { path: String, source: mcap::McapError },
}

/// What was salvaged.
#[derive(Debug, Clone, Default)]
pub struct RecoverReport {
    /// Chunks whose CRC matched and whose records were kept.
    pub chunks_kept: usize,
    /// Chunks that were skipped (bad CRC, bad compression, bad records).
    pub chunks_dropped: usize,
    /// Messages written on contrail channels (the appended outcome not included).
    pub messages: usize,
    /// Converged increments salvaged, and the last of them.
    pub increments: usize,
    pub last_increment: Option<usize>,
    /// Why the walk stopped (`end of data` for a finalised file).
    pub stopped: String,
    /// Whether an `/outcome` was appended (false: the salvaged part had one).
    pub outcome_appended: bool,
}

struct Message {
    topic: String,
    header: MessageHeader,
    data: Vec<u8>,
}

/// A schema of the damaged file: name, encoding, text.
type SchemaText = (String, String, Vec<u8>);

#[derive(Default)]
struct Salvage {
    library: String,
    metadata: Vec<Metadata>,
    attachments: Vec<mcap::Attachment<'static>>,
    /// Topic and schema id of each channel.
    topics: HashMap<u16, (String, u16)>,
    schemas: HashMap<u16, SchemaText>,
    /// The schema each contrail topic had (from its channel).
    topic_schemas: HashMap<String, SchemaText>,
    messages: Vec<Message>,
}

impl Salvage {
    fn record(&mut self, r: Record) {
        match r {
            Record::Header(h) => self.library = h.library,
            Record::Schema { header, data } => {
                let text = (header.name, header.encoding, data.into_owned());
                self.schemas.insert(header.id, text);
            }
            Record::Channel(c) => {
                if let Some(schema) = self.schemas.get(&c.schema_id) {
                    if schemas::channel(&c.topic).is_some() {
                        self.topic_schemas.insert(c.topic.clone(), schema.clone());
                    }
                }
                self.topics.insert(c.id, (c.topic, c.schema_id));
            }
            Record::Metadata(m) => self.metadata.push(m),
            Record::Attachment { header, data, .. } => self.attachments.push(mcap::Attachment {
                log_time: header.log_time,
                create_time: header.create_time,
                name: header.name,
                media_type: header.media_type,
                data: std::borrow::Cow::Owned(data.into_owned()),
            }),
            Record::Message { header, data } => {
                if let Some((topic, _)) = self.topics.get(&header.channel_id) {
                    if schemas::channel(topic).is_some() {
                        self.messages.push(Message {
                            topic: topic.clone(),
                            header,
                            data: data.into_owned(),
                        });
                    }
                }
            }
            _ => {}
        }
    }
}

/// Salvage `bytes` (the damaged file, `name` in messages) into a new recording on `out`.
pub fn recover<W: Write + Seek>(bytes: &[u8], name: &str, out: W) -> Result<(W, RecoverReport), RecoverError> {
    if bytes.len() < mcap::MAGIC.len() || &bytes[..mcap::MAGIC.len()] != mcap::MAGIC {
        return Err(RecoverError::NotMcap { path: name.into() });
    }
    let mut s = Salvage::default();
    let mut rep = RecoverReport {
        stopped: "end of file".into(),
        ..RecoverReport::default()
    };
    let limit = (bytes.len() as u64).saturating_mul(200).max(64 << 20);
    for rec in split(&bytes[mcap::MAGIC.len()..]) {
        let (opcode, body) = match rec {
            Ok(r) => r,
            Err(e) => {
                rep.stopped = format!("an unfinished record ({e})");
                break;
            }
        };
        if opcode == op::DATA_END || opcode == op::FOOTER {
            rep.stopped = "end of data".into();
            break;
        }
        let Ok(record) = mcap::parse_record(opcode, body) else {
            if opcode == op::CHUNK {
                rep.chunks_dropped += 1;
            }
            continue;
        };
        if let Record::Chunk { header, data } = record {
            let Ok(content) = expand(&header, &data, limit) else {
                rep.chunks_dropped += 1;
                continue;
            };
            let inner: Result<Vec<Record>, _> = split(&content)
                .map(|r| r.and_then(|(op, b)| mcap::parse_record(op, b)))
                .collect();
            match inner {
                Ok(records) => {
                    rep.chunks_kept += 1;
                    records.into_iter().for_each(|r| s.record(r));
                }
                Err(_) => rep.chunks_dropped += 1,
            }
        } else {
            s.record(record);
        }
    }
    if s.messages.is_empty() {
        return Err(RecoverError::Nothing {
            path: name.into(),
            what: format!(
                "no complete chunk with contrail messages before {} ({} chunks dropped)",
                rep.stopped, rep.chunks_dropped
            ),
        });
    }
    write(s, name, out, rep)
}

/// Every channel of this build, each with the file's own schema for its topic (a recording of
/// an older format keeps its layout), or this build's when the file's was lost: the channel
/// id of each topic.
fn add_channels<W: Write + Seek>(
    w: &mut mcap::Writer<W>,
    s: &Salvage,
) -> Result<HashMap<&'static str, u16>, mcap::McapError> {
    let mut ids = HashMap::new();
    for c in CHANNELS {
        let schema = match s.topic_schemas.get(c.topic) {
            Some((name, encoding, data)) => w.add_schema(name, encoding, data),
            None => w.add_schema(c.schema_name, "jsonschema", c.schema_text().as_bytes()),
        }?;
        let mut meta = BTreeMap::new();
        meta.insert("description".to_string(), c.description.to_string());
        ids.insert(c.topic, w.add_channel(schema, c.topic, "json", &meta)?);
    }
    Ok(ids)
}

/// The outcome appended to a recording that has none: failed during increment `during`,
/// cut off, with the chunks kept and dropped.
fn cut_off(during: usize, t: f64, rep: &RecoverReport) -> Outcome {
    Outcome::Failed {
        increment: during,
        t,
        reason: format!(
            "{RECOVERED}: the recording was cut off during increment {during} (the run was killed, lost power or filled its disk); {} complete chunks kept, {} damaged chunks dropped",
            rep.chunks_kept, rep.chunks_dropped
        ),
        residuals: Vec::new(),
        kind: crate::record::FailureKind::Recording,
        points: Vec::new(),
    }
}

fn write<W: Write + Seek>(
    s: Salvage,
    name: &str,
    out: W,
    mut rep: RecoverReport,
) -> Result<(W, RecoverReport), RecoverError> {
    let werr = |source| RecoverError::Write {
        path: name.to_string(),
        source,
    };
    let library = if s.library.is_empty() {
        format!("contrail {} (recovered)", crate::VERSION)
    } else {
        format!("{} (recovered by contrail {})", s.library, crate::VERSION)
    };
    // the mcap writer cannot recover from an I/O error inside a chunk: it never sees one
    let io = FirstError::default();
    let mut w = mcap::WriteOptions::new()
        .profile(schemas::PROFILE)
        .library(library)
        .compression(Some(mcap::Compression::Zstd))
        .create(Guarded::new(out, io.clone()))
        .map_err(werr)?;
    let ids = add_channels(&mut w, &s).map_err(werr)?;
    for m in &s.metadata {
        w.write_metadata(m).map_err(werr)?;
    }
    for a in &s.attachments {
        w.attach(a).map_err(werr)?;
    }
    let mut last_time = 0;
    let mut last_t = 0.0;
    let mut outcome_seen = false;
    let mut outcome_seq = 0;
    for m in &s.messages {
        let Some(&channel_id) = ids.get(m.topic.as_str()) else {
            continue;
        };
        let header = MessageHeader { channel_id, ..m.header };
        w.write_to_known_channel(&header, &m.data).map_err(werr)?;
        rep.messages += 1;
        last_time = last_time.max(m.header.log_time);
        match m.topic.as_str() {
            schemas::INCREMENT => {
                if let Ok(inc) = serde_json::from_slice::<IncrementRecord>(&m.data) {
                    rep.increments += 1;
                    rep.last_increment = Some(inc.increment);
                    last_t = inc.t;
                }
            }
            schemas::OUTCOME => {
                outcome_seen = true;
                outcome_seq = m.header.sequence.saturating_add(1);
            }
            _ => {}
        }
    }
    if !outcome_seen {
        let during = rep.last_increment.map_or(1, |i| i.saturating_add(1));
        let outcome = cut_off(during, last_t, &rep);
        let data = serde_json::to_vec(&outcome).map_err(|e| werr(mcap::McapError::Io(e.into())))?;
        let channel_id = *ids
            .get(schemas::OUTCOME)
            .ok_or_else(|| werr(mcap::McapError::UnknownChannel(outcome_seq, 0)))?;
        let header = MessageHeader {
            channel_id,
            sequence: outcome_seq,
            log_time: last_time,
            publish_time: last_time,
        };
        w.write_to_known_channel(&header, &data).map_err(werr)?;
        rep.outcome_appended = true;
    }
    w.finish().map_err(werr)?;
    let mut out = w.into_inner();
    let _ = out.flush();
    if let Some(e) = io.get() {
        return Err(werr(mcap::McapError::Io(e)));
    }
    Ok((out.into_inner(), rep))
}
