//! Live progress as server-sent events: `status` (queued, running, and the end with its
//! status and failure kind) and `progress` (increment, load level, monitor force, cut-backs,
//! crossings) events, for one run (the stream ends with the run) or for all.

use super::api::{run_or_404, summary, Svc};
use super::catalogue::is_final;
use super::errors::ApiError;
use super::live::Event as LiveEvent;
use axum::extract::{Path, State};
use axum::response::sse::{Event, KeepAlive, Sse};
use futures_util::stream::{self, Stream, StreamExt};
use std::convert::Infallible;
use tokio::sync::broadcast::error::RecvError;
use tokio::sync::broadcast::Receiver;

fn sse(e: &LiveEvent) -> Event {
    Event::default()
        .event(e.event)
        .json_data(serde_json::json!({ "id": e.id, "data": e.data }))
        .unwrap_or_default()
}

/// Events from `rx` (of run `only`, or of all runs), ending after a final status of `only`.
fn follow(rx: Receiver<LiveEvent>, only: Option<String>) -> impl Stream<Item = Result<Event, Infallible>> {
    stream::unfold((rx, only, false), |(mut rx, only, done)| async move {
        if done {
            return None;
        }
        loop {
            match rx.recv().await {
                Ok(e) if e.event == "shutdown" => return None,
                Ok(e) if only.as_deref().is_none_or(|id| id == e.id) => {
                    let ended =
                        only.is_some() && e.event == "status" && e.data["status"].as_str().is_some_and(is_final);
                    return Some((Ok(sse(&e)), (rx, only, ended)));
                }
                Ok(_) | Err(RecvError::Lagged(_)) => continue,
                Err(RecvError::Closed) => return None,
            }
        }
    })
}

/// `GET /api/runs/{id}/events`: the run as it is now (a `status` event with its summary),
/// then its events until it ends.
pub async fn run_events(
    State(svc): Svc,
    Path(id): Path<String>,
) -> Result<Sse<impl Stream<Item = Result<Event, Infallible>>>, ApiError> {
    // subscribe before reading the state, so that nothing falls between the two
    let rx = svc.live.subscribe();
    let r = run_or_404(&svc, &id)?;
    let now = LiveEvent {
        event: "status",
        id: r.id.clone(),
        data: summary(&svc, &r),
    };
    let first = stream::once(async move { Ok(sse(&now)) });
    let rest = if is_final(&r.status) {
        follow(rx, Some(id)).take(0).boxed()
    } else {
        follow(rx, Some(id)).boxed()
    };
    Ok(Sse::new(first.chain(rest)).keep_alive(KeepAlive::default()))
}

/// `GET /api/events`: every run's events (the web page's table follows this).
pub async fn all_events(State(svc): Svc) -> Sse<impl Stream<Item = Result<Event, Infallible>>> {
    Sse::new(follow(svc.live.subscribe(), None)).keep_alive(KeepAlive::default())
}
