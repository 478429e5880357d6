//! The force–displacement curve of the rerun view: a separate 2D view (entities under
//! `/curve`) in which the curve grows with the increments as a line strip, the current point
//! is marked and labelled with its values, and increments with a segment crossing carry a
//! marker. Without a monitor the curve is the sum of normal forces against the load level.
//! Each monitor of a scene has its curve: the first under `/curve`, monitor `i ≥ 1` under
//! `/curve/monitor/i`, placed two to a row to the right of and below the first (all in the
//! same view).
//!
//! Both axes are scaled to a box `WIDTH × 1` whose extents are "nice" numbers (1, 2, 5 ×
//! 10ⁿ) at least as large as the largest value so far; the extents are written at the ends of
//! the axes. When an extent grows, the whole curve is logged again on the new scale. The line
//! is logged in pieces of [`PIECE`] points, so a long run does not log its history again at
//! every increment.

use crate::format::plain;
use crate::record::rrd::style::{nice_ceiling, AXES, CURVE, GRID, SLIP, Y_UP_SCALE};
use rerun::RecordingStream;

/// Width of the curve box (its height is 1).
const WIDTH: f64 = 1.6;
/// Space between the boxes of several curves.
const GAP: f32 = 0.6;
/// Points per logged piece of the line.
const PIECE: usize = 100;

/// The curve and what has been logged of it.
pub(crate) struct Curve {
    /// Entity path of the curve (`curve` or `curve/monitor/i`).
    root: String,
    x_name: String,
    y_name: String,
    points: Vec<[f64; 2]>,
    crossings: Vec<[f64; 2]>,
    extent: [f64; 2],
}

type LogResult = Result<(), rerun::RecordingStreamError>;

impl Curve {
    /// Curve `index` (0: the first, under `/curve`) and its static parts: the y-up transform
    /// of `/curve`, or the place of a further curve next to the first.
    pub(crate) fn new(
        rec: &RecordingStream,
        index: usize,
        x_name: &str,
        y_name: &str,
    ) -> Result<Self, rerun::RecordingStreamError> {
        let root = if index == 0 {
            rec.log_static("curve", &rerun::Transform3D::from_scale(Y_UP_SCALE))?;
            "curve".to_string()
        } else {
            let (col, row) = ((index % 2) as f32, (index / 2) as f32);
            let root = format!("curve/monitor/{index}");
            let at = [col * (WIDTH as f32 + GAP), -row * (1.0 + GAP), 0.0];
            rec.log_static(root.as_str(), &rerun::Transform3D::from_translation(at))?;
            root
        };
        Ok(Curve {
            root,
            x_name: x_name.to_string(),
            y_name: y_name.to_string(),
            points: Vec::new(),
            crossings: Vec::new(),
            extent: [0.0, 0.0],
        })
    }

    fn to_box(&self, p: [f64; 2]) -> [f32; 2] {
        [(WIDTH * p[0] / self.extent[0]) as f32, (p[1] / self.extent[1]) as f32]
    }

    fn piece(&self, k: usize) -> Vec<[f32; 2]> {
        let end = ((k + 1) * PIECE + 1).min(self.points.len());
        self.points[k * PIECE..end].iter().map(|p| self.to_box(*p)).collect()
    }

    /// Add the point of the current increment (`crossed`: a segment crossing happened in it).
    pub(crate) fn push(&mut self, rec: &RecordingStream, p: [f64; 2], crossed: bool) -> LogResult {
        if !(p[0].is_finite() && p[1].is_finite()) {
            return Ok(());
        }
        self.points.push(p);
        if crossed {
            self.crossings.push(p);
        }
        let big = |k: usize| self.points.iter().map(|q| q[k].abs()).fold(0.0, f64::max);
        let extent = [nice_ceiling(big(0)), nice_ceiling(big(1))];
        let rescaled = extent != self.extent;
        self.extent = extent;
        let last = (self.points.len() - 1) / PIECE;
        if rescaled {
            self.axes(rec)?;
            for k in 0..last {
                rec.log(format!("{}/line/{k}", self.root), &self.line(self.piece(k)))?;
            }
        }
        // a point that starts a new piece also ends the previous one
        if !rescaled && last > 0 && self.points.len() == last * PIECE + 1 {
            rec.log(
                format!("{}/line/{}", self.root, last - 1),
                &self.line(self.piece(last - 1)),
            )?;
        }
        rec.log(format!("{}/line/{last}", self.root), &self.line(self.piece(last)))?;
        if rescaled || crossed {
            rec.log(
                format!("{}/crossings", self.root),
                &rerun::Points2D::new(self.crossings.iter().map(|p| self.to_box(*p)))
                    .with_colors([SLIP])
                    .with_radii([rerun::Radius::new_ui_points(3.0)]),
            )?;
        }
        rec.log(
            format!("{}/now", self.root),
            &rerun::Points2D::new([self.to_box(p)])
                .with_colors([CURVE])
                .with_radii([rerun::Radius::new_ui_points(5.0)])
                .with_labels([format!(
                    "{} = {}, {} = {}",
                    self.x_name,
                    plain(p[0]),
                    self.y_name,
                    plain(p[1])
                )])
                .with_show_labels(true),
        )
    }

    fn line(&self, pts: Vec<[f32; 2]>) -> rerun::LineStrips2D {
        rerun::LineStrips2D::new([pts])
            .with_colors([CURVE])
            .with_radii([rerun::Radius::new_ui_points(1.5)])
    }

    /// Axes, a thinner frame at the extents with mid-lines, and the extents as labels at the
    /// axis ends.
    fn axes(&self, rec: &RecordingStream) -> LogResult {
        let (w, h) = (WIDTH as f32, 1.0f32);
        rec.log(
            format!("{}/axes", self.root),
            &rerun::LineStrips2D::new([vec![[0.0, 0.0], [w, 0.0]], vec![[0.0, 0.0], [0.0, h]]])
                .with_colors([AXES])
                .with_radii([rerun::Radius::new_ui_points(0.75)]),
        )?;
        rec.log(
            format!("{}/grid", self.root),
            &rerun::LineStrips2D::new([
                vec![[0.0, h], [w, h], [w, 0.0]],
                vec![[w / 2.0, 0.0], [w / 2.0, h]],
                vec![[0.0, h / 2.0], [w, h / 2.0]],
            ])
            .with_colors([GRID])
            .with_radii([rerun::Radius::new_ui_points(0.35)]),
        )?;
        rec.log(
            format!("{}/ticks", self.root),
            &rerun::Points2D::new([[0.0, 0.0], [w, 0.0], [0.0, h], [w / 2.0, 0.0], [0.0, h / 2.0]])
                .with_colors([AXES])
                .with_radii([rerun::Radius::new_ui_points(1.0)])
                .with_labels([
                    "0".to_string(),
                    format!("{} = {}", self.x_name, plain(self.extent[0])),
                    format!("{} = {}", self.y_name, plain(self.extent[1])),
                    plain(self.extent[0] / 2.0),
                    plain(self.extent[1] / 2.0),
                ])
                .with_show_labels(true),
        )
    }
}
