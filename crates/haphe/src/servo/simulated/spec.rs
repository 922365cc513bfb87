//! The specification every simulated device reports.

use glam::DVec3;

use crate::servo::device::DeviceSpec;

/// The specification of every simulated device: like a common desktop device,
/// [`DEFAULT_MAX_FORCE_N`](crate::scene::DEFAULT_MAX_FORCE_N) and 2000 N/m, with a generous workspace (±0.5 m) so that simulations are not cut off.
pub fn simulated_spec() -> DeviceSpec {
    DeviceSpec {
        name: "simulated",
        max_force: crate::scene::DEFAULT_MAX_FORCE_N,
        max_stiffness: 2000.0,
        workspace_min: DVec3::splat(-0.5),
        workspace_max: DVec3::splat(0.5),
    }
}
