//! [`Servo`]: the tick function — read the device, move the objects, tick the proxy,
//! write the force — with safe start and fault handling, and a simulation mode that runs
//! it on a virtual clock.

mod clutch;
mod effects;
mod hand;
mod motion;
mod options;
mod stats;

pub use motion::{MAX_MOTION_AMPLITUDE, Motion, ObjectMotion};
pub use options::ServoOptions;
pub use stats::{Histogram, TickStats};

use std::time::Instant;

use glam::DVec3;

use crate::proxy::Proxy;
use crate::scene::{ObjectKey, Param, ParamError, Scene};
use crate::servo::device::{Device, DeviceError, DeviceFault, DeviceMapping, DeviceSpec};
use crate::servo::trace::{Phase, TickRecord};
use hand::Hand;

/// Lowest servo rate accepted, Hz (the table of domains: [`Param::RateHz`]).
pub const MIN_RATE_HZ: f64 = Param::RateHz.domain().low;
/// Highest servo rate accepted, Hz.
pub const MAX_RATE_HZ: f64 = Param::RateHz.domain().high;

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
    /// One of several devices could not be opened or calibrated (those opened before it
    /// were closed again, with zero force).
    #[error("device {device}: {error}")]
    DeviceAt {
        /// Its index among the devices, from 0.
        device: usize,
        /// Why.
        #[source]
        error: DeviceError,
    },
    /// A servo was asked to tick no device, or devices at different rates (one servo
    /// thread ticks every device on the same deadlines).
    #[error("{0}")]
    Devices(&'static str),
    /// An effect of the scene cannot be rendered at the servo's rate (a vibration above
    /// half of it).
    #[error("an effect of the scene: {0}")]
    Effect(#[source] ParamError),
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

/// The servo's tick function over one device or several and a scene, with its
/// statistics.
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
/// # Several devices
///
/// [`Servo::with_devices`] makes one servo of several devices in one scene (two hands):
/// each device has its own [`Proxy`], mapping, clutch, safe start, ramp and force clamp
/// (its own [`ServoOptions`]), and every tick ([`tick_devices`](Servo::tick_devices))
/// reads every device, then ticks every proxy against the same scene, then writes every
/// force, so all of them render the same instant. A fault of any one device writes zero
/// force to every device and stops them all; [`faulted_device`](Servo::faulted_device)
/// names it. The records of a tick come one per device, in the order given, each with its
/// index in [`TickRecord::device`].
///
/// # Real-time
/// `tick_at` allocates nothing, takes no lock and never panics (given a device that keeps
/// the [`Device`] contract); its work is bounded by the proxy's caps, the number of
/// objects and the number of devices.
#[derive(Debug)]
pub struct Servo<D: Device> {
    /// At least one.
    hands: Vec<Hand<D>>,
    scene: Scene,
    motions: Vec<ObjectMotion>,
    /// The moving objects' keys, one per motion: poses are set without a lookup by name.
    motion_keys: Vec<ObjectKey>,
    /// The records of the last tick, one per device (sized once).
    records: Vec<TickRecord>,
    /// The device whose fault stopped the servo.
    faulted: Option<usize>,
    stats: TickStats,
    closed: bool,
}

impl<D: Device> Servo<D> {
    /// Opens and calibrates `device` and prepares to render `scene`.
    ///
    /// # Errors
    /// [`ServoError::Device`] when the device cannot be opened or calibrated;
    /// [`ServoError::Effect`] when an effect of the scene cannot be rendered at the rate.
    pub fn new(device: D, scene: Scene, options: ServoOptions) -> Result<Servo<D>, ServoError> {
        check_effects(&scene, options.rate_hz)?;
        let hand = Hand::open(device, options)?;
        Ok(Servo::of_hands(vec![hand], scene))
    }

    /// Opens and calibrates every device, in order, each with its own options (mapping,
    /// proxy, ramp, clutch), and prepares to render `scene` with all of them on one
    /// servo: see "Several devices" above. The rate is the devices' common rate.
    ///
    /// # Errors
    /// [`ServoError::Devices`] for no device or devices at different rates (nothing is
    /// opened then), or an effect of the scene that cannot be rendered at their rate
    /// ([`ServoError::Effect`]); [`ServoError::DeviceAt`] naming the first device that cannot be
    /// opened or calibrated (the devices opened before it are closed, with zero force).
    pub fn with_devices(
        devices: Vec<(D, ServoOptions)>,
        scene: Scene,
    ) -> Result<Servo<D>, ServoError> {
        let Some(rate) = devices.first().map(|(_, o)| o.rate_hz) else {
            return Err(ServoError::Devices("a servo needs at least one device"));
        };
        if devices.iter().any(|(_, o)| o.rate_hz != rate) {
            return Err(ServoError::Devices(
                "the devices of one servo tick at one rate, and their options give several",
            ));
        }
        check_effects(&scene, rate)?;
        let mut hands: Vec<Hand<D>> = Vec::with_capacity(devices.len());
        for (device, (d, options)) in devices.into_iter().enumerate() {
            match Hand::open(d, options) {
                Ok(hand) => hands.push(hand),
                Err(error) => {
                    for h in &mut hands {
                        h.close();
                    }
                    return Err(ServoError::DeviceAt { device, error });
                }
            }
        }
        Ok(Servo::of_hands(hands, scene))
    }

    fn of_hands(hands: Vec<Hand<D>>, scene: Scene) -> Servo<D> {
        Servo {
            records: vec![TickRecord::default(); hands.len()],
            hands,
            scene,
            motions: Vec::new(),
            motion_keys: Vec::new(),
            faulted: None,
            stats: TickStats::new(),
            closed: false,
        }
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

    /// The first device's.
    fn first(&self) -> &Hand<D> {
        &self.hands[0]
    }

    /// The mapping in force (of the first device; [`Servo::mapping_of`] for another):
    /// [`ServoOptions::mapping`] with its offset moved by every use of the clutch
    /// ([`ServoOptions::with_clutch_button`]).
    pub fn mapping(&self) -> &DeviceMapping {
        &self.first().mapping
    }

    /// The settings in use (of the first device; [`Servo::options_of`] for another),
    /// with the proxy's maximum force lowered to the device's.
    pub fn options(&self) -> &ServoOptions {
        &self.first().options
    }

    /// Seconds between ticks.
    pub fn period(&self) -> f64 {
        1.0 / self.first().options.rate_hz
    }

    /// The (first) device's specification.
    pub fn spec(&self) -> &DeviceSpec {
        &self.first().spec
    }

    /// The (first) device.
    pub fn device(&self) -> &D {
        &self.first().device
    }

    /// The scene.
    pub fn scene(&self) -> &Scene {
        &self.scene
    }

    /// The (first) device's proxy.
    pub fn proxy(&self) -> &Proxy {
        &self.first().proxy
    }

    /// Where the (first) device is in its start-up.
    pub fn phase(&self) -> Phase {
        self.first().phase
    }

    /// The number of devices the servo ticks (1 unless made by [`Servo::with_devices`]).
    pub fn devices(&self) -> usize {
        self.hands.len()
    }

    /// Device `i` (in the order given), if there is one.
    pub fn device_of(&self, i: usize) -> Option<&D> {
        self.hands.get(i).map(|h| &h.device)
    }

    /// Device `i`'s proxy.
    pub fn proxy_of(&self, i: usize) -> Option<&Proxy> {
        self.hands.get(i).map(|h| &h.proxy)
    }

    /// Device `i`'s mapping in force (moved by its clutch).
    pub fn mapping_of(&self, i: usize) -> Option<&DeviceMapping> {
        self.hands.get(i).map(|h| &h.mapping)
    }

    /// Device `i`'s settings in use.
    pub fn options_of(&self, i: usize) -> Option<&ServoOptions> {
        self.hands.get(i).map(|h| &h.options)
    }

    /// Device `i`'s specification.
    pub fn spec_of(&self, i: usize) -> Option<&DeviceSpec> {
        self.hands.get(i).map(|h| &h.spec)
    }

    /// The device whose fault stopped the servo (its index), if one did.
    pub fn faulted_device(&self) -> Option<usize> {
        self.faulted
    }

    /// The statistics so far. With several devices, the counters of what a device did
    /// (`held_ticks`, `contact_ticks`, `clamped_ticks`, ...) add up every device's ticks.
    pub fn stats(&self) -> &TickStats {
        &self.stats
    }

    pub(super) fn stats_mut(&mut self) -> &mut TickStats {
        &mut self.stats
    }

    /// Writes zero force to every device and marks them all faulted, device `device`
    /// having faulted with `fault`.
    fn fault(&mut self, device: usize, fault: DeviceFault) {
        for (h, r) in self.hands.iter_mut().zip(&mut self.records) {
            h.stop(r);
        }
        if let Some(r) = self.records.get_mut(device) {
            r.fault = Some(fault);
        }
        self.faulted = Some(device);
    }

    /// One servo tick at the scheduled time `t`, seconds since the start (simulated
    /// devices and scripted motions use it as their clock); the record of the (first)
    /// device. With several devices, [`tick_devices`](Servo::tick_devices) gives them all.
    ///
    /// # Real-time
    /// No allocation, lock or panic; see [`Servo`].
    pub fn tick_at(&mut self, t: f64) -> TickRecord {
        self.tick_devices(t)[0]
    }

    /// One servo tick of every device at the scheduled time `t` (see [`Servo::tick_at`]):
    /// every device is read, then every proxy ticked, then every force written; the
    /// records, one per device in order.
    ///
    /// # Real-time
    /// No allocation, lock or panic; see [`Servo`].
    pub fn tick_devices(&mut self, t: f64) -> &[TickRecord] {
        let tick = self.stats.ticks;
        for (i, (h, r)) in self.hands.iter().zip(&mut self.records).enumerate() {
            *r = h.blank(u32::try_from(i).unwrap_or(u32::MAX), tick, t);
        }
        self.stats.ticks += 1;
        if self.faulted.is_some() || self.closed || self.hands[0].phase == Phase::Faulted {
            for h in &mut self.hands {
                let _ = h.device.write_force(DVec3::ZERO);
            }
            return &self.records;
        }
        self.scene.begin_tick();
        for (m, key) in self.motions.iter().zip(&mut self.motion_keys) {
            self.scene.set_pose_keyed(key, m.pose_at(t));
        }
        for i in 0..self.hands.len() {
            if let Err(f) = self.hands[i].read(t) {
                self.fault(i, f);
                return &self.records;
            }
        }
        for (h, r) in self.hands.iter_mut().zip(&mut self.records) {
            h.render(&self.scene, t, r, &mut self.stats);
        }
        for i in 0..self.hands.len() {
            if let Err(f) = self.hands[i].write(&self.records[i]) {
                self.fault(i, f);
                return &self.records;
            }
        }
        &self.records
    }

    /// Simulation mode: runs up to `ticks` ticks on a virtual clock (tick `k` at
    /// `k / rate` seconds, as fast as the machine goes), timing each tick's computation,
    /// and hands every record to `on_tick` (with several devices, one per device per
    /// tick, in the devices' order). Stops early at a device fault. Repeated calls
    /// continue the clock.
    ///
    /// The same devices, scene and options give the same records, bit for bit.
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
            self.tick_devices(k as f64 * period);
            let ns = began.elapsed().as_nanos();
            self.stats
                .compute
                .record(u64::try_from(ns).unwrap_or(u64::MAX));
            let mut fault = None;
            for r in &self.records {
                on_tick(r);
                fault = fault.or(r.fault);
            }
            if let Some(f) = fault {
                stop = StopReason::Fault(f);
                break;
            }
        }
        self.stats.wall_seconds += start.elapsed().as_secs_f64();
        stop
    }

    /// Writes zero force to every device (ignoring a fault). Called when a run stops.
    pub fn zero_force(&mut self) {
        for h in &mut self.hands {
            let _ = h.device.write_force(DVec3::ZERO);
        }
    }

    /// Writes zero force to every device and closes them; later ticks do nothing but
    /// write zero force. Also done when the servo is dropped.
    pub fn close(&mut self) {
        if !self.closed {
            self.zero_force();
            for h in &mut self.hands {
                h.device.close();
            }
            self.closed = true;
        }
    }
}

/// Whether every effect of `scene` renders at `rate_hz`.
fn check_effects(scene: &Scene, rate_hz: f64) -> Result<(), ServoError> {
    for e in scene.effects() {
        e.check_rate(rate_hz).map_err(ServoError::Effect)?;
    }
    Ok(())
}

impl<D: Device> Drop for Servo<D> {
    fn drop(&mut self) {
        self.close();
    }
}
