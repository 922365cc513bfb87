//! The servo loop with a device and a per-tick callback.

use std::ffi::{c_char, c_void};

use haphe_lib::servo::{
    Device, HandOptions, PathKind, Servo, ServoOptions, SimulatedHand, TickRecord, scripted_path,
};

use crate::error::{Failure, HapheStatus, guard};
use crate::scene::{HapheScene, scene_mut};
use crate::shape::text;

/// One tick of a servo run, world frame.
#[repr(C)]
#[derive(Debug, Clone, Copy)]
pub struct HapheTickRecord {
    /// Tick number, from 0.
    pub tick: u64,
    /// Scheduled time, seconds since the run started.
    pub t: f64,
    /// The device point, metres.
    pub hip: [f64; 3],
    /// The proxy, metres.
    pub proxy: [f64; 3],
    /// The force written to the device, newtons.
    pub force: [f64; 3],
    /// 1 when in contact.
    pub in_contact: u8,
    /// The triangle under the proxy (face index of the mesh as given), -1 when free.
    pub triangle: i64,
    /// Depth of the device point behind the proxy, metres (0 when free).
    pub penetration: f64,
}

/// Called once per tick with the tick's record (valid for the call only) and the caller's
/// `user` pointer. It runs on the servo's thread between ticks: keep it short, and do not
/// let a C++ exception escape it.
pub type HapheTickCallback =
    Option<extern "C" fn(record: *const HapheTickRecord, user: *mut c_void)>;

/// Opens the device named `device`: `"hand"`, the simulated hand following the scripted
/// `path`. Hardware devices are added here once the device crate provides them.
fn open_device(
    device: &str,
    path: &str,
    scene: &haphe_lib::scene::Scene,
    seconds: f64,
) -> Result<Box<dyn Device>, Failure> {
    match device {
        "hand" => {
            let kind: PathKind = path.parse().map_err(Failure::argument)?;
            let path = scripted_path(kind, scene, seconds, 1)
                .map_err(|e| Failure(HapheStatus::Device, e.to_string()))?;
            Ok(Box::new(SimulatedHand::new(path, HandOptions::default())))
        }
        other => Err(Failure(
            HapheStatus::Device,
            format!(
                "device {other:?} is not available in this build: the devices are \"hand\" (the simulated hand)"
            ),
        )),
    }
}

/// The C record of a tick.
fn record(r: &TickRecord) -> HapheTickRecord {
    HapheTickRecord {
        tick: r.tick,
        t: r.t,
        hip: r.hip.to_array(),
        proxy: r.proxy.to_array(),
        force: r.force.to_array(),
        in_contact: u8::from(r.in_contact()),
        triangle: r.triangle.map_or(-1, i64::from),
        penetration: r.penetration,
    }
}

/// Runs the servo loop over a copy of `scene` for `seconds` at `rate_hz` with the device
/// named `device` (NUL-terminated: `"hand"`, the simulated hand, following the scripted
/// `path`: `"press"`, `"slide"`, `"circle"`, `"explore"` or `"strike"`), on a simulated
/// clock as fast as the machine goes, calling `callback` (may be null) after every tick.
/// Safe start: no force until the device point is outside every solid, then a 50 ms ramp.
/// `*ticks` (may be null) receives the number of ticks run. The scene is only read.
/// Errors: `HAPHE_STATUS_DEVICE` (unknown device, or one that faulted),
/// `HAPHE_STATUS_INVALID_ARGUMENT` (`rate_hz` outside 1 to 40000 Hz, named by
/// `haphe_last_error()`; `seconds` not positive).
#[unsafe(no_mangle)]
pub extern "C" fn haphe_run(
    scene: *mut HapheScene,
    device: *const c_char,
    path: *const c_char,
    seconds: f64,
    rate_hz: f64,
    callback: HapheTickCallback,
    user: *mut c_void,
    ticks: *mut u64,
) -> HapheStatus {
    guard(|| {
        let sc = scene_mut(scene)?;
        let device = text("device", device)?;
        let path = text("path", path)?;
        // The library's table of domains checks the rate.
        let options = ServoOptions::new(rate_hz)?;
        if !(seconds.is_finite() && seconds > 0.0 && seconds * rate_hz <= 1e9) {
            return Err(Failure::argument(format!(
                "seconds {seconds} must be positive"
            )));
        }
        let objects = sc.inner.objects();
        let mut world = haphe_lib::scene::Scene::local(objects.len());
        for o in objects {
            // Cannot fail: room for every object, ids unique.
            let _ = world.insert(o.clone());
        }
        let dev = open_device(device, path, &world, seconds)?;
        let mut servo = Servo::new(dev, world, options)
            .map_err(|e| Failure(HapheStatus::Device, e.to_string()))?;
        let mut count = 0u64;
        let stop = servo.run_simulated((seconds * rate_hz).round() as u64, |r| {
            count += 1;
            if let Some(f) = callback {
                let c = record(r);
                f(&c, user);
            }
        });
        servo.close();
        if !ticks.is_null() {
            // SAFETY: a non-null `ticks` points to a writable u64 (documented).
            unsafe { *ticks = count };
        }
        match stop {
            haphe_lib::servo::StopReason::Fault(f) => Err(Failure(
                HapheStatus::Device,
                format!("the device faulted: {f:?}"),
            )),
            _ => Ok(()),
        }
    })
}
