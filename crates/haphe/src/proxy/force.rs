//! The rendered force and the friction rule, as plain functions shared by the proxy and
//! its oracle.

use glam::DVec3;

use crate::scene::{Material, Relief};

/// A maximum force below this (newtons) renders no force at all.
pub const MIN_MAX_FORCE: f64 = 1e-9;

/// The force on the device, newtons, world frame: the spring–damper
/// `k (proxy − hip) − b v` toward the proxy, with force shading and a clamp.
///
/// - `normal`: the contact plane's unit normal (toward the proxy), or `None` in free space
///   (then the force is zero: the proxy is the device point).
/// - `shading_normal`: the interpolated normal at the contact, used as the direction of the
///   normal part of the spring on a single face (`constraints == 1`), so a coarse mesh
///   feels smooth; on an edge or in a corner the plain spring is used.
/// - damping acts along the spring only, on the device velocity `v` (m/s).
/// - `relief`: the texture under the contact (world frame, its gradient in the contact
///   plane; [`Relief::FLAT`] for none): the depth along the normal `d` is felt as
///   `e = d + h φ(d)` with `φ(d) = min(1, d / A)`, the normal part scaled by
///   `e (1 + h φ') / d` and `−e φ ∇h` added across (`scene/texture`: the gradient of
///   `k e² / 2`).
///
/// Returns the force and whether it was clamped to `max_force` (newtons). A non-finite
/// result gives zero. Always inlined: the tick calls it once, and a call returns the force
/// through memory.
#[inline(always)]
pub fn contact_force(
    proxy: DVec3,
    hip: DVec3,
    velocity: DVec3,
    contact: Option<(DVec3, DVec3, u8)>,
    (material, relief): (&Material, &Relief),
    max_force: f64,
) -> (DVec3, bool) {
    let Some((normal, shading_normal, constraints)) = contact else {
        return (DVec3::ZERO, false);
    };
    let d = proxy - hip;
    let dn = d.dot(normal);
    let shaded = constraints == 1 && shading_normal.is_finite();
    let mut spring = if shaded {
        dn * shading_normal + (d - dn * normal)
    } else {
        d
    };
    if relief.amplitude > 0.0 && dn > 0.0 {
        let (fade, slope) = if dn < relief.amplitude {
            (dn / relief.amplitude, 1.0 / relief.amplitude)
        } else {
            (1.0, 0.0)
        };
        let felt = dn + relief.height * fade;
        let along = if shaded { shading_normal } else { normal };
        spring +=
            (felt * (1.0 + relief.height * slope) - dn) * along - (felt * fade) * relief.gradient;
    }
    let mut force = material.stiffness * spring;
    let len = d.length();
    if len > 0.0 {
        let u = d / len;
        force -= material.damping * velocity.dot(u) * u;
    }
    clamp_force(force, max_force)
}

/// `force` (newtons) scaled down to `max_force` when longer, and whether it was; zero
/// (not clamped) when it is not finite. The last step of the proxy's force and of the
/// servo's sum with the effects.
pub(crate) fn clamp_force(force: DVec3, max_force: f64) -> (DVec3, bool) {
    if !force.is_finite() {
        return (DVec3::ZERO, false);
    }
    // Below a nanonewton (far below any device) the maximum counts as zero: scaling by
    // such tiny ratios loses the precision that keeps the result within the maximum.
    let max = if max_force.is_finite() && max_force >= MIN_MAX_FORCE {
        max_force
    } else {
        0.0
    };
    let f = force.length();
    if f > max {
        let scaled = if f > 0.0 {
            force * (max / f)
        } else {
            DVec3::ZERO
        };
        (
            if scaled.is_finite() {
                scaled
            } else {
                DVec3::ZERO
            },
            true,
        )
    } else {
        (force, false)
    }
}

/// Coulomb friction on the proxy. `held` is where the proxy was (already resting on the
/// surface), `free` where it would go without friction, `hip` the device point.
///
/// The normal force is proportional to `|free − hip|` and the tangential force to
/// `|held − free|`; the proxy sticks (returns `held`, `true`) while the tangential part is
/// within `mu` times the normal part, where `mu` is the static coefficient when it was
/// sticking and the dynamic one when it was slipping (hysteresis). Otherwise it slips to
/// the point between `free` and `held` where the ratio equals the dynamic coefficient
/// (returns it, `false`).
pub fn friction_target(
    held: DVec3,
    free: DVec3,
    hip: DVec3,
    material: &Material,
    was_sticking: bool,
) -> (DVec3, bool) {
    let normal = free.distance(hip);
    let e = held - free;
    let tangential = e.length();
    let mu = if was_sticking {
        material.static_friction
    } else {
        material.dynamic_friction
    };
    if tangential <= mu * normal {
        return (held, true);
    }
    let keep = material.dynamic_friction * normal / tangential;
    (free + keep * e, false)
}
