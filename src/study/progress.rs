//! A run's progress as JSON lines, one per converged increment, and its typed outcome as the
//! last line: what `contrail run --progress FILE` writes, and what `contrail serve` reads
//! from its solver processes for live progress (small: a few numbers per increment, not the
//! contact points).

use super::StudyOutcome;
use crate::record::{ChangingPoint, IncrementRecord, Observer, ObserverError, RunInfo, StepView};
use serde::{Deserialize, Serialize};
use serde_json::Value;
use std::io::Write;

/// One line of a progress stream.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "lowercase")]
pub enum ProgressLine {
    /// The model is built and the run starts.
    Start {
        scene: String,
        dofs: usize,
        t_end: f64,
        transfer: Vec<String>,
    },
    /// A converged increment.
    Increment {
        increment: usize,
        t: f64,
        t_end: f64,
        /// The first monitor's displacement and force (None: the scene has no monitor).
        displacement: Option<f64>,
        force: Option<f64>,
        iterations: usize,
        /// Cut-backs and crossings so far.
        cutbacks: usize,
        crossings: usize,
        /// Crossings in this increment.
        new_crossings: usize,
        wall_time_s: f64,
    },
    /// How the run ended; `culprit`: the contact points that kept changing in a failed
    /// increment, most still-changing first.
    End {
        outcome: Box<StudyOutcome>,
        #[serde(default)]
        culprit: Vec<ChangingPoint>,
    },
}

impl ProgressLine {
    /// Parse one line (None: not a progress line). JSON writes a non-finite number as
    /// `null`, which a number field does not take back: an outcome with such values (the
    /// position of an unpaired contact point is NaN) is read leniently (see [`lenient`]).
    pub fn parse(line: &str) -> Option<ProgressLine> {
        let line = line.trim();
        if !line.starts_with('{') {
            return None;
        }
        serde_json::from_str(line).ok().or_else(|| {
            let v: Value = serde_json::from_str(line).ok()?;
            (v["kind"] == "end").then(|| ProgressLine::End {
                outcome: Box::new(lenient(&v["outcome"])),
                culprit: serde_json::from_value(v["culprit"].clone()).unwrap_or_default(),
            })
        })
    }
}

/// Entries of a JSON array that read as `T` (those with a `null` for a non-finite number
/// are left out).
fn entries<T: serde::de::DeserializeOwned>(v: &Value) -> Vec<T> {
    v.as_array()
        .map(|a| {
            a.iter()
                .filter_map(|x| serde_json::from_value(x.clone()).ok())
                .collect()
        })
        .unwrap_or_default()
}

/// An outcome read part by part: status and figures as they are, the data's lists without
/// the entries that carried non-finite numbers.
fn lenient(v: &Value) -> StudyOutcome {
    let d = &v["data"];
    StudyOutcome {
        status: serde_json::from_value(v["status"].clone()).unwrap_or(super::Status::Interrupted {
            increment: 0,
            t: f64::NAN,
        }),
        figures: serde_json::from_value(v["figures"].clone()).unwrap_or_default(),
        data: super::RunData {
            curve: entries(&d["curve"]),
            crossings: entries(&d["crossings"]),
            final_contact: entries(&d["final_contact"]),
            final_surface_contact: entries(&d["final_surface_contact"]),
            final_reaction: serde_json::from_value(d["final_reaction"].clone()).unwrap_or_default(),
            contact_lost: entries(&d["contact_lost"]),
        },
    }
}

/// Writes [`ProgressLine`]s, flushed line by line.
pub struct ProgressSink {
    out: Box<dyn Write + Send>,
    name: String,
    t_end: f64,
    cutbacks: usize,
    crossings: usize,
    started: std::time::Instant,
}

impl ProgressSink {
    pub fn new(out: Box<dyn Write + Send>, name: &str) -> ProgressSink {
        ProgressSink {
            out,
            name: name.to_string(),
            t_end: 0.0,
            cutbacks: 0,
            crossings: 0,
            started: std::time::Instant::now(),
        }
    }

    /// Write one line and flush it.
    pub fn write(&mut self, line: &ProgressLine) -> Result<(), ObserverError> {
        let err = |e: std::io::Error| ObserverError::new(&self.name, e);
        let mut text = serde_json::to_string(line).map_err(|e| ObserverError::new(&self.name, e))?;
        text.push('\n');
        self.out.write_all(text.as_bytes()).map_err(err)?;
        self.out.flush().map_err(err)
    }
}

impl Observer for ProgressSink {
    fn start(&mut self, model: crate::model::ModelRef<'_>, info: &RunInfo) -> Result<(), ObserverError> {
        self.t_end = info.settings.stepping.end;
        self.write(&ProgressLine::Start {
            scene: model.name().to_string(),
            dofs: info.dofs,
            t_end: self.t_end,
            transfer: info.transfer.clone(),
        })
    }

    fn increment(&mut self, rec: &IncrementRecord, view: &StepView) -> Result<(), ObserverError> {
        self.cutbacks += rec.cutbacks;
        self.crossings += view.crossings.len();
        let line = ProgressLine::Increment {
            increment: rec.increment,
            t: rec.t,
            t_end: self.t_end,
            displacement: rec.monitor.as_ref().map(|m| m.displacement),
            force: rec.monitor.as_ref().map(|m| m.force),
            iterations: rec.iterations,
            cutbacks: self.cutbacks,
            crossings: self.crossings,
            new_crossings: view.crossings.len(),
            wall_time_s: self.started.elapsed().as_secs_f64(),
        };
        self.write(&line)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::study::Study;
    use std::sync::atomic::AtomicBool;
    use std::sync::{Arc, Mutex};

    #[derive(Clone, Default)]
    struct Shared(Arc<Mutex<Vec<u8>>>);
    impl Write for Shared {
        fn write(&mut self, b: &[u8]) -> std::io::Result<usize> {
            self.0.lock().unwrap().extend_from_slice(b);
            Ok(b.len())
        }
        fn flush(&mut self) -> std::io::Result<()> {
            Ok(())
        }
    }

    #[test]
    fn one_line_per_increment_with_running_totals() {
        let buf = Shared::default();
        let mut sink = ProgressSink::new(Box::new(buf.clone()), "progress");
        let s = Study::new("crossing", vec!["stepping.increments=40".into()]);
        let out = s
            .run(&Default::default(), &mut [&mut sink], &AtomicBool::new(false))
            .unwrap();
        let text = String::from_utf8(buf.0.lock().unwrap().clone()).unwrap();
        let lines: Vec<ProgressLine> = text.lines().map(|l| ProgressLine::parse(l).unwrap()).collect();
        assert!(matches!(&lines[0], ProgressLine::Start { t_end, .. } if *t_end == out.figures.t_end));
        assert_eq!(lines.len(), 1 + out.figures.increments);
        match lines.last().unwrap() {
            ProgressLine::Increment {
                increment,
                crossings,
                force,
                ..
            } => {
                assert_eq!(*increment, out.figures.increments);
                assert_eq!(*crossings, out.figures.crossings);
                assert_eq!(*force, out.data.curve.last().map(|c| c[2]));
            }
            other => panic!("last line {other:?}"),
        }
        assert!(ProgressLine::parse("written runs/x.mcap").is_none());
        // a non-finite number is written as null and read back leniently
        let mut end = serde_json::to_value(ProgressLine::End {
            outcome: Box::new(out.clone()),
            culprit: vec![],
        })
        .unwrap();
        end["outcome"]["data"]["final_contact"] = serde_json::json!([[null, 0.0], [0.5, 1.0]]);
        match ProgressLine::parse(&end.to_string()) {
            Some(ProgressLine::End { outcome, .. }) => {
                assert_eq!(outcome.status, out.status);
                assert_eq!(outcome.data.curve, out.data.curve);
                assert_eq!(outcome.data.final_contact, vec![[0.5, 1.0]]);
            }
            other => panic!("{other:?}"),
        }
    }
}
