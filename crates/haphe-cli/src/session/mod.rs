//! A haptic session: the objects in a scene, a device (simulated, replayed or real), the
//! servo loop on a virtual clock or a real-time thread, the summary, the CSV trace and
//! the plot. `haphe simulate`, `run` and `demo` each describe one and run it.

pub mod device;
#[cfg(feature = "view")]
pub mod live;
pub mod plot;
pub mod summary;
pub mod trace;
pub mod wait;

use std::io::Write;
use std::path::{Path, PathBuf};

use anyhow::{anyhow, bail};
use haphe::DVec3;
use haphe::scene::Scene;
use haphe::servo::{
    Device, DeviceClock, DeviceMapping, DeviceSpec, HandOptions, HipTrace, Interference,
    ObjectMotion, PathKind, RealtimeOptions, RealtimeSetup, ReplayDevice, STIFFNESS_RATED_AT_HZ,
    ScriptedDevice, Servo, ServoLoop, ServoOptions, SimulatedHand, StandbyReport, StopReason,
    TickRecord, TickStats, TrajectoryError, scripted_path,
};

use self::device::VendorChoice;
use self::summary::{RunInfo, Summary};
use self::trace::TraceOut;
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
    /// A real device, or the network device, named by a specification (`haphe run`).
    Vendor(VendorChoice),
}

impl DeviceChoice {
    pub fn describe(&self) -> String {
        match self {
            DeviceChoice::Hand(p, _) => format!("the simulated hand, path {p}"),
            DeviceChoice::Scripted(p) => format!("a scripted device (no hand), path {p}"),
            DeviceChoice::Replay(t) => format!("a replayed trace of {} samples", t.len()),
            DeviceChoice::Vendor(v) => format!("device {}", v.spec),
        }
    }
}

/// Everything a run needs.
pub struct Session {
    pub title: String,
    pub objects: Vec<LoadedObject>,
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
}

/// A device named by a specification, opened for the session.
struct Vendor {
    choice: VendorChoice,
    description: String,
    clock: Option<Box<dyn DeviceClock>>,
    report: Report,
}

/// How the servo ran, whatever the clock.
struct Ran {
    stats: TickStats,
    stop: StopReason,
    setup: Option<RealtimeSetup>,
    interference: Option<Interference>,
    standby: Option<StandbyReport>,
    dropped: u64,
    /// How far the clutch moved the device's origin in the world, metres.
    moved: DVec3,
}

/// Inserts `objects` into a new scene.
fn build_scene(objects: Vec<LoadedObject>) -> anyhow::Result<Built> {
    let capacity = objects.len() + 4;
    let mut scene = Scene::local(capacity);
    let mut motions: Vec<ObjectMotion> = Vec::new();
    let mut names = Vec::new();
    let mut triangles = 0usize;
    for o in objects {
        triangles += o.object.shape.surface().triangles().len();
        names.push(format!(
            "{} (id {}, {} triangles, {:.0} N/m, friction {}/{})",
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
    Ok(Built {
        scene,
        motions,
        names,
        triangles,
    })
}

impl Session {
    /// Builds the scene and device, runs, prints the summary, writes trace and plot.
    pub fn run(self, out: &mut impl Write) -> anyhow::Result<()> {
        let Built {
            scene,
            motions,
            names,
            triangles,
        } = build_scene(self.objects)?;
        let proxy = ToolRadius::apply(&self.tool_radius, proxy_options(self.max_force)?, &scene)?;
        // A real device runs until Ctrl-C unless told otherwise.
        let until_stopped = matches!(&self.device, DeviceChoice::Vendor(v) if v.spec != "hand")
            && self.seconds.is_none();
        let seconds = run_seconds(&self.device, self.seconds, until_stopped, self.rate_hz)?;
        let replay = matches!(self.device, DeviceChoice::Replay(_));
        let (device, vendor) = open_device(self.device, &scene, seconds, self.seed, &self.presses)?;
        let mapping = match &vendor {
            Some(v) => device::mapping(&v.choice, &device.spec(), &scene)?,
            None => DeviceMapping::IDENTITY,
        };
        let options = ServoOptions::new(self.rate_hz)
            .map_err(|e| anyhow!("{}", e.named("--rate")))?
            .with_proxy(proxy)
            .with_mapping(mapping)
            .with_clutch_button(self.clutch_button);
        let stiffness = stiffest(&scene);
        // The objects as placed at the start, for the plot's section (shapes shared).
        let placed: Vec<haphe::scene::SceneObject> = match &self.plot {
            Some(_) => scene.objects().to_vec(),
            None => Vec::new(),
        };
        warn_stiffness(stiffness, &mapping, &device.spec(), self.rate_hz);
        let mut servo = Servo::new(device, scene, options)?;
        servo.set_motions(motions);
        let max_force = servo.options().proxy().max_force();

        writeln!(out, "{}", self.title)?;
        let tool = servo.options().proxy().tool_radius();
        print_scene(out, &names, triangles, self.build_seconds, tool)?;
        if let Some(v) = &vendor {
            writeln!(out, "device: {}", v.description)?;
            device::print_mapping(out, &v.choice, &mapping, stiffness)?;
        }
        let realtime = self.realtime || vendor.is_some();
        let limit = (!until_stopped).then_some(seconds);
        let ticks = (seconds * self.rate_hz).round().max(1.0) as u64;
        let mut summary = Summary::new(ticks);
        let mut trace = match &self.out {
            Some(p) => Some(TraceOut::create(p)?),
            None => None,
        };
        let mut on_tick = |r: &TickRecord| {
            summary.add(r);
            if let Some(t) = trace.as_mut() {
                t.add(r);
            }
        };
        let mut report = None;
        let ran = if realtime {
            let options = RealtimeOptions::default()
                .with_spin_seconds(self.spin_seconds)?
                .with_realtime_priority(self.fifo)
                .with_standby_core(self.standby_core);
            let (ran, said) = run_realtime(out, servo, vendor, limit, options, &mut on_tick)?;
            report = said;
            ran
        } else {
            let stop = servo.run_simulated(ticks, &mut on_tick);
            servo.close();
            Ran {
                stats: servo.stats().clone(),
                stop,
                setup: None,
                interference: None,
                standby: None,
                dropped: 0,
                moved: moved(&servo),
            }
        };
        writeln!(out, "\nrun:")?;
        summary::print(
            out,
            &summary,
            &ran.stats,
            &RunInfo {
                rate_hz: self.rate_hz,
                scale: mapping.scale(),
                realtime,
                max_force,
                stop: ran.stop,
                setup: ran.setup.as_ref(),
                interference: ran.interference,
                standby: ran.standby,
                dropped_records: ran.dropped,
                clutch: self.clutch_button.map(|b| (b, ran.moved)),
            },
        )?;
        let plot = self.plot.as_deref().map(|p| (p, placed.as_slice()));
        write_files(out, trace, plot, &self.title, &summary)?;
        let said = report.as_ref().and_then(|r| r());
        outcome(out, ran.stop, said, touch_of(replay, &summary))
    }
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

/// How far the clutch moved `servo`'s device origin in the world, metres.
fn moved<D: Device>(servo: &Servo<D>) -> DVec3 {
    servo.mapping().offset() - servo.options().mapping().offset()
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

/// The device of `choice` (a simulated one holding the buttons of `presses`), and when
/// it is named by a specification, what was opened.
fn open_device(
    choice: DeviceChoice,
    scene: &Scene,
    seconds: f64,
    seed: u64,
    presses: &[(u32, f64, f64)],
) -> anyhow::Result<(Box<dyn Device>, Option<Vendor>)> {
    Ok(match choice {
        DeviceChoice::Hand(kind, hand) => {
            let hand = SimulatedHand::new(scripted_path(kind, scene, seconds, seed)?, hand);
            (
                Box::new(pressing(hand, presses, SimulatedHand::press)?),
                None,
            )
        }
        DeviceChoice::Scripted(kind) => {
            let device = ScriptedDevice::new(scripted_path(kind, scene, seconds, seed)?);
            (
                Box::new(pressing(device, presses, ScriptedDevice::press)?),
                None,
            )
        }
        DeviceChoice::Replay(trace) => {
            let device = ReplayDevice::new(trace);
            (
                Box::new(pressing(device, presses, ReplayDevice::press)?),
                None,
            )
        }
        DeviceChoice::Vendor(choice) => {
            let opened = device::open(&choice, scene, seconds)?;
            let vendor = Vendor {
                choice,
                description: opened.description,
                clock: opened.clock,
                report: opened.report,
            };
            (opened.device, Some(vendor))
        }
    })
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

/// Warns on standard error when the stiffest object, felt at the device through
/// `mapping`, is above what the device renders stably at `rate_hz`
/// ([`DeviceSpec::stable_stiffness`], the passivity rule of a sampled wall).
fn warn_stiffness(stiffness: f64, mapping: &DeviceMapping, spec: &DeviceSpec, rate_hz: f64) {
    let at_device = mapping.stiffness_at_device(stiffness);
    let stable = spec.stable_stiffness(rate_hz);
    if at_device > stable {
        let felt = if mapping.scale() == 1.0 {
            String::new()
        } else {
            format!(", felt as {at_device:.0} N/m at the device")
        };
        eprintln!(
            "haphe: warning: stiffness {stiffness} N/m{felt} is above the {stable:.0} N/m the device ({}, rated {:.0} N/m at {STIFFNESS_RATED_AT_HZ:.0} Hz) renders stably at {rate_hz} Hz \
             (passivity of a sampled wall, K < K_rated · rate / {STIFFNESS_RATED_AT_HZ:.0} Hz): \
             expect a buzzing wall; lower --stiffness or --scale, or raise --rate",
            spec.name, spec.max_stiffness
        );
    }
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
    tool_radius: f64,
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
    Ok(())
}

/// What a device reports after a run.
type Report = Box<dyn Fn() -> Option<String> + Send + Sync>;

/// Runs `servo` on a real-time thread (driven by the vendor device's clock when it has
/// one, within its overrun budget) until the run ends or Ctrl-C, handing each record to
/// `on_tick`; with the vendor device's report.
fn run_realtime(
    out: &mut impl Write,
    servo: Servo<Box<dyn Device>>,
    vendor: Option<Vendor>,
    limit: Option<f64>,
    mut options: RealtimeOptions,
    on_tick: &mut impl FnMut(&TickRecord),
) -> anyhow::Result<(Ran, Option<Report>)> {
    let mut clock = None;
    let mut report = None;
    if let Some(v) = vendor {
        options = options.with_overrun_budget(v.choice.overrun_budget);
        clock = v.clock;
        report = Some(v.report);
        if limit.is_none() {
            // A network peer can also end the run (the stop flag of its datagram).
            let or_peer = if v.choice.spec.starts_with("udp") {
                " or the peer sends stop"
            } else {
                ""
            };
            writeln!(out, "running until Ctrl-C{or_peer}")?;
        }
    }
    out.flush()?;
    wait::servo_starting();
    let running = match clock {
        Some(clock) => ServoLoop::spawn_clocked(servo, clock, limit, options)?,
        None => ServoLoop::spawn(servo, limit, options)?,
    };
    let run = wait::wait(running, on_tick)?;
    let ran = Ran {
        stats: run.servo.stats().clone(),
        stop: run.stop,
        setup: Some(run.setup),
        interference: Some(run.interference),
        standby: run.standby,
        dropped: run.dropped_records,
        moved: moved(&run.servo),
    };
    Ok((ran, report))
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

/// Prints what the device `said` after the run and one warning when it did not `touch`
/// an object (the one that is true: never touching, or held by the safe start); the
/// session's error when the device faulted (with what it said) or the servo missed too
/// many deadlines.
fn outcome(
    out: &mut impl Write,
    stop: StopReason,
    said: Option<String>,
    touch: Touch,
) -> anyhow::Result<()> {
    if let Some(line) = &said {
        writeln!(out, "{line}")?;
    }
    let warning = match touch {
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
    };
    if let Some(w) = warning {
        writeln!(out, "warning: {w}")?;
    }
    if let StopReason::Fault(f) = stop
        && f != haphe::servo::DeviceFault::Ended
    {
        match said {
            Some(line) => bail!("the device faulted: {f} ({line}); zero force was written"),
            None => bail!("the device faulted: {f}; zero force was written"),
        }
    }
    if stop == StopReason::Overruns {
        bail!("the servo missed more deadlines than its overrun budget; zero force was written");
    }
    Ok(())
}
