//! Prescribed histories over the pseudo-time `t` of a run.

use serde::{Deserialize, Serialize};

/// A piecewise-linear function of the pseudo-time `t`, given by `(t, value)` knots sorted
/// by `t`. Before the first knot it holds the first value, after the last knot the last.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Ramp {
    pub knots: Vec<(f64, f64)>,
}

impl Ramp {
    /// The linear ramp from 0 at `t = 0` to `value` at `t = end`.
    pub fn linear(value: f64, end: f64) -> Self {
        Ramp {
            knots: vec![(0.0, 0.0), (end, value)],
        }
    }

    /// Constant value.
    pub fn constant(value: f64) -> Self {
        Ramp {
            knots: vec![(0.0, value)],
        }
    }

    /// Zero at every time (every knot's value zero; no knot at all is zero too).
    pub fn is_zero(&self) -> bool {
        self.knots.iter().all(|(_, v)| *v == 0.0)
    }

    pub fn at(&self, t: f64) -> f64 {
        let k = &self.knots;
        if k.is_empty() {
            return 0.0;
        }
        if t <= k[0].0 {
            return k[0].1;
        }
        for w in k.windows(2) {
            let ((t0, v0), (t1, v1)) = (w[0], w[1]);
            if t <= t1 {
                if t1 <= t0 {
                    return v1;
                }
                return v0 + (v1 - v0) * (t - t0) / (t1 - t0);
            }
        }
        k[k.len() - 1].1
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn interpolates_and_clamps() {
        let r = Ramp {
            knots: vec![(0.0, 0.0), (1.0, -0.1), (3.0, -0.1), (4.0, 0.5)],
        };
        assert_eq!(r.at(-1.0), 0.0);
        assert!((r.at(0.5) + 0.05).abs() < 1e-15);
        assert_eq!(r.at(2.0), -0.1);
        assert!((r.at(3.5) - 0.2).abs() < 1e-15);
        assert_eq!(r.at(9.0), 0.5);
        assert_eq!(Ramp::linear(2.0, 4.0).at(1.0), 0.5);
    }
}
