//! Errors of the HTTP API: a status and a JSON body `{"error": {"code", "message", "hint"}}`
//! for every 4xx and 5xx, including axum's own rejections (bad JSON, too large a body).

use axum::extract::rejection::{JsonRejection, QueryRejection};
use axum::http::StatusCode;
use axum::response::{IntoResponse, Response};
use axum::Json;

#[derive(Debug)]
pub struct ApiError {
    pub status: StatusCode,
    pub code: &'static str,
    pub message: String,
    pub hint: String,
}

impl ApiError {
    pub fn new(
        status: StatusCode,
        code: &'static str,
        message: impl Into<String>,
        hint: impl Into<String>,
    ) -> ApiError {
        ApiError {
            status,
            code,
            message: message.into(),
            hint: hint.into(),
        }
    }

    pub fn bad(message: impl Into<String>, hint: impl Into<String>) -> ApiError {
        ApiError::new(StatusCode::BAD_REQUEST, "bad-request", message, hint)
    }

    pub fn not_found(what: impl Into<String>) -> ApiError {
        ApiError::new(
            StatusCode::NOT_FOUND,
            "not-found",
            what,
            "GET /api/runs lists the catalogued runs",
        )
    }

    pub fn internal(e: impl std::fmt::Display) -> ApiError {
        ApiError::new(
            StatusCode::INTERNAL_SERVER_ERROR,
            "internal",
            e.to_string(),
            "see the service's error output",
        )
    }
}

impl IntoResponse for ApiError {
    fn into_response(self) -> Response {
        let body = serde_json::json!({
            "error": { "code": self.code, "message": self.message, "hint": self.hint }
        });
        (self.status, Json(body)).into_response()
    }
}

impl From<rusqlite::Error> for ApiError {
    fn from(e: rusqlite::Error) -> ApiError {
        ApiError::new(
            StatusCode::SERVICE_UNAVAILABLE,
            "catalogue",
            format!("the catalogue cannot be read or written: {e}"),
            "check the data folder's disk space and permissions",
        )
    }
}

impl From<JsonRejection> for ApiError {
    fn from(r: JsonRejection) -> ApiError {
        let status = r.status();
        let code = if status == StatusCode::PAYLOAD_TOO_LARGE {
            "too-large"
        } else {
            "bad-json"
        };
        ApiError::new(
            status,
            code,
            r.body_text(),
            "send a JSON body (Content-Type: application/json) as schemas/openapi.json describes",
        )
    }
}

impl From<QueryRejection> for ApiError {
    fn from(r: QueryRejection) -> ApiError {
        ApiError::new(
            r.status(),
            "bad-query",
            r.body_text(),
            "see schemas/openapi.json for the query parameters",
        )
    }
}

/// A run id or file name as it may appear in a path: letters, digits, `.`, `_`, `-`, at most
/// 128, starting with a letter or digit (so never `..`, a hidden file, or a path).
pub fn check_id(id: &str) -> Result<(), ApiError> {
    let ok = !id.is_empty()
        && id.len() <= 128
        && id.chars().next().is_some_and(|c| c.is_ascii_alphanumeric())
        && id
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || matches!(c, '.' | '_' | '-'));
    if ok {
        Ok(())
    } else {
        Err(ApiError::bad(
            format!("`{}` is not a run id", id.chars().take(140).collect::<String>()),
            "a run id is letters, digits, `.`, `_` and `-` (e.g. crossing-0123456789ab)",
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn ids_that_could_leave_the_runs_folder_are_refused() {
        for bad in [
            "",
            "..",
            "../x",
            "a/b",
            ".hidden",
            "a\\b",
            "a b",
            "%2e%2e",
            &"x".repeat(129),
        ] {
            assert!(check_id(bad).is_err(), "{bad}");
        }
        for good in ["crossing-0123456789ab", "a", "strip-channel-00ff00ff00ff", "x.y_z"] {
            assert!(check_id(good).is_ok(), "{good}");
        }
    }
}
