//! `haphe simulate`: a haptic session without hardware — a simulated hand (or a scripted
//! device, or a replayed trace) on a mesh, a built-in shape or a scene file, ticked by the
//! servo loop on a virtual clock or on the wall clock; a per-tick CSV trace, a summary and
//! a plot.

pub(crate) mod args;
pub mod plot;
pub mod summary;

use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::sync::Arc;
use std::time::Instant;

use anyhow::{Context, anyhow, bail};
use haphe::map::MapOptions;
use haphe::mesh::Units;
use haphe::mesh::shapes::Catalog;
use haphe::proxy::ProxyOptions;
use haphe::scene::{Material, ObjectId, Param, Pose, Scene, SceneObject};
use haphe::servo::{
    Device, HandOptions, HipTrace, ObjectMotion, PathKind, RealtimeOptions, ReplayDevice,
    ScriptedDevice, Servo, ServoLoop, ServoOptions, SimulatedHand, StopReason, TickRecord,
    scripted_path, write_csv_header,
};

use crate::files::input::{self, read_input};
use crate::files::output::{Staged, check_outputs};

pub use self::args::{ModelArgs, OutputArgs};
use self::summary::{RunInfo, Summary};
use crate::scene::{LoadedObject, load_scene, mesh_shape, shape_of};

/// Arguments of `haphe simulate`.
#[derive(clap::Args, Debug)]
#[command(allow_negative_numbers = true)]
pub struct Args {
    #[command(flatten)]
    model: ModelArgs,
    /// The motion: press, slide, circle, explore or strike (over the top of the objects).
    #[arg(long, default_value = "explore")]
    path: PathKind,
    /// The simulated hand (a mass–spring–damper arm pushed back by the force) follows the
    /// path (the default).
    #[arg(long, overrides_with = "no_hand")]
    hand: bool,
    /// The device point follows the path exactly, whatever the force.
    #[arg(long = "no-hand", overrides_with = "hand")]
    no_hand: bool,
    /// Replay a recorded device trace, CSV `t,x,y,z` (instead of --path).
    #[arg(long, value_name = "HIP.csv")]
    replay: Option<PathBuf>,
    /// Servo rate, Hz (1 to 40000).
    #[arg(long, default_value_t = 1000.0)]
    rate: f64,
    /// Length of the run, seconds, at most 3600 (default 5, or the length of the replayed
    /// trace; a replay stops when its trace ends).
    #[arg(long, allow_negative_numbers = true)]
    seconds: Option<f64>,
    /// Run on the wall clock on a real-time thread (default: a virtual clock, as fast as
    /// possible).
    #[arg(long)]
    realtime: bool,
    /// With --realtime: spin (instead of sleeping) for this last part before each
    /// deadline, microseconds (default: 200, at most 30 % of the period).
    #[arg(long, value_name = "US")]
    spin_us: Option<f64>,
    /// With --realtime: keep the normal, time-shared priority instead of asking for FIFO
    /// real-time priority. Linux throttles a real-time thread that never sleeps (by
    /// default 50 ms in every second); a normal thread may spin the whole period
    /// (`--spin-us` equal to it) on its own core.
    #[arg(long)]
    normal_priority: bool,
    /// With --realtime: a standby thread pinned to this core ticks in place of the servo
    /// thread when that one is 20 µs late (its core taken away by the host or another
    /// thread). It spins the whole period at normal priority: it costs a second core.
    #[arg(long, value_name = "CORE")]
    standby_core: Option<usize>,
    #[command(flatten)]
    output: OutputArgs,
    /// Seed of the explore path.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Largest force rendered, N (the simulated device's maximum is 3.3 N).
    #[arg(long, default_value_t = 3.3)]
    max_force: f64,
}

/// Runs `haphe simulate`.
pub fn run(args: &Args) -> anyhow::Result<ExitCode> {
    // The library's table of domains checks every number, named as its flag.
    ServoOptions::new(args.rate).map_err(|e| anyhow!("{}", e.named("--rate")))?;
    let outputs: Vec<&Path> = [&args.output.out, &args.output.plot]
        .into_iter()
        .flatten()
        .map(PathBuf::as_path)
        .collect();
    let inputs: Vec<&Path> = [&args.model.mesh, &args.model.scene, &args.replay]
        .into_iter()
        .flatten()
        .map(PathBuf::as_path)
        .collect();
    check_outputs(&outputs, &inputs)?;
    if let Some(core) = args.standby_core {
        haphe::servo::check_core(core).map_err(|e| anyhow!("--standby-core: {e}"))?;
    }
    // The same check as a scene file's materials.
    let material = args.model.material()?;
    proxy_options(args.max_force)?;
    spin(args.spin_us)?;
    let started = Instant::now();
    let (objects, what) = load_model(args.model.model(), material)?;
    let build_seconds = started.elapsed().as_secs_f64();
    let device = if let Some(file) = &args.replay {
        let name = file.display().to_string();
        let bytes = read_input(file, input::TRACE)?;
        DeviceChoice::Replay(HipTrace::read(&name, bytes.as_slice())?)
    } else if args.no_hand && !args.hand {
        DeviceChoice::Scripted(args.path)
    } else {
        DeviceChoice::Hand(args.path, HandOptions::default())
    };
    let session = Session {
        title: format!("haphe simulate: {} on {what}", device.describe()),
        objects,
        build_seconds,
        device,
        rate_hz: args.rate,
        seconds: args.seconds,
        realtime: args.realtime,
        spin_seconds: args.spin_us.map(|us| us * 1e-6),
        fifo: !args.normal_priority,
        standby_core: args.standby_core,
        seed: args.seed,
        max_force: args.max_force,
        out: args.output.out.clone(),
        plot: args.output.plot.clone(),
    };
    session.run(&mut std::io::stdout().lock())?;
    Ok(ExitCode::SUCCESS)
}

/// The proxy's options with the maximum force of `--max-force`.
///
/// # Errors
/// A force outside its domain, named as its flag.
pub fn proxy_options(max_force: f64) -> anyhow::Result<ProxyOptions> {
    ProxyOptions::default()
        .with_max_force(max_force)
        .map_err(|e| anyhow!("{}", e.named("--max-force")))
}

/// The real-time options with the spin of `--spin-us`, microseconds.
///
/// # Errors
/// A spin outside its domain, named as its flag (in microseconds).
fn spin(spin_us: Option<f64>) -> anyhow::Result<RealtimeOptions> {
    RealtimeOptions::default()
        .with_spin_seconds(spin_us.map(|us| us * 1e-6))
        .map_err(|_| {
            let domain = Param::SpinSeconds.domain();
            anyhow!(
                "--spin-us must be a finite number from {} to {} µs, not {}",
                domain.low * 1e6,
                domain.high * 1e6,
                spin_us.unwrap_or_default()
            )
        })
}

/// Where the objects of a run come from: one of a scene file, a mesh file, a built-in shape.
pub struct Model<'a> {
    pub scene: Option<&'a Path>,
    pub mesh: Option<&'a Path>,
    pub shape: Option<&'a str>,
    pub triangles: usize,
    pub units: Units,
}

/// Loads the objects of a run (a --mesh or --shape object gets `material`), and says
/// what they are.
pub fn load_model(
    model: Model<'_>,
    material: Material,
) -> anyhow::Result<(Vec<LoadedObject>, String)> {
    let map = MapOptions::default();
    Ok(if let Some(file) = model.scene {
        (load_scene(file, &map)?, file.display().to_string())
    } else if let Some(file) = model.mesh {
        let shape = Arc::new(mesh_shape(file, model.units, &map)?);
        // The paths explore the workspace around the origin: the mesh is placed there.
        let (lo, hi) = shape.surface().bounds();
        let centre = (lo + hi) * 0.5;
        if centre.length() > 1e-9 {
            eprintln!(
                "haphe: {} placed with its centre at the origin (moved by {:.6?} m)",
                file.display(),
                (-centre).to_array()
            );
        }
        let o = SceneObject::new(
            ObjectId(0),
            shape,
            Pose::from_translation(-centre)
                .map_err(|e| anyhow!("{}: placing it at the origin: {e}", file.display()))?,
            material,
        );
        (
            vec![LoadedObject {
                name: file.display().to_string(),
                object: o,
                motion: None,
            }],
            file.display().to_string(),
        )
    } else {
        let name = model.shape.unwrap_or("blob");
        let which: Catalog = name.parse().map_err(|e| anyhow!("--shape {name:?}: {e}"))?;
        Catalog::check_triangles(model.triangles).map_err(|e| anyhow!("--triangles: {e}"))?;
        let shape = Arc::new(shape_of(which, model.triangles, &map)?);
        let o = SceneObject::new(ObjectId(0), shape, Pose::IDENTITY, material);
        (
            vec![LoadedObject {
                name: name.to_string(),
                object: o,
                motion: None,
            }],
            format!("the built-in {name}"),
        )
    })
}

/// Which device drives the run.
pub enum DeviceChoice {
    /// The simulated hand following a scripted path.
    Hand(PathKind, HandOptions),
    /// The device point on the scripted path exactly.
    Scripted(PathKind),
    /// A recorded trace.
    Replay(HipTrace),
    /// A real device, or the network device, named by a specification (`haphe run`).
    Vendor(crate::run::VendorChoice),
}

impl DeviceChoice {
    fn describe(&self) -> String {
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
    pub out: Option<PathBuf>,
    pub plot: Option<PathBuf>,
}

/// Default length of a run, seconds.
pub const DEFAULT_SECONDS: f64 = 5.0;

/// The longest run, seconds (an hour: 3.6 million ticks at 1 kHz, a 400 MB trace).
pub const MAX_SECONDS: f64 = 3600.0;

/// The CSV trace writer, when asked for: a temporary file beside the target, renamed over
/// it when the run is complete (an earlier trace stays as it was if the run fails).
struct TraceOut {
    staged: Staged,
    error: Option<std::io::Error>,
}

impl TraceOut {
    fn create(path: &Path) -> anyhow::Result<TraceOut> {
        let mut staged = Staged::create(path)?;
        write_csv_header(staged.writer())
            .with_context(|| format!("cannot write {}", path.display()))?;
        Ok(TraceOut {
            staged,
            error: None,
        })
    }

    fn add(&mut self, r: &TickRecord) {
        if self.error.is_none()
            && let Err(e) = r.write_csv(self.staged.writer())
        {
            self.error = Some(e);
        }
    }

    fn finish(mut self) -> anyhow::Result<()> {
        if let Some(e) = self.error.take() {
            return Err(e)
                .with_context(|| format!("cannot write {}", self.staged.path().display()));
        }
        self.staged.commit()
    }
}

/// Objects listed by name in the summary.
const LISTED_OBJECTS: usize = 20;

impl Session {
    /// Builds the scene and device, runs, prints the summary, writes trace and plot.
    pub fn run(self, out: &mut impl Write) -> anyhow::Result<()> {
        let capacity = self.objects.len() + 4;
        let mut scene = Scene::local(capacity);
        let mut motions: Vec<ObjectMotion> = Vec::new();
        let mut names = Vec::new();
        let mut triangles = 0usize;
        for o in self.objects {
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
        // A real device runs until Ctrl-C unless told otherwise.
        let until_stopped = matches!(&self.device, DeviceChoice::Vendor(v) if v.spec != "hand")
            && self.seconds.is_none();
        let seconds = match (&self.device, self.seconds) {
            (_, Some(s)) if s.is_finite() && s > 0.0 && s <= MAX_SECONDS => s,
            (_, Some(s)) => {
                bail!("--seconds must be a positive number of at most {MAX_SECONDS}, not {s}")
            }
            (DeviceChoice::Vendor(_), None) if until_stopped => crate::run::PLOT_SECONDS,
            // Every sample, the last one included.
            (DeviceChoice::Replay(t), None) => {
                let length = t.end_time() - t.start_time();
                if length > MAX_SECONDS {
                    bail!(
                        "the replayed trace spans {length} s, more than a run may last ({MAX_SECONDS} s); give --seconds to replay its beginning"
                    );
                }
                length + 1.0 / self.rate_hz
            }
            (_, None) => DEFAULT_SECONDS,
        };
        let mut vendor = None;
        let replay = matches!(self.device, DeviceChoice::Replay(_));
        let device: Box<dyn Device> = match self.device {
            DeviceChoice::Hand(kind, hand) => Box::new(SimulatedHand::new(
                scripted_path(kind, &scene, seconds, self.seed)?,
                hand,
            )),
            DeviceChoice::Scripted(kind) => Box::new(ScriptedDevice::new(scripted_path(
                kind, &scene, seconds, self.seed,
            )?)),
            DeviceChoice::Replay(trace) => Box::new(ReplayDevice::new(trace)),
            DeviceChoice::Vendor(choice) => {
                let opened = crate::run::open(&choice, &scene, seconds)?;
                let device = opened.device;
                vendor = Some((choice, opened.description, opened.clock, opened.report));
                device
            }
        };
        let mapping = match &vendor {
            Some((choice, ..)) => crate::run::mapping(choice, &device.spec(), &scene)?,
            None => haphe::servo::DeviceMapping::IDENTITY,
        };
        let options = ServoOptions::new(self.rate_hz)
            .map_err(|e| anyhow!("{}", e.named("--rate")))?
            .with_proxy(proxy_options(self.max_force)?)
            .with_mapping(mapping);
        let stiffness = scene
            .objects()
            .iter()
            .map(|o| o.material.stiffness())
            .fold(0.0, f64::max);
        let mut servo = Servo::new(device, scene, options)?;
        servo.set_motions(motions);
        let max_force = servo.options().proxy().max_force();

        writeln!(out, "{}", self.title)?;
        writeln!(
            out,
            "scene: {} object(s), {triangles} triangles, surfaces, maps and clear zones built in {:.2} s",
            names.len(),
            self.build_seconds
        )?;
        // A large scene (a grid of copies) lists its first objects only.
        for n in names.iter().take(LISTED_OBJECTS) {
            writeln!(out, "  {n}")?;
        }
        if names.len() > LISTED_OBJECTS {
            writeln!(out, "  ... and {} more", names.len() - LISTED_OBJECTS)?;
        }
        if let Some((choice, description, ..)) = &vendor {
            writeln!(out, "device: {description}")?;
            crate::run::print_mapping(out, choice, &mapping, stiffness)?;
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
        let (stats, stop, setup, interference, standby, dropped) = if realtime {
            let mut options = RealtimeOptions::default()
                .with_spin_seconds(self.spin_seconds)?
                .with_realtime_priority(self.fifo)
                .with_standby_core(self.standby_core);
            let mut clock = None;
            if let Some((choice, _, c, r)) = vendor {
                options = options.with_overrun_budget(choice.overrun_budget);
                clock = c;
                report = Some(r);
                if limit.is_none() {
                    writeln!(out, "running until Ctrl-C")?;
                }
            }
            out.flush()?;
            crate::run::servo_starting();
            let running = match clock {
                Some(clock) => ServoLoop::spawn_clocked(servo, clock, limit, options)?,
                None => ServoLoop::spawn(servo, limit, options)?,
            };
            let run = crate::run::wait(running, &mut on_tick)?;
            let stats = run.servo.stats().clone();
            (
                stats,
                run.stop,
                Some(run.setup),
                Some(run.interference),
                run.standby,
                run.dropped_records,
            )
        } else {
            let stop = servo.run_simulated(ticks, &mut on_tick);
            servo.close();
            (servo.stats().clone(), stop, None, None, None, 0)
        };
        writeln!(out, "\nrun:")?;
        summary::print(
            out,
            &summary,
            &stats,
            &RunInfo {
                rate_hz: self.rate_hz,
                realtime,
                max_force,
                stop,
                setup: setup.as_ref(),
                interference,
                standby,
                dropped_records: dropped,
            },
        )?;
        if let Some(t) = trace {
            let path = t.staged.path().to_owned();
            t.finish()?;
            writeln!(out, "trace: {} ({} ticks)", path.display(), summary.ticks)?;
        }
        if let Some(p) = &self.plot {
            plot::write(p, &self.title, &summary.plot)?;
            writeln!(
                out,
                "plot: {} (force and penetration over time; the path seen from the side)",
                p.display()
            )?;
        }
        let said = report.as_ref().and_then(|r| r());
        if let Some(line) = &said {
            writeln!(out, "{line}")?;
        }
        if summary.contact_ticks == 0 && !replay {
            writeln!(
                out,
                "warning: the device never touched any object (the path stays outside them all)"
            )?;
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
            bail!(
                "the servo missed more deadlines than its overrun budget; zero force was written"
            );
        }
        Ok(())
    }
}
