//! The model view of a 3D run: `hertz-3d` on a coarse mesh solved on a service with a
//! token; the endpoints `GET /api/runs/{id}/model` and `/model/{increment}` against the
//! recording (read with the library): the nodes, the boundary faces, the rigid sphere, node
//! positions equal to the recording's in single precision, the contact points and their
//! states; then the page in headless Chromium (`service_common::cdp`): it fetches the model
//! from the service and nothing from anywhere else, draws every edge of the boundary and
//! the contact points with a position, has one slider step per increment, and turns the
//! view when the canvas is dragged.
//!
//! `CONTRAIL_SCREENSHOT_DIR=docs cargo test --test service_web_model_3d` also writes the
//! picture of docs/service.md (service-model-3d.png).

mod service_common;

use contrail::analysis::recording::Recording;
use contrail::model::hex_boundary::boundary_quads;
use serde_json::{json, Value};
use service_common::cdp::Browser;
use service_common::{chromium, Server, TempDir};

const TOKEN: &str = "web-model-3d-token-1";
/// The quarter block on 6 × 6 × 4 hexahedra, the sphere pressed in 6 increments, node
/// positions every 2nd increment.
const SETS: [&str; 2] = ["body.block.mesh.elements=[6,6,4]", "stepping.increments=6"];
const EVERY: usize = 2;
const CANVAS: &str = "document.querySelector('#model-canvas')";
const SHOWN: &str = "document.querySelector('#model-card') ? document.querySelector('#model-card').innerText : document.querySelector('#run-view').innerText";

#[test]
fn the_run_page_plays_a_3d_model_from_the_service() {
    let dir = TempDir::new("svc-web-model-3d");
    let srv = Server::start(&dir.0.join("data"), &["--workers", "1", "--token", TOKEN]);
    let (id, rec) = srv.solved(("hertz-3d", &SETS, EVERY), 300);
    the_model_is_the_recording(&srv, &id, &rec);
    the_increments_are_the_recording(&srv, &id, &rec);
    let Some(chrome) = chromium() else { return };
    let mut b = Browser::launch(&chrome, 1280, 1000);
    the_page_draws_and_turns_it(&mut b, &srv, &id, &rec);
}

fn numbers(v: &Value) -> Vec<Option<f64>> {
    let a = v.as_array().unwrap_or_else(|| panic!("not an array: {v}"));
    a.iter().map(Value::as_f64).collect()
}

/// `points` as the endpoints give them: f32, NaN as null.
fn as_f32(points: &[[f64; 3]]) -> Vec<Option<f64>> {
    (points.iter().flatten())
        .map(|x| x.is_finite().then_some(*x as f32 as f64))
        .collect()
}

/// The boundary edges of the recording's hexahedra, each once.
fn edge_count(rec: &Recording) -> usize {
    let mut edges: Vec<[usize; 2]> = (boundary_quads(&rec.model.hexahedra).iter())
        .flat_map(|q| (0..4).map(move |k| [q[k].min(q[(k + 1) % 4]), q[k].max(q[(k + 1) % 4])]))
        .collect();
    edges.sort_unstable();
    edges.dedup();
    edges.len()
}

fn body_len(srv: &Server, path: &str) -> usize {
    srv.bytes(path, &[("Authorization", &format!("Bearer {TOKEN}"))])
        .1
        .len()
}

/// The model: 3 numbers per node, the boundary quadrilaterals, the sphere, the index of
/// increments, bounds that hold every recorded position.
fn the_model_is_the_recording(srv: &Server, id: &str, rec: &Recording) {
    let (s, m) = srv.get(&format!("/api/runs/{id}/model"));
    assert_eq!(s, 200, "{m}");
    let n = rec.model.nodes_3d.len();
    assert_eq!((m["dim"].as_u64(), m["node_count"].as_u64()), (Some(3), Some(n as u64)));
    assert_eq!(numbers(&m["nodes"]), as_f32(&rec.model.nodes_3d));
    let quads = boundary_quads(&rec.model.hexahedra);
    assert_eq!(m["faces"], json!(quads.iter().flatten().collect::<Vec<_>>()));
    assert_eq!(m["face_body"], json!(vec![0; quads.len()]));
    assert_eq!(m["element_count"].as_u64(), Some(rec.model.hexahedra.len() as u64));
    assert_eq!(m["rigid"][0]["kind"], "sphere", "{}", m["rigid"]);
    assert_eq!(m["rigid"][0]["radius"], 1.0);
    assert_eq!(
        m["pairs"][0]["slaves"].as_u64(),
        Some(rec.model.surface_contacts[0].slave_nodes.len() as u64)
    );
    let incs: Vec<usize> = rec.increments.iter().map(|i| i.increment).collect();
    assert_eq!(m["frames"]["increment"], json!(incs));
    let counts: Vec<usize> = incs.iter().map(|&k| rec.surface_at(k).len()).collect();
    assert_eq!(m["frames"]["contact"], json!(counts));
    let with_positions: Vec<usize> = rec.positions.iter().map(|p| p.increment).collect();
    assert_eq!(m["positions_at"], json!(with_positions));
    let b: Vec<f64> = serde_json::from_value(m["bounds"].clone()).unwrap();
    assert_eq!(b.len(), 6);
    for p in rec.positions.iter().flat_map(|p| &p.nodes_3d) {
        assert!((0..3).all(|c| p[c] >= b[c] && p[c] <= b[c + 3]), "{p:?} outside {b:?}");
    }
    assert!(m["largest"]["force"].as_f64().unwrap() > 0.0, "{}", m["largest"]);
}

/// Each increment's positions (its own or the nearest earlier ones), the sphere's offset and
/// the contact points with their states, as recorded; a bad increment is a JSON 404.
fn the_increments_are_the_recording(srv: &Server, id: &str, rec: &Recording) {
    let last = rec.increments.last().unwrap().increment;
    for k in 1..=last {
        let (s, f) = srv.get(&format!("/api/runs/{id}/model/{k}"));
        assert_eq!((s, f["dim"].as_u64()), (200, Some(3)), "{f}");
        let shown = rec
            .positions
            .iter()
            .filter(|p| p.increment <= k)
            .max_by_key(|p| p.increment);
        let nodes = shown.map_or(&rec.model.nodes_3d, |p| &p.nodes_3d);
        assert_eq!(
            f["positions_increment"].as_u64(),
            Some(shown.map_or(0, |p| p.increment) as u64)
        );
        assert_eq!(numbers(&f["nodes"]), as_f32(nodes), "increment {k}");
        assert_eq!(
            numbers(&f["rigid_offsets"]),
            as_f32(&rec.surface_offsets[&k]),
            "increment {k}"
        );
        let points = rec.surface_at(k);
        let c = &f["contact"];
        assert_eq!(c["count"].as_u64(), Some(points.len() as u64));
        let states: Vec<Value> = points.iter().map(|p| json!(p.state)).collect();
        assert_eq!(c["state"], json!(states));
        let nodes: Vec<usize> = points.iter().map(|p| p.node).collect();
        assert_eq!(c["node"], json!(nodes));
        let positions: Vec<[f64; 3]> = points.iter().map(|p| p.position).collect();
        assert_eq!(numbers(&c["position"]), as_f32(&positions));
    }
    let closed = rec.surface_at(last).iter().filter(|p| p.normal_force > 0.0).count();
    assert!(closed > 0, "the sphere presses the block at the last increment");
    let (model_bytes, frame_bytes) = (
        body_len(srv, &format!("/api/runs/{id}/model")),
        body_len(srv, &format!("/api/runs/{id}/model/{last}")),
    );
    eprintln!("3D model {model_bytes} bytes, a frame {frame_bytes} bytes ({last} increments)");
    let (s, e) = srv.get(&format!("/api/runs/{id}/model/{}", last + 1));
    assert_eq!((s, &e["error"]["code"]), (404, &json!("no-increment")), "{e}");
}

fn the_page_draws_and_turns_it(b: &mut Browser, srv: &Server, id: &str, rec: &Recording) {
    b.navigate(&format!("{}/?token={TOKEN}&live=0#/runs/{id}", srv.url));
    let last = rec.increments.last().unwrap().increment;
    b.wait_for(&format!("{CANVAS}.dataset.increment === '{last}'"), 30, SHOWN);
    let drawn = b.eval(&format!(
        "[{CANVAS}.dataset.edges, document.querySelector('#model-slider').max, {CANVAS}.dataset.contacts]"
    ));
    let placed = (rec.surface_at(last).iter())
        .filter(|p| p.position.iter().all(|x| x.is_finite()))
        .count();
    assert_eq!(
        drawn,
        json!([edge_count(rec).to_string(), last.to_string(), placed.to_string()])
    );
    assert_eq!(last, rec.increments.len(), "one slider step per increment");
    // the page asked the service, and nothing else
    let urls = b.eval("performance.getEntriesByType('resource').map((e) => e.name)");
    let urls: Vec<&str> = urls.as_array().unwrap().iter().map(|u| u.as_str().unwrap()).collect();
    for u in &urls {
        assert!(u.starts_with(&srv.url), "a request left the service: {u}");
    }
    for want in [
        "/model3d.js".to_string(),
        format!("/api/runs/{id}/model?"),
        format!("/api/runs/{id}/model/{last}?"),
    ] {
        assert!(urls.iter().any(|u| u.contains(&want)), "{want} not among {urls:?}");
    }
    // dragging the canvas turns the view; the slider moves to an earlier increment
    let before = b.eval(&format!("{CANVAS}.dataset.azimuth"));
    b.drag("#model-canvas", 60.0, 0.0, 4);
    let after = b.eval(&format!("{CANVAS}.dataset.azimuth"));
    assert_ne!(before, after, "a drag turns the view");
    b.eval(&format!(
        "{CANVAS}.dispatchEvent(new MouseEvent('dblclick', {{ bubbles: true }}))"
    ));
    assert_eq!(
        b.eval(&format!("{CANVAS}.dataset.azimuth")),
        before,
        "double-click: the first view"
    );
    let k = last / 2 + 1;
    set_slider(b, k);
    b.wait_for(&format!("{CANVAS}.dataset.increment === '{k}'"), 20, SHOWN);
    let recorded = b.eval(&format!("+{CANVAS}.dataset.contactsRecorded"));
    assert_eq!(recorded, json!(rec.surface_at(k).len()));
    // the picture: the last increment, displacements magnified 20 times
    set_slider(b, last);
    b.wait_for(&format!("{CANVAS}.dataset.increment === '{last}'"), 20, SHOWN);
    b.choose("#model-magnify", "20");
    picture(b);
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
        std::fs::write(std::path::Path::new(&dir).join("service-model-3d.png"), png).unwrap();
    }
}
