//! The web page: one HTML file, its scripts (the page's, and the model view's) and its style
//! sheet, embedded in the binary (no build step). The page reads the JSON API and follows
//! `/api/events`.

use axum::http::header;
use axum::response::IntoResponse;

/// The paths served without the token: the page's scripts and style sheet, the same for
/// every service and holding no data (the page itself, `/`, and the API need the token).
pub const PUBLIC: [&str; 4] = ["/app.js", "/model.js", "/model3d.js", "/style.css"];

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

/// The model view of a run's page (a canvas; `GET /api/runs/{id}/model`).
pub async fn model_script() -> impl IntoResponse {
    (
        [(header::CONTENT_TYPE, "text/javascript; charset=utf-8")],
        include_str!("web/model.js"),
    )
}

/// The model view's drawing of a 3D run (`Model3D`, called by model.js).
pub async fn model3d_script() -> impl IntoResponse {
    (
        [(header::CONTENT_TYPE, "text/javascript; charset=utf-8")],
        include_str!("web/model3d.js"),
    )
}

pub async fn style() -> impl IntoResponse {
    (
        [(header::CONTENT_TYPE, "text/css; charset=utf-8")],
        include_str!("web/style.css"),
    )
}
