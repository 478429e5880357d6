//! The service's client verbs: `contrail submit SCENE [--set ...] [--wait]`, `contrail runs
//! [filters]`, `contrail fetch ID` against `--server URL` (default: the local service).

use super::out::outln;
use super::{BadInput, RunFailed};
use serde_json::{json, Value};
use std::io::{BufRead, BufReader, Write};
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(clap::Args, Debug)]
pub struct ServerArgs {
    /// The service's address.
    #[arg(long, env = "CONTRAIL_SERVER", default_value_t = format!("http://127.0.0.1:{}", super::serve::DEFAULT_PORT))]
    pub server: String,
    /// The service's token, if it was started with one.
    #[arg(long, env = "CONTRAIL_TOKEN", hide_env_values = true)]
    pub token: Option<String>,
}

#[derive(clap::Args, Debug)]
pub struct SubmitArgs {
    /// A built-in scene name, a scene TOML file, or (with --plan) a sweep plan file.
    pub scene: String,
    /// Override a scene value, e.g. --set contact.mu=0.1 (repeatable).
    #[arg(long = "set", value_name = "KEY=VALUE")]
    pub sets: Vec<String>,
    /// SCENE is a sweep plan (TOML, built-in scenes): queue all its runs.
    #[arg(long)]
    pub plan: bool,
    /// Solve again even if the run is catalogued.
    #[arg(long)]
    pub rerun: bool,
    /// Follow the run until it ends (exit code as `contrail run`: 0, 1 failed, 130 interrupted).
    #[arg(long)]
    pub wait: bool,
    /// Node positions every N-th increment in the recording.
    #[arg(long, value_name = "N")]
    pub positions_every: Option<usize>,
    #[command(flatten)]
    pub server: ServerArgs,
}

#[derive(clap::Args, Debug)]
pub struct RunsArgs {
    #[arg(long)]
    pub scene: Option<String>,
    /// queued, running, completed, failed, interrupted or cancelled.
    #[arg(long)]
    pub status: Option<String>,
    /// e.g. no-convergence, cycling, diverged, recording, bad-input, aborted.
    #[arg(long)]
    pub failure_kind: Option<String>,
    /// Runs of this sweep plan.
    #[arg(long)]
    pub sweep: Option<String>,
    /// Runs whose override KEY has VALUE (repeatable), e.g. --param contact.mu=0.3.
    #[arg(long = "param", value_name = "KEY=VALUE")]
    pub params: Vec<String>,
    /// Sort by seq, id, scene, status, failure_kind, submitted_at or finished_at.
    #[arg(long, default_value = "seq")]
    pub sort: String,
    #[arg(long)]
    pub desc: bool,
    #[arg(long, default_value_t = 100)]
    pub limit: usize,
    /// Print the service's JSON.
    #[arg(long)]
    pub json: bool,
    #[command(flatten)]
    pub server: ServerArgs,
}

#[derive(clap::Args, Debug)]
pub struct FetchArgs {
    /// The run id.
    pub id: String,
    /// Where to write the recording (default: ID.mcap).
    #[arg(long, value_name = "FILE")]
    pub out: Option<PathBuf>,
    /// Also write its load–displacement curve (.csv or .svg).
    #[arg(long, value_name = "FILE")]
    pub curve: Option<PathBuf>,
    #[command(flatten)]
    pub server: ServerArgs,
}

struct Client {
    agent: ureq::Agent,
    base: String,
    token: Option<String>,
}

impl Client {
    fn new(s: &ServerArgs) -> Client {
        let agent = ureq::Agent::config_builder().http_status_as_error(false).build().into();
        Client {
            agent,
            base: s.server.trim_end_matches('/').to_string(),
            token: s.token.clone(),
        }
    }

    fn auth(&self) -> Option<String> {
        self.token.as_ref().map(|t| format!("Bearer {t}"))
    }

    fn unreachable(&self, e: ureq::Error) -> anyhow::Error {
        BadInput(format!(
            "{}: cannot reach the service: {e}\n  hint: start it with `contrail serve`, or give --server URL",
            self.base
        ))
        .into()
    }

    /// The JSON answer of a request; a 4xx/5xx answer is an error with the service's message.
    fn answer(&self, res: Result<ureq::http::Response<ureq::Body>, ureq::Error>) -> anyhow::Result<Value> {
        let mut res = res.map_err(|e| self.unreachable(e))?;
        let status = res.status();
        let v: Value = res
            .body_mut()
            .with_config()
            .limit(256 << 20)
            .read_json()
            .unwrap_or(Value::Null);
        if status.is_success() {
            return Ok(v);
        }
        let e = &v["error"];
        let msg = format!(
            "{} ({status}): {}{}",
            self.base,
            e["message"].as_str().unwrap_or("request failed"),
            e["hint"]
                .as_str()
                .filter(|h| !h.is_empty())
                .map_or(String::new(), |h| format!("\n  hint: {h}"))
        );
        Err(if status.is_client_error() {
            BadInput(msg).into()
        } else {
            anyhow::anyhow!(msg)
        })
    }

    fn get(&self, path: &str) -> anyhow::Result<Value> {
        let mut req = self.agent.get(format!("{}{path}", self.base));
        if let Some(a) = self.auth() {
            req = req.header("Authorization", &a);
        }
        self.answer(req.call())
    }

    fn post(&self, path: &str, body: &Value) -> anyhow::Result<Value> {
        let mut req = self.agent.post(format!("{}{path}", self.base));
        if let Some(a) = self.auth() {
            req = req.header("Authorization", &a);
        }
        self.answer(req.send_json(body))
    }

    /// Stream a download into `to` (written beside it and renamed when complete).
    fn download(&self, path: &str, to: &std::path::Path) -> anyhow::Result<u64> {
        let mut req = self.agent.get(format!("{}{path}", self.base));
        if let Some(a) = self.auth() {
            req = req.header("Authorization", &a);
        }
        let res = req.call().map_err(|e| self.unreachable(e))?;
        if !res.status().is_success() {
            return self.answer(Ok(res)).map(|_| 0);
        }
        let mut file = contrail::record::atomic_file::AtomicFile::create(to)
            .map_err(|e| BadInput(format!("{}: cannot create: {e}", to.display())))?;
        let n = std::io::copy(&mut res.into_body().into_reader(), &mut file)?;
        file.commit()?;
        Ok(n)
    }
}

fn query_escape(s: &str) -> String {
    s.bytes()
        .map(|b| match b {
            b'A'..=b'Z' | b'a'..=b'z' | b'0'..=b'9' | b'-' | b'_' | b'.' | b'~' => (b as char).to_string(),
            _ => format!("%{b:02X}"),
        })
        .collect()
}

pub fn submit(a: SubmitArgs) -> anyhow::Result<ExitCode> {
    let c = Client::new(&a.server);
    if a.plan {
        let plan = std::fs::read_to_string(&a.scene).map_err(|e| BadInput(format!("{}: cannot read: {e}", a.scene)))?;
        let v = c.post(
            "/api/sweeps",
            &json!({ "plan": plan, "rerun": a.rerun, "positions_every": a.positions_every }),
        )?;
        outln!(
            "plan {}: {} runs, {} queued, {} already catalogued",
            v["plan"].as_str().unwrap_or(""),
            v["runs"].as_array().map_or(0, Vec::len),
            v["queued"],
            v["existing"]
        )?;
        return Ok(ExitCode::SUCCESS);
    }
    let mut body = json!({ "set": a.sets, "rerun": a.rerun, "positions_every": a.positions_every });
    if contrail::scene::builtin::find(&a.scene).is_some() {
        body["scene"] = json!(a.scene);
    } else {
        let text = std::fs::read_to_string(&a.scene).map_err(|e| {
            BadInput(format!(
                "{}: neither a built-in scene nor a readable file: {e}\n  hint: `contrail scenes` lists the built-in scenes",
                a.scene
            ))
        })?;
        body["scene_toml"] = json!(text);
    }
    let v = c.post("/api/runs", &body)?;
    let id = v["id"].as_str().unwrap_or("").to_string();
    let state = if v["existing"].as_bool() == Some(true) {
        "catalogued"
    } else {
        "queued"
    };
    outln!("run {id} {state} ({})", v["status"].as_str().unwrap_or(""))?;
    outln!("page {}/#/runs/{id}", c.base)?;
    if !a.wait {
        return Ok(ExitCode::SUCCESS);
    }
    wait(&c, &id)
}

/// Follow a run's events until it ends; report it, exit as `contrail run` would.
fn wait(c: &Client, id: &str) -> anyhow::Result<ExitCode> {
    let mut req = c.agent.get(format!("{}/api/runs/{id}/events", c.base));
    if let Some(a) = c.auth() {
        req = req.header("Authorization", &a);
    }
    if let Ok(res) = req.call() {
        let quiet = !std::io::IsTerminal::is_terminal(&std::io::stderr());
        for line in BufReader::new(res.into_body().into_reader()).lines() {
            let Ok(line) = line else { break };
            let Some(data) = line.strip_prefix("data:") else {
                continue;
            };
            let v: Value = serde_json::from_str(data.trim()).unwrap_or(Value::Null);
            let d = &v["data"];
            if !quiet && d["increment"].is_number() {
                eprint!(
                    "\rincrement {} t = {:.4} / {} force {:.5e}   ",
                    d["increment"],
                    d["t"].as_f64().unwrap_or(0.0),
                    d["t_end"],
                    d["force"].as_f64().unwrap_or(f64::NAN)
                );
                let _ = std::io::stderr().flush();
            }
        }
        if !quiet {
            eprintln!();
        }
    }
    let mut v = c.get(&format!("/api/runs/{id}"))?;
    while matches!(v["status"].as_str(), Some("queued" | "running")) {
        std::thread::sleep(std::time::Duration::from_millis(500));
        v = c.get(&format!("/api/runs/{id}"))?;
    }
    let status = v["status"].as_str().unwrap_or("").to_string();
    let f = &v["figures"];
    outln!(
        "ended {status}{} after {} increments ({} s)",
        v["failure_kind"].as_str().map_or(String::new(), |k| format!(" ({k})")),
        f["increments"],
        f["wall_time_s"].as_f64().map_or("?".into(), |t| format!("{t:.2}"))
    )?;
    if let Some(m) = v["message"].as_str().filter(|m| !m.is_empty()) {
        outln!("message {m}")?;
    }
    outln!("fetch contrail fetch {id} --server {}", c.base)?;
    match status.as_str() {
        "completed" => Ok(ExitCode::SUCCESS),
        other => Err(RunFailed {
            message: format!("run {id} {other}: {}", v["message"].as_str().unwrap_or("")),
            interrupted: matches!(other, "interrupted" | "cancelled"),
        }
        .into()),
    }
}

pub fn runs(a: RunsArgs) -> anyhow::Result<ExitCode> {
    let c = Client::new(&a.server);
    let mut q = vec![
        format!("sort={}", query_escape(&a.sort)),
        format!("limit={}", a.limit),
        format!("order={}", if a.desc { "desc" } else { "asc" }),
    ];
    for (k, v) in [
        ("scene", &a.scene),
        ("status", &a.status),
        ("failure_kind", &a.failure_kind),
        ("sweep", &a.sweep),
    ] {
        if let Some(v) = v {
            q.push(format!("{k}={}", query_escape(v)));
        }
    }
    for p in &a.params {
        let (k, v) = p
            .split_once('=')
            .ok_or_else(|| BadInput(format!("--param {p}: expected KEY=VALUE, e.g. contact.mu=0.3")))?;
        q.push(format!("param.{}={}", query_escape(k), query_escape(v)));
    }
    let v = c.get(&format!("/api/runs?{}", q.join("&")))?;
    if a.json {
        outln!("{}", serde_json::to_string_pretty(&v)?)?;
        return Ok(ExitCode::SUCCESS);
    }
    outln!(
        "{:<34} {:<16} {:<12} {:<17} {:>10} {:>9}",
        "id",
        "scene",
        "status",
        "failure",
        "increments",
        "wall s"
    )?;
    for r in v["runs"].as_array().into_iter().flatten() {
        let incs = match r["progress"]["increment"].as_u64() {
            Some(i) => format!("{i}…"),
            None => r["figures"]["increments"]
                .as_u64()
                .map_or(String::new(), |i| i.to_string()),
        };
        outln!(
            "{:<34} {:<16} {:<12} {:<17} {:>10} {:>9}",
            r["id"].as_str().unwrap_or(""),
            r["scene"].as_str().unwrap_or(""),
            r["status"].as_str().unwrap_or(""),
            r["failure_kind"].as_str().unwrap_or(""),
            incs,
            r["figures"]["wall_time_s"]
                .as_f64()
                .map_or(String::new(), |t| format!("{t:.2}"))
        )?;
    }
    outln!("{} of {} runs", v["runs"].as_array().map_or(0, Vec::len), v["total"])?;
    Ok(ExitCode::SUCCESS)
}

pub fn fetch(a: FetchArgs) -> anyhow::Result<ExitCode> {
    let c = Client::new(&a.server);
    let id = &a.id;
    let out = a.out.clone().unwrap_or_else(|| PathBuf::from(format!("{id}.mcap")));
    let n = c.download(&format!("/api/runs/{}/recording", query_escape(id)), &out)?;
    outln!("written {} ({n} bytes)", out.display())?;
    if let Some(curve) = &a.curve {
        let kind = match curve.extension().and_then(|e| e.to_str()) {
            Some("svg") => "curve.svg",
            Some("csv") => "curve.csv",
            _ => return Err(BadInput(format!("--curve {}: use a .csv or .svg file", curve.display())).into()),
        };
        c.download(&format!("/api/runs/{}/{kind}", query_escape(id)), curve)?;
        outln!("written {}", curve.display())?;
    }
    outln!("view it with `contrail replay {} --rerun-spawn`", out.display())?;
    Ok(ExitCode::SUCCESS)
}
