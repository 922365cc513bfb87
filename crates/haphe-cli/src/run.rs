//! `haphe run`: a haptic session with a real device (Force Dimension, OpenHaptics), the
//! network device, or the simulated hand, on a mesh, a built-in shape or a scene file;
//! and `haphe devices`, which lists what is found. The session itself is
//! `haphe simulate`'s (scene building, summary, CSV trace, plot).

use std::io::Write;
use std::process::ExitCode;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

use anyhow::{Context, anyhow, bail};
use haphe::DVec3;
use haphe::scene::{Param, Scene};
use haphe::servo::{Device, DeviceMapping, DeviceSpec, RealtimeRun, ServoLoop, TickRecord};
use haphe_devices::{OpenedDevice, UdpOptions, list_devices, open_device, workspace_mapping};

use crate::simulate::{DeviceChoice, ModelArgs, OutputArgs, Session, load_model};

/// Length of a run until Ctrl-C, for sizing the plot's sampling only, seconds.
pub const PLOT_SECONDS: f64 = 60.0;

/// Default overrun budget: deadlines a run may miss before it stops with zero force.
pub const DEFAULT_OVERRUN_BUDGET: u64 = haphe_devices::DEFAULT_OVERRUN_BUDGET;

/// Arguments of `haphe run`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// The device: dhd (Force Dimension), openhaptics (3D Systems Touch), udp:HOST:PORT
    /// (listen there for a network device), or hand (the simulated hand).
    #[arg(long, value_name = "SPEC")]
    device: String,
    #[command(flatten)]
    model: ModelArgs,
    /// Length of the run, seconds (default: until Ctrl-C; 5 s for the simulated hand).
    #[arg(long)]
    seconds: Option<f64>,
    /// Servo rate, Hz (OpenHaptics: its scheduler's rate, 1000 on a Touch).
    #[arg(long, default_value_t = 1000.0)]
    rate: f64,
    #[command(flatten)]
    mapping: MappingArgs,
    /// Stop with zero force once the servo has missed this many deadlines.
    #[arg(long, default_value_t = DEFAULT_OVERRUN_BUDGET)]
    overrun_budget: u64,
    /// udp: seconds without a new position before the device faults (zero force, stop).
    #[arg(long, default_value_t = haphe_devices::UDP_TIMEOUT_S)]
    udp_timeout: f64,
    /// udp: the peer's workspace, the half size of a cube centred on its origin, metres.
    #[arg(long, default_value_t = 0.1)]
    udp_workspace: f64,
    /// Keep the normal, time-shared priority instead of asking for FIFO real-time
    /// priority for haphe's servo thread.
    #[arg(long)]
    normal_priority: bool,
    #[command(flatten)]
    output: OutputArgs,
    /// Largest force rendered, N (lowered to the device's maximum).
    #[arg(long, default_value_t = 3.3)]
    max_force: f64,
}

/// How a real device's workspace is mapped onto the scene; shared by `haphe run` and
/// `haphe view`.
#[derive(clap::Args, Debug, Clone, Copy)]
pub struct MappingArgs {
    /// World metres per device metre (default: the device's workspace covers the scene's
    /// bounds).
    #[arg(long)]
    pub scale: Option<f64>,
    /// The world point the centre of the device's workspace maps to, metres, "x,y,z"
    /// (default: the centre of the scene's bounds).
    #[arg(long, value_name = "X,Y,Z", value_parser = parse_point)]
    pub centre: Option<DVec3>,
}

impl MappingArgs {
    /// Checks `--scale` and `--centre` against the library's table of domains.
    ///
    /// # Errors
    /// A value outside its domain, named as its flag.
    pub fn check(&self) -> anyhow::Result<()> {
        if let Some(s) = self.scale {
            Param::Scale
                .check(s)
                .map_err(|e| anyhow!("{}", e.named("--scale")))?;
        }
        if let Some(c) = self.centre {
            Param::Centre
                .check_vector(c.to_array())
                .map_err(|e| anyhow!("{}", e.named("--centre")))?;
        }
        Ok(())
    }
}

/// Arguments of `haphe devices`.
#[derive(clap::Args, Debug)]
pub struct DevicesArgs {}

/// How `haphe run` chose its device.
#[derive(Debug, Clone)]
pub struct VendorChoice {
    /// The specification.
    pub spec: String,
    /// Settings of the network device.
    pub udp: UdpOptions,
    /// `--scale`.
    pub scale: Option<f64>,
    /// `--centre`.
    pub centre: Option<DVec3>,
    /// `--overrun-budget`.
    pub overrun_budget: Option<u64>,
}

fn parse_point(s: &str) -> Result<DVec3, String> {
    let v: Vec<f64> = s
        .split(',')
        .map(|x| x.trim().parse::<f64>().map_err(|e| format!("{x:?}: {e}")))
        .collect::<Result<_, _>>()?;
    match v.as_slice() {
        [x, y, z] if v.iter().all(|c| c.is_finite()) => Ok(DVec3::new(*x, *y, *z)),
        _ => Err(format!("expected three finite numbers x,y,z, not {s:?}")),
    }
}

/// Set by Ctrl-C.
static INTERRUPTED: AtomicBool = AtomicBool::new(false);

/// Set once the servo thread is about to start: from then on Ctrl-C asks it to stop
/// (with zero force); before, Ctrl-C ends the process at once (no force is being
/// rendered while the scene is built or a device is opened).
static SERVO_RUNNING: AtomicBool = AtomicBool::new(false);

/// Called just before the servo thread starts.
pub fn servo_starting() {
    SERVO_RUNNING.store(true, Ordering::SeqCst);
}

/// Whether Ctrl-C was pressed.
pub fn interrupted() -> bool {
    INTERRUPTED.load(Ordering::Relaxed)
}

/// Installs the handler of Ctrl-C (SIGINT) and SIGTERM: before [`servo_starting`] they
/// end the process at once (exit code 130); after, they set [`interrupted`], and the
/// caller stops the servo, which writes zero force before the process exits.
pub fn catch_interrupts() -> anyhow::Result<()> {
    ctrlc::set_handler(|| {
        if SERVO_RUNNING.load(Ordering::SeqCst) {
            INTERRUPTED.store(true, Ordering::Relaxed);
        } else {
            std::process::exit(130);
        }
    })
    .context("cannot install the Ctrl-C handler")
}

/// The device choice of `haphe view`: `mapping`, and `haphe run`'s default network
/// settings and overrun budget.
#[cfg(feature = "view")]
pub fn view_choice(spec: &str, mapping: MappingArgs) -> VendorChoice {
    VendorChoice {
        spec: spec.to_string(),
        udp: UdpOptions::default(),
        scale: mapping.scale,
        centre: mapping.centre,
        overrun_budget: Some(DEFAULT_OVERRUN_BUDGET),
    }
}

/// Runs `haphe run`.
pub fn run(args: &Args) -> anyhow::Result<ExitCode> {
    // Parsed first: a wrong specification is reported before the scene is built.
    args.device.parse::<haphe_devices::DeviceKind>()?;
    args.mapping.check()?;
    if !(args.udp_timeout.is_finite() && args.udp_timeout > 0.0) {
        bail!("--udp-timeout must be positive, not {}", args.udp_timeout);
    }
    if !(args.udp_workspace.is_finite() && args.udp_workspace > 0.0) {
        bail!(
            "--udp-workspace must be positive, not {}",
            args.udp_workspace
        );
    }
    catch_interrupts()?;
    let material = args.model.material()?;
    crate::simulate::proxy_options(args.max_force)?;
    let started = Instant::now();
    let (objects, what) = load_model(args.model.model(), material)?;
    let build_seconds = started.elapsed().as_secs_f64();
    let h = args.udp_workspace;
    let choice = VendorChoice {
        spec: args.device.clone(),
        udp: UdpOptions {
            timeout_s: args.udp_timeout,
            workspace: (DVec3::splat(-h), DVec3::splat(h)),
            max_force: args.max_force,
            ..UdpOptions::default()
        },
        scale: args.mapping.scale,
        centre: args.mapping.centre,
        overrun_budget: Some(args.overrun_budget),
    };
    let session = Session {
        title: format!("haphe run: device {} on {what}", args.device),
        objects,
        build_seconds,
        device: DeviceChoice::Vendor(choice),
        rate_hz: args.rate,
        seconds: args.seconds,
        realtime: true,
        spin_seconds: None,
        fifo: !args.normal_priority,
        standby_core: None,
        seed: 1,
        max_force: args.max_force,
        out: args.output.out.clone(),
        plot: args.output.plot.clone(),
    };
    session.run(&mut std::io::stdout().lock())?;
    Ok(ExitCode::SUCCESS)
}

/// Opens the device of `choice` (for the session).
pub fn open(choice: &VendorChoice, scene: &Scene, seconds: f64) -> anyhow::Result<OpenedDevice> {
    Ok(open_device(&choice.spec, scene, seconds, choice.udp)?)
}

/// The mapping of the run: the device's workspace centred on the scene and scaled to
/// cover its bounds, unless `--scale` / `--centre` say otherwise. The simulated hand
/// moves in the world already.
///
/// # Errors
/// A scale or centre outside its domain, named as its flag.
pub fn mapping(
    choice: &VendorChoice,
    spec: &DeviceSpec,
    scene: &Scene,
) -> anyhow::Result<DeviceMapping> {
    if choice.spec == "hand" {
        return Ok(DeviceMapping::IDENTITY);
    }
    workspace_mapping(spec, scene, choice.scale, choice.centre).map_err(|e| {
        let flag = if e.param() == Param::Scale {
            "--scale"
        } else {
            "--centre"
        };
        anyhow!("{}", e.named(flag))
    })
}

/// Prints the mapping and what it does to stiffness.
pub fn print_mapping(
    out: &mut impl Write,
    choice: &VendorChoice,
    m: &DeviceMapping,
    stiffness: f64,
) -> std::io::Result<()> {
    if choice.spec == "hand" {
        return Ok(());
    }
    let c = m.offset();
    writeln!(
        out,
        "mapping: {:.3} world m per device m, device origin at world ({:.4}, {:.4}, {:.4}) m \
         (set with --scale, --centre); {stiffness:.0} N/m is felt as {:.0} N/m at the device",
        m.scale(),
        c.x,
        c.y,
        c.z,
        m.stiffness_at_device(stiffness)
    )
}

/// Hands records to `f` until the run ends by itself or Ctrl-C stops it (then zero
/// force is written by the servo as it stops).
pub fn wait<D: Device + 'static>(
    mut running: ServoLoop<D>,
    mut f: impl FnMut(&TickRecord),
) -> anyhow::Result<RealtimeRun<D>> {
    while !running.is_finished() && !interrupted() {
        if running.drain(&mut f) == 0 {
            std::thread::sleep(Duration::from_millis(2));
        }
    }
    Ok(running.stop(f)?)
}

/// Runs `haphe devices`.
pub fn devices(_args: &DevicesArgs) -> anyhow::Result<ExitCode> {
    let mut out = std::io::stdout().lock();
    for found in list_devices() {
        writeln!(
            out,
            "{} ({}): {}",
            found.spec,
            found.sdk,
            if found.ready {
                "ready"
            } else {
                "not available"
            }
        )?;
        for line in &found.lines {
            writeln!(out, "  {line}")?;
        }
    }
    writeln!(
        out,
        "udp:HOST:PORT (network device): always available; haphe listens there (docs/devices.md)"
    )?;
    writeln!(out, "hand (the simulated hand): always available")?;
    Ok(ExitCode::SUCCESS)
}
