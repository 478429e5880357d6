//! What the same content costs in format 2: the messages of a format-3 recording written
//! again in format 2's layout — one `/contact` message per point (`contrail.ContactPoint`),
//! `/positions` as `[x, y]` pairs, `/pressure` as a list of point objects, no `multiplier`
//! on penalty points (format 2 had none), the other contrail channels as they are, no
//! Foxglove channels — with the same mcap options as
//! `contrail run` (zstd level 1 by default, chunks of 1 MiB, message indexes).
//!
//! ```sh
//! contrail run strip-channel --set stepping.increments=4800 --set stepping.max_cutbacks=0 \
//!     --out f3.mcap
//! cargo run --release --example format2_size -- f3.mcap [--level N] [--no-index] \
//!     [--out f2.mcap] [--check golden-f2.mcap]
//! ```
//!
//! Prints the size of the file in both formats, per channel the bytes of the messages before
//! compression, and the ratio. `--check FILE` compares every rewritten message with the
//! messages of a recording written in format 2 by contrail itself, channel by channel (the
//! JSON values, so the rewrite is known to be format 2's layout): give it a format-2
//! recording and its `contrail convert` into format 3.

use contrail::record::mcap::arrays::{ContactArrays, PressureArrays};
use contrail::record::messages::{ContactPointMessage, ModelRecord, PackedPositions};
use std::collections::{BTreeMap, HashMap};
use std::io::Cursor;

type Messages = Vec<(String, Vec<u8>, u64)>;

/// What a recording holds besides its messages: the schema of each channel (name and
/// text), the metadata records and the attachments.
#[derive(Default)]
struct Extras {
    schemas: BTreeMap<String, (String, Vec<u8>)>,
    metadata: Vec<mcap::records::Metadata>,
    attachments: Vec<mcap::Attachment<'static>>,
}

/// The messages of `bytes` in log-time order (topic, data, log time), and the rest.
fn messages(bytes: &[u8]) -> (Messages, Extras) {
    let mut extras = Extras::default();
    let stream = mcap::MessageStream::new(bytes).expect("an MCAP file");
    let msgs = stream
        .map(|m| m.expect("a readable message"))
        .map(|m| {
            if let Some(s) = &m.channel.schema {
                let schema = (s.name.clone(), s.data.to_vec());
                extras.schemas.entry(m.channel.topic.clone()).or_insert(schema);
            }
            (m.channel.topic.clone(), m.data.to_vec(), m.log_time)
        })
        .collect();
    for record in mcap::read::LinearReader::new(bytes).expect("an MCAP file") {
        match record.expect("a readable record") {
            mcap::records::Record::Metadata(m) => extras.metadata.push(m),
            mcap::records::Record::Attachment { header, data, .. } => extras.attachments.push(mcap::Attachment {
                log_time: header.log_time,
                create_time: header.create_time,
                name: header.name,
                media_type: header.media_type,
                data: std::borrow::Cow::Owned(data.into_owned()),
            }),
            _ => {}
        }
    }
    (msgs, extras)
}

/// The schemas of format 2 for the channels whose layout format 3 changed.
fn format2_schemas(extras: &Extras) -> BTreeMap<String, (String, Vec<u8>)> {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("schemas/format2");
    let mut schemas = extras.schemas.clone();
    for (topic, name, file) in [
        ("/contact", "contrail.ContactPoint", "contact_point.schema.json"),
        ("/positions", "contrail.Positions", "positions.schema.json"),
        ("/pressure", "contrail.Pressure", "pressure.schema.json"),
    ] {
        let text = std::fs::read(dir.join(file)).expect("schemas/format2");
        schemas.insert(topic.to_string(), (name.to_string(), text));
    }
    schemas
}

/// The format-2 messages of one format-3 message (none for a Foxglove channel).
fn rewrite(topic: &str, data: &[u8], model: &Option<ModelRecord>) -> Vec<Vec<u8>> {
    let json = |v: &dyn erased::Json| v.to_vec();
    match topic {
        "/contact" => {
            let arrays: ContactArrays = serde_json::from_slice(data).expect("contact arrays");
            let model = model.as_ref().expect("/model before /contact");
            let points = arrays.records(model).expect("consistent arrays");
            points
                .into_iter()
                .map(|point| {
                    let text = json(&ContactPointMessage {
                        increment: arrays.increment,
                        t: arrays.t,
                        point,
                    });
                    without_penalty_multiplier(text)
                })
                .collect()
        }
        "/positions" => {
            let packed: PackedPositions = serde_json::from_slice(data).expect("packed positions");
            vec![json(&packed.unpack().expect("whole nodes"))]
        }
        "/pressure" => {
            let arrays: PressureArrays = serde_json::from_slice(data).expect("pressure arrays");
            vec![json(&arrays.record().expect("consistent arrays"))]
        }
        t if t.starts_with("/foxglove/") => Vec::new(),
        _ => vec![data.to_vec()],
    }
}

/// Format 2 had no `multiplier` field (the augmented Lagrangian came with format 3, which
/// writes it only for augmented pairs): a penalty point's `[NaN, NaN]` is left out.
fn without_penalty_multiplier(text: Vec<u8>) -> Vec<u8> {
    const NONE: &str = ",\"multiplier\":[\"NaN\",\"NaN\"]";
    let s = String::from_utf8(text).expect("JSON is UTF-8");
    s.replacen(NONE, "", 1).into_bytes()
}

mod erased {
    /// A value serialised to JSON bytes (object-safe).
    pub trait Json {
        fn to_vec(&self) -> Vec<u8>;
    }
    impl<T: serde::Serialize> Json for T {
        fn to_vec(&self) -> Vec<u8> {
            serde_json::to_vec(self).expect("serialisable")
        }
    }
}

/// Write `msgs` as an MCAP file with contrail's writer options, the given schemas, and the
/// metadata and attachments of `extras`.
fn write(
    msgs: &Messages,
    schemas: &BTreeMap<String, (String, Vec<u8>)>,
    extras: &Extras,
    level: i32,
    indexes: bool,
) -> Vec<u8> {
    let opts = mcap::WriteOptions::new()
        .profile("contrail")
        .compression(Some(mcap::Compression::Zstd))
        .compression_level(level as u32)
        .compression_threads(0)
        .emit_message_indexes(indexes);
    let mut w = opts.create(Cursor::new(Vec::new())).expect("a writer");
    let mut channels: HashMap<String, u16> = HashMap::new();
    let mut sequence: HashMap<u16, u32> = HashMap::new();
    for m in &extras.metadata {
        w.write_metadata(m).expect("metadata");
    }
    for a in &extras.attachments {
        w.attach(a).expect("attachment");
    }
    for (topic, data, time) in msgs {
        let id = *channels.entry(topic.clone()).or_insert_with(|| {
            let (name, text) = &schemas[topic];
            let schema = w.add_schema(name, "jsonschema", text).expect("schema");
            w.add_channel(schema, topic, "json", &BTreeMap::new()).expect("channel")
        });
        let seq = sequence.entry(id).or_insert(0);
        let header = mcap::records::MessageHeader {
            channel_id: id,
            sequence: *seq,
            log_time: *time,
            publish_time: *time,
        };
        *seq += 1;
        w.write_to_known_channel(&header, data).expect("written");
    }
    w.finish().expect("finished");
    w.into_inner().into_inner()
}

/// Bytes of the messages per channel (before compression).
fn per_channel(msgs: &Messages) -> BTreeMap<String, (usize, usize)> {
    let mut m = BTreeMap::new();
    for (topic, data, _) in msgs {
        let e = m.entry(topic.clone()).or_insert((0, 0));
        e.0 += 1;
        e.1 += data.len();
    }
    m
}

/// Compare the rewritten messages with those of a format-2 recording, channel by channel.
fn check(ours: &Messages, theirs: &Messages) {
    let by_topic = |msgs: &Messages| {
        let mut m: BTreeMap<String, Vec<serde_json::Value>> = BTreeMap::new();
        for (topic, data, _) in msgs {
            let v = serde_json::from_slice(data).expect("JSON");
            m.entry(topic.clone()).or_default().push(v);
        }
        m
    };
    let (a, b) = (by_topic(ours), by_topic(theirs));
    assert_eq!(a.keys().collect::<Vec<_>>(), b.keys().collect::<Vec<_>>(), "channels");
    for (topic, va) in &a {
        let vb = &b[topic];
        assert_eq!(va.len(), vb.len(), "{topic}: message counts");
        let same = va.iter().zip(vb).filter(|(x, y)| x == y).count();
        println!("check        {topic}: {same} of {} messages equal", va.len());
    }
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let value = |flag: &str| args.iter().position(|a| a == flag).map(|i| args[i + 1].clone());
    let level: i32 = value("--level").map_or(1, |l| l.parse().expect("a zstd level"));
    let indexes = !args.iter().any(|a| a == "--no-index");
    let bytes = std::fs::read(&args[0]).expect("the format-3 recording");
    let (f3, extras) = messages(&bytes);
    let mut model: Option<ModelRecord> = None;
    let mut f2 = Messages::new();
    for (topic, data, time) in &f3 {
        if topic == "/model" {
            model = Some(serde_json::from_slice(data).expect("the model"));
        }
        f2.extend(
            rewrite(topic, data, &model)
                .into_iter()
                .map(|d| (topic.clone(), d, *time)),
        );
    }
    let file2 = write(&f2, &format2_schemas(&extras), &extras, level, indexes);
    if let Some(out) = value("--out") {
        std::fs::write(&out, &file2).expect("written");
    }
    let f3_no_foxglove: Messages = f3.iter().filter(|m| !m.0.starts_with("/foxglove/")).cloned().collect();
    let file3_no_foxglove = write(&f3_no_foxglove, &extras.schemas, &extras, level, indexes);
    println!("format 3     {:>10} bytes (the file)", bytes.len());
    println!(
        "format 3     {:>10} bytes (written again without the Foxglove channels)",
        file3_no_foxglove.len()
    );
    println!(
        "format 2     {:>10} bytes (the same content in format 2's layout)",
        file2.len()
    );
    println!(
        "ratio        {:.2} (format 2 / format 3 file), {:.2} (without the Foxglove channels)",
        file2.len() as f64 / bytes.len() as f64,
        file2.len() as f64 / file3_no_foxglove.len() as f64
    );
    let (c3, c2) = (per_channel(&f3), per_channel(&f2));
    println!("channel      messages (3 / 2)   bytes before compression (3 / 2)");
    for (topic, (n3, b3)) in &c3 {
        let (n2, b2) = c2.get(topic).copied().unwrap_or((0, 0));
        println!("{topic:20} {n3:>7} {n2:>7}   {b3:>10} {b2:>10}");
    }
    if let Some(reference) = value("--check") {
        let (theirs, _) = messages(&std::fs::read(reference).expect("the format-2 recording"));
        check(&f2, &theirs);
    }
}
