//! `haphe run`: a haptic session with a real device (Force Dimension, OpenHaptics), the
//! network device, or the simulated hand, on a mesh, a built-in shape or a scene file.
//! The session itself is `haphe simulate`'s ([`crate::session`]).

use std::process::ExitCode;
use std::time::Instant;

use anyhow::bail;
use haphe::DVec3;
use haphe_devices::UdpOptions;

use crate::args::cut::CutArgs;
use crate::args::deform::DeformArgs;
use crate::args::feel::FeelArgs;
use crate::args::{
    ClutchArgs, DEFAULT_OVERRUN_BUDGET, MappingArgs, ModelArgs, OutputArgs, ToolArgs, per_device,
};
use crate::input::model::load_model;
use crate::session::device::VendorChoice;
use crate::session::wait::catch_interrupts;
use crate::session::{DeviceChoice, Session};

/// Arguments of `haphe run`.
#[derive(clap::Args, Debug)]
pub struct Args {
    /// The device: dhd (Force Dimension; dhd:N the one at index N), openhaptics (3D
    /// Systems Touch; openhaptics:NAME the one configured under NAME), udp:HOST:PORT
    /// (listen there for a network device), or hand (the simulated hand; hand:SEED along
    /// the path of that seed). Repeat it for several devices in one scene, each with its
    /// own proxy, mapping and safety, on one servo thread (docs/devices.md, "Two hands").
    #[arg(long, value_name = "SPEC", required = true)]
    device: Vec<String>,
    #[command(flatten)]
    model: ModelArgs,
    #[command(flatten)]
    feel: FeelArgs,
    #[command(flatten)]
    deform: DeformArgs,
    #[command(flatten)]
    cut: CutArgs,
    /// Length of the run, seconds (default: until Ctrl-C; 5 s for the simulated hand).
    #[arg(long)]
    seconds: Option<f64>,
    /// Servo rate, Hz (OpenHaptics: its scheduler's rate, 1000 on a Touch).
    #[arg(long, default_value_t = 1000.0)]
    rate: f64,
    #[command(flatten)]
    mapping: MappingArgs,
    #[command(flatten)]
    clutch: ClutchArgs,
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
    /// The tool's radius, metres: a sphere centred on the proxy, which keeps it that far
    /// from every surface (0, a point, by default; at most 0.5 m, and at most the diagonal
    /// of the box bounding the scene's objects). Overrides a scene file's `tool_radius`.
    /// With several --device, once per device, in their order.
    // Negative numbers are values, so that `-0.001` is refused naming the flag.
    #[arg(long, value_name = "METRES", allow_negative_numbers = true)]
    tool_radius: Vec<f64>,
    /// Largest force rendered, N (lowered to the device's maximum).
    #[arg(long, default_value_t = haphe::scene::DEFAULT_MAX_FORCE_N)]
    max_force: f64,
}

/// Runs `haphe run`.
pub fn run(args: &Args) -> anyhow::Result<ExitCode> {
    // Parsed and paired first: a wrong specification, a device given twice or a mapping
    // missing for one device is reported before the scene is built or a device opened.
    haphe_devices::parse_devices(&args.device)?;
    let mappings = args.mapping.per_device(&args.device)?;
    let tools = per_device("--tool-radius", &args.tool_radius, &args.device)?;
    for &tool_radius in &tools {
        // The flag's domain first; its fit to the scene once the scene is built.
        ToolArgs { tool_radius }.radius(None)?;
    }
    check(args)?;
    let feel = args.feel.check(args.rate)?;
    let deform = args.deform.check(args.rate)?;
    catch_interrupts()?;
    let material = args.model.material()?;
    crate::args::proxy_options(args.max_force)?;
    let started = Instant::now();
    let (mut loaded, what) = load_model(args.model.model(), material)?;
    feel.apply(&mut loaded, args.rate)?;
    let cut = args
        .cut
        .setup(loaded.cutter.take(), args.rate, deform.is_some())?;
    let build_seconds = started.elapsed().as_secs_f64();
    let h = args.udp_workspace;
    let udp = UdpOptions {
        timeout_s: args.udp_timeout,
        workspace: (DVec3::splat(-h), DVec3::splat(h)),
        max_force: args.max_force,
        ..UdpOptions::default()
    };
    let mut choices = Vec::with_capacity(args.device.len());
    for ((spec, (scale, centre)), tool_radius) in args.device.iter().zip(mappings).zip(tools) {
        choices.push(VendorChoice {
            spec: spec.clone(),
            udp,
            scale,
            centre,
            overrun_budget: Some(args.overrun_budget),
            tool_radius: ToolArgs { tool_radius }.radius(loaded.tool_radius.clone())?,
        });
    }
    let session = Session {
        title: format!("haphe run: device {} on {what}", args.device.join(", ")),
        objects: loaded.objects,
        effects: loaded.effects,
        build_seconds,
        rate_hz: args.rate,
        seconds: args.seconds,
        realtime: true,
        spin_seconds: None,
        fifo: !args.normal_priority,
        standby_core: None,
        seed: 1,
        max_force: args.max_force,
        // Each device has its own, in its choice.
        tool_radius: choices[0].tool_radius.clone(),
        device: DeviceChoice::Vendor(choices),
        out: args.output.out.clone(),
        plot: args.output.plot.clone(),
        clutch_button: args.clutch.clutch_button,
        presses: Vec::new(),
        deform,
        cut,
    };
    session.run(&mut std::io::stdout().lock())?;
    Ok(ExitCode::SUCCESS)
}

/// Checks the network device's flags and that a plot is of one device.
fn check(args: &Args) -> anyhow::Result<()> {
    if !(args.udp_timeout.is_finite() && args.udp_timeout > 0.0) {
        bail!("--udp-timeout must be positive, not {}", args.udp_timeout);
    }
    if !(args.udp_workspace.is_finite() && args.udp_workspace > 0.0) {
        bail!(
            "--udp-workspace must be positive, not {}",
            args.udp_workspace
        );
    }
    args.cut.one_device(args.device.len())?;
    if args.device.len() > 1 && args.output.plot.is_some() {
        bail!(
            "--plot draws one device's run; with several --device, write --out and plot each device's columns"
        );
    }
    Ok(())
}
