//! The [`Device`] side of the simulated devices, written once: each says where its hand
//! point is at a time and what it does with the force written ([`Simulated`]); its `spec`
//! and `open` fields, opening, closing and refusing reads and writes while closed are the
//! same for all of them.

use glam::DVec3;

use super::behaviour::Simulated;
use super::hand::SimulatedHand;
use super::replay::ReplayDevice;
use super::scripted::ScriptedDevice;
use crate::servo::device::{Device, DeviceError, DeviceFault, DeviceSpec, DeviceState};

/// `impl Device` for simulated devices, by way of their [`Simulated`] parts and their
/// fields `spec: DeviceSpec` and `open: bool`.
macro_rules! simulated_device {
    ($($device:ty),*) => {$(
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
                    buttons: Default::default(),
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
