//! Force Dimension devices (omega, delta, sigma, lambda, and the Novint Falcon through
//! the same SDK) over the SDK's C API (`dhdc.h`), loaded at run time from `libdhd.so`.
//!
//! Frames and units: the SDK speaks metres, m/s and newtons in the device's frame (x
//! towards the user, y to the right, z up), which is the haphe device frame as it is.

use std::ffi::{c_char, c_double, c_int, c_uchar, c_uint};
use std::sync::Arc;
use std::sync::atomic::{AtomicI32, Ordering};

use glam::DVec3;
use haphe::servo::{Buttons, Device, DeviceError, DeviceFault, DeviceSpec, DeviceState};

use crate::library::{DHD_LIBRARY, LoadError, Loaded, c_text, symbol};

/// The device's own ID in calls (`-1` in `dhdc.h` is "the default device"; haphe passes
/// the ID `dhdOpen` returned).
type DeviceId = c_char;

/// The SDK's functions haphe calls, resolved once when the library is loaded.
pub(crate) struct DhdApi {
    get_device_count: unsafe extern "C" fn() -> c_int,
    open: unsafe extern "C" fn() -> c_int,
    open_id: unsafe extern "C" fn(c_char) -> c_int,
    close: unsafe extern "C" fn(DeviceId) -> c_int,
    get_system_name: unsafe extern "C" fn(DeviceId) -> *const c_char,
    enable_force: unsafe extern "C" fn(c_uchar, DeviceId) -> c_int,
    get_position:
        unsafe extern "C" fn(*mut c_double, *mut c_double, *mut c_double, DeviceId) -> c_int,
    get_linear_velocity:
        unsafe extern "C" fn(*mut c_double, *mut c_double, *mut c_double, DeviceId) -> c_int,
    get_button_mask: unsafe extern "C" fn(DeviceId) -> c_uint,
    set_force: unsafe extern "C" fn(c_double, c_double, c_double, DeviceId) -> c_int,
    get_max_force: unsafe extern "C" fn(DeviceId) -> c_double,
    error_get_last: unsafe extern "C" fn() -> c_int,
    error_get_last_str: unsafe extern "C" fn() -> *const c_char,
    error_get_str: unsafe extern "C" fn(c_int) -> *const c_char,
    /// Keeps the functions above valid; dropped last.
    loaded: Loaded,
}

impl DhdApi {
    /// Loads `libdhd.so` (or `$HAPHE_DHD_LIBRARY`) and resolves every function.
    ///
    /// # Errors
    /// A [`LoadError`] naming the library, the variable and the SDK.
    pub(crate) fn load() -> Result<DhdApi, LoadError> {
        let l = DHD_LIBRARY.load()?;
        let lib = &DHD_LIBRARY;
        // SAFETY: each type below is the function's C signature in `dhdc.h` (every
        // `char ID` argument last, `int` results negative on error), and the pointers are
        // kept in the same struct as the library, which is dropped after them.
        unsafe {
            Ok(DhdApi {
                get_device_count: symbol(lib, &l, "dhdGetDeviceCount")?,
                open: symbol(lib, &l, "dhdOpen")?,
                open_id: symbol(lib, &l, "dhdOpenID")?,
                close: symbol(lib, &l, "dhdClose")?,
                get_system_name: symbol(lib, &l, "dhdGetSystemName")?,
                enable_force: symbol(lib, &l, "dhdEnableForce")?,
                get_position: symbol(lib, &l, "dhdGetPosition")?,
                get_linear_velocity: symbol(lib, &l, "dhdGetLinearVelocity")?,
                get_button_mask: symbol(lib, &l, "dhdGetButtonMask")?,
                set_force: symbol(lib, &l, "dhdSetForce")?,
                get_max_force: symbol(lib, &l, "dhdGetMaxForce")?,
                error_get_last: symbol(lib, &l, "dhdErrorGetLast")?,
                error_get_last_str: symbol(lib, &l, "dhdErrorGetLastStr")?,
                error_get_str: symbol(lib, &l, "dhdErrorGetStr")?,
                loaded: l,
            })
        }
    }

    /// Where the library was loaded from.
    pub(crate) fn path(&self) -> &str {
        &self.loaded.path
    }

    /// Devices connected (`dhdGetDeviceCount`), or the SDK's error.
    pub(crate) fn device_count(&self) -> Result<usize, String> {
        // SAFETY: no arguments; the function is resolved from the loaded library.
        let n = unsafe { (self.get_device_count)() };
        usize::try_from(n).map_err(|_| self.last_error())
    }

    /// The SDK's text for its last error on this thread.
    pub(crate) fn last_error(&self) -> String {
        // SAFETY: no arguments; the result is null or a C string, copied at once.
        c_text(unsafe { (self.error_get_last_str)() }).unwrap_or_else(|| "unknown error".into())
    }

    /// The SDK's text for an error code.
    pub(crate) fn error_text(&self, code: i32) -> String {
        // SAFETY: any int is accepted; the result is null or a C string, copied at once.
        c_text(unsafe { (self.error_get_str)(code) }).unwrap_or_else(|| format!("error {code}"))
    }
}

/// What the device found at open, for reports.
#[derive(Debug, Clone, PartialEq)]
pub struct DhdInfo {
    /// `dhdGetSystemName`.
    pub name: String,
    /// `dhdGetMaxForce`, newtons (`None`: the SDK's limit is disabled).
    pub max_force: Option<f64>,
}

/// Workspace haphe assumes for a Force Dimension device, metres, device frame: `dhdc.h`
/// has no workspace query. A 0.1 m cube centred on the device origin lies within the
/// published workspaces of the omega.x (160 × 110 mm), delta.x, sigma.x, lambda.x and
/// the Falcon (about 100 mm); the mapping flags of `haphe run` use more of a larger one.
pub const DHD_WORKSPACE_HALF_M: f64 = 0.05;

/// A Force Dimension device: open (`dhdOpen`, forces enabled), read position, velocity
/// and buttons, write the force, close (zero force, forces disabled, `dhdClose`).
///
/// # Real-time
/// `read` and `write_force` make three or one C calls and keep an error code in an
/// atomic: no allocation, no lock (beyond what the SDK does).
pub struct DhdDevice {
    api: Arc<DhdApi>,
    /// The index to open (`dhdOpenID`), or none for the first available (`dhdOpen`).
    index: Option<u8>,
    id: Option<DeviceId>,
    info: Option<DhdInfo>,
    /// The SDK's error code of the last fault on the servo path (0: none).
    fault_code: Arc<AtomicI32>,
}

impl DhdDevice {
    /// Loads the SDK (not yet opening a device); the device opened will be the first
    /// available (`dhdOpen`).
    ///
    /// # Errors
    /// A [`LoadError`] naming `libdhd.so`, `HAPHE_DHD_LIBRARY` and the SDK.
    pub fn load() -> Result<DhdDevice, LoadError> {
        DhdDevice::load_at(None)
    }

    /// Loads the SDK (not yet opening a device); the device opened will be the one at
    /// `index` among those connected (`dhdOpenID`, 0 the first), or with `None` the first
    /// available (`dhdOpen`). Several devices at once: one `DhdDevice` per index.
    ///
    /// # Errors
    /// A [`LoadError`] naming `libdhd.so`, `HAPHE_DHD_LIBRARY` and the SDK.
    pub fn load_at(index: Option<u8>) -> Result<DhdDevice, LoadError> {
        Ok(DhdDevice {
            api: Arc::new(DhdApi::load()?),
            index,
            id: None,
            info: None,
            fault_code: Arc::new(AtomicI32::new(0)),
        })
    }

    /// What was found at open.
    pub fn info(&self) -> Option<&DhdInfo> {
        self.info.as_ref()
    }

    /// A report of the last fault, for after a run: the SDK's text for it.
    pub fn fault_report(&self) -> impl Fn() -> Option<String> + Send + Sync + 'static {
        let api = Arc::clone(&self.api);
        let code = Arc::clone(&self.fault_code);
        move || match code.load(Ordering::Relaxed) {
            0 => None,
            c => Some(format!(
                "Force Dimension SDK: {} (error {c})",
                api.error_text(c)
            )),
        }
    }

    pub(crate) fn api(&self) -> &DhdApi {
        &self.api
    }

    fn fail(&self) -> DeviceFault {
        // SAFETY: no arguments; reads the SDK's last error code of this thread.
        let code = unsafe { (self.api.error_get_last)() };
        let code = if code == 0 { -1 } else { code };
        self.fault_code.store(code, Ordering::Relaxed);
        DeviceFault::Hardware(code.unsigned_abs())
    }
}

impl Device for DhdDevice {
    fn spec(&self) -> DeviceSpec {
        let h = DHD_WORKSPACE_HALF_M;
        DeviceSpec {
            name: "Force Dimension",
            max_force: self
                .info
                .as_ref()
                .and_then(|i| i.max_force)
                .unwrap_or(f64::INFINITY),
            max_stiffness: f64::INFINITY,
            workspace_min: DVec3::splat(-h),
            workspace_max: DVec3::splat(h),
        }
    }

    fn open(&mut self) -> Result<(), DeviceError> {
        if self.id.is_some() {
            return Ok(());
        }
        let api = &self.api;
        let count = api
            .device_count()
            .map_err(|e| DeviceError::Open(format!("dhdGetDeviceCount failed: {e}")))?;
        if count == 0 {
            return Err(DeviceError::Open(
                "no Force Dimension device is connected (dhdGetDeviceCount is 0): check the \
                 USB cable, the power, and the udev rule (docs/devices.md)"
                    .into(),
            ));
        }
        let (id, call) = match self.index {
            // SAFETY: no arguments; returns the new device's ID or -1.
            None => (unsafe { (api.open)() }, "dhdOpen".to_string()),
            Some(i) if usize::from(i) >= count => {
                return Err(DeviceError::Open(format!(
                    "no Force Dimension device at index {i} (dhd:{i}): {count} connected, \
                     dhd:0 to dhd:{}",
                    count - 1
                )));
            }
            Some(i) => {
                let index = c_char::try_from(i).unwrap_or(c_char::MAX);
                // SAFETY: a plain char index below the device count; returns the new
                // device's ID or -1.
                (unsafe { (api.open_id)(index) }, format!("dhdOpenID({i})"))
            }
        };
        let id = DeviceId::try_from(id)
            .ok()
            .filter(|i| *i >= 0)
            .ok_or_else(|| DeviceError::Open(format!("{call} failed: {}", api.last_error())))?;
        // SAFETY: `id` was returned by dhdOpen; the result is null or a C string, copied.
        let name = c_text(unsafe { (api.get_system_name)(id) }).unwrap_or_else(|| "unknown".into());
        // SAFETY: `id` is open.
        let max = unsafe { (api.get_max_force)(id) };
        // SAFETY: `id` is open; zero force first, then forces on (DHD_ON is 1).
        let enabled =
            unsafe { (api.set_force)(0.0, 0.0, 0.0, id) >= 0 && (api.enable_force)(1, id) >= 0 };
        if !enabled {
            let why = api.last_error();
            // SAFETY: `id` is open; closed once here.
            unsafe { (api.close)(id) };
            return Err(DeviceError::Open(format!(
                "dhdEnableForce failed on {name}: {why}"
            )));
        }
        self.info = Some(DhdInfo {
            name,
            max_force: (max.is_finite() && max > 0.0).then_some(max),
        });
        self.id = Some(id);
        Ok(())
    }

    fn read(&mut self, _t: f64) -> Result<DeviceState, DeviceFault> {
        let Some(id) = self.id else {
            return Err(DeviceFault::NotOpen);
        };
        let (mut p, mut v) = ([0.0f64; 3], [0.0f64; 3]);
        let [px, py, pz] = &mut p;
        let [vx, vy, vz] = &mut v;
        // SAFETY: `id` is open; the pointers are to three distinct local doubles each.
        let ok = unsafe {
            (self.api.get_position)(px, py, pz, id) >= 0
                && (self.api.get_linear_velocity)(vx, vy, vz, id) >= 0
        };
        if !ok {
            return Err(self.fail());
        }
        // SAFETY: `id` is open.
        let buttons = unsafe { (self.api.get_button_mask)(id) };
        Ok(DeviceState {
            position: DVec3::from_array(p),
            velocity: DVec3::from_array(v),
            buttons: Buttons(buttons),
        })
    }

    fn write_force(&mut self, force: DVec3) -> Result<(), DeviceFault> {
        let Some(id) = self.id else {
            return Err(DeviceFault::NotOpen);
        };
        let f = if force.is_finite() {
            force
        } else {
            DVec3::ZERO
        };
        // SAFETY: `id` is open; plain doubles.
        if unsafe { (self.api.set_force)(f.x, f.y, f.z, id) } < 0 {
            return Err(self.fail());
        }
        Ok(())
    }

    fn close(&mut self) {
        if let Some(id) = self.id.take() {
            // SAFETY: `id` is open; zero force, forces off (DHD_OFF is 0), then closed once.
            unsafe {
                (self.api.set_force)(0.0, 0.0, 0.0, id);
                (self.api.enable_force)(0, id);
                (self.api.close)(id);
            }
        }
    }
}

impl Drop for DhdDevice {
    fn drop(&mut self) {
        self.close();
    }
}
