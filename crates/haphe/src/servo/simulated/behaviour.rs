//! The [`Simulated`] trait: what differs between the simulated devices (where the hand
//! point is at a time, what the force written does).

use glam::DVec3;

use crate::servo::device::DeviceFault;

/// What differs between the simulated devices.
pub(super) trait Simulated {
    /// Position and velocity of the hand point at `t` seconds after the start.
    fn sample(&mut self, t: f64) -> Result<(DVec3, DVec3), DeviceFault>;
    /// Takes the force written (zero when the device closes).
    fn feel(&mut self, force: DVec3);
}
