//! One device of a [`Servo`](super::Servo): the device itself, its proxy, its mapping into
//! the world, its clutch and its safe start. A servo of several devices (two hands in one
//! scene) holds one of these per device and ticks them all against the same scene.

use glam::DVec3;

use super::clutch::Clutch;
use super::effects::{EffectState, Sensed, effects_force};
use super::options::ServoOptions;
use super::stats::TickStats;
use crate::proxy::{Proxy, TickStatus, clamp_force};
use crate::query::{Side, classify_point};
use crate::scene::Scene;
use crate::servo::device::{
    Buttons, Device, DeviceError, DeviceFault, DeviceMapping, DeviceSpec, DeviceState,
};
use crate::servo::trace::{Phase, TickRecord};

/// A device with everything that is its own in a servo.
#[derive(Debug)]
pub(super) struct Hand<D: Device> {
    pub(super) device: D,
    pub(super) spec: DeviceSpec,
    pub(super) proxy: Proxy,
    /// Its settings, with the proxy's maximum force lowered to the device's.
    pub(super) options: ServoOptions,
    /// The mapping in force: the options' until the clutch moves its offset.
    pub(super) mapping: DeviceMapping,
    clutch: Clutch,
    pub(super) phase: Phase,
    ramp_start: f64,
    /// What the device read at this tick.
    state: DeviceState,
    /// What the scene's effects remember for this device.
    effects: EffectState,
}

impl<D: Device> Hand<D> {
    /// Opens and calibrates `device`, its proxy's maximum force lowered to the device's.
    ///
    /// # Errors
    /// The device's, when it cannot be opened or calibrated.
    pub(super) fn open(mut device: D, options: ServoOptions) -> Result<Hand<D>, DeviceError> {
        let spec = device.spec();
        let mut options = options;
        if spec.max_force.is_finite() && spec.max_force >= 0.0 {
            options.proxy.max_force = options.proxy.max_force.min(spec.max_force);
        }
        device.open()?;
        device.calibrate()?;
        Ok(Hand {
            device,
            spec,
            proxy: Proxy::new(DVec3::ZERO, options.proxy),
            mapping: options.mapping,
            clutch: Clutch::new(options.clutch_button),
            options,
            phase: Phase::Holding,
            ramp_start: 0.0,
            state: DeviceState::default(),
            effects: EffectState::new(),
        })
    }

    /// The record of this device at tick `tick`, time `t`, before it is read: at the
    /// proxy's place, no force.
    #[inline]
    pub(super) fn blank(&self, device: u32, tick: u64, t: f64) -> TickRecord {
        TickRecord {
            tick,
            t,
            device,
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
        }
    }

    /// Reads the device at time `t` and keeps what it read for [`Hand::render`].
    ///
    /// # Errors
    /// The device's fault.
    #[inline]
    pub(super) fn read(&mut self, t: f64) -> Result<(), DeviceFault> {
        self.state = self.device.read(t)?;
        Ok(())
    }

    /// Writes zero force (ignoring a fault) and marks the device faulted, as `record`.
    pub(super) fn stop(&mut self, record: &mut TickRecord) {
        let _ = self.device.write_force(DVec3::ZERO);
        self.phase = Phase::Faulted;
        record.force = DVec3::ZERO;
        record.phase = Phase::Faulted;
    }

    /// Writes the force of `record`, mapped to the device frame.
    ///
    /// # Errors
    /// The device's fault.
    #[inline]
    pub(super) fn write(&mut self, record: &TickRecord) -> Result<(), DeviceFault> {
        self.device
            .write_force(self.mapping.force_to_device(record.force))
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

    /// The clutch's fade per tick: the period over the ramp's time (1: at once).
    fn fade_step(&self) -> f64 {
        if self.options.ramp_seconds > 0.0 {
            (1.0 / self.options.rate_hz) / self.options.ramp_seconds
        } else {
            1.0
        }
    }

    /// From what the device read: the clutch, the device point in the world, the safe
    /// start, the proxy's tick against `scene` and the force (ramped and faded), into
    /// `record`; its counters into `stats`.
    ///
    /// # Real-time
    /// No allocation, lock or panic; bounded by the proxy's caps.
    pub(super) fn render(
        &mut self,
        scene: &Scene,
        t: f64,
        record: &mut TickRecord,
        stats: &mut TickStats,
    ) {
        let state = self.state;
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
            if hip.is_finite() && velocity.is_finite() && !inside_any(scene, hip) {
                self.proxy.reset(hip);
                self.ramp_start = t;
                self.phase = if self.options.ramp_seconds > 0.0 {
                    Phase::Ramping
                } else {
                    Phase::Running
                };
            } else {
                stats.held_ticks += 1;
            }
        }
        if self.phase == Phase::Holding {
            return;
        }
        let mut out = self.proxy.tick(scene, hip, velocity);
        if !scene.effects().is_empty() {
            let max = self.options.proxy.max_force;
            let sensed = Sensed {
                hip,
                velocity,
                t,
                contact: out.contact.as_ref(),
            };
            let sum = out.force + effects_force(scene, &mut self.effects, &sensed, max);
            let (force, clamped) = clamp_force(sum, max);
            out.force = force;
            out.status.force_clamped |= clamped;
        }
        let gain = self.ramp_gain(t);
        record.phase = self.phase;
        record.proxy = out.proxy;
        record.force = out.force * (gain * fade);
        record.status = out.status;
        if let Some(c) = out.contact {
            record.object = Some(c.id);
            record.triangle = Some(scene.objects().get(c.object).map_or(c.triangle.0, |o| {
                o.shape.surface().source_triangle(c.triangle)
            }));
            record.penetration = c.penetration;
            stats.contact_ticks += 1;
        }
        let s = out.status;
        stats.clamped_ticks += u64::from(s.force_clamped);
        stats.rejected_ticks += u64::from(s.input_rejected);
        stats.capped_ticks += u64::from(s.step_cap_hit || s.walk_cap_hit);
    }

    /// Writes zero force and closes the device.
    pub(super) fn close(&mut self) {
        let _ = self.device.write_force(DVec3::ZERO);
        self.device.close();
    }
}

/// Whether the world point `p` is inside a solid object of `scene`.
fn inside_any(scene: &Scene, p: DVec3) -> bool {
    let objects = scene.objects();
    scene.near(p, p).indices(objects.len()).any(|i| {
        let o = &objects[i];
        let shape = &*o.shape;
        shape.is_solid()
            && o.pose.to_world(shape.bound_centre()).distance(p) <= shape.bound_radius()
            && classify_point(shape.surface(), shape.map(), o.pose.to_object(p)).0 == Side::Inside
    })
}
