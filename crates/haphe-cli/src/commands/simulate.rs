//! `haphe simulate`: a haptic session without hardware — a simulated hand (or a scripted
//! device, or a replayed trace) on a mesh, a built-in shape or a scene file, ticked by the
//! servo loop on a virtual clock or on the wall clock; a per-tick CSV trace, a summary and
//! a plot. The session itself is [`crate::session`]'s.

use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

use anyhow::anyhow;
use haphe::servo::{HandOptions, HipTrace, PathKind, ServoOptions};

use crate::args::cut::CutArgs;
use crate::args::deform::DeformArgs;
use crate::args::feel::FeelArgs;
use crate::args::{ClutchArgs, ModelArgs, OutputArgs, ToolArgs, proxy_options, spin};
use crate::input::files::{self, read_input};
use crate::input::model::load_model;
use crate::output::check_outputs;
use crate::session::{DeviceChoice, Session};

/// Arguments of `haphe simulate`.
#[derive(clap::Args, Debug)]
#[command(allow_negative_numbers = true)]
pub struct Args {
    #[command(flatten)]
    model: ModelArgs,
    #[command(flatten)]
    feel: FeelArgs,
    #[command(flatten)]
    deform: DeformArgs,
    #[command(flatten)]
    cut: CutArgs,
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
    #[command(flatten)]
    tool: ToolArgs,
    #[command(flatten)]
    clutch: ClutchArgs,
    /// Hold button N of the simulated device from FROM until UNTIL seconds of the run
    /// (repeatable): for --clutch-button, or to record button states.
    #[arg(long, value_name = "N@FROM-UNTIL", value_parser = parse_press)]
    press: Vec<(u32, f64, f64)>,
    /// Seed of the explore path.
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Largest force rendered, N (the simulated device's maximum is the default).
    #[arg(long, default_value_t = haphe::scene::DEFAULT_MAX_FORCE_N)]
    max_force: f64,
}

/// Parses a `--press` value, `N@FROM-UNTIL`: button N (0 to 31) held from FROM until
/// UNTIL seconds, finite, FROM before UNTIL.
fn parse_press(s: &str) -> Result<(u32, f64, f64), String> {
    let form = || format!("expected N@FROM-UNTIL (button 0 to 31, seconds), not {s:?}");
    let (button, times) = s.split_once('@').ok_or_else(form)?;
    let (from, until) = times.split_once('-').ok_or_else(form)?;
    let button: u32 = button.trim().parse().map_err(|_| form())?;
    let from: f64 = from.trim().parse().map_err(|_| form())?;
    let until: f64 = until.trim().parse().map_err(|_| form())?;
    if button >= 32 || !from.is_finite() || !until.is_finite() || from >= until {
        return Err(form());
    }
    Ok((button, from, until))
}

/// Runs `haphe simulate`.
pub fn run(args: &Args) -> anyhow::Result<ExitCode> {
    // The library's table of domains checks every number, named as its flag.
    ServoOptions::new(args.rate).map_err(|e| anyhow!("{}", e.named("--rate")))?;
    let feel = args.feel.check(args.rate)?;
    let deform = args.deform.check(args.rate)?;
    let outputs: Vec<&Path> = [&args.output.out, &args.output.plot, &args.cut.save_volume]
        .into_iter()
        .flatten()
        .map(PathBuf::as_path)
        .collect();
    let inputs: Vec<&Path> = [
        &args.model.mesh,
        &args.model.scene,
        &args.model.volume.volume,
        &args.replay,
    ]
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
    // The flag's domain first; its fit to the scene once the scene is built.
    args.tool.radius(None)?;
    let (mut loaded, what) = load_model(args.model.model(), material)?;
    feel.apply(&mut loaded, args.rate)?;
    let cut = args
        .cut
        .setup(loaded.cutter.take(), args.rate, deform.is_some())?;
    let build_seconds = started.elapsed().as_secs_f64();
    let device = if let Some(file) = &args.replay {
        let name = file.display().to_string();
        let bytes = read_input(file, files::TRACE)?;
        DeviceChoice::Replay(HipTrace::read(&name, bytes.as_slice())?)
    } else if args.no_hand && !args.hand {
        DeviceChoice::Scripted(args.path)
    } else {
        DeviceChoice::Hand(args.path, HandOptions::default())
    };
    let session = Session {
        title: format!("haphe simulate: {} on {what}", device.describe()),
        objects: loaded.objects,
        effects: loaded.effects,
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
        tool_radius: args.tool.radius(loaded.tool_radius)?,
        out: args.output.out.clone(),
        plot: args.output.plot.clone(),
        clutch_button: args.clutch.clutch_button,
        presses: args.press.clone(),
        deform,
        cut,
    };
    session.run(&mut std::io::stdout().lock())?;
    Ok(ExitCode::SUCCESS)
}
