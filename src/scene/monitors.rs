//! The `monitor` key of a scene: one table (`[monitor]`) or an array of tables
//! (`[[monitor]]`, one per monitor, like `[[body]]` and `[[contact]]`).

use super::types::MonitorSpec;
use schemars::{json_schema, JsonSchema, Schema, SchemaGenerator};
use serde::de::value::{MapAccessDeserializer, SeqAccessDeserializer};
use serde::de::{MapAccess, SeqAccess, Visitor};
use serde::{Deserialize, Deserializer, Serialize, Serializer};
use std::borrow::Cow;

/// The monitors of a scene, in order; `[monitor]` is a list of one.
#[derive(Debug, Clone, Default)]
pub struct Monitors(pub Vec<MonitorSpec>);

impl std::ops::Deref for Monitors {
    type Target = [MonitorSpec];
    fn deref(&self) -> &[MonitorSpec] {
        &self.0
    }
}

impl Serialize for Monitors {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        self.0.serialize(s)
    }
}

struct OneOrMany;

impl<'de> Visitor<'de> for OneOrMany {
    type Value = Monitors;
    fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        f.write_str("a [monitor] table or [[monitor]] tables")
    }
    fn visit_map<A: MapAccess<'de>>(self, map: A) -> Result<Monitors, A::Error> {
        MonitorSpec::deserialize(MapAccessDeserializer::new(map)).map(|m| Monitors(vec![m]))
    }
    fn visit_seq<A: SeqAccess<'de>>(self, seq: A) -> Result<Monitors, A::Error> {
        Vec::<MonitorSpec>::deserialize(SeqAccessDeserializer::new(seq)).map(Monitors)
    }
}

impl<'de> Deserialize<'de> for Monitors {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Monitors, D::Error> {
        d.deserialize_any(OneOrMany)
    }
}

impl JsonSchema for Monitors {
    fn schema_name() -> Cow<'static, str> {
        "Monitors".into()
    }
    fn json_schema(g: &mut SchemaGenerator) -> Schema {
        let one = g.subschema_for::<MonitorSpec>();
        json_schema!({
            "description": "Load–displacement monitors: one `[monitor]` table or several `[[monitor]]` tables. Each is a named column of the CSV, a record of `/increment` and a curve of the rerun view; the first is the one summaries, `contrail plot` and sweeps use by default.",
            "anyOf": [
                one.clone(),
                { "type": "array", "items": one }
            ]
        })
    }
}
