//! The JSON Schemas in `schemas/` must be the ones generated from the record types (and the
//! Foxglove ones the ones embedded in recordings). Refresh them on purpose with
//! `CONTRAIL_BLESS=1 cargo test --test recording_schemas`. The schemas of format 2 stay in
//! `schemas/format2/` for older recordings.

use contrail::record::mcap::schemas::{self, CHANNELS};
use std::path::Path;

#[test]
fn checked_in_schemas_match_the_record_types() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("schemas");
    if std::env::var_os("CONTRAIL_BLESS").is_some() {
        schemas::write_all(&dir).expect("write schemas/");
    }
    let stale = schemas::stale(&dir);
    assert!(
        stale.is_empty(),
        "schemas/{{{}}} differ from the record types; if the change is intended, run \
         `CONTRAIL_BLESS=1 cargo test --test recording_schemas` and commit the files",
        stale.join(", ")
    );
}

#[test]
fn every_schema_is_a_2020_12_object_schema_and_documents_non_finite_reals() {
    for c in CHANNELS.iter().filter(|c| c.is_contrail()) {
        let v: serde_json::Value = serde_json::from_str(&c.schema_text()).unwrap();
        assert_eq!(
            v["$schema"], "https://json-schema.org/draft/2020-12/schema",
            "{}",
            c.file
        );
        assert_eq!(
            v["$id"],
            schemas::schema_id(c.file),
            "{}: the $id carries the format version",
            c.file
        );
        let text = c.schema_text();
        if c.topic != schemas::MODEL {
            assert!(text.contains("\"NaN\""), "{} does not document NaN", c.file);
        }
    }
}

#[test]
fn every_real_of_a_per_increment_record_can_carry_nan_and_infinity() {
    // a plain `f64` field has the schema {"type": "number", "format": "double"} and is written
    // as `null` when NaN, which no reader gets back: give it `#[serde(with = "Real")]`
    // (`Real2` for `[f64; 2]`, `Reals` for `Vec<f64>`, see src/record/real.rs)
    for c in CHANNELS.iter().filter(|c| c.is_contrail() && c.topic != schemas::MODEL) {
        let v: serde_json::Value = serde_json::from_str(&c.schema_text()).unwrap();
        let mut plain = Vec::new();
        find_doubles(&v, "", &mut plain);
        assert!(
            plain.is_empty(),
            "{}: plain f64 fields {plain:?}; add #[serde(with = \"Real\")] to them",
            c.file
        );
    }
}

fn find_doubles(v: &serde_json::Value, at: &str, out: &mut Vec<String>) {
    match v {
        serde_json::Value::Object(m) => {
            if m.get("format").and_then(|f| f.as_str()) == Some("double") {
                out.push(at.to_string());
            }
            for (k, x) in m {
                find_doubles(x, &format!("{at}/{k}"), out);
            }
        }
        serde_json::Value::Array(a) => {
            for (i, x) in a.iter().enumerate() {
                find_doubles(x, &format!("{at}/{i}"), out);
            }
        }
        _ => {}
    }
}

#[test]
fn the_format_2_schemas_stay_for_older_recordings() {
    // the recordings of format 2 embed these texts; interop validates them against them
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("schemas/format2");
    for (file, title) in [
        ("contact_point.schema.json", "ContactPointMessage"),
        ("pressure.schema.json", "PressureRecord"),
        ("increment.schema.json", "IncrementRecord"),
    ] {
        let text = std::fs::read_to_string(dir.join(file)).unwrap();
        let v: serde_json::Value = serde_json::from_str(&text).unwrap();
        assert_eq!(v["title"], title, "{file}");
        assert!(v.get("$id").is_none(), "{file} is the format-2 text, unchanged");
    }
}

#[test]
fn the_format_3_arrays_have_one_array_per_field() {
    let text = schemas::channel(schemas::CONTACT).unwrap().schema_text();
    let v: serde_json::Value = serde_json::from_str(&text).unwrap();
    let props = v["properties"].as_object().unwrap();
    for field in [
        "slave",
        "segment",
        "previous_segment",
        "xi",
        "xi_anchor",
        "gap",
        "normal_force",
        "trial_traction",
        "traction",
        "state",
        "crossing",
        "position",
        "contact_point",
        "normal",
        "tangent",
    ] {
        let f = &props[field];
        let is_array = f["type"] == "array" || f["$ref"] == "#/$defs/Reals";
        assert!(is_array, "/contact {field}: {f}");
    }
}
