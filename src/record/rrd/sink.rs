//! rerun stream of a run: the deformed mesh, rigid surfaces, contact points and traction
//! arrows in a 2D view (y up; a 3D view, z up, for a model of hexahedra), the force–displacement curve in a second 2D view, Newton
//! residuals and a text log of crossings and messages, on the timelines `increment`
//! (default) and `newton` (a running count of Newton iterations).
//!
//! [`RerunView`] logs from records alone, so `contrail replay` rebuilds the same stream from
//! an MCAP recording; [`RerunSink`] is the observer that feeds it during a run.

use crate::record::interface::{interfaces, InterfaceLayout};
use crate::record::messages::{ModelRecord, PositionsMessage};
pub use crate::record::rrd::view::{RerunView, FLUSH_TIMEOUT};
use crate::record::surface_contact::master_offset;
use crate::record::{IncrementRecord, IterationRecord, LogRecord, Outcome};
use crate::record::{Observer, ObserverError, RunInfo, StepView};
use rerun::blueprint::components::{PanelState, PlayState};
use rerun::blueprint::{
    Blueprint, BlueprintPanel, Horizontal, SelectionPanel, Spatial2DView, Spatial3DView, TextLogView, TimePanel,
    TimeSeriesView, Vertical,
};
use rerun::{RecordingStream, RecordingStreamBuilder};
use std::path::PathBuf;

/// Where the stream goes (any combination).
#[derive(Debug, Clone, Default)]
pub struct RerunTargets {
    /// Write an `.rrd` file.
    pub save: Option<PathBuf>,
    /// Start a viewer (the `rerun` executable on PATH) and stream to it.
    pub spawn: bool,
    /// Stream to a running viewer, e.g. `rerun+http://127.0.0.1:9876/proxy`.
    pub connect: Option<String>,
}

impl RerunTargets {
    pub fn any(&self) -> bool {
        self.save.is_some() || self.spawn || self.connect.is_some()
    }
}

/// The rerun stream could not be opened or written.
#[derive(Debug, thiserror::Error)]
pub enum RerunError {
    #[error("rerun: cannot write {path}: {message}")]
    File { path: String, message: String },
    #[error("rerun: cannot start a viewer: {0}\n  hint: install one with `pip install rerun-sdk==0.36.3`, or use --rerun-save FILE.rrd")]
    Spawn(String),
    #[error("rerun: `{url}` is not a viewer address: {message}\n  hint: e.g. rerun+http://127.0.0.1:9876/proxy")]
    Url { url: String, message: String },
    #[error("{0}")]
    Stream(String),
}

fn stream_err(e: impl std::fmt::Display) -> RerunError {
    RerunError::Stream(e.to_string())
}

/// The default layout, sized for a laptop screen (side and selection panels collapsed, time
/// panel on the `increment` timeline following the latest increment): the model and the
/// event log on the left; the force–displacement curve, the Newton residuals and the load
/// level stacked on the right.
/// A 3D model (`dim` 3) is shown in a 3D view, z up.
pub fn blueprint(dim: usize) -> Blueprint {
    let model: rerun::blueprint::ContainerLike = match dim {
        3 => Spatial3DView::new("model (z up)")
            .with_origin("/")
            .with_contents(["+ /scene/**"])
            .into(),
        _ => Spatial2DView::new("model (y up)")
            .with_origin("/")
            .with_contents(["+ /scene/**"])
            .into(),
    };
    Blueprint::new(
        Horizontal::new([
            Vertical::new([model, TextLogView::new("events").with_origin("/events").into()])
                .with_row_shares(vec![0.74, 0.26])
                .into(),
            Vertical::new([
                Spatial2DView::new("force–displacement")
                    .with_origin("/")
                    .with_contents(["+ /curve/**"])
                    .into(),
                TimeSeriesView::new("Newton: per increment (timeline increment), per iteration (timeline newton)")
                    .with_origin("/plots")
                    .with_contents(["+ /plots/increment/**", "+ /plots/newton"])
                    .into(),
                TimeSeriesView::new("load level t").with_origin("/plots/load").into(),
            ])
            .with_row_shares(vec![0.46, 0.32, 0.22])
            .into(),
        ])
        .with_column_shares(vec![0.6, 0.4]),
    )
    .with_blueprint_panel(BlueprintPanel::from_state(PanelState::Collapsed))
    .with_selection_panel(SelectionPanel::from_state(PanelState::Collapsed))
    .with_time_panel(
        TimePanel::new()
            .with_state(PanelState::Collapsed)
            .with_timeline("increment")
            .with_play_state(PlayState::Following),
    )
}

/// Open a stream to `targets` (application `contrail`, recording named `name`) for a model
/// of dimension `dim`.
pub fn open(targets: &RerunTargets, name: &str, dim: usize) -> Result<RecordingStream, RerunError> {
    let mut sinks: Vec<Box<dyn rerun::sink::LogSink>> = Vec::new();
    if let Some(path) = &targets.save {
        let sink = rerun::sink::FileSink::new(path.clone()).map_err(|e| RerunError::File {
            path: path.display().to_string(),
            message: e.to_string(),
        })?;
        sinks.push(Box::new(sink));
    }
    let mut urls = Vec::new();
    if targets.spawn {
        let info = rerun::spawn(&rerun::SpawnOptions::default()).map_err(|e| RerunError::Spawn(e.to_string()))?;
        urls.push(format!("rerun+http://127.0.0.1:{}/proxy", info.port));
    }
    urls.extend(targets.connect.iter().cloned());
    for url in urls {
        let uri: rerun::external::re_uri::ProxyUri =
            url.parse()
                .map_err(|e: rerun::external::re_uri::Error| RerunError::Url {
                    url: url.clone(),
                    message: e.to_string(),
                })?;
        sinks.push(Box::new(rerun::sink::GrpcSink::new(uri)));
    }
    RecordingStreamBuilder::new("contrail")
        .recording_name(name)
        .with_blueprint(blueprint(dim))
        .set_sinks(sinks)
        .map_err(stream_err)
}

/// The observer: streams a run to rerun as it goes.
pub struct RerunSink {
    stream: Option<RecordingStream>,
    view: Option<RerunView>,
    /// The model's two-pass interfaces, worked out at `start`.
    interfaces: InterfaceLayout,
    name: String,
}

impl RerunSink {
    /// `stream` from [`open`]; `name` names the sink in error messages.
    pub fn new(stream: RecordingStream, name: &str) -> Self {
        RerunSink {
            stream: Some(stream),
            view: None,
            interfaces: InterfaceLayout::default(),
            name: name.to_string(),
        }
    }

    fn view(&mut self) -> Result<&mut RerunView, ObserverError> {
        let name = self.name.clone();
        self.view
            .as_mut()
            .ok_or_else(|| ObserverError::new(&name, "rerun stream not started"))
    }
}

impl Observer for RerunSink {
    fn start(&mut self, model: crate::model::ModelRef<'_>, info: &RunInfo) -> Result<(), ObserverError> {
        let stream = self
            .stream
            .take()
            .ok_or_else(|| ObserverError::new(&self.name, "started twice"))?;
        self.interfaces = InterfaceLayout::new(model.plane());
        self.view = Some(
            RerunView::new(stream, &ModelRecord::of(model, info.settings.stepping.end))
                .map_err(|e| ObserverError::new(&self.name, e))?,
        );
        Ok(())
    }
    fn iteration(&mut self, rec: &IterationRecord) -> Result<(), ObserverError> {
        let name = self.name.clone();
        self.view()?.iteration(rec).map_err(|e| ObserverError::new(&name, e))
    }
    fn increment(&mut self, rec: &IncrementRecord, view: &StepView) -> Result<(), ObserverError> {
        let name = self.name.clone();
        let positions = PositionsMessage::of(rec.increment, rec.t, view.model, view.u);
        let offsets: Vec<[f64; 3]> = match view.model {
            crate::model::ModelRef::Solid(m) => (m.surface_contacts.iter()).map(|p| master_offset(p, rec.t)).collect(),
            crate::model::ModelRef::Plane(_) => Vec::new(),
        };
        let joined = interfaces(
            &self.interfaces,
            view.model.plane(),
            view.u,
            rec.t,
            rec.increment,
            view.contact,
        );
        let v = self.view()?;
        (v.surface(rec.increment, view.surface, &offsets))
            .and_then(|()| v.increment(rec, Some(&positions), view.contact, view.crossings))
            .and_then(|()| v.interfaces(rec.increment, &joined))
            .map_err(|e| ObserverError::new(&name, e))
    }
    fn log(&mut self, rec: &LogRecord) -> Result<(), ObserverError> {
        let name = self.name.clone();
        self.view()?.log(rec).map_err(|e| ObserverError::new(&name, e))
    }
    fn finish(&mut self, outcome: &Outcome) -> Result<(), ObserverError> {
        let Some(mut view) = self.view.take() else {
            return Ok(());
        };
        let r = view.outcome(outcome);
        let f = view.finish();
        r.and(f).map_err(|e| ObserverError::new(&self.name, e))
    }
}
