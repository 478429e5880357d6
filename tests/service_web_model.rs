//! The model view of a run's page: the endpoints `GET /api/runs/{id}/model` and
//! `/model/{increment}` against the run's recording (read with the library), and the page in
//! headless Chromium over the DevTools protocol (`service_common::cdp`) on a service with a
//! token: the page fetches the model from the service and nothing from anywhere else, draws
//! every element, has one slider step per increment, and after the slider is moved draws the
//! recording's contact points of that increment; play runs to the last increment. While a
//! longer run is solved, its partial recording is read (the increments of its complete chunks).
//!
//! `CONTRAIL_SCREENSHOT_DIR=docs cargo test --test service_web_model` also writes the picture
//! of docs/service.md (service-model.png).

mod service_common;

use contrail::analysis::recording::Recording;
use serde_json::{json, Value};
use service_common::cdp::Browser;
use service_common::{chromium, Server, TempDir};
use std::time::{Duration, Instant};

const TOKEN: &str = "web-model-token-1";
/// The strip drawn into the channel with a finer mesh: 48 × 2 elements, 60 nominal steps,
/// node positions every 4th increment.
const SETS: [&str; 2] = ["body.strip.mesh.elements=[48,2]", "stepping.increments=60"];
const EVERY: usize = 4;
const CANVAS: &str = "document.querySelector('#model-canvas')";
const SHOWN: &str = "document.querySelector('#model-card') ? document.querySelector('#model-card').innerText : document.querySelector('#run-view').innerText";

#[test]
fn the_run_page_plays_the_model_from_the_service() {
    let dir = TempDir::new("svc-web-model");
    let srv = Server::start(&dir.0.join("data"), &["--workers", "2", "--token", TOKEN]);
    let (id, rec) = srv.solved(("strip-channel", &SETS, EVERY), 300);
    the_endpoints_are_the_recording(&srv, &id, &rec);
    a_running_run_is_read_from_its_partial_recording(&srv);
    let Some(chrome) = chromium() else { return };
    let mut b = Browser::launch(&chrome, 1280, 1000);
    the_page_draws_and_plays_it(&mut b, &srv, &id, &rec);
}

fn body_len(srv: &Server, path: &str) -> usize {
    srv.bytes(path, &[("Authorization", &format!("Bearer {TOKEN}"))])
        .1
        .len()
}

/// The model and an increment, as the recording has them; the payloads are small; a bad
/// increment is a clear JSON error.
fn the_endpoints_are_the_recording(srv: &Server, id: &str, rec: &Recording) {
    let (s, m) = srv.get(&format!("/api/runs/{id}/model"));
    assert_eq!(s, 200, "{m}");
    assert_eq!(m["element_count"].as_u64(), Some(96));
    assert_eq!(m["elements"].as_array().unwrap().len(), 4 * 96);
    let incs: Vec<usize> = rec.increments.iter().map(|i| i.increment).collect();
    assert_eq!(m["frames"]["increment"], json!(incs));
    let with_positions: Vec<usize> = rec.positions.iter().map(|p| p.increment).collect();
    assert_eq!(m["positions_at"], json!(with_positions));
    let last = *incs.last().unwrap();
    let k = (1..last)
        .find(|k| k % EVERY != 0 && !rec.contact_at(*k).is_empty())
        .unwrap();
    let (s, f) = srv.get(&format!("/api/runs/{id}/model/{k}"));
    assert_eq!(s, 200, "{f}");
    assert_eq!(f["contact"]["count"].as_u64(), Some(rec.contact_at(k).len() as u64));
    assert_eq!(f["positions_increment"].as_u64(), Some((k / EVERY * EVERY) as u64));
    assert_eq!(f["positions_exact"], false);
    let (model_bytes, frame_bytes) = (
        body_len(srv, &format!("/api/runs/{id}/model")),
        body_len(srv, &format!("/api/runs/{id}/model/{last}")),
    );
    eprintln!("model {model_bytes} bytes, a frame {frame_bytes} bytes ({last} increments)");
    assert!(
        model_bytes < 200_000 && frame_bytes < 50_000,
        "{model_bytes} {frame_bytes}"
    );
    let (s, e) = srv.get(&format!("/api/runs/{id}/model/{}", last + 1));
    assert_eq!((s, &e["error"]["code"]), (404, &json!("no-increment")), "{e}");
    let (s, e) = srv.get(&format!("/api/runs/{id}/model/last"));
    assert_eq!((s, &e["error"]["code"]), (400, &json!("bad-request")), "{e}");
}

/// strip-channel with a 120 × 4 mesh and its 1200 nominal steps (seconds): once its first
/// chunks are written, its model has the increments recorded so far, read from the partial
/// recording; then it is cancelled.
fn a_running_run_is_read_from_its_partial_recording(srv: &Server) {
    let (s, run) = srv.post(
        "/api/runs",
        &json!({ "scene": "strip-channel", "set": ["body.strip.mesh.elements=[120,4]"] }),
    );
    assert_eq!(s, 201, "{run}");
    let id = run["id"].as_str().unwrap().to_string();
    let t0 = Instant::now();
    let m = loop {
        let (s, m) = srv.get(&format!("/api/runs/{id}/model?mesh=false"));
        if s == 200 {
            break m;
        }
        assert!(matches!(m["error"]["code"].as_str(), Some("no-recording")), "{s} {m}");
        assert!(t0.elapsed() < Duration::from_secs(240), "no increment readable: {m}");
        std::thread::sleep(Duration::from_millis(200));
    };
    let (_, now) = srv.get(&format!("/api/runs/{id}"));
    let incs = m["frames"]["increment"].as_array().unwrap().len();
    assert!(incs > 0 && m["nodes"].is_null(), "{m}");
    if now["status"] == "running" {
        assert_eq!(m["partial"], true, "{m}");
        let (s, f) = srv.get(&format!("/api/runs/{id}/model/{incs}"));
        assert_eq!((s, &f["partial"]), (200, &json!(true)), "{f}");
        let (s, e) = srv.get(&format!("/api/runs/{id}/model/{}", incs + 100_000));
        assert_eq!(s, 404, "{e}");
        assert!(e["error"]["hint"].as_str().unwrap().contains("running"), "{e}");
    }
    srv.post(&format!("/api/runs/{id}/cancel"), &json!({}));
    srv.wait_ended(&id, 60);
}

fn the_page_draws_and_plays_it(b: &mut Browser, srv: &Server, id: &str, rec: &Recording) {
    b.navigate(&format!("{}/?token={TOKEN}&live=0#/runs/{id}", srv.url));
    let last = rec.increments.last().unwrap().increment;
    b.wait_for(&format!("{CANVAS}.dataset.increment === '{last}'"), 30, SHOWN);
    let drawn = b.eval(&format!(
        "[{CANVAS}.dataset.elements, document.querySelector('#model-slider').max]"
    ));
    assert_eq!(drawn, json!([rec.model.elements.len().to_string(), last.to_string()]));
    assert_eq!(last, rec.increments.len(), "one slider step per increment");
    // the page asked the service, and nothing else
    let urls = b.eval("performance.getEntriesByType('resource').map((e) => e.name)");
    let urls: Vec<&str> = urls.as_array().unwrap().iter().map(|u| u.as_str().unwrap()).collect();
    for u in &urls {
        assert!(u.starts_with(&srv.url), "a request left the service: {u}");
    }
    for want in [
        format!("/api/runs/{id}/model?"),
        format!("/api/runs/{id}/model/{last}?"),
    ] {
        assert!(urls.iter().any(|u| u.contains(&want)), "{want} not among {urls:?}");
    }
    move_the_slider(b, rec);
    // the picture: two thirds into the run, at an increment with positions
    let k = rec.positions[rec.positions.len() * 2 / 3].increment;
    set_slider(b, k);
    b.wait_for(&format!("{CANVAS}.dataset.increment === '{k}'"), 20, SHOWN);
    picture(b);
    // from the last increment, play starts again at the reference configuration
    set_slider(b, last);
    b.wait_for(&format!("{CANVAS}.dataset.increment === '{last}'"), 20, SHOWN);
    let before = b.eval(&format!("+{CANVAS}.dataset.requests")).as_u64().unwrap();
    b.click("#model-play");
    let playing = b.eval("document.querySelector('#model-play').textContent");
    assert!(playing.as_str().unwrap().contains("pause"), "{playing}");
    b.wait_for(
        &format!("{CANVAS}.dataset.increment === '{last}' && document.querySelector('#model-play').textContent.includes('play')"),
        60,
        SHOWN,
    );
    let after = b.eval(&format!("+{CANVAS}.dataset.requests")).as_u64().unwrap();
    assert!(
        after >= before + last as u64 / 2,
        "played through the increments: {before} then {after} requests"
    );
}

/// To an increment with contact points whose positions are an earlier increment's: the points
/// are the recording's (drawn: those with a position; an open slave out of reach may have
/// none), and the page says whose positions the mesh has.
fn move_the_slider(b: &mut Browser, rec: &Recording) {
    let k = rec
        .increments
        .iter()
        .map(|i| i.increment)
        .filter(|k| k % EVERY != 0 && *k < rec.increments.len())
        .max_by_key(|k| rec.contact_at(*k).len())
        .unwrap();
    set_slider(b, k);
    b.wait_for(&format!("{CANVAS}.dataset.increment === '{k}'"), 20, SHOWN);
    let points = rec.contact_at(k);
    let placed = points
        .iter()
        .filter(|p| p.position.iter().all(|x| x.is_finite()))
        .count();
    let drawn = b.eval(&format!(
        "[+{CANVAS}.dataset.contactsRecorded, +{CANVAS}.dataset.contacts]"
    ));
    assert_eq!(drawn, json!([points.len(), placed]), "increment {k}: recorded, drawn");
    assert!(placed > 0);
    let note: Value = b.eval("document.querySelector('#model-positions').textContent");
    let shown = k / EVERY * EVERY;
    assert!(
        note.as_str().unwrap().contains(&format!("increment {shown}'s")),
        "{note}"
    );
    let info = b.eval("document.querySelector('#model-info').innerText");
    let iterations = rec.increments[k - 1].iterations;
    assert!(
        info.as_str()
            .unwrap()
            .contains(&format!("Newton iterations\n{iterations}"))
            || info
                .as_str()
                .unwrap()
                .contains(&format!("Newton iterations\t{iterations}")),
        "{info}"
    );
}

/// Move the increment slider (its value and the `input` event a drag gives).
fn set_slider(b: &mut Browser, k: usize) {
    b.eval(&format!(
        "(() => {{ const s = document.querySelector('#model-slider'); s.focus(); s.value = {k};
           s.dispatchEvent(new Event('input', {{ bubbles: true }})); }})()"
    ));
}

/// The model card, checked to be a PNG, kept in $CONTRAIL_SCREENSHOT_DIR if set.
fn picture(b: &mut Browser) {
    let png = b.screenshot(Some("#model-card"));
    assert!(
        png.starts_with(b"\x89PNG\r\n\x1a\n") && png.len() > 10_000,
        "{} bytes",
        png.len()
    );
    if let Some(dir) = std::env::var_os("CONTRAIL_SCREENSHOT_DIR") {
        std::fs::write(std::path::Path::new(&dir).join("service-model.png"), png).unwrap();
    }
}
