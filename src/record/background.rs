//! An observer on a thread of its own: the solver's thread hands owned copies of the
//! records, in batches, to a bounded channel and goes on solving, while a writer thread serialises them
//! into the wrapped sink (an MCAP file: JSON encoding and chunking cost about as much as a
//! small model's solve). On two cores the recording then costs the solver little more than
//! copying the records.
//!
//! Ordering and completeness are those of the wrapped sink: messages are handled in the
//! order they were sent, and [`Observer::finish`] waits until the writer has handled every
//! earlier record and finished the sink, so a finished run (failed, interrupted or
//! completed) leaves the same file as the sink would have written on the solver's thread.
//! A sink error surfaces at the solver's next call (the run stops there) or at `finish`.

use super::{
    ContactLabels, ContactPointRecord, CrossingRecord, IncrementRecord, IterationRecord, LogRecord, Observer,
    ObserverError, Outcome, RunInfo, StepView,
};
use crate::contact::law::ContactState;
use crate::model::{AnyModel, ModelRef};
use std::sync::mpsc::{sync_channel, Receiver, SyncSender};
use std::sync::{Arc, Mutex};
use std::thread::JoinHandle;

/// Batches queued before the solver waits for the writer.
const QUEUE: usize = 16;

/// A batch is handed over when it holds this many records …
const BATCH_RECORDS: usize = 64;

/// … or this many bytes of copied data (a large model's displacement vectors), whichever
/// comes first. Handing records over one by one woke the writer thread (a futex call on
/// each side) for every Newton iteration: on the 24×1 strip-channel run (12 000 records)
/// that was most of what the recording cost the solver's thread.
const BATCH_BYTES: usize = 1 << 20;

enum Message {
    Start(Box<AnyModel>, Box<RunInfo>),
    Iteration(IterationRecord),
    Increment {
        rec: Box<IncrementRecord>,
        u: Vec<f64>,
        contact: Vec<Point>,
        crossings: Vec<CrossingRecord>,
        surface: Vec<super::surface_contact::SurfacePointRecord>,
    },
    Log(LogRecord),
    Finish(Outcome),
}

/// A contact point record without its names, as handed to the writer thread: a plain copy
/// (the names are shared `Arc`s, and cloning one on the solver's thread while the writer
/// drops another contends for its counter); the writer names the points again from the
/// model ([`ContactLabels`]).
#[derive(Clone, Copy)]
struct Point {
    pair: usize,
    slave: usize,
    segment: Option<usize>,
    previous_segment: Option<usize>,
    xi: f64,
    xi_anchor: f64,
    gap: f64,
    normal_force: f64,
    trial_traction: f64,
    traction: f64,
    state: ContactState,
    crossing: bool,
    position: [f64; 2],
    contact_point: [f64; 2],
    normal: [f64; 2],
    tangent: [f64; 2],
    multiplier: [f64; 2],
    force: [f64; 2],
}

impl Point {
    fn of(p: &ContactPointRecord) -> Self {
        Point {
            pair: p.pair,
            slave: p.slave,
            segment: p.segment,
            previous_segment: p.previous_segment,
            xi: p.xi,
            xi_anchor: p.xi_anchor,
            gap: p.gap,
            normal_force: p.normal_force,
            trial_traction: p.trial_traction,
            traction: p.traction,
            state: p.state,
            crossing: p.crossing,
            position: p.position,
            contact_point: p.contact_point,
            normal: p.normal,
            tangent: p.tangent,
            multiplier: p.multiplier,
            force: p.force,
        }
    }

    /// The record again, named by `labels` (`None` for a pair or slave the model lacks).
    fn record(&self, labels: &ContactLabels) -> Option<ContactPointRecord> {
        let (pair_name, slave_label) = labels.label(self.pair, self.slave)?;
        Some(ContactPointRecord {
            pair: self.pair,
            pair_name,
            slave: self.slave,
            slave_label,
            segment: self.segment,
            previous_segment: self.previous_segment,
            xi: self.xi,
            xi_anchor: self.xi_anchor,
            gap: self.gap,
            normal_force: self.normal_force,
            trial_traction: self.trial_traction,
            traction: self.traction,
            state: self.state,
            crossing: self.crossing,
            position: self.position,
            contact_point: self.contact_point,
            normal: self.normal,
            tangent: self.tangent,
            multiplier: self.multiplier,
            force: self.force,
        })
    }
}

/// The first error of the wrapped sink, shared with the writer thread.
type Failure = Arc<Mutex<Option<ObserverError>>>;

/// Runs a sink on a writer thread (see the module documentation).
pub struct Background {
    name: String,
    tx: Option<SyncSender<Vec<Message>>>,
    /// Records not yet handed over, and the bytes they copied.
    pending: Vec<Message>,
    pending_bytes: usize,
    worker: Option<JoinHandle<Result<(), ObserverError>>>,
    failure: Failure,
}

impl Background {
    /// Start the writer thread for `inner`; `name` names the sink in error messages.
    pub fn new(inner: Box<dyn Observer + Send>, name: &str) -> Self {
        let (tx, rx) = sync_channel(QUEUE);
        let failure: Failure = Arc::default();
        let shared = failure.clone();
        let worker = std::thread::Builder::new()
            .name(format!("contrail-writer {name}"))
            .spawn(move || write(inner, rx, shared))
            .ok();
        Background {
            name: name.to_string(),
            tx: worker.is_some().then_some(tx),
            pending: Vec::with_capacity(BATCH_RECORDS),
            pending_bytes: 0,
            worker,
            failure,
        }
    }

    /// Queue `m` (`bytes`: what it copied); hand the batch over when it is full.
    fn send(&mut self, m: Message, bytes: usize) -> Result<(), ObserverError> {
        self.pending.push(m);
        self.pending_bytes += bytes;
        if self.pending.len() < BATCH_RECORDS && self.pending_bytes < BATCH_BYTES {
            return Ok(());
        }
        self.flush()
    }

    /// Hand the pending records to the writer; reports the writer's first error.
    fn flush(&mut self) -> Result<(), ObserverError> {
        if let Some(e) = self.failure.lock().ok().and_then(|mut f| f.take()) {
            return Err(e);
        }
        let batch = std::mem::replace(&mut self.pending, Vec::with_capacity(BATCH_RECORDS));
        self.pending_bytes = 0;
        let sent = self.tx.as_ref().map(|tx| tx.send(batch).is_ok()).unwrap_or(false);
        if sent {
            Ok(())
        } else {
            Err(self.stopped())
        }
    }

    /// The writer is gone: its result (or why it could not start).
    fn stopped(&mut self) -> ObserverError {
        self.tx = None;
        match self.worker.take().map(JoinHandle::join) {
            Some(Ok(Err(e))) => e,
            Some(Err(_)) => ObserverError::new(&self.name, "the writer thread panicked"),
            _ => ObserverError::new(&self.name, "the writer thread is not running"),
        }
    }
}

fn write(
    mut inner: Box<dyn Observer + Send>,
    rx: Receiver<Vec<Message>>,
    failure: Failure,
) -> Result<(), ObserverError> {
    let mut model: Option<Box<AnyModel>> = None;
    let mut labels = ContactLabels::default();
    let mut records: Vec<ContactPointRecord> = Vec::new();
    let mut failed = false;
    for m in rx.into_iter().flatten() {
        let r = match m {
            Message::Finish(outcome) => return inner.finish(&outcome),
            // after an error the sink sees nothing but `finish`
            _ if failed => Ok(()),
            Message::Start(m, info) => {
                let r = inner.start(m.view(), &info);
                labels = ContactLabels::new(m.view().plane());
                model = Some(m);
                r
            }
            Message::Iteration(rec) => inner.iteration(&rec),
            Message::Increment {
                rec,
                u,
                contact,
                crossings,
                surface,
            } => match &model {
                Some(model) => {
                    records.clear();
                    records.extend(contact.iter().filter_map(|p| p.record(&labels)));
                    inner.increment(
                        &rec,
                        &StepView {
                            model: model.view(),
                            u: &u,
                            contact: &records,
                            crossings: &crossings,
                            surface: &surface,
                        },
                    )
                }
                None => Ok(()),
            },
            Message::Log(rec) => inner.log(&rec),
        };
        if let Err(e) = r {
            failed = true;
            if let Ok(mut f) = failure.lock() {
                f.get_or_insert(e);
            }
        }
    }
    Ok(())
}

impl Observer for Background {
    fn start(&mut self, model: ModelRef<'_>, info: &RunInfo) -> Result<(), ObserverError> {
        self.send(Message::Start(Box::new(model.to_owned()), Box::new(info.clone())), 0)?;
        self.flush()
    }
    fn iteration(&mut self, rec: &IterationRecord) -> Result<(), ObserverError> {
        self.send(Message::Iteration(rec.clone()), std::mem::size_of::<IterationRecord>())
    }
    fn increment(&mut self, rec: &IncrementRecord, view: &StepView) -> Result<(), ObserverError> {
        let bytes = 8 * (view.u.len() + rec.residuals.len())
            + std::mem::size_of::<Point>() * view.contact.len()
            + std::mem::size_of_val(view.crossings);
        let m = Message::Increment {
            rec: Box::new(rec.clone()),
            u: view.u.to_vec(),
            contact: view.contact.iter().map(Point::of).collect(),
            crossings: view.crossings.to_vec(),
            surface: view.surface.to_vec(),
        };
        self.send(m, bytes)
    }
    fn log(&mut self, rec: &LogRecord) -> Result<(), ObserverError> {
        self.send(Message::Log(rec.clone()), rec.message.len())
    }
    /// Hands over what is pending and waits for the writer to handle every record and
    /// finish the sink.
    fn finish(&mut self, outcome: &Outcome) -> Result<(), ObserverError> {
        let earlier = self.failure.lock().ok().and_then(|mut f| f.take());
        self.pending.push(Message::Finish(outcome.clone()));
        let batch = std::mem::take(&mut self.pending);
        let sent = self.tx.take().map(|tx| tx.send(batch).is_ok()).unwrap_or(false);
        let finished = match self.worker.take().map(JoinHandle::join) {
            Some(Ok(r)) if sent => r,
            Some(Ok(Err(e))) => Err(e),
            Some(Err(_)) => Err(ObserverError::new(&self.name, "the writer thread panicked")),
            _ => Err(ObserverError::new(&self.name, "the writer thread is not running")),
        };
        match (earlier, finished) {
            (Some(e), _) => Err(e),
            (None, r) => r,
        }
    }
}

impl Drop for Background {
    /// A run that never called `finish` (a panic) still lets the writer drain and stop.
    fn drop(&mut self) {
        if let (Some(tx), false) = (&self.tx, self.pending.is_empty()) {
            let _ = tx.send(std::mem::take(&mut self.pending));
        }
        self.tx = None;
        if let Some(w) = self.worker.take() {
            let _ = w.join();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A sink that keeps what it got (for the order test) and fails on demand.
    struct Shared(Arc<Mutex<Vec<String>>>, Option<usize>);
    impl Observer for Shared {
        fn iteration(&mut self, rec: &IterationRecord) -> Result<(), ObserverError> {
            if Some(rec.iteration) == self.1 {
                return Err(ObserverError::new("shared", "disk full"));
            }
            self.0.lock().unwrap().push(format!("it {}", rec.iteration));
            Ok(())
        }
        fn finish(&mut self, _o: &Outcome) -> Result<(), ObserverError> {
            self.0.lock().unwrap().push("finish".into());
            Ok(())
        }
    }

    fn it(k: usize) -> IterationRecord {
        IterationRecord {
            increment: 1,
            attempt: 0,
            t: 0.1,
            iteration: k,
            residual: 1.0,
            energy: 1.0,
            reference: 1.0,
            line_search: 1.0,
            active_set_changes: 0,
        }
    }

    fn done() -> Outcome {
        Outcome::Completed { increments: 1, t: 1.0 }
    }

    #[test]
    fn records_arrive_in_order_and_finish_waits_for_them() {
        let seen = Arc::new(Mutex::new(Vec::new()));
        let mut b = Background::new(Box::new(Shared(seen.clone(), None)), "test");
        for k in 1..=1000 {
            b.iteration(&it(k)).unwrap();
        }
        b.finish(&done()).unwrap();
        let seen = seen.lock().unwrap();
        assert_eq!(seen.len(), 1001);
        assert_eq!(seen[0], "it 1");
        assert_eq!(seen[999], "it 1000");
        assert_eq!(seen[1000], "finish");
    }

    /// A `Memory` behind a lock, so the test can look at it after the writer is done.
    struct Locked(Arc<Mutex<crate::record::Memory>>);
    impl Observer for Locked {
        fn increment(&mut self, rec: &IncrementRecord, view: &StepView) -> Result<(), ObserverError> {
            self.0.lock().unwrap().increment(rec, view)
        }
    }

    #[test]
    fn contact_records_reach_the_sink_as_the_solver_made_them() {
        let (src, problem) = crate::load_scene("strip-channel", &["stepping.increments=20".into()]).unwrap();
        let info = crate::run_info(&src, &[], &problem);
        let behind = Arc::new(Mutex::new(crate::record::Memory::default()));
        let mut b = Background::new(Box::new(Locked(behind.clone())), "test");
        let mut direct = crate::record::Memory::default();
        let mut fan = crate::record::Fanout::default();
        fan.sinks.push(&mut b);
        fan.sinks.push(&mut direct);
        let stop = std::sync::atomic::AtomicBool::new(false);
        let _ = crate::solver::run(&problem, &info, &mut fan, &stop);
        drop(fan);
        let behind = behind.lock().unwrap();
        assert_eq!(behind.contact.len(), direct.contact.len());
        assert!(direct.contact.iter().map(Vec::len).sum::<usize>() > 0);
        let json = |c: &Vec<Vec<ContactPointRecord>>| serde_json::to_string(c).unwrap();
        assert_eq!(json(&behind.contact), json(&direct.contact));
    }

    #[test]
    fn a_sink_error_stops_the_run_and_finish_still_reaches_the_sink() {
        let seen = Arc::new(Mutex::new(Vec::new()));
        let mut b = Background::new(Box::new(Shared(seen.clone(), Some(3))), "test");
        let mut first_err = None;
        for k in 1..=2000 {
            if let Err(e) = b.iteration(&it(k)) {
                first_err = Some((k, e.to_string()));
                break;
            }
        }
        let (k, msg) = first_err.expect("the error surfaces at a later call");
        assert!(k > 3 && msg.contains("disk full"), "{k}: {msg}");
        b.finish(&done()).unwrap();
        let seen = seen.lock().unwrap();
        assert_eq!(seen.last().map(String::as_str), Some("finish"));
        assert!(!seen.iter().any(|s| s == "it 4"), "nothing after the error: {seen:?}");
    }
}
