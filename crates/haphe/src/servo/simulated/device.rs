//! The [`Device`] side of the simulated devices, written once: each says where its hand
//! point is at a time and what it does with the force written ([`Simulated`]); its `spec`
//! and `open` fields, opening, closing, refusing reads and writes while closed, and the
//! buttons pressed at given times (`presses`) are the same for all of them.

use glam::DVec3;

use super::behaviour::Simulated;
use super::hand::SimulatedHand;
use super::replay::ReplayDevice;
use super::scripted::ScriptedDevice;
use super::trajectory::TrajectoryError;
use crate::servo::device::{Device, DeviceError, DeviceFault, DeviceSpec, DeviceState};

/// `impl Device` for simulated devices, by way of their [`Simulated`] parts and their
/// fields `spec: DeviceSpec`, `open: bool` and `presses: Presses`.
macro_rules! simulated_device {
    ($($device:ty),*) => {$(
        impl $device {
            /// The same device with `button` (0 is the first) held from `from` until
            /// `until`, seconds of the run's clock; presses add up (several buttons, or
            /// one button several times). For a clutch
            /// ([`ServoOptions::with_clutch_button`](crate::servo::ServoOptions::with_clutch_button))
            /// and for tests.
            ///
            /// # Errors
            /// [`TrajectoryError::Press`] for a button beyond 31, a time that is not
            /// finite, or `from` not before `until`.
            pub fn press(mut self, button: u32, from: f64, until: f64) -> Result<Self, TrajectoryError> {
                self.presses.add(button, from, until)?;
                Ok(self)
            }
        }

        impl Device for $device {
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
                let (position, velocity) = self.sample(t)?;
                Ok(DeviceState {
                    position,
                    velocity,
                    buttons: self.presses.at(t),
                })
            }

            fn write_force(&mut self, force: DVec3) -> Result<(), DeviceFault> {
                if !self.open {
                    return Err(DeviceFault::NotOpen);
                }
                self.feel(force);
                Ok(())
            }

            fn close(&mut self) {
                self.feel(DVec3::ZERO);
                self.open = false;
            }
        }
    )*};
}

simulated_device!(SimulatedHand, ScriptedDevice, ReplayDevice);
