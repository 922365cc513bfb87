//! OpenHaptics devices (3D Systems Touch, Touch X, Phantom Premium) over the HD API,
//! loaded at run time from `libHD.so`; the HD scheduler owns the servo thread and calls
//! haphe back once per period ([`HdClock`]).
//!
//! Frames and units: the HD API speaks millimetres, mm/s and newtons with x to the
//! right, y up and z towards the user. haphe's device frame for every device is that of
//! Force Dimension (x towards the user, y to the right, z up), so
//! `p_haphe = (z, x, y)_HD / 1000` and `f_HD = (f.y, f.z, f.x)`.

use std::cell::UnsafeCell;
use std::ffi::{CString, c_char, c_double, c_int, c_uint, c_ulong, c_ushort, c_void};
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, AtomicU32, AtomicU64, Ordering};
use std::time::{Duration, Instant};

use glam::DVec3;
use haphe::servo::{
    Buttons, Device, DeviceClock, DeviceError, DeviceFault, DeviceSpec, DeviceState,
};

use crate::library::{HD_LIBRARY, LoadError, Loaded, c_text, symbol};

type Hhd = c_uint;
type HdEnum = c_uint;
type HdSchedulerHandle = c_ulong;
type HdCallback = unsafe extern "C" fn(*mut c_void) -> c_uint;

/// `HDErrorInfo`.
#[repr(C)]
#[derive(Debug, Clone, Copy)]
struct HdErrorInfo {
    error_code: c_uint,
    internal_error_code: c_int,
    h_hd: Hhd,
}

const HD_INVALID_HANDLE: Hhd = 0xFFFF_FFFF;
const HD_CURRENT_BUTTONS: HdEnum = 0x2000;
const HD_CURRENT_POSITION: HdEnum = 0x2050;
const HD_CURRENT_VELOCITY: HdEnum = 0x2051;
const HD_DEVICE_MODEL_TYPE: HdEnum = 0x2501;
const HD_USABLE_WORKSPACE_DIMENSIONS: HdEnum = 0x2551;
const HD_UPDATE_RATE: HdEnum = 0x2600;
const HD_NOMINAL_MAX_STIFFNESS: HdEnum = 0x2602;
const HD_NOMINAL_MAX_CONTINUOUS_FORCE: HdEnum = 0x2604;
const HD_CURRENT_FORCE: HdEnum = 0x2700;
const HD_FORCE_OUTPUT: HdEnum = 0x4000;
const HD_CALLBACK_DONE: c_uint = 0;
const HD_CALLBACK_CONTINUE: c_uint = 1;
const HD_MAX_SCHEDULER_PRIORITY: c_ushort = c_ushort::MAX;

/// How long the HD scheduler may go without calling back before the device counts as
/// gone, seconds: 100 periods at 1 kHz.
pub const HD_STALL_TIMEOUT_S: f64 = 0.1;

/// Millimetres per metre.
const MM: f64 = 1000.0;

/// The HD API functions haphe calls, resolved once when the library is loaded.
pub(crate) struct HdApi {
    init_device: unsafe extern "C" fn(*const c_char) -> Hhd,
    disable_device: unsafe extern "C" fn(Hhd),
    make_current_device: unsafe extern "C" fn(Hhd),
    begin_frame: unsafe extern "C" fn(Hhd),
    end_frame: unsafe extern "C" fn(Hhd),
    enable: unsafe extern "C" fn(HdEnum),
    disable: unsafe extern "C" fn(HdEnum),
    get_doublev: unsafe extern "C" fn(HdEnum, *mut c_double),
    get_integerv: unsafe extern "C" fn(HdEnum, *mut c_int),
    set_doublev: unsafe extern "C" fn(HdEnum, *const c_double),
    get_string: unsafe extern "C" fn(HdEnum) -> *const c_char,
    get_error: unsafe extern "C" fn() -> HdErrorInfo,
    get_error_string: unsafe extern "C" fn(c_uint) -> *const c_char,
    start_scheduler: unsafe extern "C" fn(),
    stop_scheduler: unsafe extern "C" fn(),
    schedule_asynchronous:
        unsafe extern "C" fn(HdCallback, *mut c_void, c_ushort) -> HdSchedulerHandle,
    unschedule: unsafe extern "C" fn(HdSchedulerHandle),
    /// Keeps the functions above valid; dropped last.
    loaded: Loaded,
}

impl HdApi {
    /// Loads `libHD.so` (or `$HAPHE_HD_LIBRARY`) and resolves every function.
    ///
    /// # Errors
    /// A [`LoadError`] naming the library, the variable and the SDK.
    pub(crate) fn load() -> Result<HdApi, LoadError> {
        let l = HD_LIBRARY.load()?;
        let lib = &HD_LIBRARY;
        // SAFETY: each type below is the function's C signature in the HD API headers
        // (`hd.h`, `hdScheduler.h`, `hdDefines.h`: HHD and HDenum are unsigned int,
        // HDSchedulerHandle unsigned long, callbacks return HDCallbackCode), and the
        // pointers live in the same struct as the library, dropped after them.
        unsafe {
            Ok(HdApi {
                init_device: symbol(lib, &l, "hdInitDevice")?,
                disable_device: symbol(lib, &l, "hdDisableDevice")?,
                make_current_device: symbol(lib, &l, "hdMakeCurrentDevice")?,
                begin_frame: symbol(lib, &l, "hdBeginFrame")?,
                end_frame: symbol(lib, &l, "hdEndFrame")?,
                enable: symbol(lib, &l, "hdEnable")?,
                disable: symbol(lib, &l, "hdDisable")?,
                get_doublev: symbol(lib, &l, "hdGetDoublev")?,
                get_integerv: symbol(lib, &l, "hdGetIntegerv")?,
                set_doublev: symbol(lib, &l, "hdSetDoublev")?,
                get_string: symbol(lib, &l, "hdGetString")?,
                get_error: symbol(lib, &l, "hdGetError")?,
                get_error_string: symbol(lib, &l, "hdGetErrorString")?,
                start_scheduler: symbol(lib, &l, "hdStartScheduler")?,
                stop_scheduler: symbol(lib, &l, "hdStopScheduler")?,
                schedule_asynchronous: symbol(lib, &l, "hdScheduleAsynchronous")?,
                unschedule: symbol(lib, &l, "hdUnschedule")?,
                loaded: l,
            })
        }
    }

    /// Where the library was loaded from.
    pub(crate) fn path(&self) -> &str {
        &self.loaded.path
    }

    /// The oldest error on the HD error stack (code 0: none).
    fn error(&self) -> HdErrorInfo {
        // SAFETY: no arguments; returns the struct by value.
        unsafe { (self.get_error)() }
    }

    /// The API's text for an error code.
    pub(crate) fn error_text(&self, code: u32) -> String {
        // SAFETY: any code is accepted; the result is null or a C string, copied at once.
        let text = c_text(unsafe { (self.get_error_string)(code) });
        format!(
            "{} (HD error 0x{code:04x})",
            text.unwrap_or_else(|| "unknown error".into())
        )
    }

    fn doubles<const N: usize>(&self, what: HdEnum) -> [f64; N] {
        let mut v = [0.0f64; N];
        // SAFETY: `what` is a parameter whose value has at most N doubles (the callers
        // ask for 1, 3 or 6 as the API documents for each).
        unsafe { (self.get_doublev)(what, v.as_mut_ptr()) };
        v
    }
}

/// What the device found at open, for reports.
#[derive(Debug, Clone, PartialEq)]
pub struct HdInfo {
    /// `HD_DEVICE_MODEL_TYPE`.
    pub model: String,
    /// `HD_NOMINAL_MAX_CONTINUOUS_FORCE`, newtons.
    pub max_force: f64,
    /// `HD_NOMINAL_MAX_STIFFNESS`, converted to N/m.
    pub max_stiffness: f64,
    /// `HD_USABLE_WORKSPACE_DIMENSIONS`, converted to metres in haphe's device frame.
    pub workspace: (DVec3, DVec3),
    /// `HD_UPDATE_RATE`, Hz.
    pub rate_hz: f64,
}

/// haphe's device frame from the HD frame (and millimetres to metres).
fn from_hd(v: [f64; 3]) -> DVec3 {
    DVec3::new(v[2], v[0], v[1]) / MM
}

/// The HD frame from haphe's device frame, newtons (not scaled).
fn force_to_hd(f: DVec3) -> [f64; 3] {
    [f.y, f.z, f.x]
}

/// An OpenHaptics device. Each servo tick is one HD frame: `read` begins it and reads
/// position, velocity and buttons; `write_force` sets the force and ends it (beginning
/// one when the tick did not read, as after a fault). Run it with the [`HdClock`] from
/// [`HdDevice::clock`], on the HD scheduler's thread.
///
/// # Real-time
/// A few C calls per tick and an atomic store on a fault: no allocation, no lock.
pub struct HdDevice {
    api: Arc<HdApi>,
    /// The configured name to open (`hdInitDevice`), or none for the default device.
    name: Option<CString>,
    handle: Option<Hhd>,
    info: Option<HdInfo>,
    in_frame: bool,
    fault_code: Arc<AtomicU32>,
}

impl HdDevice {
    /// Loads the HD API (not yet opening a device); the device opened will be the
    /// default one (`HD_DEFAULT_DEVICE`).
    ///
    /// # Errors
    /// A [`LoadError`] naming `libHD.so`, `HAPHE_HD_LIBRARY` and the SDK.
    pub fn load() -> Result<HdDevice, LoadError> {
        HdDevice::load_named(None)
    }

    /// Loads the HD API (not yet opening a device); the device opened will be the one
    /// configured under `name` (in Touch Setup; `None`: the default device). Several
    /// devices at once: one `HdDevice` per name, all ticked in the one HD scheduler's
    /// callback (run the servo with any one's [`HdClock`]). A name with a NUL byte
    /// names no device, and opening it fails.
    ///
    /// # Errors
    /// A [`LoadError`] naming `libHD.so`, `HAPHE_HD_LIBRARY` and the SDK.
    pub fn load_named(name: Option<&str>) -> Result<HdDevice, LoadError> {
        Ok(HdDevice {
            api: Arc::new(HdApi::load()?),
            name: name.map(|n| CString::new(n).unwrap_or_default()),
            handle: None,
            info: None,
            in_frame: false,
            fault_code: Arc::new(AtomicU32::new(0)),
        })
    }

    /// What was found at open.
    pub fn info(&self) -> Option<&HdInfo> {
        self.info.as_ref()
    }

    /// The HD scheduler, to clock the servo.
    pub fn clock(&self) -> HdClock {
        HdClock {
            api: Arc::clone(&self.api),
            fault_code: Arc::clone(&self.fault_code),
        }
    }

    /// A report of the last fault, for after a run: the API's text for it.
    pub fn fault_report(&self) -> impl Fn() -> Option<String> + Send + Sync + 'static {
        let api = Arc::clone(&self.api);
        let code = Arc::clone(&self.fault_code);
        move || match code.load(Ordering::Relaxed) {
            0 => None,
            c => Some(format!("OpenHaptics: {}", api.error_text(c))),
        }
    }

    pub(crate) fn api(&self) -> &HdApi {
        &self.api
    }

    /// The first error on the stack as a fault, kept for the report; `None` when clear.
    fn check(&mut self) -> Option<DeviceFault> {
        let e = self.api.error();
        (e.error_code != 0).then(|| {
            self.fault_code.store(e.error_code, Ordering::Relaxed);
            DeviceFault::Hardware(e.error_code)
        })
    }

    fn end_frame(&mut self, h: Hhd) {
        if self.in_frame {
            // SAFETY: `h` is the open device and a frame was begun on it.
            unsafe { (self.api.end_frame)(h) };
            self.in_frame = false;
        }
    }
}

impl Device for HdDevice {
    fn spec(&self) -> DeviceSpec {
        let (min, max) = self
            .info
            .as_ref()
            .map_or((DVec3::splat(-0.05), DVec3::splat(0.05)), |i| i.workspace);
        DeviceSpec {
            name: "OpenHaptics",
            max_force: self.info.as_ref().map_or(f64::INFINITY, |i| i.max_force),
            max_stiffness: self
                .info
                .as_ref()
                .map_or(f64::INFINITY, |i| i.max_stiffness),
            workspace_min: min,
            workspace_max: max,
        }
    }

    fn open(&mut self) -> Result<(), DeviceError> {
        if self.handle.is_some() {
            return Ok(());
        }
        let api = Arc::clone(&self.api);
        let (name, shown) = match &self.name {
            Some(n) => (n.as_ptr(), format!("{:?}", n.to_string_lossy())),
            None => (std::ptr::null(), "HD_DEFAULT_DEVICE".to_string()),
        };
        // SAFETY: a null name is HD_DEFAULT_DEVICE; otherwise a C string kept in `self`.
        let h = unsafe { (api.init_device)(name) };
        let e = api.error();
        if h == HD_INVALID_HANDLE || e.error_code != 0 {
            let configured = if self.name.is_some() {
                "is a Touch configured under that name (Touch_Setup)"
            } else {
                "is the Touch configured (Touch_Setup)"
            };
            return Err(DeviceError::Open(format!(
                "hdInitDevice({shown}) failed: {}; {configured} and its driver running? \
                 (docs/devices.md)",
                api.error_text(e.error_code)
            )));
        }
        // SAFETY: `h` was returned by hdInitDevice; the strings are null or C strings,
        // copied at once; each parameter asked has the number of doubles read.
        let info = unsafe {
            (api.make_current_device)(h);
            let model =
                c_text((api.get_string)(HD_DEVICE_MODEL_TYPE)).unwrap_or_else(|| "unknown".into());
            let ws: [f64; 6] = api.doubles(HD_USABLE_WORKSPACE_DIMENSIONS);
            let (a, b) = (
                from_hd([ws[0], ws[1], ws[2]]),
                from_hd([ws[3], ws[4], ws[5]]),
            );
            let [force] = api.doubles(HD_NOMINAL_MAX_CONTINUOUS_FORCE);
            // N/mm to N/m.
            let [stiffness] = api.doubles(HD_NOMINAL_MAX_STIFFNESS);
            let mut rate: c_int = 0;
            (api.get_integerv)(HD_UPDATE_RATE, &raw mut rate);
            // The force is zero at initialisation; the first tick's frame sets it.
            (api.enable)(HD_FORCE_OUTPUT);
            HdInfo {
                model,
                max_force: if force.is_finite() && force > 0.0 {
                    force
                } else {
                    f64::INFINITY
                },
                max_stiffness: if stiffness.is_finite() && stiffness > 0.0 {
                    stiffness * MM
                } else {
                    f64::INFINITY
                },
                workspace: (a.min(b), a.max(b)),
                rate_hz: if rate > 0 { f64::from(rate) } else { 1000.0 },
            }
        };
        let e = api.error();
        if e.error_code != 0 {
            // SAFETY: `h` is open; disabled once here.
            unsafe { (api.disable_device)(h) };
            return Err(DeviceError::Open(format!(
                "cannot enable force output on {}: {}",
                info.model,
                api.error_text(e.error_code)
            )));
        }
        self.info = Some(info);
        self.handle = Some(h);
        Ok(())
    }

    fn read(&mut self, _t: f64) -> Result<DeviceState, DeviceFault> {
        let Some(h) = self.handle else {
            return Err(DeviceFault::NotOpen);
        };
        let mut buttons: c_int = 0;
        // SAFETY: `h` is open and made current (another device may have been since its
        // last frame); a frame is begun (ended in write_force); position and velocity are
        // three doubles, buttons one int.
        let (p, v) = unsafe {
            (self.api.make_current_device)(h);
            (self.api.begin_frame)(h);
            self.in_frame = true;
            let p: [f64; 3] = self.api.doubles(HD_CURRENT_POSITION);
            let v: [f64; 3] = self.api.doubles(HD_CURRENT_VELOCITY);
            (self.api.get_integerv)(HD_CURRENT_BUTTONS, &raw mut buttons);
            (p, v)
        };
        if let Some(f) = self.check() {
            return Err(f);
        }
        Ok(DeviceState {
            position: from_hd(p),
            velocity: from_hd(v),
            buttons: Buttons(buttons as u32),
        })
    }

    fn write_force(&mut self, force: DVec3) -> Result<(), DeviceFault> {
        let Some(h) = self.handle else {
            return Err(DeviceFault::NotOpen);
        };
        let f = force_to_hd(if force.is_finite() {
            force
        } else {
            DVec3::ZERO
        });
        // SAFETY: `h` is open: made current, since another device's frame may have been
        // begun after this one's (several devices tick in one callback).
        unsafe { (self.api.make_current_device)(h) };
        if !self.in_frame {
            // SAFETY: `h` is open; the frame is ended below.
            unsafe { (self.api.begin_frame)(h) };
            self.in_frame = true;
        }
        // SAFETY: `h` is open, current and in a frame; the force is three doubles.
        unsafe { (self.api.set_doublev)(HD_CURRENT_FORCE, f.as_ptr()) };
        self.end_frame(h);
        match self.check() {
            Some(fault) => Err(fault),
            None => Ok(()),
        }
    }

    fn close(&mut self) {
        if let Some(h) = self.handle.take() {
            let zero = [0.0f64; 3];
            // SAFETY: `h` is open: made current, zero force in a frame, force output off,
            // then the device disabled once.
            unsafe {
                (self.api.make_current_device)(h);
                if !self.in_frame {
                    (self.api.begin_frame)(h);
                }
                (self.api.set_doublev)(HD_CURRENT_FORCE, zero.as_ptr());
                (self.api.end_frame)(h);
                self.in_frame = false;
                (self.api.disable)(HD_FORCE_OUTPUT);
                (self.api.disable_device)(h);
            }
        }
    }
}

impl Drop for HdDevice {
    fn drop(&mut self) {
        self.close();
    }
}

/// The HD scheduler as the servo's clock: the tick runs in an asynchronous callback at
/// the device's rate (1 kHz on a Touch) on the scheduler's thread.
pub struct HdClock {
    api: Arc<HdApi>,
    fault_code: Arc<AtomicU32>,
}

/// What the callback and the waiting thread share.
struct Shared<'a> {
    /// Touched by the scheduler's thread only (one callback at a time).
    tick: UnsafeCell<&'a mut (dyn FnMut() -> bool + Send)>,
    done: AtomicBool,
    panicked: AtomicBool,
    calls: AtomicU64,
}

// SAFETY: `tick` is Send and only the scheduler's thread calls it, one callback at a
// time; the other fields are atomics.
unsafe impl Sync for Shared<'_> {}

/// The asynchronous callback: one servo tick.
unsafe extern "C" fn servo_callback(user: *mut c_void) -> c_uint {
    // SAFETY: `user` is the `Shared` that `HdClock::run` keeps alive until the scheduler
    // is stopped and the callback unscheduled.
    let shared = unsafe { &*(user as *const Shared<'_>) };
    if shared.done.load(Ordering::Acquire) {
        return HD_CALLBACK_DONE;
    }
    // SAFETY: only this thread touches `tick`, and the HD scheduler runs one callback at
    // a time, so this is the only reference.
    let tick = unsafe { &mut *shared.tick.get() };
    let going = std::panic::catch_unwind(std::panic::AssertUnwindSafe(tick)).unwrap_or_else(|_| {
        shared.panicked.store(true, Ordering::Relaxed);
        false
    });
    shared.calls.fetch_add(1, Ordering::Release);
    if going {
        HD_CALLBACK_CONTINUE
    } else {
        shared.done.store(true, Ordering::Release);
        HD_CALLBACK_DONE
    }
}

impl DeviceClock for HdClock {
    fn run(&mut self, tick: &mut (dyn FnMut() -> bool + Send)) -> Result<(), DeviceFault> {
        let shared = Shared {
            tick: UnsafeCell::new(tick),
            done: AtomicBool::new(false),
            panicked: AtomicBool::new(false),
            calls: AtomicU64::new(0),
        };
        let user = (&raw const shared).cast_mut().cast::<c_void>();
        // SAFETY: `shared` outlives the callback: the scheduler is stopped and the
        // callback unscheduled below before `shared` goes out of scope.
        let handle = unsafe {
            let handle =
                (self.api.schedule_asynchronous)(servo_callback, user, HD_MAX_SCHEDULER_PRIORITY);
            (self.api.start_scheduler)();
            handle
        };
        let started = self.api.error();
        let stall = Duration::from_secs_f64(HD_STALL_TIMEOUT_S);
        let mut outcome = Ok(());
        if started.error_code != 0 {
            self.fault_code.store(started.error_code, Ordering::Relaxed);
            outcome = Err(DeviceFault::Hardware(started.error_code));
        } else {
            let mut seen = 0u64;
            let mut last = Instant::now();
            while !shared.done.load(Ordering::Acquire) {
                std::thread::sleep(Duration::from_millis(1));
                let calls = shared.calls.load(Ordering::Acquire);
                if calls != seen {
                    (seen, last) = (calls, Instant::now());
                } else if last.elapsed() > stall {
                    outcome = Err(DeviceFault::Disconnected);
                    break;
                }
            }
        }
        shared.done.store(true, Ordering::Release);
        // SAFETY: stops the scheduler's thread (no callback runs after it returns), then
        // removes the callback: `shared` is no longer used.
        unsafe {
            (self.api.stop_scheduler)();
            (self.api.unschedule)(handle);
        }
        if shared.panicked.load(Ordering::Relaxed) {
            outcome = Err(DeviceFault::Disconnected);
        }
        outcome
    }
}
