//! `contrail serve` end to end: `contrail submit strip-channel --wait`, the run on the web
//! page with its curve (headless Chromium's DOM), the recording by range requests (here and
//! into Python's `mcap` reader), resubmission, sweeps, filters, live events, cancel.

mod service_common;

use contrail::analysis::recording::Recording;
use contrail::record::Outcome;
use serde_json::{json, Value};
use service_common::{browse, chromium, python_with_mcap, Server, TempDir};
use std::io::{BufRead, BufReader};

fn run_id(stdout: &str) -> String {
    stdout
        .split_whitespace()
        .skip_while(|w| *w != "run")
        .nth(1)
        .unwrap_or_else(|| panic!("no run id in {stdout}"))
        .to_string()
}

#[test]
fn submit_wait_shows_the_run_with_its_curve_on_the_page_and_its_recording_reads_by_range() {
    let dir = TempDir::new("svc-flow");
    let srv = Server::start(&dir.0.join("data"), &["--workers", "2"]);
    let (code, out, err) = srv.client(&["submit", "strip-channel", "--wait"]);
    assert_eq!(code, 0, "{out}\n{err}");
    assert!(out.contains("ended completed"), "{out}");
    let id = run_id(&out);
    let (status, run) = srv.get(&format!("/api/runs/{id}"));
    assert_eq!((status, run["status"].as_str()), (200, Some("completed")), "{run}");
    let increments = run["figures"]["increments"].as_u64().unwrap() as usize;

    // the whole file, then the same bytes in four ranges
    let path = format!("/api/runs/{id}/recording");
    let (s, whole, h) = srv.bytes(&path, &[]);
    assert_eq!(s, 200);
    assert_eq!(h["accept-ranges"], "bytes");
    let n = whole.len();
    let mut joined = Vec::new();
    for k in 0..4 {
        let (a, b) = (k * n / 4, (k + 1) * n / 4 - 1);
        let (s, part, h) = srv.bytes(&path, &[("Range", &format!("bytes={a}-{b}"))]);
        assert_eq!(s, 206);
        assert_eq!(h["content-range"], format!("bytes {a}-{b}/{n}").as_str());
        joined.extend(part);
    }
    assert_eq!(joined, whole);
    let (s, _, _) = srv.bytes(&path, &[("Range", &format!("bytes={}-", n + 10))]);
    assert_eq!(s, 416);
    let rec = Recording::from_bytes(&whole, "downloaded").unwrap();
    assert_eq!(rec.increments.len(), increments);
    assert!(matches!(rec.outcome, Some(Outcome::Completed { .. })));

    // the curve: one point per increment (the scene has a monitor), crossings marked
    let (_, curve) = srv.get(&format!("/api/runs/{id}/curve"));
    let points = curve["points"].as_array().unwrap().len();
    let crossings = curve["crossings"].as_array().unwrap().len();
    assert_eq!(points, increments);
    assert!(crossings > 0 && crossings <= run["figures"]["crossings"].as_u64().unwrap() as usize);
    let (_, csv, _) = srv.bytes(&format!("/api/runs/{id}/curve.csv"), &[]);
    assert_eq!(String::from_utf8(csv).unwrap().lines().count(), points + 1);
    let (_, svg, h) = srv.bytes(&format!("/api/runs/{id}/curve.svg"), &[]);
    assert_eq!(h["content-type"], "image/svg+xml");
    assert!(String::from_utf8(svg).unwrap().contains("<svg"));

    // the client's download is the same file
    let to = dir.0.join("fetched.mcap");
    let (code, out, err) = srv.client(&["fetch", &id, "--out", to.to_str().unwrap()]);
    assert_eq!(code, 0, "{out}{err}");
    assert_eq!(std::fs::read(&to).unwrap(), whole);

    if let Some(chrome) = chromium() {
        let dom = browse(&chrome, &format!("{}/?live=0#/runs/{id}", srv.url), None);
        assert!(dom.contains(&format!("<h2 id=\"run-id\">{id}")), "{dom}");
        assert!(dom.contains("class=\"status completed\""));
        let path_d = dom
            .split("<path class=\"curve\"")
            .nth(1)
            .and_then(|p| p.split(" d=\"").nth(1))
            .and_then(|p| p.split('"').next())
            .expect("the curve's path");
        assert_eq!(path_d.matches('L').count(), points - 1, "one segment per increment");
        assert_eq!(dom.matches("<circle class=\"crossing\"").count(), crossings);
        assert!(dom.contains(&format!("contrail replay {id}.mcap --rerun-spawn")));
        let list = browse(&chrome, &format!("{}/?live=0", srv.url), None);
        assert!(list.contains(&format!("<tr data-id=\"{id}\"")), "{list}");
    }
    match python_with_mcap() {
        Some(py) => {
            let script = concat!(env!("CARGO_MANIFEST_DIR"), "/.ci/service_mcap.py");
            let out = std::process::Command::new(py)
                .args([script, &srv.url, &id, &increments.to_string()])
                .output()
                .unwrap();
            let text = String::from_utf8_lossy(&out.stdout);
            assert!(out.status.success(), "{text}{}", String::from_utf8_lossy(&out.stderr));
            eprintln!("{text}");
        }
        None => eprintln!("the Python `mcap` part runs in .ci/interop.sh (no interop venv here)"),
    }
}

#[test]
fn the_same_run_is_catalogued_once_sweeps_get_the_sweep_ids_and_filters_find_runs() {
    let dir = TempDir::new("svc-ids");
    let srv = Server::start(&dir.0.join("data"), &["--workers", "2"]);
    let body = json!({ "scene": "crossing", "set": ["stepping.increments=40"] });
    let (s1, a) = srv.post("/api/runs", &body);
    let (s2, b) = srv.post("/api/runs", &body);
    assert_eq!((s1, s2), (201, 200));
    assert_eq!(a["id"], b["id"]);
    assert_eq!(b["existing"], true);
    let id = a["id"].as_str().unwrap().to_string();
    srv.wait_ended(&id, 60);
    let (s3, c) = srv.post(
        "/api/runs",
        &json!({ "scene": "crossing", "set": ["stepping.increments=40"], "rerun": true }),
    );
    assert_eq!(
        (s3, c["id"].as_str(), c["attempt"].as_i64()),
        (201, Some(id.as_str()), Some(2))
    );
    assert_eq!(srv.wait_ended(&id, 60)["status"], "completed");

    let plan = "name = \"mu\"\n[[study]]\nscene = \"block-slide\"\nset = [\"stepping.increments=12\"]\n\
                grid = { \"contact.mu\" = [0.1, 0.2, 0.3] }\n";
    let (s, sw) = srv.post("/api/sweeps", &json!({ "plan": plan }));
    assert_eq!(s, 201, "{sw}");
    let parsed = contrail::sweep::Plan::parse(plan, "p", std::path::Path::new("")).unwrap();
    let expected: Vec<String> = contrail::sweep::expand(&parsed)
        .unwrap()
        .into_iter()
        .map(|r| r.id)
        .collect();
    let got: Vec<String> = serde_json::from_value(sw["runs"].clone()).unwrap();
    assert_eq!(got, expected, "the ids of `contrail sweep`");
    for i in &got {
        srv.wait_ended(i, 60);
    }
    let (_, l) = srv.get("/api/runs?sweep=mu&param.contact.mu=0.2");
    assert_eq!(l["total"], 1);
    assert_eq!(l["runs"][0]["id"], got[1].as_str());
    let (_, l) = srv.get("/api/runs?scene=block-slide&status=completed");
    assert_eq!(l["total"], 3);

    let failing = json!({ "scene": "strip-channel", "set": ["solver.max_iterations=2", "stepping.max_cutbacks=0"] });
    let (_, f) = srv.post("/api/runs", &failing);
    let f = srv.wait_ended(f["id"].as_str().unwrap(), 60);
    assert_eq!(f["status"], "failed");
    let kind = f["failure_kind"].as_str().unwrap().to_string();
    assert!(
        !f["culprit"].as_array().unwrap().is_empty(),
        "the failure names its culprit points"
    );
    let (_, l) = srv.get(&format!("/api/runs?failure_kind={kind}"));
    assert_eq!(l["total"], 1);
    let (code, out, _) = srv.client(&["runs", "--status", "failed"]);
    assert_eq!(code, 0);
    assert!(
        out.contains(f["id"].as_str().unwrap()) && out.contains("1 of 1 runs"),
        "{out}"
    );
}

/// Events of a run's stream until it ends: (event, data) pairs.
fn events(url: &str) -> Vec<(String, Value)> {
    let res = ureq::get(url).call().unwrap();
    let mut out = Vec::new();
    let mut event = String::new();
    for line in BufReader::new(res.into_body().into_reader()).lines() {
        let line = line.unwrap();
        if let Some(e) = line.strip_prefix("event:") {
            event = e.trim().to_string();
        } else if let Some(d) = line.strip_prefix("data:") {
            out.push((event.clone(), serde_json::from_str(d.trim()).unwrap()));
        }
    }
    out
}

#[test]
fn live_events_follow_a_run_and_cancel_interrupts_with_a_finalised_recording() {
    let dir = TempDir::new("svc-live");
    let srv = Server::start(&dir.0.join("data"), &["--workers", "1"]);
    let long = json!({ "scene": "strip-channel", "set": ["stepping.increments=200000"] });
    let (_, a) = srv.post("/api/runs", &long);
    let a = a["id"].as_str().unwrap().to_string();
    let (_, b) = srv.post(
        "/api/runs",
        &json!({ "scene": "block-slide", "set": ["stepping.increments=24"] }),
    );
    let b = b["id"].as_str().unwrap().to_string();
    let (_, c) = srv.post("/api/runs", &json!({ "scene": "crossing" }));
    let c = c["id"].as_str().unwrap().to_string();
    // b waits behind a: its whole stream is seen
    let stream = format!("{}/api/runs/{b}/events", srv.url);
    let follower = std::thread::spawn(move || events(&stream));
    srv.wait_for(&a, |v| v["progress"]["increment"].as_u64() >= Some(50), 60);
    let (s, cc) = srv.post(&format!("/api/runs/{c}/cancel"), &json!({}));
    assert_eq!((s, cc["status"].as_str()), (200, Some("cancelled")));
    let (s, _) = srv.post(&format!("/api/runs/{a}/cancel"), &json!({}));
    assert_eq!(s, 200);
    let ra = srv.wait_ended(&a, 60);
    assert_eq!(ra["status"], "interrupted", "{ra}");
    let rec = Recording::open(&srv.data.join(format!("runs/{a}.mcap"))).unwrap();
    assert!(
        matches!(rec.outcome, Some(Outcome::Interrupted { .. })),
        "the recording ends in its outcome"
    );
    assert!(!rec.increments.is_empty());

    let seen = follower.join().unwrap();
    let rb = srv.wait_ended(&b, 60);
    let progress: Vec<&Value> = seen
        .iter()
        .filter(|(e, d)| e == "progress" && d["data"]["kind"] == "increment")
        .map(|(_, d)| &d["data"])
        .collect();
    assert!(seen
        .iter()
        .any(|(e, d)| e == "progress" && d["data"]["kind"] == "start"));
    assert_eq!(progress.len() as u64, rb["figures"]["increments"].as_u64().unwrap());
    assert!(progress
        .windows(2)
        .all(|w| w[1]["increment"].as_u64() > w[0]["increment"].as_u64()));
    assert!(progress.iter().all(|p| p["force"].is_number() && p["t"].is_number()));
    let last = seen.last().unwrap();
    assert_eq!(
        (last.0.as_str(), last.1["data"]["status"].as_str()),
        ("status", Some("completed"))
    );
    let (s, e) = srv.post(&format!("/api/runs/{b}/cancel"), &json!({}));
    assert_eq!((s, e["error"]["code"].as_str()), (409, Some("finished")));

    // the diff of two runs of one scene, and its refusal across scenes
    let (_, d) = srv.post(
        "/api/runs",
        &json!({ "scene": "block-slide", "set": ["stepping.increments=24", "contact.mu=0.5"] }),
    );
    let d = d["id"].as_str().unwrap().to_string();
    srv.wait_ended(&d, 60);
    let (s, diff) = srv.get(&format!("/api/diff?a={b}&b={d}"));
    assert_eq!(s, 200, "{diff}");
    assert_eq!(diff["within_tolerance"], false);
    assert_eq!(
        (diff["only_in_a"].as_u64(), diff["only_in_b"].as_u64()),
        (Some(0), Some(0))
    );
    let (s, e) = srv.get(&format!("/api/diff?a={b}&b={a}"));
    assert_eq!((s, e["error"]["code"].as_str()), (400, Some("bad-request")), "{e}");
}
