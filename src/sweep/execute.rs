//! Running a plan: validate every run first, skip the finished ones, run the rest on
//! `jobs` worker threads (one run per core), record each to MCAP, and rewrite the index
//! after every finished run. Merging shard folders into one index.

use super::expand::{expand, PlannedRun, Shard};
use super::index::{read_records, write_atomic, write_index, write_record, IndexRow, RunRecord};
use super::plan::Plan;
use super::score::score;
use super::SweepError;
use crate::study::{RunOptions, Status, Study};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::mpsc;

/// How to run a plan.
#[derive(Debug, Clone)]
pub struct SweepOptions {
    /// Output folder.
    pub out: PathBuf,
    /// Runs at a time (worker threads); 0 = one per core.
    pub jobs: usize,
    pub shard: Option<Shard>,
    /// Node positions every N-th increment in the recordings.
    pub positions_every: usize,
}

/// What a sweep did.
#[derive(Debug, Clone)]
pub struct SweepReport {
    /// Runs in the plan, in this shard, already finished before, and run now.
    pub planned: usize,
    pub selected: usize,
    pub skipped: usize,
    pub ran: usize,
    /// Stopped before every selected run finished.
    pub interrupted: bool,
    pub index_csv: PathBuf,
    pub index_json: PathBuf,
    pub rows: Vec<IndexRow>,
}

fn io(path: &Path) -> impl FnOnce(std::io::Error) -> SweepError + '_ {
    move |source| SweepError::Io {
        path: path.display().to_string(),
        source,
    }
}

fn index_stem(shard: Option<Shard>) -> String {
    shard.map_or("index".into(), |s| format!("index-shard-{}-of-{}", s.index, s.count))
}

fn local_recording(r: &RunRecord) -> String {
    format!("runs/{}.mcap", r.id)
}

fn record_of(run: &PlannedRun, plan: &Plan, outcome: crate::study::StudyOutcome) -> RunRecord {
    RunRecord {
        id: run.id.clone(),
        ordinal: run.ordinal,
        study: plan.studies[run.study].name.clone(),
        scene: run.scene.clone(),
        params: run.params.clone(),
        sets: run.sets.clone(),
        family: run.family.clone(),
        outcome,
    }
}

/// Every selected run must load and check before any runs.
fn check_runs(selected: &[&PlannedRun]) -> Result<(), SweepError> {
    for r in selected {
        Study::new(r.scene.clone(), r.sets.clone())
            .check()
            .map_err(|source| SweepError::BadRun {
                id: r.id.clone(),
                sets: r.sets.join(" "),
                source: Box::new(source),
            })?;
    }
    Ok(())
}

/// The output folder with its `runs/` and the plan as run (`plan.json`).
fn prepare_folder(out: &Path, plan: &Plan) -> Result<(), SweepError> {
    std::fs::create_dir_all(out.join("runs")).map_err(io(out))?;
    let plan_json = serde_json::to_string_pretty(plan).map_err(|e| SweepError::Index {
        path: out.join("plan.json").display().to_string(),
        message: e.to_string(),
    })?;
    write_atomic(&out.join("plan.json"), plan_json.as_bytes())
}

/// The records already in `out` of the selected runs that finished (an interrupted run is
/// made again).
fn finished_runs(out: &Path, selected: &[&PlannedRun]) -> BTreeMap<String, RunRecord> {
    let wanted: BTreeMap<&str, &PlannedRun> = selected.iter().map(|r| (r.id.as_str(), *r)).collect();
    read_records(out)
        .into_iter()
        .filter(|r| wanted.contains_key(r.id.as_str()) && !matches!(r.outcome.status, Status::Interrupted { .. }))
        .map(|r| (r.id.clone(), r))
        .collect()
}

/// Worker threads: `jobs`, or one per core when 0, never more than the runs to make.
fn worker_count(jobs: usize, pending: usize) -> usize {
    let jobs = if jobs == 0 {
        crate::threads::available_cores()
    } else {
        jobs
    };
    jobs.min(pending.max(1))
}

/// The progress line of the `k`-th finished run of `total`.
fn progress_line(k: usize, total: usize, run: &PlannedRun, outcome: &crate::study::StudyOutcome) -> String {
    let params: Vec<String> = run.params.iter().map(|(k, v)| format!("{k}={v}")).collect();
    let failure = match &outcome.status {
        Status::Failed { kind, increment, .. } => format!(" ({kind} at increment {increment})"),
        _ => String::new(),
    };
    format!(
        "[{k}/{total}] {} {} {}{failure} ({:.2} s)",
        run.id,
        params.join(" "),
        outcome.status.name(),
        outcome.figures.wall_time_s
    )
}

/// One worker thread: takes the next pending run until none is left or `stop` is set, runs
/// it recorded into `opts.out/runs/ID.mcap`, and sends its result.
fn worker<'a>(
    pending: &[&'a PlannedRun],
    threads: usize,
    next: &AtomicUsize,
    opts: &SweepOptions,
    stop: &AtomicBool,
    tx: mpsc::Sender<(
        &'a PlannedRun,
        Result<crate::study::StudyOutcome, crate::study::StudyError>,
    )>,
) {
    while !stop.load(Ordering::Relaxed) {
        let k = next.fetch_add(1, Ordering::SeqCst);
        let Some(run) = pending.get(k) else { break };
        let ro = RunOptions {
            mcap: Some(opts.out.join("runs").join(format!("{}.mcap", run.id))),
            positions_every: opts.positions_every,
            threads,
        };
        let result = Study::new(run.scene.clone(), run.sets.clone()).run(&ro, &mut [], stop);
        if tx.send((*run, result)).is_err() {
            break;
        }
    }
}

/// Run `plan` (or its shard) into `opts.out`. `progress` gets one line per finished run.
/// Stops taking new runs when `stop` is set; runs under way end as interrupted and are not
/// recorded as finished (a later call makes them again).
pub fn run_sweep(
    plan: &Plan,
    opts: &SweepOptions,
    stop: &AtomicBool,
    progress: &(dyn Fn(&str) + Sync),
) -> Result<SweepReport, SweepError> {
    let runs = expand(plan)?;
    let selected: Vec<&PlannedRun> = runs
        .iter()
        .filter(|r| opts.shard.is_none_or(|s| s.contains(r.ordinal)))
        .collect();
    check_runs(&selected)?;
    let out = &opts.out;
    prepare_folder(out, plan)?;
    let mut done = finished_runs(out, &selected);
    let pending: Vec<&PlannedRun> = selected.iter().copied().filter(|r| !done.contains_key(&r.id)).collect();
    let skipped = selected.len() - pending.len();
    let stem = index_stem(opts.shard);
    let write = |done: &BTreeMap<String, RunRecord>| -> Result<_, SweepError> {
        let recs: Vec<RunRecord> = done.values().cloned().collect();
        let rows = score(plan, &recs, &local_recording)?;
        let (csv, json) = write_index(out, &stem, &plan.name, &rows)?;
        Ok((csv, json, rows))
    };
    let (mut csv, mut json, mut rows) = write(&done)?;
    let jobs = worker_count(opts.jobs, pending.len());
    // the runs side by side share the machine: each gets its part of the cores
    let threads = crate::threads::share(crate::threads::available_cores(), jobs);
    progress(&format!(
        "{} runs, {jobs} side by side on {} cores: {threads} thread{} each (a scene's `solver.threads` overrides)",
        pending.len(),
        crate::threads::available_cores(),
        if threads == 1 { "" } else { "s" }
    ));
    let next = AtomicUsize::new(0);
    let (tx, rx) = mpsc::channel();
    let mut ran = 0;
    let mut interrupted = false;
    let mut first_error = None;
    std::thread::scope(|scope| {
        for _ in 0..jobs {
            let tx = tx.clone();
            let (next, pending) = (&next, &pending);
            scope.spawn(move || worker(pending, threads, next, opts, stop, tx));
        }
        drop(tx);
        for (run, result) in rx {
            match result {
                Ok(outcome) => {
                    let line = progress_line(done.len() + 1, selected.len(), run, &outcome);
                    if let Status::Interrupted { .. } = outcome.status {
                        interrupted = true;
                        progress(&line);
                        continue;
                    }
                    let rec = record_of(run, plan, outcome);
                    let res = write_record(out, &rec).and_then(|_| {
                        done.insert(rec.id.clone(), rec);
                        write(&done)
                    });
                    match res {
                        Ok(w) => (csv, json, rows) = w,
                        Err(e) => {
                            stop.store(true, Ordering::SeqCst);
                            first_error.get_or_insert(e);
                        }
                    }
                    ran += 1;
                    progress(&line);
                }
                Err(e) => {
                    stop.store(true, Ordering::SeqCst);
                    first_error.get_or_insert(e.into());
                }
            }
        }
    });
    if let Some(e) = first_error {
        return Err(e);
    }
    interrupted |= done.len() < selected.len();
    Ok(SweepReport {
        planned: runs.len(),
        selected: selected.len(),
        skipped,
        ran,
        interrupted,
        index_csv: csv,
        index_json: json,
        rows,
    })
}

/// Join the run records of several sweep folders of one plan (the shards) into one index in
/// `out`; recordings are referenced where they are. Returns the rows and the index paths.
pub fn merge(dirs: &[PathBuf], out: &Path) -> Result<(Vec<IndexRow>, PathBuf, PathBuf), SweepError> {
    let mut plan: Option<(Plan, PathBuf)> = None;
    let mut records: BTreeMap<String, (RunRecord, PathBuf)> = BTreeMap::new();
    for d in dirs {
        let p = d.join("plan.json");
        let text = std::fs::read_to_string(&p).map_err(|source| SweepError::Io {
            path: p.display().to_string(),
            source,
        })?;
        let this: Plan = serde_json::from_str(&text).map_err(|e| SweepError::Index {
            path: p.display().to_string(),
            message: e.to_string(),
        })?;
        match &plan {
            None => plan = Some((this, d.clone())),
            Some((first, fd)) if *first != this => {
                return Err(SweepError::Merge {
                    message: format!("{} and {} were made from different plans", fd.display(), d.display()),
                    hint: "merge only the shards of one plan".into(),
                })
            }
            _ => {}
        }
        for r in read_records(d) {
            records.entry(r.id.clone()).or_insert((r, d.clone()));
        }
    }
    let Some((plan, _)) = plan else {
        return Err(SweepError::Merge {
            message: "no sweep folders given".into(),
            hint: "contrail sweep merge DIR1 DIR2 ... --out DIR".into(),
        });
    };
    let ids: std::collections::BTreeSet<String> = expand(&plan)?.into_iter().map(|r| r.id).collect();
    let out_canon = std::fs::create_dir_all(out)
        .and_then(|_| out.canonicalize())
        .map_err(io(out))?;
    let place: BTreeMap<String, PathBuf> = records.iter().map(|(k, (_, d))| (k.clone(), d.clone())).collect();
    let recs: Vec<RunRecord> = records
        .into_values()
        .map(|(r, _)| r)
        .filter(|r| ids.contains(&r.id))
        .collect();
    let recording = |r: &RunRecord| {
        let d = &place[&r.id];
        if d.canonicalize().ok().as_ref() == Some(&out_canon) {
            local_recording(r)
        } else {
            d.join(local_recording(r)).display().to_string()
        }
    };
    let rows = score(&plan, &recs, &recording)?;
    let plan_json = serde_json::to_string_pretty(&plan).map_err(|e| SweepError::Index {
        path: out.join("plan.json").display().to_string(),
        message: e.to_string(),
    })?;
    write_atomic(&out.join("plan.json"), plan_json.as_bytes())?;
    let (csv, json) = write_index(out, "index", &plan.name, &rows)?;
    Ok((rows, csv, json))
}
