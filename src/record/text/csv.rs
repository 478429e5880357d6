//! CSV sink: the load–displacement history, one row per converged increment.
//!
//! Columns: `increment, t, displacement, force` (the first monitor), `iterations, cutbacks,
//! reaction_x, reaction_y, contact_closed, crossings`, then two named columns per monitor in
//! scene order, `LABEL.displacement` and `LABEL.force` (quoted when the label needs it).

use crate::record::{IncrementRecord, Observer, ObserverError, Outcome, StepView};
use std::io::Write;

pub struct CsvSink<W: Write> {
    out: W,
    name: String,
}

impl<W: Write> CsvSink<W> {
    pub fn new(out: W, name: &str) -> Self {
        CsvSink {
            out,
            name: name.to_string(),
        }
    }
    /// The writer, with everything written so far.
    pub fn into_inner(self) -> W {
        self.out
    }
    fn err(&self, e: std::io::Error) -> ObserverError {
        ObserverError::new(&self.name, e)
    }
}

impl<W: Write> Observer for CsvSink<W> {
    fn start(&mut self, m: crate::model::ModelRef<'_>, _i: &crate::record::RunInfo) -> Result<(), ObserverError> {
        let mut header =
            "increment,t,displacement,force,iterations,cutbacks,reaction_x,reaction_y,contact_closed,crossings"
                .to_string();
        for mon in m.monitors() {
            for q in ["displacement", "force"] {
                header.push(',');
                header.push_str(&field(&format!("{}.{q}", mon.label)));
            }
        }
        writeln!(self.out, "{header}").map_err(|e| self.err(e))
    }
    fn increment(&mut self, rec: &IncrementRecord, view: &StepView) -> Result<(), ObserverError> {
        let (d, f) = rec
            .monitor
            .as_ref()
            .map(|m| (m.displacement, m.force))
            .unwrap_or((f64::NAN, f64::NAN));
        // the 2D points and the 3D (node-to-surface) points: a model has one kind or the other
        let open = crate::contact::law::ContactState::Open;
        let closed = view.contact.iter().filter(|c| c.state != open).count()
            + view.surface.iter().filter(|p| p.state != open).count();
        let crossings = view.crossings.len() + view.surface.iter().filter(|p| p.crossing).count();
        write!(
            self.out,
            "{},{:.10e},{:.10e},{:.10e},{},{},{:.10e},{:.10e},{},{}",
            rec.increment,
            rec.t,
            d,
            f,
            rec.iterations,
            rec.cutbacks,
            rec.reaction_total[0],
            rec.reaction_total[1],
            closed,
            crossings
        )
        .map_err(|e| self.err(e))?;
        for m in &rec.monitors {
            write!(self.out, ",{:.10e},{:.10e}", m.displacement, m.force).map_err(|e| self.err(e))?;
        }
        writeln!(self.out).map_err(|e| self.err(e))
    }
    fn finish(&mut self, _o: &Outcome) -> Result<(), ObserverError> {
        self.out.flush().map_err(|e| self.err(e))
    }
}

/// A CSV field: quoted (with doubled quotes) when it has a comma, a quote or a line break.
pub fn field(s: &str) -> String {
    if s.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", s.replace('"', "\"\""))
    } else {
        s.to_string()
    }
}
