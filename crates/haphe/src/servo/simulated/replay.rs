//! Replay of a recorded device trace ([`HipTrace`]: CSV lines `t,x,y,z`, seconds, metres,
//! device frame).

use glam::DVec3;

use super::behaviour::Simulated;
use super::presses::Presses;
use super::spec::simulated_spec;
use crate::servo::device::{DeviceFault, DeviceSpec};
use crate::servo::trace::read::HipTrace;

/// A device that replays a [`HipTrace`] from its first sample: the tick at loop time `t`
/// reads the trace at `start_time + t`. It reports [`DeviceFault::Ended`] after the last
/// sample, which ends the run.
#[derive(Debug, Clone)]
pub struct ReplayDevice {
    trace: HipTrace,
    pub(super) spec: DeviceSpec,
    pub(super) open: bool,
    pub(super) presses: Presses,
}

impl ReplayDevice {
    /// A device replaying `trace`.
    pub fn new(trace: HipTrace) -> ReplayDevice {
        ReplayDevice {
            trace,
            spec: simulated_spec(),
            open: false,
            presses: Presses::default(),
        }
    }

    /// The trace replayed.
    pub fn trace(&self) -> &HipTrace {
        &self.trace
    }
}

impl Simulated for ReplayDevice {
    fn sample(&mut self, t: f64) -> Result<(DVec3, DVec3), DeviceFault> {
        self.trace
            .sample(self.trace.start_time() + t)
            .ok_or(DeviceFault::Ended)
    }

    /// A recorded hand does not feel the force.
    fn feel(&mut self, _force: DVec3) {}
}
