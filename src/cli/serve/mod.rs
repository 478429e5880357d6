//! `contrail serve`: a run catalogue with an HTTP API, live progress and a web page. Runs are
//! solved by child processes of this binary (or Slurm jobs) and recorded to
//! `DATA/runs/ID.mcap`; the catalogue is `DATA/catalogue.sqlite` (WAL). See docs/service.md.

mod api;
mod catalogue;
mod conclude;
mod errors;
mod events;
mod files;
mod live;
mod model;
mod model_json;
mod model_json3d;
mod slurm;
mod state;
mod submit;
mod web;
mod worker;

use super::BadInput;
use catalogue::{Catalogue, Finish};
use state::{Backend, Service};
use std::net::{IpAddr, SocketAddr};
use std::path::PathBuf;
use std::process::ExitCode;
use std::sync::Arc;
use std::time::Duration;

/// The port the service listens on, and the client's default server.
pub const DEFAULT_PORT: u16 = 8717;

#[derive(clap::Args, Debug)]
pub struct ServeArgs {
    /// Port to listen on (0: any free port; the address is printed).
    #[arg(long, default_value_t = DEFAULT_PORT)]
    pub port: u16,
    /// Address to listen on. Anything but a loopback address needs --token.
    #[arg(long, default_value = "127.0.0.1")]
    pub bind: IpAddr,
    /// Data folder: catalogue.sqlite, runs/ID.mcap, scenes/.
    #[arg(long, value_name = "DIR", default_value = "recordings")]
    pub data: PathBuf,
    /// Runs solved at a time (default: one per core).
    #[arg(long, value_name = "N")]
    pub workers: Option<usize>,
    /// Threads of each run (default: the cores divided among the workers, at least one;
    /// with the Slurm backend 1, asked of Slurm as --cpus-per-task).
    #[arg(long, value_name = "N")]
    pub threads_per_run: Option<usize>,
    /// Require this token on every request (`Authorization: Bearer TOKEN` or `?token=`).
    #[arg(long, env = "CONTRAIL_TOKEN", hide_env_values = true)]
    pub token: Option<String>,
    /// Where runs are solved: child processes here, or one Slurm job per run (`sbatch`; the
    /// cluster must share the data folder).
    #[arg(long, value_enum, default_value = "local")]
    pub backend: BackendKind,
    /// Extra `sbatch` argument for the Slurm backend (repeatable), e.g. --sbatch-arg=--partition=debug.
    #[arg(long = "sbatch-arg", value_name = "ARG", allow_hyphen_values = true)]
    pub sbatch_args: Vec<String>,
    /// Largest scene the service accepts, in mesh elements.
    #[arg(long, value_name = "N", default_value_t = 200_000)]
    pub max_elements: usize,
}

#[derive(clap::ValueEnum, Clone, Copy, Debug, PartialEq)]
pub enum BackendKind {
    Local,
    Slurm,
}

/// Runs a stopped service left `running`: Slurm jobs are followed again; local solves died
/// with the service, so they are interrupted, and their partial recordings recovered.
fn resume(svc: &Arc<Service>) -> anyhow::Result<()> {
    let check = svc.catalogue.integrity()?;
    if check != "ok" {
        anyhow::bail!(
            "{}: the catalogue is damaged ({check})\n  hint: restore it from a backup; the recordings in runs/ are intact",
            svc.data.join("catalogue.sqlite").display()
        );
    }
    for run in svc.catalogue.running()? {
        if let (Backend::Slurm { .. }, Some(job), Some("slurm")) = (&svc.backend, &run.job, run.backend.as_deref()) {
            let (svc, job) = (svc.clone(), job.clone());
            svc.live.start(&run.id, None);
            std::thread::spawn(move || slurm::follow(&svc, &run, &job));
            continue;
        }
        let mut message = "interrupted: the service stopped while it ran".to_string();
        if let Some(said) = conclude::salvage(svc, &run.id) {
            message = format!("{message}; {said}");
        } else if svc.recording(&run.id).is_file() {
            message.push_str("; its recording is complete");
        }
        svc.catalogue.finish(
            &run.id,
            &Finish {
                status: "interrupted",
                failure_kind: None,
                message: &message,
                outcome: None,
                culprit: None,
                metrics: None,
                log: "",
            },
        )?;
        eprintln!("contrail serve: run {}: {message}", run.id);
    }
    Ok(())
}

/// Wait for Ctrl-C or SIGTERM (the handler of `cli::signal` sets the flag).
async fn stop_signal(svc: Arc<Service>) {
    let flag = super::signal::stop_flag();
    while !flag.load(std::sync::atomic::Ordering::SeqCst) {
        tokio::time::sleep(Duration::from_millis(200)).await;
    }
    svc.stop();
    for pid in svc.live.pids() {
        worker::interrupt(pid);
    }
    // ends the event streams, so that the server can close its connections
    svc.live.send("shutdown", "", serde_json::Value::Null);
}

pub fn serve(a: ServeArgs) -> anyhow::Result<ExitCode> {
    if !a.bind.is_loopback() && a.token.is_none() {
        return Err(BadInput(format!(
            "--bind {}: a service reachable from other machines needs --token TOKEN",
            a.bind
        ))
        .into());
    }
    for d in ["runs", "scenes"] {
        std::fs::create_dir_all(a.data.join(d))
            .map_err(|e| BadInput(format!("{}: cannot create: {e}", a.data.join(d).display())))?;
    }
    let data = a.data.canonicalize()?;
    let cat = Catalogue::open(&data.join("catalogue.sqlite")).map_err(|e| {
        BadInput(format!(
            "{}: cannot open the catalogue: {e}",
            data.join("catalogue.sqlite").display()
        ))
    })?;
    let backend = match a.backend {
        BackendKind::Local => Backend::Local,
        BackendKind::Slurm => Backend::Slurm {
            sbatch_args: a.sbatch_args.clone(),
            poll: Duration::from_millis(500),
        },
    };
    let cores = contrail::threads::available_cores();
    let workers = a.workers.unwrap_or(match backend {
        Backend::Local => cores,
        Backend::Slurm { .. } => 64,
    });
    let threads_per_run = a.threads_per_run.unwrap_or(match backend {
        Backend::Local => contrail::threads::share(cores, workers),
        Backend::Slurm { .. } => 1,
    });
    let mut svc = Service::new(data.clone(), cat, backend, workers.max(1))?;
    svc.threads_per_run = threads_per_run.max(1);
    svc.token = a.token.clone();
    svc.limits.elements = a.max_elements;
    let svc = Arc::new(svc);
    resume(&svc)?;
    worker::spawn_workers(&svc, svc.workers);
    let rt = tokio::runtime::Builder::new_multi_thread().enable_all().build()?;
    rt.block_on(async {
        let listener = tokio::net::TcpListener::bind(SocketAddr::new(a.bind, a.port))
            .await
            .map_err(|e| BadInput(format!("{}:{}: cannot listen: {e}", a.bind, a.port)))?;
        let addr = listener.local_addr()?;
        println!(
            "contrail serve: listening on http://{addr} (data {}, {} {} workers, {} thread{} per run)",
            data.display(),
            svc.workers,
            svc.backend.name(),
            svc.threads_per_run,
            if svc.threads_per_run == 1 { "" } else { "s" }
        );
        axum::serve(listener, api::app(svc.clone()))
            .with_graceful_shutdown(stop_signal(svc.clone()))
            .await?;
        anyhow::Ok(())
    })?;
    // Ctrl-C reached the solvers too (one process group); wait for them to finalise
    let t0 = std::time::Instant::now();
    while svc.catalogue.counts()?.get("running").copied().unwrap_or(0) > 0 && t0.elapsed() < Duration::from_secs(30) {
        std::thread::sleep(Duration::from_millis(100));
        if matches!(svc.backend, Backend::Slurm { .. }) {
            break;
        }
    }
    println!("contrail serve: stopped");
    Ok(ExitCode::SUCCESS)
}
