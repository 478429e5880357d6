//! Progress bar observer (only when stderr is a terminal): load level, monitored force, step
//! size, cut-backs, crossings and the time left.

use contrail::format::{count, plain, sig};
use contrail::record::{IncrementRecord, Observer, ObserverError, Outcome, StepView};
use indicatif::{ProgressBar, ProgressStyle};

pub struct Progress {
    bar: ProgressBar,
    end: f64,
    cutbacks: usize,
    crossings: usize,
}

impl Progress {
    pub fn new(end: f64) -> Self {
        let bar = ProgressBar::new(1000);
        bar.set_style(
            ProgressStyle::with_template("{spinner} {elapsed:>4} {bar:30} {msg} · {eta} left")
                .unwrap_or_else(|_| ProgressStyle::default_bar()),
        );
        Progress {
            bar,
            end,
            cutbacks: 0,
            crossings: 0,
        }
    }
}

/// The bar's message after an increment.
pub fn message(rec: &IncrementRecord, end: f64, cutbacks: usize, crossings: usize) -> String {
    let mut m = format!("t = {} of {}", sig(rec.t, 4), plain(end));
    if let Some(mo) = &rec.monitor {
        m.push_str(&format!(
            " · {} = {} · force = {}",
            mo.label,
            sig(mo.displacement, 4),
            sig(mo.force, 4)
        ));
    }
    m.push_str(&format!(
        " · step {} · {} · {}",
        sig(rec.dt, 3),
        count(cutbacks, "cut-back", "cut-backs"),
        count(crossings, "crossing", "crossings")
    ));
    m
}

impl Observer for Progress {
    fn increment(&mut self, rec: &IncrementRecord, v: &StepView) -> Result<(), ObserverError> {
        self.cutbacks += rec.cutbacks;
        self.crossings += v.crossings.len();
        self.bar.set_position((1000.0 * rec.t / self.end) as u64);
        self.bar
            .set_message(message(rec, self.end, self.cutbacks, self.crossings));
        Ok(())
    }
    fn finish(&mut self, _o: &Outcome) -> Result<(), ObserverError> {
        self.bar.finish_and_clear();
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use contrail::record::MonitorRecord;

    #[test]
    fn the_bar_shows_load_force_step_cutbacks_and_crossings() {
        let rec = IncrementRecord {
            increment: 12,
            t: 0.6413636363636566,
            dt: 0.0025,
            iterations: 4,
            cutbacks: 0,
            converged: true,
            wall_time_s: 0.0,
            residuals: vec![],
            monitor: Some(MonitorRecord {
                label: "v".into(),
                displacement: 0.6413636363636566,
                force: 4.96712,
            }),
            monitors: vec![],
            reaction_total: [0.0; 2],
            reaction_z: None,
            ..Default::default()
        };
        assert_eq!(
            message(&rec, 11.0, 1, 3),
            "t = 0.6414 of 11 · v = 0.6414 · force = 4.967 · step 0.0025 · 1 cut-back · 3 crossings"
        );
    }
}
