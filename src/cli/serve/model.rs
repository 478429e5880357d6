//! The model view's endpoints: `GET /api/runs/{id}/model` (the reference mesh and the index
//! of increments) and `GET /api/runs/{id}/model/{increment}` (one increment's positions and
//! contact points), both read from the run's recording with the library's reader
//! ([`Recording`]; JSON in [`super::model_json`]). A running run is read from its partial
//! recording (`runs/.ID.mcap.PID.N.part`), salvaged in memory as `contrail recover` does:
//! the increments of its complete chunks. Parsed recordings are kept in a small cache keyed
//! by file, length and modification time, so that playing a run parses it once.

use super::api::{run_or_404, Svc};
use super::conclude::part_files;
use super::errors::ApiError;
use super::model_json::{frame as frame_json, model as model_json};
use super::state::Service;
use axum::extract::{Path, Query, State};
use axum::http::StatusCode;
use axum::Json;
use contrail::analysis::recording::Recording;
use contrail::analysis::recover::recover;
use serde::Deserialize;
use serde_json::Value;
use std::path::PathBuf;
use std::sync::{Arc, Mutex};
use std::time::SystemTime;

/// Recordings parsed at most: the runs a few pages are playing.
const CACHED: usize = 4;

/// Which file, as it was when it was read.
#[derive(Debug, Clone, PartialEq)]
struct Key {
    path: PathBuf,
    len: u64,
    modified: Option<SystemTime>,
}

/// The recordings parsed last (newest last).
#[derive(Default)]
pub struct Recordings {
    entries: Mutex<Vec<(Key, Arc<Recording>)>>,
}

impl Recordings {
    fn get(&self, key: &Key) -> Option<Arc<Recording>> {
        let mut e = self.entries.lock().unwrap_or_else(|e| e.into_inner());
        let i = e.iter().position(|(k, _)| k == key)?;
        let hit = e.remove(i);
        let rec = hit.1.clone();
        e.push(hit);
        Some(rec)
    }

    fn put(&self, key: Key, rec: Arc<Recording>) {
        let mut e = self.entries.lock().unwrap_or_else(|e| e.into_inner());
        e.retain(|(k, _)| k.path != key.path);
        e.push((key, rec));
        let over = e.len().saturating_sub(CACHED);
        e.drain(..over);
    }
}

/// Where a run's recording is: its file once the run has ended, its partial file while it
/// runs (`true`: partial).
fn source(svc: &Service, id: &str, status: &str) -> Result<(PathBuf, bool), ApiError> {
    let done = svc.recording(id);
    if done.is_file() {
        return Ok((done, false));
    }
    if status == "running" {
        if let Some(part) = part_files(&svc.data, id).into_iter().next() {
            return Ok((part, true));
        }
    }
    Err(ApiError::new(
        StatusCode::CONFLICT,
        "no-recording",
        format!("run `{id}` has no recording yet ({status})"),
        "the model is shown once the run has started and written its first increments",
    ))
}

/// Parse a recording file; a partial one is salvaged in memory first (its complete chunks).
fn parse(path: &std::path::Path, partial: bool) -> Result<Recording, ApiError> {
    let name = path.display().to_string();
    let bytes = std::fs::read(path).map_err(ApiError::internal)?;
    if !partial {
        return Recording::from_bytes(&bytes, &name).map_err(unreadable);
    }
    let not_yet = |e: String| {
        ApiError::new(
            StatusCode::CONFLICT,
            "no-recording",
            format!("the run's recording has no complete increment yet: {e}"),
            "a running run's increments are readable once their chunk of the recording is written; try again shortly",
        )
    };
    let (out, _) = recover(&bytes, &name, std::io::Cursor::new(Vec::new())).map_err(|e| not_yet(e.to_string()))?;
    Recording::from_bytes(&out.into_inner(), &name).map_err(|e| not_yet(e.to_string()))
}

fn unreadable(e: contrail::analysis::recording::RecordingError) -> ApiError {
    ApiError::new(
        StatusCode::INTERNAL_SERVER_ERROR,
        "bad-recording",
        e.to_string(),
        "`contrail inspect` the recording on the service's machine",
    )
}

/// The run's recording, parsed (from the cache when the file has not changed), and whether
/// it is a running run's partial one.
async fn load(svc: &Arc<Service>, id: &str) -> Result<(Arc<Recording>, bool), ApiError> {
    let r = run_or_404(svc, id)?;
    let (path, partial) = source(svc, &r.id, &r.status)?;
    let meta = std::fs::metadata(&path).map_err(ApiError::internal)?;
    let key = Key {
        path: path.clone(),
        len: meta.len(),
        modified: meta.modified().ok(),
    };
    if let Some(rec) = svc.recordings.get(&key) {
        return Ok((rec, partial));
    }
    let rec = tokio::task::spawn_blocking(move || parse(&path, partial))
        .await
        .map_err(ApiError::internal)??;
    let rec = Arc::new(rec);
    svc.recordings.put(key, rec.clone());
    Ok((rec, partial))
}

#[derive(Debug, Deserialize)]
pub struct ModelQuery {
    /// `false`: the index of increments without the mesh (a page following a running run).
    #[serde(default)]
    mesh: Option<bool>,
    #[serde(default)]
    #[allow(dead_code)]
    token: Option<String>,
}

/// `GET /api/runs/{id}/model[?mesh=false]`.
pub async fn model(
    State(svc): Svc,
    Path(id): Path<String>,
    q: Result<Query<ModelQuery>, axum::extract::rejection::QueryRejection>,
) -> Result<Json<Value>, ApiError> {
    let Query(q) = q?;
    let (rec, partial) = load(&svc, &id).await?;
    let mut v = model_json(&rec, q.mesh.unwrap_or(true));
    v["id"] = Value::from(id);
    v["partial"] = Value::from(partial);
    Ok(Json(v))
}

/// The increment of a path: a number, or a 400 that says so.
fn increment_of(text: &str) -> Result<usize, ApiError> {
    text.parse().map_err(|_| {
        ApiError::bad(
            format!(
                "`{}` is not an increment number",
                text.chars().take(40).collect::<String>()
            ),
            "an increment is 0 (the reference configuration) or a number GET /api/runs/{id}/model lists in frames.increment",
        )
    })
}

/// `GET /api/runs/{id}/model/{increment}`.
pub async fn frame(State(svc): Svc, Path((id, increment)): Path<(String, String)>) -> Result<Json<Value>, ApiError> {
    let inc = increment_of(&increment)?;
    let (rec, partial) = load(&svc, &id).await?;
    let mut v = frame_json(&rec, inc).map_err(|e| {
        let hint = if partial {
            "the run is running: its later increments are not recorded yet"
        } else {
            "GET /api/runs/{id}/model lists the increments in frames.increment"
        };
        ApiError::new(StatusCode::NOT_FOUND, "no-increment", e.to_string(), hint)
    })?;
    v["id"] = Value::from(id);
    v["partial"] = Value::from(partial);
    Ok(Json(v))
}
