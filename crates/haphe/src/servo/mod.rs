//! Stage 6 — the servo loop: a fixed-rate tick that reads a [`Device`], moves the scene's
//! scripted objects, ticks the [`Proxy`](crate::proxy::Proxy) and writes the force; the
//! device abstraction; simulated devices that need no hardware; recorded traces; and
//! tick statistics.
//!
//! # The pieces
//!
//! - [`Device`] — what a haptic device offers (open, calibrate, read position, velocity
//!   and buttons, write force, close; a [`DeviceSpec`] with maximum force, stiffness and
//!   workspace), in SI units and the device frame; a [`DeviceMapping`] places the device
//!   workspace in the world (`world_from_device`, with workspace scaling).
//! - Simulated devices: the [`SimulatedHand`] (a mass–spring–damper arm that follows a
//!   [`Trajectory`] and is pushed back by the rendered force), the [`ScriptedDevice`] (follows a
//!   path exactly) and the [`ReplayDevice`] (replays a [`HipTrace`] read from CSV
//!   `t,x,y,z`). [`scripted_path`] builds press, slide, circle, explore and strike paths
//!   over a scene.
//! - [`Servo`] — the tick function with safe start and fault handling, and
//!   [`Servo::run_simulated`], which runs it on a virtual clock as fast as possible.
//! - [`ServoLoop`] — the same tick on a dedicated thread on the wall clock: absolute
//!   deadlines (sleep, then spin), FIFO priority and core pinning where permitted, records
//!   handed out through a wait-free ring, and the [`Interference`] the system reports
//!   (steal time of the servo's core, preemptions of its thread); optionally a standby
//!   thread on a second core that ticks in its place when it is late
//!   ([`RealtimeOptions::standby_core`], [`StandbyReport`]); and, for devices whose SDK
//!   owns the servo thread (OpenHaptics), the same tick clocked by the device's own
//!   callbacks ([`DeviceClock`], [`ServoLoop::spawn_clocked`]). An overrun budget
//!   ([`RealtimeOptions::overrun_budget`]) stops a run with zero force.
//! - [`TickStats`] — compute time and lateness histograms ([`Histogram`], preallocated)
//!   and counters; [`TickRecord`] — one tick, written as CSV by
//!   [`TickRecord::write_csv`] under [`CSV_HEADER`].
//!
//! # Frames and units
//!
//! Devices speak in the device frame; the servo maps the device point into the world
//! (`p_world = offset + scale · R · p_device`) and the world force back (rotated, not
//! scaled). Records are in the world frame. Time is seconds since the loop started.
//!
//! # Real-time
//!
//! A tick allocates nothing, takes no lock, does no I/O and never panics (with a standby
//! thread, the two threads claim each tick with a non-blocking `try_lock` that neither
//! ever waits on; the claim allocates nothing, see `servo/realtime/standby.rs`); the test
//! `tests/servo_alloc.rs` runs the loop with the simulated hand, a moving object and the
//! statistics under a counting allocator. A shape computes each triangle's clear zone on
//! its first contact (a few microseconds, once); call
//! [`Shape::prepare_clear_zones`](crate::scene::Shape::prepare_clear_zones) when a shape
//! is loaded to keep that work off the servo thread.
//!
//! # Examples
//!
//! ```
//! use std::sync::Arc;
//! use haphe::DVec3;
//! use haphe::map::MapOptions;
//! use haphe::mesh::{Surface, SurfaceOptions, shapes::Catalog};
//! use haphe::scene::{Material, ObjectId, Pose, Scene, SceneObject, Shape};
//! use haphe::servo::{HandOptions, PathKind, Servo, ServoOptions, SimulatedHand, scripted_path};
//!
//! let surface = Surface::new(Catalog::Sphere.with_triangles(500), &SurfaceOptions::default())?;
//! let shape = Arc::new(Shape::build(surface, &MapOptions::default())?);
//! let mut scene = Scene::local(1);
//! scene.insert(SceneObject::new(ObjectId(0), shape, Pose::IDENTITY, Material::default()))
//!     .map_err(|(e, _)| e)?;
//! let path = scripted_path(PathKind::Press, &scene, 2.0, 1)?;
//! let hand = SimulatedHand::new(path, HandOptions::default());
//! let mut servo = Servo::new(hand, scene, ServoOptions::default())?;
//! let mut deepest = 0.0f64;
//! servo.run_simulated(2000, |r| deepest = deepest.max(r.penetration));
//! assert!(deepest > 1e-3 && deepest < 5e-3, "{deepest}");
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod device;
mod realtime;
#[cfg(feature = "scene-file")]
pub mod scene_file;
mod simulated;
mod tick;
mod trace;

// The rule's constant, for the command's message; `DeviceSpec::stable_stiffness` says it.
#[doc(hidden)]
pub use device::STIFFNESS_RATED_AT_HZ;
pub use device::{
    Buttons, Device, DeviceError, DeviceFault, DeviceMapping, DeviceSpec, DeviceState,
};
pub use realtime::{
    DeviceClock, Interference, RealtimeOptions, RealtimeRun, RealtimeSetup, ServoLoop,
    StandbyReport,
};
// The command's early check of `--standby-core` (`ServoLoop::spawn` checks the core itself).
#[doc(hidden)]
pub use realtime::check_core;
#[doc(hidden)]
pub use simulated::scene_bounds;
#[doc(hidden)]
pub use simulated::simulated_spec;
pub use simulated::{
    HandOptions, PathKind, ReplayDevice, ScriptedDevice, SimulatedHand, Trajectory,
    TrajectoryError, scripted_path,
};
#[doc(hidden)]
pub use tick::MAX_MOTION_AMPLITUDE;
pub use tick::{
    Histogram, Motion, ObjectMotion, Servo, ServoError, ServoOptions, StopReason, TickStats,
};
#[doc(hidden)]
pub use tick::{MAX_RATE_HZ, MIN_RATE_HZ};
pub use trace::read::{HipTrace, TickTrace, TraceError, TraceRow};
// The status columns' names, for the view's replay.
#[doc(hidden)]
pub use trace::STATUS_NAMES;
pub use trace::{CSV_HEADER, Phase, TickRecord, write_csv_header};
