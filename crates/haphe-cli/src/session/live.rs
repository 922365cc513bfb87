//! A live session in the browser view (`haphe view`, `haphe demo --view`): the scene
//! served with its device (the mouse, the simulated hand or a real device) until Ctrl-C.

mod changes;

use anyhow::anyhow;
use haphe::DVec3;
use haphe::scene::{Scene, SceneEditor};
use haphe::servo::{
    Device, DeviceMapping, HandOptions, ObjectMotion, PathKind, RealtimeOptions, ServoOptions,
    SimulatedHand, scene_bounds, scripted_path,
};
use haphe_view::{LiveSource, Model, MouseDevice, Source, ViewOptions, ViewServer};
use std::process::ExitCode;

use self::changes::Changes;
use super::device::{self, VendorChoice};
use super::wait;
use crate::args::ToolRadius;
use crate::args::cut::CutSetup;
use crate::args::deform::Deform;
use crate::input::scene::LoadedScene;

/// Port the view serves on by default.
pub const DEFAULT_PORT: u16 = 8417;

/// Length of a `--device hand` run, seconds, unless `--seconds` says.
pub const HAND_SECONDS: f64 = 60.0;

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
    /// Real devices (`dhd`, `openhaptics`, `udp:HOST:PORT`; one, or several in one scene),
    /// opened and mapped as `haphe run` does, for this many seconds or until Ctrl-C, with a
    /// clutch on this button.
    Vendor(Vec<VendorChoice>, Option<f64>, Option<u32>),
}

/// The scene of a view: the scene, the objects' names and their motions.
pub type ViewScene = (Scene, Vec<String>, Vec<ObjectMotion>);

/// Builds the scene of `loaded` (its objects and effects): the scene, the objects' names
/// and their motions.
pub fn scene_of(loaded: LoadedScene) -> anyhow::Result<ViewScene> {
    Ok(editable_scene_of(loaded, false)?.0)
}

/// [`scene_of`], with the scene's editor when `editor` (a scene that another thread
/// changes: a deforming or cut object's).
fn editable_scene_of(
    loaded: LoadedScene,
    editor: bool,
) -> anyhow::Result<(ViewScene, Option<SceneEditor>)> {
    let capacity = loaded.objects.len() + 4;
    let (mut scene, editor) = if editor {
        let (scene, editor) = Scene::new(capacity);
        (scene, Some(editor))
    } else {
        (Scene::local(capacity), None)
    };
    let mut names = Vec::new();
    let mut motions = Vec::new();
    super::add_effects(&mut scene, &loaded.effects)?;
    for o in loaded.objects {
        names.push(o.name);
        motions.extend(o.motion);
        scene
            .insert(o.object)
            .map_err(|(e, _)| anyhow!("cannot add an object: {e}"))?;
    }
    Ok(((scene, names, motions), editor))
}

/// Serves a live view of `loaded` (its objects and effects) touched by `device` with a
/// tool of radius `tool` until Ctrl-C; the first object deformed by `deform`, or the
/// volume of `cut` cut (and saved at the end, as `simulate` does).
pub fn live(
    loaded: LoadedScene,
    device: ViewDevice,
    rate_hz: f64,
    tool: &ToolRadius,
    what: &str,
    (serve_options, deform, cut): (&Serve, Option<Deform>, Option<CutSetup>),
) -> anyhow::Result<ExitCode> {
    let options = ServoOptions::new(rate_hz).map_err(|e| anyhow!("{}", e.named("--rate")))?;
    let cuts = cut.as_ref().is_some_and(|c| c.cut.is_some());
    let ((scene, names, motions), editor) = editable_scene_of(loaded, deform.is_some() || cuts)?;
    let options = options.with_proxy(tool.apply(*options.proxy(), &scene)?);
    let model = Model::from_scene(&scene, &names);
    let first = names.first().map_or("", String::as_str);
    let tool_radius = options.proxy().tool_radius();
    let changes = Changes::plan(&scene, editor, first, (deform, cut), (tool_radius, rate_hz))?;
    let (lo, hi) = scene_bounds(&scene).ok_or_else(|| anyhow!("the scene has no objects"))?;
    let mut mapping = DeviceMapping::IDENTITY;
    let mut clutch_button = None;
    let mut realtime = RealtimeOptions::default();
    let mut clock = None;
    let mut reports = Vec::new();
    let mut others = Vec::new();
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
        ViewDevice::Vendor(choices, seconds, clutch) => {
            clutch_button = clutch;
            let title = format!(
                "haphe view: device {} on {what}",
                choices
                    .iter()
                    .map(|c| c.spec.as_str())
                    .collect::<Vec<_>>()
                    .join(", ")
            );
            let opened =
                open_vendors(choices, &scene, seconds, options.with_clutch_button(clutch))?;
            mapping = opened.mapping;
            realtime = realtime.with_overrun_budget(opened.overrun_budget);
            clock = opened.clock;
            reports = opened.reports;
            others = opened.others;
            (opened.device, None, seconds, title)
        }
    };
    let source = LiveSource {
        device,
        scene,
        options: options
            .with_mapping(mapping)
            .with_clutch_button(clutch_button),
        motions,
        seconds,
        realtime,
        clock,
        others,
        on_record: None,
    };
    let (mut changing, model) = changes.start(model)?;
    let source = LiveSource {
        on_record: changing.on_record.take(),
        ..source
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
    for line in reports.iter().filter_map(|r| r()) {
        println!("device: {line}");
    }
    changing.finish()?;
    Ok(code)
}

/// The devices of a live view named by specifications, opened and mapped.
struct ViewVendors {
    /// The first device and its mapping.
    device: Box<dyn Device>,
    mapping: DeviceMapping,
    /// The others, each with its options (its own mapping).
    others: Vec<(Box<dyn Device>, ServoOptions)>,
    clock: Option<Box<dyn haphe::servo::DeviceClock>>,
    overrun_budget: Option<u64>,
    reports: Vec<super::devices::Report>,
}

/// Opens the devices of `choices` as `haphe run` does (one device's clock ticks them
/// all), maps each onto `scene` and prints each with its mapping; the others get
/// `options` with their own mapping.
fn open_vendors(
    choices: Vec<VendorChoice>,
    scene: &Scene,
    seconds: Option<f64>,
    options: ServoOptions,
) -> anyhow::Result<ViewVendors> {
    let n = choices.len();
    let overrun_budget = choices.first().and_then(|c| c.overrun_budget);
    let opened = super::devices::open_vendors(choices, scene, seconds.unwrap_or(HAND_SECONDS))?;
    let stiffness = super::stiffest(scene);
    let mut first = None;
    let mut others = Vec::new();
    let mut clock = None;
    let mut reports = Vec::new();
    for (i, o) in opened.into_iter().enumerate() {
        let Some(v) = o.vendor else { continue };
        let m = device::mapping(&v.choice, &o.device.spec(), scene)?;
        if n == 1 {
            println!("device: {}", v.description);
        } else {
            println!("device {} ({}): {}", i + 1, v.choice.spec, v.description);
        }
        device::print_mapping(&mut std::io::stdout(), &v.choice, &m, stiffness)?;
        clock = clock.or(v.clock);
        reports.push(v.report);
        match first {
            None => first = Some((o.device, m)),
            Some(_) => others.push((o.device, options.with_mapping(m))),
        }
    }
    let (device, mapping) = first.ok_or_else(|| anyhow!("no device to view"))?;
    Ok(ViewVendors {
        device,
        mapping,
        others,
        clock,
        overrun_budget,
        reports,
    })
}

/// Starts the view, opens the browser, serves until Ctrl-C, and prints how the servo ran.
pub fn serve(
    model: Model,
    source: Source,
    title: &str,
    serve_options: &Serve,
) -> anyhow::Result<ExitCode> {
    wait::catch_interrupts()?;
    wait::servo_starting();
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
    while !wait::interrupted() {
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
