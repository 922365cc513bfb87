//! The HTTP and WebSocket server: the embedded page and three.js, the meshes and the trace
//! once per connection, then the live frames at display rate; pointer points from the page
//! go to the mouse device.

use std::sync::{Arc, Mutex};
use std::time::Duration;

use axum::Router;
use axum::extract::State;
use axum::extract::ws::{Message, WebSocket, WebSocketUpgrade};
use axum::http::{StatusCode, header};
use axum::response::{IntoResponse, Response};
use axum::routing::get;
use glam::DVec3;
use tokio::sync::watch;

use crate::feed::{SHAPE_RATE_HZ, ShapeFeed};
use crate::live::{FRAME_RATE_HZ, Published};
use crate::mouse::MouseHandle;

/// Everything the handlers share.
pub(crate) struct Shared {
    pub(crate) info: String,
    pub(crate) mesh: Vec<u8>,
    pub(crate) trace: Option<Vec<u8>>,
    /// The replay's poses of the moving objects, per row (see `encode_poses`).
    pub(crate) poses: Option<Vec<u8>>,
    pub(crate) frames: watch::Receiver<Option<Published>>,
    pub(crate) mouse: Option<Mutex<MouseHandle>>,
    pub(crate) closing: watch::Receiver<bool>,
    /// The versions of objects whose shape changes (deformed or cut).
    pub(crate) feeds: Vec<ShapeFeed>,
}

macro_rules! asset {
    ($path:literal) => {
        include_bytes!(concat!(env!("CARGO_MANIFEST_DIR"), "/assets/", $path)).as_slice()
    };
}

/// The page and its scripts, embedded in the binary.
const ASSETS: [(&str, &str, &[u8]); 6] = [
    ("/", "text/html; charset=utf-8", asset!("index.html")),
    ("/view.js", "text/javascript", asset!("view.js")),
    ("/chart.js", "text/javascript", asset!("chart.js")),
    (
        "/vendor/three.module.js",
        "text/javascript",
        asset!("vendor/three.module.js"),
    ),
    (
        "/vendor/three.core.js",
        "text/javascript",
        asset!("vendor/three.core.js"),
    ),
    (
        "/vendor/OrbitControls.js",
        "text/javascript",
        asset!("vendor/OrbitControls.js"),
    ),
];

/// The router of a view.
pub(crate) fn router(shared: Arc<Shared>) -> Router {
    let mut app = Router::new();
    for (path, mime, body) in ASSETS {
        app = app.route(
            path,
            get(move || async move { ([(header::CONTENT_TYPE, mime)], body) }),
        );
    }
    app.route("/info", get(info))
        .route("/mesh.bin", get(mesh))
        .route("/trace.bin", get(trace))
        .route("/poses.bin", get(poses))
        .route("/ws", get(ws))
        .with_state(shared)
}

async fn info(State(s): State<Arc<Shared>>) -> Response {
    ([(header::CONTENT_TYPE, "application/json")], s.info.clone()).into_response()
}

async fn mesh(State(s): State<Arc<Shared>>) -> Response {
    (
        [(header::CONTENT_TYPE, "application/octet-stream")],
        s.mesh.clone(),
    )
        .into_response()
}

async fn trace(State(s): State<Arc<Shared>>) -> Response {
    replay_part(s.trace.as_ref())
}

async fn poses(State(s): State<Arc<Shared>>) -> Response {
    replay_part(s.poses.as_ref())
}

/// A binary part of a replay, or 404 for a live view.
fn replay_part(part: Option<&Vec<u8>>) -> Response {
    match part {
        Some(t) => (
            [(header::CONTENT_TYPE, "application/octet-stream")],
            t.clone(),
        )
            .into_response(),
        None => (StatusCode::NOT_FOUND, "no trace: this view is live").into_response(),
    }
}

async fn ws(State(s): State<Arc<Shared>>, upgrade: WebSocketUpgrade) -> Response {
    upgrade.on_upgrade(move |socket| stream(socket, s))
}

/// One connection: the latest frame at display rate (when there is a new one), the
/// latest version of each changing object (its vertices, or its whole mesh) at most at
/// [`SHAPE_RATE_HZ`] (when its version changed; the first at once), and the pointer's
/// points to the mouse device.
async fn stream(mut socket: WebSocket, s: Arc<Shared>) {
    let mut frames = s.frames.clone();
    let mut closing = s.closing.clone();
    let mut every = tokio::time::interval(Duration::from_secs_f64(1.0 / FRAME_RATE_HZ));
    every.set_missed_tick_behavior(tokio::time::MissedTickBehavior::Skip);
    let mut shapes: Vec<watch::Receiver<_>> = s
        .feeds
        .iter()
        .map(|f| {
            let mut rx = f.rx.clone();
            rx.mark_changed();
            rx
        })
        .collect();
    let mut every_shape = tokio::time::interval(Duration::from_secs_f64(1.0 / SHAPE_RATE_HZ));
    every_shape.set_missed_tick_behavior(tokio::time::MissedTickBehavior::Skip);
    // The pump drops its sender when the servo loop ends, right after publishing the last
    // frame: that frame is still sent, once.
    let mut last_sent = false;
    loop {
        tokio::select! {
            _ = every.tick() => {
                let closed = frames.has_changed().is_err();
                if !(frames.has_changed().unwrap_or(false) || (closed && !last_sent)) {
                    continue;
                }
                last_sent |= closed;
                let json = frames.borrow_and_update().as_ref().map(|p| Arc::clone(&p.json));
                if let Some(json) = json
                    && socket.send(Message::Text(json.as_ref().into())).await.is_err()
                {
                    return;
                }
            }
            _ = every_shape.tick(), if !shapes.is_empty() => {
                for rx in &mut shapes {
                    if !rx.has_changed().unwrap_or(false) {
                        continue;
                    }
                    let bytes = rx.borrow_and_update().clone();
                    if let Some(bytes) = bytes
                        && socket.send(Message::Binary(bytes.to_vec().into())).await.is_err()
                    {
                        return;
                    }
                }
            }
            message = socket.recv() => match message {
                Some(Ok(Message::Text(text))) => pointer(&s, text.as_str()),
                Some(Ok(_)) => {}
                Some(Err(_)) | None => return,
            },
            _ = closing.changed() => {
                let _ = socket.send(Message::Close(None)).await;
                return;
            }
        }
    }
}

/// A message from the page: `{"hip":[x,y,z]}`, the device point it asks for (metres, world
/// frame). Anything else is ignored.
fn pointer(s: &Shared, text: &str) {
    #[derive(serde::Deserialize)]
    struct Pointer {
        hip: [f64; 3],
    }
    let Some(mouse) = &s.mouse else { return };
    if let Ok(p) = serde_json::from_str::<Pointer>(text)
        && let Ok(mut m) = mouse.lock()
    {
        m.set(DVec3::from_array(p.hip));
    }
}
