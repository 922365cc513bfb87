//! The servo loop with a device and a per-tick callback.

use std::ffi::{c_char, c_void};

use haphe_lib::servo::{
    Device, HandOptions, PathKind, Servo, ServoOptions, SimulatedHand, TickRecord, scripted_path,
};

use crate::effects::check_rate;
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
    /// The device's buttons held, bit 0 the first.
    pub buttons: u32,
    /// 1 while the clutch is held (`haphe_run_with_buttons`): the tool (`hip`) stays while
    /// the device moves.
    pub clutch: u8,
    /// The device point's velocity, m/s (as the damping and the effects use it).
    pub velocity: [f64; 3],
}

/// A button of the simulated hand held from `from` until `until`, seconds of the run.
#[repr(C)]
#[derive(Debug, Clone, Copy)]
pub struct HapheButtonPress {
    /// The button, 0 (the first) to 31.
    pub button: u32,
    /// When it is pressed, seconds.
    pub from: f64,
    /// When it is released, seconds.
    pub until: f64,
}

/// Called once per tick with the tick's record (valid for the call only) and the caller's
/// `user` pointer. It runs on the servo's thread between ticks: keep it short, and do not
/// let a C++ exception escape it.
pub type HapheTickCallback =
    Option<extern "C" fn(record: *const HapheTickRecord, user: *mut c_void)>;

/// Opens the device named `device`: `"hand"`, the simulated hand following the scripted
/// `path`, holding the buttons of `presses`. Hardware devices are added here once the
/// device crate provides them.
fn open_device(
    device: &str,
    path: &str,
    scene: &haphe_lib::scene::Scene,
    seconds: f64,
    presses: &[HapheButtonPress],
) -> Result<Box<dyn Device>, Failure> {
    match device {
        "hand" => {
            let kind: PathKind = path.parse().map_err(Failure::argument)?;
            let path = scripted_path(kind, scene, seconds, 1)
                .map_err(|e| Failure(HapheStatus::Device, e.to_string()))?;
            let mut hand = SimulatedHand::new(path, HandOptions::default());
            for p in presses {
                hand = hand
                    .press(p.button, p.from, p.until)
                    .map_err(|e| Failure::argument(format!("presses: {e}")))?;
            }
            Ok(Box::new(hand))
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
        buttons: r.buttons.0,
        clutch: u8::from(r.clutch),
        velocity: r.velocity.to_array(),
    }
}

/// Runs the servo loop over a copy of `scene` for `seconds` at `rate_hz` with the device
/// named `device` (NUL-terminated: `"hand"`, the simulated hand, following the scripted
/// `path`: `"press"`, `"slide"`, `"circle"`, `"explore"` or `"strike"`), on a simulated
/// clock as fast as the machine goes, calling `callback` (may be null) after every tick.
/// Safe start: no force until the device point is outside every solid, then a 50 ms ramp.
/// The scene's textures and effects are rendered. `*ticks` (may be null) receives the
/// number of ticks run. The scene is only read.
/// Errors: `HAPHE_STATUS_DEVICE` (unknown device, or one that faulted),
/// `HAPHE_STATUS_INVALID_ARGUMENT` (`rate_hz` outside 1 to 40000 Hz, named by
/// `haphe_last_error()`; `seconds` not positive; a vibration effect above half `rate_hz`,
/// `haphe_last_error()` naming `effect` and its specification).
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
    haphe_run_with_buttons(
        scene,
        device,
        path,
        seconds,
        rate_hz,
        -1,
        std::ptr::null(),
        0,
        callback,
        user,
        ticks,
    )
}

/// `haphe_run` with buttons: `clutch_button` (0 to 31; -1 for none) is a clutch, and the
/// simulated hand holds the buttons of `presses` (`press_count` of them; may be null when
/// 0). While the clutch is held the device moves without moving the tool: the tool (the
/// records' `hip`) stays where it was, the force fades out over 50 ms and back in after
/// the release, and the tool then continues from where it stayed (the device's origin
/// moved by minus the hand's travel). The records carry the buttons and the clutch.
/// Errors: those of `haphe_run`, and `HAPHE_STATUS_INVALID_ARGUMENT` for a clutch button
/// outside -1 to 31 or a press whose button is beyond 31 or whose times are not finite
/// and increasing.
#[unsafe(no_mangle)]
#[allow(clippy::too_many_arguments)]
pub extern "C" fn haphe_run_with_buttons(
    scene: *mut HapheScene,
    device: *const c_char,
    path: *const c_char,
    seconds: f64,
    rate_hz: f64,
    clutch_button: i32,
    presses: *const HapheButtonPress,
    press_count: usize,
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
        let clutch = match clutch_button {
            -1 => None,
            0..=31 => Some(clutch_button as u32),
            other => {
                return Err(Failure::argument(format!(
                    "clutch_button {other} must be a button from 0 to 31, or -1 for none"
                )));
            }
        };
        let options = options.with_clutch_button(clutch);
        let presses: &[HapheButtonPress] = match (presses.is_null(), press_count) {
            (_, 0) => &[],
            (true, _) => return Err(Failure::argument("presses is null")),
            // SAFETY: a non-null `presses` points to `press_count` presses (documented).
            (false, n) => unsafe { std::slice::from_raw_parts(presses, n) },
        };
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
        for e in sc.inner.effects() {
            // Cannot fail: room for as many effects as the scene holds.
            let _ = world.add_effect(*e);
        }
        check_rate(&world, &sc.effects, rate_hz)?;
        let dev = open_device(device, path, &world, seconds, presses)?;
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
