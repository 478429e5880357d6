//! What a run leaves: its recording (served with HTTP range requests, so Python's `mcap`
//! and Foxglove read it remotely), its load–displacement curve (JSON, CSV, SVG with the
//! crossings marked), its scene, and the diff of two runs (`contrail diff`'s report).

use super::api::{run_or_404, Svc};
use super::catalogue::RunRow;
use super::errors::{check_id, ApiError};
use super::state::Service;
use axum::extract::{Path, Query, Request, State};
use axum::http::{header, StatusCode};
use axum::response::{IntoResponse, Response};
use axum::Json;
use contrail::analysis::diff::{diff as compare, Align};
use contrail::analysis::plot::{line_chart, Series};
use contrail::analysis::recording::Recording;
use serde::Deserialize;
use serde_json::{json, Value};
use std::fmt::Write;
use tower::ServiceExt;

/// `GET /api/runs/{id}/recording`: the MCAP file, with `Range`, `If-Range` and
/// `If-Modified-Since` handled by tower-http's `ServeFile`.
pub async fn recording(State(svc): Svc, Path(id): Path<String>, req: Request) -> Result<Response, ApiError> {
    let r = run_or_404(&svc, &id)?;
    let path = svc.recording(&r.id);
    if !path.is_file() {
        return Err(ApiError::new(
            StatusCode::CONFLICT,
            "no-recording",
            format!("run `{id}` has no recording ({})", r.status),
            "a recording is in place when the run has ended; follow GET /api/runs/{id}/events",
        ));
    }
    let mut res = tower_http::services::ServeFile::new_with_mime(&path, &"application/octet-stream".parse().unwrap())
        .oneshot(req)
        .await
        .map_err(ApiError::internal)?
        .map(axum::body::Body::new);
    if let Ok(v) = format!("attachment; filename=\"{}.mcap\"", r.id).parse() {
        res.headers_mut().insert(header::CONTENT_DISPOSITION, v);
    }
    Ok(res)
}

/// A run's curve: `[t, displacement, force]` per converged increment, and the points with
/// crossings. Live for a running run, from its outcome once it has ended.
pub fn curve_of(svc: &Service, r: &RunRow) -> (Vec<[f64; 3]>, Vec<usize>) {
    if let Some(l) = svc.live.get(&r.id) {
        return (l.curve, l.crossing_at);
    }
    let Some(o) = r.outcome.as_deref().and_then(|o| serde_json::from_str::<Value>(o).ok()) else {
        return (Vec::new(), Vec::new());
    };
    let curve: Vec<[f64; 3]> = serde_json::from_value(o["data"]["curve"].clone()).unwrap_or_default();
    let mut at: Vec<usize> = o["data"]["crossings"]
        .as_array()
        .map(|cs| {
            cs.iter()
                .filter_map(|c| c["t"].as_f64())
                .filter_map(|t| curve.iter().position(|p| p[0] == t))
                .collect()
        })
        .unwrap_or_default();
    at.dedup();
    (curve, at)
}

pub async fn curve(State(svc): Svc, Path(id): Path<String>) -> Result<Json<Value>, ApiError> {
    let r = run_or_404(&svc, &id)?;
    let (points, crossings) = curve_of(&svc, &r);
    Ok(Json(
        json!({ "id": r.id, "status": r.status, "points": points, "crossings": crossings }),
    ))
}

pub async fn curve_csv(State(svc): Svc, Path(id): Path<String>) -> Result<Response, ApiError> {
    let r = run_or_404(&svc, &id)?;
    let (points, crossings) = curve_of(&svc, &r);
    let mut o = String::from("t,displacement,force,crossing\n");
    for (i, p) in points.iter().enumerate() {
        let _ = writeln!(o, "{},{},{},{}", p[0], p[1], p[2], u8::from(crossings.contains(&i)));
    }
    Ok(([(header::CONTENT_TYPE, "text/csv; charset=utf-8")], o).into_response())
}

pub async fn curve_svg(State(svc): Svc, Path(id): Path<String>) -> Result<Response, ApiError> {
    let r = run_or_404(&svc, &id)?;
    let (points, crossings) = curve_of(&svc, &r);
    let tmp = svc.data.join("tmp");
    let file = tmp.join(format!("{}-{}.svg", r.id, std::process::id()));
    let title = format!("{} ({})", r.id, r.status);
    let svg = tokio::task::spawn_blocking(move || {
        std::fs::create_dir_all(&tmp).map_err(ApiError::internal)?;
        let series = Series {
            label: "force".into(),
            points: points.iter().map(|p| (p[1], p[2])).collect(),
            markers: crossings
                .iter()
                .filter_map(|&i| points.get(i))
                .map(|p| (p[1], p[2]))
                .collect(),
        };
        line_chart(&file, &title, "displacement", "force", &[series]).map_err(ApiError::internal)?;
        let text = std::fs::read_to_string(&file).map_err(ApiError::internal);
        let _ = std::fs::remove_file(&file);
        text
    })
    .await
    .map_err(ApiError::internal)??;
    Ok(([(header::CONTENT_TYPE, "image/svg+xml")], svg).into_response())
}

/// `GET /api/runs/{id}/scene`: the scene text the run was made from (before overrides).
pub async fn scene(State(svc): Svc, Path(id): Path<String>) -> Result<Response, ApiError> {
    let r = run_or_404(&svc, &id)?;
    let text = match contrail::scene::builtin::find(&r.scene_ref) {
        Some(b) => b.text.to_string(),
        None => std::fs::read_to_string(svc.data.join(&r.scene_ref)).map_err(ApiError::internal)?,
    };
    Ok(([(header::CONTENT_TYPE, "text/plain; charset=utf-8")], text).into_response())
}

#[derive(Debug, Deserialize)]
pub struct DiffQuery {
    a: String,
    b: String,
    #[serde(default)]
    align: Option<String>,
    #[serde(default)]
    tol: Option<f64>,
    #[serde(default)]
    #[allow(dead_code)]
    token: Option<String>,
}

/// `GET /api/diff?a=ID&b=ID[&align=increment|load][&tol=1e-6]`: `contrail diff --json`.
pub async fn diff(
    State(svc): Svc,
    q: Result<Query<DiffQuery>, axum::extract::rejection::QueryRejection>,
) -> Result<Json<Value>, ApiError> {
    let Query(q) = q?;
    check_id(&q.a)?;
    check_id(&q.b)?;
    let align = match q.align.as_deref() {
        None | Some("increment") => Align::Increment,
        Some("load") => Align::Load,
        Some(other) => return Err(ApiError::bad(format!("align `{other}`"), "align is increment or load")),
    };
    let tol = q.tol.unwrap_or(1e-6);
    if !(tol.is_finite() && tol >= 0.0) {
        return Err(ApiError::bad("tol must be a non-negative number", "e.g. tol=1e-6"));
    }
    let paths = [&q.a, &q.b].map(|id| {
        run_or_404(&svc, id).and_then(|_| {
            let p = svc.recording(id);
            if p.is_file() {
                Ok(p)
            } else {
                Err(ApiError::new(
                    StatusCode::CONFLICT,
                    "no-recording",
                    format!("run `{id}` has no recording yet"),
                    "compare runs that have ended",
                ))
            }
        })
    });
    let [pa, pb] = paths;
    let (pa, pb) = (pa?, pb?);
    let report = tokio::task::spawn_blocking(move || -> Result<Value, ApiError> {
        let ra = Recording::open(&pa).map_err(|e| ApiError::bad(e.to_string(), ""))?;
        let rb = Recording::open(&pb).map_err(|e| ApiError::bad(e.to_string(), ""))?;
        let d =
            compare(&ra, &rb, align, tol).map_err(|e| ApiError::bad(e.to_string(), "compare two runs of one scene"))?;
        serde_json::to_value(d).map_err(ApiError::internal)
    })
    .await
    .map_err(ApiError::internal)??;
    Ok(Json(report))
}
