//! Whether the element kernels go faster on the team or on the calling thread alone,
//! measured while the run goes: the answer depends on the model, the machine and on what
//! else runs on it (two solvers sharing two cores gain nothing from a second thread each),
//! so it is timed, not guessed.
//!
//! Each kind of assembly (with and without the tangent) keeps a moving average of its
//! wall time in either mode and uses the faster one. The other mode is tried again after
//! [`FIRST_RETRY`] assemblies, then after twice as many each time it loses (at most
//! [`LAST_RETRY`]), so a changed load is noticed within a few hundred assemblies while the
//! losing mode costs at most one assembly in [`FIRST_RETRY`]. Both modes give the same
//! bits, so the choice never changes a result.

use std::time::Duration;

/// Assemblies before the losing mode is tried again, at first.
pub const FIRST_RETRY: u32 = 16;
/// The longest wait before the losing mode is tried again.
pub const LAST_RETRY: u32 = 512;
/// Weight of a new time in the moving average.
const WEIGHT: f64 = 0.3;

/// How the element kernels of one assembly run.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Mode {
    /// The calling thread alone.
    Alone,
    /// The calling thread and the team's workers.
    Team,
}

/// The measurements of one kind of assembly.
#[derive(Debug, Clone, Copy)]
struct Kind {
    /// Average seconds per assembly: alone, on the team (`None` until measured).
    alone: Option<f64>,
    team: Option<f64>,
    /// Assemblies until the losing mode is tried again, and the current wait.
    countdown: u32,
    wait: u32,
}

impl Default for Kind {
    fn default() -> Self {
        Kind {
            alone: None,
            team: None,
            countdown: FIRST_RETRY,
            wait: FIRST_RETRY,
        }
    }
}

impl Kind {
    fn winner(&self) -> Mode {
        match (self.alone, self.team) {
            (Some(a), Some(t)) if t < a => Mode::Team,
            (Some(_), Some(_)) => Mode::Alone,
            (None, _) => Mode::Alone,
            (Some(_), None) => Mode::Team,
        }
    }

    fn choose(&mut self) -> Mode {
        let winner = self.winner();
        if self.alone.is_none() || self.team.is_none() {
            return winner;
        }
        self.countdown = self.countdown.saturating_sub(1);
        if self.countdown > 0 {
            return winner;
        }
        match winner {
            Mode::Alone => Mode::Team,
            Mode::Team => Mode::Alone,
        }
    }

    fn record(&mut self, mode: Mode, seconds: f64) {
        let before = self.winner();
        let retry = self.countdown == 0;
        let slot = match mode {
            Mode::Alone => &mut self.alone,
            Mode::Team => &mut self.team,
        };
        // a retry replaces the loser's stale average: the load may have changed since
        *slot = Some(match *slot {
            Some(avg) if !retry => avg + WEIGHT * (seconds - avg),
            _ => seconds,
        });
        if retry {
            // a retry of the losing mode: wait longer if it lost again, start over if it won
            let after = self.winner();
            self.wait = if after == before {
                (2 * self.wait).min(LAST_RETRY)
            } else {
                FIRST_RETRY
            };
            self.countdown = self.wait;
        }
    }
}

/// The measured choice for both kinds of assembly.
#[derive(Debug, Clone, Default)]
pub struct Pacing {
    kinds: [Kind; 2],
    /// A mode imposed for every assembly (benchmarks and tests), instead of the measured one.
    forced: Option<Mode>,
    /// Assemblies made in each mode (for the run's account).
    pub alone: usize,
    pub team: usize,
}

impl Pacing {
    /// The mode of the next assembly (with or without the tangent).
    pub fn choose(&mut self, with_tangent: bool) -> Mode {
        if let Some(mode) = self.forced {
            return mode;
        }
        self.kinds[usize::from(with_tangent)].choose()
    }

    /// Use `mode` for every assembly from now on (for benchmarks and tests: the two modes
    /// give the same bits).
    pub fn force(&mut self, mode: Mode) {
        self.forced = Some(mode);
    }

    /// The time the element kernels of an assembly took in `mode`.
    pub fn record(&mut self, with_tangent: bool, mode: Mode, took: Duration) {
        self.kinds[usize::from(with_tangent)].record(mode, took.as_secs_f64());
        match mode {
            Mode::Alone => self.alone += 1,
            Mode::Team => self.team += 1,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn simulate(p: &mut Pacing, alone: f64, team: f64, n: usize) -> (usize, usize) {
        let (mut a, mut t) = (0, 0);
        for _ in 0..n {
            let m = p.choose(true);
            let s = match m {
                Mode::Alone => {
                    a += 1;
                    alone
                }
                Mode::Team => {
                    t += 1;
                    team
                }
            };
            p.record(true, m, Duration::from_secs_f64(s));
        }
        (a, t)
    }

    #[test]
    fn the_faster_mode_wins_and_the_loser_is_tried_rarely() {
        let mut p = Pacing::default();
        let (alone, team) = simulate(&mut p, 1.0, 0.6, 2000);
        assert!(team > 1990 && alone >= 2, "{alone} {team}");
        let mut p = Pacing::default();
        let (alone, team) = simulate(&mut p, 1.0, 1.8, 2000);
        assert!(alone > 1990 && team >= 2, "{alone} {team}");
    }

    #[test]
    fn a_change_of_load_is_followed() {
        let mut p = Pacing::default();
        simulate(&mut p, 1.0, 0.6, 2000);
        // another process takes the second core: the team becomes slower than one thread
        let (alone, _) = simulate(&mut p, 1.0, 2.0, 2000);
        assert!(alone > 1900, "{alone}");
        // and frees it again
        let (_, team) = simulate(&mut p, 1.0, 0.6, 2000);
        assert!(team > 1900, "{team}");
    }
}
