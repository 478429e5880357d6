//! `contrail chart stability`: where each transfer scheme (or each method) fails. One panel
//! per scheme — or per value of another key, or per family (`--panel`), at most four panels
//! a row — the two swept keys on the axes (categorical, sorted by value), one marker per
//! run: colour = load level reached (red 0 → amber → green 1), shape = failure kind (filled
//! circle = passed; see [`super::marker_shape`]). Runs sharing a cell are spread side by
//! side.

use super::{format_of, load_colour, value_cmp, ChartError, Format};
use crate::study::FailureKind;
use crate::sweep::IndexRow;
use plotters::coord::types::RangedCoordf64;
use plotters::prelude::*;
use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

/// A run on the map.
#[derive(Debug, Clone, PartialEq)]
pub struct Cell {
    pub id: String,
    /// Panel (transfer scheme), and the cell's x and y values.
    pub panel: String,
    pub x: String,
    pub y: String,
    pub passed: bool,
    pub kind: Option<FailureKind>,
    pub load_fraction: f64,
}

/// The panel of a run: its family (`panel = "family"`), the value of another swept key, or
/// (`None`) its transfer scheme.
fn panel_of(r: &IndexRow, panel: Option<&str>) -> String {
    match panel {
        Some("family") => r.family.clone(),
        Some(key) => r.params.get(key).cloned().unwrap_or_default(),
        None => r
            .params
            .get("contact.transfer")
            .cloned()
            .unwrap_or_else(|| r.transfer.clone()),
    }
}

/// The runs that have both keys, panels by [`panel_of`].
pub fn cells_by(rows: &[IndexRow], x_key: &str, y_key: &str, panel: Option<&str>) -> Vec<Cell> {
    rows.iter()
        .filter(|r| r.status != "interrupted")
        .filter_map(|r| {
            Some(Cell {
                id: r.id.clone(),
                panel: panel_of(r, panel),
                x: r.params.get(x_key)?.clone(),
                y: r.params.get(y_key)?.clone(),
                passed: r.passed(),
                kind: r.failure_kind,
                load_fraction: r.load_fraction,
            })
        })
        .collect()
}

fn sorted_values<'a>(v: impl Iterator<Item = &'a String>) -> Vec<String> {
    let mut out: Vec<String> = v.cloned().collect::<BTreeSet<_>>().into_iter().collect();
    out.sort_by(|a, b| value_cmp(a, b));
    out
}

type Px = (i32, i32);

fn polygon(n: usize, r: f64, phase: f64) -> Vec<Px> {
    (0..n)
        .map(|i| {
            let a = phase + i as f64 * std::f64::consts::TAU / n as f64;
            ((r * a.cos()).round() as i32, (r * a.sin()).round() as i32)
        })
        .collect()
}

/// Shape of a marker, in pixels around its centre: (outline, filled). `None` = passed.
/// Filled circle passed, × no convergence, ▲ active-set cycle, ■ diverged, small □ non-finite,
/// □ inverted element, △ linear solver (singular), ○ lost contact, ◆ wrong answer, + bad input /
/// recording.
pub fn marker_shape(kind: Option<FailureKind>, s: f64) -> (Vec<Vec<Px>>, bool) {
    let up = -std::f64::consts::FRAC_PI_2;
    let q = std::f64::consts::FRAC_PI_4;
    let closed = |mut p: Vec<Px>| {
        p.push(p[0]);
        p
    };
    let si = s.round() as i32;
    match kind {
        None => (vec![polygon(16, s, 0.0)], true),
        Some(FailureKind::NoConvergence) => (vec![vec![(-si, -si), (si, si)], vec![(-si, si), (si, -si)]], false),
        Some(FailureKind::ActiveSetCycle) => (vec![polygon(3, s * 1.2, up)], true),
        Some(FailureKind::Diverged) => (vec![polygon(4, s * 1.3, q)], true),
        Some(FailureKind::NonFinite) => (vec![closed(polygon(4, s * 0.9, q))], false),
        Some(FailureKind::InvertedElement) => (vec![closed(polygon(4, s * 1.3, q))], false),
        Some(FailureKind::LinearSolver) => (vec![closed(polygon(3, s * 1.2, up))], false),
        Some(FailureKind::LostContact) => (vec![closed(polygon(16, s, 0.0))], false),
        Some(FailureKind::WrongAnswer) => (vec![polygon(4, s * 1.3, 0.0)], true),
        Some(FailureKind::BadInput) | Some(FailureKind::Recording) => {
            (vec![vec![(-si, 0), (si, 0)], vec![(0, -si), (0, si)]], false)
        }
    }
}

fn label(kind: Option<FailureKind>) -> String {
    kind.map_or("passed".into(), |k| k.as_str().to_string())
}

type Chart<'a, DB> = ChartContext<'a, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>;

fn draw_marker<DB: DrawingBackend>(
    chart: &mut Chart<'_, DB>,
    at: (f64, f64),
    kind: Option<FailureKind>,
    colour: RGBColor,
) -> Result<(), String>
where
    DB::ErrorType: 'static,
{
    let (parts, filled) = marker_shape(kind, 8.0);
    for p in parts {
        let r = if filled {
            chart.draw_series(std::iter::once(EmptyElement::at(at) + Polygon::new(p, colour.filled())))
        } else {
            chart.draw_series(std::iter::once(
                EmptyElement::at(at) + PathElement::new(p, colour.stroke_width(3)),
            ))
        };
        r.map_err(|e| e.to_string())?;
    }
    Ok(())
}

fn draw_panel<DB: DrawingBackend>(
    area: &DrawingArea<DB, plotters::coord::Shift>,
    panel: &str,
    cells: &[&Cell],
    (xs, ys): (&[String], &[String]),
    (x_key, y_key): (&str, &str),
) -> Result<(), String>
where
    DB::ErrorType: 'static,
{
    let e = |x: DrawingAreaErrorKind<DB::ErrorType>| x.to_string();
    let nx = xs.len().max(1) as f64;
    let ny = ys.len().max(1) as f64;
    let mut chart = ChartBuilder::on(area)
        .caption(panel, ("sans-serif", 20))
        .margin(12)
        .x_label_area_size(45)
        .y_label_area_size(120)
        .build_cartesian_2d(-0.5..nx - 0.5, -0.5..ny - 0.5)
        .map_err(e)?;
    let lx = |v: &f64| {
        let i = v.round();
        ((v - i).abs() < 1e-6 && i >= 0.0)
            .then(|| xs.get(i as usize).cloned())
            .flatten()
            .unwrap_or_default()
    };
    let ly = |v: &f64| {
        let i = v.round();
        ((v - i).abs() < 1e-6 && i >= 0.0)
            .then(|| ys.get(i as usize).cloned())
            .flatten()
            .unwrap_or_default()
    };
    chart
        .configure_mesh()
        .disable_mesh()
        .x_labels(xs.len() + 1)
        .y_labels(ys.len() + 1)
        .x_label_formatter(&lx)
        .y_label_formatter(&ly)
        .x_desc(x_key)
        .y_desc(y_key)
        .label_style(("sans-serif", 14))
        .draw()
        .map_err(e)?;
    let mut by_cell: BTreeMap<(usize, usize), Vec<&Cell>> = BTreeMap::new();
    for c in cells {
        let (Some(i), Some(j)) = (xs.iter().position(|v| *v == c.x), ys.iter().position(|v| *v == c.y)) else {
            continue;
        };
        by_cell.entry((i, j)).or_default().push(c);
    }
    for ((i, j), cs) in &by_cell {
        let m = cs.len() as f64;
        for (k, c) in cs.iter().enumerate() {
            let dx = if m > 1.0 {
                (k as f64 - (m - 1.0) / 2.0) * 0.7 / m
            } else {
                0.0
            };
            let at = (*i as f64 + dx, *j as f64);
            draw_marker(&mut chart, at, c.kind, load_colour(c.load_fraction))?;
        }
    }
    Ok(())
}

/// The legend band: one marker and its name per failure kind present.
fn draw_legend<DB: DrawingBackend>(
    area: &DrawingArea<DB, plotters::coord::Shift>,
    kinds: &BTreeSet<Option<FailureKind>>,
) -> Result<(), String>
where
    DB::ErrorType: 'static,
{
    let e = |x: DrawingAreaErrorKind<DB::ErrorType>| x.to_string();
    let style = ("sans-serif", 15).into_text_style(area);
    let mut x = 30;
    for k in kinds {
        let (parts, filled) = marker_shape(*k, 7.0);
        let grey = RGBColor(80, 80, 80);
        for p in parts {
            if filled {
                area.draw(&(EmptyElement::at((x, 20)) + Polygon::new(p, grey.filled())))
            } else {
                area.draw(&(EmptyElement::at((x, 20)) + PathElement::new(p, grey.stroke_width(3))))
            }
            .map_err(e)?;
        }
        let text = label(*k);
        area.draw_text(&text, &style, (x + 14, 12)).map_err(e)?;
        x += 40 + 9 * text.chars().count() as i32;
    }
    Ok(())
}

fn draw<DB: DrawingBackend>(
    root: DrawingArea<DB, plotters::coord::Shift>,
    title: &str,
    cells: &[Cell],
    keys: (&str, &str),
) -> Result<(), String>
where
    DB::ErrorType: 'static,
{
    let e = |x: DrawingAreaErrorKind<DB::ErrorType>| x.to_string();
    root.fill(&WHITE).map_err(e)?;
    let root = root
        .titled(
            &format!("{title} — colour: load reached (red 0, amber ½, green 1)"),
            ("sans-serif", 22),
        )
        .map_err(e)?;
    let xs = sorted_values(cells.iter().map(|c| &c.x));
    let ys = sorted_values(cells.iter().map(|c| &c.y));
    let mut panels: Vec<&str> = cells
        .iter()
        .map(|c| c.panel.as_str())
        .collect::<BTreeSet<_>>()
        .into_iter()
        .collect();
    panels.sort_by(|a, b| value_cmp(a, b));
    let (h, _) = (root.dim_in_pixel().1, ());
    let (main, band) = root.split_vertically(h.saturating_sub(40));
    let kinds: BTreeSet<Option<FailureKind>> = cells.iter().map(|c| c.kind).collect();
    draw_legend(&band, &kinds)?;
    let (rows, cols) = grid(panels.len());
    let areas = main.split_evenly((rows, cols));
    for (p, area) in panels.iter().zip(areas.iter()) {
        let cs: Vec<&Cell> = cells.iter().filter(|c| c.panel == *p).collect();
        draw_panel(area, p, &cs, (&xs, &ys), keys)?;
    }
    Ok(())
}

/// Rows and columns of the panels: at most four a row.
fn grid(panels: usize) -> (usize, usize) {
    let cols = panels.clamp(1, 4);
    (panels.max(1).div_ceil(cols), cols)
}

/// Draw the stability map of `rows` over `x_key` × `y_key` (`--set` keys swept in the plan)
/// into `path` (.svg or .png), one panel per transfer scheme; returns the plotted cells.
pub fn stability(
    rows: &[IndexRow],
    x_key: &str,
    y_key: &str,
    title: &str,
    path: &Path,
) -> Result<Vec<Cell>, ChartError> {
    stability_by(rows, (x_key, y_key), None, title, path)
}

/// [`stability`] with the panels chosen by `panel` (`"family"`, another swept key, or
/// `None` for the transfer scheme).
pub fn stability_by(
    rows: &[IndexRow],
    (x_key, y_key): (&str, &str),
    panel: Option<&str>,
    title: &str,
    path: &Path,
) -> Result<Vec<Cell>, ChartError> {
    let cs = cells_by(rows, x_key, y_key, panel);
    if cs.is_empty() {
        let keys: BTreeSet<&String> = rows.iter().flat_map(|r| r.params.keys()).collect();
        return Err(ChartError::new(
            path,
            format!(
                "no run of the index has both `{x_key}` and `{y_key}`; its swept keys are {:?}",
                keys
            ),
        ));
    }
    let (rows, cols) = grid(cs.iter().map(|c| &c.panel).collect::<BTreeSet<_>>().len());
    let size = (40 + 520 * cols as u32, 60 + 600 * rows as u32);
    let r = match format_of(path)? {
        Format::Svg => draw(
            SVGBackend::new(path, size).into_drawing_area(),
            title,
            &cs,
            (x_key, y_key),
        ),
        Format::Png => draw(
            BitMapBackend::new(path, size).into_drawing_area(),
            title,
            &cs,
            (x_key, y_key),
        ),
    };
    r.map_err(|m| ChartError::new(path, m))?;
    Ok(cs)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_kind_has_a_distinct_shape() {
        let mut seen = Vec::new();
        for k in std::iter::once(None).chain(FailureKind::ALL.into_iter().map(Some)) {
            let s = marker_shape(k, 6.0);
            assert!(!s.0.is_empty() && s.0.iter().all(|p| p.len() >= 2));
            if !matches!(k, Some(FailureKind::Recording)) {
                assert!(!seen.contains(&s), "{k:?}");
            }
            seen.push(s);
        }
    }
}
