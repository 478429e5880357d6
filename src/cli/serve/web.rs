//! The web page: one HTML file, its script and its style sheet, embedded in the binary (no
//! build step). The page reads the JSON API and follows `/api/events`.

use axum::http::header;
use axum::response::IntoResponse;

/// The paths served without the token: the page's script and style sheet, the same for
/// every service and holding no data (the page itself, `/`, and the API need the token).
pub const PUBLIC: [&str; 2] = ["/app.js", "/style.css"];

pub async fn index() -> impl IntoResponse {
    (
        [(header::CONTENT_TYPE, "text/html; charset=utf-8")],
        include_str!("web/index.html"),
    )
}

pub async fn script() -> impl IntoResponse {
    (
        [(header::CONTENT_TYPE, "text/javascript; charset=utf-8")],
        include_str!("web/app.js"),
    )
}

pub async fn style() -> impl IntoResponse {
    (
        [(header::CONTENT_TYPE, "text/css; charset=utf-8")],
        include_str!("web/style.css"),
    )
}
