//! The sink trait the solver reports to.

use super::{IncrementRecord, IterationRecord, LogRecord, Outcome, RunInfo, StepView};
use crate::model::ModelRef;

/// Error raised by an observer (an I/O failure of a sink); it stops the run.
#[derive(Debug, thiserror::Error)]
#[error("{sink}: {source}")]
pub struct ObserverError {
    pub sink: String,
    #[source]
    pub source: Box<dyn std::error::Error + Send + Sync>,
}

impl ObserverError {
    pub fn new(sink: &str, source: impl Into<Box<dyn std::error::Error + Send + Sync>>) -> Self {
        ObserverError {
            sink: sink.to_string(),
            source: source.into(),
        }
    }
}

/// Receives the solver's records. Every method has a no-op default, so a sink implements
/// only what it keeps. `finish` is called exactly once, also after a failure or an
/// interruption, so a sink can always leave a complete file behind.
pub trait Observer {
    fn start(&mut self, _model: ModelRef<'_>, _info: &RunInfo) -> Result<(), ObserverError> {
        Ok(())
    }
    fn iteration(&mut self, _rec: &IterationRecord) -> Result<(), ObserverError> {
        Ok(())
    }
    fn increment(&mut self, _rec: &IncrementRecord, _view: &StepView) -> Result<(), ObserverError> {
        Ok(())
    }
    fn log(&mut self, _rec: &LogRecord) -> Result<(), ObserverError> {
        Ok(())
    }
    fn finish(&mut self, _outcome: &Outcome) -> Result<(), ObserverError> {
        Ok(())
    }
}

/// Forwards every call to several observers (all of them, even if one fails; the first
/// error is returned).
#[derive(Default)]
pub struct Fanout<'a> {
    pub sinks: Vec<&'a mut dyn Observer>,
}

macro_rules! fan {
    ($self:ident, $m:ident $(, $a:expr)*) => {{
        let mut first = Ok(());
        for s in $self.sinks.iter_mut() {
            if let Err(e) = s.$m($($a),*) {
                if first.is_ok() {
                    first = Err(e);
                }
            }
        }
        first
    }};
}

impl Observer for Fanout<'_> {
    fn start(&mut self, model: ModelRef<'_>, info: &RunInfo) -> Result<(), ObserverError> {
        fan!(self, start, model, info)
    }
    fn iteration(&mut self, rec: &IterationRecord) -> Result<(), ObserverError> {
        fan!(self, iteration, rec)
    }
    fn increment(&mut self, rec: &IncrementRecord, view: &StepView) -> Result<(), ObserverError> {
        fan!(self, increment, rec, view)
    }
    fn log(&mut self, rec: &LogRecord) -> Result<(), ObserverError> {
        fan!(self, log, rec)
    }
    fn finish(&mut self, outcome: &Outcome) -> Result<(), ObserverError> {
        fan!(self, finish, outcome)
    }
}

/// Keeps everything in memory (tests, plots, summaries).
#[derive(Default)]
pub struct Memory {
    pub iterations: Vec<IterationRecord>,
    pub increments: Vec<IncrementRecord>,
    pub contact: Vec<Vec<super::ContactPointRecord>>,
    pub crossings: Vec<(usize, super::CrossingRecord)>,
    /// The 3D contact points of each increment.
    pub surface: Vec<Vec<super::surface_contact::SurfacePointRecord>>,
    pub logs: Vec<LogRecord>,
    pub outcome: Option<Outcome>,
    pub final_u: Vec<f64>,
}

impl Observer for Memory {
    fn iteration(&mut self, rec: &IterationRecord) -> Result<(), ObserverError> {
        self.iterations.push(rec.clone());
        Ok(())
    }
    fn increment(&mut self, rec: &IncrementRecord, view: &StepView) -> Result<(), ObserverError> {
        self.increments.push(rec.clone());
        self.contact.push(view.contact.to_vec());
        self.surface.push(view.surface.to_vec());
        self.crossings
            .extend(view.crossings.iter().map(|c| (rec.increment, c.clone())));
        self.final_u = view.u.to_vec();
        Ok(())
    }
    fn log(&mut self, rec: &LogRecord) -> Result<(), ObserverError> {
        self.logs.push(rec.clone());
        Ok(())
    }
    fn finish(&mut self, outcome: &Outcome) -> Result<(), ObserverError> {
        self.outcome = Some(outcome.clone());
        Ok(())
    }
}
