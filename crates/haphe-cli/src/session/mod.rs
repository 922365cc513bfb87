//! A haptic session: the objects in a scene, a device (simulated, replayed or real), the
//! servo loop on a virtual clock or a real-time thread, the summary, the CSV trace and
//! the plot. `haphe simulate`, `run` and `demo` each describe one and run it.

mod clock;
pub mod cut;
pub mod deform;
pub mod device;
pub mod devices;
#[cfg(feature = "view")]
pub mod live;
pub mod plot;
pub mod publish;
pub mod summary;
pub mod trace;
pub mod wait;

use std::io::Write;
use std::path::{Path, PathBuf};

use anyhow::{anyhow, bail};
use haphe::scene::{Scene, SceneEditor};
use haphe::servo::scene_file::FileEffect;
use haphe::servo::{
    Device, HandOptions, HipTrace, ObjectMotion, PathKind, RealtimeOptions, ReplayDevice,
    ScriptedDevice, ServoOptions, SimulatedHand, StopReason, TickRecord, TrajectoryError,
    scripted_path,
};

use self::clock::{DeviceRan, How, Ran};
use self::deform::{Clock, Plan};
use self::device::VendorChoice;
use self::devices::{Opened, Vendor};
use self::summary::{RunInfo, Summary};
use self::trace::TraceOut;
use crate::args::cut::CutSetup;
use crate::args::deform::Deform;
use crate::args::{DEFAULT_SECONDS, MAX_SECONDS, PLOT_SECONDS, ToolRadius, proxy_options};
use crate::input::scene::LoadedObject;

/// Which device drives the run.
pub enum DeviceChoice {
    /// The simulated hand following a scripted path.
    Hand(PathKind, HandOptions),
    /// The device point on the scripted path exactly.
    Scripted(PathKind),
    /// A recorded trace.
    Replay(HipTrace),
    /// Real devices, network devices or simulated hands named by specifications (`haphe
    /// run`): one, or several on one servo, each with its own mapping.
    Vendor(Vec<VendorChoice>),
}

impl DeviceChoice {
    pub fn describe(&self) -> String {
        match self {
            DeviceChoice::Hand(p, _) => format!("the simulated hand, path {p}"),
            DeviceChoice::Scripted(p) => format!("a scripted device (no hand), path {p}"),
            DeviceChoice::Replay(t) => format!("a replayed trace of {} samples", t.len()),
            DeviceChoice::Vendor(v) => {
                let specs: Vec<&str> = v.iter().map(|c| c.spec.as_str()).collect();
                format!("device {}", specs.join(", "))
            }
        }
    }
}

/// Everything a run needs.
pub struct Session {
    pub title: String,
    pub objects: Vec<LoadedObject>,
    /// The force effects (a scene file's, `--effect`), checked against the rate.
    pub effects: Vec<FileEffect>,
    pub build_seconds: f64,
    pub device: DeviceChoice,
    pub rate_hz: f64,
    pub seconds: Option<f64>,
    pub realtime: bool,
    pub spin_seconds: Option<f64>,
    /// Ask for FIFO real-time priority (with `realtime`).
    pub fifo: bool,
    /// Core of a standby servo thread (with `realtime`; see
    /// [`RealtimeOptions::standby_core`]).
    pub standby_core: Option<usize>,
    pub seed: u64,
    pub max_force: f64,
    /// The tool's radius (`--tool-radius` or the scene file's), checked against the scene
    /// once it is built.
    pub tool_radius: ToolRadius,
    pub out: Option<PathBuf>,
    pub plot: Option<PathBuf>,
    /// The button that holds the clutch (`--clutch-button`).
    pub clutch_button: Option<u32>,
    /// Buttons the simulated devices press: (button, from, until), seconds (`--press`).
    pub presses: Vec<(u32, f64, f64)>,
    /// The deformation of the first object (`--deform`, `--deform-rate`).
    pub deform: Option<Deform>,
    /// The first object's volume, cut or not (`--volume`, `--voxel`, `--cut`).
    pub cut: Option<CutSetup>,
}

/// Objects listed by name in the summary.
const LISTED_OBJECTS: usize = 20;

/// The scene of a session with what the summary says of its objects.
struct Built {
    scene: Scene,
    motions: Vec<ObjectMotion>,
    /// One line per object: name, id, triangles, material.
    names: Vec<String>,
    triangles: usize,
    /// The deformation of the first object, with the scene's editor.
    deforming: Option<Plan>,
    /// The scene's editor when the first object is cut.
    cut_editor: Option<SceneEditor>,
}

/// Adds `effects` to `scene`, each named as it was given in an error.
pub fn add_effects(scene: &mut Scene, effects: &[FileEffect]) -> anyhow::Result<()> {
    for e in effects {
        scene
            .add_effect(e.effect)
            .map_err(|error| anyhow!("{} `{}`: {error}", e.place, e.spec))?;
    }
    Ok(())
}

/// Inserts `objects` into a new scene with `effects`; with `deform`, a scene with an
/// editor, and the first object's deformation; with `cut`, a scene with an editor for
/// the cutting.
fn build_scene(
    objects: Vec<LoadedObject>,
    effects: &[FileEffect],
    (deform, cut): (Option<Deform>, bool),
) -> anyhow::Result<Built> {
    let capacity = objects.len() + 4;
    let (mut scene, mut editor): (Scene, Option<SceneEditor>) = if deform.is_some() || cut {
        let (scene, editor) = Scene::new(capacity);
        (scene, Some(editor))
    } else {
        (Scene::local(capacity), None)
    };
    let cut_editor = if cut { editor.take() } else { None };
    let first = objects.first().map(|o| o.name.clone()).unwrap_or_default();
    let mut motions: Vec<ObjectMotion> = Vec::new();
    let mut names = Vec::new();
    let mut triangles = 0usize;
    for o in objects {
        triangles += o.object.shape.surface().triangles().len();
        let texture = o.object.texture.as_ref().map_or(String::new(), |t| {
            format!(", texture of amplitude {:.3} mm", t.amplitude() * 1e3)
        });
        names.push(format!(
            "{} (id {}, {} triangles, {:.0} N/m, friction {}/{}{texture})",
            o.name,
            o.object.id.0,
            o.object.shape.surface().triangles().len(),
            o.object.material.stiffness(),
            o.object.material.static_friction(),
            o.object.material.dynamic_friction()
        ));
        motions.extend(o.motion);
        scene
            .insert(o.object)
            .map_err(|(e, _)| anyhow!("cannot add an object: {e}"))?;
    }
    add_effects(&mut scene, effects)?;
    let deforming = match (deform, editor) {
        (Some(deform), Some(editor)) => Some(Plan::new(&scene, editor, &first, deform)?),
        _ => None,
    };
    Ok(Built {
        scene,
        motions,
        names,
        triangles,
        deforming,
        cut_editor,
    })
}

impl Session {
    /// Builds the scene and devices, runs, prints the summary (one block per device),
    /// writes trace and plot.
    pub fn run(self, out: &mut impl Write) -> anyhow::Result<()> {
        let cut = cut_of(&self.cut);
        let Built {
            scene,
            motions,
            names,
            triangles,
            deforming,
            cut_editor,
        } = build_scene(self.objects, &self.effects, (self.deform, cut))?;
        let proxy = ToolRadius::apply(&self.tool_radius, proxy_options(self.max_force)?, &scene)?;
        // A real device runs until Ctrl-C unless told otherwise.
        let until_stopped = matches!(&self.device, DeviceChoice::Vendor(v) if v.iter().any(|c| !c.is_hand()))
            && self.seconds.is_none();
        let seconds = run_seconds(&self.device, self.seconds, until_stopped, self.rate_hz)?;
        let replay = matches!(self.device, DeviceChoice::Replay(_));
        let opened = open_devices(self.device, &scene, seconds, self.seed, &self.presses)?;
        let options = ServoOptions::new(self.rate_hz)
            .map_err(|e| anyhow!("{}", e.named("--rate")))?
            .with_proxy(proxy)
            .with_clutch_button(self.clutch_button);
        let stiffness = stiffest(&scene);
        // The objects as placed at the start, for the plot's section (shapes shared).
        let placed = self
            .plot
            .as_ref()
            .map_or(Vec::new(), |_| scene.objects().to_vec());
        let (mut servo, mut vendors) = devices::servo_of(opened, scene, options, stiffness)?;
        servo.set_motions(motions);

        writeln!(out, "{}", self.title)?;
        // With several devices, each device's line says its tool.
        let tool = match servo.devices() {
            1 => servo.options().proxy().tool_radius(),
            _ => 0.0,
        };
        let effects: Vec<&str> = self.effects.iter().map(|e| e.spec.as_str()).collect();
        print_scene(out, &names, triangles, self.build_seconds, (tool, &effects))?;
        devices::print(out, &servo, &vendors, stiffness)?;
        let realtime = self.realtime || vendors.iter().any(Option::is_some);
        if let Some(plan) = &deforming {
            writeln!(out, "{}", plan.describe(Clock::of(realtime)))?;
        }
        let limit = (!until_stopped).then_some(seconds);
        let ticks = (seconds * self.rate_hz).round().max(1.0) as u64;
        let n = servo.devices();
        let mut summaries: Vec<Summary> = (0..n).map(|_| Summary::new(ticks)).collect();
        let mut trace = self
            .out
            .as_ref()
            .map(|p| TraceOut::create(p, n))
            .transpose()?;
        let thread = (self.spin_seconds, self.fifo, self.standby_core);
        let how = how(realtime, limit, ticks, thread)?;
        let first = servo.scene().objects().first().map(|o| (o.id, o.pose));
        let mut cutting = cut::start(out, self.cut, (cut_editor, first), (tool, self.rate_hz))?;
        let mut on_tick = |r: &TickRecord| {
            if let Some(s) = summaries.get_mut(r.device as usize) {
                s.add(r);
            }
            if let Some(t) = trace.as_mut() {
                t.add(r);
            }
            if let Some(c) = cutting.as_mut() {
                c.on_record(r);
            }
        };
        let (ran, deformed) = clock::run(out, servo, &mut vendors, deforming, how, &mut on_tick)?;
        writeln!(out, "\nrun:")?;
        let info = |d: &DeviceRan| RunInfo {
            rate_hz: self.rate_hz,
            scale: d.scale,
            realtime,
            max_force: d.max_force,
            stop: ran.stop,
            setup: ran.setup.as_ref(),
            interference: ran.interference,
            standby: ran.standby.clone(),
            dropped_records: ran.dropped,
            clutch: self.clutch_button.map(|b| (b, d.moved)),
        };
        let blocks: Vec<(String, &Summary, RunInfo<'_>)> = summaries
            .iter()
            .zip(&ran.devices)
            .enumerate()
            .map(|(i, (s, d))| (devices::name(i, n, vendors[i].as_ref()), s, info(d)))
            .collect();
        summary::print_devices(out, &blocks, &ran.stats)?;
        if let Some((refreshes, versions)) = &deformed {
            deform::print(out, refreshes, versions.as_ref(), ran.last_version)?;
        }
        if let Some(c) = &cutting {
            c.finish(out)?;
        }
        let plot = self.plot.as_deref().map(|p| (p, placed.as_slice()));
        write_files(out, trace, plot, &self.title, &summaries[0])?;
        let touched: Vec<Touch> = summaries.iter().map(|s| touch_of(replay, s)).collect();
        outcome(out, &ran, &vendors, &touched)
    }
}

/// Which clock the run is on: a real-time thread (`realtime`, for `limit` seconds or until
/// stopped, with the thread's spin, FIFO priority and standby core) or `ticks` on the
/// simulated clock.
///
/// # Errors
/// A spin out of its domain.
fn how(
    realtime: bool,
    limit: Option<f64>,
    ticks: u64,
    (spin_seconds, fifo, standby_core): (Option<f64>, bool, Option<usize>),
) -> anyhow::Result<How> {
    Ok(if realtime {
        How::Realtime {
            limit,
            options: RealtimeOptions::default()
                .with_spin_seconds(spin_seconds)?
                .with_realtime_priority(fifo)
                .with_standby_core(standby_core),
        }
    } else {
        How::Simulated { ticks }
    })
}

/// Whether `setup` cuts (`--cut`).
fn cut_of(setup: &Option<CutSetup>) -> bool {
    setup.as_ref().is_some_and(|s| s.cut.is_some())
}

/// Whether the device touched an object, from the run's summary (a replay's trace is
/// taken as touching).
fn touch_of(replay: bool, summary: &Summary) -> Touch {
    if replay || summary.contact_ticks > 0 {
        Touch::Touched
    } else if summary.held_ticks > 0 && summary.free_ticks == 0 {
        Touch::HeldThroughout
    } else if summary.held_ticks > 0 {
        Touch::LeftWithoutTouching
    } else {
        Touch::Never
    }
}

/// The length of the run: `--seconds`, or the replayed trace's, or until Ctrl-C (then the
/// plot is sized for [`PLOT_SECONDS`]), or [`DEFAULT_SECONDS`].
fn run_seconds(
    device: &DeviceChoice,
    seconds: Option<f64>,
    until_stopped: bool,
    rate_hz: f64,
) -> anyhow::Result<f64> {
    Ok(match (device, seconds) {
        (_, Some(s)) if s.is_finite() && s > 0.0 && s <= MAX_SECONDS => s,
        (_, Some(s)) => {
            bail!("--seconds must be a positive number of at most {MAX_SECONDS}, not {s}")
        }
        (DeviceChoice::Vendor(_), None) if until_stopped => PLOT_SECONDS,
        // Every sample, the last one included.
        (DeviceChoice::Replay(t), None) => {
            let length = t.end_time() - t.start_time();
            if length > MAX_SECONDS {
                bail!(
                    "the replayed trace spans {length} s, more than a run may last ({MAX_SECONDS} s); give --seconds to replay its beginning"
                );
            }
            length + 1.0 / rate_hz
        }
        (_, None) => DEFAULT_SECONDS,
    })
}

/// `device` with the buttons `presses` holds: (button, from, until), seconds.
fn pressing<D>(
    mut device: D,
    presses: &[(u32, f64, f64)],
    press: fn(D, u32, f64, f64) -> Result<D, TrajectoryError>,
) -> anyhow::Result<D> {
    for &(button, from, until) in presses {
        device = press(device, button, from, until).map_err(|e| anyhow!("--press: {e}"))?;
    }
    Ok(device)
}

/// The devices of `choice` (a simulated one holding the buttons of `presses`, or those
/// named by specifications, with what each opened).
fn open_devices(
    choice: DeviceChoice,
    scene: &Scene,
    seconds: f64,
    seed: u64,
    presses: &[(u32, f64, f64)],
) -> anyhow::Result<Vec<Opened>> {
    let device: Box<dyn Device> = match choice {
        DeviceChoice::Hand(kind, hand) => {
            let hand = SimulatedHand::new(scripted_path(kind, scene, seconds, seed)?, hand);
            Box::new(pressing(hand, presses, SimulatedHand::press)?)
        }
        DeviceChoice::Scripted(kind) => {
            let device = ScriptedDevice::new(scripted_path(kind, scene, seconds, seed)?);
            Box::new(pressing(device, presses, ScriptedDevice::press)?)
        }
        DeviceChoice::Replay(trace) => {
            let device = ReplayDevice::new(trace);
            Box::new(pressing(device, presses, ReplayDevice::press)?)
        }
        DeviceChoice::Vendor(choices) => return devices::open_vendors(choices, scene, seconds),
    };
    Ok(vec![Opened {
        device,
        vendor: None,
    }])
}

/// Completes the trace and draws the plot, each named in a line of `out`.
fn write_files(
    out: &mut impl Write,
    trace: Option<TraceOut>,
    plot: Option<(&Path, &[haphe::scene::SceneObject])>,
    title: &str,
    summary: &Summary,
) -> anyhow::Result<()> {
    if let Some(t) = trace {
        let path = t.staged.path().to_owned();
        t.finish()?;
        writeln!(out, "trace: {} ({} ticks)", path.display(), summary.ticks)?;
    }
    if let Some((p, objects)) = plot {
        plot::write(p, title, &summary.plot, objects)?;
        writeln!(
            out,
            "plot: {} (force and penetration over time; the path seen from the side)",
            p.display()
        )?;
    }
    Ok(())
}

/// The largest stiffness of the scene's objects, N/m (0 for none).
pub fn stiffest(scene: &Scene) -> f64 {
    scene
        .objects()
        .iter()
        .map(|o| o.material.stiffness())
        .fold(0.0, f64::max)
}

/// Prints the scene's line, its objects' (a large scene, a grid of copies, lists its
/// first objects only) and the tool's radius when it is not a point.
fn print_scene(
    out: &mut impl Write,
    names: &[String],
    triangles: usize,
    build_seconds: f64,
    (tool_radius, effects): (f64, &[&str]),
) -> std::io::Result<()> {
    writeln!(
        out,
        "scene: {} object(s), {triangles} triangles, surfaces, maps and clear zones built in {build_seconds:.2} s",
        names.len(),
    )?;
    for n in names.iter().take(LISTED_OBJECTS) {
        writeln!(out, "  {n}")?;
    }
    if names.len() > LISTED_OBJECTS {
        writeln!(out, "  ... and {} more", names.len() - LISTED_OBJECTS)?;
    }
    // A point tool (the default) says nothing: its output stays the point proxy's.
    if tool_radius > 0.0 {
        writeln!(out, "tool: a sphere of radius {:.3} mm", tool_radius * 1e3)?;
    }
    if !effects.is_empty() {
        writeln!(out, "effects: {}", effects.join(", "))?;
    }
    Ok(())
}

/// Whether the device touched an object during a run, for the warning after it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Touch {
    /// It did (or the run replayed a trace: nothing to say).
    Touched,
    /// Never: it stayed outside every object.
    Never,
    /// It started inside an object and the safe start held it there for the whole run.
    HeldThroughout,
    /// It started inside an object, was held, left it, and touched nothing after.
    LeftWithoutTouching,
}

/// The warning of a device that did not touch an object (the one that is true: never
/// touching, or held by the safe start).
fn warning(touch: Touch) -> Option<&'static str> {
    match touch {
        Touch::Touched => None,
        Touch::Never => {
            Some("the device never touched any object (the path stays outside them all)")
        }
        Touch::HeldThroughout => Some(
            "the device was inside an object for the whole run, so the safe start held the force at zero; start outside the objects (docs/devices.md, Safety)",
        ),
        Touch::LeftWithoutTouching => Some(
            "the device started inside an object (held at zero force until it left) and touched no object after",
        ),
    }
}

/// Prints what each device said after the run and one warning for each device that did
/// not touch an object; the session's error when a device faulted (naming it, with what
/// it said: zero force was written to every device) or the servo missed too many
/// deadlines.
fn outcome(
    out: &mut impl Write,
    ran: &Ran,
    vendors: &[Option<Vendor>],
    touched: &[Touch],
) -> anyhow::Result<()> {
    let n = touched.len();
    let said: Vec<Option<String>> = (0..n)
        .map(|i| {
            vendors
                .get(i)
                .and_then(|v| v.as_ref())
                .and_then(|v| (v.report)())
        })
        .collect();
    for (i, line) in said.iter().enumerate() {
        match line {
            Some(line) if n == 1 => writeln!(out, "{line}")?,
            Some(line) => {
                let name = devices::name(i, n, vendors[i].as_ref());
                writeln!(out, "{name}: {line}")?;
            }
            None => {}
        }
    }
    for (i, &touch) in touched.iter().enumerate() {
        match warning(touch) {
            Some(w) if n == 1 => writeln!(out, "warning: {w}")?,
            Some(w) => {
                let name = devices::name(i, n, vendors[i].as_ref());
                writeln!(
                    out,
                    "warning: {name}: {}",
                    w.replacen("the device", "it", 1)
                )?;
            }
            None => {}
        }
    }
    if let StopReason::Fault(f) = ran.stop
        && f != haphe::servo::DeviceFault::Ended
    {
        let i = ran.faulted.unwrap_or(0);
        let line = said.get(i).cloned().flatten();
        let said = line.map_or(String::new(), |l| format!(" ({l})"));
        if n == 1 {
            bail!("the device faulted: {f}{said}; zero force was written");
        }
        let name = devices::name(i, n, vendors.get(i).and_then(|v| v.as_ref()));
        bail!("{name} faulted: {f}{said}; zero force was written to every device");
    }
    if ran.stop == StopReason::Overruns {
        bail!("the servo missed more deadlines than its overrun budget; zero force was written");
    }
    Ok(())
}
