//! The deep-penetration hold of the brute-force proxy, written from the rule as
//! `docs/deep-penetration.md` states it and apart from the proxy's own code: nothing of
//! [`crate::proxy`] is called here, so that the fast proxy's hold is checked against the
//! rule, not against itself.
//!
//! The rule, in the words of that page:
//!
//! - The *saturation depth* is `F_max / k`: the spring's force reaches the device's
//!   maximum when the hand is that far behind the surface ([`saturation_depth_of`]).
//! - "When the god-object's steps of a tick end with the hand deeper than the saturation
//!   depth behind the contact plane, that tick already holds: the proxy goes back to where
//!   it first met the surface in that tick (where it rested at the start of the tick, or
//!   where it touched down), and holds there as long as the hand stays deeper than the
//!   saturation depth behind that plane. [...] Where the hand is not that deep behind the
//!   plane it first met, the proxy keeps the god-object's position of that tick and holds
//!   from the next tick on." ([`hand_deeper_than`])
//! - "The proxy remembers where it holds (the entry), where the hand was and the direction
//!   the hand went deep in (its motion over the tick that went deep, or straight in when
//!   it did not move inward)." ([`HeldContact::new`])
//! - "While it holds, its goal is the entry plus the part of the hand's travel since then
//!   that runs across that direction, pulled back to the saturation depth along the held
//!   plane's normal; the god-object's constraint steps move it toward that goal [...], and
//!   the held plane becomes the one it meets. [...] A hand that has moved across by no
//!   more than a skin (1 µm) leaves the proxy where it is." ([`HeldContact::aim`])
//! - "On the first tick the hand is back within the saturation depth of the held plane,
//!   the proxy lets go and slides on as before."

use glam::DVec3;

use crate::scene::{Material, Pose};

/// The saturation depth of `material` with a device of `max_force` newtons, metres:
/// `F_max / k`. `None` where the device renders no force (a maximum force that is not a
/// finite number of at least [`MIN_MAX_FORCE`](crate::proxy::MIN_MAX_FORCE) newtons, or no
/// finite positive stiffness): then nothing saturates and nothing holds.
pub fn saturation_depth_of(material: &Material, max_force: f64) -> Option<f64> {
    let renders = max_force.is_finite() && max_force >= crate::proxy::MIN_MAX_FORCE;
    let stiff = material.stiffness.is_finite() && material.stiffness > 0.0;
    let depth = max_force / material.stiffness;
    (renders && stiff && depth.is_finite()).then_some(depth)
}

/// Whether the hand at `hand` lies more than `depth` metres behind the plane through
/// `proxy` with the unit `normal` (toward the free side). Never, with no saturation depth.
pub fn hand_deeper_than(proxy: DVec3, hand: DVec3, normal: DVec3, depth: Option<f64>) -> bool {
    let behind = (proxy - hand).dot(normal);
    matches!(depth, Some(d) if behind > d)
}

/// What a holding proxy remembers, in the held object's frame (so that it turns with the
/// object).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HeldContact {
    /// The held object's index in the scene.
    pub object: usize,
    /// The held plane's unit normal.
    pub normal: DVec3,
    /// Where the proxy holds: where the hold began.
    pub entry: DVec3,
    /// Where the hand was when the hold began.
    pub hand: DVec3,
    /// The unit direction the hand went deep in.
    pub direction: DVec3,
}

impl HeldContact {
    /// A hold of object `object` at `pose`, beginning with the proxy at `entry` on the
    /// plane of unit `normal` and the hand at `hand` (world frame); the hand's motion over
    /// the tick that went deep was `motion` (`None` on the first tick of a proxy). The
    /// direction it went deep in is that motion where it goes into the plane, else
    /// straight in (`-normal`).
    pub fn new(
        pose: &Pose,
        object: usize,
        (entry, normal): (DVec3, DVec3),
        hand: DVec3,
        motion: Option<DVec3>,
    ) -> HeldContact {
        let inward = motion
            .filter(|m| m.dot(normal) < 0.0)
            .and_then(|m| m.try_normalize());
        let direction = match inward {
            Some(d) => d,
            None => -normal,
        };
        HeldContact {
            object,
            normal: pose.vector_to_object(normal),
            entry: pose.to_object(entry),
            hand: pose.to_object(hand),
            direction: pose.vector_to_object(direction),
        }
    }

    /// The held plane's unit normal, world frame, with the object at `pose`.
    pub fn normal_at(&self, pose: &Pose) -> DVec3 {
        pose.vector_to_world(self.normal)
    }

    /// Where the constraint steps of a proxy holding at `p` head with the hand at `hand`
    /// (world frame), and whether it moves at all: the goal (the entry plus the hand's
    /// travel since the hold began, less its part along the direction it went deep in),
    /// carried onto the held plane through `p` and pulled back from it by the saturation
    /// `depth` into the surface. The proxy stays put (`None`) while that point on the plane
    /// lies within `skin` metres of `p`.
    pub fn aim(&self, pose: &Pose, p: DVec3, hand: DVec3, depth: f64, skin: f64) -> Option<DVec3> {
        let normal = self.normal_at(pose);
        let direction = pose.vector_to_world(self.direction);
        let travel = hand - pose.to_world(self.hand);
        let across = travel - travel.dot(direction) * direction;
        let goal = pose.to_world(self.entry) + across;
        let offset = goal - p;
        let on_plane = p + (offset - offset.dot(normal) * normal);
        (on_plane.distance(p) > skin).then(|| on_plane - depth * normal)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The rule on a flat floor (normal +z, saturation depth 6.6 mm), each value worked
    /// out from the text.
    #[test]
    fn the_rule_on_a_floor() {
        let m = Material::default();
        let d = saturation_depth_of(&m, 3.3);
        assert_eq!(d, Some(3.3 / m.stiffness));
        assert_eq!(saturation_depth_of(&m, 0.0), None);
        assert_eq!(saturation_depth_of(&m, f64::INFINITY), None);
        let soft = Material {
            stiffness: 0.0,
            ..m
        };
        assert_eq!(saturation_depth_of(&soft, 3.3), None);
        let n = DVec3::Z;
        assert!(hand_deeper_than(
            DVec3::ZERO,
            DVec3::new(1.0, 0.0, -0.007),
            n,
            d
        ));
        assert!(!hand_deeper_than(
            DVec3::ZERO,
            DVec3::new(1.0, 0.0, -0.006),
            n,
            d
        ));
        assert!(!hand_deeper_than(DVec3::ZERO, -DVec3::Z, n, None));
        let pose = Pose::IDENTITY;
        // Went deep moving down and across at 45°: pushing on along that line leaves the
        // goal at the entry; a hand that moved 1 mm across that line takes it along.
        let entry = DVec3::ZERO;
        let dir = DVec3::new(1.0, 0.0, -1.0).normalize();
        let hand = entry + 0.007 * dir;
        let hold = HeldContact::new(&pose, 0, (entry, n), hand, Some(0.001 * dir));
        assert!((hold.direction - dir).length() < 1e-15);
        let depth = d.unwrap();
        assert_eq!(hold.aim(&pose, entry, hand + 0.05 * dir, depth, 1e-6), None);
        let across = DVec3::new(1.0, 0.0, 1.0).normalize() * 1e-3;
        let aim = hold.aim(&pose, entry, hand + across, depth, 1e-6).unwrap();
        assert!(
            (aim - DVec3::new(across.x, 0.0, -depth)).length() < 1e-15,
            "{aim}"
        );
        // Straight in when the motion did not go into the plane.
        let still = HeldContact::new(&pose, 0, (entry, n), hand, Some(DVec3::X));
        assert_eq!(still.direction, -n);
        let first = HeldContact::new(&pose, 0, (entry, n), hand, None);
        assert_eq!(first.direction, -n);
        // Within a skin across: no move.
        let nudge = DVec3::new(0.5e-6, 0.0, 0.0);
        assert_eq!(still.aim(&pose, entry, hand + nudge, depth, 1e-6), None);
    }
}
