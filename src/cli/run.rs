//! `contrail run`: solve a scene, write the requested files, and say how it went.

use super::out::out;
use super::progress::Progress;
use super::summary::{inspect_hint, progress_lines, Tracker};
use super::{BadInput, RunFailed};
use contrail::format::{compact_list, plain};
use contrail::record::background::Background;
use contrail::record::mcap::sink::{ChunkCompression, Iterations, McapOptions, McapSink, SceneEvery};
use contrail::record::packed_positions::{PositionsOf, Precision};
use contrail::record::rrd::sink::{self as rerun_sink, RerunSink};
use contrail::record::text::csv::CsvSink;
use contrail::record::text::jsonl::JsonlSink;
use contrail::record::vtu::sink::VtuSink;
use contrail::record::Observer;
use contrail::solver::{RunSummary, SolveError};
use contrail::study::{run_loaded, ProgressLine, ProgressSink};
use std::io::{BufWriter, IsTerminal};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

#[derive(clap::Args, Debug)]
pub struct RunArgs {
    /// Built-in scene name or path to a scene TOML file.
    pub scene: String,
    /// Write the run to FILE: `.csv` (load–displacement history), `.jsonl` (every record),
    /// `.mcap` (every record, JSON messages with JSON Schemas, compressed chunks) or `.pvd`
    /// (ParaView: a VTU series of the mesh with displacement, stress and strain, and of the
    /// contact points, in the directory `FILE` without `.pvd`). Repeatable:
    /// `--out run.mcap --out run.csv`.
    #[arg(long, value_name = "FILE")]
    pub out: Vec<PathBuf>,
    /// In an `.mcap` recording, write node positions every N-th increment (and the last).
    #[arg(long, value_name = "N", default_value_t = 1, value_parser = clap::value_parser!(u64).range(1..))]
    pub positions_every: u64,
    /// In an `.mcap` recording, write the positions of every node (`all`) or of the nodes on
    /// the boundary of the mesh (`surface`: what a view draws; a 3D model's interior nodes are
    /// most of its nodes). Contact data is always written in full.
    #[arg(long, value_enum, value_name = "WHICH", default_value_t = PositionsOf::All)]
    pub positions_of: PositionsOf,
    /// In an `.mcap` recording, write node positions as doubles, bit for bit (`double`), or
    /// rounded to singles (`single`: a relative error of at most 6e-8, half the digits).
    /// Contact data is always written in full.
    #[arg(long, value_enum, value_name = "PRECISION", default_value_t = Precision::Double)]
    pub positions_precision: Precision,
    /// Compression of the `.mcap` chunks: zstd (at `--compression-level`), lz4 or none.
    #[arg(long, value_enum, value_name = "KIND", default_value_t = ChunkCompression::Zstd)]
    pub compression: ChunkCompression,
    /// zstd level of the `.mcap` chunks: 1–19 (higher: smaller files, slower to write) or
    /// −1 to −7 (zstd's fast levels: faster, larger).
    #[arg(long, value_name = "LEVEL", default_value_t = 1, allow_negative_numbers = true,
          value_parser = clap::value_parser!(i32).range(-7..=19))]
    pub compression_level: i32,
    /// In an `.mcap` recording, write the `/contact` entries of slave nodes that stay out of
    /// reach at every increment too (by default they are left out where `/positions` is
    /// written; readers restore them).
    #[arg(long)]
    pub all_points: bool,
    /// Which Newton iterations an `.mcap` recording writes on `/iteration`: all (default) or
    /// those of failed attempts only.
    #[arg(long, value_enum, value_name = "WHICH", default_value_t = Iterations::All)]
    pub iterations: Iterations,
    #[command(flatten)]
    pub foxglove: SceneArgs,
    /// In a `.pvd` series, write every N-th increment (and the last).
    #[arg(long, value_name = "N", default_value_t = 1, value_parser = clap::value_parser!(u64).range(1..))]
    pub vtu_every: u64,
    #[command(flatten)]
    pub rerun: super::replay::RerunArgs,
    /// Override a scene value, e.g. --set contact.mu=0.1 (repeatable).
    #[arg(long = "set", value_name = "KEY=VALUE")]
    pub sets: Vec<String>,
    /// Threads this run may use, the solver's included (default: the scene's
    /// `solver.threads`, else every core this process may use). The answer does not depend
    /// on it; on a machine shared with other runs, 1 is the fair share.
    #[arg(long, value_name = "N", env = "CONTRAIL_THREADS", value_parser = clap::value_parser!(u64).range(1..))]
    pub threads: Option<u64>,
    /// No progress bar.
    #[arg(long)]
    pub quiet: bool,
    /// Write the progress as JSON lines to FILE (`-`: standard output, before the summary):
    /// one line per converged increment, and the typed outcome (status, failure kind,
    /// figures, load–displacement curve) as the last line. `contrail serve` reads it.
    #[arg(long, value_name = "FILE")]
    pub progress: Option<PathBuf>,
}

fn progress_sink(path: &Path) -> anyhow::Result<ProgressSink> {
    let out: Box<dyn std::io::Write + Send> = if path == Path::new("-") {
        Box::new(std::io::stdout())
    } else {
        Box::new(open(path)?)
    };
    Ok(ProgressSink::new(out, &path.display().to_string()))
}

/// Which increments of an `.mcap` recording get a Foxglove scene.
#[derive(clap::Args, Debug, Clone)]
pub struct SceneArgs {
    /// In an `.mcap` recording, draw the model for Foxglove (`/foxglove/scene`) every N-th
    /// increment, `auto` (about 200 scenes per run, at increments with positions) or `off`;
    /// the reference configuration
    /// and the last increment always get one unless `off`.
    #[arg(long, value_name = "N|auto|off", default_value = "auto", value_parser = parse_scene_every)]
    pub scene_every: SceneEvery,
}

fn parse_scene_every(s: &str) -> Result<SceneEvery, String> {
    match s {
        "auto" => Ok(SceneEvery::Auto),
        "off" | "0" => Ok(SceneEvery::Off),
        n => n
            .parse::<usize>()
            .map(SceneEvery::Every)
            .map_err(|_| format!("`{n}`: give a number of increments, `auto` or `off`")),
    }
}

fn open(path: &Path) -> anyhow::Result<BufWriter<std::fs::File>> {
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir)
            .map_err(|e| BadInput(format!("{}: cannot create directory: {e}", dir.display())))?;
    }
    let f = std::fs::File::create(path).map_err(|e| BadInput(format!("{}: cannot create: {e}", path.display())))?;
    Ok(BufWriter::new(f))
}

fn sink(path: &Path, a: &RunArgs) -> anyhow::Result<Box<dyn Observer>> {
    let (positions_every, vtu_every) = (a.positions_every, a.vtu_every);
    let name = path.display().to_string();
    Ok(match path.extension().and_then(|e| e.to_str()) {
        Some("csv") => Box::new(CsvSink::new(open(path)?, &name)),
        Some("jsonl") => Box::new(JsonlSink::new(open(path)?, &name)),
        Some("mcap") => {
            let opts = McapOptions {
                positions_every: positions_every as usize,
                positions_of: a.positions_of,
                positions_precision: a.positions_precision,
                compression: a.compression,
                compression_level: a.compression_level,
                thin_out_of_reach: !a.all_points,
                iterations: a.iterations,
                scene: a.foxglove.scene_every,
                ..McapOptions::default()
            };
            if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
                std::fs::create_dir_all(dir)
                    .map_err(|e| BadInput(format!("{}: cannot create directory: {e}", dir.display())))?;
            }
            // written as `.NAME.PID.N.part` beside it and renamed when finished: a reader never
            // sees a half-written file under the name, and concurrent runs do not mix
            let mcap = McapSink::create(path, opts).map_err(|e| BadInput(e.to_string()))?;
            // serialised and written on a thread of its own (`record::background`)
            Box::new(Background::new(Box::new(mcap), &name))
        }
        Some("pvd") => Box::new(
            VtuSink::create(path, vtu_every as usize)
                .map_err(|e| BadInput(format!("{name}: cannot create the VTU series: {e}")))?,
        ),
        _ => return Err(BadInput(format!("{name}: unknown output kind; use .csv, .jsonl, .mcap or .pvd")).into()),
    })
}

pub fn run(a: RunArgs) -> anyhow::Result<ExitCode> {
    super::scenes::check_scene_arg(&a.scene)?;
    for (i, p) in a.out.iter().enumerate() {
        if a.out[..i].contains(p) {
            return Err(BadInput(format!("--out {} is given twice", p.display())).into());
        }
    }
    match contrail::load_any_scene(&a.scene, &a.sets)? {
        (src, contrail::scene::AnyProblem::Plane(problem)) => run_problem(a, src, problem),
        (src, contrail::scene::AnyProblem::Solid(problem)) => run_problem(a, src, problem),
    }
}

/// Run a loaded problem of either dimension and print its summary.
fn run_problem<S: contrail::model::Dim>(
    a: RunArgs,
    src: contrail::scene::SceneSource,
    mut problem: contrail::problem::Problem<S>,
) -> anyhow::Result<ExitCode> {
    if let Some(n) = a.threads {
        problem.settings.newton.threads = n as usize;
    }
    let model = &problem.model;
    let info = contrail::run_info(&src, &a.sets, &problem);
    let stop = super::signal::stop_flag();
    let mut sinks = sinks(&a, &problem)?;
    let mut tracker = Tracker::default();
    let mut progress = a.progress.as_deref().map(progress_sink).transpose()?;
    let finished = {
        let mut observers: Vec<&mut dyn Observer> = sinks.iter_mut().map(|s| s.as_mut() as &mut dyn Observer).collect();
        observers.push(&mut tracker);
        if let Some(p) = progress.as_mut() {
            observers.push(p);
        }
        run_loaded(&problem, &info, &mut observers, &stop)
    };
    drop(sinks);
    let result = finished.result;
    if let Some(p) = progress.as_mut() {
        let culprit = match &result {
            Err(SolveError::StepFailed { points, .. }) => points.clone(),
            _ => Vec::new(),
        };
        let outcome = Box::new(finished.outcome);
        p.write(&ProgressLine::End { outcome, culprit })?;
    }
    let mcap = a.out.iter().find(|p| p.extension().is_some_and(|e| e == "mcap"));
    let mut o = String::new();
    row(&mut o, "scene", format!("{} ({})", model.name, src.origin));
    let transfer = match info.transfer.is_empty() {
        true => "none (no contact pairs)".to_string(),
        false => info.transfer.join(", "),
    };
    row(&mut o, "transfer", transfer);
    ended_rows(&mut o, &result, &mut tracker);
    progress_lines(&mut o, &tracker);
    if let Ok(s) = &result {
        summary_rows(&mut o, s);
    }
    for p in &a.out {
        row(&mut o, "written", p.display().to_string());
    }
    if let Some(p) = &a.rerun.rerun_save {
        row(
            &mut o,
            "written",
            format!("{} (view it with `rerun {}`)", p.display(), p.display()),
        );
    }
    if result.is_err() || mcap.is_some() {
        row(&mut o, "inspect", inspect_hint(mcap.map(PathBuf::as_path), &model.name));
    }
    out!("{o}")?;
    exit(result, &format!("{} ({})", model.name, src.origin), mcap)
}

/// The sinks the arguments ask for: `--out` files, rerun, the terminal's progress bar.
fn sinks<S: contrail::model::Dim>(
    a: &RunArgs,
    problem: &contrail::problem::Problem<S>,
) -> anyhow::Result<Vec<Box<dyn Observer>>> {
    let mut sinks: Vec<Box<dyn Observer>> = Vec::new();
    for path in &a.out {
        sinks.push(sink(path, a)?);
    }
    let targets = a.rerun.targets();
    if targets.any() {
        let stream = rerun_sink::open(&targets, &problem.model.name, S::D).map_err(|e| BadInput(e.to_string()))?;
        sinks.push(Box::new(RerunSink::new(stream, "rerun")));
    }
    if !a.quiet && std::io::stderr().is_terminal() {
        sinks.push(Box::new(Progress::new(problem.settings.stepping.end)));
    }
    Ok(sinks)
}

/// One `key  value` line of the summary.
fn row(o: &mut String, k: &str, v: String) {
    o.push_str(&format!("{k:<12} {v}\n"));
}

/// How the run ended: completed, or where and why it stopped.
fn ended_rows(o: &mut String, result: &Result<RunSummary, SolveError>, tracker: &mut Tracker) {
    match result {
        Ok(_) => row(o, "ended", "completed".into()),
        Err(SolveError::StepFailed {
            increment,
            t,
            dt,
            cutbacks,
            reason,
            residuals,
            kind,
            points,
        }) => {
            row(o, "ended", "FAILED".into());
            row(
                o,
                "stopped",
                format!(
                    "increment {increment} at t = {} (step {}, after {}): {reason}",
                    plain(*t),
                    plain(*dt),
                    contrail::format::count(*cutbacks, "cut-back", "cut-backs")
                ),
            );
            row(o, "residuals", compact_list(residuals, 8));
            row(o, "kind", kind.as_str().into());
            for p in points.iter().take(4) {
                row(o, "changing", p.describe());
            }
            tracker.cutbacks += cutbacks;
        }
        Err(SolveError::Interrupted { increment, .. }) => {
            row(o, "ended", format!("interrupted during increment {increment}"))
        }
        Err(SolveError::Observer(e)) => row(o, "ended", format!("recording failed: {e}")),
    }
}

/// The run's figures: wall time and where it went, multiplier updates, the linear solver,
/// elements that lost stability.
fn summary_rows(o: &mut String, s: &RunSummary) {
    row(
        o,
        "wall time",
        format!("{} s", plain((s.wall_time_s * 1e3).round() / 1e3)),
    );
    row(o, "time spent", time_split(s));
    if let Some(e) = s.equilibrium {
        row(
            o,
            "equilibrium",
            format!("each body's loads, reactions and contact forces sum to at most {e:.1e} of the force scale"),
        );
    }
    if s.augmentations > 0 {
        row(
            o,
            "augmented",
            format!(
                "{} multiplier updates (augmented Lagrangian: each one more solve of its increment)",
                s.augmentations
            ),
        );
    }
    if let Some(line) = iterative_line(&s.iterative) {
        row(o, "linear solver", line);
    }
    if let Some(line) = ldlt_line(&s.ldlt, &s.lagged, s.timings.factorizations) {
        row(o, "linear solver", line);
    }
    warning_rows(o, s);
}

/// The summary's warnings and notes: elements that lost stability, friction history lost at
/// crossings, states on segment extensions, moving contact fronts, deep penetration.
fn warning_rows(o: &mut String, s: &RunSummary) {
    if let Some(i) = &s.instability {
        row(
            o,
            "stability",
            format!(
                "the tangent lost positive definiteness at increment {} (t = {}; {}): a limit or bifurcation point (buckling, a snap) lies between t = {} and {}; see `/log`",
                i.increment,
                plain(i.t),
                i.inertia.describe(),
                plain(i.stable_until),
                plain(i.t)
            ),
        );
    }
    if let Some(u) = &s.unstable_elements {
        row(
                o,
                "WARNING",
                format!(
                    "elements lost stability from increment {} on (up to {} at once; worst: element {}, λ_min/λ_max = {:.1e}): an hourglass pattern, the answer may be wrong; see `/log`",
                    u.first_increment, u.most, u.worst_element, u.worst_ratio
                ),
            );
    }
    if s.history_jumps > 0 {
        row(
            o,
            "WARNING",
            format!(
                "the friction history jumped at {} of {} crossings (the transfer scheme does not carry it across segments): the force history is wrong from the first; see `/log`",
                s.history_jumps, s.crossings
            ),
        );
    }
    if s.on_extension > 0 || s.line_search_failures > 0 {
        row(
            o,
            "note",
            format!(
                "{} increments converged with contact points on a segment's extension (a node crossed back and forth); {} line searches found no decrease (their shortest step was taken)",
                s.on_extension, s.line_search_failures
            ),
        );
    }
    if s.stabilised_corrections > 0 {
        row(
            o,
            "note",
            format!(
                "{} corrections were shifted by pseudo-transient continuation after a line search found no decrease (a body held only by contact that has not closed yet, or a nearly singular tangent); their drag did {} of work on the way, and none acts on the converged states",
                s.stabilised_corrections,
                plain(s.stabilisation_work)
            ),
        );
    }
    if s.element_check_errors > 0 {
        row(
            o,
            "WARNING",
            format!(
                "the elements' stability could not be checked at {} converged increments (an element's tangent failed); see `/log`",
                s.element_check_errors
            ),
        );
    }
    if s.front_iterations > 0 {
        row(
            o,
            "note",
            format!(
                "{} Newton iterations reached an active set not met before in their attempt (a contact front still moving) and extended the iteration limit by one each",
                s.front_iterations
            ),
        );
    }
    if let Some(p) = &s.deep_penetration {
        row(
            o,
            "WARNING",
            format!(
                "contact `{}`: penetration up to {:.0} % of the element size ({} by {:.3e}): the penalty is soft for this load; see `/log`",
                p.pair,
                100.0 * p.ratio,
                p.slave,
                p.depth
            ),
        );
    }
}

/// The exit: success, or the failure with where its record is.
fn exit(result: Result<RunSummary, SolveError>, scene: &str, mcap: Option<&PathBuf>) -> anyhow::Result<ExitCode> {
    match result {
        Ok(_) => Ok(ExitCode::SUCCESS),
        Err(e) => {
            let interrupted = matches!(e, SolveError::Interrupted { .. });
            let what = match &e {
                SolveError::StepFailed {
                    increment, t, reason, ..
                } => format!("increment {increment} failed at t = {}: {reason}", plain(*t)),
                other => other.to_string(),
            };
            let mut message = format!("{scene}: {what}");
            if let Some(p) = mcap.filter(|p| p.exists()) {
                message.push_str(&format!("\n  the record up to this point is in {}", p.display()));
            }
            Err(RunFailed { message, interrupted }.into())
        }
    }
}

/// The iterative solver's account, when it was used: "LU" in `time spent` is then the
/// multigrid setup and "solve" the Krylov iterations.
fn iterative_line(it: &contrail::linalg::iterative::IterativeStats) -> Option<String> {
    if it.solves + it.failures == 0 {
        return None;
    }
    let levels: Vec<String> = it.levels.iter().filter(|l| **l > 0).map(|l| l.to_string()).collect();
    let mut line = format!(
        "multigrid-preconditioned Krylov ({} CG, {} BiCGStab): {} iterations in {} solves \
         (at most {}), {} hierarchy builds (levels {}, operator complexity {:.2}); \
         `LU` above is the multigrid setup, `solve` the Krylov iterations",
        it.cg_solves,
        it.solves - it.cg_solves,
        it.krylov_iterations,
        it.solves,
        it.max_krylov_iterations,
        it.builds,
        levels.join("/"),
        it.complexity,
    );
    if it.failures > 0 {
        line.push_str(&format!(
            "; {} solve(s) did not converge within the iteration limit and were repeated with the direct LU",
            it.failures
        ));
    }
    Some(line)
}

/// The symmetric factorisations' line, when any was planned.
fn ldlt_line(
    l: &contrail::linalg::ldlt::LdltStats,
    lagged: &contrail::linalg::lagged::LaggedStats,
    factorizations: usize,
) -> Option<String> {
    if l.plans == 0 {
        return None;
    }
    let ordering = l.ordering.map_or("", |o| o.name());
    let other = match l.flops.1 {
        Some(f) => format!(", the other ordering {f:.2e}"),
        None => String::new(),
    };
    let mut line = format!(
        "sparse LDLᵀ (the tangent is symmetric) for {} of {} factorisations, {ordering} ordering \
         ({:.2e} flops per factorisation{other}), {} values in the factor",
        l.solves, factorizations, l.flops.0, l.factor_nnz
    );
    if lagged.solves + lagged.abandoned > 0 {
        line.push_str(&format!(
            "; {} solve(s) by conjugate gradients preconditioned with an earlier tangent's factor \
             ({} iterations, at most {}), {} given up for a new factorisation",
            lagged.solves, lagged.iterations, lagged.max_iterations, lagged.abandoned
        ));
    }
    if let Some(f) = l.last_failure {
        let why = match f {
            contrail::linalg::ldlt::LdltFailure::Unsymmetric => "the tangent became unsymmetric".to_string(),
            contrail::linalg::ldlt::LdltFailure::ZeroPivot => "a zero pivot".to_string(),
            contrail::linalg::ldlt::LdltFailure::Inaccurate(eta) => format!("backward error {eta:.1e}"),
        };
        line.push_str(&format!(
            "; {} fallback(s) to the LU (last: {why}), after which the LU served the rest of that pattern",
            l.fallbacks
        ));
    }
    Some(line)
}

/// Where the wall time went: elements, contact, LU factorisations, substitutions,
/// recording and the rest (stepping, copies of the state), in seconds and per cent.
fn time_split(s: &contrail::solver::RunSummary) -> String {
    let t = &s.timings;
    let parts = [
        ("elements", t.elements.as_secs_f64()),
        ("contact", t.contact.as_secs_f64()),
        ("LU", t.factorization.as_secs_f64()),
        ("solve", t.solve.as_secs_f64()),
        ("recording", s.recording_s),
    ];
    let known: f64 = parts.iter().map(|p| p.1).sum();
    let total = s.wall_time_s.max(known).max(1e-12);
    let mut out: Vec<String> = parts
        .iter()
        .chain(std::iter::once(&("other", total - known)))
        .map(|(k, v)| format!("{k} {:.3} s ({:.0} %)", v, 100.0 * v / total))
        .collect();
    out.push(format!(
        "{} assemblies ({} with the tangent; {} without, expected to converge, {} of them wrongly), {} factorisations",
        t.assemblies, t.tangent_assemblies, t.tangents_skipped, t.tangents_missed, t.factorizations
    ));
    if t.kink_trials > 0 {
        out.push(format!(
            "resting points tried active at {} corrections, taken at {}",
            t.kink_trials, t.resting_corrections
        ));
    }
    out.push(match t.threads {
        0 | 1 => "one thread".to_string(),
        n => format!(
            "{n} threads (element kernels shared in {:.0} % of the assemblies, where measured faster)",
            100.0 * t.team_assemblies as f64 / t.assemblies.max(1) as f64
        ),
    });
    out.join(", ")
}
