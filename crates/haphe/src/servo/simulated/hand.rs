//! The simulated hand: a mass–spring–damper arm that tries to follow a path and is pushed
//! back by the rendered force, so that contact, resting, sliding and friction behave as
//! with a person holding the device.

use glam::DVec3;

use super::behaviour::Simulated;
use super::presses::Presses;
use super::spec::simulated_spec;
use super::trajectory::Trajectory;
use crate::servo::device::{DeviceFault, DeviceSpec};

/// Longest integration step of the hand, seconds: the arm is integrated in sub-steps of
/// at most this between two reads, so its motion does not depend on the servo rate.
pub(crate) const HAND_MAX_STEP_S: f64 = 5e-5;
/// Most sub-steps in one read: a read after a long pause (more than
/// `HAND_MAX_SUBSTEPS · HAND_MAX_STEP_S` = 0.1 s) integrates with longer steps.
pub(crate) const HAND_MAX_SUBSTEPS: usize = 2000;

/// The arm's mechanical impedance and a constant push.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HandOptions {
    /// Moving mass of hand, stylus and device, kg.
    pub mass: f64,
    /// Stiffness of the grip toward the path's target, N/m (a relaxed human arm holds a
    /// stylus with a few hundred N/m).
    pub stiffness: f64,
    /// Damping toward the path's velocity, N·s/m.
    pub damping: f64,
    /// Damping against the arm's own velocity, N·s/m (muscle and joint viscosity), which
    /// keeps the arm passive even with no grip stiffness.
    pub viscosity: f64,
    /// A constant force the hand adds, newtons, device frame (for example a steady push
    /// onto a surface).
    pub push: DVec3,
}

impl Default for HandOptions {
    /// 0.15 kg, 300 N/m, 4 N·s/m tracking damping, 1 N·s/m viscosity, no push: a light,
    /// relaxed grip.
    fn default() -> HandOptions {
        HandOptions {
            mass: 0.15,
            stiffness: 300.0,
            damping: 4.0,
            viscosity: 1.0,
            push: DVec3::ZERO,
        }
    }
}

/// A simulated hand holding a simulated device.
///
/// The end point is a point mass `m` pulled toward the path's target by a spring–damper,
/// slowed by viscosity, pushed by a constant force and by the force the servo loop
/// writes (held constant between writes, as a real device's amplifier does):
///
/// `m a = k (target − x) + b (v_target − v) − c v + push + F_rendered`
///
/// integrated with semi-implicit Euler in steps of at most 50 µs. Reads give
/// the state at the requested time, so a run on the virtual clock is exactly repeatable.
#[derive(Debug, Clone)]
pub struct SimulatedHand {
    path: Trajectory,
    options: HandOptions,
    pub(super) spec: DeviceSpec,
    position: DVec3,
    velocity: DVec3,
    force: DVec3,
    time: f64,
    pub(super) open: bool,
    pub(super) presses: Presses,
}

impl SimulatedHand {
    /// A hand at rest at the path's start (device frame), which then tries to follow it.
    pub fn new(path: Trajectory, options: HandOptions) -> SimulatedHand {
        let (position, _) = path.sample(0.0);
        SimulatedHand {
            path,
            options,
            spec: simulated_spec(),
            position,
            velocity: DVec3::ZERO,
            force: DVec3::ZERO,
            time: 0.0,
            open: false,
            presses: Presses::default(),
        }
    }

    /// The hand's settings.
    pub fn options(&self) -> &HandOptions {
        &self.options
    }

    /// Advances the arm to time `t`, seconds.
    fn advance(&mut self, t: f64) {
        let span = t - self.time;
        if !span.is_finite() || span <= 0.0 {
            return;
        }
        let steps = ((span / HAND_MAX_STEP_S).ceil() as usize).clamp(1, HAND_MAX_SUBSTEPS);
        let h = span / steps as f64;
        let o = self.options;
        let mass = if o.mass.is_finite() && o.mass > 0.0 {
            o.mass
        } else {
            1.0
        };
        for k in 1..=steps {
            let (target, target_velocity) = self.path.sample(self.time + k as f64 * h);
            let f = o.stiffness * (target - self.position)
                + o.damping * (target_velocity - self.velocity)
                - o.viscosity * self.velocity
                + o.push
                + self.force;
            self.velocity += h * f / mass;
            self.position += h * self.velocity;
        }
        self.time = t;
        if !self.position.is_finite() || !self.velocity.is_finite() {
            // Never leave the arm in a state it cannot recover from.
            self.position = self.path.sample(t).0;
            self.velocity = DVec3::ZERO;
        }
    }
}

impl Simulated for SimulatedHand {
    fn sample(&mut self, t: f64) -> Result<(DVec3, DVec3), DeviceFault> {
        self.advance(t);
        Ok((self.position, self.velocity))
    }

    /// A non-finite force pushes nothing.
    fn feel(&mut self, force: DVec3) {
        self.force = if force.is_finite() {
            force
        } else {
            DVec3::ZERO
        };
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::servo::Device;

    #[test]
    fn follows_a_still_target_and_settles_against_a_constant_force() {
        let mut hand = SimulatedHand::new(Trajectory::still(DVec3::ZERO), HandOptions::default());
        hand.open().expect("opens");
        hand.write_force(DVec3::new(0.0, 0.0, 3.0)).expect("open");
        let s = hand.read(2.0).expect("open");
        // The grip spring balances the force: 3 N / 300 N/m = 1 cm.
        assert!((s.position.z - 0.01).abs() < 1e-6, "{s:?}");
        assert!(s.velocity.length() < 1e-4);
    }
}
