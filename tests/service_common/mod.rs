//! Shared by the service tests: start `contrail serve` on a free port in a temporary data
//! folder, talk to it over HTTP, run the client verbs, find a headless Chromium.
#![allow(dead_code)]

pub mod cdp;

use serde_json::Value;
use std::io::{BufRead, BufReader};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

pub const BIN: &str = env!("CARGO_BIN_EXE_contrail");

/// A temporary folder removed on drop.
pub struct TempDir(pub PathBuf);

impl TempDir {
    pub fn new(tag: &str) -> TempDir {
        let d = std::env::temp_dir().join(format!("contrail-{tag}-{}-{:?}", std::process::id(), Instant::now()));
        let d = PathBuf::from(d.to_string_lossy().replace([' ', '{', '}', ':', ','], ""));
        std::fs::create_dir_all(&d).unwrap();
        TempDir(d)
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

/// A running service (killed on drop).
pub struct Server {
    pub child: Child,
    pub url: String,
    pub data: PathBuf,
    pub token: Option<String>,
}

impl Server {
    /// Start `contrail serve --port 0 --data DATA ARGS...` and wait for its address.
    pub fn start(data: &Path, args: &[&str]) -> Server {
        let mut child = Command::new(BIN)
            .args(["serve", "--port", "0", "--data"])
            .arg(data)
            .args(args)
            .stdout(Stdio::piped())
            .stderr(Stdio::inherit())
            .spawn()
            .expect("start contrail serve");
        let mut line = String::new();
        BufReader::new(child.stdout.take().unwrap())
            .read_line(&mut line)
            .unwrap();
        let url = line
            .split_whitespace()
            .find(|w| w.starts_with("http://"))
            .unwrap_or_else(|| panic!("no address in {line:?}"))
            .to_string();
        let token = args
            .iter()
            .position(|a| *a == "--token")
            .map(|i| args[i + 1].to_string());
        Server {
            child,
            url,
            data: data.to_path_buf(),
            token,
        }
    }

    fn agent() -> ureq::Agent {
        ureq::Agent::config_builder().http_status_as_error(false).build().into()
    }

    fn send(&self, req: Result<ureq::http::Response<ureq::Body>, ureq::Error>) -> (u16, Value) {
        let mut res = req.expect("request");
        let status = res.status().as_u16();
        let v = res.body_mut().read_json().unwrap_or(Value::Null);
        (status, v)
    }

    pub fn get(&self, path: &str) -> (u16, Value) {
        let mut r = Self::agent().get(format!("{}{path}", self.url));
        if let Some(t) = &self.token {
            r = r.header("Authorization", &format!("Bearer {t}"));
        }
        self.send(r.call())
    }

    pub fn post(&self, path: &str, body: &Value) -> (u16, Value) {
        let mut r = Self::agent().post(format!("{}{path}", self.url));
        if let Some(t) = &self.token {
            r = r.header("Authorization", &format!("Bearer {t}"));
        }
        self.send(r.send_json(body))
    }

    /// Bytes of a GET with optional headers, with the status and the headers.
    pub fn bytes(&self, path: &str, headers: &[(&str, &str)]) -> (u16, Vec<u8>, ureq::http::HeaderMap) {
        let mut r = Self::agent().get(format!("{}{path}", self.url));
        for (k, v) in headers {
            r = r.header(*k, *v);
        }
        let mut res = r.call().expect("request");
        let status = res.status().as_u16();
        let h = res.headers().clone();
        let b = res.body_mut().with_config().limit(1 << 30).read_to_vec().unwrap();
        (status, b, h)
    }

    /// Wait until run `id` has `status` (panics after `secs`).
    pub fn wait_for(&self, id: &str, pred: impl Fn(&Value) -> bool, secs: u64) -> Value {
        let t0 = Instant::now();
        loop {
            let (_, v) = self.get(&format!("/api/runs/{id}"));
            if pred(&v) {
                return v;
            }
            assert!(
                t0.elapsed() < Duration::from_secs(secs),
                "run {id} did not get there: {v}"
            );
            std::thread::sleep(Duration::from_millis(50));
        }
    }

    pub fn wait_ended(&self, id: &str, secs: u64) -> Value {
        self.wait_for(
            id,
            |v| !matches!(v["status"].as_str(), Some("queued" | "running") | None),
            secs,
        )
    }

    /// Submit `scene` with the overrides `set`, node positions every `every`-th increment;
    /// wait until it completes (within `secs`) and open its recording: its id and recording.
    pub fn solved(
        &self,
        (scene, set, every): (&str, &[&str], usize),
        secs: u64,
    ) -> (String, contrail::analysis::recording::Recording) {
        let body = serde_json::json!({ "scene": scene, "set": set, "positions_every": every });
        let (s, run) = self.post("/api/runs", &body);
        assert_eq!(s, 201, "{run}");
        let id = run["id"].as_str().unwrap().to_string();
        let run = self.wait_ended(&id, secs);
        assert_eq!(run["status"], "completed", "{run}");
        let path = self.data.join(format!("runs/{id}.mcap"));
        let rec = contrail::analysis::recording::Recording::open(&path).unwrap();
        (id, rec)
    }

    /// `contrail ARGS... --server URL` with its output and exit code.
    pub fn client(&self, args: &[&str]) -> (i32, String, String) {
        let out = Command::new(BIN)
            .args(args)
            .args(["--server", &self.url])
            .output()
            .unwrap();
        (
            out.status.code().unwrap_or(-1),
            String::from_utf8_lossy(&out.stdout).into_owned(),
            String::from_utf8_lossy(&out.stderr).into_owned(),
        )
    }

    pub fn kill9(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}

impl Drop for Server {
    fn drop(&mut self) {
        self.kill9();
    }
}

/// The Chromium binary, or None (the caller says it skipped). With CONTRAIL_REQUIRE_BROWSER
/// or CI=true set (`.ci/run` installs chromium), a missing browser is an error.
pub fn chromium() -> Option<String> {
    for c in ["chromium", "chromium-browser", "google-chrome"] {
        if Command::new(c)
            .arg("--version")
            .output()
            .is_ok_and(|o| o.status.success())
        {
            return Some(c.to_string());
        }
    }
    assert!(
        std::env::var_os("CONTRAIL_REQUIRE_BROWSER").is_none() && std::env::var("CI").as_deref() != Ok("true"),
        "no chromium on PATH, and CONTRAIL_REQUIRE_BROWSER or CI=true asks for the browser tests \
         (.ci/run installs Debian's chromium)"
    );
    eprintln!("skipped the browser part: no chromium on PATH (apt-get install chromium)");
    None
}

/// Headless Chromium on `url` with a fresh profile: `--dump-dom` (returns the DOM) or a
/// screenshot into `png`.
pub fn browse(chrome: &str, url: &str, png: Option<&Path>) -> String {
    let profile = TempDir::new("chrome");
    let mut cmd = Command::new(chrome);
    cmd.args([
        "--headless",
        "--no-sandbox",
        "--disable-gpu",
        "--disable-quic",
        "--no-first-run",
        "--disable-background-networking",
        "--disable-component-update",
        "--disable-sync",
        "--hide-scrollbars",
        "--window-size=1400,1000",
        "--virtual-time-budget=10000",
    ])
    .arg(format!("--user-data-dir={}", profile.0.display()));
    match png {
        Some(p) => cmd.arg(format!("--screenshot={}", p.display())),
        None => cmd.arg("--dump-dom"),
    };
    let out = cmd.arg(url).stderr(Stdio::null()).output().expect("run chromium");
    assert!(out.status.success(), "chromium failed on {url}");
    String::from_utf8_lossy(&out.stdout).into_owned()
}

/// A Python with the `mcap` package (the CI venv of .ci/interop.sh), or None.
pub fn python_with_mcap() -> Option<PathBuf> {
    let venv = std::env::var_os("CONTRAIL_INTEROP_VENV")
        .map(PathBuf::from)
        .or_else(|| std::env::var_os("HOME").map(|h| PathBuf::from(h).join(".cache/contrail-interop-venv")))?;
    let py = venv.join("bin/python");
    let ok = Command::new(&py)
        .args(["-c", "import mcap"])
        .output()
        .is_ok_and(|o| o.status.success());
    ok.then_some(py)
}
