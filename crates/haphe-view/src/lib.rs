//! A live 3D view of a haphe servo loop in the browser.
//!
//! [`ViewServer::start`] serves a page on `http://127.0.0.1:PORT/` that draws the scene's
//! meshes, the device point, the proxy (the tool: a sphere of its radius, or a marker for
//! a point), the line between them, the force arrow, the contact triangle and its normal,
//! the contact and sticking state, the tick rate and compute-time percentiles, a
//! force/penetration chart over the last seconds, and where the scene's force effects act
//! (a viscosity's box or object, a spring's anchor: [`EffectMark`]), and objects whose
//! shape changes (deformed, or cut) redrawn from their latest version
//! ([`ShapePublisher`]); orbit, pan and zoom with the mouse. The page and three.js are embedded in the binary: it works offline.
//!
//! Two sources:
//! - [`Source::Live`]: any [`Device`] (the [`MouseDevice`], whose
//!   point the page's pointer moves; the simulated hand; a real device) ticked by a
//!   [`ServoLoop`](haphe::servo::ServoLoop) on its real-time thread;
//! - [`Source::Replay`]: a recorded [`Trace`], played in the page with play, pause, speed
//!   and a scrubber.
//!
//! # Real-time
//!
//! The view never slows or blocks the servo thread: records leave it through the servo
//! loop's wait-free ring, tick timings through another ([`Timed`]), and pointer points
//! reach the [`MouseDevice`] through a wait-free triple buffer. A pump thread thins the
//! records to [`FRAME_RATE_HZ`] frames a second for the WebSockets.
//!
//! # Frames and units
//!
//! SI units; everything the page draws is in the world frame, z up.

mod effects;
mod feed;
mod live;
mod model;
mod mouse;
mod poses;
mod replay;
mod server;
mod timing;

pub use effects::{EffectMark, Place};
pub use feed::{
    MeshParts, REMESH_MAGIC, SHAPE_RATE_HZ, ShapeFeed, ShapeMessage, ShapePublisher,
    VERTICES_MAGIC, decode_shape, encode_mesh, encode_vertices, shape_channel,
};
pub use live::{
    FRAME_RATE_HZ, Frame, LiveRun, LiveSource, OtherTool, Published, RecordHook, STATS_WINDOW_S,
};
pub use model::{MESH_MAGIC, Model, ObjectInfo, ObjectMesh};
pub use mouse::{MOUSE_MAX_FORCE_N, MOUSE_VELOCITY_TAU_S, MouseDevice, MouseHandle};
pub use poses::{ObjectPose, POSE_VALUES, encode_poses, poses_at};
pub use replay::{ROW_VALUES, STATUS_NAMES, Trace, TraceError, TraceRow, encode_trace};
pub use timing::{TIMING_CAPACITY, Timed};

use std::net::{SocketAddr, TcpListener};
use std::sync::{Arc, Mutex};
use std::thread::JoinHandle;

use haphe::servo::{Device, ServoError};
use serde::Serialize;
use tokio::sync::watch;

use live::Live;
use server::Shared;

/// What the view shows.
pub enum Source {
    /// A servo loop running now; `mouse` is the handle of a [`MouseDevice`] when that is
    /// the device, so that the page's pointer moves it.
    Live {
        /// The servo's device, scene and options (boxed: it is large).
        source: Box<LiveSource>,
        /// The handle of the mouse device, when the device is one.
        mouse: Option<MouseHandle>,
    },
    /// A recorded trace.
    Replay(Trace),
}

/// Where and how to serve.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ViewOptions {
    /// TCP port on 127.0.0.1 (0: any free port).
    pub port: u16,
    /// A title for the page.
    pub title: String,
}

/// Why a view could not start.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum ViewError {
    /// The port could not be bound.
    #[error("cannot listen on 127.0.0.1:{port}: {source}")]
    Bind {
        /// The port.
        port: u16,
        /// Why.
        source: std::io::Error,
    },
    /// A thread or the async runtime could not be started.
    #[error("cannot start the server: {0}")]
    Start(std::io::Error),
    /// The servo could not start.
    #[error(transparent)]
    Servo(#[from] ServoError),
}

/// A running view: the server thread and, for a live source, the servo loop.
pub struct ViewServer {
    addr: SocketAddr,
    frames: watch::Receiver<Option<Published>>,
    closing: watch::Sender<bool>,
    server: Option<JoinHandle<()>>,
    live: Option<Live>,
}

/// The page's first request: what it shows.
#[derive(Serialize)]
struct Info<'a> {
    title: &'a str,
    mode: &'static str,
    objects: Vec<ObjectInfo>,
    bounds: Option<[[f64; 3]; 2]>,
    rate_hz: Option<f64>,
    /// The tool's radius, metres (0: a point): the page draws the proxy as a sphere of it.
    tool_radius: f64,
    device: Option<&'static str>,
    mouse: bool,
    statuses: [&'static str; STATUS_NAMES.len()],
    trace_rows: usize,
    row_values: usize,
    /// Ids of the objects moved by script, in the order of a replay's poses.
    moving: Vec<u32>,
    pose_values: usize,
    /// The scene's force effects, where they act.
    effects: &'a [EffectMark],
}

impl ViewServer {
    /// Binds the port, starts the servo loop (for a live source) and the server.
    ///
    /// # Errors
    /// [`ViewError`] when the port is taken, a thread cannot start or the device cannot be
    /// opened.
    pub fn start(
        model: Model,
        source: Source,
        options: &ViewOptions,
    ) -> Result<ViewServer, ViewError> {
        let listener =
            TcpListener::bind(("127.0.0.1", options.port)).map_err(|source| ViewError::Bind {
                port: options.port,
                source,
            })?;
        let addr = listener.local_addr().map_err(ViewError::Start)?;
        listener.set_nonblocking(true).map_err(ViewError::Start)?;
        let (frames_in, frames) = watch::channel(None);
        let (closing, closing_rx) = watch::channel(false);
        let bounds = model
            .bounds()
            .or_else(|| match &source {
                Source::Replay(trace) => trace.bounds(),
                Source::Live { .. } => None,
            })
            .map(|(lo, hi)| [lo.to_array(), hi.to_array()]);
        let mut tool_radius = model.tool_radius;
        let (live, mouse, trace, rate_hz, device, moving) = match source {
            Source::Live { source, mouse } => {
                let rate = source.options.rate_hz();
                tool_radius = source.options.proxy().tool_radius();
                let device = source.device.spec().name;
                let moving = source.motions.iter().map(|m| m.id.0).collect();
                let live = Live::start(*source, frames_in)?;
                (Some(live), mouse, None, Some(rate), Some(device), moving)
            }
            Source::Replay(trace) => {
                let moving = model.motions.iter().map(|m| m.id.0).collect();
                (None, None, Some(trace), None, None, moving)
            }
        };
        let info = Info {
            title: &options.title,
            mode: if live.is_some() { "live" } else { "replay" },
            objects: model.info(),
            bounds,
            rate_hz,
            tool_radius,
            device,
            mouse: mouse.is_some(),
            statuses: STATUS_NAMES,
            trace_rows: trace.as_ref().map_or(0, |t| t.rows.len()),
            row_values: ROW_VALUES,
            moving,
            pose_values: POSE_VALUES,
            effects: &model.effects,
        };
        let shared = Arc::new(Shared {
            info: serde_json::to_string(&info).unwrap_or_else(|_| "{}".into()),
            mesh: model.encode(),
            poses: trace
                .as_ref()
                .map(|t| encode_poses(&model.motions, t.rows.iter().map(|r| r.t))),
            trace: trace.map(|t| encode_trace(&t)),
            frames: frames.clone(),
            mouse: mouse.map(Mutex::new),
            feeds: model.feeds.clone(),
            closing: closing_rx.clone(),
        });
        let runtime = tokio::runtime::Builder::new_current_thread()
            .enable_all()
            .build()
            .map_err(ViewError::Start)?;
        let mut stop = closing_rx;
        let server = std::thread::Builder::new()
            .name("haphe-view-http".into())
            .spawn(move || {
                runtime.block_on(async move {
                    let Ok(listener) = tokio::net::TcpListener::from_std(listener) else {
                        return;
                    };
                    let app = server::router(shared);
                    let _ = axum::serve(listener, app)
                        .with_graceful_shutdown(async move {
                            let _ = stop.changed().await;
                        })
                        .await;
                });
            })
            .map_err(ViewError::Start)?;
        Ok(ViewServer {
            addr,
            frames,
            closing,
            server: Some(server),
            live,
        })
    }

    /// The address served.
    pub fn addr(&self) -> SocketAddr {
        self.addr
    }

    /// The page's address.
    pub fn url(&self) -> String {
        format!("http://{}/", self.addr)
    }

    /// The latest live frame (what the page was last sent or is about to be).
    pub fn latest(&self) -> Option<Frame> {
        self.frames.borrow().as_ref().map(|p| p.frame.clone())
    }

    /// Whether the live servo loop has ended (a replay never does).
    pub fn ended(&self) -> bool {
        self.latest().is_some_and(|f| f.ended)
    }

    /// Blocks until the process is interrupted (Ctrl-C, SIGINT, or SIGTERM on Unix), so
    /// that the caller can then [`stop`](Self::stop) the servo loop cleanly (zero force
    /// written). Returns at once when the signals cannot be watched.
    pub fn wait_for_interrupt(&self) {
        let Ok(runtime) = tokio::runtime::Builder::new_current_thread()
            .enable_all()
            .build()
        else {
            return;
        };
        runtime.block_on(async {
            #[cfg(unix)]
            {
                use tokio::signal::unix::{SignalKind, signal};
                if let Ok(mut term) = signal(SignalKind::terminate()) {
                    tokio::select! {
                        _ = tokio::signal::ctrl_c() => {}
                        _ = term.recv() => {}
                    }
                    return;
                }
            }
            let _ = tokio::signal::ctrl_c().await;
        });
    }

    /// Stops the servo loop (zero force, device closed) and the server; hands back the
    /// servo's run for a live view.
    ///
    /// # Errors
    /// [`ServoError::Panicked`] when the servo thread panicked.
    pub fn stop(mut self) -> Result<Option<LiveRun>, ServoError> {
        let run = self.live.take().map(Live::stop).transpose()?;
        let _ = self.closing.send(true);
        if let Some(server) = self.server.take() {
            let _ = server.join();
        }
        Ok(run)
    }
}

/// Opens `url` with the desktop's browser (`xdg-open`, or `open` on macOS) when one of them
/// is on the path; `false` when neither is (print the address instead).
pub fn open_in_browser(url: &str) -> bool {
    for opener in ["xdg-open", "open"] {
        let found = std::env::var_os("PATH").is_some_and(|paths| {
            std::env::split_paths(&paths).any(|dir| dir.join(opener).is_file())
        });
        if found
            && std::process::Command::new(opener)
                .arg(url)
                .stdin(std::process::Stdio::null())
                .stdout(std::process::Stdio::null())
                .stderr(std::process::Stdio::null())
                .spawn()
                .is_ok()
        {
            return true;
        }
    }
    false
}
