//! The web page's submit form in headless Chromium, driven over the DevTools protocol as a
//! user would (mouse clicks, typed text; `service_common::cdp`): the built-in scenes come
//! from the service, a scene with a TOML error and an unknown override get the service's
//! messages on the page, and a built-in scene with two overrides, submitted on a service
//! with a token, is followed live to `completed` and listed in the runs table.
//!
//! `CONTRAIL_SCREENSHOT_DIR=docs cargo test --test service_web_submit` also writes the
//! pictures of docs/service.md: the form filled in (service-submit.png) and the form with
//! a scene's TOML error (service-submit-error.png).

mod service_common;

use serde_json::json;
use service_common::cdp::Browser;
use service_common::{chromium, Server, TempDir};

const TOKEN: &str = "web-form-token-1";
/// What the error box says (for a failed wait).
const ERROR_BOX: &str = "document.querySelector('#submit-error').innerText";

/// A picture of the form, checked to be a PNG, kept in $CONTRAIL_SCREENSHOT_DIR if set.
fn picture(b: &mut Browser, name: &str) {
    let png = b.screenshot(Some("#submit-view"));
    assert!(
        png.starts_with(b"\x89PNG\r\n\x1a\n") && png.len() > 5_000,
        "{} bytes",
        png.len()
    );
    if let Some(dir) = std::env::var_os("CONTRAIL_SCREENSHOT_DIR") {
        std::fs::write(std::path::Path::new(&dir).join(name), png).unwrap();
    }
}

fn submit_and_read_error(b: &mut Browser) -> String {
    b.eval("document.querySelector('#submit-error').hidden = true");
    b.click("#submit-run");
    let shown =
        "document.querySelector('#submit-error').hidden ? '' : document.querySelector('#submit-message').textContent";
    let msg = b.wait_for(shown, 20, "location.hash");
    assert_eq!(b.eval("location.hash").as_str(), Some("#/submit"), "the form stays");
    msg.as_str().unwrap().to_string()
}

#[test]
fn a_run_submitted_from_the_web_page_completes_and_is_listed() {
    let Some(chrome) = chromium() else { return };
    let dir = TempDir::new("svc-web-submit");
    let srv = Server::start(&dir.0.join("data"), &["--workers", "1", "--token", TOKEN]);
    let mut b = Browser::launch(&chrome, 1280, 900);
    open_the_form(&mut b, &srv);
    refused_submissions_stay_on_the_form(&mut b, &srv);
    let id = submit_and_follow(&mut b, &srv);
    listed_then_submitted_again(&mut b, &srv, &id);
}

/// The table, then the form through its link; the built-in scenes are the service's.
fn open_the_form(b: &mut Browser, srv: &Server) {
    b.navigate(&format!("{}/?token={TOKEN}", srv.url));
    b.wait_for("document.body.dataset.ready === '1'", 20, "document.body.innerText");
    b.click("#new-run");
    b.wait_for(
        "location.hash === '#/submit' && !document.querySelector('#submit-view').hidden",
        20,
        "location.hash",
    );

    let (_, scenes) = srv.get("/api/scenes");
    let names: Vec<&str> = scenes["scenes"]
        .as_array()
        .unwrap()
        .iter()
        .map(|s| s["name"].as_str().unwrap())
        .collect();
    let options = b.wait_for(
        "[...document.querySelectorAll('#scene-select option')].map((o) => o.value)",
        20,
        "document.querySelector('#submit-view').innerText",
    );
    assert_eq!(options, json!(names));
    b.choose("#scene-select", "crossing");
    let described = b.wait_for("document.querySelector('#scene-description').textContent", 5, ERROR_BOX);
    let crossing = scenes["scenes"]
        .as_array()
        .unwrap()
        .iter()
        .find(|s| s["name"] == "crossing")
        .unwrap();
    assert_eq!(described, crossing["description"]);
}

/// A pasted scene with a TOML error gets the service's message with the line and column, a
/// built-in scene with an unknown override the field's name; nothing is catalogued.
fn refused_submissions_stay_on_the_form(b: &mut Browser, srv: &Server) {
    b.click("input[name=source][value=toml]");
    b.type_into("#scene-toml", "name = \"web\"\n[[body]]\nname = = 3\n");
    let msg = submit_and_read_error(b);
    assert!(msg.contains(".toml:3:8: extra `=`"), "{msg}");
    picture(b, "service-submit-error.png");
    b.click("input[name=source][value=builtin]");
    b.type_into("#sets", "contact.nope=1");
    let msg = submit_and_read_error(b);
    assert!(msg.contains("nope"), "{msg}");
    assert_eq!(srv.get("/api/runs").1["total"], 0, "nothing was catalogued");
}

/// `crossing` with two override lines (and a blank one), followed live on its page to
/// `completed`; the run is the one the API makes of the same request. Its id.
fn submit_and_follow(b: &mut Browser, srv: &Server) -> String {
    b.type_into("#sets", "stepping.increments=40\n\ncontact.eps_t=2.0e3\n");
    b.click("#submit-run");
    let hash = b.wait_for("location.hash.startsWith('#/runs/') && location.hash", 20, ERROR_BOX);
    let id = hash.as_str().unwrap().trim_start_matches("#/runs/").to_string();
    let status = "document.querySelector('#run-status') && document.querySelector('#run-status').textContent";
    b.wait_for(
        &format!("{status} === 'completed'"),
        120,
        "document.querySelector('#run-view').innerText",
    );
    let (_, run) = srv.get(&format!("/api/runs/{id}"));
    assert_eq!(run["status"], "completed", "{run}");
    assert_eq!(run["scene"], "crossing");
    assert_eq!(run["sets"], json!(["stepping.increments=40", "contact.eps_t=2.0e3"]));
    assert_eq!(run["figures"]["increments"], 40);
    // the page's request is the API's: sent again, it is the same run
    let (s, again) = srv.post(
        "/api/runs",
        &json!({ "scene": "crossing", "set": ["stepping.increments=40", "contact.eps_t=2.0e3"] }),
    );
    assert_eq!((s, &again["id"], &again["existing"]), (200, &json!(id), &json!(true)));
    id
}

/// The table lists the run as completed, once; the form sent again shows the catalogued run
/// and says so.
fn listed_then_submitted_again(b: &mut Browser, srv: &Server, id: &str) {
    b.click("#run-view a[href='#/']");
    let row = format!("tr[data-id=\"{id}\"] .status");
    let listed = b.wait_for(
        &format!("document.querySelector('{row}') && document.querySelector('{row}').textContent"),
        20,
        "document.querySelector('#runs').innerText",
    );
    assert_eq!(listed, "completed");
    assert_eq!(b.eval("document.querySelectorAll('#runs tbody tr').length"), 1);
    assert_eq!(srv.get("/api/runs").1["total"], 1);
    b.click("#new-run");
    b.wait_for("!document.querySelector('#submit-view').hidden", 20, "location.hash");
    assert_eq!(
        b.eval("document.querySelector('#submit-error').hidden"),
        true,
        "no stale error"
    );
    picture(b, "service-submit.png");
    b.click("#submit-run");
    b.wait_for(
        "!document.querySelector('#run-view').hidden && document.querySelector('#submit-notice').textContent.includes('catalogued already')",
        20,
        "document.querySelector('#main').innerText",
    );
    assert_eq!(b.eval("location.hash"), json!(format!("#/runs/{id}")));
    assert_eq!(srv.get("/api/runs").1["total"], 1);
}
