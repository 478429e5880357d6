//! The JSON Schemas in `schemas/` must be the ones generated from the record types.
//! Refresh them on purpose with `CONTRAIL_BLESS=1 cargo test --test recording_schemas`.

use contrail::record::schemas::{self, CHANNELS};
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
    for c in CHANNELS {
        let v: serde_json::Value = serde_json::from_str(&c.schema_text()).unwrap();
        assert_eq!(
            v["$schema"], "https://json-schema.org/draft/2020-12/schema",
            "{}",
            c.file
        );
        let text = c.schema_text();
        if c.topic != schemas::MODEL {
            assert!(text.contains("\"NaN\""), "{} does not document NaN", c.file);
        }
    }
}
