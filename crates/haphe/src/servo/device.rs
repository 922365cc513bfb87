//! The device abstraction: what a haptic device offers the servo loop, and where its
//! workspace sits in the world.

use glam::{DQuat, DVec3};

use crate::scene::{Param, ParamError};

/// What a device can do, in SI units and the device frame.
///
/// Vendor units (millimetres, counts, "stiffness units") are converted inside the adapter
/// that implements [`Device`]; everything here is metres, newtons and N/m.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DeviceSpec {
    /// A short name for reports.
    pub name: &'static str,
    /// Largest force the device renders continuously, newtons.
    pub max_force: f64,
    /// Largest stiffness the device renders stably, N/m at the device (a stiffness `k` in
    /// the world is felt as `k · scale` at the device, see [`DeviceMapping`]).
    pub max_stiffness: f64,
    /// Lower corner of the reachable workspace box, metres, device frame.
    pub workspace_min: DVec3,
    /// Upper corner of the reachable workspace box, metres, device frame.
    pub workspace_max: DVec3,
}

/// The servo rate at which a device's [`DeviceSpec::max_stiffness`] is taken to be
/// rated, Hz: vendors quote it for their 1 kHz servo loop (OpenHaptics'
/// `HD_NOMINAL_MAX_STIFFNESS`, Force Dimension's manuals).
pub const STIFFNESS_RATED_AT_HZ: f64 = 1000.0;

impl DeviceSpec {
    /// The largest wall stiffness the device renders stably at `rate_hz`, N/m at the
    /// device; infinite when the device reports no maximum.
    ///
    /// The rule is the passivity condition of a sampled virtual wall (Colgate and
    /// Schenkel, "Passivity of a class of sampled-data systems: application to haptic
    /// interfaces", J. Robotic Systems 14(1), 1997): a wall of stiffness `K` and damping
    /// `B` rendered every `T` seconds on a device of physical damping `b` is passive if
    /// `b > K·T/2 + |B|`. The device's physical damping is taken from its rated maximum,
    /// `b = max_stiffness · T₀ / 2` at 1 kHz, which gives
    /// `K < max_stiffness · rate / 1000 Hz`: twice the rate renders twice the stiffness.
    /// The wall's damping is left out: the hand holding the device adds physical damping
    /// of its own (a few N·s/m), which the rule does not count either, and counting `B`
    /// alone would warn on walls that render well.
    pub fn stable_stiffness(&self, rate_hz: f64) -> f64 {
        if !self.max_stiffness.is_finite() {
            return f64::INFINITY;
        }
        self.max_stiffness * rate_hz / STIFFNESS_RATED_AT_HZ
    }

    /// Centre of the workspace box, metres, device frame.
    pub fn workspace_centre(&self) -> DVec3 {
        0.5 * (self.workspace_min + self.workspace_max)
    }

    /// Size of the workspace box along each axis, metres.
    pub fn workspace_size(&self) -> DVec3 {
        (self.workspace_max - self.workspace_min).max(DVec3::ZERO)
    }
}

/// Buttons held down, one bit per button (bit 0 is the first button).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Hash)]
pub struct Buttons(pub u32);

impl Buttons {
    /// Whether button `index` (0-based) is held down; `false` beyond bit 31.
    pub fn is_down(self, index: u32) -> bool {
        index < 32 && self.0 & (1 << index) != 0
    }
}

/// One sample read from a device.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct DeviceState {
    /// The end point (the HIP), metres, device frame.
    pub position: DVec3,
    /// Its velocity, m/s, device frame.
    pub velocity: DVec3,
    /// Buttons held down.
    pub buttons: Buttons,
}

/// Why a device call failed on the servo path: a small `Copy` value, never a heap error.
/// The servo loop answers every fault by writing zero force and stopping.
#[derive(Debug, Clone, Copy, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum DeviceFault {
    /// The device is not open (or was closed).
    #[error("the device is not open")]
    NotOpen,
    /// The device stopped answering.
    #[error("the device is disconnected")]
    Disconnected,
    /// A replayed trace or a scripted path has no more samples: the run is over.
    #[error("the device's recording ended")]
    Ended,
    /// A vendor error code.
    #[error("device error code {0}")]
    Hardware(u32),
}

/// Why a device could not be opened or calibrated (off the servo path).
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum DeviceError {
    /// Opening failed.
    #[error("cannot open the device: {0}")]
    Open(String),
    /// Calibration failed.
    #[error("cannot calibrate the device: {0}")]
    Calibrate(String),
}

/// A point haptic device, in the shape haptic developers know from vendor SDKs: open,
/// calibrate, read the end point, write a force, close.
///
/// Units are SI and positions, velocities and forces are in the device frame; the servo
/// loop maps them to the world with a [`DeviceMapping`].
///
/// # Real-time
/// [`read`](Device::read) and [`write_force`](Device::write_force) run on the servo thread
/// every tick: they must not allocate, lock, block for long, print or panic.
pub trait Device: Send {
    /// What the device can do.
    fn spec(&self) -> DeviceSpec;

    /// Opens the device (off the servo path).
    ///
    /// # Errors
    /// When the device cannot be reached.
    fn open(&mut self) -> Result<(), DeviceError>;

    /// Calibrates the device after opening (off the servo path). The default does nothing.
    ///
    /// # Errors
    /// When calibration fails.
    fn calibrate(&mut self) -> Result<(), DeviceError> {
        Ok(())
    }

    /// Reads the device at the tick scheduled for time `t` (seconds since the loop
    /// started). Hardware adapters ignore `t`; simulated devices use it as their clock,
    /// which makes simulated runs independent of the wall clock.
    ///
    /// # Errors
    /// A [`DeviceFault`]; the loop then writes zero force and stops.
    fn read(&mut self, t: f64) -> Result<DeviceState, DeviceFault>;

    /// Sends the force to render, newtons, device frame, held until the next write.
    ///
    /// # Errors
    /// A [`DeviceFault`]; the loop then stops.
    fn write_force(&mut self, force: DVec3) -> Result<(), DeviceFault>;

    /// Closes the device. Called after a zero force was written.
    fn close(&mut self);
}

/// A boxed device is a device, so that a loop can run a device chosen at run time
/// (`Box<dyn Device>`): one virtual call per method, no allocation.
impl<D: Device + ?Sized> Device for Box<D> {
    fn spec(&self) -> DeviceSpec {
        (**self).spec()
    }
    fn open(&mut self) -> Result<(), DeviceError> {
        (**self).open()
    }
    fn calibrate(&mut self) -> Result<(), DeviceError> {
        (**self).calibrate()
    }
    fn read(&mut self, t: f64) -> Result<DeviceState, DeviceFault> {
        (**self).read(t)
    }
    fn write_force(&mut self, force: DVec3) -> Result<(), DeviceFault> {
        (**self).write_force(force)
    }
    fn close(&mut self) {
        (**self).close();
    }
}

/// Where the device workspace sits in the world: `p_world = offset + scale · (rotation ·
/// p_device)`.
///
/// Positions and velocities are scaled; forces are not (newtons are newtons), so a world
/// stiffness `k` (N/m) is felt as `k · scale` at the device: scaling a small workspace up
/// to a large world makes surfaces feel stiffer.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DeviceMapping {
    rotation: DQuat,
    scale: f64,
    offset: DVec3,
}

impl Default for DeviceMapping {
    fn default() -> DeviceMapping {
        DeviceMapping::IDENTITY
    }
}

impl DeviceMapping {
    /// The device frame is the world frame.
    pub const IDENTITY: DeviceMapping = DeviceMapping {
        rotation: DQuat::IDENTITY,
        scale: 1.0,
        offset: DVec3::ZERO,
    };

    /// A mapping from a rotation (device axes to world axes, a quaternion of any non-zero
    /// length, normalised here), a scale (world metres per device metre) and an offset
    /// (the world position of the device origin, metres).
    ///
    /// # Errors
    /// [`ParamError`] naming `rotation`, `scale` or `centre` outside its domain (see
    /// [`Param`]).
    pub fn new(rotation: DQuat, scale: f64, offset: DVec3) -> Result<DeviceMapping, ParamError> {
        Param::Rotation.check_vector(rotation.to_array())?;
        Param::Scale.check(scale)?;
        Param::Centre.check_vector(offset.to_array())?;
        Ok(DeviceMapping::sanitised(rotation, scale, offset))
    }

    /// The mapping of `spec`'s workspace, unrotated, that puts the workspace's centre at
    /// the world point `centre` and scales it by `scale`.
    ///
    /// # Errors
    /// [`ParamError`] naming `scale` or `centre` outside its domain.
    pub fn centred(
        spec: &DeviceSpec,
        scale: f64,
        centre: DVec3,
    ) -> Result<DeviceMapping, ParamError> {
        Param::Scale.check(scale)?;
        Param::Centre.check_vector(centre.to_array())?;
        DeviceMapping::new(
            DQuat::IDENTITY,
            scale,
            centre - scale * spec.workspace_centre(),
        )
    }

    /// The mapping, with unusable values replaced (a non-finite or zero rotation by the
    /// identity, a non-finite or non-positive scale by 1, a non-finite offset by zero).
    fn sanitised(rotation: DQuat, scale: f64, offset: DVec3) -> DeviceMapping {
        DeviceMapping {
            rotation: if rotation.is_finite() && rotation.length_squared() > 0.0 {
                rotation.normalize()
            } else {
                DQuat::IDENTITY
            },
            scale: if scale.is_finite() && scale > 0.0 {
                scale
            } else {
                1.0
            },
            offset: if offset.is_finite() {
                offset
            } else {
                DVec3::ZERO
            },
        }
    }

    /// Workspace scaling: the mapping (without rotation) that makes the device's workspace
    /// box cover the world box `[world_min, world_max]` (metres), centre on centre, with
    /// one scale for all axes chosen so that the box fits along every axis (a box that
    /// is not finite gives a usable mapping, not an error).
    pub fn fit(spec: &DeviceSpec, world_min: DVec3, world_max: DVec3) -> DeviceMapping {
        let device = spec.workspace_size();
        let world = (world_max - world_min).max(DVec3::ZERO);
        let ratio = |w: f64, d: f64| if d > 0.0 { w / d } else { 0.0 };
        let scale = ratio(world.x, device.x)
            .max(ratio(world.y, device.y))
            .max(ratio(world.z, device.z));
        let scale = if scale > 0.0 { scale } else { 1.0 };
        let offset = 0.5 * (world_min + world_max) - scale * spec.workspace_centre();
        DeviceMapping::sanitised(DQuat::IDENTITY, scale, offset)
    }

    /// The same mapping with the device origin at the world point `offset` (a non-finite
    /// offset keeps the current one): the clutch moves the workspace this way.
    pub(crate) fn with_offset(self, offset: DVec3) -> DeviceMapping {
        if offset.is_finite() {
            DeviceMapping { offset, ..self }
        } else {
            self
        }
    }

    /// World metres per device metre.
    pub fn scale(&self) -> f64 {
        self.scale
    }

    /// The rotation, device axes to world axes.
    pub fn rotation(&self) -> DQuat {
        self.rotation
    }

    /// The world position of the device origin, metres.
    pub fn offset(&self) -> DVec3 {
        self.offset
    }

    /// `p_world` of a device point.
    #[inline]
    pub fn position_to_world(&self, p_device: DVec3) -> DVec3 {
        self.offset + self.scale * (self.rotation * p_device)
    }

    /// `p_device` of a world point.
    #[inline]
    pub fn position_to_device(&self, p_world: DVec3) -> DVec3 {
        self.rotation.inverse() * ((p_world - self.offset) / self.scale)
    }

    /// A device velocity (m/s) in the world frame (scaled and rotated).
    #[inline]
    pub fn velocity_to_world(&self, v_device: DVec3) -> DVec3 {
        self.scale * (self.rotation * v_device)
    }

    /// A world force (newtons) in the device frame (rotated, not scaled).
    #[inline]
    pub fn force_to_device(&self, f_world: DVec3) -> DVec3 {
        self.rotation.inverse() * f_world
    }

    /// The stiffness felt at the device for a world stiffness `k_world`, N/m.
    pub fn stiffness_at_device(&self, k_world: f64) -> f64 {
        k_world * self.scale
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn spec() -> DeviceSpec {
        DeviceSpec {
            name: "test",
            max_force: crate::scene::DEFAULT_MAX_FORCE_N,
            max_stiffness: 2000.0,
            workspace_min: DVec3::new(-0.08, -0.06, -0.035),
            workspace_max: DVec3::new(0.08, 0.06, 0.035),
        }
    }

    #[test]
    fn round_trip_and_forces_are_not_scaled() {
        let m = DeviceMapping::new(DQuat::from_rotation_z(0.3), 2.5, DVec3::new(0.1, -0.2, 0.3))
            .unwrap();
        let p = DVec3::new(0.01, 0.02, -0.03);
        assert!(m.position_to_device(m.position_to_world(p)).distance(p) < 1e-15);
        let f = DVec3::new(1.0, 2.0, 3.0);
        assert!((m.force_to_device(f).length() - f.length()).abs() < 1e-12);
        assert!((m.velocity_to_world(p).length() - 2.5 * p.length()).abs() < 1e-12);
    }

    #[test]
    fn fit_covers_the_world_box() {
        let (lo, hi) = (DVec3::new(-0.2, -0.1, -0.1), DVec3::new(0.4, 0.1, 0.1));
        let m = DeviceMapping::fit(&spec(), lo, hi);
        assert!((m.scale() - 0.6 / 0.16).abs() < 1e-12);
        let s = spec();
        let a = m.position_to_world(s.workspace_min);
        let b = m.position_to_world(s.workspace_max);
        assert!(a.cmple(lo + 1e-12).all() && b.cmpge(hi - 1e-12).all());
    }

    #[test]
    fn bad_parameters_are_refused_naming_them() {
        let zero = DQuat::from_xyzw(0.0, 0.0, 0.0, 0.0);
        let e = DeviceMapping::new(zero, 1.0, DVec3::ZERO).unwrap_err();
        assert_eq!(e.param(), Param::Rotation);
        let e = DeviceMapping::new(DQuat::IDENTITY, 0.0, DVec3::ZERO).unwrap_err();
        assert_eq!(e.param(), Param::Scale);
        let e = DeviceMapping::centred(&spec(), 1.0, DVec3::NAN).unwrap_err();
        assert_eq!(e.param(), Param::Centre);
        let m = DeviceMapping::sanitised(zero, f64::NAN, DVec3::NAN);
        assert_eq!(m, DeviceMapping::IDENTITY);
        assert!(Buttons(0b10).is_down(1) && !Buttons(0b10).is_down(0) && !Buttons(1).is_down(40));
    }
}
