//! [`Servo`]: the tick function — read the device, move the objects, tick the proxy,
//! write the force — with safe start and fault handling, and a simulation mode that runs
//! it on a virtual clock.

mod clutch;
mod motion;
mod stats;

pub use motion::{MAX_MOTION_AMPLITUDE, Motion, ObjectMotion};
pub use stats::{Histogram, TickStats};

use std::time::Instant;

use glam::DVec3;

use crate::proxy::{Proxy, ProxyOptions, TickStatus};
use crate::query::{Side, classify_point};
use crate::scene::{ObjectKey, Param, ParamError, Scene};
use crate::servo::device::{Buttons, Device, DeviceError, DeviceFault, DeviceMapping, DeviceSpec};
use crate::servo::trace::{Phase, TickRecord};
use clutch::Clutch;

/// Lowest servo rate accepted, Hz (the table of domains: [`Param::RateHz`]).
pub const MIN_RATE_HZ: f64 = Param::RateHz.domain().low;
/// Highest servo rate accepted, Hz.
pub const MAX_RATE_HZ: f64 = Param::RateHz.domain().high;

/// Settings of a [`Servo`], every value within its domain (see [`Param`]).
///
/// Built by [`ServoOptions::new`] (or [`ServoOptions::default`]) and the `with_*`
/// builders; the fields are private, so a struct literal does not build:
///
/// ```compile_fail
/// let o = haphe::servo::ServoOptions { rate_hz: 0.0, ..Default::default() };
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ServoOptions {
    /// Ticks per second, Hz, within [`MIN_RATE_HZ`]..=[`MAX_RATE_HZ`].
    rate_hz: f64,
    /// The proxy's settings; its `max_force` is lowered to the device's if larger.
    pub(crate) proxy: ProxyOptions,
    /// Where the device workspace sits in the world.
    mapping: DeviceMapping,
    /// Safe start: after the device point is found outside every object, the force rises
    /// linearly from zero over this time, seconds (0: at once); the clutch fades the force
    /// out and back in over the same time.
    ramp_seconds: f64,
    /// The button that holds the clutch (bit index of [`Buttons`](crate::servo::Buttons)),
    /// none for no clutch.
    clutch_button: Option<u32>,
}

impl Default for ServoOptions {
    /// 1 kHz, the default proxy, the identity mapping, a 50 ms ramp, no clutch.
    fn default() -> ServoOptions {
        ServoOptions {
            rate_hz: 1000.0,
            proxy: ProxyOptions::default(),
            mapping: DeviceMapping::IDENTITY,
            ramp_seconds: 0.05,
            clutch_button: None,
        }
    }
}

impl ServoOptions {
    /// The default options at `rate_hz` ticks per second.
    ///
    /// # Errors
    /// [`ParamError`] naming `rate_hz` outside [`MIN_RATE_HZ`]..=[`MAX_RATE_HZ`].
    pub fn new(rate_hz: f64) -> Result<ServoOptions, ParamError> {
        Ok(ServoOptions {
            rate_hz: Param::RateHz.check(rate_hz)?,
            ..ServoOptions::default()
        })
    }

    /// The same options with the proxy's settings.
    pub fn with_proxy(self, proxy: ProxyOptions) -> ServoOptions {
        ServoOptions { proxy, ..self }
    }

    /// The same options with the device mapping.
    pub fn with_mapping(self, mapping: DeviceMapping) -> ServoOptions {
        ServoOptions { mapping, ..self }
    }

    /// The same options with the safe start's ramp, seconds.
    ///
    /// # Errors
    /// [`ParamError`] naming `ramp_seconds` outside its domain (0 to 60 s).
    pub fn with_ramp_seconds(self, ramp_seconds: f64) -> Result<ServoOptions, ParamError> {
        Ok(ServoOptions {
            ramp_seconds: Param::RampSeconds.check(ramp_seconds)?,
            ..self
        })
    }

    /// The same options with a clutch held by the device's button `button` (0 is the
    /// first; `None`: no clutch). While it is held, the device moves without moving the
    /// tool, so the hand can re-centre itself in the workspace (the indexing of haptic
    /// toolkits):
    ///
    /// - the tool (the world point given to the proxy) stays where it was at the last tick
    ///   before the press, at rest, and the proxy stays against it;
    /// - the mapping's offset follows the hand (`offset = tool − scale · R · p_device`), so
    ///   at the release it has moved by minus the hand's travel while held, mapped into the
    ///   world, and the tool continues from where it stayed ([`Servo::mapping`]);
    /// - the force fades linearly to zero over [`ramp_seconds`](ServoOptions::ramp_seconds)
    ///   after the press and rises back over the same time after the release: no jolt at
    ///   either, and no force from the hand's motion while held.
    ///
    /// A button beyond the 32 bits of [`Buttons`](crate::servo::Buttons) is never held.
    pub fn with_clutch_button(self, button: Option<u32>) -> ServoOptions {
        ServoOptions {
            clutch_button: button,
            ..self
        }
    }

    /// The button that holds the clutch, if any.
    pub fn clutch_button(&self) -> Option<u32> {
        self.clutch_button
    }

    /// Ticks per second, Hz.
    pub fn rate_hz(&self) -> f64 {
        self.rate_hz
    }

    /// The proxy's settings (after [`Servo::new`], with the maximum force lowered to the
    /// device's).
    pub fn proxy(&self) -> &ProxyOptions {
        &self.proxy
    }

    /// Where the device workspace sits in the world.
    pub fn mapping(&self) -> &DeviceMapping {
        &self.mapping
    }

    /// The safe start's ramp, seconds.
    pub fn ramp_seconds(&self) -> f64 {
        self.ramp_seconds
    }
}

/// Why a servo could not be set up or run.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum ServoError {
    /// The device could not be opened or calibrated.
    #[error(transparent)]
    Device(#[from] DeviceError),
    /// A core asked for does not exist or is not one this process may run on.
    #[error("core {core} is not one this process may run on (it may use {cores:?})")]
    NoSuchCore {
        /// The core asked for.
        core: usize,
        /// The cores this process may run on.
        cores: Vec<usize>,
    },
    /// The servo thread could not be started.
    #[error("cannot start the servo thread: {0}")]
    Spawn(#[source] std::io::Error),
    /// The servo thread panicked (the device was sent zero force as it unwound).
    #[error("the servo thread panicked")]
    Panicked,
}

/// Why a run ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StopReason {
    /// It ran the ticks (or the time) asked for.
    Finished,
    /// It was asked to stop.
    Requested,
    /// The device faulted (a replay that ended reports [`DeviceFault::Ended`]).
    Fault(DeviceFault),
    /// More deadlines were missed than the overrun budget allows (see
    /// [`RealtimeOptions::overrun_budget`](crate::servo::RealtimeOptions::overrun_budget)).
    Overruns,
}

/// The servo's tick function over a device and a scene, with its statistics.
///
/// Each [`tick_at`](Servo::tick_at):
///
/// 1. starts the scene's tick ([`Scene::begin_tick`]: edits from other threads are
///    applied, poses remembered) and moves the scripted objects ([`ObjectMotion`]);
/// 2. reads the device and maps its point into the world;
/// 3. **safe start**: until the device point is outside every solid object, no proxy is
///    placed and the force is zero ([`Phase::Holding`]); then the proxy starts at the
///    device point and the force ramps up over
///    [`ramp_seconds`](ServoOptions::ramp_seconds);
/// 4. ticks the [`Proxy`] and writes its force (mapped to the device frame).
///
/// Any device fault writes zero force and stops the servo ([`Phase::Faulted`]); dropping
/// the servo writes zero force and closes the device.
///
/// # Real-time
/// `tick_at` allocates nothing, takes no lock and never panics (given a device that keeps
/// the [`Device`] contract); its work is bounded by the proxy's caps and the number of
/// objects.
#[derive(Debug)]
pub struct Servo<D: Device> {
    device: D,
    spec: DeviceSpec,
    scene: Scene,
    motions: Vec<ObjectMotion>,
    /// The moving objects' keys, one per motion: poses are set without a lookup by name.
    motion_keys: Vec<ObjectKey>,
    proxy: Proxy,
    options: ServoOptions,
    /// The mapping in force: the options' until the clutch moves its offset.
    mapping: DeviceMapping,
    clutch: Clutch,
    phase: Phase,
    ramp_start: f64,
    stats: TickStats,
    closed: bool,
}

impl<D: Device> Servo<D> {
    /// Opens and calibrates `device` and prepares to render `scene`.
    ///
    /// # Errors
    /// [`ServoError::Device`] when the device cannot be opened or calibrated.
    pub fn new(mut device: D, scene: Scene, options: ServoOptions) -> Result<Servo<D>, ServoError> {
        let spec = device.spec();
        let mut options = options;
        if spec.max_force.is_finite() && spec.max_force >= 0.0 {
            options.proxy.max_force = options.proxy.max_force.min(spec.max_force);
        }
        device.open()?;
        device.calibrate()?;
        Ok(Servo {
            device,
            spec,
            scene,
            motions: Vec::new(),
            motion_keys: Vec::new(),
            proxy: Proxy::new(DVec3::ZERO, options.proxy),
            mapping: options.mapping,
            clutch: Clutch::new(options.clutch_button),
            options,
            phase: Phase::Holding,
            ramp_start: 0.0,
            stats: TickStats::new(),
            closed: false,
        })
    }

    /// Objects that move on their own, by script: their poses are set now, for the time
    /// of the next tick (so that they do not jump at it), and at the start of every tick.
    pub fn set_motions(&mut self, motions: Vec<ObjectMotion>) {
        let t = self.stats.ticks as f64 * self.period();
        self.motion_keys = motions.iter().map(|m| ObjectKey::new(m.id)).collect();
        for (m, key) in motions.iter().zip(&mut self.motion_keys) {
            self.scene.set_pose_keyed(key, m.pose_at(t));
        }
        self.motions = motions;
    }

    /// The mapping in force: [`ServoOptions::mapping`] with its offset moved by every use
    /// of the clutch ([`ServoOptions::with_clutch_button`]).
    pub fn mapping(&self) -> &DeviceMapping {
        &self.mapping
    }

    /// The settings in use (with the proxy's maximum force lowered to the device's).
    pub fn options(&self) -> &ServoOptions {
        &self.options
    }

    /// Seconds between ticks.
    pub fn period(&self) -> f64 {
        1.0 / self.options.rate_hz
    }

    /// The device's specification.
    pub fn spec(&self) -> &DeviceSpec {
        &self.spec
    }

    /// The device.
    pub fn device(&self) -> &D {
        &self.device
    }

    /// The scene.
    pub fn scene(&self) -> &Scene {
        &self.scene
    }

    /// The proxy.
    pub fn proxy(&self) -> &Proxy {
        &self.proxy
    }

    /// Where the servo is in its start-up.
    pub fn phase(&self) -> Phase {
        self.phase
    }

    /// The statistics so far.
    pub fn stats(&self) -> &TickStats {
        &self.stats
    }

    pub(super) fn stats_mut(&mut self) -> &mut TickStats {
        &mut self.stats
    }

    /// Whether the world point `p` is inside a solid object of the scene.
    fn inside_any(&self, p: DVec3) -> bool {
        let objects = self.scene.objects();
        self.scene.near(p, p).indices(objects.len()).any(|i| {
            let o = &objects[i];
            let shape = &*o.shape;
            shape.is_solid()
                && o.pose.to_world(shape.bound_centre()).distance(p) <= shape.bound_radius()
                && classify_point(shape.surface(), shape.map(), o.pose.to_object(p)).0
                    == Side::Inside
        })
    }

    /// Writes zero force and marks the servo faulted.
    fn fault(&mut self, mut record: TickRecord, fault: DeviceFault) -> TickRecord {
        let _ = self.device.write_force(DVec3::ZERO);
        self.phase = Phase::Faulted;
        record.force = DVec3::ZERO;
        record.phase = Phase::Faulted;
        record.fault = Some(fault);
        record
    }

    /// The force's gain at time `t` after the safe start: rising from 0 to 1 over the
    /// ramp, then 1 (the phase turns to running when the ramp is done).
    #[inline]
    fn ramp_gain(&mut self, t: f64) -> f64 {
        if self.phase != Phase::Ramping {
            return 1.0;
        }
        let g = (t - self.ramp_start) / self.options.ramp_seconds;
        if g >= 1.0 {
            self.phase = Phase::Running;
        }
        g.clamp(0.0, 1.0)
    }

    /// One servo tick at the scheduled time `t`, seconds since the start (simulated
    /// devices and scripted motions use it as their clock).
    ///
    /// # Real-time
    /// No allocation, lock or panic; see [`Servo`].
    pub fn tick_at(&mut self, t: f64) -> TickRecord {
        let mut record = TickRecord {
            tick: self.stats.ticks,
            t,
            hip: DVec3::ZERO,
            velocity: DVec3::ZERO,
            proxy: self.proxy.position(),
            force: DVec3::ZERO,
            object: None,
            triangle: None,
            penetration: 0.0,
            status: TickStatus::default(),
            phase: self.phase,
            fault: None,
            buttons: Buttons::default(),
            clutch: false,
        };
        self.stats.ticks += 1;
        if self.phase == Phase::Faulted || self.closed {
            let _ = self.device.write_force(DVec3::ZERO);
            return record;
        }
        self.scene.begin_tick();
        for (m, key) in self.motions.iter().zip(&mut self.motion_keys) {
            self.scene.set_pose_keyed(key, m.pose_at(t));
        }
        let state = match self.device.read(t) {
            Ok(s) => s,
            Err(f) => return self.fault(record, f),
        };
        record.buttons = state.buttons;
        record.clutch = self
            .clutch
            .engage(state.buttons, state.position, &mut self.mapping);
        let mapping = self.mapping;
        let hip = mapping.position_to_world(state.position);
        // Held, the tool is at rest.
        let velocity = if record.clutch {
            DVec3::ZERO
        } else {
            mapping.velocity_to_world(state.velocity)
        };
        self.clutch.remember(hip);
        let fade = self.clutch.gain(self.fade_step());
        record.hip = hip;
        record.velocity = velocity;
        record.proxy = hip;

        if self.phase == Phase::Holding {
            if hip.is_finite() && velocity.is_finite() && !self.inside_any(hip) {
                self.proxy.reset(hip);
                self.ramp_start = t;
                self.phase = if self.options.ramp_seconds > 0.0 {
                    Phase::Ramping
                } else {
                    Phase::Running
                };
            } else {
                self.stats.held_ticks += 1;
            }
        }
        if self.phase != Phase::Holding {
            let out = self.proxy.tick(&self.scene, hip, velocity);
            let gain = self.ramp_gain(t);
            record.phase = self.phase;
            record.proxy = out.proxy;
            record.force = out.force * (gain * fade);
            record.status = out.status;
            if let Some(c) = out.contact {
                record.object = Some(c.id);
                record.triangle = Some(
                    self.scene
                        .objects()
                        .get(c.object)
                        .map_or(c.triangle.0, |o| {
                            o.shape.surface().source_triangle(c.triangle)
                        }),
                );
                record.penetration = c.penetration;
                self.stats.contact_ticks += 1;
            }
            let s = out.status;
            self.stats.clamped_ticks += u64::from(s.force_clamped);
            self.stats.rejected_ticks += u64::from(s.input_rejected);
            self.stats.capped_ticks += u64::from(s.step_cap_hit || s.walk_cap_hit);
        }
        if let Err(f) = self
            .device
            .write_force(mapping.force_to_device(record.force))
        {
            return self.fault(record, f);
        }
        record
    }

    /// Simulation mode: runs up to `ticks` ticks on a virtual clock (tick `k` at
    /// `k / rate` seconds, as fast as the machine goes), timing each tick's computation,
    /// and hands every record to `on_tick`. Stops early at a device fault. Repeated calls
    /// continue the clock.
    ///
    /// The same device, scene and options give the same records, bit for bit.
    ///
    /// # Real-time
    /// The loop itself allocates nothing; `on_tick` runs on this thread between ticks.
    pub fn run_simulated(
        &mut self,
        ticks: u64,
        mut on_tick: impl FnMut(&TickRecord),
    ) -> StopReason {
        let start = Instant::now();
        let period = self.period();
        let first = self.stats.ticks;
        let mut stop = StopReason::Finished;
        for k in first..first.saturating_add(ticks) {
            let began = Instant::now();
            let record = self.tick_at(k as f64 * period);
            let ns = began.elapsed().as_nanos();
            self.stats
                .compute
                .record(u64::try_from(ns).unwrap_or(u64::MAX));
            on_tick(&record);
            if let Some(f) = record.fault {
                stop = StopReason::Fault(f);
                break;
            }
        }
        self.stats.wall_seconds += start.elapsed().as_secs_f64();
        stop
    }

    /// The clutch's fade per tick: the period over the ramp's time (1: at once).
    fn fade_step(&self) -> f64 {
        if self.options.ramp_seconds > 0.0 {
            self.period() / self.options.ramp_seconds
        } else {
            1.0
        }
    }

    /// Writes zero force (ignoring a fault). Called when a run stops.
    pub fn zero_force(&mut self) {
        let _ = self.device.write_force(DVec3::ZERO);
    }

    /// Writes zero force and closes the device; later ticks do nothing but write zero
    /// force. Also done when the servo is dropped.
    pub fn close(&mut self) {
        if !self.closed {
            self.zero_force();
            self.device.close();
            self.closed = true;
        }
    }
}

impl<D: Device> Drop for Servo<D> {
    fn drop(&mut self) {
        self.close();
    }
}
