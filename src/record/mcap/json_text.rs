//! Writing JSON text by hand into a byte buffer, for the messages whose layout is fixed by
//! someone else's schema (Foxglove's) and whose numbers are for display: the same text as
//! serde_json would write, without its per-value dispatch.

use std::io::Write;

/// Append `s` as it is (a piece of JSON).
pub fn raw(out: &mut Vec<u8>, s: &str) {
    out.extend_from_slice(s.as_bytes());
}

/// Append `s` as a JSON string (quoted and escaped).
pub fn string(out: &mut Vec<u8>, s: &str) {
    // writing into a Vec cannot fail, and a &str is always valid JSON string content
    let _ = serde_json::to_writer(&mut *out, s);
}

/// Append a non-negative integer.
pub fn uint(out: &mut Vec<u8>, n: u64) {
    out.extend_from_slice(itoa::Buffer::new().format(n).as_bytes());
}

/// Append `x` rounded to single precision (display coordinates: 7 significant digits are
/// plenty and half the text of a double); a non-finite value is written as 0, since JSON
/// has no NaN and Foxglove's schemas want numbers.
pub fn real32(out: &mut Vec<u8>, x: f64) {
    let x = x as f32;
    if x.is_finite() {
        out.extend_from_slice(ryu::Buffer::new().format_finite(x).as_bytes());
    } else {
        out.push(b'0');
    }
}

/// A point drawn in 3D: a point of the model's plane lies at `z = 0`.
pub trait Xyz: Copy {
    fn xyz(self) -> [f64; 3];
}

impl Xyz for [f64; 2] {
    fn xyz(self) -> [f64; 3] {
        [self[0], self[1], 0.0]
    }
}

impl Xyz for [f64; 3] {
    fn xyz(self) -> [f64; 3] {
        self
    }
}

/// Append `{"x":…,"y":…,"z":…}` (single precision).
pub fn point3(out: &mut Vec<u8>, p: impl Xyz) {
    let [x, y, z] = p.xyz();
    raw(out, "{\"x\":");
    real32(out, x);
    raw(out, ",\"y\":");
    real32(out, y);
    raw(out, ",\"z\":");
    if z == 0.0 {
        // the plane's points as they always were written
        raw(out, "0");
    } else {
        real32(out, z);
    }
    raw(out, "}");
}

/// Append `{"r":…,"g":…,"b":…,"a":…}` from 8-bit channels (Foxglove colours are 0–1).
pub fn colour(out: &mut Vec<u8>, c: [u8; 4]) {
    let _ = write!(
        out,
        "{{\"r\":{},\"g\":{},\"b\":{},\"a\":{}}}",
        ch(c[0]),
        ch(c[1]),
        ch(c[2]),
        ch(c[3])
    );
}

/// An 8-bit colour channel as a fraction with 3 decimals.
fn ch(v: u8) -> f32 {
    (v as f32 / 255.0 * 1000.0).round() / 1000.0
}

/// Append `{"sec":…,"nsec":…}` for a time in nanoseconds since the UNIX epoch.
pub fn time(out: &mut Vec<u8>, ns: u64) {
    raw(out, "{\"sec\":");
    uint(out, ns / 1_000_000_000);
    raw(out, ",\"nsec\":");
    uint(out, ns % 1_000_000_000);
    raw(out, "}");
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pieces_are_valid_json() {
        let mut b = Vec::new();
        raw(&mut b, "[");
        point3(&mut b, [1.5, f64::NAN]);
        raw(&mut b, ",");
        colour(&mut b, [255, 0, 128, 255]);
        raw(&mut b, ",");
        time(&mut b, 1_700_000_000_123_456_789);
        raw(&mut b, ",");
        string(&mut b, "a \"quoted\"\nline");
        raw(&mut b, ",");
        real32(&mut b, 1e-30);
        raw(&mut b, "]");
        let v: serde_json::Value = serde_json::from_slice(&b).unwrap();
        assert_eq!(v[0]["x"], 1.5);
        assert_eq!(v[0]["y"], 0);
        assert_eq!(v[1]["g"], 0.0);
        assert_eq!(v[1]["b"], 0.502);
        assert_eq!(v[2]["sec"], 1_700_000_000u64);
        assert_eq!(v[2]["nsec"], 123_456_789);
        assert_eq!(v[3], "a \"quoted\"\nline");
        assert!((v[4].as_f64().unwrap() - 1e-30).abs() < 1e-36);
    }
}
