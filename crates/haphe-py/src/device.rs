//! `haphe.run` with a real device (`dhd`, `openhaptics`, `udp:HOST:PORT`): opened by
//! `haphe-devices`, mapped onto the scene as `haphe run` maps it, and ticked on the wall
//! clock by the servo's real-time thread (OpenHaptics: by the vendor's scheduler).

use std::time::{Duration, Instant};

use haphe::DVec3;
use haphe::servo::{
    DeviceFault, RealtimeOptions, Servo, ServoLoop, ServoOptions, StopReason, TickRecord,
};
use haphe_devices::{
    DEFAULT_OVERRUN_BUDGET, SpecError, UdpOptions, open_device, workspace_mapping,
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

/// What a real device is asked to do.
pub struct DeviceRun {
    /// `dhd`, `openhaptics` or `udp:HOST:PORT`.
    pub spec: String,
    /// Length of the run, seconds.
    pub seconds: f64,
    /// Servo rate, Hz (OpenHaptics: its scheduler's rate).
    pub rate_hz: f64,
    /// World metres per device metre (default: the workspace covers the scene).
    pub scale: Option<f64>,
    /// The world point the centre of the workspace maps to (default: the scene's centre).
    pub centre: Option<DVec3>,
    /// The network device's settings.
    pub udp: UdpOptions,
    /// The button that holds the clutch, if any.
    pub clutch_button: Option<u32>,
    /// The proxy's options (the tool's radius).
    pub proxy: haphe::proxy::ProxyOptions,
}

/// How a run with a real device went.
pub struct DeviceOutcome {
    /// Every tick.
    pub records: Vec<TickRecord>,
    /// How far the clutch moved the device's origin in the world, metres.
    pub offset: DVec3,
    /// The device, as opened.
    pub description: String,
    /// Why the run ended: `finished`, `interrupted`, `overruns` or the fault.
    pub stop: String,
    /// What the device reported of its last fault or its traffic.
    pub report: Option<String>,
}

/// Opens the device, runs it until `seconds` have passed, the device faults or Python
/// is interrupted (Ctrl-C: the servo writes zero force, then `KeyboardInterrupt` is
/// raised), and returns the ticks. Call without the GIL.
pub fn run_device(run: DeviceRun, scene: haphe::scene::Scene) -> PyResult<DeviceOutcome> {
    let opened = open_device(&run.spec, &scene, run.seconds, run.udp).map_err(|e| match e {
        SpecError::Unknown(_) => haphe_error("device", e),
        other => DeviceError::new_err(format!("{}: {other}", run.spec)),
    })?;
    let mapping = workspace_mapping(&opened.device.spec(), &scene, run.scale, run.centre)
        .map_err(param_error)?;
    let options = ServoOptions::new(run.rate_hz)
        .map_err(param_error)?
        .with_proxy(run.proxy)
        .with_mapping(mapping)
        .with_clutch_button(run.clutch_button);
    let servo = Servo::new(opened.device, scene, options)
        .map_err(|e| DeviceError::new_err(format!("{}: {e}", run.spec)))?;
    let realtime = RealtimeOptions::default().with_overrun_budget(Some(DEFAULT_OVERRUN_BUDGET));
    let limit = Some(run.seconds);
    let spawned = match opened.clock {
        Some(clock) => ServoLoop::spawn_clocked(servo, clock, limit, realtime),
        None => ServoLoop::spawn(servo, limit, realtime),
    };
    let mut running = spawned.map_err(|e| DeviceError::new_err(format!("{}: {e}", run.spec)))?;
    let ticks = (run.seconds * run.rate_hz).ceil() as usize + 1;
    let mut records = Vec::with_capacity(ticks.min(10_000_000));
    let mut interrupt = None;
    let mut polled = Instant::now();
    while !running.is_finished() {
        if running.drain(|r| records.push(*r)) == 0 {
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
    let finished = running.stop(|r| records.push(*r));
    let mut finished = finished.map_err(|e| DeviceError::new_err(format!("{}: {e}", run.spec)))?;
    finished.servo.close();
    if let Some(e) = interrupt {
        return Err(e);
    }
    let stop = match finished.stop {
        StopReason::Finished => "finished".to_string(),
        StopReason::Requested => "interrupted".to_string(),
        StopReason::Overruns => "overruns".to_string(),
        StopReason::Fault(DeviceFault::Ended) => "finished".to_string(),
        StopReason::Fault(f) => format!("fault: {f}"),
    };
    Ok(DeviceOutcome {
        offset: finished.servo.mapping().offset() - finished.servo.options().mapping().offset(),
        records,
        description: opened.description,
        stop,
        report: (opened.report)(),
    })
}
