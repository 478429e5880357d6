//! The HTTP API's router (every route is listed in [`routes`]'s table, which a test holds
//! against `schemas/openapi.json`), the token check, and the run handlers: submit, list,
//! detail, cancel.

use super::catalogue::{is_final, Filter, RunRow, SORTS, STATUSES};
use super::errors::{check_id, ApiError};
use super::state::Service;
use super::submit::{catalogue, check_run, check_sweep, RunRequest, SweepRequest};
use super::{events, files, model, web};
use axum::extract::{Path, Query, Request, State};
use axum::handler::Handler;
use axum::http::StatusCode;
use axum::middleware::Next;
use axum::response::{IntoResponse, Response};
use axum::{Json, Router};
use serde_json::{json, Value};
use std::collections::HashMap;
use std::sync::Arc;

pub type Svc = State<Arc<Service>>;

/// The router and the table of its (method, path) pairs.
pub struct Routes {
    router: Router<Arc<Service>>,
    pub table: Vec<(&'static str, &'static str)>,
}

impl Routes {
    fn get<H: Handler<T, Arc<Service>>, T: 'static>(mut self, path: &'static str, h: H) -> Routes {
        self.router = self.router.route(path, axum::routing::get(h));
        self.table.push(("get", path));
        self
    }
    fn post<H: Handler<T, Arc<Service>>, T: 'static>(mut self, path: &'static str, h: H) -> Routes {
        self.router = self.router.route(path, axum::routing::post(h));
        self.table.push(("post", path));
        self
    }
}

/// Every route of the service.
pub fn routes() -> Routes {
    Routes {
        router: Router::new(),
        table: Vec::new(),
    }
    .get("/", web::index)
    .get("/app.js", web::script)
    .get("/model.js", web::model_script)
    .get("/model3d.js", web::model3d_script)
    .get("/style.css", web::style)
    .get("/api/health", health)
    .get("/api/scenes", scenes)
    .get("/api/runs", list)
    .post("/api/runs", submit)
    .post("/api/sweeps", submit_sweep)
    .get("/api/runs/{id}", detail)
    .post("/api/runs/{id}/cancel", cancel)
    .get("/api/runs/{id}/events", events::run_events)
    .get("/api/events", events::all_events)
    .get("/api/runs/{id}/recording", files::recording)
    .get("/api/runs/{id}/curve", files::curve)
    .get("/api/runs/{id}/curve.csv", files::curve_csv)
    .get("/api/runs/{id}/curve.svg", files::curve_svg)
    .get("/api/runs/{id}/scene", files::scene)
    .get("/api/runs/{id}/model", model::model)
    .get("/api/runs/{id}/model/{increment}", model::frame)
    .get("/api/diff", files::diff)
}

/// The service's app: routes, limits, token check, JSON errors for unknown routes.
pub fn app(svc: Arc<Service>) -> Router {
    let limit = svc.limits.body_bytes;
    routes()
        .router
        .fallback(not_found)
        .method_not_allowed_fallback(not_allowed)
        .layer(axum::extract::DefaultBodyLimit::max(limit))
        .layer(axum::middleware::from_fn_with_state(svc.clone(), refuse_oversized))
        .layer(axum::middleware::from_fn_with_state(svc.clone(), token_check))
        .with_state(svc)
}

async fn not_found() -> ApiError {
    ApiError::new(
        StatusCode::NOT_FOUND,
        "not-found",
        "no such route",
        "schemas/openapi.json lists the routes",
    )
}

async fn not_allowed() -> ApiError {
    ApiError::new(
        StatusCode::METHOD_NOT_ALLOWED,
        "method-not-allowed",
        "this route does not take that method",
        "schemas/openapi.json lists the routes and their methods",
    )
}

fn same(a: &[u8], b: &[u8]) -> bool {
    a.len() == b.len() && a.iter().zip(b).fold(0u8, |acc, (x, y)| acc | (x ^ y)) == 0
}

/// Bodies read to their end before an oversized request is refused, at most this many
/// times the body limit: a client still writing its body then reads the 413 instead of
/// a broken pipe. Larger bodies are refused at once and their connection closed.
const DRAIN_FACTOR: u64 = 16;

/// A request whose declared length exceeds the body limit gets a JSON 413 after its body is
/// read and dropped (up to [`DRAIN_FACTOR`] times the limit).
async fn refuse_oversized(State(svc): Svc, req: Request, next: Next) -> Response {
    use futures_util::StreamExt;
    let limit = svc.limits.body_bytes as u64;
    let declared = req
        .headers()
        .get(axum::http::header::CONTENT_LENGTH)
        .and_then(|v| v.to_str().ok())
        .and_then(|v| v.parse::<u64>().ok());
    let Some(len) = declared.filter(|&n| n > limit) else {
        return next.run(req).await;
    };
    if len <= limit.saturating_mul(DRAIN_FACTOR) {
        let mut body = req.into_body().into_data_stream();
        while let Some(Ok(_)) = body.next().await {}
    }
    ApiError::new(
        StatusCode::PAYLOAD_TOO_LARGE,
        "too-large",
        format!("the request body is {len} bytes; at most {limit} are accepted"),
        "use a generated mesh rather than listing nodes",
    )
    .into_response()
}

/// With `--token`, every request carries it: `Authorization: Bearer TOKEN`, or `?token=`
/// (for links and the browser's event streams), but for the page's script and style sheet
/// ([`web::PUBLIC`]), which the page (`/?token=`) loads without the token.
async fn token_check(State(svc): Svc, req: Request, next: Next) -> Response {
    let Some(token) = &svc.token else {
        return next.run(req).await;
    };
    if web::PUBLIC.contains(&req.uri().path()) {
        return next.run(req).await;
    }
    let header = req
        .headers()
        .get(axum::http::header::AUTHORIZATION)
        .and_then(|v| v.to_str().ok())
        .and_then(|v| v.strip_prefix("Bearer "));
    let query = req
        .uri()
        .query()
        .unwrap_or("")
        .split('&')
        .find_map(|kv| kv.strip_prefix("token="));
    let ok = header.or(query).is_some_and(|t| same(t.as_bytes(), token.as_bytes()));
    if ok {
        next.run(req).await
    } else {
        ApiError::new(
            StatusCode::UNAUTHORIZED,
            "unauthorized",
            "this service needs its token",
            "send `Authorization: Bearer TOKEN` (contrail submit --token TOKEN), or add ?token=TOKEN to the page's address",
        )
        .into_response()
    }
}

async fn health(State(svc): Svc) -> Result<Json<Value>, ApiError> {
    Ok(Json(json!({
        "status": "ok",
        "version": contrail::VERSION,
        "backend": svc.backend.name(),
        "workers": svc.workers,
        "threads_per_run": svc.threads_per_run,
        "runs": svc.catalogue.counts()?,
    })))
}

async fn scenes() -> Json<Value> {
    let list: Vec<Value> = contrail::scene::builtin::BUILTINS
        .iter()
        .map(|b| json!({ "name": b.name, "description": contrail::scene::builtin::description(b) }))
        .collect();
    Json(json!({ "scenes": list }))
}

/// Progress of a running run: live when the run is solved here, else as last catalogued.
fn progress(svc: &Service, r: &RunRow) -> Value {
    let line = svc
        .live
        .get(&r.id)
        .and_then(|l| l.progress)
        .and_then(|p| serde_json::to_value(p).ok())
        .or_else(|| r.progress.as_deref().and_then(|p| serde_json::from_str(p).ok()));
    let Some(mut line) = line else { return Value::Null };
    let t = line["t"].as_f64().unwrap_or(0.0);
    let end = line["t_end"].as_f64().unwrap_or(0.0);
    line["fraction"] = json!(if end > 0.0 { (t / end).clamp(0.0, 1.0) } else { 0.0 });
    line
}

/// A run as the list shows it.
pub fn summary(svc: &Service, r: &RunRow) -> Value {
    let mut v = serde_json::to_value(r).unwrap_or_default();
    v["progress"] = if r.status == "running" {
        progress(svc, r)
    } else {
        Value::Null
    };
    let figures = r
        .outcome
        .as_deref()
        .and_then(|o| serde_json::from_str::<Value>(o).ok())
        .map(|o| o["figures"].clone());
    v["figures"] = figures.unwrap_or(Value::Null);
    v
}

/// Everything about a run.
pub fn full(svc: &Service, r: &RunRow) -> Value {
    let mut v = summary(svc, r);
    let parse = |s: &Option<String>| s.as_deref().and_then(|x| serde_json::from_str::<Value>(x).ok());
    let mut outcome = parse(&r.outcome).unwrap_or(Value::Null);
    if let Some(o) = outcome.as_object_mut() {
        o.remove("data");
    }
    v["outcome"] = outcome;
    v["culprit"] = parse(&r.culprit).unwrap_or(json!([]));
    v["metrics"] = parse(&r.metrics).unwrap_or(Value::Null);
    v["log"] = json!(r.log);
    let has_recording = svc.recording(&r.id).is_file();
    let base = format!("/api/runs/{}", r.id);
    v["files"] = json!({
        "recording": has_recording.then(|| format!("{base}/recording")),
        "curve_csv": format!("{base}/curve.csv"),
        "curve_svg": format!("{base}/curve.svg"),
        "scene": format!("{base}/scene"),
    });
    v["commands"] = json!({
        "fetch": format!("contrail fetch {}", r.id),
        "rerun": format!("contrail replay {}.mcap --rerun-spawn", r.id),
        "inspect": format!("contrail inspect {}.mcap", r.id),
        "local": format!("contrail replay {} --rerun-spawn", svc.recording(&r.id).display()),
    });
    v
}

fn get_run(svc: &Service, id: &str) -> Result<RunRow, ApiError> {
    check_id(id)?;
    svc.catalogue
        .get(id)?
        .ok_or_else(|| ApiError::not_found(format!("no run `{id}` in the catalogue")))
}

pub fn run_or_404(svc: &Service, id: &str) -> Result<RunRow, ApiError> {
    get_run(svc, id)
}

async fn detail(State(svc): Svc, Path(id): Path<String>) -> Result<Json<Value>, ApiError> {
    let r = get_run(&svc, &id)?;
    Ok(Json(full(&svc, &r)))
}

fn parse_filter(q: &HashMap<String, String>) -> Result<Filter, ApiError> {
    let mut f = Filter {
        limit: 100,
        sort: "seq".into(),
        ..Filter::default()
    };
    for (k, v) in q {
        match k.as_str() {
            "scene" => f.scene = Some(v.clone()),
            "status" if STATUSES.contains(&v.as_str()) => f.status = Some(v.clone()),
            "status" => {
                return Err(ApiError::bad(
                    format!("unknown status `{v}`"),
                    format!("statuses: {}", STATUSES.join(", ")),
                ))
            }
            "failure_kind" => f.failure_kind = Some(v.clone()),
            "sweep" => f.sweep = Some(v.clone()),
            "sort" if SORTS.contains(&v.as_str()) => f.sort = v.clone(),
            "sort" => {
                return Err(ApiError::bad(
                    format!("cannot sort by `{v}`"),
                    format!("sort by: {}", SORTS.join(", ")),
                ))
            }
            "order" => f.descending = v == "desc",
            "limit" => {
                f.limit = v
                    .parse::<usize>()
                    .map_err(|_| ApiError::bad("limit is a number", ""))?
                    .min(1000)
            }
            "offset" => f.offset = v.parse().map_err(|_| ApiError::bad("offset is a number", ""))?,
            "token" => {}
            k if k.starts_with("param.") => f.params.push((k["param.".len()..].to_string(), v.clone())),
            other => {
                return Err(ApiError::bad(
                    format!("unknown filter `{other}`"),
                    "filters: scene, status, failure_kind, sweep, param.KEY, sort, order, limit, offset",
                ))
            }
        }
    }
    Ok(f)
}

async fn list(
    State(svc): Svc,
    q: Result<Query<HashMap<String, String>>, axum::extract::rejection::QueryRejection>,
) -> Result<Json<Value>, ApiError> {
    let Query(q) = q?;
    let f = parse_filter(&q)?;
    let (rows, total) = svc.catalogue.list(&f)?;
    let runs: Vec<Value> = rows.iter().map(|r| summary(&svc, r)).collect();
    Ok(Json(json!({ "total": total, "runs": runs })))
}

type JsonBody<T> = Result<Json<T>, axum::extract::rejection::JsonRejection>;

async fn submit(State(svc): Svc, body: JsonBody<RunRequest>) -> Result<Response, ApiError> {
    let Json(req) = body?;
    let c = check_run(&svc, &req)?;
    let queued = catalogue(&svc, &c, None, req.rerun, req.positions_every.unwrap_or(1))?;
    let r = get_run(&svc, &c.id)?;
    let mut v = full(&svc, &r);
    v["existing"] = json!(!queued);
    let code = if queued { StatusCode::CREATED } else { StatusCode::OK };
    Ok((code, Json(v)).into_response())
}

async fn submit_sweep(State(svc): Svc, body: JsonBody<SweepRequest>) -> Result<Response, ApiError> {
    let Json(req) = body?;
    let (name, runs) = check_sweep(&svc, &req)?;
    let mut queued = 0;
    for c in &runs {
        if catalogue(&svc, c, Some(&name), req.rerun, req.positions_every.unwrap_or(1))? {
            queued += 1;
        }
    }
    let ids: Vec<&str> = runs.iter().map(|c| c.id.as_str()).collect();
    let body = json!({ "plan": name, "runs": ids, "queued": queued, "existing": runs.len() - queued });
    Ok((StatusCode::CREATED, Json(body)).into_response())
}

async fn cancel(State(svc): Svc, Path(id): Path<String>) -> Result<Json<Value>, ApiError> {
    let r = get_run(&svc, &id)?;
    if r.status == "queued" && svc.catalogue.cancel_queued(&id)? {
        svc.live.send("status", &id, json!({ "status": "cancelled" }));
    } else if r.status == "running" {
        match svc.live.request_cancel(&id) {
            Some(Some(pid)) => super::worker::interrupt(pid),
            Some(None) => {}
            None => {
                return Err(ApiError::new(
                    StatusCode::CONFLICT,
                    "not-live",
                    format!("run `{id}` is not solved by this service process"),
                    "it was left running by a service that stopped; it is marked interrupted on restart",
                ))
            }
        }
    } else if is_final(&r.status) {
        return Err(ApiError::new(
            StatusCode::CONFLICT,
            "finished",
            format!("run `{id}` has ended ({})", r.status),
            "submit it again with rerun=true to solve it again",
        ));
    }
    let r = get_run(&svc, &id)?;
    Ok(Json(full(&svc, &r)))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The routes the server has are the paths and methods of schemas/openapi.json.
    #[test]
    fn the_routes_are_the_openapi_files_paths() {
        let text = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/schemas/openapi.json")).unwrap();
        let doc: Value = serde_json::from_str(&text).unwrap();
        let mut documented: Vec<(String, String)> = Vec::new();
        for (path, ops) in doc["paths"].as_object().unwrap() {
            for method in ops.as_object().unwrap().keys() {
                documented.push((method.clone(), path.clone()));
            }
        }
        let mut served: Vec<(String, String)> = routes()
            .table
            .iter()
            .map(|(m, p)| (m.to_string(), p.to_string()))
            .collect();
        documented.sort();
        served.sort();
        assert_eq!(served, documented);
    }
}
