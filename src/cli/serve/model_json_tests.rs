//! The model view's JSON, from a recording of `crossing` solved in memory: shapes and bounds
//! of the mesh and the index, one increment's positions and contact points against the
//! recording, and the endpoints' answers to bad increments, unknown runs and runs without a
//! recording (JSON errors, never a panic).

use super::*;
use crate::cli::serve::api::app;
use crate::cli::serve::catalogue::{Catalogue, Finish, NewRun};
use crate::cli::serve::state::{Backend, Service};
use axum::body::Body;
use axum::http::Request;
use contrail::record::mcap::sink::{McapOptions, McapSink};
use std::collections::BTreeMap;
use std::sync::atomic::AtomicBool;
use std::sync::Arc;
use tower::ServiceExt;

const INCREMENTS: usize = 10;
const EVERY: usize = 3;

/// `crossing` with 10 increments, positions every 3rd, recorded in memory.
fn recorded() -> Vec<u8> {
    let sets = vec![format!("stepping.increments={INCREMENTS}")];
    let (src, problem) = contrail::load_scene("crossing", &sets).unwrap_or_else(|e| panic!("{e}"));
    let info = contrail::run_info(&src, &sets, &problem);
    let opts = McapOptions {
        positions_every: EVERY,
        ..McapOptions::default()
    };
    let mut sink = McapSink::new(std::io::Cursor::new(Vec::new()), "memory", opts).unwrap();
    let _ = contrail::solver::run(&problem, &info, &mut sink, &AtomicBool::new(false));
    sink.into_inner().unwrap().into_inner()
}

fn recording() -> Recording {
    Recording::from_bytes(&recorded(), "crossing.mcap").unwrap()
}

fn len(v: &Value) -> usize {
    v.as_array().unwrap_or_else(|| panic!("not an array: {v}")).len()
}

#[test]
fn the_model_has_the_mesh_the_index_and_bounds_that_hold_the_run() {
    let rec = recording();
    let v = model(&rec, true);
    let (n, e) = (rec.model.nodes.len(), rec.model.elements.len());
    assert_eq!((v["dim"].as_u64(), v["node_count"].as_u64()), (Some(2), Some(n as u64)));
    assert_eq!(len(&v["nodes"]), 2 * n);
    assert_eq!(len(&v["elements"]), 4 * e);
    assert_eq!(len(&v["element_body"]), e);
    assert_eq!(len(&v["bodies"]), rec.model.bodies.len());
    assert_eq!(v["rigid"][0]["name"], "P");
    assert_eq!(len(&v["rigid"][0]["pieces"][0]), 2, "a rigid point: one (x, y)");
    let incs: Vec<usize> = (1..=INCREMENTS).collect();
    assert_eq!(v["frames"]["increment"], json!(incs));
    for key in [
        "t",
        "iterations",
        "cutbacks",
        "converged",
        "contact",
        "displacement",
        "force",
    ] {
        assert_eq!(len(&v["frames"][key]), INCREMENTS, "{key}");
    }
    let counts: Vec<usize> = incs.iter().map(|&i| rec.contact_at(i).len()).collect();
    assert_eq!(v["frames"]["contact"], json!(counts));
    assert_eq!(v["positions_at"], json!([3, 6, 9, 10]), "every 3rd and the last");
    assert_eq!(v["positions_every"], 3);
    let b: Vec<f64> = serde_json::from_value(v["bounds"].clone()).unwrap();
    assert!(b.iter().all(|x| x.is_finite()) && b[0] < b[2] && b[1] < b[3], "{b:?}");
    for p in rec.positions.iter().flat_map(|p| &p.nodes) {
        assert!(
            p[0] >= b[0] && p[0] <= b[2] && p[1] >= b[1] && p[1] <= b[3],
            "{p:?} outside {b:?}"
        );
    }
    assert!(v["largest"]["force"].as_f64().unwrap() > 0.0);
    let index = model(&rec, false);
    assert!(index.get("nodes").is_none() && index.get("elements").is_none());
    assert_eq!(index["frames"], v["frames"]);
}

#[test]
fn a_frame_has_its_contact_points_and_the_nearest_earlier_positions() {
    let rec = recording();
    for inc in 1..=INCREMENTS {
        let f = frame(&rec, inc).unwrap();
        let points = rec.contact_at(inc);
        let c = &f["contact"];
        assert_eq!(c["count"].as_u64(), Some(points.len() as u64), "increment {inc}");
        for key in [
            "pair",
            "slave",
            "node",
            "rigid",
            "state",
            "segment",
            "normal_force",
            "traction",
            "gap",
        ] {
            assert_eq!(len(&c[key]), points.len(), "{key}");
        }
        for key in ["position", "normal", "tangent", "force"] {
            assert_eq!(len(&c[key]), 2 * points.len(), "{key}");
        }
        let shown = if inc < EVERY {
            0
        } else {
            inc.min(INCREMENTS) / EVERY * EVERY
        };
        let shown = if inc == INCREMENTS { INCREMENTS } else { shown };
        assert_eq!(f["positions_increment"].as_u64(), Some(shown as u64), "increment {inc}");
        assert_eq!(f["positions_exact"], json!(shown == inc));
        assert_eq!(len(&f["nodes"]), 2 * rec.model.nodes.len());
        let t = rec.increments[inc - 1].t;
        assert_eq!(f["t"].as_f64(), Some(t));
        assert_eq!(
            f["iterations"].as_u64(),
            Some(rec.increments[inc - 1].iterations as u64)
        );
    }
    // a rigid slave: no node, its rigid body; a closed point is stick or slip
    let f = frame(&rec, INCREMENTS).unwrap();
    assert_eq!(
        (f["contact"]["node"][0].clone(), f["contact"]["rigid"][0].clone()),
        (json!(null), json!(0))
    );
    assert!(["stick", "slip"].contains(&f["contact"]["state"][0].as_str().unwrap()));
    // increment 0: the reference configuration, no contact
    let zero = frame(&rec, 0).unwrap();
    assert_eq!(
        (zero["t"].as_f64(), zero["contact"]["count"].as_u64()),
        (Some(0.0), Some(0))
    );
    let reference: Vec<f32> = rec
        .model
        .nodes
        .iter()
        .flat_map(|p| [p[0] as f32, p[1] as f32])
        .collect();
    assert_eq!(zero["nodes"], json!(reference));
}

#[test]
fn an_increment_the_recording_lacks_is_an_error_that_says_which_it_has() {
    let rec = recording();
    let e = frame(&rec, INCREMENTS + 1).unwrap_err();
    assert_eq!(
        e,
        FrameError::NoSuchIncrement {
            asked: INCREMENTS + 1,
            last: Some(INCREMENTS)
        }
    );
    assert!(e.to_string().contains("increments 1 to 10"), "{e}");
    assert!(frame(&rec, usize::MAX).is_err());
}

/// A service in a temporary folder with run `done` (completed, recorded) and run `waiting`
/// (queued, no recording).
fn service(dir: &std::path::Path) -> Arc<Service> {
    std::fs::create_dir_all(dir.join("runs")).unwrap();
    let cat = Catalogue::open(&dir.join("catalogue.sqlite")).unwrap();
    let svc = Service::new(dir.to_path_buf(), cat, Backend::Local, 1).unwrap();
    let params = BTreeMap::new();
    for id in ["done", "waiting"] {
        let run = NewRun {
            id,
            scene: "crossing",
            scene_ref: "crossing",
            sets: &[],
            params: &params,
            sweep: None,
            positions_every: EVERY,
        };
        svc.catalogue.insert(&run).unwrap();
    }
    svc.catalogue.claim("local").unwrap();
    let finish = Finish {
        status: "completed",
        failure_kind: None,
        message: "",
        outcome: None,
        culprit: None,
        metrics: None,
        log: "",
    };
    svc.catalogue.finish("done", &finish).unwrap();
    std::fs::write(svc.recording("done"), recorded()).unwrap();
    Arc::new(svc)
}

fn get(svc: &Arc<Service>, path: &str) -> (u16, Value) {
    let rt = tokio::runtime::Builder::new_current_thread()
        .enable_all()
        .build()
        .unwrap();
    rt.block_on(async {
        let req = Request::get(path).body(Body::empty()).unwrap();
        let res = app(svc.clone()).oneshot(req).await.unwrap();
        let status = res.status().as_u16();
        let bytes = axum::body::to_bytes(res.into_body(), 64 << 20).await.unwrap();
        (status, serde_json::from_slice(&bytes).unwrap_or(Value::Null))
    })
}

#[test]
fn the_endpoints_answer_bad_requests_with_json_errors() {
    let dir = std::env::temp_dir().join(format!("contrail-model-view-{}", std::process::id()));
    let svc = service(&dir);
    let (s, v) = get(&svc, "/api/runs/done/model");
    assert_eq!((s, v["element_count"].as_u64()), (200, Some(4)), "{v}");
    assert_eq!((v["id"].as_str(), v["partial"].as_bool()), (Some("done"), Some(false)));
    let (s, v) = get(&svc, "/api/runs/done/model?mesh=false");
    assert_eq!((s, v.get("nodes")), (200, None));
    let (s, v) = get(&svc, "/api/runs/done/model/4");
    assert_eq!((s, v["increment"].as_u64()), (200, Some(4)), "{v}");
    let code = |v: &Value| v["error"]["code"].as_str().unwrap_or_default().to_string();
    let message = |v: &Value| v["error"]["message"].as_str().unwrap_or_default().to_string();
    let (s, v) = get(&svc, "/api/runs/done/model/11");
    assert_eq!((s, code(&v).as_str()), (404, "no-increment"), "{v}");
    assert!(message(&v).contains("increments 1 to 10"), "{v}");
    for bad in ["abc", "-1", "1.5", "99999999999999999999999"] {
        let (s, v) = get(&svc, &format!("/api/runs/done/model/{bad}"));
        assert_eq!((s, code(&v).as_str()), (400, "bad-request"), "{bad}: {v}");
        assert!(message(&v).contains("not an increment number"), "{v}");
    }
    let (s, v) = get(&svc, "/api/runs/done/model?mesh=perhaps");
    assert_eq!(s, 400, "{v}");
    let (s, v) = get(&svc, "/api/runs/waiting/model");
    assert_eq!((s, code(&v).as_str()), (409, "no-recording"), "{v}");
    let (s, v) = get(&svc, "/api/runs/nobody/model/1");
    assert_eq!((s, code(&v).as_str()), (404, "not-found"), "{v}");
    let (s, v) = get(&svc, "/api/runs/..%2Fx/model");
    assert_eq!((s, code(&v).as_str()), (400, "bad-request"), "{v}");
    // a recording that is not one: a JSON 500 naming the file
    std::fs::write(svc.recording("done"), b"not an mcap file").unwrap();
    let (s, v) = get(&svc, "/api/runs/done/model");
    assert_eq!((s, code(&v).as_str()), (500, "bad-recording"), "{v}");
    std::fs::remove_dir_all(&dir).unwrap();
}
