//! `contrail serve`'s guards: loopback only unless a token is given, the token on every
//! request, ids and paths validated, body and scene limits, clear 4xx errors in JSON.

mod service_common;

use serde_json::{json, Value};
use service_common::{Server, TempDir, BIN};

fn error_code(v: &Value) -> &str {
    v["error"]["code"]
        .as_str()
        .unwrap_or_else(|| panic!("not a JSON error: {v}"))
}

#[test]
fn a_service_reachable_from_outside_needs_a_token() {
    let dir = TempDir::new("svc-bind");
    let out = std::process::Command::new(BIN)
        .args(["serve", "--port", "0", "--bind", "0.0.0.0", "--data"])
        .arg(dir.0.join("data"))
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("needs --token"));
}

#[test]
fn with_a_token_every_request_needs_it() {
    let dir = TempDir::new("svc-token");
    let mut srv = Server::start(&dir.0.join("data"), &["--token", "s3cret-token", "--workers", "1"]);
    assert_eq!(srv.get("/api/health").0, 200);
    for path in ["/", "/api/health", "/api/runs", "/api/runs/x/recording", "/api/events"] {
        let (s, body, _) = srv.bytes(path, &[]);
        assert_eq!(s, 401, "{path}");
        let v: Value = serde_json::from_slice(&body).unwrap();
        assert_eq!(error_code(&v), "unauthorized");
        let (s, _, _) = srv.bytes(path, &[("Authorization", "Bearer wrong-token!")]);
        assert_eq!(s, 401, "{path}");
    }
    let (s, _, _) = srv.bytes("/api/health?token=s3cret-token", &[]);
    assert_eq!(s, 200);
    // the page (`/?token=`) loads its scripts and style sheet without the token: the same
    // files for every service, holding no data
    for path in ["/app.js", "/model.js", "/style.css"] {
        let (s, _, h) = srv.bytes(path, &[]);
        assert_eq!(s, 200, "{path}");
        assert!(!h["content-type"].to_str().unwrap().contains("json"), "{path}");
    }
    assert_eq!(srv.bytes("/app.js/../api/runs", &[]).0, 401);
    let (code, out, err) = srv.client(&["runs", "--token", "s3cret-token"]);
    assert_eq!(code, 0, "{out}{err}");
    srv.token = None;
    let (code, _, err) = srv.client(&["runs"]);
    assert_eq!(code, 2);
    assert!(err.contains("needs its token"), "{err}");
}

#[test]
fn bad_ids_paths_bodies_and_scenes_get_clear_json_errors() {
    let dir = TempDir::new("svc-guard");
    let srv = Server::start(&dir.0.join("data"), &["--workers", "1", "--max-elements", "5000"]);
    for path in [
        "/api/runs/..%2F..%2Fcatalogue.sqlite/recording",
        "/api/runs/.hidden",
        "/api/runs/a%20b/curve",
        "/api/diff?a=..&b=x",
    ] {
        let (s, v) = srv.get(path);
        assert_eq!((s, error_code(&v)), (400, "bad-request"), "{path}");
    }
    let (s, v) = srv.get("/api/runs/..");
    assert!(s == 400 || s == 404, "{path} {v}", path = "/api/runs/..");
    let (s, v) = srv.get("/api/runs/no-such-run");
    assert_eq!((s, error_code(&v)), (404, "not-found"));
    let (s, v) = srv.get("/no/such/route");
    assert_eq!((s, error_code(&v)), (404, "not-found"));
    let (s, v) = srv.post("/api/health", &json!({}));
    assert_eq!((s, error_code(&v)), (405, "method-not-allowed"));
    let (s, v) = srv.get("/api/runs?status=bogus");
    assert_eq!((s, error_code(&v)), (400, "bad-request"));
    let (s, v) = srv.get("/api/runs?colour=red");
    assert_eq!((s, error_code(&v)), (400, "bad-request"));

    let big = "#".repeat(2 << 20);
    let (s, v) = srv.post("/api/runs", &json!({ "scene_toml": big }));
    assert_eq!((s, error_code(&v)), (413, "too-large"));
    let (s, v) = srv.post("/api/runs", &json!({ "scene_toml": "#".repeat(300 << 10) }));
    assert_eq!((s, error_code(&v)), (413, "too-large"));
    let cases = [
        (json!({ "scene": "nope" }), "not a built-in scene"),
        (json!({ "scene": "crossing", "scene_toml": "x" }), "either"),
        (json!({}), "either"),
        (json!({ "scene": "crossing", "colour": 1 }), "unknown field"),
        (json!({ "scene": "crossing", "set": ["contact.nope=1"] }), "nope"),
        (json!({ "scene": "crossing", "set": ["no-equals-sign"] }), "KEY=VALUE"),
        (
            json!({ "scene": "block-slide", "set": ["body.block.mesh.elements=[400, 400]"] }),
            "160000 elements",
        ),
        (
            json!({ "scene_toml": contrail::scene::builtin::find("half-disc").unwrap().text }),
            "mesh file",
        ),
        (json!({ "scene_toml": "this is not toml" }), "scenes/"),
    ];
    for (body, needle) in cases {
        let (s, v) = srv.post("/api/runs", &body);
        assert!(s == 400 || s == 422, "{body}: {s} {v}");
        let message = v["error"]["message"].as_str().unwrap_or_else(|| panic!("{body}: {v}"));
        assert!(message.contains(needle), "{body}: {message}");
    }
    let mut req = ureq::post(format!("{}/api/runs", srv.url))
        .config()
        .http_status_as_error(false)
        .build();
    req = req.header("Content-Type", "application/json");
    let mut res = req.send("{not json").unwrap();
    assert_eq!(res.status().as_u16(), 400);
    let v: Value = res.body_mut().read_json().unwrap();
    assert_eq!(error_code(&v), "bad-json");
    let (s, v) = srv.post(
        "/api/sweeps",
        &json!({ "plan": "name = \"p\"\n[[study]]\nscene = \"../../x.toml\"\n" }),
    );
    assert_eq!((s, error_code(&v)), (400, "bad-request"));
    // nothing of this reached the catalogue
    assert_eq!(srv.get("/api/runs").1["total"], 0);
}

/// What another site's page could send through a visitor's browser: the types an HTML form
/// sends are refused, and a preflight of a script's JSON request gets no CORS permission.
#[test]
fn another_sites_page_cannot_submit_through_a_visitors_browser() {
    let dir = TempDir::new("svc-csrf");
    let srv = Server::start(&dir.0.join("data"), &["--workers", "1"]);
    for ty in [
        "text/plain",
        "application/x-www-form-urlencoded",
        "multipart/form-data; boundary=x",
    ] {
        let mut res = ureq::post(format!("{}/api/runs", srv.url))
            .config()
            .http_status_as_error(false)
            .build()
            .header("Content-Type", ty)
            .header("Origin", "http://elsewhere.example")
            .send(r#"{"scene": "crossing"}"#)
            .unwrap();
        assert_eq!(res.status().as_u16(), 415, "{ty}");
        let v: Value = res.body_mut().read_json().unwrap();
        assert_eq!(error_code(&v), "bad-json");
    }
    let res = ureq::http::Request::options(format!("{}/api/runs", srv.url))
        .header("Origin", "http://elsewhere.example")
        .header("Access-Control-Request-Method", "POST")
        .header("Access-Control-Request-Headers", "content-type")
        .body(())
        .unwrap();
    let res = ureq::Agent::config_builder()
        .http_status_as_error(false)
        .build()
        .new_agent()
        .run(res)
        .unwrap();
    assert!(res.status().is_client_error(), "{}", res.status());
    assert!(res.headers().keys().all(|k| !k.as_str().starts_with("access-control-")));
    assert_eq!(srv.get("/api/runs").1["total"], 0);
}
