//! Friction for the brute-force proxy, written from the rule in [`crate::proxy`]'s
//! semantics apart from the proxy's own code: "In contact, with friction, the proxy stays
//! where it rested while the tangential force is inside the static friction cone, and
//! otherwise slips to the edge of the dynamic cone".

use glam::DVec3;

use crate::scene::Material;

/// Where friction leaves a proxy in contact, and whether it sticks. `rested` is where it
/// rested (before this tick's steps), `free` where the frictionless steps took it, `hand`
/// the device point; the spring's normal force is proportional to `|free - hand|` and its
/// tangential force to `|rested - free|`. The cone is the static one when the proxy stuck
/// on the previous tick (`was_sticking`) and the dynamic one when it slipped. Inside it,
/// the proxy stays at `rested`; outside, it slips from `free` toward `rested` to the edge
/// of the dynamic cone.
pub fn friction_step(
    rested: DVec3,
    free: DVec3,
    hand: DVec3,
    material: &Material,
    was_sticking: bool,
) -> (DVec3, bool) {
    let pressing = free.distance(hand);
    let drag = rested - free;
    let cone = if was_sticking {
        material.static_friction
    } else {
        material.dynamic_friction
    };
    if drag.length() <= cone * pressing {
        (rested, true)
    } else {
        let edge = material.dynamic_friction * pressing / drag.length();
        (free + edge * drag, false)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// On a floor with the hand 2 mm below the free point: the static cone (0.5) holds a
    /// drag of 1 mm and the dynamic one (0.25) lets a 2 mm drag slip back to 0.5 mm.
    #[test]
    fn sticks_inside_the_cone_and_slips_to_the_dynamic_edge() {
        let m = Material {
            static_friction: 0.5,
            dynamic_friction: 0.25,
            ..Material::default()
        };
        let free = DVec3::ZERO;
        let hand = DVec3::new(0.0, 0.0, -0.002);
        let rested = DVec3::new(0.001, 0.0, 0.0);
        assert_eq!(friction_step(rested, free, hand, &m, true), (rested, true));
        let (p, sticking) = friction_step(rested, free, hand, &m, false);
        assert!(
            !sticking && (p - DVec3::new(0.0005, 0.0, 0.0)).length() < 1e-15,
            "{p}"
        );
        let far = DVec3::new(0.002, 0.0, 0.0);
        let (p, sticking) = friction_step(far, free, hand, &m, true);
        assert!(
            !sticking && (p - DVec3::new(0.0005, 0.0, 0.0)).length() < 1e-15,
            "{p}"
        );
    }
}
