//! `haphe demo`: the README's main command. A simulated hand explores a built-in scene —
//! a noisy blob beside a thin plate 0.1 mm thick, with friction — for a few seconds of
//! simulated time at 1 kHz; the servo loop renders it, and the demo prints what a haptics
//! user wants to know and draws the run.

use std::path::PathBuf;
use std::process::ExitCode;
use std::sync::Arc;
use std::time::Instant;

use haphe::DVec3;
use haphe::map::MapOptions;
use haphe::mesh::shapes::Catalog;
use haphe::scene::{Material, ObjectId, Pose, SceneObject};
use haphe::servo::{HandOptions, PathKind};

use crate::input::scene::{LoadedObject, shape_of};
use crate::session::{DeviceChoice, Session};

/// Arguments of `haphe demo`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// Triangles per built-in model.
    #[arg(long, default_value_t = 20_000)]
    triangles: usize,
    /// Seconds of simulated time (default 6; with --view, 60 seconds of wall-clock time).
    #[arg(long)]
    seconds: Option<f64>,
    /// Servo rate, Hz.
    #[arg(long, default_value_t = 1000.0)]
    rate: f64,
    /// Where to draw the run (PNG).
    #[arg(long, default_value = "haphe-demo.png", value_parser = crate::args::parse_png_path)]
    plot: PathBuf,
    /// Also write every tick to this CSV file.
    #[arg(long, value_name = "FILE.csv")]
    out: Option<PathBuf>,
    /// A quick run for tests: 2000-triangle models, 3 s.
    #[arg(long)]
    fast: bool,
    #[command(flatten)]
    tool: crate::args::ToolArgs,
    /// Run on the wall clock on a real-time thread instead of the virtual clock.
    #[arg(long)]
    realtime: bool,
    /// Show the demo live in the browser (`haphe view`): the hand explores on the wall
    /// clock while the page draws it; no summary or plot.
    #[arg(long)]
    view: bool,
    #[cfg(feature = "view")]
    #[command(flatten)]
    serve: crate::session::live::Serve,
}

/// Seconds of the demo without `--seconds`.
pub const DEMO_SECONDS: f64 = 6.0;

/// Runs the demo.
pub fn run(args: &Args) -> anyhow::Result<ExitCode> {
    #[cfg(not(feature = "view"))]
    if args.view {
        return Err(super::missing::missing("view", "demo --view"));
    }
    let triangles = if args.fast { 2_000 } else { args.triangles };
    let seconds = (args.seconds).unwrap_or_else(|| match args.fast {
        true => 3.0,
        false => default_seconds(args),
    });
    Catalog::check_triangles(triangles).map_err(|e| anyhow::anyhow!("--triangles: {e}"))?;
    let tool = args.tool.radius(None)?;
    let outputs: Vec<&std::path::Path> = std::iter::once(args.plot.as_path())
        .chain(args.out.as_deref())
        .collect();
    crate::output::check_outputs(&outputs, &[])?;
    let map = MapOptions::default();
    let started = Instant::now();
    let blob = Arc::new(shape_of(Catalog::Blob, triangles, &map)?);
    let plate = Arc::new(shape_of(Catalog::ThinPlate, triangles, &map)?);
    let objects = vec![
        LoadedObject {
            name: "blob".into(),
            object: SceneObject::new(
                ObjectId(0),
                blob,
                Pose::IDENTITY,
                Material::builder()
                    .stiffness(600.0)
                    .damping(1.0)
                    .friction(0.3, 0.2)
                    .build()?,
            ),
            motion: None,
        },
        LoadedObject {
            name: "thin-plate".into(),
            object: SceneObject::new(
                ObjectId(1),
                plate,
                Pose::from_translation(DVec3::new(0.25, 0.0, 0.0))?,
                Material::builder()
                    .stiffness(1000.0)
                    .damping(1.0)
                    .friction(0.5, 0.4)
                    .build()?,
            ),
            motion: None,
        },
    ];
    #[cfg(feature = "view")]
    if args.view {
        return crate::session::live::live(
            objects.into(),
            crate::session::live::ViewDevice::Hand(seconds),
            args.rate,
            &tool,
            "the demo (a blob and a 0.1 mm thin plate)",
            (&args.serve, None, None),
        );
    }
    let build_seconds = started.elapsed().as_secs_f64();
    let session = Session {
        title: format!(
            "haphe demo: a simulated hand explores a blob and a 0.1 mm thin plate for {seconds} s at {} Hz ({})",
            args.rate,
            if args.realtime {
                "wall clock"
            } else {
                "simulated time"
            }
        ),
        objects,
        effects: Vec::new(),
        build_seconds,
        device: DeviceChoice::Hand(PathKind::Explore, HandOptions::default()),
        rate_hz: args.rate,
        seconds: Some(seconds),
        realtime: args.realtime,
        spin_seconds: None,
        fifo: true,
        standby_core: None,
        clutch_button: None,
        presses: Vec::new(),
        deform: None,
        cut: None,
        seed: 3,
        max_force: haphe::scene::DEFAULT_MAX_FORCE_N,
        tool_radius: tool,
        out: args.out.clone(),
        plot: Some(args.plot.clone()),
    };
    session.run(&mut std::io::stdout().lock())?;
    let haphe = command_prefix();
    println!(
        "\nNext: `{haphe} simulate --shape torus --path slide --plot slide.png`, or your own mesh with `--mesh FILE` (see `{haphe} simulate --help`)."
    );
    Ok(ExitCode::SUCCESS)
}

/// Seconds without `--seconds`: the demo's, or with `--view` those of the view's hand.
fn default_seconds(args: &Args) -> f64 {
    #[cfg(feature = "view")]
    if args.view {
        return crate::session::live::HAND_SECONDS;
    }
    #[cfg(not(feature = "view"))]
    let _ = args.view;
    DEMO_SECONDS
}

/// How to run `haphe` from where the user is: after `cargo run` (which tells the program it
/// runs its package's name in `CARGO_PKG_NAME`) the binary is not on the `PATH`; an
/// installed `haphe` (`cargo install --path crates/haphe-cli`) is.
fn command_prefix() -> &'static str {
    if std::env::var_os("CARGO_PKG_NAME").is_some_and(|name| name == "haphe-cli") {
        "cargo run --release -p haphe-cli --"
    } else {
        "haphe"
    }
}
