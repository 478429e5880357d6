//! JSON-lines sink: every record as one line `{"kind": ..., "data": ...}` (`run`,
//! `iteration`, `increment`, `contact_point`, `crossing`, `surface_contact_point` for a 3D
//! contact point, `log`, `outcome`).

use crate::record::*;
use serde::Serialize;
use std::io::Write;

pub struct JsonlSink<W: Write> {
    out: W,
    name: String,
}

impl<W: Write> JsonlSink<W> {
    pub fn new(out: W, name: &str) -> Self {
        JsonlSink {
            out,
            name: name.to_string(),
        }
    }
    fn line<T: Serialize>(&mut self, kind: &str, data: &T) -> Result<(), ObserverError> {
        #[derive(Serialize)]
        struct Line<'a, T> {
            kind: &'a str,
            data: &'a T,
        }
        serde_json::to_writer(&mut self.out, &Line { kind, data }).map_err(|e| ObserverError::new(&self.name, e))?;
        self.out.write_all(b"\n").map_err(|e| ObserverError::new(&self.name, e))
    }
}

impl<W: Write> Observer for JsonlSink<W> {
    fn start(&mut self, _m: crate::model::ModelRef<'_>, info: &RunInfo) -> Result<(), ObserverError> {
        self.line("run", info)
    }
    fn iteration(&mut self, rec: &IterationRecord) -> Result<(), ObserverError> {
        self.line("iteration", rec)
    }
    fn increment(&mut self, rec: &IncrementRecord, view: &StepView) -> Result<(), ObserverError> {
        self.line("increment", rec)?;
        for c in view.contact {
            self.line("contact_point", c)?;
        }
        for c in view.crossings {
            self.line("crossing", c)?;
        }
        for c in view.surface {
            self.line("surface_contact_point", c)?;
        }
        Ok(())
    }
    fn log(&mut self, rec: &LogRecord) -> Result<(), ObserverError> {
        self.line("log", rec)
    }
    fn finish(&mut self, outcome: &Outcome) -> Result<(), ObserverError> {
        self.line("outcome", outcome)?;
        self.out.flush().map_err(|e| ObserverError::new(&self.name, e))
    }
}
