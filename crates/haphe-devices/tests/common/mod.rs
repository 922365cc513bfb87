//! What the device tests share: the stand-in vendor libraries (plain C, built here with
//! the system's C compiler), their test-only symbols, and the reference run of a
//! scripted device pressed into a sphere and released.

#![allow(dead_code)]

use std::path::Path;
use std::sync::{Mutex, MutexGuard};

use haphe::DVec3;
use haphe::scene::{Material, Scene};
use haphe::servo::{PathKind, ScriptedDevice, Servo, ServoOptions, TickRecord, scripted_path};
use libloading::Library;

#[path = "../standin/library.rs"]
mod library;
#[allow(unused_imports)] // Not every test binary builds a stand-in.
pub use library::standin;

/// The stand-ins keep their state in globals, and the variables naming them are the
/// process's: one test at a time.
pub fn serial() -> MutexGuard<'static, ()> {
    static LOCK: Mutex<()> = Mutex::new(());
    LOCK.lock()
        .unwrap_or_else(std::sync::PoisonError::into_inner)
}

/// The stand-in's test-only symbols.
pub struct Standin {
    library: Library,
}

impl Standin {
    /// Opens the stand-in `name` (the same library the device loads: the loader hands
    /// out one copy per process).
    pub fn open(path: &Path) -> Standin {
        // SAFETY: the stand-in is our own C file, without initialisers.
        let library = unsafe { Library::new(path) }.expect("the stand-in loads");
        Standin { library }
    }

    fn f<T: Copy>(&self, name: &str) -> T {
        // SAFETY: each caller names the C type of the stand-in's function.
        unsafe { *self.library.get::<T>(name.as_bytes()).expect(name) }
    }

    pub fn reset(&self, devices: i32) {
        let f: unsafe extern "C" fn(i32) = self.f("standin_reset");
        // SAFETY: plain int argument.
        unsafe { f(devices) }
    }

    /// Position and velocity per sample, in the stand-in's units and frame.
    pub fn set_path(&self, samples: &[[f64; 6]]) {
        let f: unsafe extern "C" fn(*const f64, i32) -> i32 = self.f("standin_set_path");
        // SAFETY: the pointer is to `samples.len()` arrays of six doubles.
        let n = unsafe {
            f(
                samples.as_ptr().cast(),
                i32::try_from(samples.len()).expect("fits"),
            )
        };
        assert_eq!(n as usize, samples.len(), "the stand-in holds every sample");
    }

    /// The buttons held at each sample (a bit mask each; none held beyond them).
    pub fn set_buttons(&self, masks: &[u32]) {
        let f: unsafe extern "C" fn(*const u32, i32) -> i32 = self.f("standin_set_buttons");
        // SAFETY: the pointer is to `masks.len()` unsigned ints.
        let n = unsafe { f(masks.as_ptr(), i32::try_from(masks.len()).expect("fits")) };
        assert_eq!(n as usize, masks.len(), "the stand-in holds every mask");
    }

    pub fn fail_from(&self, call: i32) {
        let f: unsafe extern "C" fn(i32) = self.f("standin_fail_from");
        // SAFETY: plain int argument.
        unsafe { f(call) }
    }

    pub fn set_period_ns(&self, ns: i64) {
        let f: unsafe extern "C" fn(std::ffi::c_long) = self.f("standin_set_period_ns");
        // SAFETY: plain long argument.
        unsafe { f(ns as std::ffi::c_long) }
    }

    /// Every force written, in the stand-in's frame.
    pub fn forces(&self) -> Vec<[f64; 3]> {
        let f: unsafe extern "C" fn(*mut f64, i32) -> i32 = self.f("standin_forces");
        // SAFETY: a null buffer of size 0 only asks for the count.
        let n = unsafe { f(std::ptr::null_mut(), 0) };
        let mut out = vec![[0.0f64; 3]; n as usize];
        // SAFETY: the buffer holds `n` arrays of three doubles.
        unsafe { f(out.as_mut_ptr().cast(), n) };
        out
    }

    pub fn flag(&self, name: &str) -> i32 {
        let f: unsafe extern "C" fn() -> i32 = self.f(name);
        // SAFETY: no arguments.
        unsafe { f() }
    }

    /// Device `i`'s path (of a stand-in with several devices).
    pub fn set_path_of(&self, i: i32, samples: &[[f64; 6]]) {
        let f: unsafe extern "C" fn(i32, *const f64, i32) -> i32 = self.f("standin_set_path_of");
        let n = i32::try_from(samples.len()).expect("fits");
        // SAFETY: the pointer is to `samples.len()` arrays of six doubles.
        let held = unsafe { f(i, samples.as_ptr().cast(), n) };
        assert_eq!(held, n, "the stand-in holds every sample");
    }

    pub fn fail_from_of(&self, i: i32, call: i32) {
        let f: unsafe extern "C" fn(i32, i32) = self.f("standin_fail_from_of");
        // SAFETY: plain int arguments.
        unsafe { f(i, call) }
    }

    /// Every force written to device `i`, in the stand-in's frame.
    pub fn forces_of(&self, i: i32) -> Vec<[f64; 3]> {
        let f: unsafe extern "C" fn(i32, *mut f64, i32) -> i32 = self.f("standin_forces_of");
        // SAFETY: a null buffer of size 0 only asks for the count.
        let n = unsafe { f(i, std::ptr::null_mut(), 0) };
        let mut out = vec![[0.0f64; 3]; n as usize];
        // SAFETY: the buffer holds `n` arrays of three doubles.
        unsafe { f(i, out.as_mut_ptr().cast(), n) };
        out
    }

    /// The flag `name` (`standin_opened_of`, ...) of device `i`.
    pub fn flag_of(&self, name: &str, i: i32) -> i32 {
        let f: unsafe extern "C" fn(i32) -> i32 = self.f(name);
        // SAFETY: a plain int argument.
        unsafe { f(i) }
    }
}

pub fn scene() -> Scene {
    haphe::verify::sphere_scene(2_000, Material::default()).expect("the sphere scene")
}

/// The scripted device pressing into the sphere and releasing, `ticks` ticks at 1 kHz:
/// its records (device point, velocity, force).
pub fn reference(ticks: u64) -> Vec<TickRecord> {
    reference_of(PathKind::Press, ticks)
}

/// The scripted device on the path `kind` over the sphere, `ticks` ticks at 1 kHz: its
/// records (device point, velocity, force).
pub fn reference_of(kind: PathKind, ticks: u64) -> Vec<TickRecord> {
    let scene = scene();
    let path = scripted_path(kind, &scene, ticks as f64 / 1000.0, 1).expect("a path");
    let mut servo =
        Servo::new(ScriptedDevice::new(path), scene, ServoOptions::default()).expect("servo");
    let mut records = Vec::new();
    servo.run_simulated(ticks, |r| records.push(*r));
    let contact = records.iter().filter(|r| r.in_contact()).count();
    assert!(
        contact > ticks as usize / 10,
        "the press touches: {contact}"
    );
    records
}

/// The reference trajectory in haphe's device frame (metres, m/s).
pub fn trajectory(records: &[TickRecord]) -> Vec<[f64; 6]> {
    records
        .iter()
        .map(|r| {
            let (p, v) = (r.hip, r.velocity);
            [p.x, p.y, p.z, v.x, v.y, v.z]
        })
        .collect()
}

/// The same in the HD frame: millimetres, x right (haphe y), y up (haphe z), z towards
/// the user (haphe x).
pub fn trajectory_hd(records: &[TickRecord]) -> Vec<[f64; 6]> {
    records
        .iter()
        .map(|r| {
            let (p, v) = (r.hip * 1000.0, r.velocity * 1000.0);
            [p.y, p.z, p.x, v.y, v.z, v.x]
        })
        .collect()
}

/// A force in the HD frame, in haphe's device frame.
pub fn from_hd(f: [f64; 3]) -> DVec3 {
    DVec3::new(f[2], f[0], f[1])
}
