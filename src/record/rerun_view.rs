//! The rerun view of a run: what is logged where, from records alone (so a replay of an MCAP
//! recording gives the same stream as the run).

use super::messages::{ModelRecord, PositionsMessage};
use super::rerun_sink::RerunError;
use super::{ContactPointRecord, CrossingRecord, IncrementRecord, IterationRecord, LogLevel, LogRecord, Outcome};
use crate::contact::law::ContactState;
use rerun::RecordingStream;

fn stream_err(e: impl std::fmt::Display) -> RerunError {
    RerunError::Stream(e.to_string())
}

/// How long `finish` waits for the sinks (a file is written well within it).
pub const FLUSH_TIMEOUT: std::time::Duration = std::time::Duration::from_secs(20);

const GREY: [u8; 4] = [150, 150, 150, 120];
const MESH: [u8; 4] = [60, 120, 220, 255];
const RIGID: [u8; 4] = [40, 40, 40, 255];
const TRIAL: [u8; 4] = [230, 180, 30, 255];
const RETURNED: [u8; 4] = [220, 40, 40, 255];

fn state_colour(s: ContactState) -> [u8; 4] {
    match s {
        ContactState::Open => [160, 160, 160, 255],
        ContactState::Stick => [30, 170, 60, 255],
        ContactState::Slip => [240, 120, 20, 255],
    }
}

fn p32(p: [f64; 2]) -> [f32; 2] {
    [p[0] as f32, p[1] as f32]
}

/// Logs records to a rerun stream.
pub struct RerunView {
    rec: RecordingStream,
    model: ModelRecord,
    edges: Vec<[usize; 2]>,
    /// Length of the longest arrow, and the largest traction seen so far (arrow scale).
    arrow_len: f64,
    traction_max: f64,
    newton: i64,
}

impl RerunView {
    /// Log the static data (reference mesh, rigid geometry, series styles).
    pub fn new(rec: RecordingStream, model: &ModelRecord) -> Result<Self, RerunError> {
        // no wall-clock timeline: a replay then gives the same stream as the run
        rec.set_log_time_enabled(false);
        rec.set_log_tick_enabled(false);
        let edges = model.edges();
        let (lo, hi) = bbox(&model.nodes);
        let size = (hi[0] - lo[0]).max(hi[1] - lo[1]).max(1e-9);
        let strips = |pos: &[[f64; 2]]| -> Vec<Vec<[f32; 2]>> {
            edges.iter().map(|e| vec![p32(pos[e[0]]), p32(pos[e[1]])]).collect()
        };
        rec.log_static(
            "model/reference",
            &rerun::LineStrips2D::new(strips(&model.nodes))
                .with_colors([GREY])
                .with_radii([rerun::Radius::new_ui_points(0.5)]),
        )
        .map_err(stream_err)?;
        let window = [[lo[0] - size, lo[1] - size], [hi[0] + size, hi[1] + size]];
        for r in &model.rigid {
            let path = format!("rigid/{}", r.name);
            if r.kind == "point" {
                let pts: Vec<[f32; 2]> = r.pieces.iter().flatten().map(|p| p32(*p)).collect();
                rec.log_static(
                    path,
                    &rerun::Points2D::new(pts)
                        .with_colors([RIGID])
                        .with_labels([r.name.clone()])
                        .with_radii([rerun::Radius::new_ui_points(4.0)]),
                )
                .map_err(stream_err)?;
            } else {
                let segs: Vec<Vec<[f32; 2]>> = r
                    .pieces
                    .iter()
                    .flat_map(|pl| pl.windows(2).filter_map(|w| clip(w[0], w[1], window)))
                    .map(|(a, b)| vec![p32(a), p32(b)])
                    .collect();
                rec.log_static(
                    path,
                    &rerun::LineStrips2D::new(segs)
                        .with_colors([RIGID])
                        .with_radii([rerun::Radius::new_ui_points(2.0)]),
                )
                .map_err(stream_err)?;
            }
        }
        for (path, name) in [
            ("plots/load/force", "monitor force"),
            ("plots/load/displacement", "monitor displacement"),
            ("plots/load/normal_force", "sum of normal forces"),
            ("plots/newton/log10_residual", "log10 ‖R‖ / F_ref"),
            ("plots/newton/iterations", "iterations per increment"),
        ] {
            rec.log_static(path, &rerun::SeriesLines::new().with_names([name]))
                .map_err(stream_err)?;
        }
        Ok(RerunView {
            rec,
            model: model.clone(),
            edges,
            arrow_len: 0.12 * size,
            traction_max: 0.0,
            newton: 0,
        })
    }

    fn time(&self, increment: usize, t: f64) {
        self.rec.set_time_sequence("increment", increment as i64);
        self.rec.set_duration_secs("load", t);
        self.rec.set_time_sequence("newton", self.newton);
    }

    pub fn iteration(&mut self, it: &IterationRecord) -> Result<(), RerunError> {
        self.newton += 1;
        self.time(it.increment, it.t);
        let rel = it.residual / it.reference.max(f64::MIN_POSITIVE);
        if rel.is_finite() && rel > 0.0 {
            self.rec
                .log("plots/newton/log10_residual", &rerun::Scalars::single(rel.log10()))
                .map_err(stream_err)?;
        }
        Ok(())
    }

    /// One converged increment; `positions` when the node positions are known.
    pub fn increment(
        &mut self,
        inc: &IncrementRecord,
        positions: Option<&PositionsMessage>,
        contact: &[ContactPointRecord],
        crossings: &[CrossingRecord],
    ) -> Result<(), RerunError> {
        self.time(inc.increment, inc.t);
        let e = stream_err;
        if let Some(p) = positions {
            let strips: Vec<Vec<[f32; 2]>> = self
                .edges
                .iter()
                .filter_map(|ed| Some(vec![p32(*p.nodes.get(ed[0])?), p32(*p.nodes.get(ed[1])?)]))
                .collect();
            self.rec
                .log(
                    "model/deformed",
                    &rerun::LineStrips2D::new(strips)
                        .with_colors([MESH])
                        .with_radii([rerun::Radius::new_ui_points(1.0)]),
                )
                .map_err(e)?;
            for (r, off) in self.model.rigid.iter().zip(&p.rigid_offsets) {
                self.rec
                    .log(
                        format!("rigid/{}", r.name),
                        &rerun::Transform3D::from_translation([off[0] as f32, off[1] as f32, 0.0]),
                    )
                    .map_err(e)?;
            }
        }
        if let Some(m) = &inc.monitor {
            self.rec
                .log("plots/load/force", &rerun::Scalars::single(m.force))
                .map_err(e)?;
            self.rec
                .log("plots/load/displacement", &rerun::Scalars::single(m.displacement))
                .map_err(e)?;
        }
        let total_n: f64 = contact.iter().map(|c| c.normal_force).filter(|x| x.is_finite()).sum();
        self.rec
            .log("plots/load/normal_force", &rerun::Scalars::single(total_n))
            .map_err(e)?;
        self.rec
            .log(
                "plots/newton/iterations",
                &rerun::Scalars::single(inc.iterations as f64),
            )
            .map_err(e)?;
        for c in contact {
            if c.state != ContactState::Open {
                self.traction_max = self.traction_max.max(c.trial_traction.abs()).max(c.traction.abs());
            }
        }
        for (k, pair) in self.model.contacts.iter().enumerate() {
            let pts: Vec<&ContactPointRecord> = contact
                .iter()
                .filter(|c| c.pair == k && c.position.iter().all(|x| x.is_finite()))
                .collect();
            let base = format!("contact/{}", pair.name);
            self.rec
                .log(
                    format!("{base}/points"),
                    &rerun::Points2D::new(pts.iter().map(|c| p32(c.position)))
                        .with_colors(pts.iter().map(|c| state_colour(c.state)))
                        .with_labels(
                            pts.iter()
                                .map(|c| c.segment.map_or("–".to_string(), |s| format!("s{s}"))),
                        )
                        .with_show_labels(true)
                        .with_radii([rerun::Radius::new_ui_points(3.5)]),
                )
                .map_err(e)?;
            let closed: Vec<&&ContactPointRecord> = pts
                .iter()
                .filter(|c| c.state != ContactState::Open && c.tangent.iter().all(|x| x.is_finite()))
                .collect();
            let scale = if self.traction_max > 0.0 {
                self.arrow_len / self.traction_max
            } else {
                0.0
            };
            for (name, colour, value) in [
                (
                    "trial",
                    TRIAL,
                    (|c: &ContactPointRecord| c.trial_traction) as fn(&ContactPointRecord) -> f64,
                ),
                ("returned", RETURNED, |c: &ContactPointRecord| c.traction),
            ] {
                let vecs = closed.iter().map(|c| {
                    let v = value(c) * scale;
                    [(v * c.tangent[0]) as f32, (v * c.tangent[1]) as f32]
                });
                self.rec
                    .log(
                        format!("{base}/{name}"),
                        &rerun::Arrows2D::from_vectors(vecs)
                            .with_origins(closed.iter().map(|c| p32(c.position)))
                            .with_colors([colour]),
                    )
                    .map_err(e)?;
            }
        }
        for c in crossings {
            let pair = self.model.contacts.get(c.pair).map_or("?", |p| p.name.as_str());
            let text = format!(
                "crossing {pair}/{}: segment {} → {}, ξ_A = {:.4}, ξ_B = {:.4}, Δρ = ({:.3e}, {:.3e}), trial {:.4e} → {:.4e}, returned {:.4e}",
                c.slave, c.from_segment, c.to_segment, c.xi_from, c.xi_to, c.delta_rho[0], c.delta_rho[1],
                c.trial_before, c.trial_after, c.returned_after
            );
            self.rec
                .log(
                    "events/crossings",
                    &rerun::TextLog::new(text).with_level(rerun::TextLogLevel::INFO),
                )
                .map_err(e)?;
        }
        Ok(())
    }

    pub fn log(&mut self, l: &LogRecord) -> Result<(), RerunError> {
        if l.increment > 0 {
            self.time(l.increment, l.t);
        }
        // where a message falls among the Newton iterations is not recorded
        self.rec.disable_timeline("newton");
        let level = match l.level {
            LogLevel::Info => rerun::TextLogLevel::INFO,
            LogLevel::Warning => rerun::TextLogLevel::WARN,
            LogLevel::Error => rerun::TextLogLevel::ERROR,
        };
        self.rec
            .log("events/log", &rerun::TextLog::new(l.message.clone()).with_level(level))
            .map_err(stream_err)
    }

    pub fn outcome(&mut self, o: &Outcome) -> Result<(), RerunError> {
        let (text, level) = match o {
            Outcome::Completed { increments, t } => (
                format!("completed: {increments} increments to t = {t}"),
                rerun::TextLogLevel::INFO,
            ),
            Outcome::Failed {
                increment, t, reason, ..
            } => (
                format!("failed in increment {increment} at t = {t}: {reason}"),
                rerun::TextLogLevel::ERROR,
            ),
            Outcome::Interrupted { increment, t } => (
                format!("interrupted during increment {increment} (last converged t = {t})"),
                rerun::TextLogLevel::WARN,
            ),
        };
        self.rec
            .log("events/log", &rerun::TextLog::new(text).with_level(level))
            .map_err(stream_err)
    }

    /// Flush everything to the sinks and close them (the `.rrd` file is complete after this).
    /// A viewer that cannot be reached is given [`FLUSH_TIMEOUT`].
    pub fn finish(self) -> Result<(), RerunError> {
        let r = self.rec.flush_with_timeout(FLUSH_TIMEOUT).map_err(stream_err);
        self.rec.disconnect();
        r
    }
}

fn bbox(pts: &[[f64; 2]]) -> ([f64; 2], [f64; 2]) {
    let mut lo = [f64::INFINITY; 2];
    let mut hi = [f64::NEG_INFINITY; 2];
    for p in pts {
        for k in 0..2 {
            lo[k] = lo[k].min(p[k]);
            hi[k] = hi[k].max(p[k]);
        }
    }
    if lo[0] > hi[0] {
        return ([0.0; 2], [1.0; 2]);
    }
    (lo, hi)
}

/// The part of segment `a b` inside the rectangle `w` (Liang–Barsky), so that far-reaching
/// rigid surfaces do not dwarf the mesh in the view.
fn clip(a: [f64; 2], b: [f64; 2], w: [[f64; 2]; 2]) -> Option<([f64; 2], [f64; 2])> {
    let d = [b[0] - a[0], b[1] - a[1]];
    let (mut t0, mut t1) = (0.0f64, 1.0f64);
    for k in 0..2 {
        for (p, q) in [(-d[k], a[k] - w[0][k]), (d[k], w[1][k] - a[k])] {
            if p == 0.0 {
                if q < 0.0 {
                    return None;
                }
            } else {
                let r = q / p;
                if p < 0.0 {
                    t0 = t0.max(r);
                } else {
                    t1 = t1.min(r);
                }
            }
        }
    }
    (t0 <= t1).then(|| {
        let at = |t: f64| [a[0] + t * d[0], a[1] + t * d[1]];
        (at(t0), at(t1))
    })
}
