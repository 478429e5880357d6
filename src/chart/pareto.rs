//! `contrail chart pareto`: error against wall time, log–log, one series per family; the
//! Pareto front (no other run is both faster and more accurate) is joined and ringed.

use super::{format_of, metric, ChartError, Format};
use crate::sweep::IndexRow;
use plotters::prelude::*;
use std::collections::BTreeMap;
use std::path::Path;

/// A run on the chart.
#[derive(Debug, Clone, PartialEq)]
pub struct ParetoPoint {
    pub id: String,
    pub family: String,
    pub wall_time_s: f64,
    pub error: f64,
    /// Completed but flagged by a check (drawn hollow, never on the front).
    pub flagged: bool,
    pub on_front: bool,
}

/// The runs that have the metric (completed, positive error and wall time), front marked.
pub fn points(rows: &[IndexRow], metric_name: &str) -> Vec<ParetoPoint> {
    let mut pts: Vec<ParetoPoint> = rows
        .iter()
        .filter(|r| r.status == "completed" && r.wall_time_s > 0.0)
        .filter_map(|r| {
            let e = metric(r, metric_name).filter(|e| *e > 0.0 && e.is_finite())?;
            Some(ParetoPoint {
                id: r.id.clone(),
                family: r.family.clone(),
                wall_time_s: r.wall_time_s,
                error: e,
                flagged: r.failure_kind.is_some(),
                on_front: false,
            })
        })
        .collect();
    mark_front(&mut pts);
    pts
}

/// Mark the unflagged points that no other unflagged point beats in both time and error.
pub fn mark_front(pts: &mut [ParetoPoint]) {
    let mut order: Vec<usize> = (0..pts.len()).filter(|&i| !pts[i].flagged).collect();
    order.sort_by(|&a, &b| {
        pts[a]
            .wall_time_s
            .total_cmp(&pts[b].wall_time_s)
            .then(pts[a].error.total_cmp(&pts[b].error))
    });
    let mut best = f64::INFINITY;
    for i in order {
        pts[i].on_front = pts[i].error < best;
        best = best.min(pts[i].error);
    }
}

fn log_range(v: impl Iterator<Item = f64>) -> std::ops::Range<f64> {
    let (lo, hi) = v.fold((f64::MAX, f64::MIN), |(l, h), x| (l.min(x), h.max(x)));
    if lo > hi {
        return 0.1..10.0;
    }
    // whole decades: plotters labels a log axis at powers of ten
    10f64.powf(lo.log10().floor())..10f64.powf(hi.log10().ceil().max(lo.log10().floor() + 1.0))
}

/// The corner of the plot for the legend: the one with the fewest points in the box the
/// legend takes there (the outer 45 % of the width and 30 % of the height, on the log axes
/// `xr`, `yr`); the upper right first on a tie (a Pareto chart's usual empty corner).
fn legend_corner(pts: &[ParetoPoint], xr: &std::ops::Range<f64>, yr: &std::ops::Range<f64>) -> SeriesLabelPosition {
    let unit = |v: f64, r: &std::ops::Range<f64>| (v.log10() - r.start.log10()) / (r.end.log10() - r.start.log10());
    let corners = [
        (SeriesLabelPosition::UpperRight, true, true),
        (SeriesLabelPosition::LowerLeft, false, false),
        (SeriesLabelPosition::UpperLeft, false, true),
        (SeriesLabelPosition::LowerRight, true, false),
    ];
    let inside = |right: bool, upper: bool| {
        (pts.iter())
            .filter(|p| {
                let (x, y) = (unit(p.wall_time_s, xr), unit(p.error, yr));
                (if right { x >= 0.55 } else { x <= 0.45 }) && (if upper { y >= 0.7 } else { y <= 0.3 })
            })
            .count()
    };
    let best = corners.iter().min_by_key(|(_, right, upper)| inside(*right, *upper));
    best.map_or(SeriesLabelPosition::UpperRight, |c| c.0.clone())
}

fn draw<DB: DrawingBackend>(
    root: DrawingArea<DB, plotters::coord::Shift>,
    title: &str,
    metric_name: &str,
    pts: &[ParetoPoint],
) -> Result<(), String>
where
    DB::ErrorType: 'static,
{
    let e = |x: DrawingAreaErrorKind<DB::ErrorType>| x.to_string();
    root.fill(&WHITE).map_err(e)?;
    let xr = log_range(pts.iter().map(|p| p.wall_time_s));
    let yr = log_range(pts.iter().map(|p| p.error));
    let corner = legend_corner(pts, &xr, &yr);
    let mut chart = ChartBuilder::on(&root)
        .caption(title, ("sans-serif", 24))
        .margin(16)
        .x_label_area_size(50)
        .y_label_area_size(90)
        .build_cartesian_2d(xr.log_scale(), yr.log_scale())
        .map_err(e)?;
    chart
        .configure_mesh()
        .x_desc("wall time per run [s]")
        .y_desc(format!("error ({metric_name})"))
        .label_style(("sans-serif", 15))
        .x_label_formatter(&|v| format!("{v:.2e}"))
        .y_label_formatter(&|v| format!("{v:.1e}"))
        .draw()
        .map_err(e)?;
    let mut families: BTreeMap<&str, Vec<&ParetoPoint>> = BTreeMap::new();
    for p in pts {
        families.entry(p.family.as_str()).or_default().push(p);
    }
    for (i, (fam, ps)) in families.iter().enumerate() {
        let c = Palette99::pick(i).to_rgba();
        let filled = ps.iter().filter(|p| !p.flagged).map(|p| (p.wall_time_s, p.error));
        chart
            .draw_series(filled.map(|xy| Circle::new(xy, 5, c.filled())))
            .map_err(e)?
            .label(fam.to_string())
            .legend(move |(x, y)| Circle::new((x + 10, y), 5, c.filled()));
        let hollow = ps.iter().filter(|p| p.flagged).map(|p| (p.wall_time_s, p.error));
        chart
            .draw_series(hollow.map(|xy| Circle::new(xy, 5, c.stroke_width(2))))
            .map_err(e)?;
    }
    let mut front: Vec<(f64, f64)> = pts
        .iter()
        .filter(|p| p.on_front)
        .map(|p| (p.wall_time_s, p.error))
        .collect();
    front.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut steps = Vec::new();
    for (k, p) in front.iter().enumerate() {
        if k > 0 {
            steps.push((p.0, front[k - 1].1));
        }
        steps.push(*p);
    }
    chart
        .draw_series(LineSeries::new(steps, BLACK.stroke_width(1)))
        .map_err(e)?
        .label("Pareto front (hollow: flagged by a check)")
        .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], BLACK));
    chart
        .draw_series(front.iter().map(|&xy| Circle::new(xy, 9, BLACK.stroke_width(2))))
        .map_err(e)?;
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .label_font(("sans-serif", 14))
        .position(corner)
        .draw()
        .map_err(e)?;
    if pts.is_empty() {
        root.draw_text(
            "no completed run has this metric",
            &("sans-serif", 20).into_text_style(&root),
            (120, 120),
        )
        .map_err(e)?;
    }
    Ok(())
}

/// Draw the Pareto chart of `rows` for `metric_name` (an index column, see
/// [`super::METRICS`]) into `path` (.svg or .png); returns the plotted points.
pub fn pareto(rows: &[IndexRow], metric_name: &str, title: &str, path: &Path) -> Result<Vec<ParetoPoint>, ChartError> {
    if !super::METRICS.contains(&metric_name) {
        return Err(ChartError::new(
            path,
            format!(
                "unknown metric `{metric_name}`; use one of {}",
                super::METRICS.join(", ")
            ),
        ));
    }
    let pts = points(rows, metric_name);
    let size = (1100, 750);
    let r = match format_of(path)? {
        Format::Svg => draw(
            SVGBackend::new(path, size).into_drawing_area(),
            title,
            metric_name,
            &pts,
        ),
        Format::Png => draw(
            BitMapBackend::new(path, size).into_drawing_area(),
            title,
            metric_name,
            &pts,
        ),
    };
    r.map_err(|m| ChartError::new(path, m))?;
    Ok(pts)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn front_keeps_the_runs_nobody_beats() {
        let mk = |t: f64, e: f64, flagged: bool| ParetoPoint {
            id: format!("{t}"),
            family: "f".into(),
            wall_time_s: t,
            error: e,
            flagged,
            on_front: false,
        };
        let mut pts = vec![
            mk(1.0, 0.5, false),
            mk(2.0, 0.6, false),
            mk(3.0, 0.1, false),
            mk(0.5, 0.01, true),
        ];
        mark_front(&mut pts);
        let front: Vec<bool> = pts.iter().map(|p| p.on_front).collect();
        assert_eq!(front, [true, false, true, false]);
    }

    /// The legend goes to the upper right unless points lie there, then to the emptiest
    /// corner.
    #[test]
    fn the_legend_takes_the_emptiest_corner() {
        let mk = |t: f64, e: f64| ParetoPoint {
            id: format!("{t}"),
            family: "f".into(),
            wall_time_s: t,
            error: e,
            flagged: false,
            on_front: false,
        };
        let (xr, yr) = (0.01..10.0, 1e-4..0.1);
        let usual = [mk(0.02, 0.05), mk(5.0, 2e-4)];
        assert!(matches!(
            legend_corner(&usual, &xr, &yr),
            SeriesLabelPosition::UpperRight
        ));
        let upper_right = [mk(0.02, 0.05), mk(5.0, 2e-4), mk(3.0, 0.05)];
        assert!(matches!(
            legend_corner(&upper_right, &xr, &yr),
            SeriesLabelPosition::LowerLeft
        ));
    }
}
