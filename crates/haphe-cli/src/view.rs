//! `haphe view`: the live 3D view in the browser — a mesh, a built-in shape or a scene
//! file touched with the mouse (or the simulated hand), or a recorded trace replayed.

use std::path::PathBuf;
use std::process::ExitCode;
use std::sync::Arc;

use anyhow::{anyhow, bail};
use haphe::DVec3;
use haphe::map::MapOptions;
use haphe::mesh::Units;
use haphe::mesh::shapes::Catalog;
use haphe::scene::{ObjectId, Pose, Scene, SceneObject};
use haphe::servo::{
    Device, DeviceMapping, HandOptions, ObjectMotion, PathKind, RealtimeOptions, ServoOptions,
    SimulatedHand, scene_bounds, scripted_path,
};
use haphe_view::{LiveSource, Model, MouseDevice, Source, Trace, ViewOptions, ViewServer};

use crate::scene::{LoadedObject, load_scene, mesh_shape, shape_of};

/// Port the view serves on by default.
pub const DEFAULT_PORT: u16 = 8417;

/// Length of a `--device hand` run, seconds, unless `--seconds` says.
pub const HAND_SECONDS: f64 = 60.0;

/// Arguments of `haphe view`.
#[derive(clap::Args, Debug)]
#[command(group(clap::ArgGroup::new("model").args(["mesh", "scene", "shape"])))]
pub struct Args {
    /// A mesh file (OBJ, STL, PLY, OFF) placed at the origin.
    #[arg(long, value_name = "FILE")]
    mesh: Option<PathBuf>,
    /// A scene file (TOML): objects, poses, materials, motions.
    #[arg(long, value_name = "FILE.toml")]
    scene: Option<PathBuf>,
    /// A built-in shape at the origin: sphere, torus, box, thin-plate, concave-corner, blob.
    #[arg(long, value_name = "NAME")]
    shape: Option<String>,
    /// Replay a trace written by `haphe simulate --out` (with --mesh, --shape or --scene
    /// the objects are drawn too).
    #[arg(long, value_name = "RUN.csv")]
    replay: Option<PathBuf>,
    /// Triangles of the built-in shape.
    #[arg(long, default_value_t = 20_000)]
    triangles: usize,
    /// Length unit of the mesh file: m, mm, cm, in, or metres per unit.
    #[arg(long, default_value = "m", value_parser = crate::validate::parse_units)]
    units: Units,
    /// The device: `mouse` (the pointer moves the device point), `hand` (the simulated
    /// hand explores the scene), dhd (Force Dimension), openhaptics (3D Systems Touch) or
    /// udp:HOST:PORT (listen there for a network device), mapped as `haphe run` maps it.
    #[arg(long, default_value = "mouse", value_name = "SPEC")]
    device: String,
    /// Servo rate, Hz.
    #[arg(long, default_value_t = 1000.0)]
    rate: f64,
    /// Length of the run, seconds (default: 60 for `--device hand`, until Ctrl-C for a
    /// real device).
    #[arg(long)]
    seconds: Option<f64>,
    #[command(flatten)]
    mapping: crate::run::MappingArgs,
    /// Stiffness of a --mesh or --shape object, N/m.
    #[arg(long, default_value_t = 600.0)]
    stiffness: f64,
    /// Static friction coefficient of a --mesh or --shape object.
    #[arg(long, default_value_t = 0.3)]
    static_friction: f64,
    /// Dynamic friction coefficient of a --mesh or --shape object.
    #[arg(long, default_value_t = 0.2)]
    dynamic_friction: f64,
    #[command(flatten)]
    serve: Serve,
}

/// Where the view is served; shared with `haphe demo --view`.
#[derive(clap::Args, Debug, Clone)]
pub struct Serve {
    /// TCP port on 127.0.0.1 (0: any free port).
    #[arg(long, default_value_t = DEFAULT_PORT)]
    pub port: u16,
    /// Do not open the browser; print the address only.
    #[arg(long)]
    pub no_open: bool,
}

/// The device of a live view.
pub enum ViewDevice {
    /// The pointer moves the device point.
    Mouse,
    /// The simulated hand explores the scene for this many seconds.
    Hand(f64),
    /// A real device (`dhd`, `openhaptics`, `udp:HOST:PORT`), opened and mapped as `haphe
    /// run` does, for this many seconds or until Ctrl-C.
    Vendor(crate::run::VendorChoice, Option<f64>),
}

/// Runs `haphe view`.
pub fn run(args: &Args) -> anyhow::Result<ExitCode> {
    let map = MapOptions::default();
    let material = crate::simulate::args::material_of_flags(
        args.stiffness,
        1.0,
        args.static_friction,
        args.dynamic_friction,
    )?;
    let single = |name: String, shape| {
        vec![LoadedObject {
            name,
            object: SceneObject::new(ObjectId(0), Arc::new(shape), Pose::IDENTITY, material),
            motion: None,
        }]
    };
    let objects = if let Some(file) = &args.scene {
        load_scene(file, &map)?
    } else if let Some(file) = &args.mesh {
        single(
            file.display().to_string(),
            mesh_shape(file, args.units, &map)?,
        )
    } else if let Some(name) = &args.shape {
        let which: Catalog = name.parse().map_err(|e| anyhow!("--shape {name:?}: {e}"))?;
        single(name.clone(), shape_of(which, args.triangles, &map)?)
    } else if args.replay.is_some() {
        Vec::new()
    } else {
        bail!("say what to show: --mesh FILE, --shape NAME, --scene FILE or --replay RUN.csv");
    };
    if let Some(file) = &args.replay {
        let name = file.display().to_string();
        // Through the input module, like every command: a size limit, devices refused.
        let bytes = crate::files::input::read_input(file, crate::files::input::TRACE)?;
        let trace = Trace::read(&name, bytes.as_slice())?;
        let (scene, names, motions) = scene_of(objects)?;
        let model = Model::from_scene(&scene, &names).with_motions(motions);
        let title = format!("haphe view: replay of {name} ({} ticks)", trace.rows.len());
        return serve(model, Source::Replay(trace), &title, &args.serve);
    }
    let device = match args.device.as_str() {
        "mouse" => ViewDevice::Mouse,
        "hand" => ViewDevice::Hand(args.seconds.unwrap_or(HAND_SECONDS)),
        other => {
            other.parse::<haphe_devices::DeviceKind>().map_err(|e| {
                anyhow!("--device {other:?}: {e} (or mouse, the default, for the view)")
            })?;
            args.mapping.check()?;
            ViewDevice::Vendor(crate::run::view_choice(other, args.mapping), args.seconds)
        }
    };
    let what = args
        .scene
        .as_ref()
        .or(args.mesh.as_ref())
        .map(|p| p.display().to_string())
        .or(args.shape.clone())
        .unwrap_or_default();
    live(objects, device, args.rate, &what, &args.serve)
}

/// Builds the scene of `objects`: the scene, the objects' names and their motions.
fn scene_of(objects: Vec<LoadedObject>) -> anyhow::Result<(Scene, Vec<String>, Vec<ObjectMotion>)> {
    let mut scene = Scene::local(objects.len() + 4);
    let mut names = Vec::new();
    let mut motions = Vec::new();
    for o in objects {
        names.push(o.name);
        motions.extend(o.motion);
        scene
            .insert(o.object)
            .map_err(|(e, _)| anyhow!("cannot add an object: {e}"))?;
    }
    Ok((scene, names, motions))
}

/// Serves a live view of `objects` touched by `device` until Ctrl-C.
pub fn live(
    objects: Vec<LoadedObject>,
    device: ViewDevice,
    rate_hz: f64,
    what: &str,
    serve_options: &Serve,
) -> anyhow::Result<ExitCode> {
    let options = ServoOptions::new(rate_hz).map_err(|e| anyhow!("{}", e.named("--rate")))?;
    let (scene, names, motions) = scene_of(objects)?;
    let model = Model::from_scene(&scene, &names);
    let (lo, hi) = scene_bounds(&scene).ok_or_else(|| anyhow!("the scene has no objects"))?;
    let mut mapping = DeviceMapping::IDENTITY;
    let mut realtime = RealtimeOptions::default();
    let mut clock = None;
    let mut report = None;
    let (device, mouse, seconds, title): (Box<dyn Device>, _, _, _) = match device {
        ViewDevice::Mouse => {
            let size = (hi - lo).max_element();
            let centre = 0.5 * (lo + hi);
            // Start above the objects, outside them, so that the proxy is placed at once.
            let start = DVec3::new(centre.x, centre.y, hi.z + 0.1 * size);
            let (device, handle) =
                MouseDevice::new(start, lo - DVec3::splat(size), hi + DVec3::splat(size));
            (
                Box::new(device),
                Some(handle),
                None,
                format!("haphe view: the mouse on {what}"),
            )
        }
        ViewDevice::Hand(seconds) => {
            let path = scripted_path(PathKind::Explore, &scene, seconds, 3)?;
            (
                Box::new(SimulatedHand::new(path, HandOptions::default())),
                None,
                Some(seconds),
                format!("haphe view: the simulated hand explores {what} for {seconds} s"),
            )
        }
        ViewDevice::Vendor(choice, seconds) => {
            let opened = crate::run::open(&choice, &scene, seconds.unwrap_or(HAND_SECONDS))?;
            mapping = crate::run::mapping(&choice, &opened.device.spec(), &scene)?;
            println!("device: {}", opened.description);
            let stiffness = scene
                .objects()
                .iter()
                .map(|o| o.material.stiffness())
                .fold(0.0, f64::max);
            crate::run::print_mapping(&mut std::io::stdout(), &choice, &mapping, stiffness)?;
            realtime = realtime.with_overrun_budget(choice.overrun_budget);
            clock = opened.clock;
            report = Some(opened.report);
            (
                opened.device,
                None,
                seconds,
                format!("haphe view: device {} on {what}", choice.spec),
            )
        }
    };
    let source = LiveSource {
        device,
        scene,
        options: options.with_mapping(mapping),
        motions,
        seconds,
        realtime,
        clock,
    };
    let code = serve(
        model,
        Source::Live {
            source: Box::new(source),
            mouse,
        },
        &title,
        serve_options,
    )?;
    if let Some(line) = report.and_then(|r| r()) {
        println!("device: {line}");
    }
    Ok(code)
}

/// Starts the view, opens the browser, serves until Ctrl-C, and prints how the servo ran.
fn serve(
    model: Model,
    source: Source,
    title: &str,
    serve_options: &Serve,
) -> anyhow::Result<ExitCode> {
    crate::run::catch_interrupts()?;
    crate::run::servo_starting();
    let view = ViewServer::start(
        model,
        source,
        &ViewOptions {
            port: serve_options.port,
            title: title.to_string(),
        },
    )?;
    let url = view.url();
    println!("{title}");
    if !serve_options.no_open && haphe_view::open_in_browser(&url) {
        println!("view: {url} (opened in the browser; Ctrl-C stops)");
    } else {
        println!("view: {url} (open it in a browser; Ctrl-C stops)");
    }
    // Ctrl-C or SIGTERM: the servo is stopped below, and writes zero force first.
    while !crate::run::interrupted() {
        std::thread::sleep(std::time::Duration::from_millis(20));
    }
    if let Some(run) = view.stop()? {
        let s = run.servo.stats();
        println!(
            "servo: {} ticks at {:.0} Hz achieved, compute p50 {:.1} µs, p99 {:.1} µs, max {:.1} µs; {} overruns; {}",
            s.ticks,
            s.achieved_rate(),
            s.compute.quantile(0.5) as f64 * 1e-3,
            s.compute.quantile(0.99) as f64 * 1e-3,
            s.compute.max() as f64 * 1e-3,
            s.overruns,
            if run.setup.realtime_priority {
                "real-time priority"
            } else {
                "normal priority"
            }
        );
    }
    Ok(ExitCode::SUCCESS)
}
