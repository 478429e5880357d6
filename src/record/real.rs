//! Real numbers in JSON records. JSON has no NaN or ∞ (serde_json would write `null`), so
//! the records write them as the strings `"NaN"`, `"Infinity"` and `"-Infinity"`; finite
//! values stay plain numbers. Readers accept both.
//!
//! Used as `#[serde(with = "Real")]` on a record field: serde calls the inherent
//! `Real::serialize`/`Real::deserialize`, and schemars takes the same path as the type whose
//! schema documents the representation. [`Real2`] is a pair (`[f64; 2]`), [`Reals`] a list.

use schemars::{json_schema, JsonSchema, Schema, SchemaGenerator};
use serde::de::{self, Deserializer, SeqAccess, Visitor};
use serde::ser::{SerializeSeq, SerializeTuple, Serializer};
use std::borrow::Cow;
use std::fmt;

/// A JSON number, or one of the strings `"NaN"`, `"Infinity"`, `"-Infinity"`.
pub struct Real;
/// Two [`Real`]s (a 2D vector or point).
pub struct Real2;
/// A list of [`Real`]s.
pub struct Reals;
/// A list of [`Real2`]s (points or vectors; its schema is that of `Vec<Real2>`).
pub struct Real2s;
/// Three [`Real`]s (a 3D vector or point).
pub struct Real3;
/// A list of [`Real3`]s (its schema is that of `Vec<Real3>`).
pub struct Real3s;

/// The string written for a non-finite value (`None` when finite).
pub fn non_finite_name(x: f64) -> Option<&'static str> {
    if x.is_nan() {
        Some("NaN")
    } else if x == f64::INFINITY {
        Some("Infinity")
    } else if x == f64::NEG_INFINITY {
        Some("-Infinity")
    } else {
        None
    }
}

/// The value of a non-finite name (`None` for anything else).
pub fn parse_non_finite(s: &str) -> Option<f64> {
    match s {
        "NaN" => Some(f64::NAN),
        "Infinity" => Some(f64::INFINITY),
        "-Infinity" => Some(f64::NEG_INFINITY),
        _ => None,
    }
}

/// Serialises like [`Real`] (for use inside sequences and columns).
#[derive(Clone, Copy)]
pub struct Item(pub f64);

/// Serialises like [`Real2`] (for use inside sequences and columns).
#[derive(Clone, Copy)]
pub struct Item2(pub [f64; 2]);

impl serde::Serialize for Item2 {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        Real2::serialize(&self.0, s)
    }
}

impl serde::Serialize for Item {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        match non_finite_name(self.0) {
            Some(name) => s.serialize_str(name),
            None => s.serialize_f64(self.0),
        }
    }
}

struct ItemVisitor;

impl<'de> Visitor<'de> for ItemVisitor {
    type Value = f64;
    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("a number or one of \"NaN\", \"Infinity\", \"-Infinity\"")
    }
    fn visit_f64<E: de::Error>(self, v: f64) -> Result<f64, E> {
        Ok(v)
    }
    fn visit_i64<E: de::Error>(self, v: i64) -> Result<f64, E> {
        Ok(v as f64)
    }
    fn visit_u64<E: de::Error>(self, v: u64) -> Result<f64, E> {
        Ok(v as f64)
    }
    fn visit_str<E: de::Error>(self, v: &str) -> Result<f64, E> {
        parse_non_finite(v).ok_or_else(|| E::invalid_value(de::Unexpected::Str(v), &self))
    }
}

struct ItemDe(f64);

impl<'de> serde::Deserialize<'de> for ItemDe {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        d.deserialize_any(ItemVisitor).map(ItemDe)
    }
}

impl Real {
    pub fn serialize<S: Serializer>(x: &f64, s: S) -> Result<S::Ok, S::Error> {
        serde::Serialize::serialize(&Item(*x), s)
    }
    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<f64, D::Error> {
        d.deserialize_any(ItemVisitor)
    }
}

impl Real2 {
    pub fn serialize<S: Serializer>(x: &[f64; 2], s: S) -> Result<S::Ok, S::Error> {
        let mut t = s.serialize_tuple(2)?;
        t.serialize_element(&Item(x[0]))?;
        t.serialize_element(&Item(x[1]))?;
        t.end()
    }
    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<[f64; 2], D::Error> {
        let v: [ItemDe; 2] = serde::Deserialize::deserialize(d)?;
        Ok([v[0].0, v[1].0])
    }
}

impl Real3 {
    pub fn serialize<S: Serializer>(x: &[f64; 3], s: S) -> Result<S::Ok, S::Error> {
        let mut t = s.serialize_tuple(3)?;
        for v in x {
            t.serialize_element(&Item(*v))?;
        }
        t.end()
    }
    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<[f64; 3], D::Error> {
        let v: [ItemDe; 3] = serde::Deserialize::deserialize(d)?;
        Ok(v.map(|x| x.0))
    }
}

/// Serialises like [`Real3`] (inside sequences).
#[derive(Clone, Copy)]
pub struct Item3(pub [f64; 3]);

impl serde::Serialize for Item3 {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        Real3::serialize(&self.0, s)
    }
}

struct Item3De([f64; 3]);

impl<'de> serde::Deserialize<'de> for Item3De {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        Real3::deserialize(d).map(Item3De)
    }
}

impl Real3s {
    pub fn serialize<S: Serializer>(x: &[[f64; 3]], s: S) -> Result<S::Ok, S::Error> {
        let mut seq = s.serialize_seq(Some(x.len()))?;
        for v in x {
            seq.serialize_element(&Item3(*v))?;
        }
        seq.end()
    }
    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<Vec<[f64; 3]>, D::Error> {
        // a corrupt file may announce any length: `Vec`'s own visitor caps the hint
        let v: Vec<Item3De> = serde::Deserialize::deserialize(d)?;
        Ok(v.into_iter().map(|x| x.0).collect())
    }
}

struct SeqVisitor;

impl<'de> Visitor<'de> for SeqVisitor {
    type Value = Vec<f64>;
    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("a list of numbers")
    }
    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Vec<f64>, A::Error> {
        let mut out = Vec::with_capacity(seq.size_hint().unwrap_or(0));
        while let Some(ItemDe(x)) = seq.next_element()? {
            out.push(x);
        }
        Ok(out)
    }
}

impl Reals {
    pub fn serialize<S: Serializer>(x: &[f64], s: S) -> Result<S::Ok, S::Error> {
        let mut seq = s.serialize_seq(Some(x.len()))?;
        for v in x {
            seq.serialize_element(&Item(*v))?;
        }
        seq.end()
    }
    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<Vec<f64>, D::Error> {
        d.deserialize_seq(SeqVisitor)
    }
}

struct PairSeqVisitor;

impl<'de> Visitor<'de> for PairSeqVisitor {
    type Value = Vec<[f64; 2]>;
    fn expecting(&self, f: &mut fmt::Formatter) -> fmt::Result {
        f.write_str("a list of pairs of numbers")
    }
    fn visit_seq<A: SeqAccess<'de>>(self, mut seq: A) -> Result<Vec<[f64; 2]>, A::Error> {
        // a corrupt file may announce any length: the hint is capped
        let mut out = Vec::with_capacity(seq.size_hint().unwrap_or(0).min(4096));
        while let Some([ItemDe(x), ItemDe(y)]) = seq.next_element::<[ItemDe; 2]>()? {
            out.push([x, y]);
        }
        Ok(out)
    }
}

impl Real2s {
    pub fn serialize<S: Serializer>(x: &[[f64; 2]], s: S) -> Result<S::Ok, S::Error> {
        let mut seq = s.serialize_seq(Some(x.len()))?;
        for v in x {
            seq.serialize_element(&Item2(*v))?;
        }
        seq.end()
    }
    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<Vec<[f64; 2]>, D::Error> {
        d.deserialize_seq(PairSeqVisitor)
    }
}

impl JsonSchema for Real {
    fn schema_name() -> Cow<'static, str> {
        "Real".into()
    }
    fn json_schema(_: &mut SchemaGenerator) -> Schema {
        json_schema!({
            "description": "A real number. JSON has no NaN or infinity, so those are written as the strings \"NaN\", \"Infinity\" and \"-Infinity\"; finite values are JSON numbers.",
            "anyOf": [
                { "type": "number" },
                { "type": "string", "enum": ["NaN", "Infinity", "-Infinity"] }
            ]
        })
    }
}

impl JsonSchema for Real2 {
    fn schema_name() -> Cow<'static, str> {
        "Real2".into()
    }
    fn json_schema(g: &mut SchemaGenerator) -> Schema {
        let item = g.subschema_for::<Real>();
        json_schema!({
            "description": "A 2D vector (x, y) of Reals.",
            "type": "array",
            "items": item,
            "minItems": 2,
            "maxItems": 2
        })
    }
}

impl JsonSchema for Real3 {
    fn schema_name() -> Cow<'static, str> {
        "Real3".into()
    }
    fn json_schema(g: &mut SchemaGenerator) -> Schema {
        let item = g.subschema_for::<Real>();
        json_schema!({
            "description": "A 3D vector (x, y, z) of Reals.",
            "type": "array",
            "items": item,
            "minItems": 3,
            "maxItems": 3
        })
    }
}

impl JsonSchema for Reals {
    fn schema_name() -> Cow<'static, str> {
        "Reals".into()
    }
    fn json_schema(g: &mut SchemaGenerator) -> Schema {
        let item = g.subschema_for::<Real>();
        json_schema!({ "type": "array", "items": item })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde::{Deserialize, Serialize};

    #[derive(Serialize, Deserialize, Debug)]
    struct T {
        #[serde(with = "Real")]
        a: f64,
        #[serde(with = "Real2")]
        b: [f64; 2],
        #[serde(with = "Reals")]
        c: Vec<f64>,
    }

    #[derive(Serialize, Deserialize, Debug)]
    struct T3 {
        #[serde(with = "Real3")]
        a: [f64; 3],
        #[serde(with = "Real3s")]
        b: Vec<[f64; 3]>,
    }

    #[test]
    fn triples_round_trip_with_non_finite_values_as_strings() {
        let t = T3 {
            a: [f64::NAN, -0.5, 2.0],
            b: vec![[1.0, f64::INFINITY, 0.0], [0.25, 0.5, f64::NEG_INFINITY]],
        };
        let s = serde_json::to_string(&t).unwrap();
        assert_eq!(
            s,
            r#"{"a":["NaN",-0.5,2.0],"b":[[1.0,"Infinity",0.0],[0.25,0.5,"-Infinity"]]}"#
        );
        let back: T3 = serde_json::from_str(&s).unwrap();
        assert!(back.a[0].is_nan());
        assert_eq!(back.b[1][2], f64::NEG_INFINITY);
        assert!(serde_json::from_str::<T3>(r#"{"a":[1,2],"b":[]}"#).is_err());
        assert!(serde_json::from_str::<T3>(r#"{"a":[1,2,3],"b":[[1,2]]}"#).is_err());
    }

    #[test]
    fn non_finite_values_round_trip_as_strings() {
        let t = T {
            a: f64::NAN,
            b: [f64::INFINITY, 1.5],
            c: vec![f64::NEG_INFINITY, 0.25, 3.0],
        };
        let s = serde_json::to_string(&t).unwrap();
        assert_eq!(s, r#"{"a":"NaN","b":["Infinity",1.5],"c":["-Infinity",0.25,3.0]}"#);
        let back: T = serde_json::from_str(&s).unwrap();
        assert!(back.a.is_nan());
        assert_eq!(back.b[0], f64::INFINITY);
        assert_eq!(back.c, vec![f64::NEG_INFINITY, 0.25, 3.0]);
        let ints: T = serde_json::from_str(r#"{"a":1,"b":[2,-3],"c":[]}"#).unwrap();
        assert_eq!(ints.a, 1.0);
        assert!(serde_json::from_str::<T>(r#"{"a":"nan","b":[0,0],"c":[]}"#).is_err());
        assert!(serde_json::from_str::<T>(r#"{"a":null,"b":[0,0],"c":[]}"#).is_err());
    }
}
