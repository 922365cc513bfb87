//! The mouse as a device: the page sends the pointer's world point over the WebSocket, the
//! server hands it to the servo thread through a wait-free latest-value buffer, and
//! [`MouseDevice`] reads it every tick. It renders no force (a mouse has no motor); the
//! view shows the force the servo computes.

use glam::DVec3;
use haphe::servo::{Buttons, Device, DeviceError, DeviceFault, DeviceSpec, DeviceState};
use triple_buffer::{Input, Output, triple_buffer};

/// Time constant of the velocity estimate, seconds: the pointer moves in steps at the
/// display rate (~60 Hz), so a raw difference between ticks is zero most ticks and a
/// spike at the others; damping would kick at every step. 20 ms smooths over one frame.
pub const MOUSE_VELOCITY_TAU_S: f64 = 0.02;

/// Largest force the mouse device reports it can render, newtons: the simulated device's,
/// so that a scene feels (and is drawn) as in `haphe simulate`.
pub const MOUSE_MAX_FORCE_N: f64 = haphe::scene::DEFAULT_MAX_FORCE_N;

/// The writing end: the server sets the device point (metres, world frame) here.
#[derive(Debug)]
pub struct MouseHandle {
    input: Input<DVec3>,
    lo: DVec3,
    hi: DVec3,
}

impl MouseHandle {
    /// Sets the device point, clamped to the device's workspace box. A non-finite point
    /// is ignored (returns `false`).
    ///
    /// # Real-time
    /// Wait-free: the servo thread never waits for it, nor it for the servo thread.
    pub fn set(&mut self, p_world: DVec3) -> bool {
        if !p_world.is_finite() {
            return false;
        }
        self.input.write(p_world.clamp(self.lo, self.hi));
        true
    }
}

/// A device whose point is set from outside (the pointer in the view), read every tick
/// through a wait-free triple buffer.
///
/// # Real-time
/// [`read`](Device::read) and [`write_force`](Device::write_force) allocate nothing,
/// take no lock and never panic: a read is one atomic swap.
#[derive(Debug)]
pub struct MouseDevice {
    output: Output<DVec3>,
    spec: DeviceSpec,
    open: bool,
    last: Option<(f64, DVec3)>,
    velocity: DVec3,
}

impl MouseDevice {
    /// A mouse device starting at `start` (metres, world frame; the servo's mapping
    /// should be the identity) whose points are clamped to the box `[lo, hi]`.
    pub fn new(start: DVec3, lo: DVec3, hi: DVec3) -> (MouseDevice, MouseHandle) {
        let (lo, hi) = (lo.min(hi), lo.max(hi));
        let start = if start.is_finite() {
            start.clamp(lo, hi)
        } else {
            0.5 * (lo + hi)
        };
        let (input, output) = triple_buffer(&start);
        let spec = DeviceSpec {
            name: "mouse",
            max_force: MOUSE_MAX_FORCE_N,
            max_stiffness: f64::INFINITY,
            workspace_min: lo,
            workspace_max: hi,
        };
        (
            MouseDevice {
                output,
                spec,
                open: false,
                last: None,
                velocity: DVec3::ZERO,
            },
            MouseHandle { input, lo, hi },
        )
    }
}

impl Device for MouseDevice {
    fn spec(&self) -> DeviceSpec {
        self.spec
    }

    fn open(&mut self) -> Result<(), DeviceError> {
        self.open = true;
        Ok(())
    }

    fn read(&mut self, t: f64) -> Result<DeviceState, DeviceFault> {
        if !self.open {
            return Err(DeviceFault::NotOpen);
        }
        let position = *self.output.read();
        if let Some((t0, p0)) = self.last {
            let dt = t - t0;
            if dt > 0.0 {
                let raw = (position - p0) / dt;
                let a = dt / (MOUSE_VELOCITY_TAU_S + dt);
                self.velocity += a * (raw - self.velocity);
            }
        }
        self.last = Some((t, position));
        Ok(DeviceState {
            position,
            velocity: self.velocity,
            buttons: Buttons(0),
        })
    }

    fn write_force(&mut self, _force: DVec3) -> Result<(), DeviceFault> {
        if self.open {
            Ok(())
        } else {
            Err(DeviceFault::NotOpen)
        }
    }

    fn close(&mut self) {
        self.open = false;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_latest_point_is_read_clamped_and_bad_points_are_ignored() {
        let (mut device, mut handle) =
            MouseDevice::new(DVec3::new(0.0, 0.0, 0.5), DVec3::splat(-1.0), DVec3::ONE);
        device.open().expect("opens");
        assert_eq!(device.read(0.0).expect("read").position.z, 0.5);
        assert!(handle.set(DVec3::new(0.1, 0.2, 0.3)));
        assert!(handle.set(DVec3::new(0.2, 0.2, 9.0)));
        assert!(!handle.set(DVec3::new(f64::NAN, 0.0, 0.0)));
        let s = device.read(0.001).expect("read");
        assert_eq!(s.position, DVec3::new(0.2, 0.2, 1.0));
        assert!(s.velocity.is_finite() && s.velocity.z > 0.0);
        // The velocity decays once the point rests.
        let mut v = s.velocity.length();
        for k in 2..200 {
            let now = device
                .read(f64::from(k) * 1e-3)
                .expect("read")
                .velocity
                .length();
            assert!(now <= v);
            v = now;
        }
        assert!(v < 1e-3 * s.velocity.length());
        device.close();
        assert_eq!(device.read(1.0), Err(DeviceFault::NotOpen));
    }
}
