//! The rerun view of a run: what is logged where, from records alone (so a replay of an MCAP
//! recording gives the same stream as the run).
//!
//! Entities: `/scene/**` (the model, y up through one static transform on `/scene`),
//! `/curve/**` (the force–displacement curve, see [`crate::record::rrd::curve`]), `/plots/newton`
//! (per Newton iteration, timeline `newton` only), `/plots/increment/**` (per increment:
//! Newton iterations, final residual, load level; timeline `increment` only) and `/events/**`.
//! A 3D model is drawn by [`crate::record::rrd::view3d`] under the same `/scene`, z up.

use crate::format::{plain, sig};
use crate::record::interface::InterfaceRecord;
use crate::record::messages::{ModelRecord, PositionsMessage};
use crate::record::rrd::curve::Curve;
use crate::record::rrd::sink::RerunError;
use crate::record::rrd::style::{
    point_colour, point_label, relative_residual, traction_arrows, TractionArrows, ARROW_FRACTION,
    ARROW_OFFSET_FRACTION, MESH, PRESSURE, REFERENCE, RETURNED, RIGID, TRIAL, Y_UP_SCALE,
};
use crate::record::rrd::view3d::SolidView;
use crate::record::surface_contact::SurfacePointRecord;
use crate::record::{
    ContactPointRecord, CrossingRecord, IncrementRecord, IterationRecord, LogLevel, LogRecord, Outcome,
};
use rerun::RecordingStream;

fn stream_err(e: impl std::fmt::Display) -> RerunError {
    RerunError::Stream(e.to_string())
}

/// How long `finish` waits for the sinks (a file is written well within it).
pub const FLUSH_TIMEOUT: std::time::Duration = std::time::Duration::from_secs(20);

fn p32(p: [f64; 2]) -> [f32; 2] {
    [p[0] as f32, p[1] as f32]
}

/// Logs records to a rerun stream.
pub struct RerunView {
    rec: RecordingStream,
    model: ModelRecord,
    edges: Vec<[usize; 2]>,
    /// Arrow length at the Coulomb limit and offset of the arrows from the face.
    arrow_len: f64,
    arrow_offset: f64,
    /// One force–displacement curve per monitor (or `ΣN` against `t` without one).
    curves: Vec<Curve>,
    /// Running count of Newton iterations (timeline `newton`).
    newton: i64,
    /// Reference force of the last Newton iteration (for the final residual of an increment).
    reference: f64,
    /// The 3D part of the view (a model of hexahedra).
    solid: Option<SolidView>,
    /// `ΣN` of the 3D points given to [`Self::surface`] for the coming increment.
    surface_normal: f64,
}

impl RerunView {
    /// Log the static data (the y-up transform, reference mesh, rigid geometry, series
    /// styles).
    pub fn new(rec: RecordingStream, model: &ModelRecord) -> Result<Self, RerunError> {
        // no wall-clock timeline: a replay then gives the same stream as the run
        rec.set_log_time_enabled(false);
        rec.set_log_tick_enabled(false);
        let e = stream_err;
        let edges = model.edges();
        let (lo, hi) = bbox(&model.nodes);
        let size = (hi[0] - lo[0]).max(hi[1] - lo[1]).max(1e-9);
        let solid = match model.dim() {
            3 => Some(SolidView::new(&rec, model)?),
            _ => {
                rec.log_static("scene", &rerun::Transform3D::from_scale(Y_UP_SCALE))
                    .map_err(e)?;
                None
            }
        };
        let strips = |pos: &[[f64; 2]]| -> Vec<Vec<[f32; 2]>> {
            edges.iter().map(|e| vec![p32(pos[e[0]]), p32(pos[e[1]])]).collect()
        };
        rec.log_static(
            "scene/model/reference",
            &rerun::LineStrips2D::new(strips(&model.nodes))
                .with_colors([REFERENCE])
                .with_radii([rerun::Radius::new_ui_points(0.5)]),
        )
        .map_err(e)?;
        let window = [[lo[0] - size, lo[1] - size], [hi[0] + size, hi[1] + size]];
        for r in &model.rigid {
            let path = format!("scene/rigid/{}", r.name);
            if r.kind == "point" {
                let pts: Vec<[f32; 2]> = r.pieces.iter().flatten().map(|p| p32(*p)).collect();
                rec.log_static(
                    path,
                    &rerun::Points2D::new(pts)
                        .with_colors([RIGID])
                        .with_radii([rerun::Radius::new_ui_points(6.0)]),
                )
                .map_err(e)?;
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
                        .with_radii([rerun::Radius::new_ui_points(3.0)]),
                )
                .map_err(e)?;
            }
        }
        for (path, name) in [
            ("plots/newton", "log10 ‖R‖/F_ref per iteration"),
            ("plots/increment/iterations", "Newton iterations"),
            ("plots/increment/final_residual", "log10 final ‖R‖/F_ref"),
            ("plots/load/t", "load level t"),
        ] {
            rec.log_static(path, &rerun::SeriesLines::new().with_names([name]))
                .map_err(e)?;
        }
        let labels = model.monitor_labels();
        let curves = if labels.is_empty() {
            vec![Curve::new(&rec, 0, "t", "ΣN").map_err(e)?]
        } else {
            (labels.iter().enumerate())
                .map(|(i, l)| Curve::new(&rec, i, l, "force"))
                .collect::<Result<Vec<_>, _>>()
                .map_err(e)?
        };
        Ok(RerunView {
            rec,
            model: model.clone(),
            edges,
            arrow_len: ARROW_FRACTION * size,
            arrow_offset: ARROW_OFFSET_FRACTION * size,
            curves,
            newton: 0,
            reference: 0.0,
            solid,
            surface_normal: 0.0,
        })
    }

    /// Per-increment data: on `increment`, and on `newton` at the last iteration so that the
    /// model stays visible on that timeline.
    fn at_increment(&self, increment: usize) {
        self.rec.reset_time();
        self.rec.set_time_sequence("increment", increment as i64);
        self.rec.set_time_sequence("newton", self.newton);
    }

    /// One Newton iteration: its relative residual on the `newton` timeline only.
    pub fn iteration(&mut self, it: &IterationRecord) -> Result<(), RerunError> {
        self.newton += 1;
        if it.reference > 0.0 {
            self.reference = it.reference;
        }
        self.rec.reset_time();
        self.rec.set_time_sequence("newton", self.newton);
        if let Some(rel) = relative_residual(it.residual, it.reference) {
            self.rec
                .log("plots/newton", &rerun::Scalars::single(rel.log10()))
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
        let e = stream_err;
        self.at_increment(inc.increment);
        if let Some(p) = positions {
            self.positions(p)?;
        }
        self.contact(contact, crossings)?;
        let total_n: f64 = contact
            .iter()
            .map(|c| c.normal_force)
            .filter(|x| x.is_finite())
            .sum::<f64>()
            + std::mem::take(&mut self.surface_normal);
        let monitors = inc.all_monitors();
        let crossed = !crossings.is_empty();
        if monitors.is_empty() {
            if let Some(c) = self.curves.first_mut() {
                c.push(&self.rec, [inc.t, total_n], crossed).map_err(e)?;
            }
        }
        for (c, m) in self.curves.iter_mut().zip(&monitors) {
            c.push(&self.rec, [m.displacement, m.force], crossed).map_err(e)?;
        }
        for c in crossings {
            let pair = self.model.contacts.get(c.pair).map_or("?", |p| p.name.as_str());
            let slave = self
                .model
                .contacts
                .get(c.pair)
                .and_then(|p| p.slaves.get(c.slave))
                .map_or_else(|| c.slave.to_string(), Clone::clone);
            let text = format!(
                "crossing {pair}/{slave}: segment {} → {}, ξ_A = {}, ξ_B = {}, Δρ = ({}, {}), trial {} → {}, returned {}",
                c.from_segment,
                c.to_segment,
                sig(c.xi_from, 4),
                sig(c.xi_to, 4),
                sig(c.delta_rho[0], 3),
                sig(c.delta_rho[1], 3),
                sig(c.trial_before, 4),
                sig(c.trial_after, 4),
                sig(c.returned_after, 4)
            );
            self.rec
                .log(
                    "events/crossings",
                    &rerun::TextLog::new(text).with_level(rerun::TextLogLevel::INFO),
                )
                .map_err(e)?;
        }
        // the per-increment summary lives on `increment` only
        self.rec.disable_timeline("newton");
        self.rec
            .log(
                "plots/increment/iterations",
                &rerun::Scalars::single(inc.iterations as f64),
            )
            .map_err(e)?;
        if let Some(rel) = inc.residuals.last().and_then(|r| relative_residual(*r, self.reference)) {
            self.rec
                .log("plots/increment/final_residual", &rerun::Scalars::single(rel.log10()))
                .map_err(e)?;
        }
        self.rec.log("plots/load/t", &rerun::Scalars::single(inc.t)).map_err(e)
    }

    /// The 3D contact points of increment `increment` and the rigid masters' offsets (one
    /// per pair; see [`SolidView::contact`]); called before [`Self::increment`] of the same
    /// increment, whose `ΣN` curve then includes them.
    pub fn surface(
        &mut self,
        increment: usize,
        points: &[SurfacePointRecord],
        offsets: &[[f64; 3]],
    ) -> Result<(), RerunError> {
        let Some(solid) = &self.solid else {
            return Ok(());
        };
        self.at_increment(increment);
        self.surface_normal = points.iter().map(|p| p.normal_force).filter(|x| x.is_finite()).sum();
        solid.contact(&self.rec, points, offsets)
    }

    fn positions(&mut self, p: &PositionsMessage) -> Result<(), RerunError> {
        let e = stream_err;
        if let Some(solid) = &self.solid {
            return solid.positions(&self.rec, &p.nodes_3d);
        }
        let strips: Vec<Vec<[f32; 2]>> = self
            .edges
            .iter()
            .filter_map(|ed| Some([*p.nodes.get(ed[0])?, *p.nodes.get(ed[1])?]))
            // an edge with an end not recorded (`--positions-of surface`) is not drawn
            .filter(|ends| ends.iter().flatten().all(|x| x.is_finite()))
            .map(|ends| ends.map(p32).to_vec())
            .collect();
        self.rec
            .log(
                "scene/model/deformed",
                &rerun::LineStrips2D::new(strips)
                    .with_colors([MESH])
                    .with_radii([rerun::Radius::new_ui_points(1.0)]),
            )
            .map_err(e)?;
        for (r, off) in self.model.rigid.iter().zip(&p.rigid_offsets) {
            self.rec
                .log(
                    format!("scene/rigid/{}", r.name),
                    &rerun::Transform3D::from_translation([off[0] as f32, off[1] as f32, 0.0]),
                )
                .map_err(e)?;
        }
        Ok(())
    }

    fn contact(&mut self, contact: &[ContactPointRecord], crossings: &[CrossingRecord]) -> Result<(), RerunError> {
        let e = stream_err;
        for (k, pair) in self.model.contacts.iter().enumerate() {
            let pts: Vec<&ContactPointRecord> = contact
                .iter()
                .filter(|c| c.pair == k && c.position.iter().all(|x| x.is_finite()))
                .collect();
            let base = format!("scene/contact/{}", pair.name);
            let labelled: Vec<(&ContactPointRecord, String)> = pts
                .iter()
                .filter_map(|c| {
                    let from = crossings
                        .iter()
                        .find(|x| x.pair == k && x.slave == c.slave)
                        .map(|x| x.from_segment);
                    point_label(c, from).map(|l| (*c, l))
                })
                .collect();
            let radius = rerun::Radius::new_ui_points(3.5);
            self.rec
                .log(
                    format!("{base}/points"),
                    &rerun::Points2D::new(pts.iter().map(|c| p32(c.position)))
                        .with_colors(pts.iter().map(|c| point_colour(c.state, pair.mu)))
                        .with_radii([radius]),
                )
                .map_err(e)?;
            self.rec
                .log(
                    format!("{base}/labels"),
                    &rerun::Points2D::new(labelled.iter().map(|(c, _)| p32(c.position)))
                        .with_colors(labelled.iter().map(|(c, _)| point_colour(c.state, pair.mu)))
                        .with_labels(labelled.iter().map(|(_, l)| l.clone()))
                        .with_show_labels(true)
                        .with_radii([radius]),
                )
                .map_err(e)?;
            let arrows: Vec<TractionArrows> = pts
                .iter()
                .filter_map(|c| traction_arrows(c, pair.mu, self.arrow_len, self.arrow_offset))
                .collect();
            let origins: Vec<[f32; 2]> = arrows.iter().map(|a| p32(a.origin)).collect();
            let trial: Vec<[f32; 2]> = arrows.iter().map(|a| p32(a.trial)).collect();
            let returned: Vec<[f32; 2]> = arrows.iter().map(|a| p32(a.returned)).collect();
            for (name, colour, radius, vectors) in [("trial", TRIAL, 1.0, trial), ("returned", RETURNED, 2.0, returned)]
            {
                self.rec
                    .log(
                        format!("{base}/{name}"),
                        &rerun::Arrows2D::from_vectors(vectors)
                            .with_origins(origins.iter().copied())
                            .with_colors([colour])
                            .with_radii([rerun::Radius::new_ui_points(radius)]),
                    )
                    .map_err(e)?;
            }
        }
        Ok(())
    }

    /// The two-pass interfaces of an increment (after [`RerunView::increment`]): under
    /// `scene/interface/NAME`, the nodes of the first pass's master face coloured by the
    /// interface's state (`nodes`) and its pressure as arrows into that face, the largest
    /// as long as a traction arrow at the Coulomb limit (`pressure`).
    pub fn interfaces(&mut self, increment: usize, interfaces: &[InterfaceRecord]) -> Result<(), RerunError> {
        let e = stream_err;
        if interfaces.is_empty() {
            return Ok(());
        }
        self.at_increment(increment);
        for f in interfaces {
            let mu = self.model.contacts.get(f.first_pass).map_or(0.0, |p| p.mu);
            let base = format!("scene/interface/{}", f.name);
            self.rec
                .log(
                    format!("{base}/nodes"),
                    &rerun::Points2D::new(f.position.iter().map(|p| p32(*p)))
                        .with_colors(f.state.iter().map(|s| point_colour(*s, mu)))
                        .with_radii([rerun::Radius::new_ui_points(2.5)]),
                )
                .map_err(e)?;
            let top = f
                .pressure
                .iter()
                .filter(|p| p.is_finite())
                .fold(0.0, |a: f64, p| a.max(p.abs()));
            let scale = if top > 0.0 { self.arrow_len / top } else { 0.0 };
            let vectors = (f.normal.iter().zip(&f.pressure)).map(|(n, p)| {
                if p.is_finite() {
                    p32([-n[0] * p * scale, -n[1] * p * scale])
                } else {
                    [0.0; 2]
                }
            });
            self.rec
                .log(
                    format!("{base}/pressure"),
                    &rerun::Arrows2D::from_vectors(vectors)
                        .with_origins(f.position.iter().map(|p| p32(*p)))
                        .with_colors([PRESSURE])
                        .with_radii([rerun::Radius::new_ui_points(1.5)]),
                )
                .map_err(e)?;
        }
        Ok(())
    }

    /// A log message (cut-back, failure) on the `increment` timeline.
    pub fn log(&mut self, l: &LogRecord) -> Result<(), RerunError> {
        if l.increment > 0 {
            self.at_increment(l.increment);
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

    /// How the run ended, as the last line of the event log.
    pub fn outcome(&mut self, o: &Outcome) -> Result<(), RerunError> {
        let (text, level) = match o {
            Outcome::Completed { increments, t } => (
                format!("completed: {increments} increments to t = {}", plain(*t)),
                rerun::TextLogLevel::INFO,
            ),
            Outcome::Failed {
                increment, t, reason, ..
            } => (
                format!("failed in increment {increment} at t = {}: {reason}", plain(*t)),
                rerun::TextLogLevel::ERROR,
            ),
            Outcome::Interrupted { increment, t } => (
                format!(
                    "interrupted during increment {increment} (last converged t = {})",
                    plain(*t)
                ),
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

pub(crate) fn bbox(pts: &[[f64; 2]]) -> ([f64; 2], [f64; 2]) {
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
pub(crate) fn clip(a: [f64; 2], b: [f64; 2], w: [[f64; 2]; 2]) -> Option<([f64; 2], [f64; 2])> {
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
