//! Running a session's servo on its clock: the simulated clock as fast as the machine goes
//! (with a deforming object's deformer in lockstep), or a real-time thread on the wall
//! clock (with the deformer beside it), and what the run left for the summary.

use std::io::Write;

use haphe::DVec3;
use haphe::scene::Scene;
use haphe::servo::{
    Device, Interference, RealtimeOptions, RealtimeSetup, Servo, ServoLoop, StandbyReport,
    StopReason, TickRecord, TickStats,
};

use super::deform::{self, Clock, Plan, Refreshes, Versions};
use super::devices::Vendor;
use super::wait;

/// Which clock the servo runs on.
pub enum How {
    /// The simulated clock, this many ticks.
    Simulated { ticks: u64 },
    /// A real-time thread, for this many seconds (`None`: until Ctrl-C).
    Realtime {
        limit: Option<f64>,
        options: RealtimeOptions,
    },
}

/// What a deformer did: its refreshes, and on the simulated clock the versions the ticks
/// used.
pub type Deformed = Option<(Refreshes, Option<Versions>)>;

/// How the servo ran, whatever the clock.
pub struct Ran {
    pub stats: TickStats,
    pub stop: StopReason,
    pub setup: Option<RealtimeSetup>,
    pub interference: Option<Interference>,
    pub standby: Option<StandbyReport>,
    pub dropped: u64,
    /// What each device did, in order.
    pub devices: Vec<DeviceRan>,
    /// The device whose fault stopped the run.
    pub faulted: Option<usize>,
    /// The version of the first object's shape when the run ended.
    pub last_version: Option<u64>,
}

/// What a device of the run was and did, for its summary.
pub struct DeviceRan {
    /// How far the clutch moved the device's origin in the world, metres.
    pub moved: DVec3,
    /// World metres per device metre.
    pub scale: f64,
    /// The largest force rendered, N (lowered to the device's maximum).
    pub max_force: f64,
}

/// What each device of `servo` was and did.
pub fn devices_ran<D: Device>(servo: &Servo<D>) -> Vec<DeviceRan> {
    (0..servo.devices())
        .filter_map(|i| {
            let (mapping, options) = (servo.mapping_of(i)?, servo.options_of(i)?);
            Some(DeviceRan {
                moved: mapping.offset() - options.mapping().offset(),
                scale: mapping.scale(),
                max_force: options.proxy().max_force(),
            })
        })
        .collect()
}

/// Runs `servo` as `how` says, with the deformer of `deforming` when there is one,
/// handing each record to `on_tick`.
pub fn run(
    out: &mut impl Write,
    mut servo: Servo<Box<dyn Device>>,
    vendors: &mut [Option<Vendor>],
    deforming: Option<Plan>,
    how: How,
    on_tick: &mut impl FnMut(&TickRecord),
) -> anyhow::Result<(Ran, Deformed)> {
    match how {
        How::Realtime { limit, options } => {
            // The deformer starts refreshing now, beside the servo thread about to start.
            let deformer = deforming.map(|p| p.spawn(Clock::Wall, None)).transpose()?;
            let ran = run_realtime(out, servo, vendors, limit, options, on_tick)?;
            let deformed = match deformer {
                Some(d) => Some((d.finish()?, None)),
                None => None,
            };
            Ok((ran, deformed))
        }
        How::Simulated { ticks } => {
            let (stop, deformed) = match deforming {
                Some(plan) => {
                    let mut deformer = plan.spawn(Clock::Simulated, None)?;
                    let (stop, versions) =
                        deform::run_lockstep(&mut servo, &mut deformer, ticks, on_tick)?;
                    (stop, Some((deformer.finish()?, Some(versions))))
                }
                None => (servo.run_simulated(ticks, on_tick), None),
            };
            servo.close();
            let ran = Ran {
                stats: servo.stats().clone(),
                stop,
                setup: None,
                interference: None,
                standby: None,
                dropped: 0,
                devices: devices_ran(&servo),
                faulted: servo.faulted_device(),
                last_version: first_version(servo.scene()),
            };
            Ok((ran, deformed))
        }
    }
}

/// The version of the shape of `scene`'s first object (the one `--deform` deforms).
fn first_version(scene: &Scene) -> Option<u64> {
    scene.objects().first().map(|o| o.shape.version())
}

/// Runs `servo` on a real-time thread (driven by a vendor device's clock when one has
/// it, within the overrun budget) until the run ends or Ctrl-C, handing each record to
/// `on_tick`.
fn run_realtime(
    out: &mut impl Write,
    servo: Servo<Box<dyn Device>>,
    vendors: &mut [Option<Vendor>],
    limit: Option<f64>,
    mut options: RealtimeOptions,
    on_tick: &mut impl FnMut(&TickRecord),
) -> anyhow::Result<Ran> {
    // One device's clock drives the ticks of all (OpenHaptics' scheduler).
    let clock = vendors.iter_mut().flatten().find_map(|v| v.clock.take());
    if let Some(v) = vendors.iter().flatten().next() {
        options = options.with_overrun_budget(v.choice.overrun_budget);
        if limit.is_none() {
            // A network peer can also end the run (the stop flag of its datagram).
            let peer = vendors
                .iter()
                .flatten()
                .any(|v| v.choice.spec.starts_with("udp"));
            let or_peer = if peer { " or the peer sends stop" } else { "" };
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
    Ok(Ran {
        stats: run.servo.stats().clone(),
        stop: run.stop,
        setup: Some(run.setup),
        interference: Some(run.interference),
        standby: run.standby,
        dropped: run.dropped_records,
        devices: devices_ran(&run.servo),
        faulted: run.servo.faulted_device(),
        last_version: first_version(run.servo.scene()),
    })
}
