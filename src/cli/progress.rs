//! Progress bar observer (only when stdout is a terminal).

use contrail::record::{IncrementRecord, Observer, ObserverError, Outcome, StepView};
use indicatif::{ProgressBar, ProgressStyle};

pub struct Progress {
    bar: ProgressBar,
    end: f64,
}

impl Progress {
    pub fn new(end: f64) -> Self {
        let bar = ProgressBar::new(1000);
        bar.set_style(
            ProgressStyle::with_template("{spinner} [{elapsed_precise}] {bar:40} t = {msg}")
                .unwrap_or_else(|_| ProgressStyle::default_bar()),
        );
        Progress { bar, end }
    }
}

impl Observer for Progress {
    fn increment(&mut self, rec: &IncrementRecord, _v: &StepView) -> Result<(), ObserverError> {
        self.bar.set_position((1000.0 * rec.t / self.end) as u64);
        self.bar.set_message(format!(
            "{:.4} (increment {}, {} it)",
            rec.t, rec.increment, rec.iterations
        ));
        Ok(())
    }
    fn finish(&mut self, _o: &Outcome) -> Result<(), ObserverError> {
        self.bar.finish_and_clear();
        Ok(())
    }
}
