//! Charts of a sweep index (plotters, SVG or PNG by the file's extension):
//! [`pareto`] — error against wall time, log–log, one series per family, Pareto front
//! marked; [`stability`] — pass/fail maps over two swept keys, one panel per transfer
//! scheme, colour = load level reached, marker = failure kind.

mod pareto;
mod stability;

pub use pareto::{mark_front, pareto, ParetoPoint};
pub use stability::{marker_shape, stability, stability_by, Cell};

use crate::sweep::IndexRow;
use plotters::prelude::*;
use std::path::Path;

/// A chart that could not be drawn.
#[derive(Debug, thiserror::Error)]
#[error("chart {path}: {message}")]
pub struct ChartError {
    pub path: String,
    pub message: String,
}

impl ChartError {
    pub(crate) fn new(path: &Path, message: impl Into<String>) -> ChartError {
        ChartError {
            path: path.display().to_string(),
            message: message.into(),
        }
    }
}

/// Metric names accepted by `pareto` (columns of the index).
pub const METRICS: [&str; 10] = [
    "err_max_rel",
    "err_max",
    "err_rms",
    "peak_err",
    "plateau_err",
    "jump_max",
    "jump_rel_max",
    "roughness",
    "spike_rel",
    "analytic_err",
];

/// The absolute value of a metric of a row by its index column name.
pub fn metric(row: &IndexRow, name: &str) -> Option<f64> {
    let m = &row.metrics;
    let v = match name {
        "err_max_rel" => m.err_max_rel,
        "err_max" => m.err_max,
        "err_rms" => m.err_rms,
        "peak_err" => m.peak_err,
        "plateau_err" => m.plateau_err,
        "jump_max" => m.jump_max,
        "jump_rel_max" => m.jump_rel_max,
        "roughness" => m.roughness,
        "spike_rel" => m.spike_rel,
        "analytic_err" => m.analytic_err,
        _ => None,
    };
    v.map(f64::abs)
}

/// Colour of a load fraction in [0, 1]: red (nothing) through amber to green (all of it).
pub fn load_colour(f: f64) -> RGBColor {
    let f = if f.is_finite() { f.clamp(0.0, 1.0) } else { 0.0 };
    let lerp = |a: u8, b: u8, s: f64| (a as f64 + (b as f64 - a as f64) * s).round() as u8;
    let (r0, r1, r2) = ((215u8, 48u8, 39u8), (254u8, 196u8, 79u8), (26u8, 152u8, 80u8));
    if f < 0.5 {
        let s = 2.0 * f;
        RGBColor(lerp(r0.0, r1.0, s), lerp(r0.1, r1.1, s), lerp(r0.2, r1.2, s))
    } else {
        let s = 2.0 * f - 1.0;
        RGBColor(lerp(r1.0, r2.0, s), lerp(r1.1, r2.1, s), lerp(r1.2, r2.2, s))
    }
}

/// The two backends, chosen by the output's extension.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Format {
    Svg,
    Png,
}

/// The backend for `path`, with its folder created and the embedded font registered.
pub(crate) fn format_of(path: &Path) -> Result<Format, ChartError> {
    crate::analysis::plot::register_font();
    let f = match path.extension().and_then(|e| e.to_str()) {
        Some("svg") => Format::Svg,
        Some("png") => Format::Png,
        _ => return Err(ChartError::new(path, "use a .svg or .png file name")),
    };
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).map_err(|e| ChartError::new(path, format!("cannot create the folder: {e}")))?;
    }
    Ok(f)
}

/// Sort key of a parameter value: its numbers (so `[48, 2]` < `[240, 8]` and `1e3` < `1e4`),
/// then the text.
pub(crate) fn value_key(v: &str) -> (Vec<f64>, String) {
    let nums = v
        .split(|c: char| !(c.is_ascii_digit() || c == '.' || c == '-' || c == 'e' || c == 'E' || c == '+'))
        .filter_map(|t| t.parse::<f64>().ok())
        .collect();
    (nums, v.to_string())
}

/// Compare two parameter values by [`value_key`].
pub(crate) fn value_cmp(a: &str, b: &str) -> std::cmp::Ordering {
    let (ka, kb) = (value_key(a), value_key(b));
    for (x, y) in ka.0.iter().zip(&kb.0) {
        match x.total_cmp(y) {
            std::cmp::Ordering::Equal => {}
            o => return o,
        }
    }
    ka.0.len().cmp(&kb.0.len()).then(ka.1.cmp(&kb.1))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn values_sort_by_their_numbers() {
        let mut v = vec!["[240, 8]", "[48, 2]", "[24, 1]", "[48, 1]"];
        v.sort_by(|a, b| value_cmp(a, b));
        assert_eq!(v, ["[24, 1]", "[48, 1]", "[48, 2]", "[240, 8]"]);
        let mut v = vec!["100000.0", "1000.0", "10000.0", "continuous"];
        v.sort_by(|a, b| value_cmp(a, b));
        assert_eq!(v, ["continuous", "1000.0", "10000.0", "100000.0"]);
    }

    #[test]
    fn colours_and_metrics() {
        assert_eq!(load_colour(0.0), RGBColor(215, 48, 39));
        assert_eq!(load_colour(1.0), RGBColor(26, 152, 80));
        assert_eq!(load_colour(f64::NAN), load_colour(0.0));
        assert!(format_of(Path::new("x.pdf")).is_err());
    }
}
