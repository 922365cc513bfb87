//! `haphe.run` with real devices (`dhd`, `openhaptics`, `udp:HOST:PORT`; one, or several
//! in one scene): opened by `haphe-devices`, each mapped onto the scene as `haphe run`
//! maps it, and ticked on the wall clock by one real-time servo thread (OpenHaptics: by
//! the vendor's scheduler).

use std::time::{Duration, Instant};

use haphe::DVec3;
use haphe::servo::{
    DeviceFault, RealtimeOptions, Servo, ServoLoop, ServoOptions, StopReason, TickRecord,
};
use haphe_devices::{
    DEFAULT_OVERRUN_BUDGET, SpecError, UdpOptions, open_devices, workspace_mapping,
};
use pyo3::create_exception;
use pyo3::exceptions::PyOSError;
use pyo3::prelude::*;

use crate::errors::{haphe_error, param_error};

create_exception!(
    haphe,
    DeviceError,
    PyOSError,
    "A device or its vendor library could not be opened, or the device failed during a run: \
     the message names the library, the variable that selects it and the SDK."
);

/// How often the waiting thread looks for Ctrl-C in Python.
const SIGNAL_POLL: Duration = Duration::from_millis(50);

/// What real devices are asked to do.
pub struct DeviceRun {
    /// `dhd`, `openhaptics`, `udp:HOST:PORT`, ...: one, or several in one scene.
    pub specs: Vec<String>,
    /// Length of the run, seconds.
    pub seconds: f64,
    /// Servo rate, Hz (OpenHaptics: its scheduler's rate).
    pub rate_hz: f64,
    /// Each device's world metres per device metre (default: the workspace covers the
    /// scene).
    pub scales: Vec<Option<f64>>,
    /// The world point each device's workspace centre maps to (default: the scene's
    /// centre).
    pub centres: Vec<Option<DVec3>>,
    /// The network devices' settings.
    pub udp: UdpOptions,
    /// The button that holds the clutch, if any.
    pub clutch_button: Option<u32>,
    /// Each device's proxy options (its tool's radius).
    pub proxies: Vec<haphe::proxy::ProxyOptions>,
}

/// How a run went for one device.
pub struct DeviceOutcome {
    /// Every tick.
    pub records: Vec<TickRecord>,
    /// How far the clutch moved the device's origin in the world, metres.
    pub offset: DVec3,
    /// The device, as opened.
    pub description: String,
    /// Why the run ended: `finished`, `interrupted`, `overruns` or the fault (with
    /// several devices, naming the device that faulted).
    pub stop: String,
    /// What the device reported of its last fault or its traffic.
    pub report: Option<String>,
}

/// A device's specification error as the exception for it: a bad argument (an unknown
/// device, one given twice) or a device that cannot be opened (named by its
/// specification when it is the only one, else by its position too).
fn spec_error(e: SpecError, single: bool) -> PyErr {
    match e {
        SpecError::Unknown(_) | SpecError::Twice { .. } => haphe_error("device", e),
        SpecError::At { spec, error, .. } if single => {
            DeviceError::new_err(format!("{spec}: {error}"))
        }
        other => DeviceError::new_err(other.to_string()),
    }
}

/// Opens the devices, runs them on one servo until `seconds` have passed, a device faults
/// (zero force to every device) or Python is interrupted (Ctrl-C: the servo writes zero
/// force, then `KeyboardInterrupt` is raised), and returns each device's ticks. Call
/// without the GIL.
pub fn run_devices(run: DeviceRun, scene: haphe::scene::Scene) -> PyResult<Vec<DeviceOutcome>> {
    let single = run.specs.len() == 1;
    let opened = open_devices(&run.specs, &scene, run.seconds, run.udp)
        .map_err(|e| spec_error(e, single))?;
    let n = opened.len();
    let mut devices = Vec::with_capacity(n);
    let mut clock = None;
    let mut described = Vec::with_capacity(n);
    for (((o, scale), centre), proxy) in opened
        .into_iter()
        .zip(&run.scales)
        .zip(&run.centres)
        .zip(&run.proxies)
    {
        let mapping =
            workspace_mapping(&o.device.spec(), &scene, *scale, *centre).map_err(param_error)?;
        let options = ServoOptions::new(run.rate_hz)
            .map_err(param_error)?
            .with_proxy(*proxy)
            .with_mapping(mapping)
            .with_clutch_button(run.clutch_button);
        devices.push((o.device, options));
        // One device's clock ticks them all (OpenHaptics' scheduler).
        clock = clock.or(o.clock);
        described.push((o.description, o.report));
    }
    let name = |i: usize| match run.specs.get(i) {
        Some(spec) if n > 1 => format!("device {} ({spec}): ", i + 1),
        Some(spec) => format!("{spec}: "),
        None => String::new(),
    };
    let servo = Servo::with_devices(devices, scene)
        .map_err(|e| DeviceError::new_err(format!("{}{e}", name(0))))?;
    let realtime = RealtimeOptions::default().with_overrun_budget(Some(DEFAULT_OVERRUN_BUDGET));
    let limit = Some(run.seconds);
    let spawned = match clock {
        Some(clock) => ServoLoop::spawn_clocked(servo, clock, limit, realtime),
        None => ServoLoop::spawn(servo, limit, realtime),
    };
    let mut running = spawned.map_err(|e| DeviceError::new_err(format!("{}{e}", name(0))))?;
    let ticks = (run.seconds * run.rate_hz).ceil() as usize + 1;
    let mut records: Vec<Vec<TickRecord>> = (0..n)
        .map(|_| Vec::with_capacity(ticks.min(10_000_000)))
        .collect();
    let mut keep = |r: &TickRecord| {
        if let Some(v) = records.get_mut(r.device as usize) {
            v.push(*r);
        }
    };
    let mut interrupt = None;
    let mut polled = Instant::now();
    while !running.is_finished() {
        if running.drain(&mut keep) == 0 {
            std::thread::sleep(Duration::from_millis(2));
        }
        if polled.elapsed() >= SIGNAL_POLL {
            polled = Instant::now();
            if let Err(e) = Python::attach(|py| py.check_signals()) {
                interrupt = Some(e);
                break;
            }
        }
    }
    let finished = running.stop(&mut keep);
    let mut finished = finished.map_err(|e| DeviceError::new_err(format!("{}{e}", name(0))))?;
    finished.servo.close();
    if let Some(e) = interrupt {
        return Err(e);
    }
    let stop = match finished.stop {
        StopReason::Finished => "finished".to_string(),
        StopReason::Requested => "interrupted".to_string(),
        StopReason::Overruns => "overruns".to_string(),
        StopReason::Fault(DeviceFault::Ended) => "finished".to_string(),
        StopReason::Fault(f) if n > 1 => {
            let culprit = finished.servo.faulted_device().unwrap_or(0);
            format!("fault: {}{f}", name(culprit))
        }
        StopReason::Fault(f) => format!("fault: {f}"),
    };
    let servo = &finished.servo;
    Ok(records
        .into_iter()
        .zip(described)
        .enumerate()
        .map(|(i, (records, (description, report)))| DeviceOutcome {
            offset: match (servo.mapping_of(i), servo.options_of(i)) {
                (Some(m), Some(o)) => m.offset() - o.mapping().offset(),
                _ => DVec3::ZERO,
            },
            records,
            description,
            stop: stop.clone(),
            report: report(),
        })
        .collect())
}
