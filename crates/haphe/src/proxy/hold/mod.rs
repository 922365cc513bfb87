//! Deep penetration: the proxy holds its contact once the force saturates.
//!
//! In the physical range — the device point no deeper behind the contact plane than the
//! saturation depth `F_max / k`, where the spring's force reaches the device's maximum —
//! the proxy is the god-object. Beyond it the god-object's rule ("get as close to the
//! device point as the surface allows") is wrong: with the hand pushed deep into a thick
//! convex part, the closest surface point moves around the body, the proxy crawls after it
//! to the far side and the force then pulls the hand on through the object. So a proxy
//! whose device point lies deeper than the saturation depth behind its contact plane
//! *holds*, from the tick the hand goes that deep: it goes back to where it first met the
//! surface in that tick (where it rested, or touched down) and holds that contact (or, when
//! the hand is not that deep behind that first plane, it holds from the next tick where
//! the god-object left it). It heads for a goal that depends only on where the hand is: the
//! entry (the proxy when the hold began) plus the part of the hand's travel since then
//! that runs across the direction it went deep in, pulled back to the saturation depth
//! along the held plane's normal ([`hold_slide`]); the god-object's constraint steps take
//! it there, so it never enters the object. Pushing on along the direction of entry leaves
//! it where it is; sliding sideways moves it with the hand. It lets go (the god-object
//! resumes from where it is) on the first tick the device point is back within the
//! saturation depth of the held plane — the hand has come back out toward the side of
//! entry.

mod tick;

use glam::DVec3;

use super::force::MIN_MAX_FORCE;
use crate::scene::{Material, Pose, SurfaceRef};

/// The saturation depth of `material` with a device of `max_force` newtons, metres: the
/// penetration at which the spring alone reaches the maximum force. `None` where no force
/// is rendered (a maximum below [`MIN_MAX_FORCE`] or no stiffness): then the proxy never
/// holds.
#[inline]
pub fn saturation_depth(material: &Material, max_force: f64) -> Option<f64> {
    let k = material.stiffness;
    let depth = max_force / k;
    // A maximum below the least or not a number, a stiffness not above 0 or not finite, or
    // an infinite quotient (an infinite maximum among them): no depth.
    (max_force >= MIN_MAX_FORCE && k > 0.0 && k < f64::INFINITY && depth.is_finite())
        .then_some(depth)
}

/// Whether a proxy at `proxy` whose contact plane has the unit `normal` (world frame,
/// toward the proxy) holds with the device point at `hip`: the device point lies more than
/// `depth` metres behind the plane through the proxy.
#[inline]
pub fn is_deep(proxy: DVec3, hip: DVec3, normal: DVec3, depth: Option<f64>) -> bool {
    depth.is_some_and(|d| (proxy - hip).dot(normal) > d)
}

/// The contact a holding proxy keeps: its object and the triangle under it, the contact
/// plane's normal in the object's frame (so that it turns with a moving object) and the
/// number of planes that were active.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Hold {
    pub on: SurfaceRef,
    pub normal_object: DVec3,
    pub constraints: u8,
    /// Where the proxy was when the hold began (the entry), object frame.
    pub entry_object: DVec3,
    /// Where the device point was when the hold began, object frame.
    pub hip_object: DVec3,
    /// The unit direction the hand went deep in, object frame (see [`deep_direction`]).
    pub direction_object: DVec3,
}

impl Hold {
    /// A hold on the triangle `on` of an object at `pose`, with `constraints` planes
    /// active: it begins with the proxy at `entry` on the contact plane of unit `normal`,
    /// the hand at `hip_entry`, and the direction the hand went deep in taken from its
    /// motion `previous → hip` ([`deep_direction`]). World frame in; the hold keeps them in
    /// the object's frame, so that it turns with a moving object.
    #[inline]
    pub fn begin(
        pose: &Pose,
        (on, constraints): (SurfaceRef, u8),
        (entry, normal): (DVec3, DVec3),
        hip_entry: DVec3,
        (previous, hip): (Option<DVec3>, DVec3),
    ) -> Hold {
        Hold {
            on,
            normal_object: pose.vector_to_object(normal),
            constraints,
            entry_object: pose.to_object(entry),
            hip_object: pose.to_object(hip_entry),
            direction_object: pose.vector_to_object(deep_direction(previous, hip, normal)),
        }
    }

    /// The held plane's unit normal in the world frame, with the object at `pose`.
    #[inline]
    pub fn normal(&self, pose: &Pose) -> DVec3 {
        pose.vector_to_world(self.normal_object)
    }

    /// Where a holding proxy at `p` heads with the device point at `hip`, and the unit
    /// normal of the held plane, world frame (see [`hold_slide`]).
    #[inline]
    pub fn targets(&self, pose: &Pose, p: DVec3, hip: DVec3) -> (DVec3, DVec3) {
        let normal = self.normal(pose);
        let slide = hold_slide(
            pose.to_world(self.entry_object),
            pose.to_world(self.hip_object),
            pose.vector_to_world(self.direction_object),
            normal,
            p,
            hip,
        );
        (slide, normal)
    }
}

/// The unit direction the hand went deep in: its motion over the tick that went beyond
/// the saturation depth (`previous` to `hip`) where that motion goes into the contact
/// plane of unit `normal`, else straight in (`-normal`).
#[inline]
pub fn deep_direction(previous: Option<DVec3>, hip: DVec3, normal: DVec3) -> DVec3 {
    previous
        .map(|q| hip - q)
        .filter(|m| m.dot(normal) < 0.0)
        .and_then(DVec3::try_normalize)
        .unwrap_or(-normal)
}

/// The point over the goal of a holding proxy at `p`, on the held plane (unit `normal`)
/// through `p`. The goal is the `entry` (the proxy when the hold began) plus the part of
/// the hand's travel since then (`hip - hip_entry`) across the unit `direction` it went
/// deep in: pushing on along `direction` leaves it where it is, moving sideways moves it
/// with the hand. The proxy's constraint steps aim at this point pulled back into the
/// surface by the saturation depth, along `-normal`.
#[inline]
pub fn hold_slide(
    entry: DVec3,
    hip_entry: DVec3,
    direction: DVec3,
    normal: DVec3,
    p: DVec3,
    hip: DVec3,
) -> DVec3 {
    let travel = hip - hip_entry;
    let goal = entry + (travel - direction * travel.dot(direction));
    let to_goal = goal - p;
    p + (to_goal - normal * to_goal.dot(normal))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn saturation_depth_is_max_force_over_stiffness_or_none() {
        let m = Material::default();
        assert_eq!(saturation_depth(&m, 3.3), Some(3.3 / 500.0));
        assert_eq!(saturation_depth(&m, 0.0), None);
        assert_eq!(saturation_depth(&m, f64::NAN), None);
        let n = DVec3::Z;
        let d = saturation_depth(&m, 3.3);
        assert!(!is_deep(DVec3::ZERO, DVec3::new(0.5, 0.0, -0.006), n, d));
        assert!(is_deep(DVec3::ZERO, DVec3::new(0.5, 0.0, -0.007), n, d));
        assert!(!is_deep(DVec3::ZERO, DVec3::new(0.0, 0.0, -1.0), n, None));
    }
}
