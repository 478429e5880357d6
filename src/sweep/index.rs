//! The index of a sweep: one row per finished run (parameters, outcome, failure kind,
//! figures, error metrics, recording), as CSV and JSON, written atomically (a temporary file
//! renamed over the old one) so an interrupted sweep always leaves a consistent index; and
//! the per-run record files that make a sweep resumable and mergeable.

use super::SweepError;
use crate::study::{FailureKind, StudyOutcome};
use serde::{Deserialize, Serialize};
use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// What a finished run left in `runs/ID.json` (the index is recomputed from these).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RunRecord {
    pub id: String,
    pub ordinal: usize,
    pub study: String,
    pub scene: String,
    pub params: BTreeMap<String, String>,
    pub sets: Vec<String>,
    pub family: String,
    pub outcome: StudyOutcome,
}

/// Error metrics of a run (None: not measurable for this run or reference).
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct Metrics {
    /// Max and RMS of |F − F_ref| over the common range, and max over the largest |F_ref|.
    pub err_max: Option<f64>,
    pub err_rms: Option<f64>,
    pub err_max_rel: Option<f64>,
    /// Relative errors of the peak force and of the plateau.
    pub peak_err: Option<f64>,
    pub plateau_err: Option<f64>,
    /// Largest |trial after − trial before| at a crossing, absolute and relative.
    pub jump_max: Option<f64>,
    pub jump_rel_max: Option<f64>,
    /// Largest |F − local cubic fit| at a crossing.
    pub roughness: Option<f64>,
    /// Largest |F − cubic fit| over the plan's `spike_window`, over the peak |F|.
    #[serde(default)]
    pub spike_rel: Option<f64>,
    /// Largest relative error against the analytic reference, and what it is made of.
    pub analytic_err: Option<f64>,
    pub analytic_detail: String,
}

/// One row of the index.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct IndexRow {
    pub id: String,
    pub ordinal: usize,
    pub study: String,
    pub scene: String,
    pub family: String,
    /// Transfer schemes of the contact pairs (distinct, joined by `+`).
    pub transfer: String,
    pub params: BTreeMap<String, String>,
    /// `completed`, `failed` or `interrupted`.
    pub status: String,
    /// Why it failed, or why a completed run is flagged (lost contact, wrong answer).
    pub failure_kind: Option<FailureKind>,
    pub failure_increment: Option<usize>,
    pub failure_t: Option<f64>,
    /// Fraction of the load path reached.
    pub load_fraction: f64,
    pub increments: usize,
    pub newton_iterations: usize,
    pub cutbacks: usize,
    pub crossings: usize,
    pub dofs: usize,
    pub wall_time_s: f64,
    #[serde(flatten)]
    pub metrics: Metrics,
    /// Id of the reference run, `csv:PATH`, `hertz`, `coulomb`, or empty.
    pub reference: String,
    /// The MCAP recording, relative to the index's folder.
    pub recording: String,
    pub message: String,
}

impl IndexRow {
    /// Completed and not flagged by a check.
    pub fn passed(&self) -> bool {
        self.status == "completed" && self.failure_kind.is_none()
    }
}

/// The JSON index.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Index {
    pub plan: String,
    pub runs: Vec<IndexRow>,
}

impl Index {
    /// Read an `index.json` (or the `index.json` in a folder).
    pub fn load(path: &Path) -> Result<Index, SweepError> {
        let path = if path.is_dir() {
            path.join("index.json")
        } else {
            path.to_path_buf()
        };
        let text = std::fs::read_to_string(&path).map_err(|source| SweepError::Io {
            path: path.display().to_string(),
            source,
        })?;
        serde_json::from_str(&text).map_err(|e| SweepError::Index {
            path: path.display().to_string(),
            message: format!("line {}: {e}", e.line()),
        })
    }
}

fn io(path: &Path) -> impl FnOnce(std::io::Error) -> SweepError + '_ {
    move |source| SweepError::Io {
        path: path.display().to_string(),
        source,
    }
}

/// Write `bytes` to `path` through a temporary file in the same folder and a rename, so a
/// reader never sees a half-written file.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<(), SweepError> {
    let name = path
        .file_name()
        .map_or("index".into(), |n| n.to_string_lossy().into_owned());
    let tmp = path.with_file_name(format!(".{name}.tmp-{}", std::process::id()));
    std::fs::write(&tmp, bytes).map_err(io(&tmp))?;
    std::fs::rename(&tmp, path).map_err(io(path))
}

fn opt<T: std::fmt::Display>(v: &Option<T>) -> String {
    v.as_ref().map_or(String::new(), |x| x.to_string())
}

fn csv_field(s: &str) -> String {
    if s.contains([',', '"', '\n']) {
        format!("\"{}\"", s.replace('"', "\"\""))
    } else {
        s.to_string()
    }
}

/// The index as CSV: fixed columns, one column per parameter key, then the metrics.
pub fn to_csv(rows: &[IndexRow]) -> String {
    let keys: BTreeSet<&String> = rows.iter().flat_map(|r| r.params.keys()).collect();
    let mut head: Vec<String> = ["id", "ordinal", "study", "scene", "family", "transfer"]
        .iter()
        .map(|s| s.to_string())
        .collect();
    head.extend(keys.iter().map(|k| k.to_string()));
    head.extend(
        [
            "status",
            "failure_kind",
            "failure_increment",
            "failure_t",
            "load_fraction",
            "increments",
            "newton_iterations",
            "cutbacks",
            "crossings",
            "dofs",
            "wall_time_s",
            "err_max",
            "err_rms",
            "err_max_rel",
            "peak_err",
            "plateau_err",
            "jump_max",
            "jump_rel_max",
            "roughness",
            "spike_rel",
            "analytic_err",
            "analytic_detail",
            "reference",
            "recording",
            "message",
        ]
        .map(String::from),
    );
    let mut out = head.iter().map(|h| csv_field(h)).collect::<Vec<_>>().join(",");
    out.push('\n');
    for r in rows {
        let m = &r.metrics;
        let mut f: Vec<String> = vec![
            r.id.clone(),
            r.ordinal.to_string(),
            r.study.clone(),
            r.scene.clone(),
            r.family.clone(),
            r.transfer.clone(),
        ];
        f.extend(keys.iter().map(|k| r.params.get(*k).cloned().unwrap_or_default()));
        f.extend([
            r.status.clone(),
            opt(&r.failure_kind),
            opt(&r.failure_increment),
            opt(&r.failure_t),
            r.load_fraction.to_string(),
            r.increments.to_string(),
            r.newton_iterations.to_string(),
            r.cutbacks.to_string(),
            r.crossings.to_string(),
            r.dofs.to_string(),
            format!("{:.6}", r.wall_time_s),
            opt(&m.err_max),
            opt(&m.err_rms),
            opt(&m.err_max_rel),
            opt(&m.peak_err),
            opt(&m.plateau_err),
            opt(&m.jump_max),
            opt(&m.jump_rel_max),
            opt(&m.roughness),
            opt(&m.spike_rel),
            opt(&m.analytic_err),
            m.analytic_detail.clone(),
            r.reference.clone(),
            r.recording.clone(),
            r.message.replace('\n', " | "),
        ]);
        out.push_str(&f.iter().map(|s| csv_field(s)).collect::<Vec<_>>().join(","));
        out.push('\n');
    }
    out
}

/// Write `STEM.csv` and `STEM.json` in `dir` atomically; returns their paths.
pub fn write_index(dir: &Path, stem: &str, plan: &str, rows: &[IndexRow]) -> Result<(PathBuf, PathBuf), SweepError> {
    let csv = dir.join(format!("{stem}.csv"));
    let json = dir.join(format!("{stem}.json"));
    let index = Index {
        plan: plan.to_string(),
        runs: rows.to_vec(),
    };
    let text = serde_json::to_string_pretty(&index).map_err(|e| SweepError::Index {
        path: json.display().to_string(),
        message: e.to_string(),
    })?;
    write_atomic(&json, text.as_bytes())?;
    write_atomic(&csv, to_csv(rows).as_bytes())?;
    Ok((csv, json))
}

/// Path of a run's record file in an output folder.
pub fn record_path(dir: &Path, id: &str) -> PathBuf {
    dir.join("runs").join(format!("{id}.json"))
}

/// Write a run's record atomically.
pub fn write_record(dir: &Path, rec: &RunRecord) -> Result<(), SweepError> {
    let path = record_path(dir, &rec.id);
    let text = serde_json::to_string(rec).map_err(|e| SweepError::Index {
        path: path.display().to_string(),
        message: e.to_string(),
    })?;
    write_atomic(&path, text.as_bytes())
}

/// Every readable run record in `dir/runs` (an unreadable one counts as not finished, so a
/// resumed sweep makes that run again).
pub fn read_records(dir: &Path) -> Vec<RunRecord> {
    let Ok(entries) = std::fs::read_dir(dir.join("runs")) else {
        return Vec::new();
    };
    let mut out: Vec<RunRecord> = entries
        .filter_map(Result::ok)
        .map(|e| e.path())
        .filter(|p| p.extension().is_some_and(|x| x == "json"))
        .filter_map(|p| std::fs::read_to_string(p).ok())
        .filter_map(|t| serde_json::from_str(&t).ok())
        .collect();
    out.sort_by_key(|r: &RunRecord| r.ordinal);
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn row(id: &str) -> IndexRow {
        IndexRow {
            id: id.into(),
            ordinal: 0,
            study: "s".into(),
            scene: "crossing".into(),
            family: "continuous".into(),
            transfer: "continuous".into(),
            params: [("contact.mu".to_string(), "0.1".to_string())].into(),
            status: "failed".into(),
            failure_kind: Some(FailureKind::ActiveSetCycle),
            failure_increment: Some(3),
            failure_t: Some(0.5),
            load_fraction: 0.25,
            increments: 2,
            newton_iterations: 7,
            cutbacks: 1,
            crossings: 0,
            dofs: 20,
            wall_time_s: 0.01,
            metrics: Metrics {
                err_max: Some(1.5),
                analytic_detail: "a, b".into(),
                ..Metrics::default()
            },
            reference: String::new(),
            recording: "runs/x.mcap".into(),
            message: "no convergence\nhint".into(),
        }
    }

    #[test]
    fn csv_has_a_column_per_parameter_and_quotes() {
        let csv = to_csv(&[row("a")]);
        let mut lines = csv.lines();
        let head: Vec<&str> = lines.next().unwrap().split(',').collect();
        assert_eq!(head[6], "contact.mu");
        let line = lines.next().unwrap();
        assert!(line.starts_with("a,0,s,crossing,continuous,continuous,0.1,failed,active-set-cycle,3,0.5,0.25,"));
        assert!(line.contains(",\"a, b\","), "{line}");
        assert!(line.ends_with("no convergence | hint"));
    }

    #[test]
    fn index_and_records_round_trip_atomically() {
        let dir = std::env::temp_dir().join(format!("contrail-index-test-{}", std::process::id()));
        std::fs::create_dir_all(dir.join("runs")).unwrap();
        let (_, json) = write_index(&dir, "index", "p", &[row("a"), row("b")]).unwrap();
        let back = Index::load(&json).unwrap();
        assert_eq!(back.runs, vec![row("a"), row("b")]);
        assert_eq!(Index::load(&dir).unwrap().plan, "p");
        std::fs::write(dir.join("runs/broken.json"), "{").unwrap();
        assert!(read_records(&dir).is_empty());
        assert!(std::fs::read_dir(&dir)
            .unwrap()
            .all(|e| !e.unwrap().file_name().to_string_lossy().contains(".tmp-")));
        let e = Index::load(&dir.join("runs/broken.json")).unwrap_err().to_string();
        assert!(e.contains("broken.json"), "{e}");
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
