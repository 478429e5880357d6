//! A bounded load test of `contrail serve` on localhost: 50 concurrent clients send 1 000
//! submissions of small scenes (250 distinct runs, each sent four times) while the workers
//! saturate the cores; every run is catalogued exactly once, none is lost, all complete. The
//! API latency (p50, p99) is printed, not asserted (docs/service.md has it, measured once).

mod service_common;

use serde_json::json;
use service_common::{Server, TempDir};
use std::collections::{BTreeMap, BTreeSet};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

const CLIENTS: usize = 50;
const SUBMISSIONS: usize = 1000;
const DISTINCT: usize = 250;

/// The k-th distinct small run.
fn body(k: usize) -> serde_json::Value {
    if k.is_multiple_of(2) {
        json!({ "scene": "crossing", "set": [format!("stepping.increments={}", 20 + k / 2)] })
    } else {
        json!({ "scene": "block-slide", "set": ["stepping.increments=12", format!("contact.mu={}", 0.1 + 0.001 * k as f64)] })
    }
}

fn percentile(sorted: &[f64], p: f64) -> f64 {
    sorted[((sorted.len() - 1) as f64 * p).round() as usize]
}

#[test]
fn fifty_clients_a_thousand_submissions_every_run_catalogued_once() {
    let dir = TempDir::new("svc-load");
    let srv = Arc::new(Server::start(&dir.0.join("data"), &[]));
    let submit_ms = Arc::new(Mutex::new(Vec::new()));
    let read_ms = Arc::new(Mutex::new(Vec::new()));
    let ids = Arc::new(Mutex::new(BTreeMap::<usize, BTreeSet<String>>::new()));
    let t0 = Instant::now();
    let clients: Vec<_> = (0..CLIENTS)
        .map(|c| {
            let (srv, submit_ms, read_ms, ids) = (srv.clone(), submit_ms.clone(), read_ms.clone(), ids.clone());
            std::thread::spawn(move || {
                for i in 0..SUBMISSIONS / CLIENTS {
                    let k = (c * (SUBMISSIONS / CLIENTS) + i) % DISTINCT;
                    let t = Instant::now();
                    let (s, v) = srv.post("/api/runs", &body(k));
                    submit_ms.lock().unwrap().push(t.elapsed().as_secs_f64() * 1e3);
                    assert!(s == 200 || s == 201, "{s} {v}");
                    let id = v["id"].as_str().unwrap().to_string();
                    let t = Instant::now();
                    let (s, _) = srv.get(&format!("/api/runs/{id}"));
                    read_ms.lock().unwrap().push(t.elapsed().as_secs_f64() * 1e3);
                    assert_eq!(s, 200);
                    let t = Instant::now();
                    let (s, _) = srv.get("/api/runs?status=running&limit=50");
                    read_ms.lock().unwrap().push(t.elapsed().as_secs_f64() * 1e3);
                    assert_eq!(s, 200);
                    ids.lock().unwrap().entry(k).or_default().insert(id);
                }
            })
        })
        .collect();
    for c in clients {
        c.join().unwrap();
    }
    let sent = t0.elapsed();
    let ids = ids.lock().unwrap().clone();
    assert_eq!(ids.len(), DISTINCT);
    assert!(ids.values().all(|s| s.len() == 1), "one id per distinct run");
    let all: BTreeSet<String> = ids.values().flatten().cloned().collect();
    assert_eq!(all.len(), DISTINCT, "distinct runs have distinct ids");
    // every run ends, completed, catalogued once
    let t1 = Instant::now();
    loop {
        let (_, l) = srv.get("/api/runs?limit=1000");
        let done = l["runs"]
            .as_array()
            .unwrap()
            .iter()
            .filter(|r| r["status"] == "completed")
            .count();
        if done == DISTINCT {
            let listed: BTreeSet<String> = l["runs"]
                .as_array()
                .unwrap()
                .iter()
                .map(|r| r["id"].as_str().unwrap().to_string())
                .collect();
            assert_eq!(listed, all);
            assert_eq!(l["total"], DISTINCT);
            break;
        }
        assert!(
            t1.elapsed() < Duration::from_secs(600),
            "{done} of {DISTINCT} runs completed"
        );
        std::thread::sleep(Duration::from_millis(200));
    }
    let solved = t0.elapsed();
    let db = rusqlite::Connection::open(srv.data.join("catalogue.sqlite")).unwrap();
    let (rows, distinct): (i64, i64) = db
        .query_row("SELECT COUNT(*), COUNT(DISTINCT id) FROM runs", [], |r| {
            Ok((r.get(0)?, r.get(1)?))
        })
        .unwrap();
    assert_eq!((rows, distinct), (DISTINCT as i64, DISTINCT as i64));
    for id in &all {
        assert!(
            srv.data.join(format!("runs/{id}.mcap")).is_file(),
            "{id} has its recording"
        );
    }
    let mut s = submit_ms.lock().unwrap().clone();
    let mut r = read_ms.lock().unwrap().clone();
    s.sort_by(f64::total_cmp);
    r.sort_by(f64::total_cmp);
    println!(
        "load: {CLIENTS} clients, {SUBMISSIONS} submissions ({DISTINCT} distinct runs solved) sent in {:.1} s, \
         all solved in {:.1} s; POST /api/runs p50 {:.1} ms p99 {:.1} ms; GET p50 {:.1} ms p99 {:.1} ms ({} requests)",
        sent.as_secs_f64(),
        solved.as_secs_f64(),
        percentile(&s, 0.5),
        percentile(&s, 0.99),
        percentile(&r, 0.5),
        percentile(&r, 0.99),
        s.len() + r.len()
    );
}
