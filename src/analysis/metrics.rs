//! Error metrics of a load–displacement curve against a reference curve, and of the
//! crossings: max and RMS error over the common range (the reference linearly interpolated
//! at the run's points), peak and plateau errors, crossing-jump sizes and the roughness of
//! the curve at the crossings (max |F − local cubic fit| over a window of points).
//!
//! Curves are `(x, y)` points; references are sorted by `x` here, so a reference given in
//! any order works, but a curve that doubles back on itself in `x` is compared pointwise.

/// Max and RMS of `|y − y_ref(x)|` over the `x` range common to both curves.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CurveError {
    pub max: f64,
    pub rms: f64,
    /// Points of the run inside the common range.
    pub points: usize,
    /// Largest `|y_ref|` over the common range (to make the errors relative).
    pub scale: f64,
}

fn sorted(reference: &[(f64, f64)]) -> Vec<(f64, f64)> {
    let mut r: Vec<(f64, f64)> = reference
        .iter()
        .copied()
        .filter(|p| p.0.is_finite() && p.1.is_finite())
        .collect();
    r.sort_by(|a, b| a.0.total_cmp(&b.0));
    r
}

/// Linear interpolation of a curve sorted by `x` (None outside its range).
pub fn interpolate(sorted_ref: &[(f64, f64)], x: f64) -> Option<f64> {
    let (first, last) = (sorted_ref.first()?, sorted_ref.last()?);
    if !(first.0..=last.0).contains(&x) {
        return None;
    }
    let i = sorted_ref.partition_point(|p| p.0 < x);
    if i == 0 {
        return Some(sorted_ref[0].1);
    }
    let (a, b) = (sorted_ref[i - 1], sorted_ref[i.min(sorted_ref.len() - 1)]);
    if b.0 == a.0 {
        return Some(b.1);
    }
    Some(a.1 + (b.1 - a.1) * (x - a.0) / (b.0 - a.0))
}

/// Max and RMS error of `curve` against `reference` over their common `x` range (None when
/// they do not overlap).
pub fn curve_error(curve: &[(f64, f64)], reference: &[(f64, f64)]) -> Option<CurveError> {
    let r = sorted(reference);
    let (mut max, mut sum, mut n, mut scale) = (0.0f64, 0.0, 0usize, 0.0f64);
    for &(x, y) in curve.iter().filter(|p| p.0.is_finite() && p.1.is_finite()) {
        if let Some(yr) = interpolate(&r, x) {
            let e = (y - yr).abs();
            max = max.max(e);
            sum += e * e;
            n += 1;
            scale = scale.max(yr.abs());
        }
    }
    (n > 0).then(|| CurveError {
        max,
        rms: (sum / n as f64).sqrt(),
        points: n,
        scale,
    })
}

/// Largest `y` of a curve and its `x`.
pub fn peak(curve: &[(f64, f64)]) -> Option<(f64, f64)> {
    curve
        .iter()
        .copied()
        .filter(|p| p.1.is_finite())
        .max_by(|a, b| a.1.total_cmp(&b.1))
}

/// Relative error of the peak force, `(max y − max y_ref) / |max y_ref|`.
pub fn peak_error(curve: &[(f64, f64)], reference: &[(f64, f64)]) -> Option<f64> {
    let (p, r) = (peak(curve)?, peak(reference)?);
    (r.1 != 0.0).then(|| (p.1 - r.1) / r.1.abs())
}

/// Mean `y` over the points with `x ≥ from`.
pub fn plateau(curve: &[(f64, f64)], from: f64) -> Option<f64> {
    let ys: Vec<f64> = curve
        .iter()
        .filter(|p| p.0 >= from && p.1.is_finite())
        .map(|p| p.1)
        .collect();
    (!ys.is_empty()).then(|| ys.iter().sum::<f64>() / ys.len() as f64)
}

/// Relative error of the plateau (mean force for `x ≥ from`) against the reference's; None
/// when either curve has no point there or the reference plateau is zero.
pub fn plateau_error(curve: &[(f64, f64)], reference: &[(f64, f64)], from: f64) -> Option<f64> {
    let (p, r) = (plateau(curve, from)?, plateau(reference, from)?);
    (r != 0.0).then(|| (p - r) / r.abs())
}

/// Largest `|after − before|` of the trial tractions at the crossings (None: no crossing).
pub fn max_jump(jumps: &[(f64, f64)]) -> Option<f64> {
    jumps
        .iter()
        .map(|(b, a)| (a - b).abs())
        .filter(|j| j.is_finite())
        .reduce(f64::max)
}

/// Largest jump relative to the traction before it, `|after − before| / |before|` (a jump
/// from zero counts as relative size 1 when nonzero).
pub fn max_relative_jump(jumps: &[(f64, f64)]) -> Option<f64> {
    jumps
        .iter()
        .map(|(b, a)| {
            let j = (a - b).abs();
            if b.abs() > 0.0 {
                j / b.abs()
            } else if j > 0.0 {
                1.0
            } else {
                0.0
            }
        })
        .filter(|j| j.is_finite())
        .reduce(f64::max)
}

/// Least-squares cubic through `pts` (x shifted and scaled to [−1, 1] for conditioning);
/// returns the largest |y − fit| (None with fewer than 5 points or a singular fit).
fn cubic_misfit(pts: &[(f64, f64)]) -> Option<f64> {
    if pts.len() < 5 {
        return None;
    }
    let (lo, hi) = pts
        .iter()
        .fold((f64::MAX, f64::MIN), |(l, h), p| (l.min(p.0), h.max(p.0)));
    let (mid, half) = (0.5 * (lo + hi), 0.5 * (hi - lo));
    if half <= 0.0 {
        return None;
    }
    let basis = |x: f64| {
        let s = (x - mid) / half;
        [1.0, s, s * s, s * s * s]
    };
    let mut a = nalgebra::Matrix4::<f64>::zeros();
    let mut b = nalgebra::Vector4::<f64>::zeros();
    for &(x, y) in pts {
        let phi = basis(x);
        for i in 0..4 {
            b[i] += phi[i] * y;
            for j in 0..4 {
                a[(i, j)] += phi[i] * phi[j];
            }
        }
    }
    let c = a.lu().solve(&b)?;
    pts.iter()
        .map(|&(x, y)| {
            let phi = basis(x);
            (y - (0..4).map(|i| c[i] * phi[i]).sum::<f64>()).abs()
        })
        .reduce(f64::max)
}

/// Roughness of `curve` at the given `x` positions (the crossings): for each, the largest
/// |F − cubic fit| over the `window` points on either side of the curve point nearest to it
/// (at least 5 points in all, else that crossing is skipped). None when nothing was measured.
pub fn roughness(curve: &[(f64, f64)], at: &[f64], window: usize) -> Option<f64> {
    let pts: Vec<(f64, f64)> = curve
        .iter()
        .copied()
        .filter(|p| p.0.is_finite() && p.1.is_finite())
        .collect();
    if pts.is_empty() {
        return None;
    }
    at.iter()
        .filter_map(|&x| {
            let i = (0..pts.len()).min_by(|&i, &j| (pts[i].0 - x).abs().total_cmp(&(pts[j].0 - x).abs()))?;
            let lo = i.saturating_sub(window);
            let hi = (i + window + 1).min(pts.len());
            cubic_misfit(&pts[lo..hi])
        })
        .reduce(f64::max)
}

/// Crossing spikes of `curve` over `[x0, x1]`: the largest |F − cubic least-squares fit|
/// over the points with `x` in the window, over the largest |F| of the whole curve (None
/// with fewer than 5 points in the window).
pub fn spike(curve: &[(f64, f64)], [x0, x1]: [f64; 2]) -> Option<f64> {
    let pts: Vec<(f64, f64)> = (curve.iter().copied())
        .filter(|p| p.0.is_finite() && p.1.is_finite())
        .collect();
    let peak = pts.iter().map(|p| p.1.abs()).fold(0.0, f64::max);
    let window: Vec<(f64, f64)> = pts.into_iter().filter(|p| p.0 >= x0 && p.0 <= x1).collect();
    cubic_misfit(&window).filter(|_| peak > 0.0).map(|m| m / peak)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn line(n: usize, f: impl Fn(f64) -> f64, x0: f64, x1: f64) -> Vec<(f64, f64)> {
        (0..=n)
            .map(|i| {
                let x = x0 + (x1 - x0) * i as f64 / n as f64;
                (x, f(x))
            })
            .collect()
    }

    #[test]
    fn interpolation_is_linear_and_bounded() {
        let r = vec![(0.0, 0.0), (1.0, 2.0), (3.0, 0.0)];
        assert_eq!(interpolate(&r, 0.5), Some(1.0));
        assert_eq!(interpolate(&r, 2.0), Some(1.0));
        assert_eq!(interpolate(&r, 3.0), Some(0.0));
        assert_eq!(interpolate(&r, 3.1), None);
        assert_eq!(interpolate(&[], 0.0), None);
    }

    #[test]
    fn curve_error_over_the_common_range_only() {
        let reference = line(10, |x| 2.0 * x, 0.0, 1.0);
        // the run goes further than the reference; beyond x = 1 it is not compared
        let mut curve = line(20, |x| 2.0 * x + 0.1, 0.0, 2.0);
        curve.push((f64::NAN, 1.0));
        let e = curve_error(&curve, &reference).unwrap();
        assert!((e.max - 0.1).abs() < 1e-12 && (e.rms - 0.1).abs() < 1e-12);
        assert_eq!(e.points, 11);
        assert!((e.scale - 2.0).abs() < 1e-12);
        // one point off by 1 among 4: max 1, rms 0.5
        let c = vec![(0.0, 0.0), (0.25, 0.5), (0.5, 2.0), (0.75, 1.5)];
        let e = curve_error(&c, &reference).unwrap();
        assert!((e.max - 1.0).abs() < 1e-12 && (e.rms - 0.5).abs() < 1e-12);
        assert!(curve_error(&line(3, |x| x, 5.0, 6.0), &reference).is_none());
        // the reference may come unsorted
        let mut rev = reference.clone();
        rev.reverse();
        assert!(curve_error(&reference, &rev).unwrap().max < 1e-12);
    }

    #[test]
    fn peak_and_plateau_errors_are_relative() {
        let reference = vec![(0.0, 0.0), (1.0, 4.0), (2.0, 1.0), (3.0, 1.0)];
        let curve = vec![(0.0, 0.0), (1.2, 5.0), (2.0, 1.1), (3.0, 1.1)];
        assert!((peak_error(&curve, &reference).unwrap() - 0.25).abs() < 1e-12);
        assert_eq!(peak(&curve), Some((1.2, 5.0)));
        assert!((plateau_error(&curve, &reference, 2.0).unwrap() - 0.1).abs() < 1e-12);
        assert!(plateau_error(&curve, &reference, 4.0).is_none());
        assert!(peak_error(&curve, &[(0.0, 0.0)]).is_none());
    }

    #[test]
    fn jumps_absolute_and_relative() {
        let j = [(1.0, 1.0), (2.0, 1.0), (0.0, 0.5), (-4.0, -3.0)];
        assert_eq!(max_jump(&j), Some(1.0));
        assert_eq!(max_relative_jump(&j), Some(1.0));
        assert_eq!(max_relative_jump(&[(4.0, 3.0)]), Some(0.25));
        assert_eq!(max_jump(&[]), None);
    }

    #[test]
    fn spike_is_the_misfit_over_the_window_relative_to_the_peak() {
        let mut c = line(40, |x| 2.0 + x - 0.1 * x * x * x, 0.0, 4.0);
        assert!(spike(&c, [1.0, 3.0]).unwrap() < 1e-12);
        c[20].1 += 0.01; // x = 2
        let peak = c.iter().map(|p| p.1.abs()).fold(0.0, f64::max);
        let s = spike(&c, [1.0, 3.0]).unwrap() * peak;
        assert!(s > 0.005 && s < 0.01, "{s}");
        assert!(spike(&c, [10.0, 11.0]).is_none());
    }

    #[test]
    fn roughness_is_zero_on_a_cubic_and_sees_a_step() {
        let cubic = line(40, |x| 1.0 + x - 2.0 * x * x + 0.5 * x * x * x, 0.0, 4.0);
        let r = roughness(&cubic, &[1.0, 2.0, 3.9], 4).unwrap();
        assert!(r < 1e-10, "{r}");
        // a step of 1 at x = 2 in a straight line: the cubic cannot follow it
        let step = line(40, |x| x + if x > 2.0 { 1.0 } else { 0.0 }, 0.0, 4.0);
        let r = roughness(&step, &[2.0], 4).unwrap();
        assert!(r > 0.1 && r < 1.0, "{r}");
        // away from the step, smooth again
        assert!(roughness(&step, &[0.5], 4).unwrap() < 1e-10);
        assert!(roughness(&step[..3], &[0.0], 4).is_none());
        assert!(roughness(&[], &[0.0], 4).is_none());
    }
}
